#include "spp/continuation/continuation.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <iomanip>
#include <limits>
#include <list>
#include <map>
#include <memory>
#include <numbers>
#include <sstream>
#include <tuple>

#include "continuation/corrector.hpp"
#include "search/tolerances.hpp"
#include "spp/detail/internal_error.hpp"
#include "spp/detail/invalid.hpp"
#include "spp/modal/equation_set.hpp"
#include "spp/modal/modal.hpp"
#include "spp/orbit/orbit.hpp"
#include "spp/search/solver.hpp"

namespace spp {

void ContinueOptions::validate() const {
  constexpr const char* where = "continue options";
  if (!(t1_max > 0.0) || !std::isfinite(t1_max)) detail::invalid_option(where, "t1_max", t1_max, "> 0 and finite");
  if (!(t2_max > 0.0) || !std::isfinite(t2_max)) detail::invalid_option(where, "t2_max", t2_max, "> 0 and finite");
  if (!(t1_min >= 0.0 && t1_min < t1_max)) detail::invalid_option(where, "t1_min", t1_min, "in [0, t1_max)");
  if (!(t2_min >= 0.0 && t2_min < t2_max)) detail::invalid_option(where, "t2_min", t2_min, "in [0, t2_max)");
  if (seeds < 2 || seeds > 100000) detail::invalid_option(where, "seeds", seeds, "in [2, 100000]");
  // min_step first, then max_step against it: a max_step at or below the default min_step names max_step, the option
  // given (`spp continue --max-step 1e-300` was told about min_step, which it has no option for)
  if (!(min_step > 0.0 && min_step < 0.5)) detail::invalid_option(where, "min_step", min_step, "in (0, 0.5)");
  if (!(max_step > min_step && max_step <= 0.5)) {
    std::ostringstream rule;
    rule << "in (min_step, 0.5] = (" << min_step << ", 0.5] (a step below min_step stalls the branch)";
    detail::invalid_option(where, "max_step", max_step, rule.str());
  }
  if (!(max_turn > 0.0 && max_turn < 1.5)) detail::invalid_option(where, "max_turn", max_turn, "in (0, 1.5)");
  if (max_points < 10) detail::invalid_option(where, "max_points", max_points, ">= 10");
  if (!(locate_tol > 0.0 && locate_tol < 1e-3)) detail::invalid_option(where, "locate_tol", locate_tol, "in (0, 1e-3)");
  if (threads < 0) detail::invalid_option(where, "threads", threads, ">= 0");
}

const char* to_string(BranchEventKind k) {
  switch (k) {
    case BranchEventKind::LeavesWindow: return "leaves_window";
    case BranchEventKind::RangeEnd: return "range_end";
    case BranchEventKind::Fold: return "fold";
    case BranchEventKind::AdmissibilityLost: return "admissibility_lost";
    case BranchEventKind::AdmissibilityGained: return "admissibility_gained";
    case BranchEventKind::GapClosure: return "gap_closure";
    case BranchEventKind::ClosedLoop: return "closed_loop";
    case BranchEventKind::Stalled: return "stalled";
    case BranchEventKind::StabilityLost: return "stability_lost";
    case BranchEventKind::StabilityGained: return "stability_gained";
  }
  return "?";
}

const char* to_string(MultiplierCrossing c) {
  switch (c) {
    case MultiplierCrossing::None: return "none";
    case MultiplierCrossing::PlusOne: return "plus_one";
    case MultiplierCrossing::MinusOne: return "minus_one";
    case MultiplierCrossing::ComplexPair: return "complex_pair";
  }
  return "?";
}

const char* to_string(ContinuationStatus s) {
  return s == ContinuationStatus::Success ? "success" : "incomplete";
}

std::string ContinuationResult::brief_report() const {
  long points = 0;
  std::map<std::string, int> kinds;
  for (const Branch& b : branches) {
    points += static_cast<long>(b.points.size());
    for (const BranchEvent& e : b.events) ++kinds[to_string(e.kind)];
  }
  std::ostringstream os;
  os << "continue: " << to_string(status) << ", " << branches.size() << " branches, " << points << " points over "
     << parameter.name << " in [" << parameter.min << ", " << parameter.max << "]; events:";
  if (kinds.empty()) os << " none";
  for (const auto& [k, c] : kinds) os << " " << c << " " << k;
  os << "; " << seed_spps << " seed SPPs, " << seed_crossings << " seed crossings; ";
  if (incomplete_seed_solves) os << incomplete_seed_solves << " incomplete seed solves, ";
  if (stalled_branches) os << stalled_branches << " stalled branch ends, ";
  if (unlisted_crossings) os << unlisted_crossings << " unlisted crossings, ";
  os << warnings.size() << " warnings; " << corrector_solves << " corrector solves, " << seconds << " s";
  return os.str();
}

std::vector<BranchPoint> gap_closures(const ContinuationResult& r) {
  std::vector<BranchPoint> out;
  for (const Branch& b : r.branches)
    for (const BranchEvent& e : b.events)
      if (e.kind == BranchEventKind::GapClosure) out.push_back(e.at);
  std::sort(out.begin(), out.end(), [](const BranchPoint& a, const BranchPoint& b) { return a.mu < b.mu; });
  return out;
}

namespace {
using Vec = Eigen::VectorXd;
using Mat = Eigen::MatrixXd;
using V3 = Eigen::Vector3d;

// Tolerances of the branch tracer, in the scaled coordinates y = (t1 / t1_max, t2 / t2_max, (mu - min) / range).
/// Central-difference step of the Jacobian's mu column, relative to max(1, |y_mu|): ~eps^(1/3), the step that
/// balances truncation (h^2) against rounding (eps / h) of F.
constexpr double kDifferenceStep = 1e-6;
/// The corrector (continuation/corrector.hpp): 12 iterations (3 to 5 when converging), a step longer than 0.2 in
/// scaled units left the branch (the arclength is halved), converged at a step of 1e-14 (~1e2 eps of y ~ 1), or at
/// a step that stagnates below 1e-10: issue 14's last session found one branch of the chain with k5 in [0.9, 1],
/// window (0, 12]^2, traced as two (branches 65 and 66), each stalled from its side between k5 = 0.99604 and 0.99631
/// (t1 10.01 to 10.25) where F jitters by 3e-13 over an ill-conditioned J: Newton's steps never fell below 1e-14
/// even from predictors 1e-9 away, and a stability event between the two pieces was lost. 1e-10 is far below the
/// distances that tell SPPs apart (kSeedMatch) and far above that jitter.
constexpr continuation::CorrectorOptions kCorrector{12, 0.2, 1e-14, 1e-10};
/// Steps shorter than this fraction of max_step count as creeping; kCreepSteps of them in a row is a stall.
constexpr double kCreepFraction = 1e-3;
constexpr int kCreepSteps = 200;
/// Back at the start with a tangent within ~25 degrees of the first one (cosine above this): a closed branch.
constexpr double kClosedLoopCos = 0.9;
/// A seed SPP and a branch crossing of that seed value closer than this fraction of t1_max and t2_max are one SPP:
/// the crossing is located to locate_tol in arclength, far finer, and distinct SPPs lie much farther apart.
constexpr double kSeedMatch = 1e-7;
/// Events are looked for up to the located window edge times this: a relative 1e-7 past it, so that an event located
/// at the edge itself (to locate_tol) is not lost to rounding of the edge's arclength.
constexpr double kEdgeOvershoot = 1.0000001;
/// Parameter values whose modal forms are kept (the corrector and the difference Jacobian revisit a few of them).
constexpr size_t kCachedForms = 6;

struct Eval {
  Eigen::Vector2d F;
  Vec a;  // null vector of N (modal), oriented by the border: b^T a = 1
};

// One traced point: scaled position, tangent, the physical mid-flight shape that orients the null vector.
struct State {
  V3 y, tau;
  Vec xref;
  BranchPoint point;
};

class Tracer {
 public:
  Tracer(const ParametricSystem& ps, const ContinueOptions& o, double t1_min, double t2_min)
      : ps_(ps), o_(o), t1_min_(t1_min), t2_min_(t2_min) {
    L_ << o.t1_max, o.t2_max, ps.parameter().max - ps.parameter().min;
  }

