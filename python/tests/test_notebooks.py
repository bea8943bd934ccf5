"""The example notebooks (examples/*.ipynb) are executed from examples/ with Debian's nbclient: every cell must run,
and the cells assert what they show (the paper's values, statuses, the simulator's return), so they cannot rot."""
import glob
import os

import nbclient
import nbformat
import pytest

import spp

SRC = os.environ.get("SPP_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
EXAMPLES = os.path.join(SRC, "examples")
NOTEBOOKS = sorted(glob.glob(os.path.join(EXAMPLES, "*.ipynb")))


def test_the_examples_hold_the_paper_figures_and_a_parameter_study():
    names = {os.path.basename(p) for p in NOTEBOOKS}
    assert {"paper_figures.ipynb", "parameter_study.ipynb"} <= names


@pytest.mark.parametrize("path", NOTEBOOKS, ids=os.path.basename)
def test_notebook_runs_and_its_checks_pass(path, monkeypatch):
    monkeypatch.setenv("PYDEVD_DISABLE_FILE_VALIDATION", "1")  # ipykernel's debugger warning on frozen modules
    # the kernel runs in examples/ and must import the spp under test (not an installed one): its folder first, absolute
    here = os.path.dirname(os.path.dirname(os.path.abspath(spp.__file__)))
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join([here] + [os.path.abspath(p) for p in
                                                                os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]))
    nb = nbformat.read(path, as_version=4)
    client = nbclient.NotebookClient(nb, timeout=600, kernel_name="python3",
                                     resources={"metadata": {"path": EXAMPLES}})
    client.execute()  # raises CellExecutionError, with the cell and its traceback, on any failure
    images = sum("image/png" in o.get("data", {}) for c in nb.cells for o in c.get("outputs", []))
    assert images >= 1  # the figures were drawn inline (no backend switch)
