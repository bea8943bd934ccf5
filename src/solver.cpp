#include "spp/solver.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <mutex>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "spp/detail/brent.hpp"
#include "spp/detail/tridiagonal.hpp"
#include "spp/modal.hpp"

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
  Vec b;
};

struct EdgeHit {
  double pos = 0;  // coordinate along the pole line (t2 on a vertical line, t1 on a horizontal one)
  double t1 = 0, t2 = 0, g = 0;
  Vec b;
};

struct Candidate {
  double t1, t2;
  bool near_double = false, near_pole = false;
  Eigen::VectorXd b;  // null vector of H from the trace (empty: take the SVD of N)
};

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
    const Vec c = md_.onset_direction(t2, sym_);
    const double cn = c.norm();
    const Vec ch = c / cn;
    const double g = ch.dot(b);
    if (!db) return {g, 0.0};
    const Vec dc = md_.onset_direction_dt2(t2, sym_) * dt2_ds;
    return {g, ch.dot(*db) + (dc - ch * ch.dot(dc)).dot(b) / cn};
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
  };
  Pair eigenpair(double t1, double t2, int k) {
    const detail::SymmetricTridiagonal T(H_at(t1, t2));
    Pair p{t1, t2, T.eigenvalue(k), T.norm_bound(), Vec()};
    p.b = T.eigenvector(p.lam);
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

  void rectangle(const Rect& r, std::vector<EdgeHit>& left_exits, std::vector<EdgeHit>& top_exits,
                 std::vector<EdgeHit>& right_entries, std::vector<EdgeHit>& bottom_entries) {
    ++st_.rectangles;
    const detail::SymmetricTridiagonal BLt = corner(r.a1, r.A), TRt = corner(r.b1, r.B);
    const int kmin = TRt.count_below(0.0), kmax = BLt.count_below(0.0);  // curves k in [kmin, kmax)
    if (kmin >= kmax) return;
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
      TracePoint pout = trace(r, k, pin, out);
      auto hit = [](const TracePoint& p, double pos) { return EdgeHit{pos, p.t1, p.t2, p.g, p.b}; };
      if (in_bottom ? r.bottom_pole : r.right_pole)
        (in_bottom ? bottom_entries : right_entries).push_back(hit(pin, in_bottom ? pin.t1 : pin.t2));
      if (out_left ? r.left_pole : r.top_pole)
        (out_left ? left_exits : top_exits).push_back(hit(pout, out_left ? pout.t2 : pout.t1));
    }
  }

  // Trace curve k from entry to exit; returns the oriented exit point. Roots of g go to candidates_.
  TracePoint trace(const Rect& r, int k, const TracePoint& pin, const Pair& out) {
    const double s_in = pin.s, s_out = out.t2 - out.t1;
    const double span = s_out - s_in;
    TracePoint cur = pin;
    if (!(span > 0)) {
      TracePoint p = point(out, &cur.b);
      examine(r, k, cur, p, 0);
      return p;
    }
    double h = span;
    double slope = 0.0;  // dtau/ds estimate for the predictor
    budget_ = kPieceBudget;
    while (cur.s < s_out) {
      if (--budget_ < 0) {  // b turns faster than the step control can follow (near-degenerate eigenvalues)
        ++st_.unresolved_pieces;
        TracePoint p = point(out, &cur.b);
        examine(r, k, cur, p, 0);
        return p;
      }
      const double remaining = s_out - cur.s;
      const bool last = h >= remaining;
      const double step = last ? remaining : h;
      // The turn of b is measured over both halves of the step: comparing only the ends would accept a b that
      // swings away and comes back (near an avoided crossing of two eigenvalues), losing the orientation of g
      // or a pair of roots in between.
      const TracePoint mid = point(diagonal_root(r, cur.s + 0.5 * step, cur.t1 + slope * 0.5 * step, k), &cur.b);
      TracePoint p;
      if (last) {
        p = point(out, &mid.b);
      } else {
        p = point(diagonal_root(r, cur.s + step, cur.t1 + slope * step, k), &mid.b);
      }
      auto turn_of = [](const Vec& x, const Vec& y) { return std::acos(std::min(1.0, std::abs(x.dot(y)))); };
      const double turn = turn_of(cur.b, mid.b) + turn_of(mid.b, p.b);
      // next step aims at 0.6 max_turn, assuming the turn grows linearly with the step
      const double factor = turn > 0 ? 0.6 * opt_.max_turn / turn : 4.0;
      if (turn > opt_.max_turn && step > hmin_) {
        h = std::max(hmin_, step * std::clamp(factor, 0.1, 0.5));  // h < step <= remaining: not last
        continue;
      }
      examine(r, k, cur, mid, 0);
      examine(r, k, mid, p, 0);
      if (p.s > cur.s) slope = (p.t1 - cur.t1) / (p.s - cur.s);
      if (last) return p;
      cur = p;
      h = std::min(span, step * std::clamp(factor, 0.3, 4.0));
    }
    return cur;
  }

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
      if (h <= hmin_ || depth > 60 || budget_ <= 0) {
        if (budget_ <= 0 && !endpoints_differ) ++st_.unresolved_pieces;
        if (!endpoints_differ && std::min(std::abs(A.g), std::abs(B.g)) < 1e-8) {
          ++st_.near_double_roots;
          candidates_.push_back({0.5 * (A.t1 + B.t1), 0.5 * (A.t2 + B.t2), true, false, {}});
        }
        if (!endpoints_differ) return;
      } else {
        --budget_;
        const double s = A.s + (endpoints_differ ? 0.5 : xmin) * h;
        const TracePoint M = point(diagonal_root(r, s, guess(s), k), &A.b);
        examine(r, k, A, M, depth + 1);
        examine(r, k, M, B, depth + 1);
        return;
      }
    }
    if (!endpoints_differ) return;
    // One sign change: Brent on g(s), each evaluation a 1-D solve on the anti-diagonal.
    auto g_at = [&](double s) {
      const Pair e = diagonal_root(r, s, guess(s), k);
      Vec b = e.b;
      if (b.dot(A.b) < 0) b = -b;
      return onset_g(b, e.t2).first;
    };
    const double s = detail::brent(g_at, A.s, B.s, A.g, B.g, 1e-15 * (std::abs(A.s) + std::abs(B.s) + 1.0));
    const Pair e = diagonal_root(r, s, guess(s), k);
    candidates_.push_back({e.t1, e.t2, false, false, e.b});
  }

  // Pairs curves across one pole line, in order along it (both lists are sorted here); a sign change of the oriented g
  // inside the thin strip is an SPP there.
  void pair_across(std::vector<EdgeHit>& from, std::vector<EdgeHit>& to) {
    auto by_pos = [](const EdgeHit& x, const EdgeHit& y) { return x.pos < y.pos; };
    std::sort(from.begin(), from.end(), by_pos);
    std::sort(to.begin(), to.end(), by_pos);
    if (from.size() != to.size()) {
      st_.unpaired_crossings += static_cast<long>(std::max(from.size(), to.size()) - std::min(from.size(), to.size()));
      return;
    }
    for (size_t i = 0; i < from.size(); ++i) {
      ++st_.strip_pairs;
      double g2 = to[i].g;
      if (from[i].b.dot(to[i].b) < 0) g2 = -g2;
      if ((from[i].g > 0) != (g2 > 0))
        candidates_.push_back({0.5 * (from[i].t1 + to[i].t1), 0.5 * (from[i].t2 + to[i].t2), false, true, {}});
    }
  }

  std::vector<Candidate> candidates_;

 private:
  const ModalForm& md_;
  const SolveOptions& opt_;
  SolveStats& st_;
  const double hmin_;                         // smallest trace step in s
  static constexpr int kPieceBudget = 20000;  // trace steps and subdivisions per curve piece
  int budget_ = kPieceBudget;
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

