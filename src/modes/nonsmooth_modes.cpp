#include "spp/modes/nonsmooth_modes.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "continuation/corrector.hpp"
#include "spp/detail/cosine_sum.hpp"
#include "spp/detail/invalid.hpp"

namespace spp::modes {

const char* to_string(ModeEventKind kind) {
  switch (kind) {
    case ModeEventKind::GrazingStart: return "grazing_start";
    case ModeEventKind::BranchStart: return "branch_start";
    case ModeEventKind::GrazingContinuation: return "grazing_continuation";
    case ModeEventKind::BranchPoint: return "branch_point";
    case ModeEventKind::ImpactGrazing: return "impact_grazing";
    case ModeEventKind::FlightGrazing: return "flight_grazing";
    case ModeEventKind::EnergyMax: return "energy_max";
    case ModeEventKind::Stalled: return "stalled";
    case ModeEventKind::NoAdmissibleSide: return "no_admissible_side";
    case ModeEventKind::AdmissibilityRegained: return "admissibility_regained";
    case ModeEventKind::Interrupted: return "interrupted";
    case ModeEventKind::ClosedLoop: return "closed_loop";
    case ModeEventKind::Seeded: return "seeded";
  }
  return "?";
}

const char* to_string(ModesStatus s) {
  switch (s) {
    case ModesStatus::NotRun: return "not run";
    case ModesStatus::Traced: return "traced";
    case ModesStatus::Incomplete: return "incomplete";
  }
  return "?";
}

void ModesOptions::validate() const {
  const char* where = "ModesOptions";
  if (k_values.empty()) detail::invalid("ModesOptions: k_values must list at least one k, got none");
  std::set<int> seen;
  for (int k : k_values) {
    if (k < 1 || k > kMaxImpactsPerPeriod)
      detail::invalid_option(where, "k", k, "in [1, " + std::to_string(kMaxImpactsPerPeriod) + "]");
    if (!seen.insert(k).second) detail::invalid_option(where, "k", k, "listed once");
  }
  if (!(energy_max > 0) || !std::isfinite(energy_max))
    detail::invalid_option(where, "energy_max", energy_max, "> 0 and finite");
  if (!(max_step > 0) || !(max_step <= 1)) detail::invalid_option(where, "max_step", max_step, "in (0, 1]");
  if (!(min_step > 0)) detail::invalid_option(where, "min_step", min_step, "> 0");
  if (!(min_step < max_step)) {  // both named: either may be the one the user set (--max-step 1e-10 named min_step)
    std::ostringstream os;
    os << "ModesOptions: min_step must be < max_step, got min_step = " << min_step << " and max_step = " << max_step
       << " (raise max_step or lower min_step)";
    detail::invalid(os.str());
  }
  if (!(max_turn > 0) || !(max_turn < 1.5)) detail::invalid_option(where, "max_turn", max_turn, "in (0, 1.5)");
  if (max_points < 2) detail::invalid_option(where, "max_points", max_points, "at least 2");
  if (period_multiples < 1 || period_multiples > kMaxPeriodMultiples)
    detail::invalid_option(where, "period_multiples", period_multiples,
                           "in [1, " + std::to_string(kMaxPeriodMultiples) + "]");
  if (!(seed_period_max >= 0) || !std::isfinite(seed_period_max))
    detail::invalid_option(where, "seed_period_max", seed_period_max, ">= 0 and finite");
  if (!(locate_tol > 0) || !(locate_tol < max_step))
    detail::invalid_option(where, "locate_tol", locate_tol, "in (0, max_step)");
}

std::string ModesProgress::line() const {
  std::ostringstream os;
  os.setf(std::ios::fixed);
  os.precision(1);
  os << "tracing k = " << k << " (k up to " << k_last << "): " << families << " families, " << steps << " steps, "
     << seconds << " s elapsed";
  return os.str();
}

std::string ModesResult::brief_report() const {
  std::ostringstream os;
  long genuine = 0, points = 0;
  std::map<std::string, long> kinds;
  for (const ModeFamily& f : families) {
    genuine += f.multiplicity == 1;
    points += static_cast<long>(f.points.size());
    for (const ModeEvent& e : f.events) ++kinds[to_string(e.kind)];
  }
  os << "spp modes: " << to_string(status) << ", " << families.size() << " families (" << genuine << " genuine, "
     << families.size() - genuine << " repetitions), " << points << " points, events:";
  for (const auto& [k, c] : kinds) os << " " << k << " " << c;
  if (inadmissible_stretches > 0) os << "; " << inadmissible_stretches << " inadmissible stretches followed";
  os << "; " << corrector_solves << " corrector solves, " << seconds << " s";
  return os.str();
}

namespace {

// A family's first point is a tangency (a linear mode touching the obstacle, or a flight grazing it split into two
// zero-speed impacts): its margin is 0 in exact arithmetic, and computed it is rounding of either sign. Within this
// (relative to g0 and the speed scale, as the margin) it is taken as exactly 0, so that `admissible = margin >= 0`
// holds at every point (the start was marked admissible whatever its computed margin; an independent attack found
// margins of -1e-16 and, before the start of a past-grazing family was corrected onto it, -1.5e-6).
constexpr double kTangencyMargin = 1e-9;

namespace cont = spp::continuation;

struct Tracer {
  const KippModel& model;
  const ModesOptions& options;
  ModesResult& result;
  Eigen::VectorXd D;            // y = D z
  std::set<int> wanted;         // the requested k
  std::vector<size_t> pending;  // families ending at flight_grazing, to continue with k + 2 impacts
  // Inadmissible stretches to follow (ModesOptions::through_inadmissible): from y (unscaled unknowns, an inadmissible
  // solution) along the curve in the direction tau (scaled), h the step to try first; `from` names the family.
  struct Stretch {
    KippShape shape;
    Eigen::VectorXd y, tau;
    double h = 0.0;
    int mode = 0;
    std::string from;
    double energy_limit = 0.0;  // the stretch ends above this
  };
  std::vector<Stretch> stretches;
  bool stopped = false;         // options.progress returned false: nothing more is traced
  int general_index = 0;        // general families listed (for their labels)
  bool quiet = false;           // a repetition traced for its branch points only: no inadmissible stretches
  int regained = 0;             // families started by follow_stretch (for their labels)
  static constexpr long kMaxStretches = 10000;  // a bound on the work of through_inadmissible

  int current_k = 1, k_last = 1;  // for the progress reports
  long steps = 0;
  std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();

  bool keep_going() {
    if (stopped || !options.progress) return !stopped;
    ModesProgress p;
    p.k = current_k;
    p.k_last = k_last;
    p.families = static_cast<long>(result.families.size());
    p.steps = ++steps;
    p.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    if (!options.progress(p)) stopped = true;
    return !stopped;
  }

  Eigen::VectorXd scales(const KippShape& shape) const {
    const double bn = model.b().norm(), g0 = model.g0();
    const double wmax = model.omega().maxCoeff(), wmin = model.omega().minCoeff();
    Eigen::VectorXd d(shape.unknowns());
    d.head(shape.n).setConstant(g0 / bn);
    if (shape.symmetry == KippSymmetry::ImpactImpact) d(shape.n) = g0 * wmax / bn;
    if (shape.symmetry == KippSymmetry::None) d.segment(shape.n, shape.n).setConstant(g0 * wmax / bn);
    d.tail(shape.m() + 1).setConstant(2.0 * std::acos(-1.0) / wmin);
    return d;
  }

  void linearize(const KippShape& shape, const Eigen::VectorXd& z, Eigen::VectorXd& F, Eigen::MatrixXd& J) const {
    kipp_residual(model, shape, (D.array() * z.array()).matrix(), F, J);
    J = J * D.asDiagonal();
  }