  long corrector_solves = 0;

  double t1(const V3& y) const { return y(0) * L_(0); }
  double t2(const V3& y) const { return y(1) * L_(1); }
  double mu(const V3& y) const { return ps_.parameter().min + y(2) * L_(2); }
  V3 scaled(double t1, double t2, double mu) const {
    return V3(t1 / L_(0), t2 / L_(1), (mu - ps_.parameter().min) / L_(2));
  }

  struct Cached {
    System system;
    ModalForm modal;
    std::unique_ptr<EquationSet> equations;  // on `modal` (the Cached is not moved once built)
  };
  // The system, modal form and equations at mu, or nullptr where there is no valid system: a corrector or a
  // bisection may try a mu beyond the declared range where M(mu) or K(mu) is not positive definite (or the
  // spectrum is beyond double precision). That is an outcome of the step (it fails and is shortened), never an
  // error of the run. System and ModalForm refuse by throwing from their constructors (their one way to validate):
  // this is the one place where the refusal is turned into that outcome.
  const Cached* try_at(double mu) {
    for (auto it = cache_.begin(); it != cache_.end(); ++it)
      if (it->first == mu) {
        cache_.splice(cache_.begin(), cache_, it);
        return cache_.front().second.get();
      }
    std::unique_ptr<Cached> c;
    try {
      System s = ps_.at(mu);
      ModalForm md(s);
      c = std::make_unique<Cached>(Cached{std::move(s), std::move(md), nullptr});
    } catch (const std::invalid_argument&) {
      return nullptr;
    }
    c->equations = make_equations(c->modal, o_.symmetry);
    cache_.emplace_front(mu, std::move(c));
    if (cache_.size() > kCachedForms) cache_.pop_back();
    return cache_.front().second.get();
  }
  // The same where mu is known valid (a converged point's): its absence is a defect.
  const Cached& at(double mu) {
    const Cached* c = try_at(mu);
    if (c == nullptr) detail::internal_error("continuation: no valid system at a converged point's parameter value");
    return *c;
  }

