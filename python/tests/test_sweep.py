"""spp.sweep: one solve per parameter value on a thread pool (concurrent.futures) or over MPI ranks (mpi4py, under
mpirun), each value's SPPs those of spp.solve at that value; resumed from the result files; a failing value reported."""
import json
import os
import shutil
import subprocess
import sys

import pytest

import spp

# Paper §2.3's 2-dof system, K = [[1 + k2, -k2], [-k2, k2]], obstacle on mass 2, g0 = 1; k2 the parameter.
TWO_DOF_K2 = {
    "M": [[1.0, 0.0], [0.0, 1.0]],
    "K": {"constant": [[1.0, 0.0], [0.0, 0.0]], "k2": [[1.0, -1.0], [-1.0, 1.0]]},
    "w": [0.0, -1.0],
    "g0": 1.0,
    "parameter": {"name": "k2", "min": 1.0, "max": 10.0},
}
VALUES = [1.0, 1.5, 2.0, 2.5, 3.0, 3.5]
WINDOW = dict(t1_max=8.0, t2_max=8.0)


@pytest.fixture
def system_file(tmp_path):
    p = tmp_path / "two_dof_k2.json"
    p.write_text(json.dumps(TWO_DOF_K2))
    return str(p)


def out_dir(tmp_path, name):
    d = tmp_path / name
    d.mkdir()
    return str(d)


def test_each_values_spps_are_those_of_solve_at_that_value(system_file, tmp_path):
    table = spp.sweep(system_file, out_dir(tmp_path, "out"), parameter="k2", values=VALUES, workers=2, **WINDOW)
    ps = spp.ParametricSystem.from_json(system_file)
    assert [i["value"] for i in table["items"]] == VALUES
    for item in table["items"]:
        assert item["outcome"] == "solved", item["message"]
        direct = spp.solve(ps.at(item["value"]), threads=1, **WINDOW)
        assert [(s["t1"], s["t2"]) for s in item["spps"]] == [(s.t1, s.t2) for s in direct.solutions]
        assert len(item["spps"]) > 0
    csv = open(os.path.join(str(tmp_path / "out"), "sweep.csv")).read().splitlines()
    assert csv[0].startswith("index,k2,system_file,result_file,solve_status,t1,t2")
    assert len(csv) == 1 + sum(len(i["spps"]) for i in table["items"])


def test_a_sweep_run_again_resumes_and_a_failing_value_is_reported(system_file, tmp_path):
    d = out_dir(tmp_path, "out")
    values = [1.0, -0.9, 2.0]  # k2 = -0.9: K is not positive definite
    with pytest.warns(UserWarning, match=r"k2 = -0.9, lies outside the range \[1, 10\]"):
        first = spp.sweep(system_file, d, parameter="k2", values=values, workers=2, **WINDOW)
    assert [i["outcome"] for i in first["items"]] == ["solved", "failed", "solved"]
    assert "k2 = -0.9" in first["items"][1]["message"]
    written = {i["result_file"]: os.stat(i["result_file"]).st_mtime_ns for i in first["items"] if i["spps"]}
    with pytest.warns(UserWarning, match="outside the range"):
        again = spp.sweep(system_file, d, parameter="k2", values=values, workers=2, **WINDOW)
    assert [i["outcome"] for i in again["items"]] == ["resumed", "failed", "resumed"]
    assert {f: os.stat(f).st_mtime_ns for f in written} == written  # not written again
    assert [i["spps"] for i in again["items"]] == [i["spps"] for i in first["items"]]


def test_a_bad_plan_raises_value_error_before_any_solve(system_file, tmp_path):
    d = out_dir(tmp_path, "out")
    with pytest.raises(ValueError, match='declares the parameter "k2"'):
        spp.sweep(system_file, d, parameter="k3", values=[1.0], **WINDOW)
    with pytest.raises(ValueError, match="does not exist"):
        spp.sweep(system_file, d + "/missing", parameter="k2", values=[1.0], **WINDOW)
    with pytest.raises(ValueError, match="unknown option"):
        spp.sweep(system_file, d, parameter="k2", values=[1.0], t1_maximum=3, **WINDOW)
    assert os.listdir(d) == []


MPI_SCRIPT = """
import json, sys
import spp
table = spp.sweep(sys.argv[1], sys.argv[2], parameter="k2", values=json.loads(sys.argv[3]), t1_max=8.0, t2_max=8.0)
if table is not None:
    print("TABLE " + json.dumps([i["spps"] for i in table["items"]]))
"""


