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


# Issue 15: the paper's chain (examples/chain5.json), k = 2, sampled at E = 1, 3, 5 (T <= 40): the independent search
# finds 38 admissible genuine 2-IPPs; `spp modes --multiples 13 --through-inadmissible` listed 11 of them, with
# `--seed-period-max 40` (families seeded from the plane of the two flight durations, docs/modes.md §3) 35. The orbits
# still missed are printed (NOT LISTED): non-reversible ones (unequal impact speeds).
def test_chain5_two_ipps_found_by_the_search_are_listed_with_seeds(capsys):
    system = os.path.join(os.environ.get("SPP_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", "..")),
                          "examples", "chain5.json")
    counts = scan.main([system, "--k", "2", "--energies", "1", "3", "5", "--period-max", "40", "--starts", "300",
                        "--seed", "1", "--spp", SPP, "--spp-args",
                        "--multiples 13 --through-inadmissible --seed-period-max 40"])
    listed, found = counts[2]
    missed = [line for line in capsys.readouterr().out.splitlines() if "NOT LISTED" in line]
    print("\n".join(missed))
    assert found >= 38  # measured: 38
    assert listed >= 35, missed  # measured: 35 (11 without the seeds)
