#pragma once
// What every binding file shares: pybind11 with Eigen and STL conversions, the result enums as Python enums
// (spp._outcome.Outcome), Options filled from keyword arguments, and the checks on numpy input.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

// (every header that declares a result enum's to_string: outcome() names them qualified, so they must be seen here)
#include "spp/continuation/continuation.hpp"
#include "spp/detail/invalid.hpp"
#include "spp/modal/modal.hpp"
#include "spp/search/solver.hpp"
#include "spp/simulation/simulator.hpp"
#include "spp/simulation/verify.hpp"

namespace spp::python {

namespace py = pybind11;
using namespace pybind11::literals;

// Samples handed to Python at once (t, gap, force and x, v of n each: 2n + 3 values a sample) are bounded by this
// many values, 800 MB of doubles: a request past it is named before any work instead of a MemoryError or a swap
// storm (trajectory's samples, simulate's duration x samples_per_unit; found by independent attacks)
constexpr double kMaxSampleValues = 1e8;

// A file to read that does not exist raises FileNotFoundError naming it (an OSError, as open() raises), not the
// ValueError of a file that is there but wrong (System.from_json("nofile.json"); found by an attack on issue 13).
inline void require_existing_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    // a JSON text given for its path (SolveResult.from_json(text)) was echoed whole, 77 KB, in the error (issue 11
    // attack): a path longer than any file system takes (PATH_MAX), or one with a line break, is named by its start
    constexpr size_t kLongestPath = 4096, kQuoted = 60;
    if (path.size() >= kLongestPath || path.find('\n') != std::string::npos)
      detail::invalid(
          "expected the path of an existing file, got a text of " + std::to_string(path.size()) +
          " characters starting " +
          py::repr(py::reinterpret_steal<py::str>(PyUnicode_DecodeUTF8(
                       path.data(), static_cast<Py_ssize_t>(std::min(path.size(), kQuoted)), "backslashreplace")))
              .cast<std::string>() +
          " (for a JSON text: write it to a file first)");
    PyErr_SetObject(PyExc_FileNotFoundError, py::make_tuple(2, "No such file or directory", path).ptr());  // ENOENT
    throw py::error_already_set();
  }
}
inline long long max_samples(long n) {
  return static_cast<long long>(kMaxSampleValues / (2.0 * static_cast<double>(n) + 3.0));
}

// Result statuses and kinds as Python enums (spp._outcome.Outcome: str subclasses) whose members are the C++
// to_string names: one mechanism for every result enum, its members taken from C++ so that they cannot drift.
template <class E>
py::handle& outcome_class() {
  static py::handle cls;  // owned by the module (m.attr), never freed before it
  return cls;
}
// Every value of E is bound: 0 .. value_count(E) - 1, the count declared next to E's to_string (found by ADL, in spp
// or spp::modes). The names must be new and real (not the switch's fallback "?", "unknown", "") and the value past
// the count must have none of its own: a count not updated with its enum fails the import (std::logic_error naming
// the enum), never a value silently lost. (It stopped at the first name not new: a heuristic that lost
// Verdict::Leaves and ContinuationStatus::Incomplete, whose two-way to_string names an out-of-range value; earlier,
// hand-written lists drifted: ModeEventKind lacked grazing_continuation.)
template <class E>
void bind_outcome(py::module_& m, const char* name, const char* doc) {
  using U = std::underlying_type_t<E>;
  constexpr int kCount = value_count(E{});
  static_assert(kCount > 0, "value_count of a result enum");
  const auto named = [](U i) { return std::string(to_string(static_cast<E>(i))); };
  const auto fallback = [](const std::string& s) { return s.empty() || s == "?" || s == "unknown"; };
  std::vector<std::string> seen;
  py::list members;
  for (U i = 0; i < static_cast<U>(kCount); ++i) {
    const std::string s = named(i);
    if (fallback(s) || std::find(seen.begin(), seen.end(), s) != seen.end())
      throw std::logic_error(std::string("bind_outcome: ") + name + ": expected " + std::to_string(kCount) +
                             " named values (value_count), got value " + std::to_string(i) + " named \"" + s + "\"");
    seen.push_back(s);
    members.append(py::make_tuple(s, s));
  }
  if (const std::string past = named(static_cast<U>(kCount));
      !fallback(past) && std::find(seen.begin(), seen.end(), past) == seen.end())
    throw std::logic_error(std::string("bind_outcome: ") + name + ": expected " + std::to_string(kCount) +
                           " values (value_count), got a value " + std::to_string(kCount) + " named \"" + past +
                           "\": update value_count with the enum");
  py::object cls = py::module_::import("spp._outcome").attr("Outcome")(name, members, "module"_a = "spp");
  cls.attr("__doc__") = doc;
  m.attr(name) = cls;
  outcome_class<E>() = cls;
}
template <class E>
py::object outcome(E v) {
  return outcome_class<E>()(to_string(v));
}