  // F at y and, when J is given, its Jacobian in y: analytic in t1 and t2 (derivatives of the bordered solve, on
  // the same LU), central differences in mu (the modal form's dependence on mu has no closed form here).
  // F is NaN (and J) where there is no valid system at mu(y) (try_at): Newton and the tangent then fail the step.
  Eval eval(const V3& y, const Vec& xref, Eigen::Matrix<double, 2, 3>* J = nullptr) {
    const Cached* cp = try_at(mu(y));
    if (cp == nullptr) {
      Eval none;
      none.F.setConstant(std::numeric_limits<double>::quiet_NaN());
      if (J != nullptr) J->setConstant(std::numeric_limits<double>::quiet_NaN());
      return none;
    }
    const Cached& c = *cp;
    const ModalForm& md = c.modal;
    const EquationSet& eq = *c.equations;
    const int m = md.m();
    Vec b = md.omega().asDiagonal() * (md.Phi().transpose() * (c.system.M() * xref));
    b /= b.norm();
    Mat B = Mat::Zero(m + 1, m + 1);
    B.topLeftCorner(m, m) = eq.N(t1(y), t2(y));
    B.topRightCorner(m, 1) = b;
    B.bottomLeftCorner(1, m) = b.transpose();
    Vec rhs = Vec::Zero(m + 1);
    rhs(m) = 1.0;
    const Eigen::PartialPivLU<Mat> lu = B.partialPivLu();
    const Vec sol = lu.solve(rhs);
    Eval e;
    e.a = sol.head(m);
    e.F(0) = sol(m);
    const double zn = md.z().norm();
    e.F(1) = md.z().dot(eq.onset_position(t1(y), e.a)) / zn;
    if (J == nullptr) return e;
    // B (a, s) = e_m with b fixed: B d(a, s)/dt = -(dN/dt a, 0), and F(1) is linear in a (onset_position).
    const double T1 = t1(y), T2 = t2(y);
    Vec r = Vec::Zero(m + 1);
    r.head(m) = -(eq.dN_dt1(T1, T2) * e.a);
    Vec ds = lu.solve(r);
    (*J)(0, 0) = ds(m) * L_(0);
    (*J)(1, 0) = md.z().dot(eq.onset_position_dt1(T1, e.a) + eq.onset_position(T1, ds.head(m))) / zn * L_(0);
    r.head(m) = -(eq.dN_dt2(T1, T2) * e.a);
    ds = lu.solve(r);
    (*J)(0, 1) = ds(m) * L_(1);
    (*J)(1, 1) = md.z().dot(eq.onset_position(T1, ds.head(m))) / zn * L_(1);
    // last: evaluations at other mu may evict `c` from the cache
    const double h = kDifferenceStep * std::max(1.0, std::abs(y(2)));
    V3 yp = y, ym = y;
    yp(2) += h;
    ym(2) -= h;
    J->col(2) = (eval(yp, xref).F - eval(ym, xref).F) / (2.0 * h);
    return e;
  }

  V3 tangent(const V3& y, const Vec& xref, const V3& orient) {
    Eigen::Matrix<double, 2, 3> J;
    eval(y, xref, &J);
    return continuation::curve_tangent(J, orient);
  }

  // Newton on F(y) = 0, tau . (y - ypred) = 0 from ypred. Returns false if it does not converge (also where a
  // trial parameter value has no valid system: F is NaN there, see eval).
  bool correct(const V3& ypred, const V3& tau, const Vec& xref, V3& y, Eval& e, int& its) {
    ++corrector_solves;
    auto linearize = [&](const Vec& yk, Vec& F, Mat& J) {
      Eigen::Matrix<double, 2, 3> Jk;
      F = eval(V3(yk), xref, &Jk).F;
      J = Jk;
    };
    Vec yc;
    const continuation::CorrectorResult r =
        continuation::correct_pseudo_arclength(linearize, ypred, tau, yc, kCorrector);
    its = r.iterations;
    if (!r.converged) return false;
    y = yc;
    e = eval(y, xref);
    return e.F.allFinite();
  }

  BranchPoint point(const V3& y, const Eval& e) {
    BranchPoint p;
    p.mu = mu(y);
    p.t1 = t1(y);
    p.t2 = t2(y);
    p.period = 2.0 * (p.t1 + p.t2);
    p.margin = std::numeric_limits<double>::quiet_NaN();
    // (a bisection's unconverged trial point may lie where there is no valid system: no orbit, not admissible)
    const Cached* cp = e.F.allFinite() ? try_at(p.mu) : nullptr;
    if (cp == nullptr) {
      p.closure = std::numeric_limits<double>::quiet_NaN();
      p.admissible = false;
      return p;
    }
    const Cached& c = *cp;
    const ModalForm& md = c.modal;
    const Eigen::ArrayXd& w = md.omega().array();
    // u^T W^-1 cos(W t1) a: the gap at onset (axial, p0 = cos(W t1) a) or the normal velocity at onset (point,
    // p0' = cos(W t1) a), continuous along the branch.
    const Vec q0 = ((w * p.t1).cos() * e.a.array() / w).matrix();
    p.closure = md.u().dot(q0) / (e.a.array() / w).matrix().norm();
    const EquationSet& eq = *c.equations;
    const bool free_scale = md.g0() == 0.0;
    // no orbit where eq. (5.2) has no scale (u^T W^-1 p0 = 0 exactly), or no null vector to scale to unit energy
    if (free_scale ? e.a.squaredNorm() > 0.0 : gap_can_close(eq, p.t1, e.a)) {
      const Orbit o = free_scale ? make_unit_energy_orbit(eq, p.t1, p.t2, e.a) : make_orbit(eq, p.t1, p.t2, e.a);
      p.energy = o.energy;
      p.x0 = o.x0;
      p.v0 = o.v0;
      // With g0 = 0 the orbit closes the gap only where closure = 0: the margin means nothing elsewhere; point
      // symmetric orbits are never admissible (no margin).
      if (!free_scale && eq.can_be_admissible()) {
        p.margin = admissibility_margin(md, o);
        const Floquet f = floquet(eq, o);
        p.spectral_radius = f.spectral_radius;
        p.spectral_radius_error = f.spectral_radius_error;
      }
    }
    p.admissible = p.margin >= 0.0;
    return p;
  }