  Eigen::MatrixXd jacobian(const KippShape& shape, const Eigen::VectorXd& z) const {
    Eigen::VectorXd F;
    Eigen::MatrixXd J;
    linearize(shape, z, F, J);
    return J;
  }

  bool correct(const KippShape& shape, const Eigen::VectorXd& z_pred, const Eigen::VectorXd& tau, Eigen::VectorXd& z) {
    ++result.corrector_solves;
    cont::CorrectorOptions co;
    co.step_tol = 1e-11;
    co.max_iterations = 15;
    co.full_pivoting = false;  // the bordered system is n + m + 1 square: blocked partial pivoting (corrector.hpp)
    const auto lin = [&](const Eigen::VectorXd& zz, Eigen::VectorXd& F, Eigen::MatrixXd& J) {
      linearize(shape, zz, F, J);
    };
    const cont::CorrectorResult r = cont::correct_pseudo_arclength(lin, z_pred, tau, z, co);
    if (!r.converged) return false;
    // the durations must stay positive: a flight of zero length is two impacts merging
    for (int j = shape.first_tau(); j < shape.unknowns(); ++j)
      if (!(z(j) > 0)) return false;
    return true;
  }

  // One predictor-corrector step from z along tau: h is halved until the corrector converges and the tangent turns
  // by at most turn_limit (rad). zn, its tangent tn (oriented along tau) and the Jacobian there; false when h fell
  // below min_step.
  bool advance(const KippShape& shape, const Eigen::VectorXd& z, const Eigen::VectorXd& tau, double turn_limit,
               double& h, Eigen::VectorXd& zn, Eigen::VectorXd& tn, Eigen::MatrixXd& Jn) {
    for (; h >= options.min_step; h *= 0.5) {
      if (!correct(shape, z + h * tau, tau, zn)) continue;
      Jn = jacobian(shape, zn);
      tn = cont::curve_tangent(Jn, tau);
      if (tn.allFinite() && std::acos(std::clamp(tn.dot(tau), -1.0, 1.0)) <= turn_limit) return true;
    }
    return false;
  }

  // The inadmissible stretch beyond z (unscaled y = D z) in the direction tau is followed later
  // (ModesOptions::through_inadmissible; follow_stretch).
  void follow_later(const KippShape& shape, const Eigen::VectorXd& z, const Eigen::VectorXd& tau, double h,
                    const ModeFamily& f) {
    // the general families (KippSymmetry::None) are followed from branch points only (general_search)
    if (!options.through_inadmissible || quiet || shape.symmetry == KippSymmetry::None) return;
    std::ostringstream from;
    from << "k" << shape.k << " " << to_string(shape.symmetry) << " mode " << f.mode;
    const Eigen::VectorXd y = (D.array() * z.array()).matrix();
    const double e = kipp_orbit(model, shape, y).energy;
    stretches.push_back({shape, y, tau, h, f.mode, from.str(), kInadmissibleEnergyFactor * std::max(options.energy_max, e)});
  }

  // A point already listed as an end or a start of a family of the same shape (to 1e-6 in the scaled unknowns).
  bool listed(const KippShape& shape, const Eigen::VectorXd& y) const {
    for (const ModeFamily& f : result.families) {
      if (f.k != shape.k || f.symmetry != shape.symmetry) continue;
      for (const ModeEvent& e : f.events)
        if (e.at.y.size() == y.size() && ((e.at.y - y).array() / D.array()).matrix().norm() <= 1e-6) return true;
    }
    return false;
  }

  // Follows one inadmissible stretch (or one above energy_max) until the curve is admissible again below energy_max;
  // there a family starts (admissibility_regained), unless that point is already listed as a family's end or start
  // (the same family reached from its other side). Ends silently where the step falls below min_step, after
  // max_points steps or above kInadmissibleEnergyFactor * energy_max.
  void follow_stretch(const Stretch& st) {
    if (++result.inadmissible_stretches > kMaxStretches) {
      ++result.stalled_families;  // not followed: the result is incomplete
      return;
    }
    const KippShape& shape = st.shape;
    current_k = shape.k;
    D = scales(shape);
    Eigen::VectorXd z = (st.y.array() / D.array()).matrix(), tau = st.tau, zn, tn;
    Eigen::MatrixXd Jn;
    double h = std::min(options.max_step, st.h);
    // >= 0: listed (admissible, energy <= energy_max); the orbit's margin and relative energy margin
    const auto inside = [&](const Eigen::VectorXd& zz) {
      const KippOrbit o = kipp_orbit(model, shape, (D.array() * zz.array()).matrix());
      return std::min(o.margin, 1.0 - o.energy / options.energy_max);
    };
    for (int count = 0; count < options.max_points && keep_going(); ++count) {
      if (!advance(shape, z, tau, options.max_turn, h, zn, tn, Jn)) return;
      const KippOrbit o = kipp_orbit(model, shape, (D.array() * zn.array()).matrix());
      if (o.energy > st.energy_limit) return;
      if (std::min(o.margin, 1.0 - o.energy / options.energy_max) >= 0) {
        Eigen::VectorXd ze, za = zn;
        locate(shape, z, tau, h, inside, ze, &za);
        const Eigen::VectorXd ya = (D.array() * za.array()).matrix();
        if (listed(shape, ya)) return;
        ModeFamily g;
        g.k = shape.k;
        g.symmetry = shape.symmetry;
        g.mode = st.mode;
        const ModePoint p0 = tangency(point(shape, za));
        g.points.push_back(p0);
        add_event(g, ModeEventKind::AdmissibilityRegained, p0,
                  std::string(p0.margin <= 1e-6 ? "admissible" : "below energy_max") +
                      " again after a stretch of inadmissible orbits (or above energy_max) from " + st.from);
        const Eigen::VectorXd t0 = cont::curve_tangent(jacobian(shape, za), tau);
        const long stalled = result.stalled_families;
        trace(g, shape, za, t0, nullptr);
        g.multiplicity = g.points.size() > 1 ? g.points[1].multiplicity : p0.multiplicity;
        if (g.multiplicity == 1 && listed_already(g)) {  // reached from another side, or its time reverse
          result.stalled_families = stalled;
          return;
        }
        std::ostringstream label;
        label << st.from << " regained #" << ++regained;
        g.label = label.str();
        result.families.push_back(g);
        note(result.families.size() - 1);
        return;
      }
      z = zn;
      tau = tn;
      h = std::min(options.max_step, 1.5 * h);
    }
  }

  ModePoint point(const KippShape& shape, const Eigen::VectorXd& z) const {
    const Eigen::VectorXd y = (D.array() * z.array()).matrix();
    const KippOrbit o = kipp_orbit(model, shape, y);
    ModePoint p;
    p.energy = o.energy;
    p.period = o.period;
    p.frequency = 2.0 * std::acos(-1.0) / o.period;
    p.impact_times = o.impact_times;
    p.x0 = o.x0;
    p.v0 = o.v0;
    p.margin = o.margin;
    p.admissible = o.margin >= 0.0;
    p.multiplicity = o.multiplicity;
    p.y = y;
    return p;
  }

  // A family's first point, a tangency: its margin within kTangencyMargin of 0 is 0 (admissible); beyond, it is
  // what it is (a start that is no tangency is reported as not admissible, not hidden).
  static ModePoint tangency(ModePoint p) {
    if (std::abs(p.margin) <= kTangencyMargin) p.margin = 0.0;
    p.admissible = p.margin >= 0.0;
    return p;
  }

