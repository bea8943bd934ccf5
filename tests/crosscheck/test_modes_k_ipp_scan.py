"""`spp modes --k 2` against the independent k-IPP search (modes_k_ipp_scan.py: least squares from random starts on
the periodic-orbit equations, exact modal flow, e = 1 impact map, no symmetry assumed).

The paper's 2-dof system of §2.3 (`spp generate two-dof`), at E = 5, 12, 19 (T <= 21): the search finds 12 admissible
genuine 2-IPPs (4 at each energy, among them the non-reversible one of constant period 7.990517 and the (I, I) one
of period 11.570212), and `spp modes --k 2 --multiples 6` lists every one (it listed 1 before the families with no
symmetry assumed, docs/modes.md §3). The spp command-line tool is given by the SPP_CLI environment variable (CTest
sets it).
"""
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import modes_k_ipp_scan as scan  # noqa: E402

SPP = os.environ.get("SPP_CLI", "build/spp")


def test_two_dof_every_admissible_two_ipp_found_is_listed(tmp_path):
    system = tmp_path / "two_dof.json"
    subprocess.run([SPP, "generate", "two-dof", "--out", str(system)], check=True, capture_output=True)
    counts = scan.main([str(system), "--k", "2", "--energies", "5", "12", "19", "--period-max", "21", "--starts",
                        "300", "--seed", "1", "--spp", SPP, "--spp-args", "--multiples 6"])
    listed, found = counts[2]
    assert found >= 12  # measured: 12
    assert listed == found
