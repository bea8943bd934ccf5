// The window's work units traced apart (as on other processes) and merged give solve()'s result exactly, and the
// sweep: one result per value equal to solve()'s, resumed from the files already written, a failing value reported.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <numbers>

#include "paper_examples.hpp"
#include "paper_reference.hpp"
#include "spp/core/generators.hpp"
#include "spp/distributed/sweep.hpp"
#include "spp/distributed/window_work.hpp"
#include "spp/io.hpp"
#include "spp/modal/modal.hpp"

namespace fs = std::filesystem;
using namespace spp;

namespace {

// The result file's text without the time: equal texts are equal results (doubles written with 17 digits).
std::string untimed(const System& s, SolveResult r) {
  r.stats.seconds = 0.0;
  return result_json(s, r);
}

// Each unit traced by its own WindowWork (another process would build its own), last unit first; merged by a third.
SolveResult traced_apart(const System& s, const SolveOptions& o, size_t* units = nullptr) {
  const ModalForm md(s);
  std::vector<std::string> outputs;
  {
    const WindowWork probe(s, md, o);
    outputs.resize(probe.units());
  }
  for (size_t j = outputs.size(); j-- > 0;) {
    const WindowWork apart(s, md, o);
    outputs[j] = apart.trace_unit(j);
  }
  if (units) *units = outputs.size();
  const WindowWork merger(s, md, o);
  return merger.finish(outputs);
}

SolveOptions window(double t1, double t2) {
  SolveOptions o;
  o.t1_max = t1;
  o.t2_max = t2;
  return o;
}

void expect_same_as_solve(const System& s, const SolveOptions& o) {
  size_t units = 0;
  const SolveResult apart = traced_apart(s, o, &units);
  const SolveResult whole = solve(s, o);
  EXPECT_GT(units, 2u) << "too few units to test the merge";
  EXPECT_GT(whole.solutions.size(), 0u);
  EXPECT_EQ(untimed(s, apart), untimed(s, whole));
}

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("spp_test_sweep_" + std::to_string(::getpid())) / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// Paper §2.3's 2-dof system with g0 = 1, the second spring k2 the parameter (in [1, 10]).
std::string two_dof_k2_file() {
  const ParametricSystem ps =
      parametrize([](double k2) { return two_dof(1.0, 1.0, 1.0, k2, 1.0); }, Parameter{"k2", 1.0, 10.0});
  const fs::path p = temp_dir("system") / "two_dof_k2.json";
  write_file_atomic(p.string(), parametric_system_json(ps));
  return p.string();
}

SolveOptions sweep_window() {
  return window(8.0, 8.0);
}

}  // namespace

TEST(WindowWork, UnitsTracedApartGiveSolvesResultOnTheChain) {
  expect_same_as_solve(test::chain5(), window(12.0, 12.0));
}

TEST(WindowWork, UnitsTracedApartGiveSolvesResultOnTheRod) {
  expect_same_as_solve(test::rod4(), window(12.0, 12.0));
}

TEST(WindowWork, UnitsTracedApartGiveSolvesResultOnARandomSystem) {
  const System s = ref::random_system(5, 7u, 1.0, 0.5, 6.0);
  const ModalForm md(s);
  expect_same_as_solve(s, window(2.0 * std::numbers::pi / md.omega()(0), 2.0 * std::numbers::pi / md.d()(1)));
}

TEST(WindowWork, UnitsTracedApartGiveSolvesResultWithoutCertificates) {
  SolveOptions o = window(12.0, 12.0);
  o.certify_steps = false;
  expect_same_as_solve(test::chain5(), o);
}

TEST(WindowWork, RefusesOutputsOfAnotherUnitOrWindowOrCutShort) {
  const System s = test::chain5();
  const ModalForm md(s);
  const WindowWork w(s, md, window(12.0, 12.0));
  std::vector<std::string> outputs;
  for (size_t j = 0; j < w.units(); ++j) outputs.push_back(w.trace_unit(j));
  auto refused = [&](std::vector<std::string> o, const std::string& what) {
    try {
      (void)w.finish(o);
      ADD_FAILURE() << "accepted " << what;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("unit"), std::string::npos) << e.what();
    }
  };
  auto swapped = outputs;
  std::swap(swapped[0], swapped[1]);
  refused(swapped, "two units swapped");
  auto cut = outputs;
  cut[1].pop_back();
  refused(cut, "an output cut short");
  auto longer = outputs;
  longer[1] += "x";
  refused(longer, "bytes after an output");
  refused(std::vector<std::string>(outputs.begin(), outputs.end() - 1), "one output missing");
  const WindowWork other(s, md, window(11.0, 12.5));
  std::vector<std::string> theirs;
  for (size_t j = 0; j < other.units(); ++j) theirs.push_back(other.trace_unit(j));
  if (theirs.size() == outputs.size()) refused(theirs, "the outputs of another window");
  EXPECT_THROW((void)w.trace_unit(w.units()), std::invalid_argument);
}

