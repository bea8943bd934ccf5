#include "search/cell_trace.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "search/bordered_form.hpp"
#include "search/step_certificate.hpp"
#include "search/tolerances.hpp"
#include "spp/detail/brent.hpp"
#include "spp/detail/tridiagonal.hpp"

namespace spp::search {

namespace {

using Vec = Eigen::VectorXd;
using Mat = Eigen::MatrixXd;

// A point on curve k: position, oriented null vector, signed g and dg/ds along s = t2 - t1.
struct TracePoint {
  double s = 0, t1 = 0, t2 = 0, g = 0, dg = 0;
  // for the step certificate (residual, neighbouring eigenvalues and error bound filled with certify_steps only)
  double lam_below = -std::numeric_limits<double>::infinity(), lam_above = std::numeric_limits<double>::infinity();
  double residual = 0, eig_error = 0, offset_norm = 0, slope_sum = 0;
  double tangent = 0;  // dtau/ds = -l2 / (l1 + l2) here (the curve's tangent, for the predictor of the next step)
  // distance along (1, 1) to the true curve point on the same anti-diagonal: (|lambda_k| + error) / (l1 + l2)
  double pos_err = 0;
  int proved_sign = 0;  // sign of the true g, proved by the certified step that reached this point (0: not proved)
  Vec b;
};

StepEnd step_end(const TracePoint& p) {
  return {p.s,        p.t1,        p.t2,          p.g,         p.dg,      p.lam_below,   p.lam_above,
          p.residual, p.eig_error, p.offset_norm, p.slope_sum, p.pos_err, p.proved_sign, &p.b};
}

}  // namespace

class CellTracer::Impl {
 public:
  Impl(const EquationSet& eq, const SolveOptions& opt, SolveStats& st, Evaluator& ev, const std::atomic<bool>* stop)
      : eq_(eq),
        md_(eq.modal()),
        ev_(ev),
        opt_(opt),
        st_(st),
        stop_(stop),
        hmin_(opt.min_step * (opt.t1_max + opt.t2_max)),
        zhat_(md_.z().normalized()) {}

  // g = c^T b with c the onset direction, and dg/ds given db/ds and dt2/ds. Fixed (axial): c = z / |z| (z^T p0 = 0
  // with p0 along b), computed once (this runs at every trace point). Moving (point): c(t2), not normalised.
  std::pair<double, double> onset_g(const Vec& b, double t2, const Vec* db = nullptr, double dt2_ds = 0.0) const {
    if (eq_.onset_direction_fixed()) return {zhat_.dot(b), db ? zhat_.dot(*db) : 0.0};
    // c(t2) is not normalised (its sign is all that matters, and the certificate bounds c^T b).
    const Vec c = eq_.onset_direction(t2);
    const double g = c.dot(b);
    if (!db) return {g, 0.0};
    const Vec dc = eq_.onset_direction_dt2(t2) * dt2_ds;
    return {g, c.dot(*db) + dc.dot(b)};
  }

  // ---- evaluations (search::Evaluator) ----
  std::shared_ptr<const HPoint> corner(double t1, double t2) { return ev_.at(t1, t2); }

  // The k-th eigenpair of H (tridiagonal form, bisection, inverse iteration).
  struct Pair {
    double t1 = 0, t2 = 0, lam = 0, scale = 0;
    Vec b;
    std::shared_ptr<const HPoint> at;  // H at (t1, t2), for the bordered solve of point()
    int k = 0;
    // placed in the bordered form (segment_root): lam is B's, and `bordered` holds its distance estimate to the curve
    BorderedOffset bordered;
  };
  Pair eigenpair(double t1, double t2, int k) {
    const std::shared_ptr<const HPoint> T = ev_.at(t1, t2);
    Pair p;
    p.t1 = t1;
    p.t2 = t2;
    p.lam = T->eigenvalue(k);
    p.scale = T->norm_bound();
    p.at = T;
    p.b = T->eigenvector(p.lam);
    p.k = k;
    return p;
  }

  // b^T dH/dt1 b and b^T dH/dt2 b (both >= 0).
  std::pair<double, double> grads(const Vec& b, double t1, double t2) const {
    const double l1 = (eq_.dflight_dt1(t1).array() * b.array().square()).sum();
    const Vec y = md_.G().transpose() * b;
    const double l2 = (eq_.dcontact_eigs(t2).array() * y.array().square()).sum();
    return {l1, l2};
  }

