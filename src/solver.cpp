#include "spp/solver.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <map>
#include <mutex>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "spp/detail/brent.hpp"
#include "spp/detail/tridiagonal.hpp"
#include "spp/modal.hpp"
#include "search/step_certificate.hpp"

namespace spp {

const char* to_string(SolveStatus s) {
  switch (s) {
    case SolveStatus::NotRun: return "not_run";
    case SolveStatus::Success: return "success";
    case SolveStatus::Incomplete: return "incomplete";
  }
  return "unknown";
}

void SolveOptions::validate() const {
  auto positive_finite = [](double v, const char* name) {
    if (!(std::isfinite(v) && v > 0.0)) {
      std::ostringstream os;
      os << "options: " << name << " must be positive and finite, got " << v;
      throw std::invalid_argument(os.str());
    }
  };
  positive_finite(t1_max, "t1_max");
  positive_finite(t2_max, "t2_max");
  auto lower = [](double v, double hi, const char* name, const char* hiname) {
    if (!(std::isfinite(v) && v >= 0.0 && v < hi)) {
      std::ostringstream os;
      os << "options: " << name << " must be >= 0 and < " << hiname << " = " << hi << " (0 = automatic), got " << v;
      throw std::invalid_argument(os.str());
    }
  };
  lower(t1_min, t1_max, "t1_min", "t1_max");
  lower(t2_min, t2_max, "t2_min", "t2_max");
  auto in_open = [](double v, double lo, double hi, const char* name) {
    if (!(v > lo && v < hi)) {
      std::ostringstream os;
      os << "options: " << name << " must be in (" << lo << ", " << hi << "), got " << v;
      throw std::invalid_argument(os.str());
    }
  };
  in_open(pole_margin, 0.0, 0.1, "pole_margin");
  in_open(max_turn, 0.0, 1.0, "max_turn");
  in_open(min_step, 0.0, 1e-3, "min_step");
  in_open(admissibility_tol, 0.0, 1e-2, "admissibility_tol");
  if (threads < 0)
    throw std::invalid_argument("options: threads must be >= 0 (0 = all), got " + std::to_string(threads));
  if (max_cells < 1)
    throw std::invalid_argument("options: max_cells must be >= 1, got " + std::to_string(max_cells));
}

std::string SolveResult::brief_report() const {
  std::ostringstream os;
  long adm = std::count_if(solutions.begin(), solutions.end(), [](const Solution& s) { return s.admissible; });
  os << "spp: " << to_string(status) << ", " << solutions.size() << " SPPs (" << adm << " admissible) in (" << t1_min
     << ", " << t1_max << "] x (" << t2_min << ", " << t2_max << "]; " << stats.rectangles << " rectangles, "
     << stats.curve_pieces << " curve pieces, " << stats.evaluations << " evaluations, " << stats.seconds << " s";
  return os.str();
}

namespace {

using Vec = Eigen::VectorXd;
using Mat = Eigen::MatrixXd;

// A point on curve k: position, oriented null vector, signed g and dg/ds along s = t2 - t1.
struct TracePoint {
  double s = 0, t1 = 0, t2 = 0, g = 0, dg = 0;
  double lam_below = 0, lam_above = 0, residual = 0, eig_error = 0, slope_sum = 0;  // for the step certificate
  Vec b;
};

search::StepEnd step_end(const TracePoint& p) {
  return {p.s, p.t1, p.t2, p.g, p.dg, p.lam_below, p.lam_above, p.residual, p.eig_error, p.slope_sum, &p.b};
}

struct EdgeHit {
  double pos = 0;  // coordinate along the pole line (t2 on a vertical line, t1 on a horizontal one)
  double t1 = 0, t2 = 0, g = 0;
  Vec b;
  size_t cell = 0;  // column of the cell (hits on horizontal lines)
};

struct Candidate {
  double t1, t2;
  bool uncertified = false, near_pole = false;
  Eigen::VectorXd b;  // null vector of H from the trace (empty: take the SVD of N)
};

// Absolute error bound of eigenvalues computed from the tridiagonal form (backward stable, ~ m eps |H|).
double eigen_error(const detail::SymmetricTridiagonal& T) {
  return 8.0 * T.size() * std::numeric_limits<double>::epsilon() * T.norm_bound();
}

class Search {
 public:
  Search(const ModalForm& md, const SolveOptions& opt, SolveStats& st)
      : md_(md),
        opt_(opt),
        st_(st),
        hmin_(opt.min_step * (opt.t1_max + opt.t2_max)),
        sym_(opt.symmetry),
        zhat_(md.z().normalized()) {}

  // g = c^T b / |c| with c the onset direction (z for axial symmetry: z^T p0 = 0 with p0 along b), and dg/ds
  // given db/ds and dt2/ds. Axial: c is constant, its unit vector computed once (this runs at every trace point).
  std::pair<double, double> onset_g(const Vec& b, double t2, const Vec* db = nullptr, double dt2_ds = 0.0) const {
    if (sym_ == Symmetry::Axial) return {zhat_.dot(b), db ? zhat_.dot(*db) : 0.0};
    // Point symmetry: c(t2) is not normalised (its sign is all that matters, and the certificate bounds c^T b).
    const Vec c = md_.onset_direction(t2, sym_);
    const double g = c.dot(b);
    if (!db) return {g, 0.0};
    const Vec dc = md_.onset_direction_dt2(t2, sym_) * dt2_ds;
    return {g, c.dot(*db) + dc.dot(b)};
  }

  // ---- evaluations ----
  const Mat& H_at(double t1, double t2) {
    if (t2 != cached_t2_) {
      C_ = md_.contact_part(t2, sym_);
      cached_t2_ = t2;
    }
    Hbuf_ = C_;
    Hbuf_.diagonal() += md_.flight_part(t1, sym_);
    ++st_.evaluations;
    return Hbuf_;
  }

  // Tridiagonal form of H at a corner: counts and the eigenvalues that are needed.
  detail::SymmetricTridiagonal corner(double t1, double t2) { return detail::SymmetricTridiagonal(H_at(t1, t2)); }