// The options (or their defaults) with the keyword arguments set on them, field by field: one mechanism for every
// function that takes an Options struct. An unknown keyword is refused with the list of fields; the list is the bound
// attributes (not the dunders nor validate), so it cannot drift from the binding.
// A value's type and (shortened) repr for a message: "str '3'".
inline std::string typed_repr(const py::handle& v) {
  std::string r = py::repr(v).cast<std::string>();
  if (r.size() > 60) r = r.substr(0, 60) + "...";
  return std::string(py::str(py::type::of(v).attr("__name__"))) + " " + r;
}

// The bound fields of an Options object (its attributes but the dunders and validate): with_fields, fields_repr and
// the options' pickling take this one list.
inline std::vector<std::string> option_field_names(const py::object& o) {
  std::vector<std::string> known;
  for (const py::handle a : py::module_::import("builtins").attr("dir")(o)) {
    const std::string n = py::str(a);
    if (n.rfind("_", 0) != 0 && n != "validate") known.push_back(n);
  }
  return known;
}

template <class Options>
Options with_fields(const py::object& options, const py::kwargs& fields, const char* where, const char* type_name) {
  // a wrong type is a TypeError naming the argument, not pybind11's cast failure (RuntimeError) or signature dump
  if (!options.is_none() && !py::isinstance<Options>(options)) {
    if (py::isinstance<py::dict>(options))
      throw py::type_error(std::string(where) + ": options must be an spp." + type_name +
                           " or None, got a dict: pass its entries as keywords (**options)");
    throw py::type_error(std::string(where) + ": options must be an spp." + type_name + " or None, got " +
                         typed_repr(options) + " (the window is given as keywords, e.g. t1_max=12, t2_max=12)");
  }
  py::object o = options.is_none() ? py::cast(Options{}) : py::cast(options.cast<Options>());
  const std::vector<std::string> known = option_field_names(o);
  for (const auto& [key, value] : fields) {
    const std::string name = py::str(key);
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      std::string list;
      for (const std::string& n : known) list += (list.empty() ? "" : ", ") + n;
      detail::invalid(std::string(where) + ": unknown option \"" + name + "\" (" + type_name + " fields: " + list +
                      ")");
    }
    // converted and checked by the field's own setter (field_value: the message an attribute set gives), named
    // here with the function it was given to
    try {
      py::setattr(o, key, value);
    } catch (const py::error_already_set& e) {
      const std::string message = std::string(where) + ": " + py::str(e.value()).cast<std::string>();
      if (e.matches(PyExc_TypeError)) throw py::type_error(message);
      if (e.matches(PyExc_ValueError)) throw py::value_error(message);
      throw;
    }
  }
  return o.cast<Options>();
}