  // The coupled modes' leading multiplier(s) at a branch point (Floquet::leading); empty where point() computes no
  // spectral radius.
  std::vector<std::complex<double>> leading_multipliers(const V3& y, const Eval& e) {
    const Cached* cp = e.F.allFinite() ? try_at(mu(y)) : nullptr;
    if (cp == nullptr || cp->modal.g0() == 0.0 || !cp->equations->can_be_admissible() ||
        !gap_can_close(*cp->equations, t1(y), e.a))
      return {};
    return floquet(cp->modal, make_orbit(*cp->equations, t1(y), t2(y), e.a)).leading;
  }

  // Zero-gap SPP at a located closure: its margin with the unit-energy orbit.
  void finish_closure(BranchPoint& p, const V3& y, const Eval& e) {
    const Cached& c = at(mu(y));
    const ModalForm& md = c.modal;
    const Orbit o = make_unit_energy_orbit(*c.equations, p.t1, p.t2, e.a);
    p.margin = md.g0() == 0.0 && c.equations->can_be_admissible() ? admissibility_margin(md, o)
                                                                  : std::numeric_limits<double>::quiet_NaN();
    p.admissible = p.margin >= 0.0;
    p.energy = o.energy;
    // The closure is located to rounding: put x0 exactly on the obstacle (g0 = 0: w^T x0 = 0), a correction of
    // the order of the location tolerance, so that a simulation can start from it.
    p.x0 = md.g0() == 0.0 ? Vec(o.x0 - c.system.w() * c.system.w().dot(o.x0)) : o.x0;
    p.v0 = o.v0;
  }

  Vec mid_flight_shape(const V3& y, const Eval& e) {
    const ModalForm& md = at(mu(y)).modal;
    Vec x = md.Phi() * (e.a.array() / md.omega().array()).matrix();
    return x / x.norm();
  }

  const V3& scale() const { return L_; }
  double t1_min() const { return t1_min_; }
  double t2_min() const { return t2_min_; }

 private:
  const ParametricSystem& ps_;
  const ContinueOptions& o_;
  double t1_min_, t2_min_;
  V3 L_;
  std::list<std::pair<double, std::unique_ptr<Cached>>> cache_;
};

struct SeedCrossing {
  int seed = 0;
  double t1 = 0.0, t2 = 0.0;
};

// Which multiplier crosses at a located stability event, from the leading multiplier(s) there; the detail names it.
void classify_crossing(BranchEvent& ev, std::vector<std::complex<double>> leading) {
  std::ostringstream os;
  os << std::setprecision(10) << "a Floquet multiplier crosses the unit circle";
  if (leading.empty()) {
    ev.detail = os.str() + " (multipliers not computed at the located point)";
    return;
  }
  const std::complex<double> z = leading.front();
  ev.crossing_angle = std::abs(std::arg(z));
  if (leading.size() == 2) {
    ev.crossing = MultiplierCrossing::ComplexPair;
    os << ": a complex pair exp(+-i theta), theta = " << ev.crossing_angle << " (Neimark-Sacker), " << z.real()
       << " +- " << std::abs(z.imag()) << "i";
  } else if (z.real() > 0.0) {
    ev.crossing = MultiplierCrossing::PlusOne;
    os << " through +1 (real, " << z.real() << ")";
  } else {
    ev.crossing = MultiplierCrossing::MinusOne;
    os << " through -1 (period doubling, " << z.real() << ")";
  }
  ev.crossing_multipliers = std::move(leading);
  ev.detail = os.str();
}

// Follows one direction of a branch from a converged state until it stops.
class BranchWalker {
 public:
  BranchWalker(Tracer& tr, const ContinueOptions& o, const std::vector<double>& seed_mu, bool free_scale)
      : tr_(tr), o_(o), seed_mu_(seed_mu), free_scale_(free_scale) {}

  std::vector<SeedCrossing> crossings;
  bool interrupted = false;  // o_.progress returned false: no branch is walked further

  bool keep_going() {
    if (!interrupted && o_.progress && !o_.progress()) interrupted = true;
    return !interrupted;
  }

  // points: traced points after the start; events in order.
  // Returns true if the branch closed on itself (then the other direction need not be walked).
  bool walk(State s, std::vector<BranchPoint>& points, std::vector<BranchEvent>& events) {
    const V3 y_start = s.y, tau_start = s.tau;
    double travelled = 0.0;
    double h = 0.25 * o_.max_step;
    int creeping = 0;  // consecutive steps far below max_step
    for (int count = 0;; ++count) {
      if (!keep_going()) {
        events.push_back({BranchEventKind::Stalled, s.point, "interrupted"});
        return false;
      }
      if (count >= o_.max_points) {
        events.push_back({BranchEventKind::Stalled, s.point, "max_points reached"});
        return false;
      }
      V3 y;
      Eval e;
      int its = 0;
      bool ok = tr_.correct(s.y + h * s.tau, s.tau, s.xref, y, e, its);
      V3 tau;
      if (ok) {
        tau = tr_.tangent(y, s.xref, s.tau);  // NaN where there is no valid system (eval)
        ok = tau.allFinite() && tau.dot(s.tau) >= std::cos(o_.max_turn) && (y - s.y).norm() <= 2.0 * h;
      }
      if (!ok) {
        h *= 0.5;
        if (h < o_.min_step) {
          events.push_back({BranchEventKind::Stalled, s.point, "step below min_step"});
          return false;
        }
        continue;
      }
      State next{y, tau, tr_.mid_flight_shape(y, e), tr_.point(y, e)};
      if (handle_step(s, next, h, points, events)) return false;
      travelled += (next.y - s.y).norm();
      // Back at the start, in the same direction: a closed branch.
      if (travelled > 4.0 * h && (next.y - y_start).norm() <= std::max(h, (next.y - s.y).norm()) &&
          next.tau.dot(tau_start) > kClosedLoopCos && (y_start - s.y).dot(s.tau) >= 0 &&
          (y_start - next.y).dot(next.tau) <= 0) {
        events.push_back({BranchEventKind::ClosedLoop, next.point, "back at the first point: a closed branch"});
        return true;
      }
      points.push_back(next.point);
      s = std::move(next);
      if (its <= 3) h = std::min(1.5 * h, o_.max_step);
      creeping = h < kCreepFraction * o_.max_step ? creeping + 1 : 0;
      if (creeping >= kCreepSteps) {
        events.push_back({BranchEventKind::Stalled, s.point,
                          "200 steps below 1e-3 max_step: a degenerate point (e.g. a continuum of SPPs at one "
                          "parameter value, or the t1 -> 0 axis)"});
        return false;
      }
    }
  }