  // The k-th eigenpair of H (tridiagonal form, bisection, inverse iteration).
  struct Pair {
    double t1 = 0, t2 = 0, lam = 0, scale = 0;
    Vec b;
    double lam_below = -std::numeric_limits<double>::infinity(), lam_above = std::numeric_limits<double>::infinity();
    double eig_error = 0;
  };
  Pair eigenpair(double t1, double t2, int k) {
    const detail::SymmetricTridiagonal T(H_at(t1, t2));
    Pair p{t1, t2, T.eigenvalue(k), T.norm_bound(), Vec()};
    p.b = T.eigenvector(p.lam);
    p.eig_error = eigen_error(T);
    if (k > 0) p.lam_below = T.eigenvalue(k - 1);
    if (k + 1 < T.size()) p.lam_above = T.eigenvalue(k + 1);
    return p;
  }

  // b^T dH/dt1 b and b^T dH/dt2 b (both >= 0).
  std::pair<double, double> grads(const Vec& b, double t1, double t2) const {
    const double l1 = (md_.dflight_dt1(t1, sym_).array() * b.array().square()).sum();
    const Vec y = md_.G().transpose() * b;
    const double l2 = (md_.dcontact_eigs(t2, sym_).array() * y.array().square()).sum();
    return {l1, l2};
  }

  // Trace point from the eigenpair: g = zhat^T b and dg/ds, with db/ds from the bordered system
  // [[H - lam I, b], [b^T, 0]] [db; mu] = [-(I - b b^T) dH/ds b; 0] (first-order eigenvector perturbation).
  TracePoint point(const Pair& q, const Vec* ref) {
    TracePoint p;
    p.t1 = q.t1;
    p.t2 = q.t2;
    p.s = q.t2 - q.t1;
    const Vec& b0 = q.b;
    const double sign = (ref && b0.dot(*ref) < 0) ? -1.0 : 1.0;
    const auto [l1, l2] = grads(b0, q.t1, q.t2);
    const double tp = -l2 / (l1 + l2);  // dtau/ds on the curve
    const Vec y = md_.G().transpose() * b0;
    const Vec e2 = md_.dcontact_eigs(q.t2, sym_);
    const Vec dHb = tp * md_.dflight_dt1(q.t1, sym_).cwiseProduct(b0) + (tp + 1.0) * (md_.G() * e2.cwiseProduct(y));
    const int m = static_cast<int>(b0.size());
    Mat B(m + 1, m + 1);
    B.topLeftCorner(m, m) = H_at(q.t1, q.t2);
    B.topLeftCorner(m, m).diagonal().array() -= q.lam;
    B.col(m).head(m) = b0;
    B.row(m).head(m) = b0.transpose();
    B(m, m) = 0.0;
    Vec rhs(m + 1);
    rhs.head(m) = -(dHb - b0.dot(dHb) * b0);
    rhs(m) = 0.0;
    const Vec db = B.partialPivLu().solve(rhs);
    p.residual = (B.topLeftCorner(m, m) * b0).norm() + std::abs(q.lam);
    p.lam_below = q.lam_below;
    p.lam_above = q.lam_above;
    p.eig_error = q.eig_error;
    p.slope_sum = l1 + l2;
    p.b = sign * b0;
    const Vec dbh = db.head(m);
    const auto [g, dg] = onset_g(b0, q.t2, &dbh, tp + 1.0);
    p.g = sign * g;
    p.dg = sign * dg;
    return p;
  }

  // Root of lambda_k on the segment (t1a, t2a) + sigma (dt1, dt2), sigma in [lo, hi], lambda_k(lo) <= 0 <
  // lambda_k(hi). lambda_k is non-decreasing along the segment (dt1, dt2 >= 0 in one of the two senses), so a
  // Newton step safeguarded by bisection on the bracket converges; it stops at the rounding level of
  // lambda_k (rel_ftol times the largest |eigenvalue|).
  Pair segment_root(double t1a, double t2a, double dt1, double dt2, double lo, double hi, double guess, int k,
                    double rel_ftol) {
    double x = (guess > lo && guess < hi) ? guess : 0.5 * (lo + hi);
    Pair e;
    const double xtol = 4e-16 * (std::abs(lo) + std::abs(hi));
    for (int it = 0; it < 200; ++it) {
      e = eigenpair(t1a + x * dt1, t2a + x * dt2, k);
      const double f = e.lam;
      if (std::abs(f) <= rel_ftol * e.scale) break;
      if (f < 0)
        lo = x;
      else
        hi = x;
      const auto [l1, l2] = grads(e.b, e.t1, e.t2);
      const double df = dt1 * l1 + dt2 * l2;
      double next = df != 0.0 ? x - f / df : 0.5 * (lo + hi);
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      if (hi - lo <= xtol || next == x) break;
      x = next;
    }
    return e;
  }

  // Root of lambda_k on the edge from (t1a, t2a) to (t1b, t2b), with lambda_k = fa <= 0 and fb > 0 there.
  Pair edge_root(double t1a, double t2a, double t1b, double t2b, int k, double fa, double fb) {
    const double guess = fa / (fa - fb);  // secant on the end values
    return segment_root(t1a, t2a, t1b - t1a, t2b - t2a, 0.0, 1.0, guess, k, 1e-14);
  }

  // ---- one rectangle ----
  struct Rect {
    double a1, b1, A, B;  // shrunk bounds
    bool left_pole, right_pole, bottom_pole, top_pole;
  };

  // Root of lambda_k on the anti-diagonal t2 - t1 = s inside rectangle r (tau = t1 on the segment).
  Pair diagonal_root(const Rect& r, double s, double guess, int k) {
    const double lo = std::max(r.a1, r.A - s), hi = std::min(r.b1, r.B - s);
    return segment_root(0.0, s, 1.0, 1.0, lo, hi, guess, k, 1e-13);
  }