def test_under_mpirun_the_ranks_give_the_thread_pools_table(system_file, tmp_path):
    mpirun = shutil.which("mpirun")
    try:
        import mpi4py  # noqa: F401  (Debian python3-mpi4py, installed by scripts/install-deps.sh)
    except ImportError:
        mpi4py = None
    if mpirun is None or mpi4py is None:
        pytest.skip("mpirun or mpi4py not installed (scripts/install-deps.sh installs both)")
    script = tmp_path / "sweep_mpi.py"
    script.write_text(MPI_SCRIPT)
    d = out_dir(tmp_path, "mpi")
    r = subprocess.run([mpirun, "-n", "2", "--oversubscribe", "--allow-run-as-root", "-x", "PYTHONPATH",
                        sys.executable, str(script), system_file, d, json.dumps(VALUES)],
                       capture_output=True, text=True, timeout=600, env=dict(os.environ))
    assert r.returncode == 0, r.stdout + r.stderr
    lines = [l for l in r.stdout.splitlines() if l.startswith("TABLE ")]
    assert len(lines) == 1, r.stdout  # rank 0 only
    spread = json.loads(lines[0][len("TABLE "):])
    local = spp.sweep(system_file, out_dir(tmp_path, "threads"), parameter="k2", values=VALUES, workers=2, **WINDOW)
    assert spread == [i["spps"] for i in local["items"]]
    assert all(len(s) > 0 for s in spread)


# ---- issue 16's defects (an independent attack) ----

def test_values_and_workers_of_the_wrong_kind_are_refused_naming_the_argument(system_file, tmp_path):
    d = out_dir(tmp_path, "out")
    for values in ("25", "1:10:1", 3.0, 2):  # a str was iterated ('25' swept 2.0 and 5.0); a number a TypeError
        with pytest.raises(TypeError, match="values must be a list of numbers"):
            spp.sweep(system_file, d, parameter="k2", values=values, **WINDOW)
    with pytest.raises(TypeError, match="not read in Python"):
        spp.sweep(system_file, d, parameter="k2", values="1:10:1", **WINDOW)
    with pytest.raises(TypeError, match=r"values\[0\] must be a real number, got the bool True"):
        spp.sweep(system_file, d, parameter="k2", values=[True], **WINDOW)
    with pytest.raises(TypeError, match=r"values\[1\] must be a real number"):
        spp.sweep(system_file, d, parameter="k2", values=[1.0, "2"], **WINDOW)
    with pytest.raises(ValueError, match=r"values\[0\] must be finite, got nan"):
        spp.sweep(system_file, d, parameter="k2", values=[float("nan")], **WINDOW)
    for workers in (0, -1):
        with pytest.raises(ValueError, match="workers must be >= 1"):
            spp.sweep(system_file, d, parameter="k2", values=[1.0], workers=workers, **WINDOW)
    for workers in (1.5, True, "2"):
        with pytest.raises(TypeError, match="workers must be a whole number"):
            spp.sweep(system_file, d, parameter="k2", values=[1.0], workers=workers, **WINDOW)
    assert os.listdir(d) == []


def test_python_errors_do_not_name_the_cli_flag(system_file, tmp_path):
    with pytest.raises(ValueError) as e:
        spp.sweep(system_file, out_dir(tmp_path, "out"), parameter="k3", values=[1.0], **WINDOW)
    assert 'declares the parameter "k2"' in str(e.value) and "--parameter" not in str(e.value)


def test_a_refused_resume_writes_nothing(system_file, tmp_path):
    # another window (or options) in the same out_dir: ValueError before any solve, the first table kept
    d = out_dir(tmp_path, "out")
    spp.sweep(system_file, d, parameter="k2", values=[1.0, 2.0], workers=1, **WINDOW)
    table = open(os.path.join(d, "sweep.json")).read()
    with pytest.raises(ValueError, match="holds results this sweep cannot resume from.*the window"):
        spp.sweep(system_file, d, parameter="k2", values=[1.0, 2.0], workers=1, t1_max=7.0, t2_max=8.0)
    # (named as Python says it too: certify_steps=False, found by an independent attack on the CLI-only wording)
    with pytest.raises(ValueError, match=r"certified steps.*certify_steps=False"):
        spp.sweep(system_file, d, parameter="k2", values=[1.0, 2.0], workers=1, certify_steps=False, **WINDOW)
    assert open(os.path.join(d, "sweep.json")).read() == table


def test_an_out_dir_that_cannot_be_written_is_refused_before_any_solve(system_file, tmp_path):
    f = tmp_path / "a_file"
    f.write_text("x")
    with pytest.raises(ValueError, match="is not a directory"):
        spp.sweep(system_file, str(f), parameter="k2", values=[1.0], **WINDOW)
    if os.geteuid() != 0:  # as root, chmod does not stop writes
        d = out_dir(tmp_path, "ro")
        os.chmod(d, 0o500)
        try:
            with pytest.raises(ValueError, match="cannot write in the directory"):
                spp.sweep(system_file, d, parameter="k2", values=[1.0], **WINDOW)
        finally:
            os.chmod(d, 0o700)
        assert os.listdir(d) == []


def test_a_value_outside_the_declared_range_is_warned(system_file, tmp_path):
    with pytest.warns(UserWarning, match=r"k2 = 0.5, lies outside the range \[1, 10\]"):
        table = spp.sweep(system_file, out_dir(tmp_path, "out"), parameter="k2", values=[0.5], workers=1, **WINDOW)
    assert table["items"][0]["outcome"] == "solved"