  // Trace point from the eigenpair: g = zhat^T b and dg/ds, with db/ds from the bordered system
  // [[H - lam I, b], [b^T, 0]] [db; mu] = [-(I - b b^T) dH/ds b; 0] (first-order eigenvector perturbation).
  // With `bordered_estimate`, the bordered form's distance estimate is formed and taken where smaller even below
  // kPosErrBordered (one more decomposition: trace() asks for it only where a step's end sign depends on it).
  TracePoint point(const Pair& q, const Vec* ref, bool bordered_estimate = false) {
    TracePoint p;
    p.t1 = q.t1;
    p.t2 = q.t2;
    p.s = q.t2 - q.t1;
    const Vec& b0 = q.b;
    const double sign = (ref && b0.dot(*ref) < 0) ? -1.0 : 1.0;
    const auto [l1, l2] = grads(b0, q.t1, q.t2);
    const double tp = -l2 / (l1 + l2);  // dtau/ds on the curve
    const Vec y = md_.G().transpose() * b0;
    const Vec e2 = eq_.dcontact_eigs(q.t2);
    const Vec dHb = tp * eq_.dflight_dt1(q.t1).cwiseProduct(b0) + (tp + 1.0) * (md_.G() * e2.cwiseProduct(y));
    const Vec dbh = q.at->solve_bordered(q.lam, b0, -(dHb - b0.dot(dHb) * b0));
    p.slope_sum = l1 + l2;
    p.tangent = tp;
    p.pos_err = (std::abs(q.lam) + q.at->eigen_error()) / (l1 + l2);
    if (opt_.certify_steps) {  // residual, neighbouring eigenvalues and error bound only feed the certificate
      // The true curve point that stands for this one: lambda_k = 0 at about |lambda_k| / l away along t1 (l = l1),
      // t2 (l2) or (1, 1) (l1 + l2); twice that for safety, plus the rounding of t in tan. Of the three, the one that
      // moves b least: next to a contact pole line |dH/dt2 b| is ~100x b^T dH/dt2 b, and moving along t1 alone keeps
      // the offset bound (hence the uncertainty of g near a root) ~100x smaller than along (1, 1).
      const double lam_err = std::abs(q.lam) + q.at->eigen_error();
      const double rounding = 4.0 * std::numeric_limits<double>::epsilon() * std::max(q.t1, q.t2);
      const double inf = std::numeric_limits<double>::infinity();
      Offset off{inf, inf};
      double moves[3][2] = {{lam_err / (l1 + l2), lam_err / (l1 + l2)}, {lam_err / l1, 0.0}, {0.0, lam_err / l2}};
      // Far above rounding (next to a pole line, where H's eigenvalue error grows like 1 / distance): the same
      // distances from the bordered form, whose error stays at its O(1) scale; the smaller estimate is kept.
      // A point placed in the bordered form brings that estimate at no cost: it is taken wherever it is smaller, also
      // when the (1, 1) distance from H stays below kPosErrBordered while the moves along t1 or t2 alone, the only
      // ones offset_bound accepts next to a pole line, do not (that exit point of the n = 15 chain: 6.8e-8 along t1
      // from H, 4e-14 from B; with H's, the sign of g there, -1.2e-6, was not proved; issue 12). Both are
      // bounds of the distance to the same zero set, so the smaller one is still a bound.
      if (q.bordered.valid || bordered_estimate || p.pos_err > kPosErrBordered * std::max(q.t1, q.t2)) {
        // (a point placed in the bordered form brings its own estimate: no second eigendecomposition)
        const BorderedOffset bo = q.bordered.valid ? q.bordered : bordered_offset(eq_, q.t1, q.t2, &eigen_cache_);
        if (bo.valid) {
          const double via[3] = {bo.lam_err / (bo.l1 + bo.l2), bo.lam_err / bo.l1, bo.lam_err / bo.l2};
          for (int i = 0; i < 3; ++i)
            for (double& e : moves[i])
              if (e > 0 && via[i] < e) e = via[i];
        }
      }
      for (const auto& mv : moves) {
        const double e1 = 2.0 * mv[0] + rounding, e2 = 2.0 * mv[1] + rounding;
        if (!std::isfinite(e1) || !std::isfinite(e2)) continue;
        const Offset o = offset_bound(eq_, q.t1, q.t2, e1, e2, b0);
        if (o.residual < off.residual) {
          off = o;
          p.pos_err = 0.5 * std::max(e1, e2);
        }
      }
      p.residual = (q.at->apply(b0) - q.lam * b0).norm() + std::abs(q.lam) + off.residual;
      if (q.k > 0) p.lam_below = q.at->eigenvalue(q.k - 1);
      if (q.k + 1 < q.at->size()) p.lam_above = q.at->eigenvalue(q.k + 1);
      p.eig_error = q.at->eigen_error();
      p.offset_norm = off.norm;
    }
    p.b = sign * b0;
    const auto [g, dg] = onset_g(b0, q.t2, &dbh, tp + 1.0);
    p.g = sign * g;
    p.dg = sign * dg;
    return p;
  }

  // Root of lambda_k on the segment (t1a, t2a) + sigma (dt1, dt2), sigma in [lo, hi], lambda_k(lo) <= 0 <
  // lambda_k(hi). lambda_k is non-decreasing along the segment (dt1, dt2 >= 0 in one of the two senses), so a
  // Newton step safeguarded by bisection on the bracket converges: a Newton step that leaves the bracket is replaced
  // by bisection, and so is every other step once kNewtonSteps have not converged (near an avoided crossing next to a
  // pole line lambda_k bends so much that Newton jumped from one end of the bracket to the other for 200 iterations,
  // shaving off slivers, and returned a point with lambda_k = -0.024 as an edge root). Rules that bisect earlier
  // (rtsafe's) move the roots of ordinary pieces by rounding-level amounts and changed the outcome of fragile pieces
  // next to pole lines both ways; this one leaves every root that converges within kNewtonSteps as it was.
  // It stops at the rounding level of lambda_k (rel_ftol times the largest |eigenvalue|).
  // With certify_steps, a segment whose first point H cannot place (the distance to the curve that H's eigenvalue
  // error bound allows exceeds kPosErrBordered, as next to a pole line) is solved in the bordered form of the
  // segment's box instead (bordered_eigenpair: the same sign and zero, B's O(1) error): a root placed by H there was
  // off the curve by up to 65 in t on the 300-dof chain (|H| ~ 1e10, 1e-10 from a pole line), which no step
  // certificate could take as an end.
  Pair segment_root(double t1a, double t2a, double dt1, double dt2, double lo, double hi, double guess, int k,
                    double rel_ftol) {
    double x = (guess > lo && guess < hi) ? guess : 0.5 * (lo + hi);
    Pair e;
    const double xtol = kSegmentRootXtol * (std::abs(lo) + std::abs(hi));
    std::unique_ptr<BorderedForm> bf;  // set once H could not place the first point
    for (int it = 0; it < kSegmentRootIterations; ++it) {
      const double t1 = t1a + x * dt1, t2 = t2a + x * dt2;
      if (bf) {
        e = bordered_pair(*bf, t1, t2, k);
        if (!e.bordered.valid) bf.reset();  // (B's eigenvalue or slopes unusable here: H as before)
      }
      if (!bf) e = eigenpair(t1, t2, k);
      auto [l1, l2] = bf ? std::pair{e.bordered.l1, e.bordered.l2} : grads(e.b, e.t1, e.t2);
      // (H's error bound alone, over the slope along the segment: the distance in t within which H cannot place the
      // root on it. Along an edge that only moves t1 the slope is l1, not l1 + l2: an exit point 2.3e-8 below a
      // contact pole line of the n = 15 chain (H's eigenvalue error 1.2e-6 there, l1 ~ l2 ~ 17) was placed by H, 6.8e-8
      // in t1 from the curve, while (1, 1) gave 3.4e-8, under the threshold; issue 12.)
      const double slope = std::abs(dt1 * l1 + dt2 * l2), reach = std::max(std::abs(dt1), std::abs(dt2));
      if (it == 0 && opt_.certify_steps && e.at->eigen_error() * reach / slope > kPosErrBordered * std::max(t1, t2)) {
        const double s1 = t1a + lo * dt1, s2 = t1a + hi * dt1, u1 = t2a + lo * dt2, u2 = t2a + hi * dt2;
        bf =
            std::make_unique<BorderedForm>(eq_, std::min(s1, s2), std::max(s1, s2), std::min(u1, u2), std::max(u1, u2));
        Pair eb;
        if (bf->valid() && bf->bordered() > 0) eb = bordered_pair(*bf, t1, t2, k);
        if (eb.bordered.valid) {
          e = eb;
          l1 = e.bordered.l1;
          l2 = e.bordered.l2;
        } else {
          bf.reset();
        }
      }
      const double f = e.lam;
      if (std::abs(f) <= rel_ftol * e.scale) break;
      if (f < 0)
        lo = x;
      else
        hi = x;
      const double df = dt1 * l1 + dt2 * l2;
      double next = df != 0.0 ? x - f / df : 0.5 * (lo + hi);
      if (!(next > lo && next < hi) || (it >= kNewtonSteps && it % 2 == 0)) next = 0.5 * (lo + hi);
      if (hi - lo <= xtol || next == x) break;
      x = next;
    }
    if (bf) e.at = ev_.at(e.t1, e.t2);  // H at the root, for point()
    return e;
  }

