#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "io/json.hpp"
#include "paper_examples.hpp"
#include "spp/core/generators.hpp"
#include "spp/io.hpp"
#include "spp/modal/modal.hpp"
#include "spp/orbit/orbit.hpp"
#include "spp/search/solver.hpp"

using namespace spp;
namespace fs = std::filesystem;

namespace {
fs::path tmpdir() {
  fs::path d = fs::temp_directory_path() / ("spp_test_io_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}
void write(const fs::path& p, const std::string& s) {
  std::ofstream(p) << s;
}
// The message with which a reader refuses a JSON text (named r.json / c.json in its messages), or "(accepted)": the
// refusal tests of the result and continuation readers below.
template <class Parse>
std::string refusal(Parse parse, const io::json& j, const char* name) {
  try {
    parse(j.dump(), name);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(accepted)";
}
std::string result_refusal(const io::json& j) {
  return refusal([](const std::string& t, const char* n) { return parse_result_file(t, n); }, j, "r.json");
}
std::string continuation_refusal(const io::json& j) {
  return refusal([](const std::string& t, const char* n) { return parse_continuation_file(t, n); }, j, "c.json");
}

// The chain's branch through its SPP near (5.707, 2.510) for k5 in [0.9, 1] (the continuation file tests).
ParametricSystem chain_k5() {
  return spp::test::paper_chain_k5(0.9, 1.0);
}
ContinuationResult chain_k5_branch(const ParametricSystem& ps) {
  const SolutionAt seed = solution_at(ps.at(0.98), 5.703374, 2.514785);
  EXPECT_TRUE(seed.found) << seed.brief_report();
  ContinueOptions o;
  o.t1_max = 8.0;
  o.t2_max = 3.0;
  return continue_branch(ps, 0.98, seed.solution, o);
}
}  // namespace

TEST(Io, SystemJsonRoundTrip) {
  const System s = rod_with_slip(-0.25, 0.25);
  const fs::path p = tmpdir() / "rod.json";
  write_file_atomic(p.string(), system_json(s, -1));
  const System t = load_system(p.string());
  EXPECT_EQ((s.M() - t.M()).norm(), 0.0);
  EXPECT_EQ((s.K() - t.K()).norm(), 0.0);
  EXPECT_EQ((s.w() - t.w()).norm(), 0.0);
  EXPECT_EQ(s.g0(), t.g0());
}

TEST(Io, MatrixMarketCoordinateSymmetricAndArray) {
  const fs::path d = tmpdir();
  write(d / "K.mtx", "%%MatrixMarket matrix coordinate real symmetric\n% chain\n2 2 3\n1 1 2\n2 1 -1\n2 2 1\n");
  write(d / "M.mtx", "%%MatrixMarket matrix array real general\n2 2\n1\n0\n0\n1\n");
  write(d / "sys.json",
        R"({"name": "mm", "M": {"matrix_market": "M.mtx"}, "K": {"matrix_market": "K.mtx"}, "w": [0, -1], "g0": 1})");
  const System s = load_system((d / "sys.json").string());
  EXPECT_EQ(s.K()(0, 1), -1.0);
  EXPECT_EQ(s.K()(1, 0), -1.0);
  EXPECT_EQ(s.K()(0, 0), 2.0);
  EXPECT_EQ(s.M()(1, 1), 1.0);
}

TEST(Io, ErrorsNameTheFieldAndFile) {
  const fs::path d = tmpdir();
  auto expect = [&](const std::string& json, const std::string& part) {
    write(d / "bad.json", json);
    try {
      load_system((d / "bad.json").string());
      FAIL() << "no error for " << json;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("bad.json"), std::string::npos) << e.what();
    }
  };
  expect(R"({"M": [[1,0],[0,1]], "K": [[2,-1],[-1,1]], "w": [0,-1]})", "missing field \"g0\"");
  expect(R"({"M": [[1,0],[0,1]], "K": [[2,-1],[-1,1]], "w": [0,-1], "g0": 1)", "malformed JSON");
  expect(R"({"M": [[1,0],[0]], "K": [[2,-1],[-1,1]], "w": [0,-1], "g0": 1})", "\"M\" row 1 must have 2 entries");
  expect(R"({"M": [[1,0],[0,1]], "K": [[2,"x"],[-1,1]], "w": [0,-1], "g0": 1})", "\"K\"[0][1] must be a number");
  expect(R"({"M": [[1,0],[0,1]], "K": {"matrix_market": "nope.mtx"}, "w": [0,-1], "g0": 1})", "nope.mtx");
  expect(R"({"M": [[1,0],[0,1]], "K": [[2,-1],[-1,1]], "w": [0,0], "g0": 1})", "w must be non-zero");
}

TEST(Io, AtomicWriteRefusesToReplaceADeviceOrAPipe) {
  // Found by an independent attack: the rename of the atomic write replaced /dev/full (as root) by a regular file.
  // A FIFO stands for any entry that is not a regular file.
  const fs::path d = tmpdir() / "atomic_fifo";
  fs::remove_all(d);
  fs::create_directories(d);
  const fs::path fifo = d / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  try {
    write_file_atomic(fifo.string(), "{}");
    FAIL() << "expected a refusal";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_fifo(fifo));
  size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(d)) ++entries;
  EXPECT_EQ(entries, 1u) << "a temporary file was left in " << d;
}

TEST(Io, AtomicWriteLeavesNoFileOnFailure) {
  EXPECT_THROW(write_file_atomic("/nonexistent_dir_spp/x.json", "{}"), std::invalid_argument);
  EXPECT_FALSE(fs::exists("/nonexistent_dir_spp/x.json"));
  // A failure after the temporary file was written (the final rename onto a directory fails): the target is
  // untouched and no temporary file is left behind.
  const fs::path d = tmpdir() / "atomic";
  fs::remove_all(d);
  fs::create_directories(d / "target");
  EXPECT_THROW(write_file_atomic((d / "target").string(), "{}"), std::invalid_argument);
  EXPECT_TRUE(fs::is_directory(d / "target"));
  size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(d)) ++entries;
  EXPECT_EQ(entries, 1u) << "a temporary file was left in " << d;
  // and a successful write replaces the file whole
  write_file_atomic((d / "r.json").string(), "old");
  write_file_atomic((d / "r.json").string(), "new");
  std::ifstream in(d / "r.json");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "new");
}

namespace {
void expect_same_vector(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (Eigen::Index i = 0; i < a.size(); ++i) EXPECT_EQ(a(i), b(i)) << what << "[" << i << "]";
}

// Every field of a SolveResult, compared exactly (JSON numbers round-trip doubles exactly).
void expect_same_result(const SolveResult& a, const SolveResult& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.symmetry, b.symmetry);
  EXPECT_EQ(a.warnings, b.warnings);
  EXPECT_EQ(a.t1_min, b.t1_min);
  EXPECT_EQ(a.t1_max, b.t1_max);
  EXPECT_EQ(a.t2_min, b.t2_min);
  EXPECT_EQ(a.t2_max, b.t2_max);
  EXPECT_EQ(a.decoupled_modes, b.decoupled_modes);
  EXPECT_EQ(a.repeated_groups, b.repeated_groups);
  const SolveStats &s = a.stats, &t = b.stats;
  EXPECT_EQ(s.flight_pole_lines, t.flight_pole_lines);
  EXPECT_EQ(s.contact_pole_lines, t.contact_pole_lines);
  EXPECT_EQ(s.rectangles, t.rectangles);
  EXPECT_EQ(s.curve_pieces, t.curve_pieces);
  EXPECT_EQ(s.roots, t.roots);
  EXPECT_EQ(s.evaluations, t.evaluations);
  EXPECT_EQ(s.strip_pairs, t.strip_pairs);
  EXPECT_EQ(s.certified_steps, t.certified_steps);
  EXPECT_EQ(s.heuristic_steps, t.heuristic_steps);
  EXPECT_EQ(s.uncertified_steps, t.uncertified_steps);
  EXPECT_EQ(s.uncertified_corners, t.uncertified_corners);
  EXPECT_EQ(s.unpaired_crossings, t.unpaired_crossings);
  EXPECT_EQ(s.unresolved_pieces, t.unresolved_pieces);
  EXPECT_EQ(s.unpolished_roots, t.unpolished_roots);
  EXPECT_EQ(s.pole_line_artifacts, t.pole_line_artifacts);
  EXPECT_EQ(s.seconds, t.seconds);
  ASSERT_EQ(a.uncertified.size(), b.uncertified.size());
  for (size_t i = 0; i < a.uncertified.size(); ++i) {
    EXPECT_EQ(a.uncertified[i].t1_lo, b.uncertified[i].t1_lo);
    EXPECT_EQ(a.uncertified[i].t2_hi, b.uncertified[i].t2_hi);
    EXPECT_EQ(a.uncertified[i].cause, b.uncertified[i].cause);
  }
  ASSERT_EQ(a.solutions.size(), b.solutions.size());
  for (size_t i = 0; i < a.solutions.size(); ++i) {
    const Solution &x = a.solutions[i], &y = b.solutions[i];
    const std::string at = "solution " + std::to_string(i);
    EXPECT_EQ(x.t1(), y.t1()) << at;
    EXPECT_EQ(x.t2(), y.t2()) << at;
    EXPECT_EQ(x.period(), y.period()) << at;
    EXPECT_EQ(x.admissible(), y.admissible()) << at;
    EXPECT_EQ(x.min_gap(), y.min_gap()) << at;
    EXPECT_EQ(x.min_force(), y.min_force()) << at;
    EXPECT_EQ(x.energy(), y.energy()) << at;
    EXPECT_EQ(x.residual, y.residual) << at;
    EXPECT_EQ(x.return_error, y.return_error) << at;
    EXPECT_EQ(x.flags, y.flags) << at;
    EXPECT_EQ(x.floquet.multipliers, y.floquet.multipliers) << at;
    EXPECT_EQ(std::isnan(x.floquet.spectral_radius), std::isnan(y.floquet.spectral_radius)) << at;
    if (!std::isnan(x.floquet.spectral_radius)) {
      EXPECT_EQ(x.floquet.spectral_radius, y.floquet.spectral_radius) << at;
      EXPECT_EQ(x.floquet.margin, y.floquet.margin) << at;
      EXPECT_EQ(x.floquet.structure_residual, y.floquet.structure_residual) << at;
      EXPECT_EQ(x.stable(), y.stable()) << at;
      EXPECT_EQ(x.floquet.spectral_radius_error, y.floquet.spectral_radius_error) << at;
      // (the part of it from the SPP's location: written since an attack found it read back as 0)
      EXPECT_EQ(x.floquet.location_error, y.floquet.location_error) << at;
      EXPECT_EQ(x.floquet.verdict, y.floquet.verdict) << at;
    }
    const Admissibility &p = x.admissibility, &q = y.admissibility;
    EXPECT_EQ(p.admissible, q.admissible) << at;
    EXPECT_EQ(p.min_gap, q.min_gap) << at;
    EXPECT_EQ(p.min_force, q.min_force) << at;
    EXPECT_EQ(p.mid_flight_gap, q.mid_flight_gap) << at;
    EXPECT_EQ(p.mid_contact_force, q.mid_contact_force) << at;
    EXPECT_EQ(p.onset_force_rate, q.onset_force_rate) << at;
    EXPECT_EQ(p.ends_ok, q.ends_ok) << at;
    EXPECT_EQ(p.certified, q.certified) << at;
    const Orbit &o = x.orbit, &r = y.orbit;
    EXPECT_EQ(o.t1, r.t1) << at;
    EXPECT_EQ(o.t2, r.t2) << at;
    EXPECT_EQ(o.symmetry, r.symmetry) << at;
    EXPECT_EQ(o.closure_ratio, r.closure_ratio) << at;
    EXPECT_EQ(o.energy, r.energy) << at;
    EXPECT_EQ(o.obstacle_velocity, r.obstacle_velocity) << at;
    expect_same_vector(o.a, r.a, at + " a");
    expect_same_vector(o.c, r.c, at + " c");
    expect_same_vector(o.p0, r.p0, at + " p0");
    expect_same_vector(o.p0dot, r.p0dot, at + " p0dot");
    expect_same_vector(o.x0, r.x0, at + " x0");
    expect_same_vector(o.v0, r.v0, at + " v0");
  }
}
}  // namespace

