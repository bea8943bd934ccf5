#!/usr/bin/env python3
"""How close do the k-IPP families come to the SPPs as k grows (the paper's §1 conjecture, issue 15)?

Runs `spp solve` (admissible SPPs of a window) and `spp modes` (k-IPP families, k = 1..K) on one system and prints,
for each k and each admissible SPP, the distance from the SPP to the nearest admissible point of a k-IPP family on the
frequency-energy plot: d = sqrt(ln(E / E_spp)^2 + ((f - f_spp) / f_spp)^2), with its two parts. "genuine" counts only
families of least period T (multiplicity 1); "all" also the repetitions of shorter orbits. Points only: the distance
to a polyline between points is not interpolated (max_step bounds the spacing).

usage: modes_vs_spps.py SYSTEM.json --kmax K [--window 12] [--spp build/spp] [--modes-args '--multiples 13 ...']
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("system")
    ap.add_argument("--kmax", type=int, default=6)
    ap.add_argument("--window", type=float, default=12.0)
    ap.add_argument("--spp", default=os.path.join(os.path.dirname(__file__), "..", "build", "spp"))
    ap.add_argument("--energy-factor", type=float, default=1.5, help="energy_max = factor * largest SPP energy")
    ap.add_argument("--modes-args", default="", help="more arguments of spp modes, e.g. '--multiples 13 "
                    "--through-inadmissible'")
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as d:
        solve = os.path.join(d, "solve.json")
        subprocess.run([a.spp, "solve", a.system, "--t1-max", str(a.window), "--t2-max", str(a.window),
                        "--admissible-only", "--json", solve], check=True, stdout=subprocess.DEVNULL)
        spps = [s for s in json.load(open(solve))["solutions"] if s["admissible"]]
        if not spps:
            sys.exit("no admissible SPP in the window")
        emax = a.energy_factor * max(s["energy"] for s in spps)
        modes = os.path.join(d, "modes.json")
        out = subprocess.run([a.spp, "modes", a.system, "--k", f"1..{a.kmax}", "--energy-max", repr(emax),
                              "--json", modes] + a.modes_args.split(), check=True, capture_output=True, text=True)
        families = json.load(open(modes))["families"]
    print(out.stdout.strip().splitlines()[-1])
    print(f"{len(spps)} admissible SPPs in (0, {a.window}]^2; energy_max {emax:.4g}")
    print("| SPP | " + " | ".join(f"#{i}" for i in range(len(spps))) + " |")
    print("|---|" + "---|" * len(spps))
    print("| E | " + " | ".join(f"{s['energy']:.3g}" for s in spps) + " |")
    print("| f | " + " | ".join(f"{2 * math.pi / s['period']:.4f}" for s in spps) + " |")
    for kind in ("genuine", "all"):
        print(f"| d, k-IPPs ({kind}) | " + " | ".join("" for _ in spps) + " |")
        for k in range(1, a.kmax + 1):
            row = []
            for s in spps:
                es, fs = s["energy"], 2 * math.pi / s["period"]
                best = math.inf
                for f in families:
                    if f["k"] != k or (kind == "genuine" and f["multiplicity"] != 1):
                        continue
                    for p in f["points"]:
                        if p["admissible"] and p["energy"] > 0:
                            best = min(best, math.hypot(math.log(p["energy"] / es), (p["frequency"] - fs) / fs))
                row.append("-" if best == math.inf else f"{best:.2g}")
            print(f"| k = {k} | " + " | ".join(row) + " |")

if __name__ == "__main__":
    main()