  // Curve k's eigenpair at (t1, t2) read in the bordered form bf (bordered_eigenpair): lam and scale are B's, b is H's
  // null vector where lam = 0; `bordered` carries B's distance estimate to the curve for point(), valid only where B's
  // eigenvalue and slopes are usable. H itself is not evaluated (segment_root does, at the root).
  Pair bordered_pair(const BorderedForm& bf, double t1, double t2, int k) {
    const BorderedEigen be = bordered_eigenpair(bf, t1, t2, k);
    ++st_.evaluations;
    Pair p;
    p.t1 = t1;
    p.t2 = t2;
    p.k = k;
    if (!be.ok || !(be.l1 + be.l2 > 0)) return p;
    p.lam = be.lam;
    p.scale = be.scale;
    p.b = be.b;
    p.bordered = {true, std::abs(be.lam) + be.error, be.l1, be.l2};
    return p;
  }

  // Root of lambda_k on the edge from (t1a, t2a) to (t1b, t2b), with lambda_k = fa <= 0 and fb > 0 there.
  Pair edge_root(double t1a, double t2a, double t1b, double t2b, int k, double fa, double fb) {
    const double guess = fa / (fa - fb);  // secant on the end values
    return segment_root(t1a, t2a, t1b - t1a, t2b - t2a, 0.0, 1.0, guess, k, kEdgeRootTol);
  }

  // ---- one rectangle ----
  using Rect = Cell;

  // Root of lambda_k on the anti-diagonal t2 - t1 = s inside rectangle r (tau = t1 on the segment).
  Pair diagonal_root(const Rect& r, double s, double guess, int k) {
    const double lo = std::max(r.a1, r.A - s), hi = std::min(r.b1, r.B - s);
    return segment_root(0.0, s, 1.0, 1.0, lo, hi, guess, k, kDiagonalRootTol);
  }

  // One cell: count the curves at its corners, find each curve's entry and exit, trace it. Returns false when a
  // part of the cell could not be certified (the caller records the cell).
  bool trace_cell(Rect r, size_t column, std::vector<EdgeHit>& left_exits, std::vector<EdgeHit>& top_exits,
                  std::vector<EdgeHit>& right_entries, std::vector<EdgeHit>& bottom_entries) {
    ++st_.rectangles;
    bool certified = true;
    // Corner counts are exact only when no eigenvalue lies within its error bound of 0: where H's bound (8 m eps |H|,
    // large next to a pole line) does not prove the count, the bordered form's does (corner_count); where neither
    // does, the corner is moved outwards (into the pole margin or past the window edge, never leaving a gap) and
    // counted again. Checked with certify_steps only (the midpoint trace takes H's count as it is).
    std::shared_ptr<const HPoint> BLt = corner(r.a1, r.A), TRt = corner(r.b1, r.B);
    int nBL = corner_count(*BLt, r.a1, r.A), nTR = corner_count(*TRt, r.b1, r.B);
    for (int tries = 0; tries < 4 && (nBL < 0 || nTR < 0); ++tries) {
      const double d1 = kCornerMove * (r.b1 - r.a1), d2 = kCornerMove * (r.B - r.A);
      if (nBL < 0) {
        r.a1 -= d1;
        r.A -= d2;
        BLt = corner(r.a1, r.A);
        nBL = corner_count(*BLt, r.a1, r.A);
      }
      if (nTR < 0) {
        r.b1 += d1;
        r.B += d2;
        TRt = corner(r.b1, r.B);
        nTR = corner_count(*TRt, r.b1, r.B);
      }
    }
    if (nBL < 0 || nTR < 0) {
      ++st_.uncertified_corners;
      certified = false;
      if (nBL < 0) nBL = BLt->count_below(0.0);
      if (nTR < 0) nTR = TRt->count_below(0.0);
    }
    const int kmin = nTR, kmax = nBL;  // curves k in [kmin, kmax)
    if (kmin >= kmax) return certified;
    const std::shared_ptr<const HPoint> BRt = corner(r.b1, r.A), TLt = corner(r.a1, r.B);
    const int nBR = BRt->count_below(0.0), nTL = TLt->count_below(0.0);
    // A cell where Hc is nonsingular throughout holds no SPP: its pieces need no trace, only their ends (the exit
    // oriented so that g keeps its sign).
    const bool root_free = opt_.certify_steps && onset_free(r.a1, r.A, r.b1, r.B);
    for (int k = kmin; k < kmax; ++k) {
      ++st_.curve_pieces;
      // entry on the lower-right path, exit on the upper-left path (design note §3b)
      Pair in, out;
      // lambda_k > 0 at a corner iff fewer than k + 1 eigenvalues lie below 0 there
      const bool in_bottom = nBR <= k, out_left = nTL <= k;
      const double bl = BLt->eigenvalue(k), tr = TRt->eigenvalue(k), br = BRt->eigenvalue(k), tl = TLt->eigenvalue(k);
      if (in_bottom)
        in = edge_root(r.a1, r.A, r.b1, r.A, k, bl, br);
      else
        in = edge_root(r.b1, r.A, r.b1, r.B, k, br, tr);
      if (out_left)
        out = edge_root(r.a1, r.A, r.a1, r.B, k, bl, tl);
      else
        out = edge_root(r.a1, r.B, r.b1, r.B, k, tl, tr);
      TracePoint pin = point(in, nullptr);
      TracePoint pout;
      if (root_free) {
        ++st_.certified_steps;
        pout = point(out, &pin.b);
        orient_like(pout, pin);
      } else {
        pout = trace(r, k, pin, out, certified);
      }
      auto hit = [column](const TracePoint& p, double pos) { return EdgeHit{pos, p.t1, p.t2, p.g, p.b, column}; };
      if (in_bottom ? r.bottom_pole : r.right_pole)
        (in_bottom ? bottom_entries : right_entries).push_back(hit(pin, in_bottom ? pin.t1 : pin.t2));
      if (out_left ? r.left_pole : r.top_pole)
        (out_left ? left_exits : top_exits).push_back(hit(pout, out_left ? pout.t2 : pout.t1));
    }
    return certified;
  }