  bool speed_limited(const KippShape& shape, const Eigen::VectorXd& z) const {
    return kipp_orbit(model, shape, (D.array() * z.array()).matrix()).speed_limited;
  }

  double bordered_det(const KippShape& shape, const Eigen::VectorXd& z, const Eigen::VectorXd& tau) const {
    return bordered_det(jacobian(shape, z), tau);
  }
  static double bordered_det(const Eigen::MatrixXd& J, const Eigen::VectorXd& tau) {
    Eigen::MatrixXd A(J.rows() + 1, J.cols());
    A.topRows(J.rows()) = J;
    A.row(J.rows()) = tau.transpose();
    return A.partialPivLu().determinant();
  }

  // Bisection on s in (0, h) from z0 along tau for the sign change of phi (phi(0) and phi(h) of opposite signs).
  // z_event: the last point found on z0's side (phi of z0's sign), so that the event point keeps its admissibility.
  // z_beyond (optional): the last point found on the other side (none found: unchanged).
  template <class Phi>
  bool locate(const KippShape& shape, const Eigen::VectorXd& z0, const Eigen::VectorXd& tau, double h, Phi&& phi,
              Eigen::VectorXd& z_event, Eigen::VectorXd* z_beyond = nullptr) {
    double lo = 0.0, hi = h;
    const bool sign_lo = phi(z0) >= 0;
    Eigen::VectorXd z = z0;
    z_event = z0;
    for (int it = 0; it < 200 && hi - lo > options.locate_tol; ++it) {
      const double s = 0.5 * (lo + hi);
      // at a branch point the bordered system is singular and the corrector may fail close to it: keep what was found
      if (!correct(shape, z0 + s * tau, tau, z)) return it > 0;
      if ((phi(z) >= 0) == sign_lo) {
        lo = s;
        z_event = z;
      } else {
        hi = s;
        if (z_beyond) *z_beyond = z;
      }
    }
    return true;
  }

  void add_event(ModeFamily& f, ModeEventKind kind, const ModePoint& p, const std::string& detail) {
    f.events.push_back({kind, p, detail});
  }

  // Follows one family from z0 with tangent tau0 (oriented). Branch points of repetitions are reported in `branches`
  // (z, the other branch's direction) when requested.
  void trace(ModeFamily& f, const KippShape& shape, const Eigen::VectorXd& z_start, const Eigen::VectorXd& tau0,
             std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>>* branches) {
    current_k = shape.k;
    Eigen::VectorXd z = z_start, tau = tau0, zn;
    double h = std::min(options.max_step, 0.01);
    // the sign of the bordered determinant is watched only where branch points are looked for (an O(N^3) LU and a
    // Jacobian per point were spent on every family before)
    double det_prev = branches ? bordered_det(shape, z, tau) : 1.0;
    ModePoint prev = f.points.back();
    double travelled = 0.0;  // scaled arclength, for the closed-loop test
    for (int count = 1;; ++count) {
      if (!keep_going()) {
        // not a stall: the status is incomplete through `interrupted` (it read "stalled"; found by an attack)
        add_event(f, ModeEventKind::Interrupted, prev, "interrupted by the progress callback (Ctrl-C)");
        return;
      }
      if (count >= options.max_points) {
        add_event(f, ModeEventKind::Stalled, prev, "max_points reached");
        ++result.stalled_families;
        return;
      }
      Eigen::VectorXd tn;
      Eigen::MatrixXd Jn;
      // the first step off a branch point may turn more: the bordered Jacobian is singular at the start
      if (!advance(shape, z, tau, count == 1 ? 1.2 : options.max_turn, h, zn, tn, Jn)) {
        add_event(f, ModeEventKind::Stalled, prev, "the step fell below min_step");
        ++result.stalled_families;
        return;
      }
      ModePoint p = point(shape, zn);
      bool energy_first = false;
      // admissibility lost between z and zn (prev admissible, or the start at margin 0)
      if (p.margin < 0) {
        Eigen::VectorXd ze;
        const auto margin = [&](const Eigen::VectorXd& zz) {
          return kipp_orbit(model, shape, (D.array() * zz.array()).matrix()).margin;
        };
        locate(shape, z, tau, h, margin, ze);
        const ModePoint pe = point(shape, ze);  // the last admissible point, to locate_tol
        // energy_max reached first within the step: the energy_max event below ends the family (an attack found
        // families ending past energy_max at an admissibility event, E 10.06 for energy_max 10)
        energy_first = pe.energy > options.energy_max;
        if (!energy_first) {
          const bool by_speed = speed_limited(shape, zn);
          f.points.push_back(pe);
          add_event(f, by_speed ? ModeEventKind::ImpactGrazing : ModeEventKind::FlightGrazing, pe,
                    by_speed ? "an impact's incoming speed reaches 0" : "the gap touches 0 inside a flight");
          follow_later(shape, zn, tn, h, f);
          return;
        }
      }
      if (p.energy > options.energy_max || energy_first) {
        Eigen::VectorXd ze;
        const auto de = [&](const Eigen::VectorXd& zz) { return point(shape, zz).energy - options.energy_max; };
        locate(shape, z, tau, h, de, ze);
        const ModePoint pe = point(shape, ze);
        f.points.push_back(pe);
        add_event(f, ModeEventKind::EnergyMax, pe, "energy_max reached");
        return;
      }
      const double det = branches ? bordered_det(Jn, tn) : 1.0;
      if (branches && std::isfinite(det) && std::isfinite(det_prev) && (det > 0) != (det_prev > 0) && det != 0 &&
          det_prev != 0) {
        Eigen::VectorXd zb;
        const auto sd = [&](const Eigen::VectorXd& zz) {
          return bordered_det(shape, zz, cont::curve_tangent(jacobian(shape, zz), tau));
        };
        if (locate(shape, z, tau, h, sd, zb)) {
          // the other branch: the kernel of J at zb orthogonal to this branch's tangent
          const Eigen::MatrixXd J = jacobian(shape, zb);
          const Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeFullV);
          const Eigen::MatrixXd V = svd.matrixV().rightCols(2);
          const Eigen::VectorXd tb = tau;  // this branch's direction (J is singular at zb: its kernel is 2-D)
          Eigen::VectorXd other = V.col(0) - V.col(0).dot(tb) * tb;
          const Eigen::VectorXd other1 = V.col(1) - V.col(1).dot(tb) * tb;
          if (other1.norm() > other.norm()) other = other1;
          if (other.norm() > 1e-3) {
            branches->push_back({zb, other.normalized()});
            const ModePoint pb = point(shape, zb);
            add_event(f, ModeEventKind::BranchPoint, pb, "a family of genuine k-IPPs branches off here");
          }
        }
      }
      det_prev = det;
      travelled += (zn - z).norm();
      // Back at the first point, in the direction it left it (the criterion of the SPP branches' closed_loop,
      // continuation.cpp): the first point lies between z and zn along the curve, zn is within a step of it. A closed
      // loop was traced until max_points and reported stalled (chain5 --k 1..5: 3 families, 12 000 points).
      if (travelled > 4.0 * h && (zn - z_start).norm() <= std::max(h, (zn - z).norm()) && tn.dot(tau0) > 0.9 &&
          (z_start - z).dot(tau) >= 0 && (z_start - zn).dot(tn) <= 0) {
        add_event(f, ModeEventKind::ClosedLoop, f.points.front(), "back at the first point: a closed loop");
        return;
      }
      f.points.push_back(p);
      prev = p;
      z = zn;
      tau = tn;
      h = std::min(options.max_step, 1.5 * h);
    }
  }

