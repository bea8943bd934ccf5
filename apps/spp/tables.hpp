#pragma once
// Human-readable tables printed by the spp command line (one row per SPP, check or branch event).

#include <string>

#include "spp/continuation/continuation.hpp"
#include "spp/search/solver.hpp"
#include "spp/simulation/verify.hpp"

namespace spp::cli {

/// t1, t2, period, admissible, min gap, min force, flags.
std::string result_table(const SolveResult& result);
/// One row per checked SPP: return error, verdict, periods followed, growth per period, note.
std::string verify_table(const VerifyResult& result);
/// One row per branch event.
std::string continuation_table(const ContinuationResult& result);
/// The zero-gap SPPs (g0 = 0, paper §6.1): parameter value, t1, t2, period, admissible, margin.
std::string zero_gap_table(const ContinuationResult& result);

}  // namespace spp::cli