  // Traces curve k from its entry to its exit in steps of s = t2 - t1, each step certified by
  // certify_step (no sign change of g, or exactly one, proved from bounds over the step's box); a step the
  // bound cannot certify is halved. Sign changes are located by Brent and become candidates. Returns the oriented
  // exit point; clears `certified` if a step at the minimum length, or the piece's step budget, was not enough.
  TracePoint trace(const Rect& r, int k, const TracePoint& pin, const Pair& out, bool& certified) {
    const double s_out = out.t2 - out.t1, span = s_out - pin.s;
    TracePoint cur = pin;
    if (!(span > 0)) return point(out, &cur.b);  // the curve only touches the cell at a corner
    double h = span, slope = 0.0;                // slope: dtau/ds estimate for the predictor
    double bend = 0.0;  // d2tau/ds2 estimate (the tangents' difference over the last step): certified predictor
    int halvings = 0;
    examine_budget_ = kPieceBudget;
    // Stall watch: when certified steps have shrunk 4x since the last step that grew, the trace may approach a pole
    // line or a small gap (the zeroth-order and curvature bounds then shrink the step geometrically) while Hc stays
    // nonsingular on a much larger box: one long step (16x) is tried on the onset inertia first.
    double ref_h = h;
    bool prove = opt_.certify_steps;
    int fallbacks = 0;  // steps of this piece the proofs left to the midpoint check
    // Once a piece is unproved (a fallback outside the axis bands), the proofs only decide how much of it is proved,
    // not the window's status: after the f-th fallback they skip 2^(f-1) - 1 midpoint steps and then get at most
    // kRetryTries shortenings. (Next to clustered pole lines of the 300-dof chain a piece otherwise alternated 40
    // failed proofs and one midpoint step at the minimum length, up to kFallbacks times: ~15 minutes per piece.)
    long skip_proofs = 0;
    // Root watch: certified steps that shrink while |g| falls (both 4x, kApproach times) approach a root that the
    // bounds only let a step cross late: one step of 3 |g / g'| is tried on the proofs; where they fail and half the
    // piece's step budget is spent, the midpoint check takes it (counted as not proved); the proofs resume after it.
    int approach = 0;
    double root_g = std::abs(cur.g), root_h = h;
    bool stalled = false;
    MonotoneRun run;
    const int proof_budget = prove ? kProofBudget : kPieceBudget;
    for (int budget = proof_budget;; --budget) {
      const bool onset_first = stalled;
      if (onset_first) {
        stalled = false;
        h = std::min(span, 16.0 * h);
      }
      const double remaining = s_out - cur.s;
      const bool last = h >= remaining;
      const double step = last ? remaining : h;
      if (prove && budget <= 0) {  // the proofs allow only tiny steps here: the midpoint trace finishes the piece
        prove = false;
        budget = kPieceBudget;
        certified = false;
        h = std::max(h, kFallbackStep * span);
      }
      if (stop_ != nullptr && stop_->load(std::memory_order_relaxed)) {  // stopped: the piece ends here, unproved
        certified = false;
        return point(out, &cur.b);
      }
      if (budget <= 0 || examine_budget_ <= 0) {
        if (run.open) abandon_run(r, k, run, certified);
        return give_up(r, k, cur, out, certified);
      }
      // Inside an axis band nothing is reported (axis_band): steps there need no proof, only the midpoint check that
      // keeps b's orientation.
      const bool in_band = cur.t1 <= band_.first || cur.t2 + step <= band_.second;
      const bool crossing_try = approach >= kApproach;  // tried on the proofs once, else by the midpoint check
      if (crossing_try) {
        approach = 0;
        root_g = std::abs(cur.g);
        root_h = h;
      }
      if (prove && !in_band && skip_proofs == 0) {
        TracePoint p =
            last ? point(out, &cur.b)
                 : point(diagonal_root(r, cur.s + step, cur.t1 + (cur.tangent + 0.5 * bend * step) * step, k), &cur.b);
        auto box_free = [&] {  // the step's box, widened by the ends' distance to the true curve, inside the cell
          const double e = 2.0 * std::max(p.pos_err, cur.pos_err);
          return onset_free(std::max(r.a1, std::min(p.t1, cur.t1) - e), std::max(r.A, std::min(p.t2, cur.t2) - e),
                            std::min(r.b1, std::max(p.t1, cur.t1) + e), std::min(r.B, std::max(p.t2, cur.t2) + e));
        };
        const bool onset_proved = onset_first && box_free();
        StepCertificate cert =
            onset_proved ? StepCertificate{}
                         : certify_step(eq_, step_end(cur), step_end(p), {r.a1, r.b1, r.A, r.B}, &eigen_cache_);
        st_.evaluations += cert.evaluations;
        // The piece's exit point, whose true g's sign the bounds could not prove: its position error from H (next to a
        // pole line, H's eigenvalue error grows like 1 / distance) may be far above the bordered form's, also below
        // kPosErrBordered; once more with the smaller one (the n = 15 chain box: an exit 2.3e-8 below a contact pole
        // line, g = -1.2e-6, 3.7e-8 from H, g's error bound 4.4e-6; issue 12). Still a proof: both are bounds of the
        // distance to the same zero set.
        // (Only where g is proved monotone on the step, so that the end sign alone is missing: tried after every
        // refused last step, the n = 15 window (9.5, 10.6] x (8.3, 9.1] took 7 038 evaluations instead of 6 958.)
        if (last && !onset_proved && cert.verdict == StepVerdict::Uncertified && cert.monotone_dir != 0 &&
            cert.sign_b == 0) {
          TracePoint pb = point(out, &cur.b, true);
          ++st_.evaluations;  // (the bordered form's decomposition at the exit point)
          if (pb.pos_err < p.pos_err) {
            p = std::move(pb);
            cert = certify_step(eq_, step_end(cur), step_end(p), {r.a1, r.b1, r.A, r.B}, &eigen_cache_);
            st_.evaluations += cert.evaluations;
          }
        }
        // Where the curvature bound is too weak (next to pole lines, mostly), the step's box may still be proved
        // root-free by the onset inertia at its two Loewner corners; g keeps its sign then, which orients p.
        // (Not while a monotone run is open: it needs the proved sign of g that a certificate gives.)
        const bool by_onset =
            !run.open && (onset_proved || (cert.verdict == StepVerdict::Uncertified && !onset_first && box_free()));
        if (by_onset) orient_like(p, cur);
        if (cert.verdict != StepVerdict::Uncertified || by_onset) {
          // a certificate proves the sign of g at cur too: g keeps its sign over the step, or changes it once
          if (run.open)
            close_run(r, k, run, cert.verdict == StepVerdict::NoRoot ? cert.end_sign : -cert.end_sign, certified);
          ++st_.certified_steps;
          halvings = 0;
          p.proved_sign = by_onset ? cur.proved_sign : cert.end_sign;
          if ((cur.g > 0) != (p.g > 0) && locate_root(r, k, cur, p)) {
            flip(p);
            p.proved_sign = 0;
          }
          if (p.s > cur.s) {
            slope = (p.t1 - cur.t1) / (p.s - cur.s);
            bend = (p.tangent - cur.tangent) / (p.s - cur.s);
          }
          if (last) return p;
          // At least 1.5x after a step the Weyl bounds proved: their safe length can stay at the step's (next to pole
          // lines) where a longer step is proved by the spectral bounds; a failed try costs one halving. After a step
          // the spectral bounds proved, at least kSpectralGrowth only (they give no length of their own).
          const double grow = cert.spectral ? kSpectralGrowth : 1.5;
          const double next = by_onset ? 2.0 * step : std::clamp(0.9 * cert.safe_length, grow * step, 4.0 * step);
          if (std::abs(p.g) > root_g || next > root_h) {
            root_g = std::abs(p.g);
            root_h = next;
          } else if (std::abs(p.g) < 0.25 * root_g && next < 0.25 * root_h && p.dg != 0.0) {
            root_g = std::abs(p.g);
            root_h = next;
            if (++approach >= kApproach) {
              cur = p;
              h = std::min(span, 3.0 * std::abs(p.g / p.dg));
              continue;
            }
          }
          if (by_onset || next > ref_h) {
            ref_h = next;
          } else if (next < 0.25 * ref_h) {
            stalled = true;
            ref_h = next;
          }
          cur = p;
          h = std::min(span, next);
          continue;
        }
        // A step on which g is proved monotone, in the direction of the open run (or opening one from a point of
        // proved sign), but whose end lies within g's error bound of zero: taken on trust until a point of proved
        // sign closes the run (MonotoneRun).
        const int sign0 = run.open ? run.sign0 : (cur.proved_sign != 0 ? cur.proved_sign : cert.sign_a);
        if (!by_onset && cert.monotone_dir != 0 && sign0 != 0 && (!run.open || cert.monotone_dir == run.dir)) {
          if (!run.open) run = MonotoneRun{true, cert.monotone_dir, sign0, 0, false, {}, {}};
          ++run.steps;
          halvings = 0;
          if (!run.flipped && (cur.g > 0) != (p.g > 0)) {
            run.flipped = true;
            run.flip_a = cur;
            run.flip_b = p;
          }
          p.proved_sign = 0;
          if (cert.sign_b != 0) {
            close_run(r, k, run, cert.sign_b, certified);
            p.proved_sign = cert.sign_b;
          } else if (last) {
            abandon_run(r, k, run, certified);
          }
          if (p.s > cur.s) {
            slope = (p.t1 - cur.t1) / (p.s - cur.s);
            bend = (p.tangent - cur.tangent) / (p.s - cur.s);
          }
          if (last) return p;
          cur = p;
          h = std::min(span, 1.5 * step);
          continue;
        }
        // Shorten, towards the length the curvature bound says it could prove (at most 50x at once); after
        // kCertifyTries failures in a row or at the minimum step, the step goes to the midpoint check below.
        const bool bounded = cert.gap > 0 && cert.curvature > 0;  // the bound was computed (not cut short)
        const int tries = fallbacks > 0 ? kRetryTries : kCertifyTries;
        if (!(crossing_try && budget < proof_budget / 2) && ++halvings <= tries && step > hmin_) {
          const bool crossing = (cur.g > 0) != (p.g > 0);  // only the curvature bound proves a crossing step
          // A try on which no bound held (no Weyl gap, the spectral bounds' perturbation too large at both ends) is far
          // too long, mostly the first tries of a piece (from its whole span): shrink by kFarTooLong, not by half.
          const double shrink = bounded || cert.spectral_valid ? 0.5 : kFarTooLong;
          h = std::max(hmin_,
                       bounded && crossing ? std::clamp(cert.safe_length, 0.02 * step, 0.5 * step) : shrink * step);
          // From a start whose null vector its own bounds leave undetermined (next to a pole line, where H's error
          // bound exceeds the gap), only the far end's spectral bounds can prove a step, and halving rarely helps (the
          // 300-dof chain: 13-30 failed halvings down to the minimum step per piece, each a certificate and a 1-D
          // root): after kUndeterminedTries, one try at the minimum step, the most favourable length, decides.
          if (undetermined(cur) && halvings > kUndeterminedTries) h = hmin_;
          continue;
        }
      }
      // Midpoint check: the turn of b is measured over both halves of the step (comparing only the ends would accept
      // a b that swings away and comes back near an avoided crossing), g examined on both halves. Not a proof.
      if (run.open) abandon_run(r, k, run, certified);
      TracePoint mid = point(diagonal_root(r, cur.s + 0.5 * step, cur.t1 + slope * 0.5 * step, k), &cur.b);
      TracePoint q =
          last ? point(out, &mid.b) : point(diagonal_root(r, cur.s + step, cur.t1 + slope * step, k), &mid.b);
      const double turn1 = turn_between(cur.b, mid.b), turn2 = turn_between(mid.b, q.b), turn = turn1 + turn2;
      // next step aims at 0.6 max_turn, assuming the turn grows linearly with the step
      const double factor = turn > 0 ? 0.6 * opt_.max_turn / turn : 4.0;
      if (turn > opt_.max_turn) {
        // (From an undetermined start outside the axis bands, b is noise at any step length: shrinking to the
        // minimum step only delays the same outcome.)
        if (step > hmin_ && !(undetermined(cur) && !in_band)) {
          h = std::max(hmin_, step * std::clamp(factor, 0.1, 0.5));
          continue;
        }
        // b turns more than max_turn within the minimum step: the eigenvalues next to lambda_k are within rounding of
        // it (at n = 300, curves within 1e-9 of a pole line, where |H| ~ 1e10 makes the error bound larger than the
        // gap), and b is noise. Accepting such steps (as before) let the step fall below the minimum and the piece
        // crawl for its whole budget (hours at n = 300); the piece is given up instead, and counted.
        return give_up(r, k, cur, out, certified);
      }
      // b reaches the hyperplane c^T b = 0 and comes back only along a path at least asin|g_A| + asin|g_B| long
      // (angles of the ends to that hyperplane): where g keeps its sign over a half, its turn (a lower bound of the
      // path) must stay below half of that, or the half could hide a pair of roots that a small turn allows when
      // |g| is small (seen on a stiff 2-dof: g from -4e-4 through 0 and back to -4e-2 in one step of turn < 0.2).
      const double slack = std::min(hidden_pair_slack(cur, mid, turn1), hidden_pair_slack(mid, q, turn2));
      if (slack < 1.0 && step > hmin_) {
        h = std::max(hmin_, step * std::clamp(0.6 * slack, 0.1, 0.5));
        continue;
      }
      ++st_.heuristic_steps;
      if (!in_band) {  // not a proof, whatever the options: the window cannot end success
        ++st_.uncertified_steps;
        certified = false;
        // The piece is unproved already: after kFallbacks such steps the proofs stop trying on it.
        if (skip_proofs > 0)
          --skip_proofs;
        else if (++fallbacks >= kFallbacks)
          prove = false;
        else
          skip_proofs = (1L << std::min(fallbacks - 1, kMaxBackoff)) - 1;
      }
      halvings = 0;
      if (examine(r, k, cur, mid, 0)) {
        flip(mid);
        flip(q);  // q was oriented from mid
      }
      if (examine(r, k, mid, q, 0)) flip(q);
      if (q.s > cur.s) {
        slope = (q.t1 - cur.t1) / (q.s - cur.s);
        bend = (q.tangent - cur.tangent) / (q.s - cur.s);
      }
      if (last) return q;
      cur = q;
      h = std::min(span, std::max(hmin_, step * std::clamp(factor, 0.3, 4.0)));
    }
  }

