// Run by ctest under mpirun -n 2 (tests/CMakeLists.txt): solve_mpi gives exactly solve()'s result on the paper's
// examples and a random system, with one and two threads per rank; a failing unit is reported on every rank; the
// sweep over the ranks gives the serial sweep's table and resumes from the files already written. Every test is
// collective (all ranks call the same functions); rank 0 checks.
#include <gtest/gtest.h>
#include <mpi.h>

#include <filesystem>
#include <numbers>
#include <set>

#include "paper_examples.hpp"
#include "paper_reference.hpp"
#include "spp/core/generators.hpp"
#include "spp/distributed/mpi.hpp"
#include "spp/io.hpp"
#include "spp/modal/modal.hpp"

namespace fs = std::filesystem;
using namespace spp;

namespace {

int rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

int ranks() {
  int s = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &s);
  return s;
}

std::string untimed(const System& s, SolveResult r) {
  r.stats.seconds = 0.0;
  return result_json(s, r);
}

SolveOptions window(double t1, double t2, int threads) {
  SolveOptions o;
  o.t1_max = t1;
  o.t2_max = t2;
  o.threads = threads;
  return o;
}

void expect_serial_result(const System& s, const SolveOptions& o) {
  const ModalForm md(s);
  const SolveResult distributed = solve_mpi(s, md, o, MPI_COMM_WORLD);
  if (rank() != 0) {
    EXPECT_EQ(distributed.status, SolveStatus::NotRun);
    return;
  }
  SolveOptions serial = o;
  serial.threads = 1;
  const SolveResult whole = solve(s, md, serial);
  EXPECT_GT(whole.solutions.size(), 0u);
  EXPECT_EQ(untimed(s, distributed), untimed(s, whole));
}

// A directory all ranks name alike (rank 0's pid), emptied and created by rank 0.
fs::path shared_dir(const std::string& name) {
  long pid = static_cast<long>(::getpid());
  MPI_Bcast(&pid, 1, MPI_LONG, 0, MPI_COMM_WORLD);
  const fs::path d = fs::temp_directory_path() / ("spp_test_mpi_" + std::to_string(pid)) / name;
  if (rank() == 0) {
    fs::remove_all(d);
    fs::create_directories(d);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  return d;
}

std::string two_dof_k2_file() {
  const fs::path d = shared_dir("system");
  const fs::path p = d / "two_dof_k2.json";
  if (rank() == 0) {
    const ParametricSystem ps =
        parametrize([](double k2) { return two_dof(1.0, 1.0, 1.0, k2, 1.0); }, Parameter{"k2", 1.0, 10.0});
    write_file_atomic(p.string(), parametric_system_json(ps));
  }
  MPI_Barrier(MPI_COMM_WORLD);
  return p.string();
}

std::vector<double> twenty_values() {
  std::vector<double> v;
  for (int i = 0; i < 20; ++i) v.push_back(1.0 + 0.25 * i);
  return v;
}

void expect_same_rows(const SweepTable& a, const SweepTable& b) {
  ASSERT_EQ(a.rows.size(), b.rows.size());
  for (size_t r = 0; r < a.rows.size(); ++r) {
    EXPECT_EQ(a.rows[r].index, b.rows[r].index);
    EXPECT_EQ(a.rows[r].value, b.rows[r].value);
    EXPECT_EQ(a.rows[r].t1, b.rows[r].t1);
    EXPECT_EQ(a.rows[r].t2, b.rows[r].t2);
    EXPECT_EQ(a.rows[r].energy, b.rows[r].energy);
    EXPECT_EQ(a.rows[r].admissible, b.rows[r].admissible);
  }
  EXPECT_EQ(a.solve_status, b.solve_status);
}

}  // namespace

TEST(MpiSolve, RunsOnTwoRanks) {
  EXPECT_EQ(ranks(), 2) << "run under mpirun -n 2";
}

TEST(MpiSolve, ChainGivesTheSerialResult) {
  expect_serial_result(test::chain5(), window(12.0, 12.0, 1));
}

TEST(MpiSolve, RodGivesTheSerialResult) {
  expect_serial_result(test::rod4(), window(12.0, 12.0, 1));
}

TEST(MpiSolve, RandomSystemGivesTheSerialResult) {
  const System s = ref::random_system(5, 7u, 1.0, 0.5, 6.0);
  const ModalForm md(s);
  expect_serial_result(s, window(2.0 * std::numbers::pi / md.omega()(0), 2.0 * std::numbers::pi / md.d()(1), 1));
}

TEST(MpiSolve, TwoThreadsPerRankGiveTheSerialResult) {
  expect_serial_result(test::chain5(), window(12.0, 12.0, 2));
}

