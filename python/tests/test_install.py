"""`pip install .` into a fresh venv (python3 -m venv --system-site-packages), offline (--no-index: the in-tree build
backend needs nothing from PyPI), then `import spp` from elsewhere: the venv's copy is the one imported, it solves, its
version is CMake's, and `pip uninstall` removes it. SPP_PIP_BUILD_DIR (set by CTest) keeps the CMake build between
runs so that only the first one compiles."""
import os
import pathlib
import re
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


def run(cmd, **kw):
    # without the test runner's PYTHONPATH (CTest points it at the build tree): only the venv's own spp may be found
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    cp = subprocess.run(cmd, capture_output=True, text=True, env=env, **kw)
    assert cp.returncode == 0, f"{' '.join(map(str, cmd))}\n{cp.stdout[-3000:]}\n{cp.stderr[-3000:]}"
    return cp.stdout


@pytest.mark.skipif(subprocess.run(["/usr/bin/python3", "-c", "import venv, ensurepip"]).returncode != 0,
                    reason="python3-venv is not installed (scripts/install-deps.sh installs it)")
def test_pip_install_into_a_venv(tmp_path):
    venv = tmp_path / "venv"
    run(["/usr/bin/python3", "-m", "venv", "--system-site-packages", str(venv)])
    pip, py = venv / "bin" / "pip", venv / "bin" / "python"
    cmd = [str(pip), "install", "--no-index", str(ROOT)]
    if os.environ.get("SPP_PIP_BUILD_DIR"):
        cmd[2:2] = ["--config-settings", "build-dir=" + os.environ["SPP_PIP_BUILD_DIR"]]
    run(cmd)
    out = run([str(py), "-c", "import spp; print(spp.__version__); print(spp.__file__); "
               "r = spp.solve(spp.chain(2), t1_max=10, t2_max=10); print(r.status)"], cwd=tmp_path)
    version, path, status = out.split()
    assert version == re.search(r"project\(spp VERSION ([0-9.]+)", (ROOT / "CMakeLists.txt").read_text()).group(1)
    assert pathlib.Path(path).resolve().is_relative_to(venv.resolve()), path
    assert status.lower().endswith("success")
    run([str(pip), "uninstall", "-y", "spp"])
    assert not list((venv / "lib").glob("python3*/site-packages/spp"))


# Issue 13: `pip install .` compiled with Ninja's default, cores + 2 jobs (4 on 2 cores), and did not finish in 25 min
# on a loaded machine, with no way to ask for fewer. The backend now runs `cmake --build --parallel N`: N from the
# config setting jobs (pip -C jobs=N), else CMAKE_BUILD_PARALLEL_LEVEL, else the cores the process may use.
def test_build_jobs_come_from_the_setting_the_environment_or_the_cores(monkeypatch, tmp_path):
    monkeypatch.syspath_prepend(str(ROOT / "python" / "build_backend"))
    import spp_build
    commands = []
    monkeypatch.setattr(spp_build.subprocess, "run", lambda cmd, **kw: commands.append(cmd))
    monkeypatch.delenv("CMAKE_BUILD_PARALLEL_LEVEL", raising=False)
    spp_build._cmake_build(tmp_path)
    assert commands[-1][-2:] == ["--parallel", str(len(os.sched_getaffinity(0)))], commands
    monkeypatch.setenv("CMAKE_BUILD_PARALLEL_LEVEL", "3")
    spp_build._cmake_build(tmp_path)
    assert commands[-1][-2:] == ["--parallel", "3"]
    spp_build._cmake_build(tmp_path, {"jobs": "1"})
    assert commands[-1][-2:] == ["--parallel", "1"]
    with pytest.raises(ValueError, match="config setting jobs: expected a positive integer, got '0'"):
        spp_build._cmake_build(tmp_path, {"jobs": "0"})
    monkeypatch.setenv("CMAKE_BUILD_PARALLEL_LEVEL", "many")
    with pytest.raises(ValueError, match="CMAKE_BUILD_PARALLEL_LEVEL: expected a positive integer, got 'many'"):
        spp_build._cmake_build(tmp_path)
    # a misspelt setting (-C job=1) was ignored without a word (found by an attack): refused before any build
    monkeypatch.delenv("CMAKE_BUILD_PARALLEL_LEVEL")
    ran = len(commands)
    for build in (spp_build.build_wheel, spp_build.build_editable):
        with pytest.raises(ValueError, match=r"unknown config setting\(s\) 'job' .*expected build-dir or jobs"):
            build(str(tmp_path), {"job": "1"})
    assert len(commands) == ran  # nothing run