  // Steps of one piece on each of which g is proved monotone in the same direction, from a point where the sign of
  // the true g is proved (sign0): g is monotone on their union, so a later point of proved sign (sign1) proves that
  // the run holds no root (same signs) or exactly one. Near a root where g' is small and lambda_{k+1} close to 0 (two
  // zero curves side by side) no single step is both short enough to be proved monotone and long enough to carry g
  // beyond its error bound; a run of such steps is. The computed g inside the run may change sign more than once (its
  // error exceeds |g| there): those changes are rounding, and the root, if any, is located at the first one.
  struct MonotoneRun {
    bool open = false;
    int dir = 0, sign0 = 0;
    long steps = 0;
    bool flipped = false;       // the computed g changed sign inside the run
    TracePoint flip_a, flip_b;  // the first step where it did
  };
  void close_run(const Rect& r, int k, MonotoneRun& run, int sign1, bool& certified) {
    if (sign1 != run.sign0 && !run.flipped) {  // the ends' signs differ, the computed g never changed: impossible
      abandon_run(r, k, run, certified);
      return;
    }
    st_.certified_steps += run.steps;
    // (b's orientation is proved continuous over the run by its bounds: locate_root's retrace verdict is not needed)
    if (sign1 != run.sign0) locate_root(r, k, run.flip_a, run.flip_b);
    run = MonotoneRun{};
  }
  // A run no point of proved sign closes: its steps are not proved (g is still monotone over it: at most one root,
  // located at the first sign change of the computed g). Counted as unproved, not as midpoint steps (the midpoint
  // check did not take them).
  void abandon_run(const Rect& r, int k, MonotoneRun& run, bool& certified) {
    st_.uncertified_steps += run.steps;
    certified = false;
    if (run.flipped) locate_root(r, k, run.flip_a, run.flip_b);
    run = MonotoneRun{};
  }

