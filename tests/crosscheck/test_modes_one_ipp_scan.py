"""`spp modes --k 1 --multiples J` against the independent scan of the explicit 1-IPP form (modes_one_ipp_scan.py).

The paper's 2-dof system of §2.3 (`spp generate two-dof`), E <= 20, T <= 21: the scan finds 4 admissible 1-IPP
branches, and `spp modes` lists all 4 with `--multiples 6` (2 without: the other two leave mode 2's grazing orbit at
period multiples, docs/modes.md §3). The spp command-line tool is given by the SPP_CLI environment variable (CTest
sets it).
"""
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import modes_one_ipp_scan as scan  # noqa: E402

SPP = os.environ.get("SPP_CLI", "build/spp")


def test_two_dof_every_admissible_one_ipp_branch_is_listed_with_multiples(tmp_path):
    system = tmp_path / "two_dof.json"
    subprocess.run([SPP, "generate", "two-dof", "--out", str(system)], check=True, capture_output=True)
    common = [str(system), "--energy-max", "20", "--period-max", "21", "--spp", SPP]
    listed, found = scan.main(common + ["--multiples", "6"])
    assert (listed, found) == (4, 4)
    listed_without, found_without = scan.main(common)  # the grazing starts alone: the check can fail
    assert (listed_without, found_without) == (2, 4)