TEST(Io, LoadResultGivesBackTheSolveResultThatWasWritten) {
  // write, read, compare every field: the paper's chain window (axial, 64 SPPs), its point-symmetric solve, and an
  // incomplete result (with uncertified regions and warnings).
  const System s = chain(5, {1.0}, {1.0}, 4, ContactSide::Upper, 1.0);
  SolveOptions o;
  o.t1_max = o.t2_max = 12.0;
  std::vector<SolveResult> results{solve(s, o)};
  o.symmetry = Symmetry::Point;
  o.t1_max = o.t2_max = 4.0;
  results.push_back(solve(s, o));
  // the chain plus an oscillator coupled to the contact by 1e-6: incomplete (sign changes of g that do not polish)
  Eigen::MatrixXd K6 = Eigen::MatrixXd::Zero(6, 6);
  K6.topLeftCorner(5, 5) = s.K();
  K6(5, 5) = 1.7;
  Eigen::VectorXd w6 = Eigen::VectorXd::Zero(6);
  w6(4) = -1.0;
  w6(5) = 1e-6;
  const System weak(Eigen::MatrixXd::Identity(6, 6), K6, w6, 1.0);
  SolveOptions ow;
  ow.t1_min = ow.t2_min = 0.5;
  ow.t1_max = ow.t2_max = 6.0;
  results.push_back(solve(weak, ow));
  ASSERT_EQ(results.back().status, SolveStatus::Incomplete);
  ASSERT_FALSE(results.back().uncertified.empty());
  ASSERT_FALSE(results.back().warnings.empty());
  const std::vector<const System*> systems{&s, &s, &weak};
  const fs::path p = tmpdir() / "result.json";
  for (size_t i = 0; i < results.size(); ++i) {
    const SolveResult& r = results[i];
    ASSERT_FALSE(r.solutions.empty());
    write_file_atomic(p.string(), result_json(*systems[i], r));
    expect_same_result(r, load_result(p.string()));
    const System back = load_result_system(p.string());
    EXPECT_EQ(back.M(), systems[i]->M());
    EXPECT_EQ(back.K(), systems[i]->K());
  }
  fs::remove(p);
}

TEST(Io, ResultWithoutModalCoordinatesReadsAndSamplesLikeTheOriginal) {
  // Files written before the "orbit" block (or edited by hand without it) are read: the modal coordinates are rebuilt
  // from x0, v0 by whatever uses them (in_modal_basis), so the trajectory is the original's; written again, the file
  // has no "orbit" block either and still reads.
  const System s = chain(5, {1.0}, {1.0}, 4, ContactSide::Upper, 1.0);
  SolveOptions o;
  o.t1_max = o.t2_max = 12.0;
  const SolveResult r = solve(s, o);
  ASSERT_FALSE(r.solutions.empty());
  nlohmann::json j = nlohmann::json::parse(result_json(s, r));
  for (auto& x : j.at("solutions")) x.erase("orbit");
  const SolveResult back = parse_result(j.dump(), "result without orbit blocks");
  ASSERT_EQ(back.solutions.size(), r.solutions.size());
  const ModalForm md(s);
  for (size_t i = 0; i < r.solutions.size(); ++i) {
    EXPECT_EQ(back.solutions[i].orbit.p0.size(), 0);
    const OrbitSamples a = sample_orbit(md, r.solutions[i].orbit, 21),
                       b = sample_orbit(md, back.solutions[i].orbit, 21);
    EXPECT_LE((a.x - b.x).norm(), 1e-10 * a.x.norm()) << i;
    EXPECT_LE((a.gap - b.gap).norm(), 1e-10 * (a.gap.norm() + 1.0)) << i;
  }
  const SolveResult again = parse_result(result_json(s, back), "written again");
  EXPECT_EQ(again.solutions.size(), r.solutions.size());
}

TEST(Io, TextGivenAsAPathIsNotEchoedWhole) {
  // SolveResult.from_json takes a path; given the JSON text itself (100 kB), its "cannot open" message echoed all of
  // it (found by an independent review). Paths are quoted to io::kQuotedPathChars characters.
  const std::string text = "{\"solutions\": [" + std::string(100000, ' ') + "]}";
  try {
    load_result(text);
    ADD_FAILURE() << "expected a refusal";
  } catch (const std::invalid_argument& e) {
    EXPECT_LT(std::string(e.what()).size(), 700u);
    EXPECT_NE(std::string(e.what()).find("cannot open"), std::string::npos) << e.what();
  }
}

TEST(Io, LoadResultNamesWhatItCannotRead) {
  const fs::path p = tmpdir() / "bad_result.json";
  const System s = chain(3, {1.0}, {1.0}, 2, ContactSide::Upper, 1.0);
  SolveOptions o;
  o.t1_max = o.t2_max = 6.0;
  io::json j = io::result_to_json(s, solve(s, o));  // the private JSON, to break one field
  ASSERT_FALSE(j["solutions"].empty());
  j["solutions"][0]["orbit"]["p0"][1] = "x";
  write_file_atomic(p.string(), j.dump());
  try {
    load_result(p.string());
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("field \"solutions\"[0]: field \"orbit\": field \"p0\"[1] must be a number"),
              std::string::npos)
        << e.what();
  }
  fs::remove(p);
}

TEST(Io, ResultFilesGiveBackTheirSystemBitForBit) {
  // Regression: the embedded system's w and g0 (stored after dividing by |w|) were normalised again on load, moving
  // them by an ulp, and the input's |w| was lost (w_input_norm read back as 1).
  Eigen::MatrixXd M(2, 2), K(2, 2);
  M << 1, 0, 0, 1;
  K << 2, -1, -1, 1;
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  const std::vector<System> systems = {System(M, K, Eigen::Vector2d(0.0, -2.0), 3.0),
                                       System(M, K, Eigen::Vector2d(normal(rng), normal(rng)), 1.0 + normal(rng))};
  const fs::path p = tmpdir() / "system_round_trip.json";
  for (const System& s : systems) {
    SolveOptions o;
    o.t1_max = o.t2_max = 4.0;
    write_file_atomic(p.string(), result_json(s, solve(s, o)));
    const System back = load_result_system(p.string());
    EXPECT_EQ(back.w(), s.w());
    EXPECT_EQ(back.g0(), s.g0());
    EXPECT_EQ(back.w_input_norm(), s.w_input_norm());
    EXPECT_EQ(result_json(back, load_result(p.string())), read_file(p.string()));  // written again: the same text
  }
  fs::remove(p);
}