// "<spp.Name field=value ...>" of the bound fields (those of with_fields), for the options' __repr__.
inline std::string fields_repr(const py::object& o, const char* type_name) {
  std::string out = std::string("<spp.") + type_name;
  for (const std::string& n : option_field_names(o))
    out += " " + n + "=" + py::repr(o.attr(n.c_str())).cast<std::string>();
  return out + ">";
}

// A complex array is refused, naming `what` (pybind11's conversion to double, and numpy's asarray(dtype=float64), keep
// the real part with a mere ComplexWarning: found by an independent review).
inline void require_real(const py::object& a, const std::string& what) {
  const py::module_ np = py::module_::import("numpy");
  if (np.attr("iscomplexobj")(a).cast<bool>())
    detail::invalid(what + " must be real, got a complex array (dtype " +
                    py::str(np.attr("asarray")(a).attr("dtype")).cast<std::string>() + ")");
}

// Numbers only: numpy's conversion to float64 took a datetime64, timedelta64 or bool array as numbers (days, 0/1), a
// masked array without its mask, and an object array of whatever converts; each is refused, named with its dtype
// (found by an independent attack). Integers and floats pass; a complex array is require_real's; strings and ragged
// lists are refused by the conversion itself, with numpy's reason.
inline void require_plain_numbers(const py::object& a, const std::string& what, const std::string& expected) {
  const py::module_ np = py::module_::import("numpy");
  if (py::isinstance(a, np.attr("ma").attr("MaskedArray")))
    detail::invalid(what + " must be " + expected +
                    ", got a masked array (its mask would be dropped): pass "
                    "a.filled(value) or the plain array");
  py::object dtype;
  if (py::isinstance(a, np.attr("ndarray")) || py::isinstance(a, np.attr("generic")))
    dtype = a.attr("dtype");
  else if (py::isinstance<py::list>(a) || py::isinstance<py::tuple>(a)) {
    try {
      dtype = np.attr("asarray")(a).attr("dtype");
    } catch (const py::error_already_set&) {
      return;  // (ragged: refused by the conversion, with numpy's reason)
    }
  }
  if (!dtype) return;
  const std::string kind = py::str(dtype.attr("kind"));
  if (kind == "b" || kind == "M" || kind == "m" || kind == "O")
    detail::invalid(what + " must be " + expected + ", got an array of dtype " + py::str(dtype).cast<std::string>() +
                    " (" +
                    (kind == "b"   ? "booleans"
                     : kind == "O" ? "Python objects"
                                   : "dates or times") +
                    "): expected integers or floats");
}

// Matrix and vector input, one conversion for System and ParametricSystem: numpy arrays, nested lists, scipy.sparse
// matrices (densified: the solver is dense), and a vector as (n,), (1, n) or (n, 1); the argument named (`what`,
// e.g. "System: M") when it cannot be converted. An empty part (`empty_ok`: a parametric system's M_mu, K_mu, w_mu)
// is returned with size 0.
inline py::object float_array(const py::object& a, const std::string& what) {
  const py::module_ np = py::module_::import("numpy");
  py::object d = py::hasattr(a, "toarray") ? a.attr("toarray")() : a;
  // (the complex check inside the try: numpy's iscomplexobj already fails on a ragged list, [[1, 2], [3]], and its
  // "inhomogeneous shape" message named no argument; found by an independent attack)
  require_plain_numbers(d, what, "an array of numbers");
  try {
    require_real(d, what);
    return np.attr("asarray")(d, "dtype"_a = "float64");
  } catch (const py::error_already_set& e) {
    // numpy's reason (a ragged list, a string) kept, shortened: it says what is wrong, ours says where
    std::string why = py::str(e.value()).cast<std::string>();
    if (why.size() > 160) why = why.substr(0, 160) + "...";
    detail::invalid(what + " must be an array of numbers, got " + typed_repr(a) + " (numpy: " + why + ")");
  }
}
inline Eigen::MatrixXd matrix_input(const py::object& a, const std::string& what, bool empty_ok = false) {
  const py::object arr = float_array(a, what);
  if (empty_ok && arr.attr("size").cast<long>() == 0) return Eigen::MatrixXd();
  if (arr.attr("ndim").cast<int>() != 2)
    detail::invalid(what + " must be a square matrix, got shape " + py::str(arr.attr("shape")).cast<std::string>());
  return arr.cast<Eigen::MatrixXd>();
}
inline Eigen::VectorXd vector_input(const py::object& a, const std::string& what, bool empty_ok = false) {
  const py::object arr = float_array(a, what);
  if (empty_ok && arr.attr("size").cast<long>() == 0) return Eigen::VectorXd();
  const py::tuple shape = arr.attr("shape").cast<py::tuple>();
  const bool vector_like =
      shape.size() == 1 || (shape.size() == 2 && (shape[0].cast<long>() == 1 || shape[1].cast<long>() == 1));
  if (!vector_like)
    detail::invalid(what + " must be a vector, (n,), (1, n) or (n, 1), got shape " +
                    py::str(py::object(shape)).cast<std::string>());
  return arr.attr("ravel")().cast<Eigen::VectorXd>();
}