TEST(WindowWork, UnitCostsAreTheStripsCellsTimesTheirWidths) {
  // the strips tile the searched t2-range: their widths add up to it (the window (0, 12], from the axis band's half
  // to a hair beyond 12)
  const System s = test::chain5();
  const ModalForm md(s);
  const WindowWork w(s, md, window(12.0, 12.0));
  double span = 0.0;
  for (size_t j = 0; j < w.units(); ++j) {
    EXPECT_GT(w.unit_cost(j), 0.0);
    span += w.unit_cost(j) / static_cast<double>(w.unit_cells(j));
  }
  EXPECT_GT(span, 11.9);
  EXPECT_LT(span, 12.1);
  EXPECT_THROW((void)w.unit_cost(w.units()), std::invalid_argument);
}

TEST(WindowWork, RefusesWhatSolveRefuses) {
  const System s = test::chain5();
  const ModalForm md(s);
  EXPECT_THROW(WindowWork(s, md, window(-1.0, 12.0)), std::invalid_argument);
  const System other = test::rod4();
  EXPECT_THROW(WindowWork(s, ModalForm(other), window(12.0, 12.0)), std::invalid_argument);
}

TEST(Sweep, RefusesAnotherParameterNameAFileWithoutParameterAndAMissingDirectory) {
  const std::string file = two_dof_k2_file();
  const std::string out = temp_dir("refusals").string();
  try {
    (void)Sweep::over_values(file, "k3", {1.0}, out);
    ADD_FAILURE() << "accepted another parameter's name";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("declares the parameter \"k2\""), std::string::npos) << e.what();
  }
  const std::string chain = std::string(SPP_SOURCE_DIR) + "/examples/chain5.json";
  EXPECT_THROW((void)Sweep::over_values(chain, "k2", {1.0}, out), std::invalid_argument);
  EXPECT_THROW((void)Sweep::over_values(file, "k2", {1.0}, out + "/missing"), std::invalid_argument);
  EXPECT_THROW((void)Sweep::over_values(file, "k2", {}, out), std::invalid_argument);
  EXPECT_THROW((void)Sweep::over_values(file, "k2", {std::nan("")}, out), std::invalid_argument);
  EXPECT_THROW((void)Sweep::over_files({}, out), std::invalid_argument);
}

TEST(Sweep, EachValuesResultIsSolvesAndTheTableListsEverySpp) {
  const std::string file = two_dof_k2_file();
  const std::vector<double> values = {1.0, 1.5, 2.0, 3.0};
  const Sweep sweep = Sweep::over_values(file, "k2", values, temp_dir("values").string());
  const SolveOptions o = sweep_window();
  const auto outcomes = run_sweep(sweep, o);
  const SweepTable t = sweep_table(sweep, outcomes);
  ASSERT_EQ(t.failed(), 0);
  const ParametricSystem ps = load_parametric_system(file);
  size_t row = 0;
  for (size_t i = 0; i < values.size(); ++i) {
    EXPECT_EQ(outcomes[i].status, SweepItemStatus::Solved);
    const System s = ps.at(values[i]);
    const SolveResult direct = solve(s, o);
    EXPECT_EQ(untimed(s, load_result(sweep.items()[i].result_file)), untimed(s, direct)) << "k2 = " << values[i];
    ASSERT_EQ(t.spps[i], static_cast<long>(direct.solutions.size()));
    for (const Solution& sol : direct.solutions) {
      ASSERT_LT(row, t.rows.size());
      EXPECT_EQ(t.rows[row].index, i);
      EXPECT_EQ(t.rows[row].value, values[i]);
      EXPECT_EQ(t.rows[row].t1, sol.t1());
      EXPECT_EQ(t.rows[row].t2, sol.t2());
      EXPECT_EQ(t.rows[row].admissible, sol.admissible());
      ++row;
    }
  }
  EXPECT_EQ(row, t.rows.size());
  EXPECT_GT(t.rows.size(), values.size());
  // the CSV: a header and one line per SPP
  const std::string csv = sweep_table_csv(t);
  EXPECT_EQ(csv.rfind("index,k2,system_file,result_file,solve_status,t1,t2", 0), 0u) << csv.substr(0, 80);
  EXPECT_EQ(static_cast<size_t>(std::count(csv.begin(), csv.end(), '\n')), t.rows.size() + 1);
}