TEST(Io, ResultSolutionsOfTheWrongSizeOrSignAreRefused) {
  // Found by an independent attack: an x0 of 1 entry on a 3-dof system, or a negative t1, read without complaint.
  const System s = chain(3, {1.0}, {1.0}, 2, ContactSide::Upper, 1.0);
  SolveOptions o;
  o.t1_max = o.t2_max = 6.0;
  const io::json good = io::result_to_json(s, solve(s, o));
  ASSERT_FALSE(good["solutions"].empty());
  const fs::path p = tmpdir() / "wrong_size.json";
  auto expect_refused = [&](io::json j, const std::string& what) {
    write_file_atomic(p.string(), j.dump());
    try {
      load_result(p.string());
      ADD_FAILURE() << "expected a refusal: " << what;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  io::json short_x0 = good;
  short_x0["solutions"][0]["x0"] = {0.5};
  expect_refused(short_x0, "field \"solutions\"[0]: x0 and v0 must have 3 entries (the system's dofs), got 1 and 3");
  io::json negative = good;
  negative["solutions"][0]["t1"] = -1.0;
  expect_refused(negative, "field \"solutions\"[0]: t1 and t2 must be positive and finite");
  fs::remove(p);
}

// D8 of an independent review: a result file with an unknown field, an empty window, a period other than
// 2 (t1 + t2), "success" beside uncertified regions, an unknown cause or a negative count was read silently by
// load_result (spp plot, verify, trajectory, SolveResult.from_json) and load_result_system. Each is refused,
// naming the file, the solution (or list entry) and the field.
TEST(Io, ResultWithUnknownFieldsOrContradictionsIsRefused) {
  const System s = chain(3, {1.0}, {1.0}, 2, ContactSide::Upper, 1.0);
  SolveOptions o;
  o.t1_max = o.t2_max = 6.0;
  const io::json good = io::result_to_json(s, solve(s, o));
  ASSERT_FALSE(good["solutions"].empty());
  const fs::path p = tmpdir() / "contradictions.json";
  write_file_atomic(p.string(), good.dump());
  EXPECT_NO_THROW(load_result(p.string()));
  EXPECT_NO_THROW(load_result_system(p.string()));
  auto expect_refused = [&](const io::json& j, const std::string& what) {
    write_file_atomic(p.string(), j.dump());
    for (int reader = 0; reader < 2; ++reader) {
      try {
        if (reader == 0) load_result(p.string());
        if (reader == 1) load_result_system(p.string());
        ADD_FAILURE() << "expected a refusal: " << what << " (reader " << reader << ")";
      } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find(p.string() + ": " + what), std::string::npos) << e.what();
      }
    }
  };
  io::json j = good;
  j["solutions"][0]["foo"] = 1;
  expect_refused(j, "field \"solutions\"[0]: unknown field \"foo\" (expected: t1, t2, period");
  j = good;
  j["solutions"][0]["orbit"]["bar"] = 1;
  expect_refused(j, "field \"solutions\"[0]: field \"orbit\": unknown field \"bar\"");
  j = good;
  j["extra"] = true;
  expect_refused(j, "unknown field \"extra\" (expected: system, window");
  j = good;
  j["window"]["t1_max"] = -5;
  expect_refused(j, "field \"window\": expected 0 < t1_min < t1_max < inf, got t1_min = ");
  j = good;
  j["window"]["t3"] = 1;
  expect_refused(j, "field \"window\": unknown field \"t3\"");
  j = good;
  j["solutions"][0]["period"] = 123;
  expect_refused(j, "field \"solutions\"[0]: field \"period\" must be 2 (t1 + t2) = ");
  j = good;
  j["status"] = "success";
  j["uncertified"] = io::json::array({{{"t1_lo", 1}, {"t1_hi", 2}, {"t2_lo", 1}, {"t2_hi", 2}, {"cause", "step"}}});
  expect_refused(j, "field \"status\" is \"success\" but field \"uncertified\" lists 1 region(s)");
  j["status"] = "incomplete";
  j["uncertified"][0]["cause"] = "nonsense";
  expect_refused(j,
                 "field \"uncertified\"[0]: field \"cause\" must be one of step, corner, budget, pairing, "
                 "polish, interrupted, got \"nonsense\"");
  j = good;
  j["stats"]["roots"] = -3;
  expect_refused(
      j, "field \"stats\": field \"roots\" must be a count, a whole number from 0 to 9223372036854775807, got -3");
  j = good;
  j["stats"]["seconds"] = -1.0;
  expect_refused(j, "field \"stats\": field \"seconds\" must be >= 0");
  fs::remove(p);
}

// Found by an independent attack: each of these read silently before (a status that its own counts contradict, a
// root count below the SPPs listed, an SPP outside the window, an unknown flag, null read as NaN, the embedded
// system's "n" or "w_input_norm" unlike its matrices).
TEST(Io, ResultWhoseFieldsContradictEachOtherIsRefused) {
  const System s = chain(3, {1.0}, {1.0}, 2, ContactSide::Upper, 1.0);
  SolveOptions o;
  o.t1_max = o.t2_max = 6.0;
  const io::json good = io::result_to_json(s, solve(s, o));
  ASSERT_EQ(good["status"], "success");
  ASSERT_GE(good["solutions"].size(), 2u);
  const auto refusal = result_refusal;
  auto expect_refused = [&](const io::json& j, const std::string& what) {
    EXPECT_NE(refusal(j).find("r.json: " + what), std::string::npos) << refusal(j);
  };
  EXPECT_EQ(refusal(good), "(accepted)");
  for (const char* count : {"uncertified_steps", "uncertified_corners", "unpaired_crossings", "unresolved_pieces",
                            "unpolished_roots", "unsearched_cells"}) {
    io::json j = good;
    j["stats"][count] = 2;
    expect_refused(j, std::string("field \"status\" is \"success\" but field \"stats\".\"") + count +
                          "\" is 2: expected 0, or status \"incomplete\"");
  }
  io::json j = good;
  j["warnings"] = {"something"};
  expect_refused(j, "field \"status\" is \"success\" but field \"warnings\" has 1 entry");
  j = good;
  j["solutions"][1]["admissibility_certified"] = false;
  expect_refused(j,
                 "field \"status\" is \"success\" but field \"solutions\"[1] has \"admissibility_certified\": false");
  j = good;
  j["status"] = "incomplete";
  expect_refused(j, "field \"status\" is \"incomplete\" but neither \"warnings\" nor \"uncertified\" says why");
  j["warnings"] = {"1 trace step(s) were not proved"};
  EXPECT_EQ(refusal(j), "(accepted)");
  j = good;  // stability claimed with its multipliers deleted (spp verify checks the multipliers given: it passed)
  j["solutions"][0].erase("floquet_multipliers");
  expect_refused(j, "field \"solutions\"[0]: field \"spectral_radius\" without \"floquet_multipliers\"");
  j = good;  // the location part of the bound: from 0 to the bound
  j["solutions"][0]["spectral_radius_location_error"] = 2.0 * good["solutions"][0]["spectral_radius_error"].get<double>() + 1.0;
  expect_refused(j, "field \"solutions\"[0]: field \"spectral_radius_location_error\": expected a number from 0");
  j = good;
  j["stats"]["roots"] = 1;
  expect_refused(j, "field \"stats\".\"roots\" must count at least the ");
  j = good;  // an admissible_only solve lists fewer SPPs than it found, and no non-admissible one
  j["stats"]["roots"] = 1000;
  io::json kept = io::json::array();
  for (const io::json& o : good["solutions"])
    if (o["admissible"] == true) kept.push_back(o);
  j["solutions"] = kept;
  EXPECT_EQ(refusal(j), "(accepted)");
  j = good;
  j["window"]["t1_max"] = 0.5 * good["solutions"][0]["t1"].get<double>() + 0.5 * good["window"]["t1_min"].get<double>();
  expect_refused(j, "field \"solutions\"[0] at (t1, t2) = (");
  j = good;
  j["solutions"][0]["flags"] = {"near_pole_line", "shiny"};
  expect_refused(j, "field \"solutions\"[0]: field \"flags\"[1]: expected one of point_symmetric, ");
  for (const char* field : {"min_gap", "energy", "residual"}) {
    j = good;
    j["solutions"][0][field] = nullptr;
    expect_refused(j,
                   std::string("field \"solutions\"[0]: field \"") + field + "\": expected a finite number, got null");
  }
  j = good;
  j["solutions"][0]["x0"][1] = nullptr;
  expect_refused(j, "field \"solutions\"[0]: field \"x0\"[1]: expected a finite number, got null");
  j = good;
  j["system"]["n"] = 7;
  expect_refused(j, "field \"system\": field \"n\" must be the size of M, K and w, 3, got 7");
  j = good;
  j["system"]["w_input_norm"] = -2.0;
  expect_refused(j, "field \"system\": field \"w_input_norm\" must be |w| as given, a positive finite number");
  j = good;
  j["system"]["w_normalized"] = !good["system"]["w_normalized"].get<bool>();
  expect_refused(j, "field \"system\": field \"w_normalized\" must be ");
  // the orbit block and the stability fields (found by an independent attack: each read silently before)
  ASSERT_TRUE(good["solutions"][0].contains("orbit"));
  ASSERT_TRUE(good["solutions"][0].contains("floquet_multipliers"));
  j = good;
  j["solutions"][0]["orbit"]["p0"].erase(0);
  expect_refused(j, "field \"solutions\"[0]: field \"orbit\": expected a, c, p0, p0dot of one length between 1 and");
  j = good;
  j["solutions"][0]["orbit"]["energy"] = 2.0 * good["solutions"][0]["energy"].get<double>();
  expect_refused(j, "field \"solutions\"[0]: field \"orbit\": field \"energy\" must be the SPP's \"energy\"");
  j = good;
  j["solutions"][0]["orbit"]["closure_ratio"] = -0.5;
  expect_refused(j, "field \"solutions\"[0]: field \"orbit\": field \"closure_ratio\": expected a number in [0, 1]");
  j = good;
  j["solutions"][0]["floquet_multipliers"] = io::json::array();
  expect_refused(j, "field \"solutions\"[0]: field \"floquet_multipliers\": expected 2n = 6 multipliers");
  j = good;
  j["solutions"][0]["spectral_radius"] = 0.5 * good["solutions"][0]["spectral_radius"].get<double>();
  expect_refused(j, "field \"solutions\"[0]: field \"spectral_radius\" must be the largest modulus");
  j = good;
  j["solutions"][0]["stability_margin"] = 7.0;
  expect_refused(j, "field \"solutions\"[0]: field \"stability_margin\" must be 1 - spectral_radius");
  j = good;
  j["system"]["name"] = std::string("chain\0three", 11);
  expect_refused(j, "field \"system\": field \"name\": expected printable text, got the control character 0 at byte 5");
  j = good;
  j["system"]["description"] = "two lines\nand a tab\t";
  EXPECT_EQ(refusal(j), "(accepted)");
  // an admissible SPP's minima, the multipliers' order, flags listed twice, counts beside SPPs (second attack)
  size_t adm = 0;
  while (adm < good["solutions"].size() && good["solutions"][adm]["admissible"] != true) ++adm;
  ASSERT_LT(adm, good["solutions"].size());
  const std::string sa = "field \"solutions\"[" + std::to_string(adm) + "]: ";
  for (const char* field : {"min_gap", "min_force"}) {
    j = good;
    j["solutions"][adm][field] = -0.5;
    expect_refused(j, sa + "field \"admissible\" is true but field \"" + field + "\" is -0.5: expected >= 0");
  }
  j = good;
  j["solutions"][adm]["min_gap"] = good["solutions"][adm]["mid_flight_gap"].get<double>() + 1.0;
  expect_refused(j, sa + "field \"min_gap\" ");
  j = good;
  std::reverse(j["solutions"][0]["floquet_multipliers"].begin(), j["solutions"][0]["floquet_multipliers"].end());
  expect_refused(j, "field \"solutions\"[0]: field \"floquet_multipliers\"[");
  EXPECT_NE(refusal(j).find("expected them sorted by modulus"), std::string::npos) << refusal(j);
  j = good;
  j["solutions"][0]["flags"] = {"near_pole_line", "near_pole_line"};
  expect_refused(j, "field \"solutions\"[0]: field \"flags\"[1]: the string \"near_pole_line\" is listed twice");
  for (const char* count : {"rectangles", "curve_pieces", "evaluations"}) {
    j = good;
    j["stats"][count] = 0;
    expect_refused(j, std::string("field \"stats\".\"") + count + "\" is 0 beside ");
  }
}