// An array argument of `ndim` dimensions (1: a vector, (n,); 2: a matrix, (rows, cols)) as numbers, `what` named with
// the shape expected when it is ragged, of another shape or not numbers: simulate's x0 = [[1, 2], [3]] and chain's
// masses = [[1, 2]] gave numpy's or pybind11's own error, naming no argument (found by an independent attack).
inline Eigen::MatrixXd array_of_numbers(const py::handle& a, const std::string& what, int ndim) {
  const std::string expected =
      ndim == 1 ? "a vector of numbers, shape (n,)" : "a matrix of numbers, shape (rows, cols)";
  py::object arr;
  require_plain_numbers(py::reinterpret_borrow<py::object>(a), what, expected);
  try {
    require_real(py::reinterpret_borrow<py::object>(a), what);
    arr = py::module_::import("numpy").attr("asarray")(a, "dtype"_a = "float64");
  } catch (const py::error_already_set& e) {
    std::string why = py::str(e.value()).cast<std::string>();  // numpy's reason (ragged, a string), shortened
    if (why.size() > 160) why = why.substr(0, 160) + "...";
    detail::invalid(what + " must be " + expected + ", got " + typed_repr(a) + " (numpy: " + why + ")");
  }
  if (arr.attr("ndim").cast<int>() != ndim)
    detail::invalid(what + " must be " + expected + ", got shape " + py::str(arr.attr("shape")).cast<std::string>());
  if (ndim == 1) return arr.cast<Eigen::VectorXd>();
  return arr.cast<Eigen::MatrixXd>();
}
inline std::vector<double> vector_of_numbers(const py::handle& a, const std::string& what) {
  const Eigen::VectorXd v = array_of_numbers(a, what, 1);
  return std::vector<double>(v.data(), v.data() + v.size());
}

// A number, bool or list of numbers given to an Options field, converted here, field by field, with the field named
// (`label`, e.g. "SolveOptions.threads"): one mechanism for every Options struct bound (OptionsBinding below), so that
// an attribute set after construction (o.threads = 2**40, o.t1_max = 10**400) says what a keyword argument says, not
// pybind11's "incompatible function arguments" with the signatures; numpy's integer and float scalars are taken where
// Python's ints and floats are (o.threads = np.int64(2) was refused; found by an independent attack). A wrong type is
// a TypeError, a number out of the C++ field's range a ValueError.
inline bool is_python_bool(const py::handle& v) {
  return py::isinstance<py::bool_>(v) || py::isinstance(v, py::module_::import("numpy").attr("bool_"));
}
inline std::string shown_value(const py::handle& v) {
  std::string r = py::repr(v).cast<std::string>();
  return r.size() > 60 ? r.substr(0, 60) + "..." : r;
}
[[noreturn]] inline void wrong_type(const std::string& label, const std::string& expected, const py::handle& v) {
  throw py::type_error(label + " must be " + expected + ", got " + typed_repr(v));
}
// Largest whole float taken as a count (max_cells=1e7, as the CLI and --help write counts): every integer up to it is
// exact in a double (2^53 ~ 9.007e15).
inline constexpr double kMaxWholeFloatCount = 9e15;