  // One cell: count the curves at its corners, find each curve's entry and exit, trace it. Returns false when a
  // part of the cell could not be certified (the caller records the cell).
  bool rectangle(Rect r, size_t column, std::vector<EdgeHit>& left_exits, std::vector<EdgeHit>& top_exits,
                 std::vector<EdgeHit>& right_entries, std::vector<EdgeHit>& bottom_entries) {
    ++st_.rectangles;
    bool certified = true;
    // Corner counts are exact only when no eigenvalue lies within its error bound of 0: otherwise the corner is
    // moved outwards (into the pole margin or past the window edge, never leaving a gap) and counted again. Checked
    // with certify_steps only: next to clustered pole lines |H| ~ 1 / margin makes the bound ~1e-3 and the check
    // fails on windows the midpoint trace handles (Solver.TraceTerminatesOnClusteredPoleLines).
    auto certain = [this](const detail::SymmetricTridiagonal& T) {
      if (!opt_.certify_steps) return true;
      const double e = eigen_error(T);
      return T.count_below(-e) == T.count_below(e);
    };
    detail::SymmetricTridiagonal BLt = corner(r.a1, r.A), TRt = corner(r.b1, r.B);
    for (int tries = 0; tries < 4 && !(certain(BLt) && certain(TRt)); ++tries) {
      const double d1 = 1e-9 * (r.b1 - r.a1), d2 = 1e-9 * (r.B - r.A);
      if (!certain(BLt)) {
        r.a1 -= d1;
        r.A -= d2;
        BLt = corner(r.a1, r.A);
      }
      if (!certain(TRt)) {
        r.b1 += d1;
        r.B += d2;
        TRt = corner(r.b1, r.B);
      }
    }
    if (!(certain(BLt) && certain(TRt))) {
      ++st_.uncertified_corners;
      certified = false;
    }
    const int kmin = TRt.count_below(0.0), kmax = BLt.count_below(0.0);  // curves k in [kmin, kmax)
    if (kmin >= kmax) return certified;
    const detail::SymmetricTridiagonal BRt = corner(r.b1, r.A), TLt = corner(r.a1, r.B);
    const int nBR = BRt.count_below(0.0), nTL = TLt.count_below(0.0);
    for (int k = kmin; k < kmax; ++k) {
      ++st_.curve_pieces;
      // entry on the lower-right path, exit on the upper-left path (design note §3b)
      Pair in, out;
      // lambda_k > 0 at a corner iff fewer than k + 1 eigenvalues lie below 0 there
      const bool in_bottom = nBR <= k, out_left = nTL <= k;
      const double bl = BLt.eigenvalue(k), tr = TRt.eigenvalue(k), br = BRt.eigenvalue(k), tl = TLt.eigenvalue(k);
      if (in_bottom)
        in = edge_root(r.a1, r.A, r.b1, r.A, k, bl, br);
      else
        in = edge_root(r.b1, r.A, r.b1, r.B, k, br, tr);
      if (out_left)
        out = edge_root(r.a1, r.A, r.a1, r.B, k, bl, tl);
      else
        out = edge_root(r.a1, r.B, r.b1, r.B, k, tl, tr);
      TracePoint pin = point(in, nullptr);
      TracePoint pout = trace(r, k, pin, out, certified);
      auto hit = [column](const TracePoint& p, double pos) { return EdgeHit{pos, p.t1, p.t2, p.g, p.b, column}; };
      if (in_bottom ? r.bottom_pole : r.right_pole)
        (in_bottom ? bottom_entries : right_entries).push_back(hit(pin, in_bottom ? pin.t1 : pin.t2));
      if (out_left ? r.left_pole : r.top_pole)
        (out_left ? left_exits : top_exits).push_back(hit(pout, out_left ? pout.t2 : pout.t1));
    }
    return certified;
  }

  // Traces curve k from its entry to its exit in steps of s = t2 - t1, each step certified by
  // search::certify_step (no sign change of g, or exactly one, proved from bounds over the step's box); a step the
  // bound cannot certify is halved. Sign changes are located by Brent and become candidates. Returns the oriented
  // exit point; clears `certified` if a step at the minimum length, or the piece's step budget, was not enough.
  TracePoint trace(const Rect& r, int k, const TracePoint& pin, const Pair& out, bool& certified) {
    const double s_out = out.t2 - out.t1, span = s_out - pin.s;
    TracePoint cur = pin;
    if (!(span > 0)) return point(out, &cur.b);  // the curve only touches the cell at a corner
    double h = span, slope = 0.0;  // slope: dtau/ds estimate for the predictor
    int halvings = 0;
    examine_budget_ = kPieceBudget;
    auto turn_of = [](const Vec& x, const Vec& y) { return std::acos(std::min(1.0, std::abs(x.dot(y)))); };
    for (int budget = kPieceBudget;; --budget) {
      const double remaining = s_out - cur.s;
      const bool last = h >= remaining;
      const double step = last ? remaining : h;
      if (budget <= 0 || examine_budget_ <= 0) {  // b turns faster than the step control can follow
        ++st_.unresolved_pieces;
        certified = false;
        const TracePoint p = point(out, &cur.b);
        examine(r, k, cur, p, 0);
        return p;
      }
      if (opt_.certify_steps) {
        const TracePoint p =
            last ? point(out, &cur.b) : point(diagonal_root(r, cur.s + step, cur.t1 + slope * step, k), &cur.b);
        const search::StepCertificate cert = search::certify_step(md_, sym_, step_end(cur), step_end(p));
        if (cert.verdict != search::StepVerdict::Uncertified) {
          ++st_.certified_steps;
          halvings = 0;
          if ((cur.g > 0) != (p.g > 0)) locate_root(r, k, cur, p, false);
          if (p.s > cur.s) slope = (p.t1 - cur.t1) / (p.s - cur.s);
          if (last) return p;
          cur = p;
          h = std::min(span, std::clamp(cert.safe_length, 0.25 * step, 4.0 * step));
          continue;
        }
        // Shorten to the length the bound says it could prove; where that is below kCertifiedFloor of the piece (the
        // bound is too weak there, mostly next to pole lines), or after 10 tries, the step goes to the midpoint
        // check below.
        const double floor = kCertifiedFloor * span;
        const bool bounded = cert.gap > 0 && cert.curvature > 0;  // the bound was computed (not cut short)
        const bool hopeless = (bounded && cert.safe_length < floor) || ++halvings > 10 || 0.5 * step < floor ||
                              step <= hmin_;
        if (!hopeless) {
          h = std::max(hmin_, bounded ? std::min(0.5 * step, std::max(cert.safe_length, floor)) : 0.5 * step);
          continue;
        }
      }
      // Midpoint check: the turn of b is measured over both halves of the step (comparing only the ends would accept
      // a b that swings away and comes back near an avoided crossing), g examined on both halves. Not a proof.
      const TracePoint mid = point(diagonal_root(r, cur.s + 0.5 * step, cur.t1 + slope * 0.5 * step, k), &cur.b);
      const TracePoint q =
          last ? point(out, &mid.b) : point(diagonal_root(r, cur.s + step, cur.t1 + slope * step, k), &mid.b);
      const double turn = turn_of(cur.b, mid.b) + turn_of(mid.b, q.b);
      // next step aims at 0.6 max_turn, assuming the turn grows linearly with the step
      const double factor = turn > 0 ? 0.6 * opt_.max_turn / turn : 4.0;
      if (turn > opt_.max_turn && step > hmin_) {
        h = std::max(hmin_, step * std::clamp(factor, 0.1, 0.5));
        continue;
      }
      ++st_.heuristic_steps;
      if (opt_.certify_steps) certified = false;
      halvings = 0;
      examine(r, k, cur, mid, 0);
      examine(r, k, mid, q, 0);
      if (q.s > cur.s) slope = (q.t1 - cur.t1) / (q.s - cur.s);
      if (last) return q;
      cur = q;
      h = std::min(span, step * std::clamp(factor, 0.3, 4.0));
    }
  }

