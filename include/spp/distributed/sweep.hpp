#pragma once
// A sweep: one solve() per parameter value of a parametric system, or per system file, each result written to its
// own file (atomically, as spp solve --json writes it), then one table of every SPP with its value (CSV / JSON, for a
// frequency-energy or parameter plot). A sweep that was stopped resumes: an item whose result file is already there
// (and holds that item's system and window) is read, not solved again. A failing item (a value where the system is
// not positive definite, an unreadable file) is reported in its outcome, never fatal to the others.
// The items are independent: run_sweep_item may run them on any thread or process (distributed/mpi_sweep.hpp).
// Cost: per item that of solve() on its window (plus O(n^3) for the system and its modal form); the table reads
// every result file back.

#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "spp/core/parametric.hpp"
#include "spp/core/system.hpp"
#include "spp/search/solver.hpp"

namespace spp {

/// One solve of a sweep.
struct SweepItem {
  size_t index = 0;
  double value = std::numeric_limits<double>::quiet_NaN();  ///< the parameter's value (NaN in a sweep over files)
  std::string system_file;  ///< the system file (a parameter sweep: the parametric file, the same for all)
  std::string result_file;  ///< its result (spp solve's JSON), in the sweep's output directory
};

class Sweep {
 public:
  /// Over values of the parameter that the parametric system file declares: `parameter` must be its name (a slip is
  /// refused naming both). Result files "<out_dir>/<parameter>_<index, 4 digits>.json". Throws std::invalid_argument
  /// naming what is wrong: an unreadable file, another parameter name, no value, a value not finite (named by its
  /// number from 1 and its position from 0), out_dir missing or not a directory. A value outside the declared range
  /// is kept, with a note (notes()).
  static Sweep over_values(const std::string& parametric_file, const std::string& parameter,
                           const std::vector<double>& values, const std::string& out_dir);
  /// Over system files (not parametric ones). Result files "<out_dir>/<index, 4 digits>_<file's stem>.json". Throws
  /// std::invalid_argument for no file or out_dir not a directory (each file is read by its own item: one unreadable
  /// file fails that item only).
  static Sweep over_files(const std::vector<std::string>& files, const std::string& out_dir);

  const std::vector<SweepItem>& items() const { return items_; }
  /// The parameter's name; empty for a sweep over files.
  const std::string& parameter() const { return parameter_; }
  /// The output directory of the result files.
  const std::string& out_dir() const { return out_dir_; }
  /// Notes for the user, one a line: the values outside the range [min, max] the parametric file declares, in one
  /// note naming the first and at most 5 more (the system is validated at each value: where it is not positive
  /// definite the item fails). Empty for files, or when every value lies in the range.
  const std::vector<std::string>& notes() const { return notes_; }
  /// The system of item i (loaded, or the parametric system at the item's value). Throws std::invalid_argument naming
  /// the file or the value (e.g. not positive definite there).
  System system(size_t i) const;

 private:
  std::string parameter_, out_dir_;
  std::vector<std::string> notes_;
  std::vector<SweepItem> items_;
  std::vector<ParametricSystem> parametric_;  // one (parameter sweeps) or none
};

enum class SweepItemStatus {
  NotRun,   ///< default
  Solved,   ///< solved by this run, result file written
  Resumed,  ///< its result file was already there (an earlier run): read, not solved again
  Failed,   ///< no result: SweepItemOutcome::message says why
};
const char* to_string(SweepItemStatus s);

struct SweepItemOutcome {
  SweepItemStatus status = SweepItemStatus::NotRun;
  std::string message;  ///< why it failed (empty otherwise)
};

/// Before any solve and any file written: the output directory can be written (a probe file is created and
/// removed), and every result file already there is one this sweep resumes from: it holds its item's system, the
/// symmetry and window of `options`, and was solved with the same certify_steps and admissible_only (inferred from
/// the file: steps certified only with certify_steps; SPPs dropped, or a non-admissible one kept). Throws
/// std::invalid_argument naming the output directory, the first file that differs and what differs (a resumed sweep
/// with other options would mix results; run_sweep_item would fail that item only, and the table would be rewritten
/// with it failed). An item whose system cannot be built is left to fail on its own. Cost: per file there, reading it
/// and the item's modal form (O(n^3)).
void check_sweep_outputs(const Sweep& sweep, const SolveOptions& options);

/// Solves item i with `options` (the window, and options.threads for this solve) and writes its result file
/// atomically; or reads it back when it is there already and holds this item's system, symmetry and window (t1_max,
/// t2_max; t1_min, t2_min when given; certify_steps and admissible_only as check_sweep_outputs infers them). A result
/// file of another system, window or options is not replaced: the item fails, naming the file. Never throws for an item's own failure (Failed with the message); throws std::invalid_argument
/// for i out of range or invalid options.
SweepItemOutcome run_sweep_item(const Sweep& sweep, size_t i, const SolveOptions& options);

/// Every item, in order, on this process (each solve with options.threads threads). on_done, if given, is called
/// after each item (e.g. to print a line).
std::vector<SweepItemOutcome> run_sweep(const Sweep& sweep, const SolveOptions& options,
                                        const std::function<void(size_t, const SweepItemOutcome&)>& on_done = {});

/// One SPP of the sweep's table.
struct SweepRow {
  size_t index = 0;
  double value = std::numeric_limits<double>::quiet_NaN();
  double t1 = 0, t2 = 0, period = 0, energy = 0, min_gap = 0, min_force = 0;
  bool admissible = false;
};

/// The merged table, read from the result files of the items that did not fail.
struct SweepTable {
  std::string parameter;                   ///< empty for a sweep over files
  std::vector<SweepItem> items;            ///< every item
  std::vector<SweepItemOutcome> outcomes;  ///< outcome of each item
  std::vector<SolveStatus> solve_status;   ///< status of each item's solve (NotRun when it failed)
  std::vector<long> spps;                  ///< SPPs of each item (0 when it failed)
  std::vector<SweepRow> rows;              ///< every SPP, items in order, each item's SPPs by period
  long failed() const;
  /// "sweep over k2: 20 values, 20 solved (0 resumed), 0 failed, 37 SPPs (21 admissible)".
  std::string brief_report() const;
};
/// Throws std::invalid_argument when outcomes does not match the items, or a result file of a successful item can
/// no longer be read.
SweepTable sweep_table(const Sweep& sweep, const std::vector<SweepItemOutcome>& outcomes);
/// index, <parameter> (or "value"), system_file, result_file, solve_status, t1, t2, period, admissible, min_gap,
/// min_force, energy: one row per SPP, each double in its shortest text that reads back to it (2.1, as in the JSON and
/// on stderr, not 2.1000000000000001).
std::string sweep_table_csv(const SweepTable& table);
/// {"parameter", "items": [{"index", "value", "system_file", "result_file", "outcome", "message", "solve_status",
/// "spps": [{"t1", "t2", "period", "admissible", "min_gap", "min_force", "energy"}]}]}.
std::string sweep_table_json(const SweepTable& table, int indent = 2);

}  // namespace spp