// Found by an independent attack (issue 11): a full result (non-admissible SPPs kept) with one SPP deleted still read
// as "success" (stats.roots 18, 17 listed: only roots >= listed was checked); so did a residual of 0.5, which the
// solver never accepts, and a window whose lower end is 0, which the solver never reports.
TEST(Io, ResultWithAnSppDeletedOrWhatTheSolverCannotWriteIsRefused) {
  const System s = chain(3, {1.0}, {1.0}, 2, ContactSide::Upper, 1.0);
  SolveOptions o;
  o.t1_max = o.t2_max = 6.0;
  const io::json good = io::result_to_json(s, solve(s, o));
  ASSERT_EQ(good["status"], "success");
  const size_t listed = good["solutions"].size();
  ASSERT_EQ(good["stats"]["roots"].get<size_t>(), listed);
  const auto refusal = result_refusal;
  EXPECT_EQ(refusal(good), "(accepted)");
  // an SPP deleted, a non-admissible one left: every SPP of the window was listed (admissible_only off)
  size_t inadmissible = listed, admissible = listed;
  for (size_t i = 0; i < listed; ++i) (good["solutions"][i]["admissible"] == true ? admissible : inadmissible) = i;
  ASSERT_LT(inadmissible, listed);
  ASSERT_LT(admissible, listed);
  io::json j = good;
  j["solutions"].erase(admissible);
  const std::string deleted = refusal(j);
  EXPECT_NE(deleted.find("r.json: field \"stats\".\"roots\" is " + std::to_string(listed) +
                         " but field \"solutions\" lists " + std::to_string(listed - 1) + " SPP(s)"),
            std::string::npos)
      << deleted;
  EXPECT_NE(deleted.find("expected " + std::to_string(listed) + " SPP(s) listed, got " + std::to_string(listed - 1)),
            std::string::npos)
      << deleted;
  // a residual the solver would not accept; the one it wrote is accepted
  j = good;
  j["solutions"][0]["residual"] = 0.5;
  EXPECT_NE(refusal(j).find("r.json: field \"solutions\"[0]: field \"residual\": expected a number below 1e-10"),
            std::string::npos)
      << refusal(j);
  // a window's lower end at 0 (the solver searches from > 0 and writes where it started)
  for (const char* end : {"t1_min", "t2_min"}) {
    j = good;
    j["window"][end] = 0.0;
    EXPECT_NE(refusal(j).find(std::string("r.json: field \"window\": expected 0 < ") + end), std::string::npos)
        << refusal(j);
  }
}

TEST(Io, MatrixMarketOfAnotherSizeThanWIsRefusedBeforeItIsAllocated) {
  // A 60-byte file declaring 20000 x 20000 as M of a 2-dof system took 3.1 GB before the sizes were compared (found
  // by an independent attack): its size line is now checked against w's length first. (A 1e6 x 1e6 declaration
  // would need 8 TB: this test would fail with an out-of-memory error if the check came after the allocation.)
  const fs::path d = tmpdir();
  write(d / "big.mtx", "%%MatrixMarket matrix coordinate real symmetric\n1000000 1000000 1\n1 1 1.0\n");
  write(d / "ok.mtx", "%%MatrixMarket matrix coordinate real symmetric\n2 2 2\n1 1 1.0\n2 2 1.0\n");
  for (const char* m : {"big.mtx", "ok.mtx"}) {
    write(d / "mm.json", std::string(R"({"M": {"matrix_market": ")") + m +
                             R"("}, "K": {"matrix_market": "big.mtx"}, "w": [0, 1], "g0": 1})");
    try {
      load_system((d / "mm.json").string());
      ADD_FAILURE() << "accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("big.mtx: declares a 1000000 x 1000000 matrix, expected 2 x 2 (the "
                                           "length of w)"),
                std::string::npos)
          << e.what();
    }
  }
  write(d / "pmm.json", R"({"parameter": {"name": "k", "min": 0, "max": 1}, "M": {"matrix_market": "big.mtx"},
                            "K": [[2, 0], [0, 2]], "w": [0, 1], "g0": 1})");
  try {
    load_parametric_system((d / "pmm.json").string());
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("declares a 1000000 x 1000000 matrix, expected 2 x 2"), std::string::npos)
        << e.what();
  }
}

namespace {
// load_system of `json` (written to bad.json) must throw std::invalid_argument containing `part`.
void expect_load_refused(const std::string& json, const std::string& part) {
  const fs::path p = tmpdir() / "bad.json";
  write(p, json);
  try {
    load_system(p.string());
    ADD_FAILURE() << "no error for " << json.substr(0, 200);
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}
}  // namespace

TEST(Io, DeeplyNestedJsonIsRefusedByTheParserWhereverItIs) {
  // Found by fuzzing: a 100 000-deep array in "description" or "name" was read without complaint (and anywhere else
  // it waits for the first recursive copy, comparison or dump to overflow the stack). Refused at the parser.
  const std::string deep = std::string(100000, '[') + "1" + std::string(100000, ']');
  const std::string message = "expected JSON nested at most 64 levels deep";
  for (const char* field : {"description", "name", "w", "g0", "extra"})
    expect_load_refused(std::string(R"({"M": [[1,0],[0,1]], "K": [[2,-1],[-1,1]], "w": [0,-1], "g0": 1, ")") + field +
                            "\": " + deep + "}",
                        message);
  expect_load_refused(std::string(100000, '{') + std::string(100000, '}'), "malformed JSON");  // an object needs keys
  std::string objects;
  for (int i = 0; i < 100000; ++i) objects += R"({"a": )";
  expect_load_refused(objects + "1" + std::string(100000, '}'), message);
  // 64 levels are read (a message about the content, not the depth)
  expect_load_refused(R"({"M": [[1,0],[0,1]], "K": [[2,-1],[-1,1]], "w": [0,-1], "g0": 1, "extra": )" +
                          std::string(62, '[') + std::string(62, ']') + "}",
                      "unknown field \"extra\"");
}

TEST(Io, NameOrDescriptionThatIsNotAStringIsRefused) {
  // Was ignored silently (the name read as empty): a list or number there is named like any other wrong type.
  expect_load_refused(R"({"name": [1], "M": [[1,0],[0,1]], "K": [[2,-1],[-1,1]], "w": [0,-1], "g0": 1})",
                      "field \"name\" must be a string, got a list (1 entries)");
  expect_load_refused(R"({"description": 3, "M": [[1,0],[0,1]], "K": [[2,-1],[-1,1]], "w": [0,-1], "g0": 1})",
                      "field \"description\" must be a string, got 3");
}

TEST(Io, UnknownFieldBesideMatrixMarketIsNamed) {
  // {"matrix_market": "M.mtx", "symmetric": true} read M.mtx and dropped the rest silently.
  const fs::path d = tmpdir();
  write(d / "I.mtx", "%%MatrixMarket matrix array real general\n2 2\n1\n0\n0\n1\n");
  expect_load_refused(
      R"({"M": {"matrix_market": "I.mtx", "symmetric": true}, "K": [[2,-1],[-1,1]], "w": [0,-1], "g0": 1})",
      "field \"M\": unknown field \"symmetric\" (expected: matrix_market)");
}

TEST(Io, ParametricPartErrorsNameTheMatrixAndThePart) {
  // An entry of K's "k2" part that is not a number was reported as field "k2"[1][1], without saying it is K's part.
  const fs::path p = tmpdir() / "bad_param.json";
  write(p, R"({"parameter": {"name": "k2", "min": 1, "max": 2}, "M": [[1,0],[0,1]],
    "K": {"constant": [[1,0],[0,0]], "k2": [[1,-1],[-1,"x"]]}, "w": [0,-1], "g0": 1})");
  try {
    load_parametric_system(p.string());
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("field \"K\": field \"k2\"[1][1] must be a number"), std::string::npos)
        << e.what();
  }
}