  // Heuristic acceptance (the midpoint check of earlier versions), used only where the certificate's bounds are too
  // weak (next to pole lines, where the pole mode's eigenvalue is huge and the single-gap resolvent bound fails):
  // g on [A, B] of curve k: locate sign changes, refine where a Hermite model of g dips towards zero.
  void examine(const Rect& r, int k, const TracePoint& A, const TracePoint& B, int depth) {
    const double h = B.s - A.s;
    auto guess = [&](double s) { return A.t1 + (B.t1 - A.t1) * (s - A.s) / h; };  // t1 interpolated in s
    // Hermite cubic in sigma in [0,1]
    auto herm = [&](double x) {
      const double h00 = (1 + 2 * x) * (1 - x) * (1 - x), h10 = x * (1 - x) * (1 - x);
      const double h01 = x * x * (3 - 2 * x), h11 = x * x * (x - 1);
      return h00 * A.g + h10 * h * A.dg + h01 * B.g + h11 * h * B.dg;
    };
    int changes = 0;
    double prev = A.g, xmin = 0.5, vmin = std::numeric_limits<double>::infinity();
    const int ns = 32;
    for (int i = 1; i <= ns; ++i) {
      const double x = static_cast<double>(i) / ns;
      const double v = i == ns ? B.g : herm(x);
      if ((v > 0) != (prev > 0)) ++changes;
      const double sv = (A.g > 0 ? v : -v);
      if (i < ns && sv < vmin) {
        vmin = sv;
        xmin = x;
      }
      prev = v;
    }
    const bool endpoints_differ = (A.g > 0) != (B.g > 0);
    const double gscale = std::max(std::abs(A.g), std::abs(B.g));
    // Interior dip of the model towards (or through) zero, away from the end values.
    const bool dip =
        vmin < 0.25 * std::min(std::abs(A.g), std::abs(B.g)) && vmin < 0.25 * gscale && xmin > 0.02 && xmin < 0.98;
    const bool suspicious = (endpoints_differ && changes > 1) || (!endpoints_differ && (changes > 0 || dip));
    if (suspicious) {
      if (h <= hmin_ || depth > 60 || examine_budget_ <= 0) {
        if (examine_budget_ <= 0 && !endpoints_differ) ++st_.unresolved_pieces;
        if (!endpoints_differ && std::min(std::abs(A.g), std::abs(B.g)) < 1e-8) {
          ++st_.uncertified_steps;
          candidates_.push_back({0.5 * (A.t1 + B.t1), 0.5 * (A.t2 + B.t2), true, false, {}});
        }
        if (!endpoints_differ) return;
      } else {
        --examine_budget_;
        const double s = A.s + (endpoints_differ ? 0.5 : xmin) * h;
        const TracePoint M = point(diagonal_root(r, s, guess(s), k), &A.b);
        examine(r, k, A, M, depth + 1);
        examine(r, k, M, B, depth + 1);
        return;
      }
    }
    if (endpoints_differ) locate_root(r, k, A, B, false);
  }

  // The one sign change of g between A and B: Brent on g(s), each evaluation a 1-D solve on the anti-diagonal.
  void locate_root(const Rect& r, int k, const TracePoint& A, const TracePoint& B, bool uncertified) {
    const double h = B.s - A.s;
    auto guess = [&](double s) { return A.t1 + (B.t1 - A.t1) * (s - A.s) / h; };  // t1 interpolated in s
    auto g_at = [&](double s) {
      const Pair e = diagonal_root(r, s, guess(s), k);
      Vec b = e.b;
      if (b.dot(A.b) < 0) b = -b;
      return onset_g(b, e.t2).first;
    };
    const double s = detail::brent(g_at, A.s, B.s, A.g, B.g, 1e-15 * (std::abs(A.s) + std::abs(B.s) + 1.0));
    const Pair e = diagonal_root(r, s, guess(s), k);
    candidates_.push_back({e.t1, e.t2, uncertified, false, e.b});
  }

  // Pairs the curves crossing one segment of a pole line (between two crossings with pole lines of the other
  // phase), in order along it: each exit from one side is the entry on the other side; a sign change of the
  // oriented g across the thin strip is an SPP there. Both lists sorted by position here.
  void pair_in_order(std::vector<EdgeHit>& from, std::vector<EdgeHit>& to) {
    for (size_t i = 0; i < std::min(from.size(), to.size()); ++i) pair(from[i], to[i]);
  }
  void pair(const EdgeHit& from, const EdgeHit& to) {
    ++st_.strip_pairs;
    double g2 = to.g;
    if (from.b.dot(to.b) < 0) g2 = -g2;
    if ((from.g > 0) != (g2 > 0))
      candidates_.push_back({0.5 * (from.t1 + to.t1), 0.5 * (from.t2 + to.t2), false, true, {}});
  }

  std::vector<Candidate> candidates_;

