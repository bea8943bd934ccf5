"""An argument of the wrong type, named plainly.

pybind11 answers a call whose argument cannot be converted (``System(M, K, w, g0="1")``) with a TypeError that dumps
every signature of the function and the whole call. ``named_type_errors`` wraps a bound function so that the same
TypeError names the argument, the type it must have and what it got; anything else passes through unchanged. The
signatures are read from the docstrings pybind11 writes (one mechanism for every function and constructor, so it
cannot drift from the binding). Written here: pybind11 has no option for it.
"""
import functools
import numbers
import os
import re

_PYBIND_MESSAGES = ("incompatible function arguments", "incompatible constructor arguments")
_SIGNATURE = re.compile(r"^\s*(?:\d+\.\s*)?(\w+)\((.*)\)\s*->")


def _split_top_level(text):
    """'a: int, b: List[float] = [1, 2]' -> ['a: int', 'b: List[float] = [1, 2]']"""
    parts, depth, current = [], 0, ""
    for ch in text:
        if ch in "[(":
            depth += 1
        elif ch in "])":
            depth -= 1
        if ch == "," and depth == 0:
            parts.append(current.strip())
            current = ""
        else:
            current += ch
    if current.strip():
        parts.append(current.strip())
    return parts


class _Params(list):
    """One overload's (name, type) pairs, with the names that have a default (`optional`) and whether it takes
    **kwargs (`open`: any other keyword is its business, e.g. an Options field)."""
    optional = frozenset()
    open = False


def _signatures(fn):
    """Each overload as a list of (name, type) from pybind11's docstring, 'self' left out."""
    out = []
    for line in (getattr(fn, "__doc__", None) or "").splitlines():
        m = _SIGNATURE.match(line)
        if not m:
            continue
        params, optional, open_ = _Params(), set(), False
        for p in _split_top_level(m.group(2)):
            if p.startswith("**"):
                open_ = True
            if p.startswith("*"):
                continue
            name, _, rest = p.partition(":")
            if name.strip() == "self":
                continue
            params.append((name.strip(), rest.split("=")[0].strip()))
            if "=" in rest:
                optional.add(name.strip())
        params.optional, params.open = frozenset(optional), open_
        out.append(params)
    return out


def _fits(value, type_name):
    """Whether pybind11 would convert value to type_name (None when the type is not one of the plain ones)."""
    if type_name.startswith("spp._spp."):  # a bound class: spp.System, spp.Solution, ...
        return type(value).__name__ == type_name.rsplit(".", 1)[-1]
    if type_name == "float":
        return isinstance(value, numbers.Real) or hasattr(value, "__float__") and not isinstance(value, (str, bytes))
    if type_name == "int":
        return isinstance(value, numbers.Integral) or hasattr(value, "__index__")
    if type_name == "str":
        return isinstance(value, str)
    if type_name == "bool":
        return isinstance(value, bool) or type(value).__name__ == "bool_"
    return None


def _explain(label, signatures, args, kwargs):
    """'spp.System: argument g0 must be float, got str '1'' for the first argument that fits no overload."""
    for params in signatures:
        given = dict(zip((p[0] for p in params), args))
        given.update(kwargs)
        for name, type_name in params:
            if name in given and _fits(given[name], type_name) is False:
                value = repr(given[name])
                value = value if len(value) <= 60 else value[:60] + "..."
                shown = "spp." + type_name.rsplit(".", 1)[-1] if type_name.startswith("spp._spp.") else type_name
                return f"{label}: argument {name} must be {shown}, got {type(given[name]).__name__} {value}"
    # no argument of a wrong type: an unknown keyword, a missing argument or too many (a single signature only;
    # pybind11 dumped its signature: spp.modes(s, k_max=1) or ParametricSystem(M0, M1, K0, K1, w, g0), found by an
    # independent attack)
    if len(signatures) == 1:
        params = signatures[0]
        names = [p[0] for p in params]
        listed = ", ".join(names)
        unknown = [k for k in kwargs if k not in names]
        if unknown and not params.open:
            return f"{label}: unknown argument {unknown[0]} (its arguments: {listed})"
        if len(args) > len(params):
            return f"{label}: takes at most {len(params)} arguments ({listed}), got {len(args)} positional"
        twice = [k for k in kwargs if k in names[:len(args)]]
        if twice:
            return f"{label}: argument {twice[0]} given twice (by position and by keyword)"
        missing = [n for n in names[len(args):] if n not in kwargs and n not in params.optional]
        if missing:
            return f"{label}: missing argument{'s' if len(missing) > 1 else ''} {', '.join(missing)} (its arguments: " \
                   f"{listed})"
    return None