// One scalar (a Python number or bool, a numpy scalar, or a 0-d numpy array: its item) as T, `label` named when it
// cannot be: a wrong type is a TypeError (`expected` says what was), a number out of T's range a ValueError. The one
// conversion of scalar Options fields (field_value) and scalar arguments (scalar_argument): spp.System(M, K, w,
// 10**400) was pybind11's "incompatible function arguments", spp.modes(s, 1, 10**400) a RuntimeError and
// o.threads = np.array(2.0) numpy's own TypeError (found by independent attacks).
template <class T>
T scalar_value(const py::handle& given, const std::string& label, const std::string& expected) {
  const py::module_ np = py::module_::import("numpy");
  py::object v = py::reinterpret_borrow<py::object>(given);
  if (py::isinstance(v, np.attr("ndarray")) && v.attr("ndim").cast<int>() == 0) v = v.attr("item")();
  if constexpr (std::is_same_v<T, bool>) {
    if (!is_python_bool(v)) wrong_type(label, expected, given);
    return PyObject_IsTrue(v.ptr()) != 0;
  } else if constexpr (std::is_integral_v<T>) {
    static_assert(std::is_signed_v<T>, "an unsigned Options field needs its own range check");
    if (is_python_bool(v)) wrong_type(label, expected, given);  // (True is no count)
    py::object whole;
    if (PyFloat_Check(v.ptr()) || py::isinstance(v, np.attr("floating"))) {
      const double d = py::cast<double>(v);
      if (!(std::floor(d) == d && std::abs(d) <= kMaxWholeFloatCount)) wrong_type(label, expected, given);
      whole = py::int_(static_cast<long long>(d));
    } else if (PyIndex_Check(v.ptr())) {  // int, numpy integers
      whole = py::reinterpret_steal<py::object>(PyNumber_Index(v.ptr()));
      if (!whole) throw py::error_already_set();
    } else {
      wrong_type(label, expected, given);
    }
    int overflow = 0;
    const long long x = PyLong_AsLongLongAndOverflow(whole.ptr(), &overflow);
    if (overflow != 0 || x < std::numeric_limits<T>::min() || x > std::numeric_limits<T>::max())
      detail::invalid(label + ": expected an integer in [" + std::to_string(std::numeric_limits<T>::min()) + ", " +
                      std::to_string(std::numeric_limits<T>::max()) +
                      "] (the range of the C++ field; validate() then checks its own bounds), got " +
                      shown_value(whole));
    return static_cast<T>(x);
  } else {
    static_assert(std::is_same_v<T, double>, "a scalar of another type needs its conversion");
    const bool number = PyFloat_Check(v.ptr()) || PyLong_Check(v.ptr()) || py::isinstance(v, np.attr("floating")) ||
                        py::isinstance(v, np.attr("integer"));
    if (is_python_bool(v) || !number) wrong_type(label, expected, given);
    const double d = PyFloat_AsDouble(v.ptr());
    if (d == -1.0 && PyErr_Occurred()) {  // an int beyond the doubles (10**400): OverflowError
      PyErr_Clear();
      detail::invalid(label + ": expected a number within the range of doubles (magnitude at most " + "1.8e308), got " +
                      shown_value(given));
    }
    return d;
  }
}