  Eigen::VectorXd energy_gradient(const KippShape& shape, const Eigen::VectorXd& z) const {
    const Eigen::VectorXd y = (D.array() * z.array()).matrix();
    Eigen::VectorXd g = Eigen::VectorXd::Zero(shape.unknowns());
    g.head(shape.n) = (model.omega().array().square() * y.head(shape.n).array()).matrix();
    if (shape.symmetry == KippSymmetry::ImpactImpact) g(shape.n) = y(shape.n);
    if (shape.symmetry == KippSymmetry::None) g.segment(shape.n, shape.n) = y.segment(shape.n, shape.n);
    return (g.array() * D.array()).matrix();  // dE/dz
  }

  // Whether the orbits just beyond the start z0 in the direction tau are admissible: a step of 1e-3 (scaled
  // arclength), then, where that one is not, 1e-4 .. 1e-6 with a margin above rounding (kTangencyMargin). An
  // admissible stretch next to a start can be narrower than 1e-3: a random 4-dof system (`spp generate random --n 4
  // --seed 3`) has one of width 1.4e-3 in T beside a grazing orbit at period multiples (the explicit scan,
  // tests/crosscheck/modes_one_ipp_scan.py, listed it; the first step jumped over it).
  bool admissible_side(const KippShape& shape, const Eigen::VectorXd& z0, const Eigen::VectorXd& tau) {
    Eigen::VectorXd z1;
    for (double h = std::min(options.max_step, 1e-3); h >= 0.99e-6; h *= 0.1) {
      if (!correct(shape, z0 + h * tau, tau, z1)) continue;
      const double margin = point(shape, z1).margin;
      if (h >= std::min(options.max_step, 1e-3) ? margin >= 0 : margin > kTangencyMargin) return true;
    }
    return false;
  }

  // A family from a start z with a first tangent: tries `dir`, then -dir, keeping the first with an admissible step.
  bool start_family(ModeFamily& f, const KippShape& shape, const Eigen::VectorXd& z0, const Eigen::VectorXd& dir,
                    std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>>* branches) {
    for (double sign : {1.0, -1.0}) {
      const Eigen::VectorXd tau = sign * dir;
      if (!admissible_side(shape, z0, tau)) continue;
      trace(f, shape, z0, tau, branches);
      return true;
    }
    add_event(f, ModeEventKind::NoAdmissibleSide, f.points.back(), "no admissible orbit on either side of the start");
    for (double sign : {1.0, -1.0}) follow_later(shape, z0, sign * dir, std::min(options.max_step, 1e-3), f);
    return false;
  }

  void note(size_t index) {
    const ModeFamily& f = result.families[index];
    if (!f.events.empty() && f.events.back().kind == ModeEventKind::FlightGrazing && wanted.count(f.k + 2))
      pending.push_back(index);
  }

  // The family with k + 2 impacts that continues family `index` past its flight_grazing end.
  void follow_grazing(size_t index) {
    const ModeFamily src = result.families[index];  // a copy: result.families grows below
    if (src.symmetry == KippSymmetry::None) return;  // its flights have no mirror: not split in pairs
    const KippShape shape{src.k, src.symmetry, model.coupled_modes()};
    const Eigen::VectorXd& y = src.points.back().y;
    const KippOrbit o = kipp_orbit(model, shape, y);
    const int j = o.min_gap_flight, t0 = shape.first_tau(), m = shape.m();
    if (j < 0) return;
    const double tau = y(t0 + j), tg = o.min_gap_time;
    const bool turning_start = j == 0 && shape.symmetry != KippSymmetry::ImpactImpact;
    const bool turning_end = j == m && shape.symmetry == KippSymmetry::FlightFlight;
    if ((turning_start && tg < 1e-6 * tau) || (turning_end && tau - tg < 1e-6 * tau)) return;  // at a symmetric point
    const KippShape next{src.k + 2, src.symmetry, model.coupled_modes()};
    Eigen::VectorXd y2(next.unknowns());
    y2.head(t0) = y.head(t0);
    for (int i = 0; i < j; ++i) y2(t0 + i) = y(t0 + i);
    y2(t0 + j) = tg;
    y2(t0 + j + 1) = tau - tg;
    for (int i = j + 1; i <= m; ++i) y2(t0 + i + 1) = y(t0 + i);
    D = scales(next);
    Eigen::VectorXd z0 = (y2.array() / D.array()).matrix();
    // The source's grazing end is located to the bisection's tolerance, so the split flight's new impact has a gap
    // of ~1e-6 g0: the start is corrected onto the k + 2 family (Newton across the curve) before it is recorded.
    Eigen::VectorXd F;
    Eigen::MatrixXd J;
    linearize(next, z0, F, J);
    Eigen::VectorXd z0c;
    if (correct(next, z0, cont::curve_tangent(J, energy_gradient(next, z0)), z0c)) z0 = z0c;
    ModeFamily g;
    g.k = next.k;
    g.symmetry = next.symmetry;
    g.mode = src.mode;
    const ModePoint p0 = tangency(point(next, z0));  // the tangency counted twice: zero speed, gap >= 0
    g.points.push_back(p0);
    add_event(g, ModeEventKind::GrazingContinuation, p0, "flight_grazing end of " + src.label);
    linearize(next, z0, F, J);
    const Eigen::VectorXd dir = cont::curve_tangent(J, energy_gradient(next, z0));
    const long stalled = result.stalled_families;
    // no admissible side: the grazing end itself, no family with k + 2 impacts (such one-point families were listed
    // and counted as genuine); its inadmissible stretches are followed (start_family)
    if (!start_family(g, next, z0, dir, nullptr)) return;
    g.multiplicity = g.points.size() > 1 ? g.points[1].multiplicity : p0.multiplicity;
    if (g.multiplicity == 1 && listed_already(g)) {  // the same family reached from another grazing end
      result.stalled_families = stalled;
      return;
    }
    std::ostringstream label;  // not string + string: GCC 12 reports a false -Wrestrict there
    // the source by its label: its index in the list changes with the k requested (the k not requested are dropped)
    label << "k" << next.k << " " << to_string(next.symmetry) << " past grazing of " << src.label;
    g.label = label.str();
    result.families.push_back(g);
    note(result.families.size() - 1);
  }

  // The 1-IPP families through the grazing orbit of coupled mode `coupled` seen with period `multiple` times its own
  // (multiple >= 2): both sides, each a family where its first step is admissible.
  void run_multiple_start(int coupled, int multiple) {
    const KippShape shape{1, KippSymmetry::FlightImpact, model.coupled_modes()};
    const int mode = model.linear_mode(coupled);
    D = scales(shape);
    const Eigen::VectorXd z0 = (grazing_start_multiple(model, shape, coupled, multiple).array() / D.array()).matrix();
    const ModePoint p0 = tangency(point(shape, z0));
    const Eigen::VectorXd dir = cont::curve_tangent(jacobian(shape, z0), energy_gradient(shape, z0));
    if (p0.energy >= options.energy_max) {  // its family may come below energy_max on either side
      ModeFamily f;
      f.mode = mode;
      for (double sign : {1.0, -1.0}) follow_later(shape, z0, sign * dir, std::min(options.max_step, 1e-3), f);
      return;
    }
    for (double sign : {1.0, -1.0}) {
      if (!keep_going()) return;
      const Eigen::VectorXd tau = sign * dir;
      ModeFamily f;
      f.mode = mode;
      if (!admissible_side(shape, z0, tau)) {
        follow_later(shape, z0, tau, std::min(options.max_step, 1e-3), f);
        continue;
      }
      f.k = 1;
      f.symmetry = shape.symmetry;
      f.mode = mode;
      f.points.push_back(p0);
      std::ostringstream detail;
      detail << "linear mode " << mode << " touching the obstacle, once every " << multiple << " periods an impact";
      add_event(f, ModeEventKind::GrazingStart, p0, detail.str());
      trace(f, shape, z0, tau, nullptr);
      f.multiplicity = 1;
      std::ostringstream label;
      label << "k1 flight-impact mode " << mode << " x" << multiple << " period" << (sign > 0 ? "+" : "-");
      f.label = label.str();
      result.families.push_back(f);
      note(result.families.size() - 1);
    }
  }