TEST(Io, MatrixMarketHexadecimalNumberIsRefused) {
  // strtod read "0x1p1" as 2 (a C99 hexadecimal float); Matrix Market numbers are decimal.
  const fs::path d = tmpdir();
  write(d / "hex.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 0x1p1\n2 2 1\n");
  expect_load_refused(R"({"M": {"matrix_market": "hex.mtx"}, "K": [[2,-1],[-1,1]], "w": [0,-1], "g0": 1})",
                      "bad entry \"1 1 0x1p1\"");
}

// Found by an independent attack (issue 11): a NUL byte inside a Matrix Market line cut the message short where it
// was quoted (what() is a C string): the line's text and the rule after it were lost. Shown escaped, file and line
// named.
TEST(Io, NulByteInsideAMatrixMarketLineIsShownEscapedNamingFileAndLine) {
  using namespace std::string_literals;  // ("..."s keeps the NUL)
  const fs::path d = tmpdir();
  write(d / "nul.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 1\0junk\n2 2 1\n"s);
  expect_load_refused(R"({"M": {"matrix_market": "nul.mtx"}, "K": [[2,-1],[-1,1]], "w": [0,-1], "g0": 1})",
                      "nul.mtx:3: bad entry \"1 1 1\\x00junk\" (expected row col value");
  write(d / "nul1.mtx", "%%MatrixMarket matrix coord\0inate real general\n2 2 2\n1 1 1\n2 2 1\n"s);
  expect_load_refused(R"({"M": {"matrix_market": "nul1.mtx"}, "K": [[2,-1],[-1,1]], "w": [0,-1], "g0": 1})",
                      "nul1.mtx:1: expected format coordinate or array, got \"coord\\x00inate\"");
}

// Found by an independent attack (issue 11): a byte that is not UTF-8 (a Latin-1 file, \xff in a Matrix Market line)
// was quoted raw, and Python, which decodes messages as UTF-8, raised an empty ValueError(). Escaped as \xNN, the
// message valid UTF-8; a character that is UTF-8 (é) is kept whole, never cut in two; C1 controls escaped like C0.
TEST(Io, BytesThatAreNotUtf8AreShownEscapedSoThatEveryMessageIsUtf8) {
  using namespace std::string_literals;
  const fs::path d = tmpdir();
  write(d / "ff.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 1\xff\n2 2 1\n"s);
  expect_load_refused(R"({"M": {"matrix_market": "ff.mtx"}, "K": [[2,-1],[-1,1]], "w": [0,-1], "g0": 1})",
                      "ff.mtx:3: bad entry \"1 1 1\\xff\"");
  // a system file in Latin-1: "name": "chaîne" with î as the one byte 0xee
  expect_load_refused(
      "{\"name\": \"cha\xee"
      "ne\", \"M\": [[1]], \"K\": [[1]], \"w\": [1], \"g0\": 1}"s,
      "\\xee");
  try {
    write(d / "latin1.json",
          "{\"name\": \"cha\xee"
          "ne\", \"M\": [[1]], \"K\": [[1]], \"w\": [1], \"g0\": 1}"s);
    load_system((d / "latin1.json").string());
    ADD_FAILURE() << "a Latin-1 file was read";
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("latin1.json: malformed JSON"), std::string::npos) << m;
    EXPECT_EQ(m.find('\xee'), std::string::npos) << m;  // (the raw byte)
  }
  // the quoting itself: UTF-8 kept, never cut inside a character; other bytes and C0/C1 controls escaped
  EXPECT_EQ(io::shorten("caf\xc3\xa9 \xff\xc3 \x00"s + "1 \xc2\x9b!"), "caf\xc3\xa9 \\xff\\xc3 \\x001 \\xc2\\x9b!");
  EXPECT_EQ(io::shorten("\xc3\xa9\xc3\xa9\xc3\xa9", 2), "\xc3\xa9\xc3\xa9...");
  EXPECT_EQ(io::shorten("\xed\xa0\x80\xe0\x80\x80"),
            "\\xed\\xa0\\x80\\xe0\\x80\\x80");  // (a surrogate, an overlong form)
  // a name is UTF-8 without controls, C1 as C0 (U+009B was accepted where U+001B was refused)
  const Eigen::MatrixXd one = Eigen::MatrixXd::Identity(1, 1);
  const Eigen::VectorXd w1 = Eigen::VectorXd::Ones(1);
  for (const auto& [name, why] :
       {std::pair<std::string, std::string>{"a\xc2\x9b", "control character U+009B at byte 1"},
        {"cha\xee"
         "ne",
         "expected UTF-8 text, got the byte 0xee at byte 3"},
        {"a\x1b", "control character 27 at byte 1"}}) {
    try {
      System(one, one, w1, 1.0, name);
      ADD_FAILURE() << "accepted the name " << io::shorten(name);
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("system: name: expected "), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(System(one, one, w1, 1.0,
                   "cha\xc3\xae"
                   "ne \xe2\x82\xac")
                .name(),
            "cha\xc3\xae"
            "ne \xe2\x82\xac");
}

// Found by an independent attack (issue 11): "matrix_market": "/proc/self/mem" (a regular file that cannot be read)
// gave libstdc++'s bare "basic_filebuf::underflow error reading the file", naming no file.
TEST(Io, MatrixMarketFileThatCannotBeReadIsNamedWithTheReason) {
  if (!fs::exists("/proc/self/mem")) GTEST_SKIP() << "no /proc/self/mem here";
  expect_load_refused(R"({"M": {"matrix_market": "/proc/self/mem"}, "K": [[2,-1],[-1,1]], "w": [0,-1], "g0": 1})",
                      "cannot read Matrix Market file \"/proc/self/mem\" at line 1: ");
}

TEST(Io, MatrixMarketIndicesAndCountsAreWholeNumbersAsWritten) {
  // "2.0" and "2e0" were read as 2 in the size line and in entries (through a double; found by an independent attack)
  const fs::path d = tmpdir();
  for (const char* size : {"2.0 2 2", "2 2e0 2", "2 2 2.5"}) {
    write(d / "sz.mtx", std::string("%%MatrixMarket matrix coordinate real general\n") + size + "\n1 1 1\n2 2 1\n");
    expect_load_refused(R"({"M": {"matrix_market": "sz.mtx"}, "K": [[2,-1],[-1,1]], "w": [0,-1], "g0": 1})",
                        std::string("bad size line \"") + size + "\"");
  }
  write(d / "ix.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 1\n2.0 2 1\n");
  expect_load_refused(R"({"M": {"matrix_market": "ix.mtx"}, "K": [[2,-1],[-1,1]], "w": [0,-1], "g0": 1})",
                      "bad entry \"2.0 2 1\"");
  write(d / "ok.mtx", "%%MatrixMarket matrix coordinate real general\n+2 2 2\n1 1 1\n2 2 1\n");
  write(d / "ok.json", R"({"M": {"matrix_market": "ok.mtx"}, "K": [[2,-1],[-1,1]], "w": [0,-1], "g0": 1})");
  EXPECT_EQ(load_system((d / "ok.json").string()).n(), 2);
}

TEST(Io, SparseSystemRoundTripsThroughMatrixMarketFiles) {
  // write_sparse_system: M and K as symmetric coordinate files beside the JSON, 17 digits: read back bit for bit by the
  // sparse loader, and by the dense one (small n)
  const SparseSystem s = bar(40, BarMass::Consistent, 17, ContactSide::Lower, 0.3);
  const fs::path p = tmpdir() / "bar40.json";
  write_sparse_system(s, p.string());
  EXPECT_TRUE(fs::exists(tmpdir() / "bar40.M.mtx"));
  EXPECT_TRUE(fs::exists(tmpdir() / "bar40.K.mtx"));
  const SparseSystem t = load_sparse_system(p.string());
  EXPECT_EQ(Eigen::MatrixXd(s.M() - t.M()).norm(), 0.0);
  EXPECT_EQ(Eigen::MatrixXd(s.K() - t.K()).norm(), 0.0);
  EXPECT_EQ((s.w() - t.w()).norm(), 0.0);
  EXPECT_EQ(t.g0(), 0.3);
  EXPECT_EQ(t.name(), "bar40");
  const System d = load_system(p.string());
  EXPECT_EQ((d.M() - Eigen::MatrixXd(s.M())).norm(), 0.0);
  EXPECT_EQ((d.K() - Eigen::MatrixXd(s.K())).norm(), 0.0);
  const std::vector<std::string> inputs = system_file_inputs(p.string());
  ASSERT_EQ(inputs.size(), 3u);
  EXPECT_EQ(fs::path(inputs[1]).filename(), "bar40.M.mtx");
}

TEST(Io, SparseMatrixMarketReaderFollowsTheDenseOne) {
  // the same files through both readers: symmetric expanded, duplicates summed, array zeros dropped
  const fs::path d = tmpdir();
  write(d / "Ks.mtx",
        "%%MatrixMarket matrix coordinate real symmetric\n3 3 5\n1 1 2\n2 1 -1\n2 1 -0.5\n2 2 3\n3 3 1\n");
  write(d / "Ma.mtx", "%%MatrixMarket matrix array real general\n2 2\n1\n0\n0\n1\n");
  for (const char* f : {"Ks.mtx", "Ma.mtx"}) {
    const Eigen::MatrixXd dense = read_matrix_market((d / f).string());
    const Eigen::SparseMatrix<double> sparse = read_sparse_matrix_market((d / f).string());
    EXPECT_EQ((dense - Eigen::MatrixXd(sparse)).norm(), 0.0) << f;
  }
  EXPECT_EQ(read_sparse_matrix_market((d / "Ks.mtx").string()).coeff(0, 1), -1.5);
  EXPECT_EQ(read_sparse_matrix_market((d / "Ma.mtx").string()).nonZeros(), 2);
  // an entry given in both triangles of a symmetric file is refused by both
  write(d / "Kboth.mtx", "%%MatrixMarket matrix coordinate real symmetric\n2 2 3\n1 1 2\n2 1 -1\n1 2 -1\n");
  EXPECT_THROW(read_matrix_market((d / "Kboth.mtx").string()), std::invalid_argument);
  try {
    read_sparse_matrix_market((d / "Kboth.mtx").string());
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("its mirror was given too"), std::string::npos) << e.what();
  }
  // the sparse reader takes sizes the dense one refuses
  write(d / "big.mtx", "%%MatrixMarket matrix coordinate real symmetric\n100000 100000 1\n100000 100000 1\n");
  EXPECT_THROW(read_matrix_market((d / "big.mtx").string()), std::invalid_argument);
  EXPECT_EQ(read_sparse_matrix_market((d / "big.mtx").string()).coeff(99999, 99999), 1.0);
}

