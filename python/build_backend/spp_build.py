"""PEP 517 / PEP 660 build backend of the spp Python package: `pip install .` and `pip install -e .`.

Standard library only, so that pip's build isolation has nothing to fetch: on the machines spp targets PyPI is not
reachable, and the backends that build a CMake + pybind11 extension (scikit-build-core, setuptools with an extension
builder) would be fetched from it into the isolated environment. Written here for that reason; it only drives CMake
(the same build as scripts/build.sh, for the interpreter pip runs under) and packs the result as a wheel.

config_settings (pip: -C key=value):
  build-dir  CMake build directory (default: a temporary one for wheels, <source>/build-python for editable installs;
             give a persistent one to make repeated installs incremental)
  jobs       parallel compile jobs (default: the environment's CMAKE_BUILD_PARALLEL_LEVEL, else the number of cores
             this process may run on; Ninja's own default, cores + 2, overloaded a shared machine)
"""
import base64
import hashlib
import os
import pathlib
import re
import subprocess
import sys
import sysconfig
import tempfile
import zipfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
NAME = "spp"


def _version():
    m = re.search(r"project\(spp VERSION ([0-9.]+)", (ROOT / "CMakeLists.txt").read_text())
    if not m:
        raise RuntimeError("spp build backend: no 'project(spp VERSION x.y.z' in CMakeLists.txt")
    return m.group(1)


def _tag():
    impl = f"cp{sys.version_info.major}{sys.version_info.minor}"
    plat = sysconfig.get_platform().replace("-", "_").replace(".", "_")
    return f"{impl}-{impl}-{plat}"


def _metadata():
    return (f"Metadata-Version: 2.1\nName: {NAME}\nVersion: {_version()}\n"
            "Summary: Periodic orbits with one lasting contact phase (SPPs) of vibro-impact oscillators\n"
            "License: BSD-3-Clause\nRequires-Python: >=3.9\nRequires-Dist: numpy\n")


SETTINGS = ("build-dir", "jobs")


def _settings(config_settings):
    """config_settings as given, every key one of SETTINGS: a misspelt one (-C job=1) was ignored without a word
    (found by an attack). Raises ValueError naming it and the known ones."""
    config_settings = config_settings or {}
    unknown = sorted(k for k in config_settings if k not in SETTINGS)
    if unknown:
        raise ValueError(f"spp build backend: unknown config setting(s) {', '.join(map(repr, unknown))} (pip -C "
                         f"key=value): expected {' or '.join(SETTINGS)}")
    return config_settings


def _jobs(config_settings):
    """Compile jobs: config setting `jobs`, else CMAKE_BUILD_PARALLEL_LEVEL, else the cores this process may use.
    Raises ValueError naming where a value that is not a positive integer came from."""
    for where, value in (("config setting jobs", (config_settings or {}).get("jobs")),
                         ("CMAKE_BUILD_PARALLEL_LEVEL", os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or None)):
        if value is None:
            continue
        if not (isinstance(value, str) and value.strip().isdigit() and int(value) >= 1):
            raise ValueError(f"spp build backend: {where}: expected a positive integer, got {value!r}")
        return int(value)
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # (not Linux)
        return os.cpu_count() or 1