TEST(Sweep, ResumesFromTheResultFilesAlreadyWrittenWithoutSolvingThemAgain) {
  const std::string file = two_dof_k2_file();
  const std::vector<double> values = {1.0, 1.5, 2.0, 3.0, 4.0};
  const SolveOptions o = sweep_window();
  const Sweep sweep = Sweep::over_values(file, "k2", values, temp_dir("resume").string());
  // a first run stopped after items 0 and 3
  for (size_t i : {0u, 3u}) ASSERT_EQ(run_sweep_item(sweep, i, o).status, SweepItemStatus::Solved);
  std::vector<fs::file_time_type> before;
  std::vector<std::string> text;
  for (size_t i : {0u, 3u}) {
    before.push_back(fs::last_write_time(sweep.items()[i].result_file));
    text.push_back(read_file(sweep.items()[i].result_file));
  }
  const auto outcomes = run_sweep(sweep, o);
  for (size_t i = 0; i < values.size(); ++i)
    EXPECT_EQ(outcomes[i].status, i == 0 || i == 3 ? SweepItemStatus::Resumed : SweepItemStatus::Solved) << i;
  size_t k = 0;
  for (size_t i : {0u, 3u}) {  // not written again
    EXPECT_EQ(fs::last_write_time(sweep.items()[i].result_file), before[k]);
    EXPECT_EQ(read_file(sweep.items()[i].result_file), text[k]);
    ++k;
  }
  // the same table as a sweep run at once
  const Sweep fresh = Sweep::over_values(file, "k2", values, temp_dir("resume_fresh").string());
  const SweepTable a = sweep_table(sweep, outcomes), b = sweep_table(fresh, run_sweep(fresh, o));
  ASSERT_EQ(a.rows.size(), b.rows.size());
  for (size_t r = 0; r < a.rows.size(); ++r) {
    EXPECT_EQ(a.rows[r].index, b.rows[r].index);
    EXPECT_EQ(a.rows[r].t1, b.rows[r].t1);
    EXPECT_EQ(a.rows[r].t2, b.rows[r].t2);
    EXPECT_EQ(a.rows[r].energy, b.rows[r].energy);
  }
}

TEST(Sweep, AFailingValueIsReportedAndTheOthersAreSolved) {
  const std::string file = two_dof_k2_file();
  // k2 = -0.9: K = [[0.1, 0.9], [0.9, -0.9]] is not positive definite
  const Sweep sweep = Sweep::over_values(file, "k2", {1.0, -0.9, 2.0}, temp_dir("failing").string());
  const auto outcomes = run_sweep(sweep, sweep_window());
  EXPECT_EQ(outcomes[0].status, SweepItemStatus::Solved);
  EXPECT_EQ(outcomes[1].status, SweepItemStatus::Failed);
  EXPECT_NE(outcomes[1].message.find("k2 = -0.9"), std::string::npos) << outcomes[1].message;
  EXPECT_EQ(outcomes[2].status, SweepItemStatus::Solved);
  EXPECT_FALSE(fs::exists(sweep.items()[1].result_file));
  const SweepTable t = sweep_table(sweep, outcomes);
  EXPECT_EQ(t.failed(), 1);
  EXPECT_NE(sweep_table_json(t).find("\"outcome\": \"failed\""), std::string::npos);
}