# The range of the C++ int behind an "int" of pybind11's signatures: a Python int beyond it fits no overload, and
# pybind11 dumped the signatures (spp.chain(2**70); found by an independent attack). (A size_t shows as "int" too: it
# takes more, so a call that failed with a value past the int range is named by this range; none of spp's functions
# takes a size_t but sweep's internal item index.)
_INT_MIN, _INT_MAX = -2**31, 2**31 - 1


def _out_of_range(label, signatures, args, kwargs):
    """'spp.chain: argument n: expected an integer in [-2147483648, 2147483647], got 2**70' (a ValueError's message),
    for the first whole number beyond a C++ int after a failed call (a single signature only), or None."""
    if len(signatures) != 1:
        return None
    params = signatures[0]
    given = dict(zip((p[0] for p in params), args))
    given.update(kwargs)
    for name, type_name in params:
        value = given.get(name)
        if type_name == "int" and isinstance(value, numbers.Integral) and not isinstance(value, bool) \
                and not _INT_MIN <= int(value) <= _INT_MAX:
            shown = repr(int(value))
            shown = shown if len(shown) <= 60 else shown[:60] + "..."
            return f"{label}: argument {name}: expected an integer in [{_INT_MIN}, {_INT_MAX}], got {shown}"
    return None


def _complex(value):
    try:
        import numpy
        return bool(numpy.iscomplexobj(value))
    except Exception:  # not array-like: pybind11 refuses it, named by _explain
        return False


def _prepared(label, signatures, args, kwargs):
    """The arguments as the binding takes them, before the call (a single signature only): a path object for a str
    (pathlib.Path: load_result(Path(...)) was refused), and a bool refused where a number is expected (g0=True,
    spp.chain(True) were taken as 1)."""
    if len(signatures) != 1:
        return args, kwargs
    params = signatures[0]
    args = list(args)
    for i, (name, type_name) in enumerate(params):
        where = (args, i) if i < len(args) else (kwargs, name) if name in kwargs else None
        if where is None:
            continue
        value = where[0][where[1]]
        if type_name == "str" and isinstance(value, os.PathLike):
            where[0][where[1]] = os.fspath(value)
        elif type_name in ("float", "int") and (isinstance(value, bool) or type(value).__name__ == "bool_"):
            raise TypeError(f"{label}: argument {name} must be {type_name}, got bool {value!r}")
        elif type_name.startswith("numpy.ndarray[numpy.float64") and _complex(value):
            # (numpy would keep the real part with a mere ComplexWarning, as System already refuses)
            raise ValueError(f"{label}: argument {name} must be real, got a complex array")
    return tuple(args), kwargs


def named_type_errors(fn, label):
    """fn with pybind11's argument TypeError replaced by one that names the argument (see the module's text)."""
    signatures = _signatures(fn)

    @functools.wraps(fn)
    def call(*args, **kwargs):
        args, kwargs = _prepared(label, signatures, args, kwargs)
        try:
            return fn(*args, **kwargs)
        except TypeError as e:
            if not any(m in str(e) for m in _PYBIND_MESSAGES):
                raise
            too_large = _out_of_range(label, signatures, args, kwargs)
            if too_large is not None:
                raise ValueError(too_large) from None
            message = _explain(label, signatures, args, kwargs)
            if message is None:
                raise
            raise TypeError(message) from None

    call.__module__ = "spp"  # pickled by reference as spp.<name>, the wrapper itself
    call.__qualname__ = label.rsplit(".", 1)[-1]
    return call


def named_constructor_type_errors(cls):
    """The same for a bound class's constructor (the first argument, self, is not named)."""
    init = cls.__init__
    signatures = _signatures(init)

    def __init__(self, *args, **kwargs):
        args, kwargs = _prepared(f"spp.{cls.__name__}", signatures, args, kwargs)
        try:
            init(self, *args, **kwargs)
        except TypeError as e:
            if not any(m in str(e) for m in _PYBIND_MESSAGES):
                raise
            too_large = _out_of_range(f"spp.{cls.__name__}", signatures, args, kwargs)
            if too_large is not None:
                raise ValueError(too_large) from None
            message = _explain(f"spp.{cls.__name__}", signatures, args, kwargs)
            if message is None:
                raise
            raise TypeError(message) from None

    __init__.__doc__ = init.__doc__
    cls.__init__ = __init__