 private:
  // Point on the branch at predictor distance hp from s (same tangent and orientation as the step).
  struct Along {
    V3 y;
    Eval e;
    BranchPoint p;
    bool on_branch = false;  ///< the corrector converged: y satisfies the SPP equations
  };
  Along along(const State& s, double hp) { return corrected(s, s.y + hp * s.tau); }
  Along corrected(const State& s, const V3& ypred) {
    Along a;
    int its = 0;
    a.on_branch = tr_.correct(ypred, s.tau, s.xref, a.y, a.e, its);
    if (!a.on_branch) a.y = ypred, a.e = tr_.eval(a.y, s.xref);
    a.p = tr_.point(a.y, a.e);
    return a;
  }

  // Bisection on hp in [0, h] for a sign change of f (f(0) and f(h) of opposite signs), every trial corrected onto
  // the branch. A trial whose corrector fails from the tangent predictor (a steep or curved branch) is corrected from
  // the chord between the bracket's two on-branch ends instead, and never taken uncorrected: issue 14's attack found
  // a stability event reported at an uncorrected predictor, 6.6e-4 from the SPP in t1 and 1e-4 off its equations
  // (chain, k5 = 0.94238, dt1/dk5 ~ 230).
  Along locate(const State& s, double h, const std::function<double(const Along&)>& f, double f0) {
    double lo = 0.0, hi = h;
    Along best = along(s, h);
    V3 ylo = s.y, yhi = best.y;
    while (hi - lo > o_.locate_tol) {
      const double mid = 0.5 * (lo + hi);
      Along a = along(s, mid);
      if (!a.on_branch) {
        const V3 d = yhi - ylo;
        Along c = corrected(s, ylo + ((mid - lo) / (hi - lo)) * d);
        // only a point within the bracket: a corrector that wandered (beyond the range, onto another branch) is no
        // trial of this crossing. When both fail the uncorrected predictor decides the side, as before (where no
        // system is valid, beyond the range, only the edges' functions of y are defined there).
        const double t = (c.y - ylo).dot(d) / d.squaredNorm();
        if (c.on_branch && t >= 0.0 && t <= 1.0 && (c.y - ylo - t * d).norm() <= d.norm()) a = std::move(c);
      }
      const double v = f(a);
      if (!std::isfinite(v)) break;
      if ((v < 0) == (f0 < 0)) {
        lo = mid;
        ylo = a.y;
      } else {
        hi = mid;
        yhi = a.y;
        best = std::move(a);
      }
    }
    return best;
  }