TEST(Sweep, AResultFileOfAnotherWindowIsNotReplaced) {
  const std::string file = two_dof_k2_file();
  const std::string dir = temp_dir("other_window").string();
  const Sweep sweep = Sweep::over_values(file, "k2", {1.5}, dir);
  ASSERT_EQ(run_sweep_item(sweep, 0, sweep_window()).status, SweepItemStatus::Solved);
  const std::string text = read_file(sweep.items()[0].result_file);
  const SweepItemOutcome o = run_sweep_item(sweep, 0, window(7.0, 8.0));
  EXPECT_EQ(o.status, SweepItemStatus::Failed);
  EXPECT_NE(o.message.find("already there"), std::string::npos) << o.message;
  EXPECT_EQ(read_file(sweep.items()[0].result_file), text);
  // and one of another system (the same file name in a sweep of another value)
  const Sweep moved = Sweep::over_values(file, "k2", {2.5}, dir);
  EXPECT_EQ(run_sweep_item(moved, 0, sweep_window()).status, SweepItemStatus::Failed);
}

TEST(Sweep, CheckSweepOutputsRefusesAResumeOfAnotherWindowOrOptionsBeforeAnySolve) {
  // issue 16: a refused resume rewrote the table with every item failed; now refused before anything is run, naming
  // the out-dir and what differs (window, symmetry, certify_steps, admissible_only inferred from the file)
  const std::string file = two_dof_k2_file();
  const std::string dir = temp_dir("check_outputs").string();
  const Sweep sweep = Sweep::over_values(file, "k2", {1.5, 2.5}, dir);
  EXPECT_NO_THROW(check_sweep_outputs(sweep, sweep_window()));  // nothing there yet
  ASSERT_EQ(run_sweep_item(sweep, 0, sweep_window()).status, SweepItemStatus::Solved);
  EXPECT_NO_THROW(check_sweep_outputs(sweep, sweep_window()));  // a resume of the same run
  auto refused = [&](const SolveOptions& o, const std::string& what) {
    try {
      check_sweep_outputs(sweep, o);
      ADD_FAILURE() << "accepted: " << what;
    } catch (const std::invalid_argument& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("\"" + dir + "\" holds results this sweep cannot resume from"), std::string::npos) << m;
      EXPECT_NE(m.find(what), std::string::npos) << m;
    }
  };
  refused(window(7.0, 8.0), "the window");
  SolveOptions point = sweep_window();
  point.symmetry = Symmetry::Point;
  refused(point, "the symmetry axial, not point as this sweep asks");
  SolveOptions midpoint = sweep_window();
  midpoint.certify_steps = false;
  refused(midpoint, "with certified steps");
  const SolveResult stored = load_result(sweep.items()[0].result_file);
  const bool inadmissible = std::any_of(stored.solutions.begin(), stored.solutions.end(),
                                        [](const Solution& s) { return !s.admissible(); });
  if (inadmissible) {
    SolveOptions admissible = sweep_window();
    admissible.admissible_only = true;
    refused(admissible, "with admissible_only off (non-admissible SPPs kept), not with it on");
  }
  // an out-dir that is a file; a value outside the declared range [1, 10] is noted
  EXPECT_THROW((void)Sweep::over_values(file, "k2", {1.5}, file), std::invalid_argument);
  try {
    (void)Sweep::over_values(file, "k2", {1.5}, file + "/x");
    ADD_FAILURE() << "an out-dir under a file accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("on its path is a file, not a directory"), std::string::npos) << e.what();
  }
  const Sweep outside = Sweep::over_values(file, "k2", {0.5, 2.0, 11.0}, dir);
  ASSERT_EQ(outside.notes().size(), 1u);  // one note for all (a sweep may have 1e6 values)
  EXPECT_NE(outside.notes()[0].find("value #1, k2 = 0.5, lies outside the range [1, 10]"), std::string::npos)
      << outside.notes()[0];
  EXPECT_NE(outside.notes()[0].find("and 1 more value: #3 (11)"), std::string::npos) << outside.notes()[0];
}

TEST(Sweep, OverSystemFilesAnUnreadableFileFailsItsItemOnly) {
  const std::string chain = std::string(SPP_SOURCE_DIR) + "/examples/chain5.json";
  const Sweep sweep = Sweep::over_files({chain, chain + ".missing"}, temp_dir("files").string());
  const auto outcomes = run_sweep(sweep, window(6.0, 6.0));
  EXPECT_EQ(outcomes[0].status, SweepItemStatus::Solved);
  EXPECT_EQ(outcomes[1].status, SweepItemStatus::Failed);
  const SweepTable t = sweep_table(sweep, outcomes);
  EXPECT_GT(t.rows.size(), 0u);
  EXPECT_TRUE(std::isnan(t.rows[0].value));
  EXPECT_EQ(sweep_table_csv(t).rfind("index,value,", 0), 0u);
}