  // The families from the grazing start of coupled mode `coupled` (0-based index into model.omega()).
  void run_start(const KippShape& shape, int coupled) {
    const int mode = model.linear_mode(coupled);  // 1-based, of all n modes
    D = scales(shape);
    const Eigen::VectorXd y0 = grazing_start(model, shape, coupled);
    Eigen::VectorXd z0 = (y0.array() / D.array()).matrix();
    ModeFamily f;
    f.k = shape.k;
    f.symmetry = shape.symmetry;
    f.mode = mode;
    // the linear mode touching the obstacle: gap >= 0, impact speeds 0
    const ModePoint p0 = tangency(point(shape, z0));
    if (p0.energy >= options.energy_max) {  // the family starts above the requested energies (it may come below)
      const Eigen::VectorXd tau = cont::curve_tangent(jacobian(shape, z0), energy_gradient(shape, z0));
      for (double sign : {1.0, -1.0}) follow_later(shape, z0, sign * tau, std::min(options.max_step, 1e-3), f);
      return;
    }
    f.points.push_back(p0);
    add_event(f, ModeEventKind::GrazingStart, p0, "linear mode " + std::to_string(mode) + " touching the obstacle");
    const Eigen::VectorXd tau = cont::curve_tangent(jacobian(shape, z0), energy_gradient(shape, z0));
    std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>> branches;
    start_family(f, shape, z0, tau, options.branch_points && shape.k > 1 ? &branches : nullptr);
    f.multiplicity = f.points.size() > 1 ? f.points[1].multiplicity : p0.multiplicity;
    std::ostringstream label;
    label << "k" << shape.k << " " << to_string(shape.symmetry) << " mode " << mode;
    if (f.multiplicity > 1) label << " (" << shape.k / f.multiplicity << "-IPP x" << f.multiplicity << ")";
    f.label = label.str();
    result.families.push_back(f);
    note(result.families.size() - 1);
    int index = 0;
    for (const auto& [zb, dir] : branches) {
      for (double sign : {1.0, -1.0}) {
        ModeFamily g;
        g.k = shape.k;
        g.symmetry = shape.symmetry;
        g.mode = mode;
        ModePoint pb = point(shape, zb);
        g.points.push_back(pb);
        add_event(g, ModeEventKind::BranchStart, pb, "branch point on " + f.label);
        const Eigen::VectorXd tau1 = sign * dir;
        if (!admissible_side(shape, zb, tau1)) {
          // not listed: a point of the repetition, no family (such one-point "families" were counted as genuine)
          follow_later(shape, zb, tau1, 1e-3, g);
          continue;
        }
        const long stalled = result.stalled_families;
        trace(g, shape, zb, tau1, nullptr);
        // a branch that stalled at its first step is only the branch point, a point of the repetition: counted with
        // it, not as a genuine family (it was, with the multiplicity computed at that point)
        g.multiplicity = g.points.size() > 1 ? g.points.back().multiplicity : f.multiplicity;
        // the same family from the branch point of its other symmetric point (a phase shift), or its time reverse
        if (g.multiplicity == 1 && listed_already(g)) {
          result.stalled_families = stalled;  // not listed: its stall (if any) is no listed family's
          continue;
        }
        std::ostringstream gl;
        gl << "k" << shape.k << " " << to_string(shape.symmetry) << " branch " << ++index << (sign > 0 ? "+" : "-")
           << " of mode " << mode;
        g.label = gl.str();
        result.families.push_back(g);
        note(result.families.size() - 1);
      }
    }
  }
  // ---- General (non-symmetric) k-IPPs: branch points of repetitions and symmetry breaking (docs/modes.md §3) ----

  // The flight durations of a point (k, from its impact times and period).
  static std::vector<double> flights(const ModePoint& p) {
    std::vector<double> d;
    for (size_t i = 0; i < p.impact_times.size(); ++i)
      d.push_back((i + 1 < p.impact_times.size() ? p.impact_times[i + 1] : p.period) - p.impact_times[i]);
    return d;
  }

  // One orbit's coordinates for comparing orbits up to phase shift and time reversal: (energy, period, the k flight
  // durations) of p, scaled by p's energy and period (a point of a family's polyline of such vectors is compared
  // with these). The time reverse of an orbit is an orbit with the same energy and period and its flights in reverse
  // order; a phase shift (another impact taken as the first) shifts them cyclically: each of the 2k forms is one
  // entry (issue 15: chain5 listed families that are the time reverses of others, and flight-flight families twice,
  // from the branch points of their two symmetric points).
  static std::vector<Eigen::VectorXd> orbit_forms(const ModePoint& p) {
    const std::vector<double> d = flights(p);
    const size_t k = d.size();
    std::vector<Eigen::VectorXd> forms;
    for (int reverse = 0; reverse < 2; ++reverse)
      for (size_t shift = 0; shift < k; ++shift) {
        Eigen::VectorXd v(static_cast<Eigen::Index>(k) + 2);
        v(0) = 1.0;
        v(1) = 1.0;
        for (size_t i = 0; i < k; ++i)
          v(static_cast<Eigen::Index>(i) + 2) = d[reverse ? (2 * k - 1 - i - shift) % k : (i + shift) % k] / p.period;
        forms.push_back(v);
      }
    return forms;
  }

  // Point a of a family in the coordinates of orbit_forms scaled by p's energy and period.
  static Eigen::VectorXd scaled_like(const ModePoint& a, const ModePoint& p) {
    const std::vector<double> d = flights(a);
    Eigen::VectorXd v(static_cast<Eigen::Index>(d.size()) + 2);
    v(0) = a.energy / p.energy;
    v(1) = a.period / p.period;
    for (size_t i = 0; i < d.size(); ++i) v(static_cast<Eigen::Index>(i) + 2) = d[i] / p.period;
    return v;
  }

  // Whether orbit p (k impacts) lies on a family already listed with k impacts, up to phase shift and time reversal:
  // within 1e-3 (largest component, relative to p's energy and period) of a segment of that family's polyline in the
  // coordinates of orbit_forms. Before, p's energy was interpolated on each segment, which failed on families along
  // which the energy hardly changes (chain5: a family and its time reverse at E 0.95642, both listed).
  bool on_listed_family(const ModePoint& p, int k) const {
    constexpr double kSameOrbit = 1e-3;
    if (!(p.energy > 0) || !(p.period > 0)) return false;
    const std::vector<Eigen::VectorXd> forms = orbit_forms(p);
    for (const ModeFamily& f : result.families) {
      if (f.k != k) continue;
      for (size_t i = 0; i + 1 < f.points.size(); ++i) {
        const ModePoint &a = f.points[i], &c = f.points[i + 1];
        if (a.impact_times.size() != p.impact_times.size() || c.impact_times.size() != p.impact_times.size()) continue;
        const Eigen::VectorXd va = scaled_like(a, p), d = scaled_like(c, p) - va;
        const double dd = d.squaredNorm();
        for (const Eigen::VectorXd& v : forms) {
          const double s = dd > 0 ? std::clamp((v - va).dot(d) / dd, 0.0, 1.0) : 0.0;
          if ((v - va - s * d).lpNorm<Eigen::Infinity>() <= kSameOrbit) return true;
        }
      }
    }
    return false;
  }