SolveResult solve(const System& system, const SolveOptions& options) {
  options.validate();
  require_nonzero_gap(system);
  const auto t0 = std::chrono::steady_clock::now();
  SolveResult res;
  const ModalForm md(system);
  res.decoupled_modes = static_cast<int>(md.omega_decoupled().size());
  res.symmetry = options.symmetry;
  res.repeated_groups = md.repeated_groups();
  SolveOptions opt = options;
  const auto [t1_min, t2_min] = default_lower_ends(md, opt.t1_max, opt.t2_max);
  if (opt.t1_min == 0.0) opt.t1_min = t1_min;
  if (opt.t2_min == 0.0) opt.t2_min = t2_min;

  // Breakpoints: window edges and pole lines. A window edge within 1e-6 (relative) of a pole line is moved
  // onto that line, so that no sliver rectangle next to a pole (where H is huge) is left.
  auto breakpoints = [&](std::vector<double> poles, double lo, double hi, std::vector<double>& bp,
                         std::vector<bool>& is_pole) {
    bp.clear();
    is_pole.clear();
    const bool lo_on_pole = !poles.empty() && poles.front() - lo <= 1e-6 * poles.front();
    const bool hi_on_pole = !poles.empty() && hi - poles.back() <= 1e-6 * hi;
    if (!lo_on_pole) {
      bp.push_back(lo);
      is_pole.push_back(false);
    }
    for (double p : poles) {
      bp.push_back(p);
      is_pole.push_back(true);
    }
    if (!hi_on_pole) {
      bp.push_back(hi);
      is_pole.push_back(false);
    }
  };
  const auto p1 = md.flight_poles(opt.t1_min, opt.t1_max), p2 = md.contact_poles(opt.t2_min, opt.t2_max);
  res.stats.flight_pole_lines = static_cast<int>(p1.size());
  res.stats.contact_pole_lines = static_cast<int>(p2.size());
  std::vector<double> b1, b2;
  std::vector<bool> pole1, pole2;
  breakpoints(p1, opt.t1_min, opt.t1_max, b1, pole1);
  breakpoints(p2, opt.t2_min, opt.t2_max, b2, pole2);
  if (b1.size() < 2 || b2.size() < 2)
    throw std::invalid_argument("options: the window holds a single pole line and nothing else; widen it");
  // margin kept on each side of breakpoint i (0 at window edges)
  auto margins = [&](const std::vector<double>& bp, const std::vector<bool>& is_pole) {
    std::vector<double> mg(bp.size(), 0.0);
    for (size_t i = 0; i < bp.size(); ++i) {
      const double left = i > 0 ? bp[i] - bp[i - 1] : bp[i + 1] - bp[i];
      const double right = i + 1 < bp.size() ? bp[i + 1] - bp[i] : left;
      const double mgn = opt.pole_margin * std::min(left, right);
      mg[i] = is_pole[i] ? std::max(mgn, 4e-16 * bp[i]) : 0.0;
    }
    return mg;
  };
  const auto m1 = margins(b1, pole1), m2 = margins(b2, pole2);
  res.t1_min = b1.front();
  res.t1_max = b1.back();
  res.t2_min = b2.front();
  res.t2_max = b2.back();

  // Strips between t2 pole lines are independent: workers take whole strips, each with its own Search (own
  // cache and counters). Pairing across pole lines and the polish follow in order, so the result does not
  // depend on the number of threads.
  const size_t I = b1.size() - 1, J = b2.size() - 1;
  struct StripOut {
    std::vector<Candidate> candidates;
    std::vector<std::vector<EdgeHit>> v_from, v_to;  // this strip's hits on each vertical pole line
    std::vector<EdgeHit> top_exits, bottom_entries;
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
        out.v_from.resize(b1.size());
        out.v_to.resize(b1.size());
        Search search(md, opt, out.stats);
        for (size_t i = 0; i < I; ++i) {
          Search::Rect r{b1[i] + m1[i], b1[i + 1] - m1[i + 1], b2[j] + m2[j], b2[j + 1] - m2[j + 1],
                         pole1[i],      pole1[i + 1],          pole2[j],      pole2[j + 1]};
          if (!(r.a1 < r.b1 && r.A < r.B)) continue;
          // curves leave through the left edge (pole line i) into the right edge of cell i - 1, and through
          // the top edge (pole line j + 1) into the bottom edge of strip j + 1
          search.rectangle(r, out.v_from[i], out.top_exits, out.v_to[i + 1], out.bottom_entries);
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

  Search merger(md, opt, res.stats);
  for (size_t j = 1; j < J; ++j) {  // horizontal pole lines
    if (!pole2[j]) continue;
    auto& from = strips[j - 1].top_exits;
    auto& to = strips[j].bottom_entries;
    merger.pair_across(from, to);
  }
  for (size_t i = 1; i + 1 < b1.size(); ++i) {  // vertical pole lines, over all strips
    if (!pole1[i]) continue;
    std::vector<EdgeHit> from, to;
    for (size_t j = 0; j < J; ++j) {
      for (auto& h : strips[j].v_from[i]) from.push_back(std::move(h));
      for (auto& h : strips[j].v_to[i]) to.push_back(std::move(h));
    }
    merger.pair_across(from, to);
  }
  std::vector<Candidate> candidates;
  for (StripOut& out : strips) {
    res.stats.rectangles += out.stats.rectangles;
    res.stats.curve_pieces += out.stats.curve_pieces;
    res.stats.evaluations += out.stats.evaluations;
    res.stats.near_double_roots += out.stats.near_double_roots;
    res.stats.unresolved_pieces += out.stats.unresolved_pieces;
    for (auto& c : out.candidates) candidates.push_back(std::move(c));
  }
  for (auto& c : merger.candidates_) candidates.push_back(std::move(c));

  // Polish, deduplicate, build orbits.
  const double window_scale = opt.t1_max + opt.t2_max;
  for (const Candidate& c : candidates) {
    const Polished p = polish(md, c.t1, c.t2, c.b, opt.symmetry);
    // Where Newton stalls with a small residual (N nearly rank-deficient in two directions, e.g. close to
    // the limit points on the axis t1 = 0) the root is reported with a flag. A candidate that does not
    // polish at all is not reported as an SPP: it is a gap in the search, and the status says so.
    if (!p.converged && !(p.residual < 1e-6)) {
      std::ostringstream os;
      os << "a sign change of g near (t1, t2) = (" << c.t1 << ", " << c.t2 << ") did not polish to a root (residual "
         << p.residual << ")";
      res.warnings.push_back(os.str());
      continue;
    }
    const char* accuracy_flag = p.converged ? nullptr : "ill_conditioned";
    // Each point (0, m pi / d_j) where a curve leaves the axis t1 = 0 satisfies both equations in the limit
    // (pure contact oscillation): roots that polish back towards an axis are these limits, not SPPs.
    if (p.t1 <= 2.0 * opt.t1_min || p.t1 > opt.t1_max || p.t2 <= 2.0 * opt.t2_min || p.t2 > opt.t2_max) continue;
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
    if (c.near_double) s.flags.push_back("near_double_root");
    if (accuracy_flag) s.flags.push_back(accuracy_flag);
    if (c.near_pole) s.flags.push_back("near_pole_line");
    res.solutions.push_back(std::move(s));
  }
  res.stats.roots = static_cast<long>(res.solutions.size());
  std::sort(res.solutions.begin(), res.solutions.end(),
            [](const Solution& a, const Solution& b) { return a.period < b.period; });
  if (options.admissible_only)
    res.solutions.erase(
        std::remove_if(res.solutions.begin(), res.solutions.end(), [](const Solution& s) { return !s.admissible; }),
        res.solutions.end());
  if (res.stats.unpaired_crossings > 0)
    res.warnings.push_back(std::to_string(res.stats.unpaired_crossings) +
                           " curve crossing(s) of a pole line could not be paired (a curve passed within the "
                           "pole margin of a pole-line intersection): a root in that thin strip is not excluded");
  if (res.stats.unresolved_pieces > 0)
    res.warnings.push_back(std::to_string(res.stats.unresolved_pieces) +
                           " curve piece(s) could not be followed within the step budget (null vector turning "
                           "faster than the step control: nearly equal eigenvalues); a root there is not excluded");
  if (res.stats.near_double_roots > 0)
    res.warnings.push_back(std::to_string(res.stats.near_double_roots) +
                           " near-double root(s): g touches zero to within the step resolution");
  for (const Solution& s : res.solutions)
    if (!s.admissibility.certified) res.warnings.push_back("admissibility of an SPP not certified to tolerance");
  res.status = res.warnings.empty() ? SolveStatus::Success : SolveStatus::Incomplete;
  res.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

}  // namespace spp