  // A piece whose null vector cannot be followed (its step budget ran out, or b turned more than max_turn within the
  // minimum step): counted as unresolved, and its exit point oriented by examining g from the last traced point.
  TracePoint give_up(const Rect& r, int k, const TracePoint& cur, const Pair& out, bool& certified) {
    ++st_.unresolved_pieces;
    certified = false;
    TracePoint p = point(out, &cur.b);
    if (examine(r, k, cur, p, 0)) flip(p);
    return p;
  }

  // The midpoint check's examination of g on [A, B] of curve k (every step by default; with certify_steps, the steps
  // the certificate cannot prove): locate sign changes, refine where a Hermite model of g dips towards zero.
  // Returns true when B's orientation (given) is opposite to the one continuous tracking from A gives (a swing of b
  // past 90 degrees inside the step, found by retrace): the caller flips B.
  bool examine(const Rect& r, int k, const TracePoint& A, const TracePoint& B, int depth) {
    const double h = B.s - A.s;
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
        if (!endpoints_differ && std::min(std::abs(A.g), std::abs(B.g)) < kTouchesZero) {
          ++st_.uncertified_steps;
          candidates_.push_back({0.5 * (A.t1 + B.t1), 0.5 * (A.t2 + B.t2), true, false, {}});
        }
        if (!endpoints_differ) return false;
      } else {
        --examine_budget_;
        const double s = A.s + (endpoints_differ ? 0.5 : xmin) * h;
        TracePoint M = point(root_between(r, k, A, B, s), &A.b);
        if (examine(r, k, A, M, depth + 1)) flip(M);
        return examine(r, k, M, B, depth + 1);
      }
    }
    return endpoints_differ && locate_root(r, k, A, B);
  }

  // Step A -> B traced again in kRetraceParts equal parts, each oriented from the previous one (parts where b still
  // turns more than max_turn are traced again in turn), each examined. Returns true when B's given orientation is
  // opposite to the continuous one.
  bool retrace(const Rect& r, int k, const TracePoint& A, const TracePoint& B, int depth) {
    const double h = B.s - A.s;
    TracePoint prev = A;
    for (int i = 1; i <= kRetraceParts; ++i) {
      const double s = A.s + h * i / kRetraceParts;
      TracePoint q = i == kRetraceParts ? B : point(root_between(r, k, A, B, s), &prev.b);
      if (i == kRetraceParts && q.b.dot(prev.b) < 0) flip(q);  // B oriented from its neighbour, as every part
      const bool again = turn_between(prev.b, q.b) > opt_.max_turn && depth < kRetraceDepth && q.s - prev.s > hmin_;
      if (again ? retrace(r, k, prev, q, depth + 1) : examine(r, k, prev, q, 0)) flip(q);
      prev = q;
    }
    return prev.b.dot(B.b) < 0;
  }

  // Root of lambda_k on the anti-diagonal s between the trace points A and B, from t1 interpolated linearly in s.
  Pair root_between(const Rect& r, int k, const TracePoint& A, const TracePoint& B, double s) {
    return diagonal_root(r, s, A.t1 + (B.t1 - A.t1) * (s - A.s) / (B.s - A.s), k);
  }
  // The null vector at p is far from determined by p's own bounds: the error bound of its neighbouring eigenvalues at
  // the true curve point (eigenvalue error plus offset) exceeds their gap kUndetermined times, so Davis-Kahan bounds no
  // angle and no nearby step length changes that (next to a pole line, where H's normwise error grows like 1 /
  // distance: 1e6-1e9 times the gap on the 300-dof chain). Only with certify_steps (the neighbours are not computed
  // otherwise: never undetermined then).
  static bool undetermined(const TracePoint& p) {
    return !(kUndetermined * std::min(p.lam_above, -p.lam_below) > p.eig_error + p.offset_norm);
  }
  // Angle (rad) between two unit null vectors, orientation ignored.
  static double turn_between(const Vec& x, const Vec& y) { return std::acos(std::min(1.0, std::abs(x.dot(y)))); }

  static void flip(TracePoint& p) {
    p.b = -p.b;
    p.g = -p.g;
    p.dg = -p.dg;
  }

  // Number of eigenvalues of H below 0 at a corner (t1, t2), proved: from H's Sturm count where no eigenvalue lies
  // within H's error bound of 0; else from the bordered form at that point, B = [[H', U], [U^T, -Lambda^-1]]
  // (bordered_form.hpp), whose entries stay O(1) next to a pole line where H's grow like 1 / distance (clustered pole
  // lines 1e-4 apart put every corner there): Haynsworth's inertia additivity, inertia(B) = inertia(H) +
  // inertia(-Lambda^-1), gives H's count as B's minus the number of positive border values. -1 where neither proves
  // it, or where H's own count disagrees. Without certify_steps, H's count as it is.
  int corner_count(const HPoint& T, double t1, double t2) const {
    if (!opt_.certify_steps) return T.count_below(0.0);
    const double e = T.eigen_error();
    const int below = T.count_below(-e);
    if (below == T.count_below(e)) return below;
    const BorderedForm bf(eq_, t1, t1, t2, t2);
    if (!bf.valid() || bf.bordered() == 0) return -1;
    const detail::SymmetricTridiagonal B(bf.matrix(t1, t2));
    const double eb = 8.0 * B.size() * std::numeric_limits<double>::epsilon() * B.norm_bound();
    const int below_b = B.count_below(-eb);
    if (below_b != B.count_below(eb)) return -1;
    const Eigen::VectorXd lam = bf.border_values(t1, t2);
    if (!lam.allFinite()) return -1;
    // The rest of the cell (edge-root brackets from H's eigenvalues at the corners) reads H as computed: a proved count
    // that H's own contradicts is not used (the corner is moved instead, else the cell is not certified).
    const int count = below_b - static_cast<int>((lam.array() > 0.0).count());
    return count == T.count_below(0.0) ? count : -1;
  }

  // True when no SPP lies in [t1lo, t1hi] x [t2lo, t2hi] (inside one cell), proved by the onset inertia: Hc grows
  // with t1 and t2 there (Loewner), so equal counts at the two extreme corners, both certain, leave no eigenvalue of
  // any Hc in the box at 0, and an SPP makes Hc singular. Only where c is constant (onset_direction_fixed): with c(t2)
  // moving, Hc is not monotone.
  bool onset_free(double t1lo, double t2lo, double t1hi, double t2hi) {
    if (!eq_.onset_direction_fixed()) return false;
    const int lo = ev_.onset_inertia(t1lo, t2lo);
    return lo >= 0 && lo == ev_.onset_inertia(t1hi, t2hi);
  }
  // Orients p's null vector like q's g (where g is proved not to change sign between them).
  static void orient_like(TracePoint& p, const TracePoint& q) {
    if ((p.g > 0) != (q.g > 0)) flip(p);
  }

  // Angle of b to the hyperplane c^T b = 0 at a trace point.
  double reach(const TracePoint& p) const {
    const double cn = eq_.onset_direction_fixed() ? 1.0 : eq_.onset_direction(p.t2).norm();  // zhat_ is a unit
    return std::asin(std::min(1.0, std::abs(p.g) / cn));
  }
  // (asin|g_A| + asin|g_B|) / (2 turn) for the turn of b from A to B, where g keeps its sign (>= 1: no pair of roots
  // can hide in a path that short), infinity where it changes sign (one crossing, located by Brent).
  double hidden_pair_slack(const TracePoint& A, const TracePoint& B, double turn) const {
    if ((A.g > 0) != (B.g > 0)) return std::numeric_limits<double>::infinity();
    // Inside the axis bands nothing is reported and |g| = O(t1^2) is tiny: the rule would only make the trace crawl.
    if (std::min(A.t1, B.t1) <= band_.first || std::min(A.t2, B.t2) <= band_.second)
      return std::numeric_limits<double>::infinity();
    return turn > 0 ? (reach(A) + reach(B)) / (2.0 * turn) : std::numeric_limits<double>::infinity();
  }

  // The one sign change of g between A and B: Brent on g(s), each evaluation a 1-D solve on the anti-diagonal.
  // Returns true when B's orientation must be flipped (see retrace).
  bool locate_root(const Rect& r, int k, const TracePoint& A, const TracePoint& B, int depth = 0) {
    auto g_at = [&](double s) {
      const Pair e = root_between(r, k, A, B, s);
      Vec b = e.b;
      if (b.dot(A.b) < 0) b = -b;
      return onset_g(b, e.t2).first;
    };
    const double s = detail::brent(g_at, A.s, B.s, A.g, B.g, kOnsetRootXtol * (std::abs(A.s) + std::abs(B.s) + 1.0));
    const Pair e = root_between(r, k, A, B, s);
    // A zero of g is continuous: where |g| stays large at the closed bracket, g jumped there (b swung past 90 degrees
    // from A's orientation inside the step, next to an eigenvalue that sweeps past lambda_k near a pole line): the
    // step is traced again finer instead.
    const double gs = std::abs(onset_g(e.b, e.t2).first);
    if (gs > std::max(kJump * std::max(std::abs(A.g), std::abs(B.g)), kJumpFloor) && depth < kRetraceDepth &&
        B.s - A.s > hmin_)
      return retrace(r, k, A, B, depth + 1);
    candidates_.push_back({e.t1, e.t2, false, false, e.b});
    return false;
  }

  std::vector<Candidate> candidates_;

 private:
  const EquationSet& eq_;
  const ModalForm& md_;  // eq_'s
  Evaluator& ev_;
  const SolveOptions& opt_;
  SolveStats& st_;
  const std::atomic<bool>* stop_;
  const double hmin_;                                      // smallest trace step in s
  const std::pair<double, double> band_ = axis_band(md_);  // roots are not reported within these of the axes
  static constexpr int kPieceBudget = 20000;               // trace steps (tried or taken) per curve piece
  static constexpr int kProofBudget = 200000;  // the same with certify_steps, before the midpoint check takes over
  int examine_budget_ = kPieceBudget;
  EigenCache eigen_cache_;                  // full eigenpairs of the certificate at the last trace points
  // Growth of the step after one the spectral bounds proved. Growing it 1.8x each time (as before) had the next try
  // refused after ~87% of such steps (chain5 box: 4 775 first refusals for 5 476 proved steps), each refusal a trace
  // point and a full decomposition. Chain boxes (`spp solve cN.json --box --threads 1`), evaluations: 59 593 -> 43 516
  // (n = 5), 374 528 -> 276 514 (n = 8), with about as many proved steps; 1.0, 1.1 and 1.15 took more.
  static constexpr double kSpectralGrowth = 1.05;
  // Shrink factor of a try on which no bound held. Chain boxes (`spp solve cN.json --box --threads 1`), evaluations
  // with 0.5 (as before) / 0.35 / 0.3 / 0.25 / 0.2: n = 5: 43 516 / 39 547 / - / 38 844 / 40 071; n = 8: 276 514 / - /
  // 247 494 / 247 498 / 254 530.
  static constexpr double kFarTooLong = 0.25;
  static constexpr int kCertifyTries = 40;  // failed proofs in a row (each at most halving) before the midpoint check
  // failed proofs in a row from an undetermined start before one try at the minimum step (the 300-dof chain's pieces
  // that were proved from such a start took at most 4; a start next to a contact pole line of chain5 took more than 7)
  static constexpr int kUndeterminedTries = 10;
  // error bound over gap beyond which a start's null vector counts as undetermined (at ~1, ordinary starts next to
  // avoided crossings, proved after a few halvings, would count: the chain5 window took 165 more evaluations)
  static constexpr double kUndetermined = 1e6;
  static constexpr int kFallbacks = 64;    // midpoint-check steps in a piece before its proofs stop trying
  static constexpr int kRetryTries = 4;    // failed proofs in a row (each at most halving) once a piece is unproved
  static constexpr int kMaxBackoff = 20;   // midpoint steps skipped before the proofs retry: at most 2^20 - 1
  static constexpr int kRetraceParts = 8;  // parts of a step traced again where g jumped
  static constexpr int kRetraceDepth = 4;  // nested retraces at most
  static constexpr int kApproach = 3;      // 4x falls of |g| and of the step towards a root before one step crosses it
  // 1-D root iterations at most: from kNewtonSteps on every other one bisects, ~94 halvings, more than a bracket of
  // doubles can take before reaching kSegmentRootXtol
  static constexpr int kSegmentRootIterations = 200;
  static constexpr int kNewtonSteps = 12;  // plain Newton steps of a 1-D root before every other one bisects
  Vec zhat_;
};

CellTracer::CellTracer(const EquationSet& equations, const SolveOptions& options, SolveStats& stats,
                       Evaluator& evaluator, const std::atomic<bool>* stop)
    : impl_(std::make_unique<Impl>(equations, options, stats, evaluator, stop)) {}
CellTracer::~CellTracer() = default;

bool CellTracer::trace_cell(const Cell& cell, size_t column, std::vector<EdgeHit>& left_exits,
                            std::vector<EdgeHit>& top_exits, std::vector<EdgeHit>& right_entries,
                            std::vector<EdgeHit>& bottom_entries) {
  return impl_->trace_cell(cell, column, left_exits, top_exits, right_entries, bottom_entries);
}

std::vector<Candidate>& CellTracer::candidates() {
  return impl_->candidates_;
}

}  // namespace spp::search