TEST(Io, SparseSystemRefusesASizeLineOtherThanWsLengthBeforeAllocatingIt) {
  // Found by an independent attack: an 11-entry file declaring 1e8 x 1e8 took 3.9 GB (setFromTriplets' outer
  // index and the checks of SparseSystem) before it was refused. The size line is now checked against w's length.
  const fs::path d = tmpdir() / "sparse_size";
  fs::create_directories(d);
  write(d / "huge.mtx", "%%MatrixMarket matrix coordinate real symmetric\n100000000 100000000 1\n1 1 1\n");
  write(d / "K.mtx", "%%MatrixMarket matrix coordinate real symmetric\n2 2 3\n1 1 2\n2 1 -1\n2 2 1\n");
  write(d / "s.json", R"({"M": {"matrix_market": "huge.mtx"}, "K": {"matrix_market": "K.mtx"}, "w": [0, 1], "g0": 1})");
  try {
    load_sparse_system((d / "s.json").string());
    FAIL() << "expected a refusal";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("expected 2 x 2 (the length of w)"), std::string::npos) << what;
    EXPECT_NE(what.find("\"M\""), std::string::npos) << what;
  }
}

TEST(Io, DenseSystemBeyondTheDenseSolverIsRefusedBeforeItsMatricesAreRead) {
  // Found by an independent attack: spp solve on a 19 999-dof model ran silently past 40 s at 8.7 GB (reading two
  // 3.2 GB dense matrices, then O(n^3) work of hours). w's length is checked first, so that M's file is not even
  // opened; the message points to spp reduce.
  const fs::path d = tmpdir() / "dense_limit";
  fs::create_directories(d);
  std::string w = "[1";
  for (int i = 1; i <= spp::kMaxDenseDofs; ++i) w += ", 0";
  write(d / "s.json",
        R"({"M": {"matrix_market": "absent.mtx"}, "K": {"matrix_market": "absent.mtx"}, "w": )" + w + R"(], "g0": 1})");
  try {
    load_system((d / "s.json").string());
    FAIL() << "expected a refusal";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("has " + std::to_string(spp::kMaxDenseDofs + 1) + " entries"), std::string::npos) << what;
    EXPECT_NE(what.find("spp reduce"), std::string::npos) << what;
    EXPECT_EQ(what.find("absent.mtx"), std::string::npos) << what;
  }
}

TEST(Io, SystemFileWithAResultsEmbeddedFieldsIsRefused) {
  // "n", "w_normalized", "w_input_norm" are what a result file adds to its system: a system file took them with
  // any value, silently (found by an independent attack)
  for (const char* field : {"n", "w_normalized", "w_input_norm"})
    expect_load_refused(
        std::string(R"({"M": [[1,0],[0,1]], "K": [[2,-1],[-1,1]], "w": [0,-1], "g0": 1, ")") + field + "\": 99}",
        std::string("field \"") + field + "\" belongs to the system a result file embeds");
}

// The stability verdict and its rounding bound (stability/floquet.hpp): files written before them read with the old
// verdict (spectral_radius < 1) and an unknown bound; a verdict that its radius and bound contradict, or one field
// without the other, is refused.
TEST(Io, StabilityVerdictReadsOldFilesAndRefusesContradictions) {
  const System s = chain(5, {1.0}, {1.0}, 4, ContactSide::Upper, 1.0);
  SolveOptions o;
  o.t1_max = o.t2_max = 12.0;
  o.admissible_only = true;
  const io::json good = io::result_to_json(s, solve(s, o));
  ASSERT_EQ(good["solutions"].size(), 7u);
  ASSERT_EQ(good["solutions"][2]["stability_verdict"], "stable");
  ASSERT_EQ(good["solutions"][1]["stability_verdict"], "unstable");
  const auto refusal = result_refusal;
  EXPECT_EQ(refusal(good), "(accepted)");
  io::json old = good;
  for (io::json& x : old["solutions"]) {
    x.erase("spectral_radius_error");
    x.erase("stability_verdict");
  }
  const SolveResult back = parse_result(old.dump(), "old.json");
  EXPECT_EQ(back.solutions[2].floquet.verdict, StabilityVerdict::Stable);
  EXPECT_TRUE(back.solutions[2].stable());
  EXPECT_EQ(back.solutions[1].floquet.verdict, StabilityVerdict::Unstable);
  EXPECT_TRUE(std::isnan(back.solutions[2].floquet.spectral_radius_error));
  io::json j = good;
  j["solutions"][1]["stability_verdict"] = "stable";  // rho = 1.0137
  j["solutions"][1]["stable"] = true;
  EXPECT_NE(refusal(j).find("r.json: field \"solutions\"[1]: field \"stability_verdict\" is \"stable\" but "
                            "spectral_radius 1.01369"),
            std::string::npos)
      << refusal(j);
  j = good;
  j["solutions"][2]["spectral_radius_error"] = 0.02;  // rho = 0.9858: within 0.02 of 1, undecided
  EXPECT_NE(refusal(j).find("gives \"undecided\""), std::string::npos) << refusal(j);
  j["solutions"][2]["stability_verdict"] = "undecided";
  EXPECT_NE(refusal(j).find("field \"stable\" must be admissible and stability_verdict \"stable\""), std::string::npos)
      << refusal(j);
  j["solutions"][2]["stable"] = false;
  EXPECT_EQ(refusal(j), "(accepted)");
  EXPECT_EQ(parse_result(j.dump(), "r.json").solutions[2].floquet.verdict, StabilityVerdict::Undecided);
  j = good;
  j["solutions"][2]["stability_verdict"] = "neutral";
  j["solutions"][2]["stable"] = false;
  EXPECT_NE(refusal(j).find("(\"neutral\" needs spectral_radius 1 exactly)"), std::string::npos) << refusal(j);
  j = good;
  j["solutions"][2]["stability_verdict"] = "maybe";
  EXPECT_NE(refusal(j).find("field \"stability_verdict\" must be one of stable, unstable, undecided, neutral"),
            std::string::npos)
      << refusal(j);
  j = good;
  j["solutions"][2].erase("stability_verdict");
  EXPECT_NE(refusal(j).find("fields \"spectral_radius_error\" and \"stability_verdict\" go together"),
            std::string::npos)
      << refusal(j);
  j = good;
  j["solutions"][2]["spectral_radius_error"] = -1.0;
  EXPECT_NE(refusal(j).find("field \"spectral_radius_error\" must be a number >= 0 or null"), std::string::npos)
      << refusal(j);
}