// A scalar argument of a bound function, through scalar_value; `label` as spp._args names the arguments pybind11
// converts ("spp.System: argument g0"), and so is the type expected ("must be float, got str '1'").
template <class T>
T scalar_argument(const py::handle& v, const std::string& label) {
  if constexpr (std::is_same_v<T, bool>)
    return scalar_value<T>(v, label, "bool");
  else if constexpr (std::is_integral_v<T>)
    return scalar_value<T>(v, label, "int");
  else
    return scalar_value<T>(v, label, "float");
}
// The same for an optional one: None is nullopt.
template <class T>
std::optional<T> optional_argument(const py::handle& v, const std::string& label) {
  if (v.is_none()) return std::nullopt;
  return scalar_argument<T>(v, label);
}

template <class T>
T field_value(const py::handle& v, const std::string& label, const T& default_value) {
  if constexpr (std::is_same_v<T, std::vector<double>>) {
    return vector_of_numbers(v, label);
  } else {
    const py::object def = py::cast(default_value);
    return scalar_value<T>(v, label,
                           std::string(py::str(py::type::of(def).attr("__name__"))) + " like its default " +
                               py::repr(def).cast<std::string>());
  }
}

// An Options struct bound field by field through field_value: `.field(name, &C::member, doc)` for every number,
// bool or list of numbers; .cls() for the rest (symmetry, validate, __repr__).
template <class C>
class OptionsBinding {
 public:
  OptionsBinding(py::module_& m, const char* name, const char* doc)
      : cls_(m, name, doc), name_(std::string("spp.") + name) {
    // Keyword constructor naming its fields, spp.SolveOptions(t1_max=3, t2_max=3) (it took none: "unknown argument
    // t1_max (its arguments: )", issue 11 attack): each set through the field's own setter, an unknown keyword a
    // TypeError naming it and listing the fields.
    const std::string ctor = name_;
    cls_.def(
        py::init([ctor](const py::kwargs& fields) {
          py::object o = py::cast(C{});
          const std::vector<std::string> known = option_field_names(o);
          for (const auto& [key, value] : fields) {
            const std::string n = py::str(key);
            if (std::find(known.begin(), known.end(), n) == known.end()) {
              std::string list;
              for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
              throw py::type_error(ctor + "(): unexpected keyword argument \"" + n +
                                   "\": expected one of its fields (" + list + ")");
            }
            py::setattr(o, key, value);
          }
          return o.cast<C>();
        }),
        (name_ + "(**fields): the defaults, with the given fields set (each checked as an attribute set is)").c_str());
    // Pickled as {field: value} of every bound field (multiprocessing and joblib pass options to their workers; they
    // could not be pickled), read back through the fields' own setters, so a hand-made or foreign state is checked
    // as an attribute set is. A Symmetry is kept as its name (the setter takes it).
    const std::string label = name_;
    cls_.def(py::pickle(
        [](const py::object& self) {
          py::dict d;
          for (const std::string& n : option_field_names(self)) {
            const py::object v = self.attr(n.c_str());
            d[n.c_str()] = py::isinstance<spp::Symmetry>(v) ? py::str(spp::to_string(v.cast<spp::Symmetry>())) : v;
          }
          return d;
        },
        [label](const py::dict& d) {
          py::object o = py::cast(C{});
          const std::vector<std::string> known = option_field_names(o);
          for (const auto& [key, value] : d) {
            const std::string n = py::str(key);
            if (std::find(known.begin(), known.end(), n) == known.end())
              detail::invalid(label + " pickle: expected its fields only, got an unknown field \"" + n + "\"");
            py::setattr(o, key, value);
          }
          return o.cast<C>();
        }));
  }
  template <class T>
  OptionsBinding& field(const char* name, T C::*member, const char* doc = "") {
    const std::string label = name_ + "." + name;
    cls_.def_property(
        name, [member](const C& o) { return o.*member; },
        [member, label](C& o, const py::object& v) { o.*member = field_value<T>(v, label, C{}.*member); }, doc);
    return *this;
  }
  py::class_<C>& cls() { return cls_; }

 private:
  py::class_<C> cls_;
  std::string name_;
};

