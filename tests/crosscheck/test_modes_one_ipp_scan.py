"""`spp modes --k 1 --multiples J` against the independent scan of the explicit 1-IPP form (modes_one_ipp_scan.py).

The paper's 2-dof system of §2.3 (`spp generate two-dof`), E <= 20, T <= 21: the scan finds 4 admissible 1-IPP
branches, and `spp modes` lists all 4 with `--multiples 6` (2 without: the other two leave mode 2's grazing orbit at
period multiples, docs/modes.md §3). The spp command-line tool is given by the SPP_CLI environment variable (CTest
sets it). Followed through their inadmissible orbits (`--through-inadmissible`), the families reach every admissible
branch of chain5 and of a random 6-dof system too (docs/modes.md §3).
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


def test_chain5_every_admissible_one_ipp_branch_is_listed_through_inadmissible_orbits():
    # E <= 5, T <= 40: 14 branches; the seeds at multiples up to 13 alone reach 8 (6 lie beyond inadmissible orbits)
    common = [os.path.join(os.path.dirname(__file__), "..", "..", "examples", "chain5.json"), "--energy-max", "5",
              "--period-max", "40", "--spp", SPP, "--multiples", "13"]
    assert scan.main(common) == (8, 14)
    assert scan.main(common + ["--through-inadmissible"]) == (14, 14)


def test_random_system_every_admissible_one_ipp_branch_is_listed_through_inadmissible_orbits(tmp_path):
    system = tmp_path / "r4.json"
    subprocess.run([SPP, "generate", "random", "--n", "6", "--seed", "4", "--out", str(system)], check=True,
                   capture_output=True)
    common = [str(system), "--energy-max", "10", "--period-max", "40", "--spp", SPP, "--multiples", "40"]
    assert scan.main(common) == (26, 31)
    assert scan.main(common + ["--through-inadmissible"]) == (31, 31)
