// Sweeps (spp/distributed/sweep.hpp) for python/spp/sweep.py, which spreads the items over mpi4py ranks or a process
// pool: each item is run from plain, picklable arguments (the files, the parameter and its values, the output
// directory, the SolveOptions fields), the sweep's plan rebuilt where it runs (reading the system file, O(its size)).
#include <memory>

#include "common.hpp"
#include "spp/detail/dense_products.hpp"
#include "spp/detail/invalid.hpp"
#include "spp/distributed/sweep.hpp"
#include "spp/io/files.hpp"

namespace spp::python {

namespace {

Sweep plan(const std::vector<std::string>& systems, const py::object& parameter, const py::object& values,
           const std::string& out_dir) {
  if (parameter.is_none() != values.is_none())
    detail::invalid(
        std::string("sweep: parameter and values go together (a sweep over a parametric system's parameter); "
                    "without them, give system files: expected both or neither, got only ") +
        (parameter.is_none() ? "values" : "parameter"));
  if (parameter.is_none()) return Sweep::over_files(systems, out_dir);
  if (systems.size() != 1)
    detail::invalid("sweep: a sweep over values takes one parametric system file, got " +
                    std::to_string(systems.size()));
  return Sweep::over_values(systems.front(), parameter.cast<std::string>(), vector_of_numbers(values, "sweep: values"),
                            out_dir);
}

SweepItemStatus status_named(const std::string& name) {
  for (SweepItemStatus s :
       {SweepItemStatus::NotRun, SweepItemStatus::Solved, SweepItemStatus::Resumed, SweepItemStatus::Failed})
    if (name == to_string(s)) return s;
  detail::invalid("sweep: unknown item outcome: expected not_run, solved, resumed or failed, got \"" + name + "\"");
}

}  // namespace

void bind_distributed(py::module_& m) {
  // Held around a pool of solves on threads: OpenBLAS on one thread for all of them. Each solve's own guard restores
  // the count it found when it ends, so guards of solves running side by side would restore it under another solve
  // still running (its rounding would then depend on the count); the pool's guard, taken first, makes theirs no-ops.
  struct BlasGuard {
    std::unique_ptr<detail::SingleThreadedBlas> guard;
  };
  py::class_<BlasGuard>(m, "_SingleThreadedBlas")
      .def(py::init<>())
      .def("__enter__",
           [](BlasGuard& g) {
             g.guard = std::make_unique<detail::SingleThreadedBlas>();
             return &g;
           })
      .def("__exit__", [](BlasGuard& g, const py::args&) { g.guard.reset(); });
  m.def(
      "_sweep_items",
      [](const std::vector<std::string>& systems, const py::object& parameter, const py::object& values,
         const std::string& out_dir) {
        const Sweep s = plan(systems, parameter, values, out_dir);
        py::list items;
        for (const SweepItem& i : s.items())
          items.append(py::dict("index"_a = i.index, "value"_a = i.value, "system_file"_a = i.system_file,
                                "result_file"_a = i.result_file));
        return items;
      },
      "systems"_a, "parameter"_a, "values"_a, "out_dir"_a,
      "The items of a sweep (index, value, system_file, result_file); ValueError for a bad plan.");
  m.def(
      "_sweep_check",
      [](const std::vector<std::string>& systems, const py::object& parameter, const py::object& values,
         const std::string& out_dir, const py::kwargs& fields) {
        const SolveOptions o = with_fields<SolveOptions>(py::none(), fields, "sweep", "SolveOptions");
        const Sweep s = plan(systems, parameter, values, out_dir);
        check_sweep_outputs(s, o);
        return s.notes();
      },
      "systems"_a, "parameter"_a, "values"_a, "out_dir"_a,
      "Before any solve: out_dir can be written and its result files are this sweep's (ValueError naming what "
      "differs); returns the notes (values outside the declared range).");
  m.def(
      "_sweep_item",
      [](const std::vector<std::string>& systems, const py::object& parameter, const py::object& values,
         const std::string& out_dir, size_t index, const py::kwargs& fields) {
        const SolveOptions o = with_fields<SolveOptions>(py::none(), fields, "sweep", "SolveOptions");
        const Sweep s = plan(systems, parameter, values, out_dir);
        SweepItemOutcome r;
        {
          py::gil_scoped_release release;
          r = run_sweep_item(s, index, o);
        }
        return py::make_tuple(to_string(r.status), r.message);
      },
      "systems"_a, "parameter"_a, "values"_a, "out_dir"_a, "index"_a,
      "Solves item `index` of the sweep (or reads its result file back): (outcome, message).");
  m.def(
      "_sweep_table",
      [](const std::vector<std::string>& systems, const py::object& parameter, const py::object& values,
         const std::string& out_dir, const std::vector<std::string>& outcomes, const std::vector<std::string>& messages,
         const std::string& csv, const std::string& json) {
        const Sweep s = plan(systems, parameter, values, out_dir);
        if (outcomes.size() != messages.size()) detail::invalid("sweep: as many messages as outcomes expected");
        std::vector<SweepItemOutcome> o;
        for (size_t i = 0; i < outcomes.size(); ++i) o.push_back({status_named(outcomes[i]), messages[i]});
        const SweepTable t = sweep_table(s, o);
        const std::string csv_text = sweep_table_csv(t), json_text = sweep_table_json(t);
        write_file_atomic(csv, csv_text);
        write_file_atomic(json, json_text);
        return py::make_tuple(json_text, t.brief_report());
      },
      "systems"_a, "parameter"_a, "values"_a, "out_dir"_a, "outcomes"_a, "messages"_a, "csv"_a, "json"_a,
      "Writes the sweep's table (CSV and JSON, atomically) from the items' outcomes: (JSON text, summary line).");
}

}  // namespace spp::python