// The symmetry from the enum or its name ("axial", "point").
inline spp::Symmetry symmetry_of(const py::object& v) {
  if (py::isinstance<spp::Symmetry>(v)) return v.cast<spp::Symmetry>();
  const std::string name = py::str(v);
  if (const std::optional<spp::Symmetry> s = spp::symmetry_named(name)) return *s;
  detail::invalid("symmetry must be Symmetry.axial, Symmetry.point, \"axial\" or \"point\", got \"" + name + "\"");
}

// spp.Cancel: a flag any thread may set (cancel()) that every long call given it as cancel= checks where it checks
// Ctrl-C. Ctrl-C reaches only a run on Python's main thread (CPython delivers signals there: PyErr_CheckSignals does
// nothing on another thread), so a solve in a threading.Thread, a ThreadPoolExecutor, a Jupyter widget's callback
// or a Dask worker could not be stopped at all (issue 13). Shared (a copy is the same flag): the run holds its own
// reference, so the token may be dropped by its owner while the run goes on.
struct Cancel {
  std::shared_ptr<std::atomic<bool>> flag = std::make_shared<std::atomic<bool>>(false);
};
inline constexpr const char* kThreadRule =
    " From a thread other than the main one Ctrl-C does not reach the run: pass cancel=spp.Cancel() and call its "
    "cancel() from any thread (the run then stops as with Ctrl-C, keeping what it has done).";

// A progress=... keyword of solve, nearest_spp or root_map (and the Ctrl-C check of continuation, modes, verify,
// simulate and trajectory, built with py::none()) (None, True/False, a callable), called from the C++ run
// (which holds no GIL: it is taken here) about every 0.2 s. Ctrl-C (KeyboardInterrupt) stops the run and keeps what was
// done; the user's callable may stop it too (by returning False) or raise. Lives in the binding's frame: the C++
// options hold a lambda that refers to it (copying a py::object without the GIL would not be safe).
struct ProgressHook {
  py::object callable = py::none();
  bool call = false, text = false, interrupted = false, shown = false, late = false;
  std::shared_ptr<std::atomic<bool>> token;  // cancel=spp.Cancel()'s flag (null: none given)
  bool cancelled = false;                    // stopped by the token (not by Ctrl-C nor the callable)