  // Whether family g (k impacts, at least 3 points) is one listed already, up to phase shift and time reversal, or a
  // union of listed pieces: its interior points sampled at 1/6 .. 5/6 of its points all lie on listed families
  // (on_listed_family). One sample is not enough: a family that crosses a listed one (a branch point) shares a point.
  bool listed_already(const ModeFamily& g) const {
    const size_t n = g.points.size();
    if (n < 3) return false;
    for (size_t j = 1; j <= 5; ++j) {
      const size_t i = std::clamp<size_t>((j * (n - 1) + 3) / 6, 1, n - 2);
      if (!on_listed_family(g.points[i], g.k)) return false;
    }
    return true;
  }

  // ---- Seeds from the plane of the flight durations (ModesOptions::seed_period_max) ----

  // det [A c] at durations taus (a symmetric shape with one impact inside the half orbit, m = 1): given the
  // durations the equations are affine in the state s (the unknowns before the durations), F = A s + c, and [A c]
  // is square. The k-IPPs with these durations are the kernel vectors of [A c] with a last entry != 0. Scaled as z.
  double duration_det(const KippShape& shape, const Eigen::VectorXd& taus, Eigen::VectorXd* state) const {
    const int t0 = shape.first_tau();
    Eigen::VectorXd y = Eigen::VectorXd::Zero(shape.unknowns()), F;
    y.tail(taus.size()) = taus;
    Eigen::MatrixXd J;
    kipp_residual(model, shape, y, F, J);
    Eigen::MatrixXd A(F.size(), t0 + 1);
    A.leftCols(t0) = J.leftCols(t0) * D.head(t0).asDiagonal();  // in the scaled state
    A.col(t0) = F;
    if (state) {
      const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
      const Eigen::VectorXd v = svd.matrixV().col(t0);
      *state = std::abs(v(t0)) > 1e-12 * v.norm() ? Eigen::VectorXd(v.head(t0) / v(t0)) : Eigen::VectorXd();
    }
    return A.partialPivLu().determinant();
  }

  // Families of k-IPPs seeded from the plane of their two durations (docs/modes.md §3, "Seeds"): the symmetric shapes
  // with one impact inside the half orbit (k = 2 flight-flight, k = 3 flight-impact, k = 4 impact-impact). For each
  // the k-IPPs of period <= seed_period_max are where det [A c]
  // (duration_det) vanishes in the triangle of durations that period allows; each edge of a grid on it (kSeedGrid
  // cells a side) whose ends differ in sign is bisected, the point corrected onto its curve and, when it is an
  // admissible genuine k-IPP below energy_max on no family listed, its family is traced both ways from it (one
  // family). A curve that crosses no grid edge (a loop inside a cell) is not seen.
  void duration_seeds(const KippShape& shape) {
    constexpr int kSeedGrid = 200;
    const bool none = shape.symmetry == KippSymmetry::None;
    // the sum of the two durations: the period (none) or half of it (the half orbit)
    const double L = none ? options.seed_period_max : 0.5 * options.seed_period_max;
    const double h = L / kSeedGrid;
    std::vector<double> det((kSeedGrid + 1) * (kSeedGrid + 1), 0.0);
    const auto at = [&](int i, int j) -> double& { return det[static_cast<size_t>(i * (kSeedGrid + 1) + j)]; };
    const auto taus = [&](double a, double b) {
      Eigen::VectorXd t(2);
      t << a, b;
      return t;
    };
    D = scales(shape);
    for (int i = 1; i < kSeedGrid; ++i)
      for (int j = 1; i + j <= kSeedGrid; ++j) at(i, j) = duration_det(shape, taus(i * h, j * h), nullptr);
    int seeds = 0;
    for (int i = 1; i < kSeedGrid && keep_going(); ++i)
      for (int j = 1; i + j <= kSeedGrid && !stopped; ++j)
        for (int dir = 0; dir < 2; ++dir) {
          const int i2 = i + (dir == 0), j2 = j + (dir == 1);
          if (i2 + j2 > kSeedGrid || i2 >= kSeedGrid) continue;
          const double d1 = at(i, j), d2 = at(i2, j2);
          if (!(d1 * d2 < 0)) continue;
          // bisection along the edge
          double lo = 0.0, hi = 1.0;
          for (int it = 0; it < 60; ++it) {
            const double s = 0.5 * (lo + hi);
            const double d = duration_det(shape, taus((i + s * (i2 - i)) * h, (j + s * (j2 - j)) * h), nullptr);
            ((d > 0) == (d1 > 0) ? lo : hi) = s;
          }
          const double s = 0.5 * (lo + hi);
          const Eigen::VectorXd t = taus((i + s * (i2 - i)) * h, (j + s * (j2 - j)) * h);
          Eigen::VectorXd state;
          duration_det(shape, t, &state);
          if (state.size() == 0 || !state.allFinite()) continue;
          Eigen::VectorXd z(shape.unknowns());
          z.head(shape.first_tau()) = state;
          z.tail(2) = (t.array() / D.tail(2).array()).matrix();
          seed_family(shape, z, ++seeds);
        }
  }

  // The family through seed z (scaled unknowns, F(z) ~ 0) of duration_seeds, when its point is new (see there).
  void seed_family(const KippShape& shape, const Eigen::VectorXd& z_seed, int seed) {
    Eigen::VectorXd z;
    const Eigen::VectorXd t0 = cont::curve_tangent(jacobian(shape, z_seed), energy_gradient(shape, z_seed));
    if (!t0.allFinite() || !correct(shape, z_seed, t0, z)) return;
    const ModePoint p = point(shape, z);
    if (p.multiplicity != 1 || !(p.margin > 0) || p.energy > options.energy_max || on_listed_family(p, shape.k)) return;
    const Eigen::VectorXd dir = cont::curve_tangent(jacobian(shape, z), t0);
    if (!dir.allFinite()) return;
    const long stalled = result.stalled_families;
    ModeFamily back;  // the side traced first, then reversed
    back.points.push_back(p);
    trace(back, shape, z, -dir, nullptr);
    ModeFamily g;
    g.k = shape.k;
    g.symmetry = shape.symmetry;
    g.multiplicity = 1;
    g.points.assign(back.points.rbegin(), back.points.rend());
    g.events = back.events;  // the end of that side, now the family's first point
    add_event(g, ModeEventKind::Seeded, p, "seeded from the plane of the flight durations");
    if (back.events.empty() || back.events.back().kind != ModeEventKind::ClosedLoop) trace(g, shape, z, dir, nullptr);
    if (g.points.size() < 3 || listed_already(g)) {
      result.stalled_families = stalled;
      return;
    }
    std::ostringstream label;
    label << "k" << shape.k << " " << to_string(shape.symmetry) << " seeded " << seed;
    g.label = label.str();
    result.families.push_back(g);
  }

  // Point p of a family (its orbit has p.impact_times.size() / multiplicity impacts) repeated to k impacts, as the
  // unknowns of the general equations (KippSymmetry::None). Empty when k is no multiple of its impacts.
  Eigen::VectorXd general_unknowns(const ModePoint& p, int k) const {
    const int kp = static_cast<int>(p.impact_times.size()) / std::max(1, p.multiplicity);
    if (kp < 1 || k % kp != 0) return {};
    const int n = model.coupled_modes();
    const Eigen::MatrixXd PtM = model.Phi().transpose() * model.system().M();
    const std::vector<double> d = flights(p);
    Eigen::VectorXd y(2 * n + k);
    y.head(n) = PtM * p.x0;
    y.segment(n, n) = PtM * p.v0;
    for (int i = 0; i < k; ++i) y(2 * n + i) = d[static_cast<size_t>(i % kp)];
    return y;
  }

