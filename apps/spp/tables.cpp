#include "tables.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace spp::cli {

namespace {
// "yes" / "no" for a decided verdict, "undecided" (|rho - 1| within its rounding bound), "neutral" (decoupled modes
// on the unit circle), "-" when not computed or not admissible (an inadmissible orbit's stability means nothing).
const char* stability_cell(const Solution& x) {
  if (std::isnan(x.floquet.spectral_radius) || !x.admissible()) return "-";
  switch (x.floquet.verdict) {
    case StabilityVerdict::Stable: return "yes";
    case StabilityVerdict::Unstable: return "no";
    case StabilityVerdict::Undecided: return "undecided";
    case StabilityVerdict::Neutral: return "neutral";
    case StabilityVerdict::NotComputed: break;
  }
  return "-";
}

// The spectral radius with enough significant digits to show its distance to 1: 6 digits printed a stable margin of
// 1.8e-9 (rho 0.99999999819, chain5 with k5 = 0.98357796928833) as "1" beside "yes" (issue 14's attack).
std::string radius_text(double rho) {
  std::ostringstream os;
  constexpr int kDigits = 6;
  const double margin = std::abs(1.0 - rho);
  int digits = kDigits;
  if (std::isfinite(rho) && margin > 0.0 && margin < 1e-4)
    digits = std::min(17, 2 + static_cast<int>(std::ceil(-std::log10(margin))));
  os << std::setprecision(digits) << rho;
  return os.str();
}
}  // namespace

std::string result_table(const SolveResult& r) {
  std::ostringstream os;
  os << std::setw(4) << "#" << std::setw(14) << "t1" << std::setw(14) << "t2" << std::setw(14) << "period"
     << std::setw(12) << "admissible" << std::setw(14) << "min_gap" << std::setw(14) << "min_force" << std::setw(12)
     << "rho" << std::setw(11) << "stable"
     << "\n";
  int i = 0;
  for (const Solution& x : r.solutions) {
    os << std::setw(4) << i++ << std::setprecision(8) << std::setw(14) << x.t1() << std::setw(14) << x.t2()
       << std::setw(14) << x.period() << std::setw(12) << (x.admissible() ? "yes" : "no") << std::setprecision(3)
       << std::setw(14) << x.min_gap() << std::setw(14) << x.min_force() << " " << std::setw(11)
       << radius_text(x.floquet.spectral_radius) << std::setw(11) << stability_cell(x);
    for (const auto& f : x.flags) os << "  [" << f << "]";
    os << "\n";
  }
  return os.str();
}

std::string verify_table(const VerifyResult& r) {
  std::ostringstream os;
  const bool perturbed =
      std::any_of(r.checks.begin(), r.checks.end(), [](const SppCheck& c) { return !c.perturbed_distances.empty(); });
  // the periods simulated: the longest list (an SPP that leaves at t = 0 has none: the table read back() of an empty
  // list and crashed, issue 14's attack, spp verify --periods 2 of a random 12-dof system with cond M 4e8)
  size_t periods_max = 0;
  for (const SppCheck& c : r.checks) periods_max = std::max(periods_max, c.return_errors.size());
  const int periods = static_cast<int>(periods_max);
  os << std::setw(4) << "#" << " " << std::setw(13) << "t1" << " " << std::setw(13) << "t2" << std::setw(12) << "admissible"
     << std::setw(14) << "return_err" << std::setw(9) << "verdict";
  if (periods > 1) os << std::setw(10) << "followed" << std::setw(14) << "err_last";
  if (perturbed) os << std::setw(12) << "growth/T";
  os << "  note\n";
  int i = 0;
  for (const SppCheck& c : r.checks) {
    os << std::setw(4) << i++ << " " << std::setprecision(8) << std::setw(13) << c.spp.t1() << " " << std::setw(13)
       << c.spp.t2() << std::setw(12) << (c.spp.admissible() ? "yes" : "no") << std::setprecision(3)
       << std::setw(14);
    if (c.return_errors.empty())
      os << "-";  // no return measured (it left at t = 0): not a return error of 0
    else
      os << c.return_errors[0];
    os << std::setw(9) << to_string(c.verdict);
    if (periods > 1) {
      os << std::setw(10) << (std::to_string(c.periods_followed) + "/" + std::to_string(periods)) << std::setw(14);
      if (c.return_errors.empty())
        os << "-";
      else
        os << c.return_errors.back();
    }
    if (perturbed) {
      if (c.perturbed_distances.empty())
        os << std::setw(12) << "-";
      else
        os << std::setprecision(6) << std::setw(12) << c.growth_per_period;
    }
    // An inconsistency's reason is printed whatever the orbit did: verify stores it in departure, also for an orbit
    // that returns and is followed (a claimed stability or x0, v0 that are not the system's), where the note read
    // "INCONSISTENT with the solver: " and nothing more (found by issue 14's attack).
    // A departure stored for an orbit that returns and is followed to the end (an impact of the perturbed run, ...) is
    // shown too: the JSON had it and the table not (--restitution 0.5, chain SPP #1; issue 14's attack).
    std::string note = c.departure.empty() ? "" : (c.verdict == Verdict::Returns ? "later: " : "") + c.departure;
    if (!c.consistent)
      note = "INCONSISTENT with the solver: " +
             (!c.departure.empty() ? c.departure
                                   : std::string(c.verdict == Verdict::Returns
                                                     ? "the simulation returns, but the solver says not admissible"
                                                     : "the simulation leaves, but the solver says admissible"));
    os << "  " << note << "\n";
  }
  return os.str();
}

std::string continuation_table(const ContinuationResult& r) {
  std::ostringstream os;
  os << std::setw(7) << "branch" << std::setw(22) << "event" << std::setw(15) << r.parameter.name << std::setw(13)
     << "t1" << std::setw(13) << "t2" << std::setw(12) << "margin"
     << "  detail\n";
  for (size_t b = 0; b < r.branches.size(); ++b)
    for (const BranchEvent& e : r.branches[b].events)
      os << std::setw(7) << b << std::setw(22) << to_string(e.kind) << std::setw(15) << std::setprecision(10) << e.at.mu
         << std::setw(13) << std::setprecision(7) << e.at.t1 << std::setw(13) << e.at.t2 << std::setw(12)
         << std::setprecision(3) << e.at.margin << "  " << e.detail << "\n";
  return os.str();
}

std::string zero_gap_table(const ContinuationResult& r) {
  std::ostringstream os;
  os << std::setw(4) << "#" << std::setw(18) << r.parameter.name << std::setw(15) << "t1" << std::setw(15) << "t2"
     << std::setw(15) << "period" << std::setw(12) << "admissible" << std::setw(12) << "margin\n";
  int k = 0;
  for (const BranchPoint& p : gap_closures(r))
    os << std::setw(4) << k++ << std::setw(18) << std::setprecision(12) << p.mu << std::setw(15) << std::setprecision(9)
       << p.t1 << std::setw(15) << p.t2 << std::setw(15) << p.period << std::setw(12) << (p.admissible ? "yes" : "no")
       << std::setw(12) << std::setprecision(3) << p.margin << "\n";
  return os.str();
}

}  // namespace spp::cli