namespace {
void expect_same_point(const BranchPoint& a, const BranchPoint& b, const std::string& at) {
  EXPECT_EQ(a.mu, b.mu) << at;
  EXPECT_EQ(a.t1, b.t1) << at;
  EXPECT_EQ(a.t2, b.t2) << at;
  EXPECT_EQ(a.period, b.period) << at;
  EXPECT_EQ(a.admissible, b.admissible) << at;
  EXPECT_TRUE(a.margin == b.margin || (std::isnan(a.margin) && std::isnan(b.margin))) << at;
  EXPECT_EQ(a.closure, b.closure) << at;
  EXPECT_EQ(a.energy, b.energy) << at;
  EXPECT_EQ(a.x0, b.x0) << at;
  EXPECT_EQ(a.v0, b.v0) << at;
  EXPECT_TRUE(a.spectral_radius == b.spectral_radius ||
              (std::isnan(a.spectral_radius) && std::isnan(b.spectral_radius)))
      << at;
}
}  // namespace

// write, read, compare every field of a continuation: the chain's branch through its SPP near (5.707, 2.510) for k5 in
// [0.9, 1], which loses or gains stability at k5 = 0.983578 (its crossing fields included); an edited crossing that
// contradicts its multipliers is refused, and a file without the crossing fields (written before them) reads None.
TEST(Io, ContinuationFileGivesBackTheResultThatWasWritten) {
  const ParametricSystem ps = chain_k5();
  const ContinuationResult r = chain_k5_branch(ps);
  ASSERT_EQ(r.branches.size(), 1u);
  int stability_events = 0;
  for (const BranchEvent& e : r.branches[0].events) stability_events += e.crossing != MultiplierCrossing::None;
  ASSERT_GE(stability_events, 1) << r.brief_report();
  const std::string text = continuation_json(ps, r);
  const ContinuationFile back = parse_continuation_file(text, "c.json");
  EXPECT_EQ(back.system.parameter().name, "k5");
  EXPECT_EQ(back.result.status, r.status);
  EXPECT_EQ(back.result.symmetry, r.symmetry);
  EXPECT_EQ(back.result.t1_min, r.t1_min);
  EXPECT_EQ(back.result.t2_max, r.t2_max);
  EXPECT_EQ(back.result.warnings, r.warnings);
  EXPECT_EQ(back.result.corrector_solves, r.corrector_solves);
  EXPECT_EQ(back.result.seconds, r.seconds);
  ASSERT_EQ(back.result.branches.size(), 1u);
  const Branch &a = r.branches[0], &b = back.result.branches[0];
  ASSERT_EQ(a.points.size(), b.points.size());
  for (size_t i = 0; i < a.points.size(); ++i)
    expect_same_point(a.points[i], b.points[i], "point " + std::to_string(i));
  ASSERT_EQ(a.events.size(), b.events.size());
  for (size_t i = 0; i < a.events.size(); ++i) {
    const std::string at = "event " + std::to_string(i);
    expect_same_point(a.events[i].at, b.events[i].at, at);
    EXPECT_EQ(a.events[i].kind, b.events[i].kind) << at;
    EXPECT_EQ(a.events[i].detail, b.events[i].detail) << at;
    EXPECT_EQ(a.events[i].crossing, b.events[i].crossing) << at;
    EXPECT_EQ(a.events[i].crossing_multipliers, b.events[i].crossing_multipliers) << at;
    EXPECT_TRUE(a.events[i].crossing_angle == b.events[i].crossing_angle ||
                (std::isnan(a.events[i].crossing_angle) && std::isnan(b.events[i].crossing_angle)))
        << at;
  }
  // edits: a crossing named against its multipliers, a crossing on another kind of event, a file from before
  io::json j = io::json::parse(text);
  size_t k = 0;
  while (!j["branches"][0]["events"][k].contains("crossing")) ++k;
  io::json& ev = j["branches"][0]["events"][k];
  const auto refusal = continuation_refusal;
  const std::string kind = ev["crossing"];
  ev["crossing"] = kind == "complex_pair" ? "plus_one" : "complex_pair";
  EXPECT_NE(refusal(j).find("c.json: field \"branches\"[0]: field \"events\"[" + std::to_string(k) +
                            "]: field \"crossing_multipliers\" must be "),
            std::string::npos)
      << refusal(j);
  ev["crossing"] = kind;
  ev["crossing_angle"] = 0.5 + ev["crossing_angle"].get<double>();
  EXPECT_NE(refusal(j).find("field \"crossing_angle\" must be |arg| of the crossing multiplier"), std::string::npos)
      << refusal(j);
  ev["crossing_angle"] = ev["crossing_angle"].get<double>() - 0.5;
  EXPECT_EQ(refusal(j), "(accepted)");
  ev["event"] = "fold";
  EXPECT_NE(refusal(j).find("field \"crossing\" belongs to stability events only, got it on a fold event"),
            std::string::npos)
      << refusal(j);
  ev["event"] = "sideways";
  EXPECT_NE(refusal(j).find("field \"event\" must be one of leaves_window, "), std::string::npos) << refusal(j);
  for (const char* f : {"crossing", "crossing_multipliers", "crossing_angle"}) ev.erase(f);
  ev["event"] = to_string(a.events[k].kind);
  const ContinuationFile old = parse_continuation_file(j.dump(), "old.json");
  EXPECT_EQ(old.result.branches[0].events[k].crossing, MultiplierCrossing::None);
}

// Found by an independent attack (issue 11): "K.mtx\u0000junk" opened K.mtx, the path cut at the NUL by the system.
TEST(Io, NulByteInAMatrixMarketPathIsRefusedNamingTheField) {
  const fs::path d = tmpdir();
  write(d / "I.mtx", "%%MatrixMarket matrix array real general\n2 2\n1\n0\n0\n1\n");
  expect_load_refused(R"({"M": {"matrix_market": "I.mtx\u0000junk"}, "K": [[2,-1],[-1,1]], "w": [0,-1], "g0": 1})",
                      "field \"M\": field \"matrix_market\": expected a file path of printable characters, got the "
                      "control character 0 at byte 5 (a NUL byte");
  // the sparse loader (spp reduce) the same
  write(d / "nul_sparse.json", R"({"M": [[1,0],[0,1]], "K": {"matrix_market": "I.mtx\u0000"}, "w": [0,-1], "g0": 1})");
  try {
    load_sparse_system((d / "nul_sparse.json").string());
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("field \"K\": field \"matrix_market\": expected a file path"),
              std::string::npos)
        << e.what();
  }
  // and any path given to the library with a NUL in it
  EXPECT_THROW(read_file((d / "I.mtx").string() + std::string(1, '\0') + "x"), std::invalid_argument);
  EXPECT_THROW(read_matrix_market((d / "I.mtx").string() + std::string(1, '\0') + "x"), std::invalid_argument);
}

// Found by an independent attack (issue 11): a NUL byte ended the JSON for the parser, so "{...}\0garbage" was read as
// "{...}". A UTF-8 byte-order mark before the text is accepted (editors write one); a NUL anywhere, or any text after
// the value, is refused with its byte offset.
TEST(Io, NulByteOrTrailingTextAfterTheJsonIsRefusedWithItsByteOffset) {
  const std::string sys = R"({"M": [[1,0],[0,1]], "K": [[2,-1],[-1,1]], "w": [0,-1], "g0": 1})";
  const std::string bom = "\xEF\xBB\xBF";
  const fs::path p = tmpdir() / "bom.json";
  write(p, bom + sys + "\n");
  EXPECT_EQ(load_system(p.string()).n(), 2);  // the BOM alone is accepted
  expect_load_refused(bom + sys + std::string(1, '\0'),
                      "expected JSON text, got a NUL byte at byte offset " + std::to_string(bom.size() + sys.size()));
  expect_load_refused(sys + std::string(1, '\0') + "garbage",
                      "got a NUL byte at byte offset " + std::to_string(sys.size()));
  expect_load_refused(sys + " garbage", "malformed JSON at byte offset " + std::to_string(sys.size() + 1));
}

// Found by an independent attack (issue 11): words after the symmetry were ignored, a header of another kind read
// as this one.
TEST(Io, MatrixMarketHeaderWithExtraWordsIsRefusedNamingLineOne) {
  const fs::path d = tmpdir();
  write(d / "extra.mtx", "%%MatrixMarket matrix coordinate real symmetric extra\n2 2 2\n1 1 1\n2 2 1\n");
  expect_load_refused(R"({"M": {"matrix_market": "extra.mtx"}, "K": [[2,-1],[-1,1]], "w": [0,-1], "g0": 1})",
                      "extra.mtx:1: expected the header \"%%MatrixMarket matrix <format> <field> <symmetry>\" (five "
                      "words), got the extra word \"extra\"");
  write(d / "five.mtx", "%%MatrixMarket matrix coordinate real symmetric  \n2 2 2\n1 1 1\n2 2 1\n");
  write(d / "five.json", R"({"M": {"matrix_market": "five.mtx"}, "K": [[2,-1],[-1,1]], "w": [0,-1], "g0": 1})");
  EXPECT_EQ(load_system((d / "five.json").string()).n(), 2);  // (trailing blanks are no word)
}