 private:
  const ModalForm& md_;
  const SolveOptions& opt_;
  SolveStats& st_;
  const double hmin_;                         // smallest trace step in s
  static constexpr int kPieceBudget = 20000;  // trace steps (tried or taken) per curve piece
  int examine_budget_ = kPieceBudget;
  static constexpr double kCertifiedFloor = 1e-4;  // shortest certified step, relative to the piece
  Symmetry sym_;
  Vec zhat_;
  double cached_t2_ = std::numeric_limits<double>::quiet_NaN();
  Mat C_, Hbuf_;
};

// Newton on the pole-free bordered system: N(t1,t2) a = 0, z^T cos(W t1) a = 0, a_ref^T a = 1.
struct Polished {
  bool converged = false;
  double t1 = 0, t2 = 0, residual = 1.0;
  Vec a;
};

double residual_of(const ModalForm& md, double t1, double t2, const Vec& a, Symmetry sym) {
  const Mat N = md.N(t1, t2, sym);
  const Vec p0 = md.onset_position(t1, a, sym);
  const double r1 = (N * a).norm() / (N.norm() * a.norm());
  const double r2 = std::abs(md.z().dot(p0)) / (md.z().norm() * std::max(p0.norm(), 1e-300));
  return std::max(r1, r2);
}

// Starting vector: a = p0 ./ cos(W t1) from the traced null vector p0 of H when the cosines are not small
// (near the axis t1 = 0, N has two small singular values and its SVD may pick the wrong one), else the SVD.
Polished polish(const ModalForm& md, double t1, double t2, const Vec& b = Vec(), Symmetry sym = Symmetry::Axial) {
  const int m = md.m();
  Polished out;
  Vec a;
  const Eigen::ArrayXd c1 = (md.omega().array() * t1).cos();
  if (b.size() == m && c1.abs().minCoeff() > 1e-3) {
    a = (b.array() / c1).matrix().normalized();
  } else {
    Eigen::JacobiSVD<Mat> svd(md.N(t1, t2, sym), Eigen::ComputeFullV);
    a = svd.matrixV().col(m - 1);
  }
  const Vec aref = a;
  const double t1_start = t1, t2_start = t2;
  double best = residual_of(md, t1, t2, a, sym);
  out = {false, t1, t2, best, a};
  for (int it = 0; it < 12; ++it) {
    const Mat N = md.N(t1, t2, sym);
    Vec F(m + 2);
    F.head(m) = N * a;
    F(m) = md.z().dot(md.onset_position(t1, a, sym));
    F(m + 1) = aref.dot(a) - 1.0;
    Mat J = Mat::Zero(m + 2, m + 2);
    J.block(0, 0, m, 1) = md.dN_dt1(t1, t2, sym) * a;
    J.block(0, 1, m, 1) = md.dN_dt2(t1, t2, sym) * a;
    J.block(0, 2, m, m) = N;
    J(m, 0) = md.z().dot(md.onset_position_dt1(t1, a, sym));
    J.block(m, 2, 1, m) = md.onset_position(t1, md.z(), sym).transpose();  // a diagonal map: its row is z's image
    J.block(m + 1, 2, 1, m) = aref.transpose();
    Vec dx = J.fullPivLu().solve(-F);
    // trust region: stay near the candidate (the limit points on the axes attract Newton) and keep t1 > 0
    double alpha = 1.0;
    while (alpha > 1e-6 &&
           (t1 + alpha * dx(0) < 0.5 * t1 || t2 + alpha * dx(1) < 0.5 * t2 ||
            std::hypot(t1 + alpha * dx(0) - t1_start, t2 + alpha * dx(1) - t2_start) > 1e-3 * (t1_start + t2_start)))
      alpha *= 0.5;
    dx *= alpha;
    t1 += dx(0);
    t2 += dx(1);
    a += dx.tail(m);
    const double res = residual_of(md, t1, t2, a, sym);
    if (res < best) {
      best = res;
      out = {false, t1, t2, res, a};
    }
    if (dx.head(2).norm() <= 1e-15 * (std::abs(t1) + std::abs(t2))) break;
  }
  out.converged = best < 1e-10;
  return out;
}

// g0 = 0 is refused by every entry point with the same message.
void require_nonzero_gap(const System& system) {
  if (system.g0() == 0.0)
    throw std::invalid_argument(
        "system: g0 = 0 (obstacle touching the rest position): SPPs then exist only for special parameter "
        "values (paper §6.1) and need one more unknown: declare a parameter in the system file (\"parameter\": "
        "{\"name\", \"min\", \"max\"}, M/K/w affine in it) and run spp solve without --at, or "
        "continue_branches() and gap_closures().");
}

Solution build_solution(const System& system, const ModalForm& md, const Polished& p, const SolveOptions& opt,
                        bool with_return_error) {
  Solution s;
  s.t1 = p.t1;
  s.t2 = p.t2;
  s.period = 2.0 * (p.t1 + p.t2);
  s.residual = p.residual;
  s.orbit = make_orbit(md, p.t1, p.t2, p.a, opt.symmetry);
  if (opt.symmetry == Symmetry::Point) {
    s.admissibility = check_point_admissibility(md, s.orbit);
    s.flags.push_back("point_symmetric");
  } else {
    s.admissibility = check_admissibility(md, s.orbit, opt.admissibility_tol);
  }
  if (s.orbit.closure_ratio < 1e-10) s.flags.push_back("gap_closure_degenerate");
  s.admissible = s.admissibility.admissible;
  s.min_gap = s.admissibility.min_gap;
  s.min_force = s.admissibility.min_force;
  s.energy = s.orbit.energy;
  for (Eigen::Index k = 0; k < md.omega_decoupled().size(); ++k) {
    const double r = md.omega_decoupled()(k) * (p.t1 + p.t2) / std::numbers::pi;
    if (std::abs(r - std::round(r)) < 1e-9 * std::max(1.0, r)) s.flags.push_back("decoupled_mode_resonant");
  }
  if (with_return_error) s.return_error = return_error(system, s.orbit);
  return s;
}

}  // namespace

std::pair<double, double> default_lower_ends(const ModalForm& md, double t1_max, double t2_max) {
  const double pi = std::numbers::pi, dmax = md.d().maxCoeff();
  return {std::min(1e-4 * pi / (2.0 * md.omega().maxCoeff()), 1e-3 * t1_max),
          std::min(dmax > 0 ? 1e-4 * pi / (2.0 * dmax) : 1e-4 * t2_max, 1e-3 * t2_max)};
}

Solution solution_at(const System& system, double t1, double t2, const SolveOptions& options) {
  if (!(std::isfinite(t1) && t1 > 0 && std::isfinite(t2) && t2 > 0)) {
    std::ostringstream os;
    os << "solution_at: t1 and t2 must be positive and finite, got t1 = " << t1 << ", t2 = " << t2;
    throw std::invalid_argument(os.str());
  }
  require_nonzero_gap(system);
  const ModalForm md(system);
  const Polished p = polish(md, t1, t2, Vec(), options.symmetry);
  if (!p.converged || std::hypot(p.t1 - t1, p.t2 - t2) > 1e-3 * (t1 + t2)) {
    std::ostringstream os;
    os << "solution_at: no SPP near (t1, t2) = (" << t1 << ", " << t2 << "): Newton reached residual " << p.residual
       << " at (" << p.t1 << ", " << p.t2 << ")";
    throw std::invalid_argument(os.str());
  }
  return build_solution(system, md, p, options, options.compute_return_error);
}

namespace {

// ---- Step 1: plan the window ----
// One axis of the search region: breakpoints (region edges and pole lines), which are poles, and the margin kept on
// each side of a pole line (0 at region edges).
struct AxisPlan {
  std::vector<double> bp;
  std::vector<bool> pole;
  std::vector<double> margin;
  size_t cells() const { return bp.size() - 1; }
};

// The region searched for the window (lo, hi] of one phase: the window widened by a hair (roots found outside the
// window are dropped by the half-open membership rule, so a root on a tile edge is found by both tiles and kept by
// one), and, where an edge falls within kEdgePole of a pole line, widened past that line so that the line is
// interior and its thin strip is covered by pairing (a window edge is never snapped onto a pole line).
AxisPlan plan_axis(const Eigen::VectorXd& freqs, double lo, double hi, bool widen_lo, double pole_margin,
                   double max_count) {
  constexpr double kEdgeSlack = 1e-9;  // relative widening of the window edges
  const double fmax = freqs.size() ? freqs.maxCoeff() : 0.0;
  const double kappa = fmax > 0 ? 1e-4 * std::numbers::pi / (2.0 * fmax) : 0.0;  // kEdgePole: 1e-4 quarter period
  double rlo = widen_lo ? lo - kEdgeSlack * (hi - lo) : lo, rhi = hi + kEdgeSlack * (hi - lo);
  for (int pass = 0; pass < 8 && kappa > 0; ++pass) {  // poles may cluster: widen until no pole is near an edge
    bool moved = false;
    if (widen_lo) {
      const auto near = tangent_poles(freqs, std::max(0.0, rlo - kappa), rlo + kappa, max_count);
      if (!near.empty()) {
        rlo = std::max(0.5 * near.front(), near.front() - kappa);
        moved = true;
      }
    }
    const auto near = tangent_poles(freqs, rhi - kappa, rhi + kappa, max_count);
    if (!near.empty()) {
      rhi = near.back() + kappa;
      moved = true;
    }
    if (!moved) break;
  }
  AxisPlan a;
  a.bp.push_back(rlo);
  a.pole.push_back(false);
  for (double p : tangent_poles(freqs, rlo, rhi, max_count)) {
    a.bp.push_back(p);
    a.pole.push_back(true);
  }
  a.bp.push_back(rhi);
  a.pole.push_back(false);
  a.margin.assign(a.bp.size(), 0.0);
  for (size_t i = 1; i + 1 < a.bp.size(); ++i) {
    const double left = a.bp[i] - a.bp[i - 1], right = a.bp[i + 1] - a.bp[i];
    a.margin[i] = std::max(std::min(pole_margin * std::max(left, right), 0.25 * std::min(left, right)),
                           4e-16 * a.bp[i]);
  }
  return a;
}

// Counts the cells before anything is listed: windows beyond max_cells are refused with their count.
void check_window_size(const ModalForm& md, const SolveOptions& opt) {
  const double c1 = count_tangent_poles(md.omega(), opt.t1_min, opt.t1_max) + 1.0;
  const double c2 = count_tangent_poles(md.d(), opt.t2_min, opt.t2_max) + 1.0;
  if (c1 * c2 > static_cast<double>(opt.max_cells)) {
    std::ostringstream os;
    os << "options: the window (" << opt.t1_min << ", " << opt.t1_max << "] x (" << opt.t2_min << ", " << opt.t2_max
       << "] holds about " << c1 * c2 << " cells (" << c1 - 1 << " x " << c2 - 1
       << " pole lines), more than max_cells = " << opt.max_cells
       << ": narrow the window, or raise max_cells (--max-cells) if the work is intended";
    throw std::invalid_argument(os.str());
  }
}

// ---- Step 4: pair across pole lines ----
// Hits of the curves on the pole lines, per cell: v_from[i][j] exits of cell (i, j) through its left edge (line
// i), v_to[i][j] entries of cell (i - 1, j) through its right edge; h_from[j][i] exits of cell (i, j - 1) through its
// top edge (line j), h_to[j][i] entries of cell (i, j) through its bottom edge.
struct PoleHits {
  std::vector<std::vector<std::vector<EdgeHit>>> v_from, v_to, h_from, h_to;
};

// Each segment of a pole line between two crossings with lines of the other phase is paired in order. A curve may
// also pass diagonally through the tiny square where a vertical and a horizontal line cross: from the cell below
// right, leaving through its left edge, into the cell above left through its bottom edge (or through the top edge
// into the right edge). It shows as one extra exit at the top end of a vertical segment and one extra entry at the
// right end of a horizontal segment (or the mirror): those are paired with each other, per crossing. Anything else
// that does not pair is counted as unpaired.
void pair_across_pole_lines(Search& merger, PoleHits& hits, const AxisPlan& a1, const AxisPlan& a2,
                            SolveStats& stats, std::vector<UncertifiedRegion>& uncertified) {
  const size_t I = a1.cells(), J = a2.cells();
  std::map<std::pair<size_t, size_t>, std::vector<EdgeHit>> diag_out_v, diag_in_h, diag_out_h, diag_in_v;
  auto by_pos = [](const EdgeHit& x, const EdgeHit& y) { return x.pos < y.pos; };
  auto unpaired = [&](long count, double t1, double t2) {
    stats.unpaired_crossings += count;
    uncertified.push_back({t1, t1, t2, t2, "pairing"});
  };
  for (size_t i = 1; i < I; ++i) {  // vertical lines, segment j between horizontal lines j and j + 1
    if (!a1.pole[i]) continue;
    for (size_t j = 0; j < J; ++j) {
      auto& from = hits.v_from[i][j];
      auto& to = hits.v_to[i][j];
      std::sort(from.begin(), from.end(), by_pos);
      std::sort(to.begin(), to.end(), by_pos);
      if (from.size() == to.size() + 1 && j + 1 < J && a2.pole[j + 1]) {
        diag_out_v[{i, j + 1}].push_back(from.back());
        from.pop_back();
      } else if (to.size() == from.size() + 1 && j > 0 && a2.pole[j]) {
        diag_in_v[{i, j}].push_back(to.front());
        to.erase(to.begin());
      }
      if (from.size() != to.size())
        unpaired(static_cast<long>(std::max(from.size(), to.size()) - std::min(from.size(), to.size())), a1.bp[i],
                 a2.bp[j]);
      else
        merger.pair_in_order(from, to);
    }
  }
  for (size_t j = 1; j < J; ++j) {  // horizontal lines, segment i between vertical lines i and i + 1
    if (!a2.pole[j]) continue;
    for (size_t i = 0; i < I; ++i) {
      auto& from = hits.h_from[j][i];
      auto& to = hits.h_to[j][i];
      std::sort(from.begin(), from.end(), by_pos);
      std::sort(to.begin(), to.end(), by_pos);
      if (from.size() == to.size() + 1 && i > 0 && a1.pole[i]) {
        diag_out_h[{i, j}].push_back(from.front());
        from.erase(from.begin());
      } else if (to.size() == from.size() + 1 && i + 1 < I && a1.pole[i + 1]) {
        diag_in_h[{i + 1, j}].push_back(to.back());
        to.pop_back();
      }
      if (from.size() != to.size())
        unpaired(static_cast<long>(std::max(from.size(), to.size()) - std::min(from.size(), to.size())), a1.bp[i],
                 a2.bp[j]);
      else
        merger.pair_in_order(from, to);
    }
  }
  // diagonal passes: left edge of the lower-right cell -> bottom edge of the upper-left cell, and top edge of the
  // lower-right cell -> right edge of the upper-left cell
  auto match = [&](auto& outs, auto& ins) {
    for (auto& [key, o] : outs) {
      auto it = ins.find(key);
      if (it != ins.end() && it->second.size() == o.size()) {
        for (size_t q = 0; q < o.size(); ++q) merger.pair(o[q], it->second[q]);
        ins.erase(it);
      } else {
        unpaired(static_cast<long>(o.size()), a1.bp[key.first], a2.bp[key.second]);
      }
    }
    for (auto& [key, in] : ins) unpaired(static_cast<long>(in.size()), a1.bp[key.first], a2.bp[key.second]);
  };
  match(diag_out_v, diag_in_h);
  match(diag_out_h, diag_in_v);
}

}  // namespace

SolveResult solve(const System& system, const SolveOptions& options) {
  options.validate();
  require_nonzero_gap(system);
  const auto t0 = std::chrono::steady_clock::now();
  SolveResult res;
  const ModalForm md(system);
  res.decoupled_modes = static_cast<int>(md.omega_decoupled().size());
  res.symmetry = options.symmetry;
  res.repeated_groups = md.repeated_groups();

  // Step 1: the window, its search region and its cells, planned (and refused if too large) before any evaluation.
  SolveOptions opt = options;
  const auto [t1_auto, t2_auto] = default_lower_ends(md, opt.t1_max, opt.t2_max);
  const bool axis1 = opt.t1_min == 0.0, axis2 = opt.t2_min == 0.0;
  if (axis1) opt.t1_min = t1_auto;
  if (axis2) opt.t2_min = t2_auto;
  check_window_size(md, opt);
  const double max_lines = static_cast<double>(opt.max_cells) + 16.0;
  const AxisPlan a1 = plan_axis(md.omega(), opt.t1_min, opt.t1_max, !axis1, opt.pole_margin, max_lines);
  const AxisPlan a2 = plan_axis(md.d(), opt.t2_min, opt.t2_max, !axis2, opt.pole_margin, max_lines);
  res.stats.flight_pole_lines = static_cast<int>(std::count(a1.pole.begin(), a1.pole.end(), true));
  res.stats.contact_pole_lines = static_cast<int>(std::count(a2.pole.begin(), a2.pole.end(), true));
  res.t1_min = opt.t1_min;
  res.t1_max = opt.t1_max;
  res.t2_min = opt.t2_min;
  res.t2_max = opt.t2_max;

  // Steps 2-3: count at the corners and trace the pieces, cell by cell. Strips between t2 breakpoints are
  // independent: workers take whole strips, each with its own Search (own cache and counters); pairing and polish
  // follow in order, so the result does not depend on the number of threads.
  const size_t I = a1.cells(), J = a2.cells();
  PoleHits hits;
  hits.v_from.assign(I + 1, std::vector<std::vector<EdgeHit>>(J));
  hits.v_to = hits.v_from;
  hits.h_from.assign(J + 1, std::vector<std::vector<EdgeHit>>(I));
  hits.h_to = hits.h_from;
  struct StripOut {
    std::vector<Candidate> candidates;
    std::vector<UncertifiedRegion> uncertified;
    SolveStats stats;
  };
  std::vector<StripOut> strips(J);
  std::atomic<size_t> next_strip{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto worker = [&]() {
    try {
      for (size_t j = next_strip++; j < J; j = next_strip++) {
        StripOut& out = strips[j];
        Search search(md, opt, out.stats);
        for (size_t i = 0; i < I; ++i) {
          Search::Rect r{a1.bp[i] + a1.margin[i], a1.bp[i + 1] - a1.margin[i + 1], a2.bp[j] + a2.margin[j],
                         a2.bp[j + 1] - a2.margin[j + 1], a1.pole[i], a1.pole[i + 1], a2.pole[j], a2.pole[j + 1]};
          if (!(r.a1 < r.b1 && r.A < r.B)) continue;
          // curves leave through the left edge (pole line i) into the right edge of cell i - 1, and through the
          // top edge (pole line j + 1) into the bottom edge of strip j + 1
          if (!search.rectangle(r, i, hits.v_from[i][j], hits.h_from[j + 1][i], hits.v_to[i + 1][j],
                                hits.h_to[j][i]))
            out.uncertified.push_back({r.a1, r.b1, r.A, r.B, "step"});
        }
        out.candidates = std::move(search.candidates_);
      }
    } catch (...) {
      const std::lock_guard<std::mutex> lock(failure_mutex);
      failure = std::current_exception();
    }
  };
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  const size_t nthreads = std::min<size_t>(J, opt.threads > 0 ? static_cast<size_t>(opt.threads) : hw);
  std::vector<std::thread> pool;
  for (size_t t = 1; t < nthreads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& th : pool) th.join();
  if (failure) std::rethrow_exception(failure);

  // Step 4: pair across pole lines.
  Search merger(md, opt, res.stats);
  pair_across_pole_lines(merger, hits, a1, a2, res.stats, res.uncertified);
  std::vector<Candidate> candidates;
  for (StripOut& out : strips) {
    const SolveStats& s = out.stats;
    res.stats.rectangles += s.rectangles;
    res.stats.curve_pieces += s.curve_pieces;
    res.stats.evaluations += s.evaluations;
    res.stats.certified_steps += s.certified_steps;
    res.stats.heuristic_steps += s.heuristic_steps;
    res.stats.uncertified_steps += s.uncertified_steps;
    res.stats.uncertified_corners += s.uncertified_corners;
    res.stats.unresolved_pieces += s.unresolved_pieces;
    for (auto& c : out.candidates) candidates.push_back(std::move(c));
    for (auto& u : out.uncertified) res.uncertified.push_back(std::move(u));
  }
  for (auto& c : merger.candidates_) candidates.push_back(std::move(c));

  // Step 5: polish, keep the roots inside the half-open window, deduplicate, build orbits.
  const double window_scale = opt.t1_max + opt.t2_max;
  auto inside = [&](double t1, double t2) {
    return t1 > (axis1 ? 2.0 * opt.t1_min : opt.t1_min) && t1 <= opt.t1_max &&
           t2 > (axis2 ? 2.0 * opt.t2_min : opt.t2_min) && t2 <= opt.t2_max;
  };
  for (const Candidate& c : candidates) {
    const Polished p = polish(md, c.t1, c.t2, c.b, opt.symmetry);
    // Where Newton stalls with a small residual (N nearly rank-deficient in two directions, e.g. close to
    // the limit points on the axis t1 = 0) the root is reported with a flag. A candidate that does not
    // polish at all is not reported as an SPP: it is a gap in the search, and the status says so.
    if (!p.converged && !(p.residual < 1e-6)) {
      if (!inside(c.t1, c.t2)) continue;
      ++res.stats.unpolished_roots;
      res.uncertified.push_back({c.t1, c.t1, c.t2, c.t2, "polish"});
      std::ostringstream os;
      os << "a sign change of g near (t1, t2) = (" << c.t1 << ", " << c.t2 << ") did not polish to a root (residual "
         << p.residual << ")";
      res.warnings.push_back(os.str());
      continue;
    }
    const char* accuracy_flag = p.converged ? nullptr : "ill_conditioned";
    // Axis windows: each point (0, m pi / d_j) where a curve leaves the axis t1 = 0 satisfies both equations in
    // the limit (pure contact oscillation); roots within 2 t1_min of the axis are these limits, not SPPs.
    if (!inside(p.t1, p.t2)) continue;
    bool dup = false;
    for (const Solution& s : res.solutions)
      if (std::hypot(s.t1 - p.t1, s.t2 - p.t2) <= 1e-9 * window_scale) dup = true;
    if (dup) continue;
    Solution s;
    try {
      s = build_solution(system, md, p, opt, options.compute_return_error);
    } catch (const std::invalid_argument& e) {
      res.warnings.push_back(std::string("root skipped: ") + e.what());
      continue;
    }
    if (c.uncertified) s.flags.push_back("uncertified_step");
    if (accuracy_flag) s.flags.push_back(accuracy_flag);
    if (c.near_pole) s.flags.push_back("near_pole_line");
    res.solutions.push_back(std::move(s));
  }

  // Step 6: finalize: order, filter, status with its counted causes.
  res.stats.roots = static_cast<long>(res.solutions.size());
  std::sort(res.solutions.begin(), res.solutions.end(),
            [](const Solution& a, const Solution& b) { return a.period < b.period; });
  if (options.admissible_only)
    res.solutions.erase(
        std::remove_if(res.solutions.begin(), res.solutions.end(), [](const Solution& s) { return !s.admissible; }),
        res.solutions.end());
  const SolveStats& st = res.stats;
  auto cause = [&](long count, const char* what) {
    if (count > 0) res.warnings.push_back(std::to_string(count) + " " + what);
  };
  cause(st.uncertified_steps, "trace step(s) could not be certified at the minimum step length (g touches zero "
                              "within the bounds' resolution: a near-double root, or nearly equal eigenvalues)");
  cause(st.unresolved_pieces, "curve piece(s) ran out of their step budget (nearly equal eigenvalues): a root there "
                              "is not excluded");
  cause(st.uncertified_corners, "cell corner(s) kept an eigenvalue within its error bound of zero");
  cause(st.unpaired_crossings, "curve crossing(s) of a pole line could not be paired: a root in that thin strip is "
                               "not excluded");
  for (const Solution& s : res.solutions)
    if (!s.admissibility.certified) res.warnings.push_back("admissibility of an SPP not certified to tolerance");
  res.status = res.warnings.empty() && res.uncertified.empty() ? SolveStatus::Success : SolveStatus::Incomplete;
  res.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

NearestSpp nearest_spp(const System& system, double t1, double t2, double radius, const SolveOptions& options) {
  if (!(std::isfinite(t1) && t1 > 0 && std::isfinite(t2) && t2 > 0)) {
    std::ostringstream os;
    os << "nearest_spp: t1 and t2 must be positive and finite, got t1 = " << t1 << ", t2 = " << t2;
    throw std::invalid_argument(os.str());
  }
  if (!(radius > 0 && radius < 1)) {
    std::ostringstream os;
    os << "nearest_spp: radius must be in (0, 1), got " << radius;
    throw std::invalid_argument(os.str());
  }
  SolveOptions o = options;
  o.t1_min = t1 * (1 - radius);
  o.t1_max = t1 * (1 + radius);
  o.t2_min = t2 * (1 - radius);
  o.t2_max = t2 * (1 + radius);
  o.admissible_only = false;
  const SolveResult r = solve(system, o);
  NearestSpp out;
  out.search_status = r.status;
  out.t1_lo = o.t1_min;
  out.t1_hi = o.t1_max;
  out.t2_lo = o.t2_min;
  out.t2_hi = o.t2_max;
  out.candidates = static_cast<long>(r.solutions.size());
  double best = std::numeric_limits<double>::infinity();
  for (const Solution& s : r.solutions) {
    const double d = std::hypot((s.t1 - t1) / t1, (s.t2 - t2) / t2);
    if (d < best) {
      best = d;
      out.solution = s;
      out.found = true;
    }
  }
  return out;
}

}  // namespace spp
