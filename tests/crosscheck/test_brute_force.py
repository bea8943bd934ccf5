"""Completeness of `spp solve` against the independent brute force (brute_force.py, written from the paper alone).

A handful of windows from compare_windows.py: the paper's chain5 SPP (3.2160302, 0.52773599) in a window away
from both axes, three random dense systems (n = 2, 3, 5) in windows away from the axes, and one window split
into tiles whose union must be the whole window's roots. Every root of the brute force must be found by spp
and every root of spp by the brute force (|t_i - t_i'| <= 1e-7 |t_i|), with status "success".
The spp command-line tool is given by the SPP_CLI environment variable (CTest sets it).
"""
import os
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import compare_windows as cw  # noqa: E402


def check(rec):
    assert rec["brute_certified"], rec["brute_warnings"]
    assert not rec["brute_unverified"]
    assert rec["brute"] >= 1                      # the window is not empty: the comparison means something
    assert rec["missing_in_spp"] == [], f"spp misses brute-force roots: {rec['spp_cmd']}"
    assert rec["extra_in_spp"] == [], f"spp has roots the brute force does not: {rec['spp_cmd']}"
    assert rec["spp_status"] == "success", rec["spp_cmd"]


def test_chain5_paper_spp_in_a_window_away_from_the_axes(tmp_path):
    rec = cw.run_case("chain5", cw.load_example("chain5.json"), [3.1, 3.3, 0.45, 0.6], str(tmp_path))
    check(rec)
    assert rec["brute"] == 1


# (n, seed, window in quarter periods pi/(2 f_max) of the flight and contact phases)
RANDOM = [(2, 18, (3.0, 7.0, 2.0, 6.0)), (3, 12, (3.0, 7.0, 2.0, 6.0)), (5, 14, (3.0, 7.0, 2.0, 6.0))]


def _window(system, w):
    q1, q2, _ = cw.scales(system)
    return [w[0] * q1, w[1] * q1, w[2] * q2, w[3] * q2]


@pytest.mark.parametrize("n,seed,w", RANDOM)
def test_random_system_small_window(tmp_path, n, seed, w):
    system = cw.random_system(n, np.random.default_rng(seed))
    check(cw.run_case(f"random_n{n}_s{seed}", system, _window(system, w), str(tmp_path)))


def test_tiles_union_is_the_whole_window(tmp_path):
    system = cw.random_system(4, np.random.default_rng(13))
    rec = cw.run_case("random_n4_s13", system, _window(system, (3.0, 7.0, 2.0, 6.0)), str(tmp_path), tiles=4,
                      rng=np.random.default_rng(5))
    check(rec)
    t = rec["tiling"]
    assert all(s == "success" for s in t["statuses"]), t["cmds"]
    assert t["duplicates"] == 0
    for k in ("whole_not_in_union", "union_not_in_whole", "brute_not_in_union", "union_not_in_brute"):
        assert t[k] == [], (k, t["cmds"])
