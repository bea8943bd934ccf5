#include "spp/distributed/sweep.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "io/json.hpp"
#include "io/text.hpp"
#include "spp/detail/invalid.hpp"
#include "spp/io/files.hpp"
#include "spp/io/result_file.hpp"
#include "spp/io/system_file.hpp"
#include "spp/modal/modal.hpp"

namespace spp {

namespace {

namespace fs = std::filesystem;

void require_out_dir(const std::string& out_dir) {
  std::error_code ec;
  if (out_dir.empty()) detail::invalid("sweep: the output directory is empty: expected a directory's path");
  const fs::file_status st = fs::status(out_dir, ec);
  if (fs::exists(st) && !fs::is_directory(st))
    detail::invalid("sweep: the output directory \"" + io::shorten(out_dir, 200) +
                    "\" is not a directory (it is a file): expected a directory");
  if (!fs::is_directory(st)) {
    for (fs::path up = fs::path(out_dir).parent_path(); !up.empty() && up != up.root_path(); up = up.parent_path())
      if (fs::exists(up, ec) && !fs::is_directory(up, ec))
        detail::invalid("sweep: the output directory \"" + io::shorten(out_dir, 200) + "\" cannot exist: \"" +
                        io::shorten(up.string(), 200) +
                        "\" on its path is a file, not a directory: expected a "
                        "directory there, got a file");
    detail::invalid("sweep: the output directory \"" + io::shorten(out_dir, 200) +
                    "\" does not exist (create it first): expected an existing directory, got no such directory");
  }
}

// The shortest text that reads back to v (2.1, not 2.1000000000000001).
std::string shortest(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

// A CSV field: quoted (quotes doubled) when it holds a comma, a quote or a line break (a file name may).
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string numbered(size_t index) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%04zu", index);
  return buf;
}

// Why the result read back is not this item's (empty: it is): system, symmetry, window.
std::string mismatch(const System& sys, const SolveOptions& opt, const System& stored, const SolveResult& res) {
  if (!same_system(sys, stored)) return "another system";
  if (res.symmetry != opt.symmetry)
    return std::string("the symmetry ") + to_string(res.symmetry) + ", not " + to_string(opt.symmetry) +
           " as this sweep asks";
  // the options the file does not record, inferred from it: certified steps exist only with certify_steps; a run
  // with admissible_only drops SPPs (roots counted > SPPs kept) and keeps no non-admissible one
  const bool certified = res.stats.certified_steps > 0;
  const bool uncertified_only = res.stats.certified_steps == 0 && res.stats.uncertified_steps > 0;
  if (certified && !opt.certify_steps)
    return "a result solved with certified steps (certify_steps on, the default), not with certify_steps off as "
           "this sweep asks (--no-certify-steps, certify_steps=False)";
  if (uncertified_only && opt.certify_steps)
    return "a result solved without certified steps (certify_steps off: --no-certify-steps, certify_steps=False), "
           "not with certify_steps on as this sweep asks";
  const bool dropped = res.stats.roots > static_cast<long>(res.solutions.size());
  const bool kept_inadmissible =
      std::any_of(res.solutions.begin(), res.solutions.end(), [](const Solution& s) { return !s.admissible(); });
  if (dropped && !opt.admissible_only)
    return "a result solved with admissible_only on (--admissible-only, admissible_only=True: non-admissible SPPs "
           "dropped), not with it off as this sweep asks";
  if (kept_inadmissible && opt.admissible_only)
    return "a result solved with admissible_only off (non-admissible SPPs kept), not with it on as this sweep asks "
           "(--admissible-only, admissible_only=True)";
  // the window as solve() reports it: lower ends filled in (0 = automatic) and raised to the axis bands
  const ModalForm md(sys);
  const auto [auto1, auto2] = default_lower_ends(md, opt.t1_max, opt.t2_max);
  const auto [band1, band2] = axis_band(md);
  const double lo1 = std::max(opt.t1_min == 0.0 ? auto1 : opt.t1_min, band1);
  const double lo2 = std::max(opt.t2_min == 0.0 ? auto2 : opt.t2_min, band2);
  if (res.t1_max != opt.t1_max || res.t2_max != opt.t2_max || res.t1_min != lo1 || res.t2_min != lo2) {
    std::ostringstream os;
    os << "the window (" << res.t1_min << ", " << res.t1_max << "] x (" << res.t2_min << ", " << res.t2_max
       << "], not (" << lo1 << ", " << opt.t1_max << "] x (" << lo2 << ", " << opt.t2_max << "]";
    return os.str();
  }
  return "";
}

}  // namespace

const char* to_string(SweepItemStatus s) {
  switch (s) {
    case SweepItemStatus::NotRun: return "not_run";
    case SweepItemStatus::Solved: return "solved";
    case SweepItemStatus::Resumed: return "resumed";
    case SweepItemStatus::Failed: return "failed";
  }
  return "unknown";
}

Sweep Sweep::over_values(const std::string& parametric_file, const std::string& parameter,
                         const std::vector<double>& values, const std::string& out_dir) {
  require_out_dir(out_dir);
  if (values.empty()) detail::invalid("sweep: no parameter value given: expected at least one");
  for (size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      detail::invalid("sweep: parameter value #" + std::to_string(i + 1) + " (position " + std::to_string(i) +
                      ") is not finite: expected a finite number, got " + shortest(values[i]));
  if (!file_declares_parameter(parametric_file))
    detail::invalid("sweep: " + io::shorten(parametric_file, 200) +
                    " declares no parameter (no field \"parameter\"): a sweep over values needs a "
                    "parametric system file; sweep over system files instead: expected a file with a parameter, "
                    "got one without");
  Sweep s;
  s.parametric_.push_back(load_parametric_system(parametric_file));
  const std::string& declared = s.parametric_.front().parameter().name;
  if (parameter != declared)
    detail::invalid("sweep: the parameter asked for is \"" + io::shorten(parameter, 80) + "\", but " +
                    io::shorten(parametric_file, 200) + " declares the parameter \"" + io::shorten(declared, 80) +
                    "\": expected \"" + io::shorten(declared, 80) + "\", got \"" + io::shorten(parameter, 80) + "\"");
  s.parameter_ = parameter;
  s.out_dir_ = out_dir;
  // one note for every value outside the declared range: the first named, at most 5 more (a sweep may have 1e6)
  const Parameter& range = s.parametric_.front().parameter();
  std::vector<size_t> outside;
  for (size_t i = 0; i < values.size(); ++i)
    if (values[i] < range.min || values[i] > range.max) outside.push_back(i);
  if (!outside.empty()) {
    std::string note = "value #" + std::to_string(outside[0] + 1) + ", " + parameter + " = " +
                       shortest(values[outside[0]]) + ", lies outside the range [" + shortest(range.min) + ", " +
                       shortest(range.max) + "] that " + io::shorten(parametric_file, 200) + " declares";
    if (outside.size() > 1) {
      note += ", and " + std::to_string(outside.size() - 1) + (outside.size() == 2 ? " more value:" : " more values:");
      constexpr size_t kNamed = 5;
      for (size_t k = 1; k < outside.size() && k <= kNamed; ++k)
        note += std::string(k > 1 ? "," : "") + " #" + std::to_string(outside[k] + 1) + " (" +
                shortest(values[outside[k]]) + ")";
      if (outside.size() - 1 > kNamed) note += ", ...";
    }
    s.notes_.push_back(note +
                       " (the system is validated at each value: where it is not positive definite, that value fails)");
  }
  for (size_t i = 0; i < values.size(); ++i)
    s.items_.push_back(
        {i, values[i], parametric_file, (fs::path(out_dir) / (parameter + "_" + numbered(i) + ".json")).string()});
  return s;
}

Sweep Sweep::over_files(const std::vector<std::string>& files, const std::string& out_dir) {
  require_out_dir(out_dir);
  if (files.empty()) detail::invalid("sweep: no system file given: expected at least one, got none");
  // one parametric file and no parameter: a usage error, before any solve (it was one failed item, exit 4)
  if (files.size() == 1 && file_declares_parameter(files.front())) {
    const ParametricSystem ps = load_parametric_system(files.front());
    detail::invalid("sweep: " + io::shorten(files.front(), 200) + " declares the parameter \"" +
                    ps.parameter().name + "\" (a parametric system): expected its values to sweep, e.g. --parameter " +
                    ps.parameter().name + " --values " + shortest(ps.parameter().min) + ":" +
                    shortest(ps.parameter().max) + ":STEP (Python: parameter=\"" + ps.parameter().name +
                    "\", values=[...])");
  }
  Sweep s;
  s.out_dir_ = out_dir;
  for (size_t i = 0; i < files.size(); ++i)
    s.items_.push_back(
        {i, std::numeric_limits<double>::quiet_NaN(), files[i],
         (fs::path(out_dir) / (numbered(i) + "_" + fs::path(files[i]).stem().string() + ".json")).string()});
  return s;
}

System Sweep::system(size_t i) const {
  if (i >= items_.size()) detail::invalid("sweep: item " + std::to_string(i) + " of " + std::to_string(items_.size()));
  if (parametric_.empty()) return load_system(items_[i].system_file);
  return parametric_.front().at(items_[i].value);  // its message names the parameter and the value
}

void check_sweep_outputs(const Sweep& sweep, const SolveOptions& options) {
  options.validate();
  check_writable_directory(sweep.out_dir(), "sweep: the output directory");
  for (size_t i = 0; i < sweep.items().size(); ++i) {
    const SweepItem& item = sweep.items()[i];
    std::error_code ec;
    if (!fs::exists(item.result_file, ec)) continue;
    const std::string refused = "sweep: the output directory \"" + io::shorten(sweep.out_dir(), 200) +
                                "\" holds results this sweep cannot resume from: " +
                                io::shorten(item.result_file, io::kQuotedPathChars);
    const std::string fix = " (remove its result files, or give another output directory); nothing was written";
    std::optional<System> sys;
    try {
      sys.emplace(sweep.system(i));
    } catch (const std::invalid_argument&) {
      continue;  // the item fails on its own (a value where the system is invalid, an unreadable file)
    }
    std::optional<ResultFile> stored;
    try {
      stored.emplace(parse_result_file(read_file(item.result_file), item.result_file));
    } catch (const std::invalid_argument& e) {
      detail::invalid(refused + " cannot be read back (" + io::shorten(e.what(), 300) + ")" + fix);
    }
    std::string why = mismatch(*sys, options, stored->system, stored->result);
    if (why == "another system" && !sweep.parameter().empty())
      why += " than " + sweep.parameter() + " = " + shortest(item.value) + " (were the values changed?)";
    if (!why.empty()) detail::invalid(refused + " holds " + why + fix);
  }
}

SweepItemOutcome run_sweep_item(const Sweep& sweep, size_t i, const SolveOptions& options) {
  options.validate();
  if (i >= sweep.items().size())
    detail::invalid("sweep: item " + std::to_string(i) + " of " + std::to_string(sweep.items().size()));
  const SweepItem& item = sweep.items()[i];
  SweepItemOutcome out;
  try {
    const System sys = sweep.system(i);
    std::error_code ec;
    if (fs::exists(item.result_file, ec)) {  // an earlier run wrote it (atomically: it is whole)
      const std::string text = read_file(item.result_file);
      const ResultFile stored = parse_result_file(text, item.result_file);
      const std::string why = mismatch(sys, options, stored.system, stored.result);
      if (!why.empty())
        detail::invalid(item.result_file + " is already there and holds " + why +
                        ": not replaced (remove it, or give another output directory)");
      out.status = SweepItemStatus::Resumed;
      return out;
    }
    SolveOptions o = options;
    o.progress = nullptr;
    const SolveResult res = solve(sys, o);
    write_file_atomic(item.result_file, result_json(sys, res));
    out.status = SweepItemStatus::Solved;
  } catch (const std::exception& e) {  // an item's failure is its own: reported, never fatal to the others
    out.status = SweepItemStatus::Failed;
    out.message = e.what();
  }
  return out;
}

std::vector<SweepItemOutcome> run_sweep(const Sweep& sweep, const SolveOptions& options,
                                        const std::function<void(size_t, const SweepItemOutcome&)>& on_done) {
  options.validate();
  std::vector<SweepItemOutcome> outcomes;
  for (size_t i = 0; i < sweep.items().size(); ++i) {
    outcomes.push_back(run_sweep_item(sweep, i, options));
    if (on_done) on_done(i, outcomes.back());
  }
  return outcomes;
}

long SweepTable::failed() const {
  return static_cast<long>(std::count_if(
      outcomes.begin(), outcomes.end(), [](const SweepItemOutcome& o) { return o.status == SweepItemStatus::Failed; }));
}

std::string SweepTable::brief_report() const {
  const auto count = [&](SweepItemStatus s) {
    return std::count_if(outcomes.begin(), outcomes.end(), [s](const SweepItemOutcome& o) { return o.status == s; });
  };
  const long adm = std::count_if(rows.begin(), rows.end(), [](const SweepRow& r) { return r.admissible; });
  std::ostringstream os;
  os << "sweep over " << (parameter.empty() ? std::string("system files") : parameter) << ": " << items.size()
     << (parameter.empty() ? " files, " : " values, ")
     << count(SweepItemStatus::Solved) + count(SweepItemStatus::Resumed) << " done (" << count(SweepItemStatus::Resumed)
     << " resumed from their files), " << failed() << " failed, " << rows.size() << " SPPs (" << adm << " admissible)";
  return os.str();
}

SweepTable sweep_table(const Sweep& sweep, const std::vector<SweepItemOutcome>& outcomes) {
  if (outcomes.size() != sweep.items().size())
    detail::invalid("sweep_table: " + std::to_string(outcomes.size()) + " outcomes for " +
                    std::to_string(sweep.items().size()) + " items");
  SweepTable t;
  t.parameter = sweep.parameter();
  t.items = sweep.items();
  t.outcomes = outcomes;
  for (size_t i = 0; i < t.items.size(); ++i) {
    const SweepItemStatus st = outcomes[i].status;
    if (st != SweepItemStatus::Solved && st != SweepItemStatus::Resumed) {
      t.solve_status.push_back(SolveStatus::NotRun);
      t.spps.push_back(0);
      continue;
    }
    const SolveResult res = load_result(t.items[i].result_file);
    t.solve_status.push_back(res.status);
    t.spps.push_back(static_cast<long>(res.solutions.size()));
    for (const Solution& s : res.solutions)
      t.rows.push_back(
          {i, t.items[i].value, s.t1(), s.t2(), s.period(), s.energy(), s.min_gap(), s.min_force(), s.admissible()});
  }
  return t;
}

std::string sweep_table_csv(const SweepTable& t) {
  std::ostringstream os;
  os << "index," << (t.parameter.empty() ? std::string("value") : t.parameter)
     << ",system_file,result_file,solve_status,t1,t2,period,admissible,min_gap,min_force,energy\n";
  for (const SweepRow& r : t.rows) {
    const SweepItem& item = t.items[r.index];
    os << r.index << "," << (std::isnan(r.value) ? std::string() : shortest(r.value)) << ","
       << csv_field(item.system_file) << "," << csv_field(item.result_file) << "," << to_string(t.solve_status[r.index])
       << "," << shortest(r.t1) << "," << shortest(r.t2) << "," << shortest(r.period) << ","
       << (r.admissible ? "true" : "false")  // (a bool column for pandas, as spp solve --csv writes it)
       << "," << shortest(r.min_gap) << "," << shortest(r.min_force) << "," << shortest(r.energy) << "\n";
  }
  return os.str();
}

std::string sweep_table_json(const SweepTable& t, int indent) {
  io::json j;
  j["parameter"] = t.parameter.empty() ? io::json(nullptr) : io::json(t.parameter);
  io::json items = io::json::array();
  for (size_t i = 0; i < t.items.size(); ++i) {
    const SweepItem& item = t.items[i];
    io::json e;
    e["index"] = i;
    e["value"] = std::isnan(item.value) ? io::json(nullptr) : io::json(item.value);
    e["system_file"] = item.system_file;
    e["result_file"] = item.result_file;
    e["outcome"] = to_string(t.outcomes[i].status);
    e["message"] = t.outcomes[i].message;
    e["solve_status"] = to_string(t.solve_status[i]);
    io::json spps = io::json::array();
    for (const SweepRow& r : t.rows)
      if (r.index == i)
        spps.push_back({{"t1", r.t1},
                        {"t2", r.t2},
                        {"period", r.period},
                        {"admissible", r.admissible},
                        {"min_gap", r.min_gap},
                        {"min_force", r.min_force},
                        {"energy", r.energy}});
    e["spps"] = std::move(spps);
    items.push_back(std::move(e));
  }
  j["items"] = std::move(items);
  return j.dump(indent);
}

}  // namespace spp