  // Events between s and next; returns true when the branch stops.
  bool handle_step(const State& s, State& next, double h, std::vector<BranchPoint>& points,
                   std::vector<BranchEvent>& events) {
    const V3 L = tr_.scale();
    // Window and range: signed distances inside (>= 0 inside).
    const double lo1 = tr_.t1_min() / L(0), lo2 = tr_.t2_min() / L(1);
    const std::array<std::function<double(const V3&)>, 6> edges = {
        [](const V3& y) { return 1.0 - y(0); }, [lo1](const V3& y) { return y(0) - lo1; },
        [](const V3& y) { return 1.0 - y(1); }, [lo2](const V3& y) { return y(1) - lo2; },
        [](const V3& y) { return 1.0 - y(2); }, [](const V3& y) { return y(2); }};
    const std::array<const char*, 6> edge_names = {"t1 = t1_max", "t1 = t1_min", "t2 = t2_max",
                                                   "t2 = t2_min", "mu = max",    "mu = min"};
    double stop_h = h;
    int stop_edge = -1;
    Along stop;
    for (int k = 0; k < 6; ++k) {
      if (edges[k](next.y) >= 0.0) continue;
      const double f0 = edges[k](s.y);
      Along a = locate(
          s, h, [&](const Along& x) { return edges[k](x.y); }, f0);
      const double hp = (a.y - s.y).norm();
      if (stop_edge < 0 || hp < stop_h) stop_h = hp, stop_edge = k, stop = std::move(a);
    }
    const BranchPoint end = stop_edge >= 0 ? stop.p : next.point;
    const V3 end_y = stop_edge >= 0 ? stop.y : next.y;
    const double end_h = stop_edge >= 0 ? std::min(h, stop_h * kEdgeOvershoot) : h;

    struct Found {
      double hp;
      BranchEvent e;
    };
    std::vector<Found> found;
    // Seed crossings (for de-duplication of seeds and the cross-check with solve()).
    for (size_t k = 0; k < seed_mu_.size(); ++k) {
      const double a = s.point.mu - seed_mu_[k], b = end.mu - seed_mu_[k];
      if (a == 0.0 || (a < 0) == (b < 0)) continue;
      Along x = locate(
          s, end_h, [&](const Along& q) { return q.p.mu - seed_mu_[k]; }, a);
      crossings.push_back({static_cast<int>(k), x.p.t1, x.p.t2});
    }
    // Fold: the mu component of the tangent changes sign.
    const V3 end_tau = stop_edge >= 0 ? tr_.tangent(end_y, s.xref, s.tau) : next.tau;
    if ((s.tau(2) < 0) != (end_tau(2) < 0)) {
      Along x = locate(
          s, end_h, [&](const Along& q) { return tr_.tangent(q.y, s.xref, s.tau)(2); }, s.tau(2));
      found.push_back({(x.y - s.y).norm(), {BranchEventKind::Fold, x.p, "d mu / ds changes sign"}});
    }
    const bool closes = (s.point.closure < 0) != (end.closure < 0);
    if (closes) {
      Along x = locate(
          s, end_h, [](const Along& q) { return q.p.closure; }, s.point.closure);
      tr_.finish_closure(x.p, x.y, x.e);
      std::ostringstream os;
      if (o_.symmetry == Symmetry::Point)
        os << "zero normal velocity at onset: "
           << (free_scale_ ? "with g0 = 0 a point-symmetric potential SPP with a fixed obstacle (paper §6.2), "
                             "never admissible (the force is odd about t2)"
                           : "the moving obstacle of this point-symmetric branch stands still");
      else if (free_scale_)
        os << "g0 = 0: an SPP (paper §6.1), scaled to unit energy, "
           << (x.p.admissible ? "admissible" : "not admissible") << " (margin " << x.p.margin << ")";
      else
        os << "u^T W^-1 p0 = 0: the orbit's amplitude diverges (the gap cannot close at g0 != 0)";
      found.push_back({(x.y - s.y).norm(), {BranchEventKind::GapClosure, x.p, os.str()}});
    }
    if (!free_scale_ && !closes && std::isfinite(s.point.margin) && std::isfinite(end.margin) &&
        (s.point.margin < 0) != (end.margin < 0)) {
      Along x = locate(
          s, end_h, [](const Along& q) { return q.p.margin; }, s.point.margin);
      const bool lost = s.point.margin >= 0;
      found.push_back({(x.y - s.y).norm(),
                       {lost ? BranchEventKind::AdmissibilityLost : BranchEventKind::AdmissibilityGained, x.p,
                        "admissibility_margin crosses zero"}});
    }
    if (!closes && std::isfinite(s.point.spectral_radius) && std::isfinite(end.spectral_radius) &&
        (s.point.spectral_radius < 1.0) != (end.spectral_radius < 1.0)) {
      // the largest modulus is continuous along the branch (not smooth where two multipliers swap): bisection
      Along x = locate(
          s, end_h, [](const Along& q) { return q.p.spectral_radius - 1.0; }, s.point.spectral_radius - 1.0);
      const bool lost = s.point.spectral_radius < 1.0;
      BranchEvent ev{lost ? BranchEventKind::StabilityLost : BranchEventKind::StabilityGained, x.p, ""};
      classify_crossing(ev, tr_.leading_multipliers(x.y, x.e));
      // The radius there with its bound: the point is located where the computed rho crosses 1, but near a fold its
      // (t1, t2) can be off the SPP of its parameter value, where rho is not 1 (issue 14's attack: 3.6e-11 off, rho - 1
      // = 8.7e-12 there, reported -1.6e-14); the bound says how far the true crossing may be.
      std::ostringstream os;
      os << std::setprecision(3) << "; spectral radius 1 " << (x.p.spectral_radius >= 1.0 ? "+ " : "- ")
         << std::abs(x.p.spectral_radius - 1.0) << " +- " << x.p.spectral_radius_error;
      ev.detail += os.str();
      found.push_back({(x.y - s.y).norm(), std::move(ev)});
    }
    std::sort(found.begin(), found.end(), [](const Found& a, const Found& b) { return a.hp < b.hp; });
    for (Found& f : found) events.push_back(std::move(f.e));
    if (stop_edge >= 0) {
      points.push_back(end);
      const bool range = stop_edge >= 4;
      events.push_back({range ? BranchEventKind::RangeEnd : BranchEventKind::LeavesWindow, end,
                        std::string("reaches ") + edge_names[stop_edge]});
      return true;
    }
    return false;
  }