  // From each branch point (zb, the other branch's direction) of family f, both directions of the other branch, each
  // a family of genuine k-IPPs with no symmetry assumed where its first step is admissible, unless it lies on a
  // family listed already (a symmetric family, or the same general family reached from another branch point).
  void branch_families(const KippShape& shape, const ModeFamily& f,
                       const std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>>& branches) {
    const int k = shape.k;
    for (const auto& [zb, bdir] : branches) {
      for (double sign : {1.0, -1.0}) {
        if (!keep_going()) return;
        D = scales(shape);
        const Eigen::VectorXd tau1 = sign * bdir;
        if (!admissible_side(shape, zb, tau1)) continue;
        ModeFamily g;
        g.k = k;
        g.symmetry = shape.symmetry;
        g.mode = f.mode;
        const ModePoint pb = point(shape, zb);
        g.points.push_back(pb);
        add_event(g, ModeEventKind::BranchStart, pb,
                  "branch point on " + f.label +
                      (shape.symmetry == KippSymmetry::None ? " (no symmetry assumed)" : " repeated"));
        const long stalled = result.stalled_families;
        trace(g, shape, zb, tau1, nullptr);
        bool genuine = g.points.size() >= 3;  // multiplicity 1 past the start
        for (size_t i = 1; i < g.points.size(); ++i) genuine = genuine && g.points[i].multiplicity == 1;
        if (!genuine || on_listed_family(g.points[g.points.size() / 3], k) ||
            on_listed_family(g.points[2 * g.points.size() / 3], k) || listed_already(g)) {
          result.stalled_families = stalled;  // not listed: its stall (if any) is no listed family's
          continue;
        }
        g.multiplicity = 1;
        std::ostringstream label;
        label << "k" << k << " " << to_string(shape.symmetry) << " branch " << ++general_index << (sign > 0 ? "+" : "-")
              << " of " << f.label;
        g.label = label.str();
        result.families.push_back(g);
      }
    }
  }

  // The general families with k + 1 impacts that leave a family's flight_grazing end where the gap touches 0 at one
  // time of the period only (a tangency at a symmetric point of a symmetric orbit, which the k + 2 grazing
  // continuation does not follow, or any tangency of a general orbit): the tangency is counted as an impact of zero
  // speed and the family is followed from there on its admissible side, with its branch points (the symmetric
  // families that cross it: on the 2-dof, the k = 2 family of constant period 7.990517 leaves the 1-IPP "mode 2 x2
  // period" family at its grazing end and the (F, F) families of T 7.53..8.06 cross it).
  void general_from_tangencies(int k, const std::vector<ModeFamily>& extra_sources) {
    const KippShape shape{k, KippSymmetry::None, model.coupled_modes()};
    const int n = model.coupled_modes();
    const Eigen::MatrixXd PtM = model.Phi().transpose() * model.system().M();
    const Eigen::VectorXd& b = model.b();
    const Eigen::VectorXd& omega = model.omega();
    const double g0 = model.g0();
    const size_t count = result.families.size();
    for (size_t fi = 0; fi < count + extra_sources.size(); ++fi) {
      // a copy: result.families grows below
      const ModeFamily src = fi < count ? result.families[fi] : extra_sources[fi - count];
      if (src.k + 1 != k || src.events.empty() || src.events.back().kind != ModeEventKind::FlightGrazing) continue;
      if (!keep_going()) return;
      const ModePoint& p = src.points.back();
      const std::vector<double> d = flights(p);
      // the interior minima of the gap over the period, sampled and refined (golden section)
      std::vector<std::pair<int, double>> touches;  // (flight, time from its start)
      Eigen::VectorXd q = PtM * p.x0, v = PtM * p.v0;
      for (size_t j = 0; j < d.size(); ++j) {
        const detail::CosineSum g = detail::CosineSum::from_cos_sin(
            g0, (b.array() * q.array()).matrix(), (b.array() * v.array() / omega.array()).matrix(), omega);
        constexpr int kSamples = 2000;
        std::vector<double> gs(kSamples + 1);
        for (int i = 0; i <= kSamples; ++i) gs[static_cast<size_t>(i)] = g.value(d[j] * i / kSamples);
        for (int i = 1; i < kSamples; ++i) {
          if (!(gs[static_cast<size_t>(i)] <= gs[static_cast<size_t>(i - 1)] &&
                gs[static_cast<size_t>(i)] <= gs[static_cast<size_t>(i + 1)]))
            continue;
          double lo = d[j] * (i - 1) / kSamples, hi = d[j] * (i + 1) / kSamples;
          for (int it = 0; it < 100; ++it) {
            const double a = lo + 0.382 * (hi - lo), c = lo + 0.618 * (hi - lo);
            if (g.value(a) < g.value(c))
              hi = c;
            else
              lo = a;
          }
          const double t = 0.5 * (lo + hi);
          if (std::abs(g.value(t)) <= 1e-5 * g0) touches.push_back({static_cast<int>(j), t});
        }
        // the exact flight to the next impact, then the reflection
        const Eigen::ArrayXd c = (omega.array() * d[j]).cos(), sn = (omega.array() * d[j]).sin();
        const Eigen::VectorXd q1 = (c * q.array() + sn / omega.array() * v.array()).matrix();
        v = (-omega.array() * sn * q.array() + c * v.array()).matrix();
        q = q1;
        v -= (2.0 * b.dot(v) / b.squaredNorm()) * b;
      }
      if (touches.empty() || touches.size() > 2) continue;
      for (const auto& [tj, tt] : touches) {
        Eigen::VectorXd y(2 * n + k);
        y.head(n) = PtM * p.x0;
        y.segment(n, n) = PtM * p.v0;
        for (int j = 0, c = 0; j < static_cast<int>(d.size()); ++j) {
          if (j == tj) {
            y(2 * n + c++) = tt;
            y(2 * n + c++) = d[static_cast<size_t>(j)] - tt;
          } else {
            y(2 * n + c++) = d[static_cast<size_t>(j)];
          }
        }
        D = scales(shape);
        Eigen::VectorXd z0 = (y.array() / D.array()).matrix(), z0c;
        const Eigen::VectorXd t0 = cont::curve_tangent(jacobian(shape, z0), energy_gradient(shape, z0));
        if (!t0.allFinite() || !correct(shape, z0, t0, z0c)) continue;
        z0 = z0c;
        const Eigen::VectorXd dir = cont::curve_tangent(jacobian(shape, z0), energy_gradient(shape, z0));
        for (double sign : {1.0, -1.0}) {
          if (!admissible_side(shape, z0, sign * dir)) continue;
          ModeFamily g;
          g.k = k;
          g.symmetry = shape.symmetry;
          g.mode = src.mode;
          const ModePoint p0 = tangency(point(shape, z0));
          g.points.push_back(p0);
          add_event(g, ModeEventKind::GrazingContinuation, p0,
                    "flight_grazing end of " + src.label + " (one tangency)");
          std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>> branches;
          const long stalled = result.stalled_families;
          trace(g, shape, z0, sign * dir, &branches);
          if (g.points.size() < 3 || on_listed_family(g.points[g.points.size() / 2], k) || listed_already(g)) {
            result.stalled_families = stalled;  // not listed
            continue;
          }
          g.multiplicity = 1;
          std::ostringstream label;
          label << "k" << k << " none past grazing " << ++general_index << " of " << src.label;
          g.label = label.str();
          result.families.push_back(g);
          branch_families(shape, g, branches);
        }
      }
    }
  }