def _cmake_build(build_dir, config_settings=None):
    """Configures and builds the _spp extension for this interpreter with _jobs(config_settings) compile jobs;
    returns the package directory it fills."""
    build_dir = pathlib.Path(build_dir)
    configure = ["cmake", "-S", str(ROOT), "-B", str(build_dir), "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                 "-DSPP_BUILD_TESTS=OFF", "-DSPP_BUILD_BENCH=OFF", f"-DPython_EXECUTABLE={sys.executable}"]
    build = ["cmake", "--build", str(build_dir), "--target", "_spp", "--parallel", str(_jobs(config_settings))]
    for cmd in (configure, build):
        print("spp build backend:", " ".join(cmd), file=sys.stderr, flush=True)
        subprocess.run(cmd, check=True, stdout=sys.stderr)
    return build_dir / "python" / NAME


def _write_wheel(wheel_directory, files):
    """files: {archive name: bytes}; adds the dist-info and RECORD, returns the wheel's file name."""
    dist_info = f"{NAME}-{_version()}.dist-info"
    files = dict(files)
    files[f"{dist_info}/METADATA"] = _metadata().encode()
    files[f"{dist_info}/WHEEL"] = (f"Wheel-Version: 1.0\nGenerator: spp_build\nRoot-Is-Purelib: false\n"
                                   f"Tag: {_tag()}\n").encode()
    files[f"{dist_info}/top_level.txt"] = f"{NAME}\n".encode()
    record = []
    for name, data in files.items():
        digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
        record.append(f"{name},sha256={digest},{len(data)}")
    record.append(f"{dist_info}/RECORD,,")
    files[f"{dist_info}/RECORD"] = ("\n".join(record) + "\n").encode()
    wheel_name = f"{NAME}-{_version()}-{_tag()}.whl"
    with zipfile.ZipFile(os.path.join(wheel_directory, wheel_name), "w", zipfile.ZIP_DEFLATED) as zf:
        for name, data in files.items():
            zf.writestr(name, data)
    return wheel_name


def get_requires_for_build_wheel(config_settings=None):
    return []


def get_requires_for_build_sdist(config_settings=None):
    return []


def _write_metadata(metadata_directory):
    dist_info = pathlib.Path(metadata_directory) / f"{NAME}-{_version()}.dist-info"
    dist_info.mkdir(parents=True, exist_ok=True)
    (dist_info / "METADATA").write_text(_metadata())
    return dist_info.name


def prepare_metadata_for_build_wheel(metadata_directory, config_settings=None):
    """Metadata without building: pip resolves the dependencies (numpy) before the CMake build starts, so a venv
    that lacks them fails at once."""
    return _write_metadata(metadata_directory)


def prepare_metadata_for_build_editable(metadata_directory, config_settings=None):
    return _write_metadata(metadata_directory)


def build_sdist(sdist_directory, config_settings=None):
    """The tracked source files (git ls-files) as NAME-VERSION.tar.gz with PKG-INFO."""
    import io
    import tarfile
    base = f"{NAME}-{_version()}"
    files = subprocess.run(["git", "-C", str(ROOT), "ls-files", "-z"], check=True, capture_output=True).stdout
    path = os.path.join(sdist_directory, base + ".tar.gz")
    with tarfile.open(path, "w:gz") as tar:
        for rel in filter(None, files.decode().split("\0")):
            tar.add(ROOT / rel, arcname=f"{base}/{rel}", recursive=False)
        info = tarfile.TarInfo(f"{base}/PKG-INFO")
        data = _metadata().encode()
        info.size = len(data)
        tar.addfile(info, io.BytesIO(data))
    return os.path.basename(path)


def get_requires_for_build_editable(config_settings=None):
    return []


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    config_settings = _settings(config_settings)
    build_dir = (config_settings or {}).get("build-dir")
    with tempfile.TemporaryDirectory(prefix="spp-wheel-") as tmp:
        pkg = _cmake_build(build_dir or tmp, config_settings)
        files = {f"{NAME}/{p.name}": p.read_bytes() for p in sorted(pkg.iterdir())
                 if p.is_file() and (p.suffix in (".py", ".so") or p.name.startswith("_spp"))}
        if not any(n.startswith(f"{NAME}/_spp") for n in files):
            raise RuntimeError(f"spp build backend: the _spp extension was not built in {pkg}")
        return _write_wheel(wheel_directory, files)


def build_editable(wheel_directory, config_settings=None, metadata_directory=None):
    """A wheel holding one .pth that puts the CMake build's python/ directory on sys.path: the package then runs
    from the build tree (after editing a .py file or the C++ sources, `cmake --build build-python --target _spp`)."""
    config_settings = _settings(config_settings)
    build_dir = pathlib.Path((config_settings or {}).get("build-dir") or ROOT / "build-python").resolve()
    pkg = _cmake_build(build_dir, config_settings)
    return _write_wheel(wheel_directory, {f"__editable__.{NAME}.pth": f"{pkg.parent}\n".encode()})