  Tracer& tr_;
  const ContinueOptions& o_;
  const std::vector<double>& seed_mu_;
  bool free_scale_;
};

BranchEvent reversed(BranchEvent e) {
  if (e.kind == BranchEventKind::AdmissibilityLost)
    e.kind = BranchEventKind::AdmissibilityGained;
  else if (e.kind == BranchEventKind::AdmissibilityGained)
    e.kind = BranchEventKind::AdmissibilityLost;
  else if (e.kind == BranchEventKind::StabilityLost)
    e.kind = BranchEventKind::StabilityGained;
  else if (e.kind == BranchEventKind::StabilityGained)
    e.kind = BranchEventKind::StabilityLost;
  return e;
}

// The branch through y0 (a point on it, scaled) whose null vector in y0's modal basis is `a`: walked forward (mu
// increasing at the start) and, unless it closed on itself, backward, as one list of points and events.
Branch trace_branch(Tracer& tr, BranchWalker& walker, const V3& y0, const Vec& a) {
  const ModalForm& md = tr.at(tr.mu(y0)).modal;
  Vec xref = md.Phi() * (a.array() / md.omega().array()).matrix();
  xref /= xref.norm();
  const Eval e0 = tr.eval(y0, xref);
  const V3 tau0 = tr.tangent(y0, xref, V3(0.0, 0.0, 1.0));
  State start{y0, tau0, xref, tr.point(y0, e0)};
  Branch br;
  br.points.push_back(start.point);
  std::vector<BranchPoint> fwd_pts;
  std::vector<BranchEvent> fwd_ev;
  const bool closed = walker.walk(start, fwd_pts, fwd_ev);
  if (!closed) {
    std::vector<BranchPoint> back_pts;
    std::vector<BranchEvent> back_ev;
    State back = start;
    back.tau = -start.tau;
    walker.walk(back, back_pts, back_ev);
    br.points.clear();
    for (auto it = back_pts.rbegin(); it != back_pts.rend(); ++it) br.points.push_back(*it);
    for (auto it = back_ev.rbegin(); it != back_ev.rend(); ++it) br.events.push_back(reversed(*it));
    br.points.push_back(start.point);
  }
  br.points.insert(br.points.end(), fwd_pts.begin(), fwd_pts.end());
  br.events.insert(br.events.end(), fwd_ev.begin(), fwd_ev.end());
  return br;
}

// The window's lower ends: options' own, or (0) as solve() picks them, the smaller over both ends of the range.
std::pair<double, double> window_lower_ends(const ParametricSystem& ps, const ContinueOptions& options) {
  double t1_min = options.t1_min, t2_min = options.t2_min;
  if (t1_min == 0.0 || t2_min == 0.0) {
    double lo1 = options.t1_max, lo2 = options.t2_max;
    for (double mu : {ps.parameter().min, ps.parameter().max}) {
      const auto [a, b] = default_lower_ends(ModalForm(ps.at(mu)), options.t1_max, options.t2_max);
      lo1 = std::min(lo1, a);
      lo2 = std::min(lo2, b);
    }
    if (t1_min == 0.0) t1_min = lo1;
    if (t2_min == 0.0) t2_min = lo2;
  }
  return {t1_min, t2_min};
}

}  // namespace

ContinuationResult continue_branches(const ParametricSystem& ps, const ContinueOptions& options) {
  options.validate();
  const auto t_start = std::chrono::steady_clock::now();
  const Parameter& par = ps.parameter();
  ContinuationResult res;
  res.parameter = par;
  res.symmetry = options.symmetry;
  res.t1_max = options.t1_max;
  res.t2_max = options.t2_max;
  const bool free_scale = ps.g0() == 0.0;

  // One window for every seed: the lower ends as solve() picks them, over both ends of the range.
  const auto [t1_min, t2_min] = window_lower_ends(ps, options);
  res.t1_min = t1_min;
  res.t2_min = t2_min;

  std::vector<double> seed_mu(options.seeds);
  for (int k = 0; k < options.seeds; ++k)
    seed_mu[k] = k + 1 == options.seeds ? par.max : par.min + (par.max - par.min) * k / (options.seeds - 1);

  // solve() at each seed (g0 = 0: the equations (5.1) do not involve g0; solve a copy with g0 = 1 for them).
  SolveOptions so;
  so.t1_min = t1_min;
  so.t2_min = t2_min;
  so.t1_max = options.t1_max;
  so.t2_max = options.t2_max;
  so.compute_return_error = false;
  so.threads = options.threads;
  so.symmetry = options.symmetry;
  bool seeds_interrupted = false;
  if (options.progress)
    so.progress = [&](const SolveProgress&) {
      if (!seeds_interrupted && !options.progress()) seeds_interrupted = true;
      return !seeds_interrupted;
    };
  std::vector<std::vector<Solution>> seed_sols(options.seeds);
  for (int k = 0; k < options.seeds && !seeds_interrupted; ++k) {
    System s = ps.at(seed_mu[k]);
    if (free_scale) s = System(s.M(), s.K(), s.w(), 1.0, s.name());
    SolveResult r = solve(s, so);
    if (r.status != SolveStatus::Success) ++res.incomplete_seed_solves;
    if (r.status != SolveStatus::Success)
      res.warnings.push_back("solve at " + par.name + " = " + std::to_string(seed_mu[k]) + ": " + r.brief_report());
    res.seed_spps += static_cast<long>(r.solutions.size());
    seed_sols[k] = std::move(r.solutions);
    if (!seeds_interrupted && options.progress && !options.progress()) seeds_interrupted = true;
  }

  Tracer tr(ps, options, t1_min, t2_min);
  BranchWalker walker(tr, options, seed_mu, free_scale);
  auto matched = [&](int k, double t1, double t2) {
    for (const SeedCrossing& c : walker.crossings)
      if (c.seed == k && std::abs(c.t1 - t1) <= kSeedMatch * options.t1_max &&
          std::abs(c.t2 - t2) <= kSeedMatch * options.t2_max)
        return true;
    return false;
  };

  walker.interrupted = seeds_interrupted;
  for (int k = 0; k < options.seeds && !walker.interrupted; ++k) {
    for (const Solution& sol : seed_sols[k]) {
      if (walker.interrupted) break;
      if (matched(k, sol.t1(), sol.t2())) continue;
      walker.crossings.push_back({k, sol.t1(), sol.t2()});
      res.branches.push_back(trace_branch(tr, walker, tr.scaled(sol.t1(), sol.t2(), seed_mu[k]), sol.orbit.a));
    }
  }

  // Cross-check: every crossing of a seed value is one of solve()'s SPPs there (not after an interruption: the seeds
  // not solved list none).
  for (const SeedCrossing& c : walker.interrupted ? std::vector<SeedCrossing>{} : walker.crossings) {
    const auto& sols = seed_sols[c.seed];
    const bool found = std::any_of(sols.begin(), sols.end(), [&](const Solution& s) {
      return std::abs(s.t1() - c.t1) <= kSeedMatch * options.t1_max &&
             std::abs(s.t2() - c.t2) <= kSeedMatch * options.t2_max;
    });
    if (found) {
      ++res.seed_crossings;
    } else {
      ++res.unlisted_crossings;
      std::ostringstream os;
      os << "a branch crosses " << par.name << " = " << seed_mu[c.seed] << " at (t1, t2) = (" << c.t1 << ", " << c.t2
         << "), which solve() there does not list";
      res.warnings.push_back(os.str());
    }
  }
  for (const Branch& b : res.branches)
    for (const BranchEvent& e : b.events) res.stalled_branches += e.kind == BranchEventKind::Stalled;
  res.interrupted = walker.interrupted;
  if (res.interrupted)
    res.warnings.push_back(
        "interrupted: the branches traced so far (the last one ends with a stalled event "
        "\"interrupted\"); the seeds not reached are not traced");
  const bool complete =
      res.incomplete_seed_solves == 0 && res.stalled_branches == 0 && res.unlisted_crossings == 0 && !res.interrupted;
  res.status = complete ? ContinuationStatus::Success : ContinuationStatus::Incomplete;
  res.corrector_solves = tr.corrector_solves;
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  return res;
}

ContinuationResult continue_branch(const ParametricSystem& ps, double mu, const Solution& solution,
                                   const ContinueOptions& options) {
  options.validate();
  const auto t_start = std::chrono::steady_clock::now();
  const Parameter& par = ps.parameter();
  if (!(mu >= par.min && mu <= par.max)) {
    std::ostringstream os;
    os << "continue_branch: expected mu in the range [" << par.min << ", " << par.max << "] of " << par.name << ", got "
       << mu;
    detail::invalid(os.str());
  }
  if (solution.orbit.symmetry != options.symmetry)
    detail::invalid(std::string("continue_branch: expected a solution of symmetry ") + to_string(options.symmetry) +
                    " (options.symmetry), got one of symmetry " + to_string(solution.orbit.symmetry));
  ContinuationResult res;
  res.parameter = par;
  res.symmetry = options.symmetry;
  res.t1_max = options.t1_max;
  res.t2_max = options.t2_max;
  std::tie(res.t1_min, res.t2_min) = window_lower_ends(ps, options);
  if (!(solution.t1() > res.t1_min && solution.t1() <= res.t1_max && solution.t2() > res.t2_min &&
        solution.t2() <= res.t2_max)) {
    std::ostringstream os;
    os << "continue_branch: the solution at (t1, t2) = (" << solution.t1() << ", " << solution.t2()
       << ") is outside the window (" << res.t1_min << ", " << res.t1_max << "] x (" << res.t2_min << ", " << res.t2_max
       << "]: expected t1_max and t2_max that hold it";
    detail::invalid(os.str());
  }
  Tracer tr(ps, options, res.t1_min, res.t2_min);
  // the solution's null vector in this modal basis (refuses an orbit of another system), then the point corrected
  // onto the branch at fixed mu: the hyperplane of the corrector is mu = const
  const ModalForm& md = tr.at(mu).modal;
  const Vec a = in_modal_basis(md, solution.orbit, "continue_branch").a;
  const V3 y_given = tr.scaled(solution.t1(), solution.t2(), mu);
  Vec xref = md.Phi() * (a.array() / md.omega().array()).matrix();
  xref /= xref.norm();
  V3 y0;
  Eval e;
  int its = 0;
  const bool on_branch = tr.correct(y_given, V3(0.0, 0.0, 1.0), xref, y0, e, its) &&
                         std::hypot(tr.t1(y0) - solution.t1(), tr.t2(y0) - solution.t2()) <=
                             search::kPolishReach * (solution.t1() + solution.t2());
  if (!on_branch) {
    std::ostringstream os;
    os << "continue_branch: the solution at (t1, t2) = (" << solution.t1() << ", " << solution.t2()
       << ") is no SPP of the system at " << par.name << " = " << mu
       << " (Newton at fixed mu did not converge near it): give a solution of system.at(mu)";
    detail::invalid(os.str());
  }
  const std::vector<double> no_seeds;  // (the walker keeps a reference)
  BranchWalker walker(tr, options, no_seeds, ps.g0() == 0.0);
  res.branches.push_back(trace_branch(tr, walker, y0, a));
  for (const BranchEvent& ev : res.branches.front().events) res.stalled_branches += ev.kind == BranchEventKind::Stalled;
  res.interrupted = walker.interrupted;
  if (res.interrupted) res.warnings.push_back("interrupted: the branch as traced so far");
  res.status =
      res.stalled_branches == 0 && !res.interrupted ? ContinuationStatus::Success : ContinuationStatus::Incomplete;
  res.corrector_solves = tr.corrector_solves;
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  return res;
}

}  // namespace spp
