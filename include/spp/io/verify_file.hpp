#pragma once
// Result files of spp verify: {"checks": [{"t1", "t2", "period", "admissible", "verdict", "consistent",
// "return_errors", "impacts", "contact_onsets", "releases", "periods_followed", "departure"?,
// "perturbed_distances"?, "growth_per_period"?}], "returned", "left", "inconsistent", "all_consistent",
// "admissibility_mismatches", "stability_mismatches", "state_mismatches", "unchecked"} ("status" success,
// inconsistent or interrupted: a stopped run, unchecked > 0 SPPs not checked).
// Cost: linear in the checks x periods written.

#include <string>

#include "spp/simulation/verify.hpp"

namespace spp {

/// indent < 0: one line.
std::string verify_json(const VerifyResult& result, int indent = 2);

}  // namespace spp