TEST(MpiSolve, EveryUnitIsDoneOnceAndTheOutputsComeInUnitOrder) {
  const size_t n = 57;
  std::vector<size_t> order(n);
  for (size_t j = 0; j < n; ++j) order[j] = (j * 13) % n;  // any permutation
  const auto out = distribute_units(MPI_COMM_WORLD, n, order, 2,
                                    [](size_t j) { return std::to_string(j) + "@" + std::to_string(rank()); });
  if (rank() != 0) {
    EXPECT_TRUE(out.empty());
    return;
  }
  ASSERT_EQ(out.size(), n);
  for (size_t j = 0; j < n; ++j) EXPECT_EQ(out[j].substr(0, out[j].find('@')), std::to_string(j));
}

TEST(MpiSolve, AFailingUnitIsReportedOnEveryRank) {
  const size_t n = 12;
  std::vector<size_t> order(n);
  for (size_t j = 0; j < n; ++j) order[j] = j;
  try {
    (void)distribute_units(MPI_COMM_WORLD, n, order, 1, [](size_t j) -> std::string {
      if (j == 5) throw std::invalid_argument("unit five is broken");
      return "ok";
    });
    ADD_FAILURE() << "no exception on rank " << rank();
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("unit five is broken"), std::string::npos) << e.what();
  }
}

TEST(MpiSweep, TwentyValuesGiveTheSerialSweepsTable) {
  const std::string file = two_dof_k2_file();
  const SolveOptions o = window(8.0, 8.0, 1);
  const Sweep spread = Sweep::over_values(file, "k2", twenty_values(), shared_dir("spread").string());
  const Sweep serial = Sweep::over_values(file, "k2", twenty_values(), shared_dir("serial").string());
  const auto outcomes = run_sweep_mpi(spread, o, MPI_COMM_WORLD);
  if (rank() != 0) {
    EXPECT_TRUE(outcomes.empty());
    return;
  }
  ASSERT_EQ(outcomes.size(), 20u);
  for (const auto& oc : outcomes) EXPECT_EQ(oc.status, SweepItemStatus::Solved) << oc.message;
  const SweepTable a = sweep_table(spread, outcomes), b = sweep_table(serial, run_sweep(serial, o));
  EXPECT_GT(a.rows.size(), 20u);
  expect_same_rows(a, b);
  for (size_t i = 0; i < 20; ++i)  // each value's file as the serial run writes it, but the time
    EXPECT_EQ(untimed(load_result_system(spread.items()[i].result_file), load_result(spread.items()[i].result_file)),
              untimed(load_result_system(serial.items()[i].result_file), load_result(serial.items()[i].result_file)));
}

TEST(MpiSweep, ResumesFromTheFilesWrittenAndReportsAFailingValue) {
  const std::string file = two_dof_k2_file();
  const SolveOptions o = window(8.0, 8.0, 1);
  std::vector<double> values = twenty_values();
  values[7] = -0.9;  // K not positive definite there
  const Sweep sweep = Sweep::over_values(file, "k2", values, shared_dir("resume").string());
  // an earlier run stopped after items 2, 3 and 11 (written by rank 0)
  const std::set<size_t> done = {2, 3, 11};
  std::vector<std::string> text;
  if (rank() == 0)
    for (size_t i : done) {
      EXPECT_EQ(run_sweep_item(sweep, i, o).status, SweepItemStatus::Solved);
      text.push_back(read_file(sweep.items()[i].result_file));
    }
  MPI_Barrier(MPI_COMM_WORLD);
  const auto outcomes = run_sweep_mpi(sweep, o, MPI_COMM_WORLD);
  if (rank() != 0) return;
  ASSERT_EQ(outcomes.size(), values.size());
  for (size_t i = 0; i < values.size(); ++i) {
    const SweepItemStatus expected = i == 7          ? SweepItemStatus::Failed
                                     : done.count(i) ? SweepItemStatus::Resumed
                                                     : SweepItemStatus::Solved;
    EXPECT_EQ(outcomes[i].status, expected) << i << ": " << outcomes[i].message;
  }
  EXPECT_NE(outcomes[7].message.find("k2 = -0.9"), std::string::npos) << outcomes[7].message;
  size_t k = 0;
  for (size_t i : done) EXPECT_EQ(read_file(sweep.items()[i].result_file), text[k++]);
  EXPECT_EQ(sweep_table(sweep, outcomes).failed(), 1);
}

int main(int argc, char** argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_SERIALIZED, &provided);
  ::testing::InitGoogleTest(&argc, argv);
  if (rank() != 0) {  // rank 0 reports; the others' failures still fail the run (their exit code)
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  const int code = RUN_ALL_TESTS();
  MPI_Finalize();
  return code;
}