  // A 1-IPP (flight-impact: y = (q_A, tau)) repeated k times, as the unknowns of symmetric type shape.symmetry
  // (docs/modes.md §3): F at A, the impacts every 2 tau; I at the 1-IPP's impact B (normal velocity).
  Eigen::VectorXd symmetric_repetition(const ModePoint& p, const KippShape& shape) const {
    const int n = model.coupled_modes(), m = shape.m(), t0 = shape.first_tau();
    if (p.y.size() != n + 1 || p.multiplicity != 1) return {};
    const double tau = p.y(n);
    Eigen::VectorXd y(shape.unknowns());
    if (shape.symmetry == KippSymmetry::ImpactImpact) {
      const Eigen::ArrayXd w = model.omega().array();
      const Eigen::VectorXd qA = p.y.head(n);
      y.head(n) = ((w * tau).cos() * qA.array()).matrix();                      // at B
      const Eigen::VectorXd pB = (-w * (w * tau).sin() * qA.array()).matrix();  // arriving, normal
      y(n) = -pB.dot(model.b().normalized());                                   // after the impact: reversed
      for (int j = 0; j <= m; ++j) y(t0 + j) = 2.0 * tau;
    } else {
      y.head(n) = p.y.head(n);
      y(t0) = tau;
      for (int j = 1; j <= m; ++j) y(t0 + j) = 2.0 * tau;
      if (shape.symmetry == KippSymmetry::FlightFlight) y(t0 + m) = tau;
    }
    return y;
  }

  // Every family listed so far whose orbits repeat to k impacts (k / its impacts times, once included: the symmetric
  // genuine k-IPPs, for their symmetry-breaking branch points) is traced in the general equations from its middle
  // point both ways (not listed again: quiet) and its branch points collected; from each, both directions of the
  // other branch are followed as families of genuine k-IPPs with no symmetry assumed, unless they lie on a family
  // already listed (a symmetric family, or the same general family reached from another branch point).
  // symmetry None: as above. A symmetric type: the 1-IPP families listed (or computed as sources) repeated k times,
  // each in the symmetric equations of that type (the grazing starts give these repetitions for the families of the
  // linear modes only: not for those from period multiples or regained after inadmissible orbits), and the
  // symmetric families that branch off them.
  void repetition_search(const KippShape& shape, const std::vector<ModeFamily>& extra_sources) {
    const int k = shape.k;
    std::vector<ModeFamily> sources;
    for (const ModeFamily& f : extra_sources)
      if (shape.symmetry == KippSymmetry::None || (f.k == 1 && f.symmetry == KippSymmetry::FlightImpact))
        sources.push_back(f);
    for (const ModeFamily& f : result.families)
      if (shape.symmetry == KippSymmetry::None ? f.k <= k && (f.symmetry != KippSymmetry::None || f.k < k)
                                               : f.k == 1 && f.symmetry == KippSymmetry::FlightImpact)
        sources.push_back(f);
    for (const ModeFamily& f : sources) {
      if (!keep_going()) return;
      if (f.points.size() < 3) continue;
      const ModePoint& mid = f.points[f.points.size() / 2];
      if (!mid.admissible) continue;
      const Eigen::VectorXd y =
          shape.symmetry == KippSymmetry::None ? general_unknowns(mid, k) : symmetric_repetition(mid, shape);
      if (y.size() == 0) continue;
      D = scales(shape);
      Eigen::VectorXd z0 = (y.array() / D.array()).matrix();
      const Eigen::VectorXd dir = cont::curve_tangent(jacobian(shape, z0), energy_gradient(shape, z0));
      if (!dir.allFinite()) continue;
      std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>> branches;
      const long stalled = result.stalled_families;
      quiet = true;
      for (double sign : {1.0, -1.0}) {
        ModeFamily rep;
        rep.points.push_back(point(shape, z0));
        trace(rep, shape, z0, sign * dir, &branches);
      }
      quiet = false;
      result.stalled_families = stalled;  // the source was listed (and its own ends counted) already
      branch_families(shape, f, branches);
    }
  }
};

}  // namespace

ModesResult nonsmooth_modes(const System& system, const ModesOptions& options) {
  options.validate();
  const auto start = std::chrono::steady_clock::now();
  const KippModel model(system);
  ModesResult result;
  result.linear_frequencies = model.omega_all();
  Tracer tracer{model, options, result, {}, {}, {}, {}, false};
  // Every k from 1 to the largest requested is traced, those not requested are dropped at the end: the families with
  // k impacts are reached from those with fewer (grazing continuations from k - 2 and k - 1 impacts, repetitions of
  // the 1-IPPs), so the list for each k is the same whatever else is requested. Before, --k 2..3 and --k 1..3 listed
  // different 3-IPPs (2-dof: 3 and 6 of the 14 an independent search found; issue 15).
  const int k_last = *std::max_element(options.k_values.begin(), options.k_values.end());
  std::vector<int> ks;
  for (int k = 1; k <= k_last; ++k) ks.push_back(k);
  tracer.k_last = k_last;
  tracer.wanted.insert(ks.begin(), ks.end());
  for (int k : ks)
    for (KippSymmetry s : symmetries_for(k))
      for (int j = 0; j < model.coupled_modes() && tracer.keep_going(); ++j)
        tracer.run_start(KippShape{k, s, model.coupled_modes()}, j);
  for (int multiple = 2; multiple <= options.period_multiples; ++multiple)
    for (int j = 0; j < model.coupled_modes() && tracer.keep_going(); ++j) tracer.run_multiple_start(j, multiple);
  // grazing continuations and inadmissible stretches, each of which may add more of both
  for (size_t i = 0, j = 0; tracer.keep_going();) {
    if (i < tracer.pending.size()) {
      tracer.follow_grazing(tracer.pending[i++]);
    } else if (j < tracer.stretches.size()) {
      const Tracer::Stretch st = tracer.stretches[j++];  // a copy: follow_stretch may add stretches
      tracer.follow_stretch(st);
    } else {
      break;
    }
  }
  // k-IPPs with no symmetry assumed, from the branch points of the repetitions and of the symmetric families, k by k
  // (those with k impacts are sought from families with k impacts or fewer only)
  if (options.branch_points && k_last >= 2 && !tracer.stopped)
    for (int k = 2; k <= k_last; ++k) {
      for (KippSymmetry s : symmetries_for(k)) tracer.repetition_search(KippShape{k, s, model.coupled_modes()}, {});
      tracer.general_from_tangencies(k, {});
      tracer.repetition_search(KippShape{k, KippSymmetry::None, model.coupled_modes()}, {});
    }
  // seeds from the plane of the flight durations, for the shapes where it is square (docs/modes.md §3, "Seeds")
  if (options.seed_period_max > 0)
    for (int k = 2; k <= std::min(k_last, 4) && !tracer.stopped; ++k) {
      for (KippSymmetry s : symmetries_for(k))
        if (interior_impacts(k, s) == 1) tracer.duration_seeds(KippShape{k, s, model.coupled_modes()});
    }
  // the k not requested: traced as sources, not listed (nor their stalls counted)
  const std::set<int> requested(options.k_values.begin(), options.k_values.end());
  const auto unrequested = [&](const ModeFamily& f) { return requested.count(f.k) == 0; };
  for (const ModeFamily& f : result.families)
    if (unrequested(f) && !f.events.empty() && f.events.back().kind == ModeEventKind::Stalled)
      --result.stalled_families;
  result.families.erase(std::remove_if(result.families.begin(), result.families.end(), unrequested),
                        result.families.end());
  result.interrupted = tracer.stopped;
  result.status = result.stalled_families > 0 || result.interrupted ? ModesStatus::Incomplete : ModesStatus::Traced;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace spp::modes