  ProgressHook(const py::object& progress, const std::string& where, const py::object& cancel = py::none())
      : callable(progress) {
    if (!cancel.is_none()) {
      if (!py::isinstance<Cancel>(cancel))
        throw py::type_error(where + ": cancel must be an spp.Cancel or None, got " + typed_repr(cancel));
      token = cancel.cast<const Cancel&>().flag;
    }
    call = PyCallable_Check(progress.ptr()) != 0;
    // True/False/None (numpy's bool too) or a callable: anything else was taken for its truth (progress=5)
    if (!call && !progress.is_none() && !py::isinstance<py::bool_>(progress) &&
        !py::isinstance(progress, py::module_::import("numpy").attr("bool_")))
      throw py::type_error(where + ": progress must be True, False, None, a callable or \"bar\", got " +
                           typed_repr(progress));
    text = !call && truth(progress);
  }
  static bool truth(const py::object& v) {
    const int t = PyObject_IsTrue(v.ptr());
    if (t < 0) throw py::error_already_set();
    return t != 0;
  }
  template <class P>
  bool operator()(const P& p) {
    const py::gil_scoped_acquire gil;
    if (!signals_allow()) return false;
    if (text && p.seconds >= 1.0) {
      py::module_::import("sys").attr("stderr").attr("write")("\r  " + p.line() + "   ");
      shown = true;
    }
    if (!call) return true;
    try {
      const py::object r = callable(p);
      return r.is_none() || truth(r);  // None continues; otherwise the value's truth
    } catch (const py::error_already_set& e) {
      // Ctrl-C while the user's callable ran (a slow one is where it most often lands): the same stop as a signal
      // between two reports, so that the partial result is kept (a bare KeyboardInterrupt lost it)
      if (!e.matches(PyExc_KeyboardInterrupt)) throw;
      interrupted = true;
      return false;
    }
  }
  // For runs with no progress report of their own (continuation, modes, verify, simulate): whether to go on, Ctrl-C
  // checked. Cheap (called per branch point, family point, SPP or 256 events).
  bool keep_going() {
    const py::gil_scoped_acquire gil;
    return signals_allow();
  }
  // Ctrl-C seen (now or before: once stopped, a run stays stopped, whatever the later calls find)?
  bool signals_allow() {
    if (interrupted) return false;
    if (token && token->load()) {
      cancelled = interrupted = true;
      return false;
    }
    if (PyErr_CheckSignals() != 0) {
      if (!PyErr_ExceptionMatches(PyExc_KeyboardInterrupt)) throw py::error_already_set();
      PyErr_Clear();
      interrupted = true;
      return false;
    }
    return true;
  }
  // For runs whose partial result is of no use (simulate, verify, trajectory): after the run (GIL held), Ctrl-C
  // seen during it is raised as KeyboardInterrupt.
  void raise_if_interrupted() {
    finish();
    if (interrupted) {
      PyErr_SetNone(PyExc_KeyboardInterrupt);
      throw py::error_already_set();
    }
  }
  // After the run (GIL held): ends the text line; a Ctrl-C that came after the last report counts as one (`late`).
  void finish() {
    if (shown) py::module_::import("sys").attr("stderr").attr("write")("\n");
    if (PyErr_CheckSignals() != 0) {
      if (!PyErr_ExceptionMatches(PyExc_KeyboardInterrupt)) throw py::error_already_set();
      PyErr_Clear();
      late = !interrupted;
      interrupted = true;
    }
  }
  // What stopped the run, for its warning: "Ctrl-C" or "cancelled" (cancel=spp.Cancel()).
  std::string cause() const { return cancelled ? "cancelled" : "Ctrl-C"; }
  // The RuntimeWarning of an interrupted run (warnings turned into errors raise); "(Ctrl-C)" in the message names
  // the cause (cause()).
  void warn(std::string message) const {
    if (!interrupted) return;
    if (const size_t at = message.find("(Ctrl-C)"); cancelled && at != std::string::npos)
      message.replace(at, 8, "(" + cause() + ")");
    if (PyErr_WarnEx(PyExc_RuntimeWarning, message.c_str(), 1) < 0) throw py::error_already_set();
  }
};

// progress and cancel are no fields of the options (a callable, a token): taken out of the keywords first.
struct RunControl {
  py::object progress = py::none(), cancel = py::none();
};
inline RunControl take_run_control(const py::kwargs& fields, py::dict& rest, bool with_progress = true) {
  RunControl c;
  for (const auto& [key, value] : fields) {
    const std::string name = py::str(key);
    if (with_progress && name == "progress")
      c.progress = py::reinterpret_borrow<py::object>(value);
    else if (name == "cancel")
      c.cancel = py::reinterpret_borrow<py::object>(value);
    else
      rest[key] = value;
  }
  return c;
}

// One function per area (python/bind/<area>.cpp), called in this order by module.cpp: types before the functions
// that return them.
/// The SolveResult of a result file with its system as attribute `system` (python/bind/io.cpp): load_result and
/// SolveResult.from_json.
py::object result_with_system(const std::string& path);

void bind_core(py::module_& m);
void bind_modal(py::module_& m);
void bind_orbit(py::module_& m);
void bind_search(py::module_& m);
void bind_stability(py::module_& m);
void bind_simulation(py::module_& m);
void bind_continuation(py::module_& m);
void bind_io(py::module_& m);
void bind_modes(py::module_& m);
void bind_distributed(py::module_& m);

}  // namespace spp::python