// Found by an independent attack (issue 11): "curve_pieces": 2^63 was read through a long as -9223372036854775808.
// Every count is a whole number from 0 to the largest value of the field it is read into.
TEST(Io, CountBeyondItsRangeInAResultIsRefusedNotReadNegative) {
  const System s = chain(3, {1.0}, {1.0}, 2, ContactSide::Upper, 1.0);
  SolveOptions o;
  o.t1_max = o.t2_max = 6.0;
  const io::json good = io::result_to_json(s, solve(s, o));
  const auto refusal = result_refusal;
  io::json j = good;
  j["stats"]["curve_pieces"] = std::uint64_t{1} << 63;
  EXPECT_NE(refusal(j).find("field \"curve_pieces\" must be a count, a whole number from 0 to 9223372036854775807, "
                            "got 9223372036854775808"),
            std::string::npos)
      << refusal(j);
  j = good;
  j["stats"]["flight_pole_lines"] = 4294967296LL;  // an int field
  EXPECT_NE(refusal(j).find("field \"flight_pole_lines\" must be a count, a whole number from 0 to 2147483647, got "
                            "4294967296"),
            std::string::npos)
      << refusal(j);
  j = good;
  j["stats"]["evaluations"] = 3.5;
  EXPECT_NE(refusal(j).find("field \"evaluations\" must be a count"), std::string::npos) << refusal(j);
  j = good;
  j["stats"]["evaluations"] = 9223372036854775807LL;  // the largest long is read as it is
  EXPECT_EQ(refusal(j), "(accepted)");
}

// Found by an independent attack (issue 11): a 100 MB "name" was read whole and copied into every table and result.
TEST(Io, NameOrDescriptionBeyondItsLimitIsRefusedNamingTheField) {
  const std::string rest = R"("M": [[1,0],[0,1]], "K": [[2,-1],[-1,1]], "w": [0,-1], "g0": 1})";
  expect_load_refused(R"({"name": ")" + std::string(4097, 'a') + "\", " + rest,
                      "field \"name\": expected at most 4096 bytes, got 4097");
  expect_load_refused(R"({"description": ")" + std::string(65537, 'a') + "\", " + rest,
                      "field \"description\": expected at most 65536 bytes, got 65537");
  const fs::path p = tmpdir() / "long_name_ok.json";
  write(p, R"({"name": ")" + std::string(4096, 'a') + "\", " + rest);
  EXPECT_EQ(load_system(p.string()).name().size(), 4096u);
  // a parametric system's parameter name is a name too
  const fs::path q = tmpdir() / "long_parameter.json";
  write(q, R"({"parameter": {"name": ")" + std::string(5000, 'k') +
               R"(", "min": 1, "max": 2}, "M": [[1,0],[0,1]], "K": [[2,-1],[-1,1]], "w": [0,-1], "g0": 1})");
  try {
    load_parametric_system(q.string());
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("field \"parameter\": field \"name\": expected at most 4096 bytes, got 5000"),
              std::string::npos)
        << e.what();
  }
}

// Found by the attack of issue 11: a result file with an SPP listed twice (roots + 1), a return_error of -5 or null,
// or an energy that is not the state's (doubled) read as written.
TEST(Io, ResultWithADuplicatedSppABadReturnErrorOrAnotherEnergyIsRefused) {
  const System s = chain(3, {1.0}, {1.0}, 2, ContactSide::Upper, 1.0);
  SolveOptions o;
  o.t1_max = o.t2_max = 6.0;
  const io::json good = io::result_to_json(s, solve(s, o));
  const auto refusal = result_refusal;
  ASSERT_EQ(refusal(good), "(accepted)");
  ASSERT_GE(good["solutions"].size(), 2u);
  io::json j = good;
  j["solutions"].insert(j["solutions"].begin() + 1, j["solutions"][1]);
  j["stats"]["roots"] = j["stats"]["roots"].get<long>() + 1;
  EXPECT_NE(refusal(j).find("r.json: field \"solutions\"[2] is at (t1, t2)"), std::string::npos) << refusal(j);
  EXPECT_NE(refusal(j).find("expected each SPP listed once, got one twice"), std::string::npos) << refusal(j);
  for (const io::json& bad : {io::json(-5.0), io::json(nullptr), io::json(-0.5)}) {
    j = good;
    j["solutions"][0]["return_error"] = bad;
    EXPECT_NE(refusal(j).find("r.json: field \"solutions\"[0]: field \"return_error\": expected a finite number >= 0, "
                              "or -1 (not computed)"),
              std::string::npos)
        << refusal(j);
  }
  j = good;
  j["solutions"][0]["return_error"] = -1.0;  // not computed
  EXPECT_EQ(refusal(j), "(accepted)");
  j = good;
  const double e = j["solutions"][0]["energy"];
  j["solutions"][0]["energy"] = 2.0 * e;
  j["solutions"][0]["orbit"]["energy"] = 2.0 * e;
  EXPECT_NE(refusal(j).find("r.json: field \"solutions\"[0]: field \"energy\" is "), std::string::npos) << refusal(j);
  EXPECT_NE(refusal(j).find("but 1/2 v0^T M v0 + 1/2 x0^T K x0 with the file's system is"), std::string::npos)
      << refusal(j);
}

// Found by the attack of issue 11: an axial result relabelled point-symmetric read as point-symmetric SPPs.
TEST(Io, ResultRelabelledToAnotherSymmetryIsRefused) {
  const System s = chain(3, {1.0}, {1.0}, 2, ContactSide::Upper, 1.0);
  SolveOptions o;
  o.t1_max = o.t2_max = 6.0;
  io::json j = io::result_to_json(s, solve(s, o));
  j["symmetry"] = "point";
  std::string what = "(accepted)";
  try {
    parse_result_file(j.dump(), "r.json");
  } catch (const std::invalid_argument& e) {
    what = e.what();
  }
  EXPECT_NE(what.find("r.json: field \"solutions\"[0]: field \"symmetry\" is \"point\": expected the flag "
                      "\"point_symmetric\""),
            std::string::npos)
      << what;
}

// Found by the attack of issue 11: the continuation reader took unknown fields, "success" beside stalled branches or
// warnings, t1 -3 or null, a parameter beyond its range, x0 of length 1, a negative energy, an empty window, a
// duplicated branch and an edited embedded system; to_json wrote a result beside another system.
TEST(Io, ContinuationFileThatContradictsItselfOrItsSystemIsRefused) {
  const ParametricSystem ps = chain_k5();
  const ContinuationResult r = chain_k5_branch(ps);
  ASSERT_EQ(r.status, ContinuationStatus::Success) << r.brief_report();
  const io::json good = io::json::parse(continuation_json(ps, r));
  const auto refusal = continuation_refusal;
  ASSERT_EQ(refusal(good), "(accepted)");
  auto expect = [&](const io::json& x, const std::string& part) {
    EXPECT_NE(refusal(x).find(part), std::string::npos) << refusal(x);
  };
  io::json j = good;
  j["extra"] = 1;
  expect(j, "c.json: unknown field \"extra\"");
  j = good;
  j["branches"][0]["points"][0]["colour"] = 1;
  expect(j, "unknown field \"colour\"");
  j = good;
  j["stats"]["stalled_branches"] = 3;
  expect(j, "c.json: field \"status\" is \"success\" but the file has 0 incomplete seed solves, 3 stalled branches");
  j = good;
  j["warnings"].push_back("something");
  expect(j, "1 warnings: expected none of them, or status \"incomplete\"");
  const std::string p0 = "c.json: field \"branches\"[0]: field \"points\"[0]: ";
  j = good;
  j["branches"][0]["points"][0]["t1"] = -3.0;
  expect(j, p0 + "fields \"t1\" and \"t2\": expected positive finite numbers, got -3");
  j = good;
  j["branches"][0]["points"][0]["t1"] = nullptr;
  expect(j, p0 + "fields \"t1\" and \"t2\": expected positive finite numbers, got nan");
  j = good;
  j["branches"][0]["points"][0]["k5"] = 7.0;
  expect(j, p0 + "field \"k5\": expected a value in the parameter's range [0.90000000000000002, 1], got 7");
  j = good;
  j["branches"][0]["points"][0]["x0"] = {1.0};
  expect(j, p0 + "expected x0 and v0 of the system's 5 dofs, got 1 and 5");
  j = good;
  j["branches"][0]["points"][0]["energy"] = -1.0;
  expect(j, p0 + "field \"energy\": expected a finite number >= 0, got -1");
  j = good;
  j["window"]["t1_min"] = 9.0;
  expect(j, "c.json: field \"window\": expected 0 <= t1_min < t1_max < inf, got t1_min = 9 and t1_max = 8");
  j = good;
  j["branches"].push_back(j["branches"][0]);
  expect(j, "c.json: field \"branches\"[1]: expected each branch once, got the points of \"branches\"[0] again");
  j = good;
  j["system"]["K"]["constant"][0][0] = 2.5;  // the embedded system edited: its points are not its SPPs
  expect(j, p0 + "field \"energy\" is ");
  // to_json beside another system (as SolveResult's): refused, naming the point
  Eigen::MatrixXd K0b = ps.K_constant();
  K0b(0, 0) = 2.5;
  const ParametricSystem other(Eigen::MatrixXd::Identity(5, 5), {}, K0b, ps.K_mu(), ps.w_constant(), {}, 1.0,
                               {"k5", 0.9, 1.0});
  std::string what = "(accepted)";
  try {
    continuation_json(other, r);
  } catch (const std::invalid_argument& e) {
    what = e.what();
  }
  EXPECT_NE(what.find("continuation_to_json: branch 0, point 0 (its points, then its events): field \"energy\" is "),
            std::string::npos)
      << what;
  EXPECT_NE(what.find("the result is another system's"), std::string::npos) << what;
}
