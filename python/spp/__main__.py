"""python3 -m spp plot RESULT.json --out DIR: the figures of a result of `spp solve --json` (also run by
`spp plot`). Writes DIR/frequency_energy.{png,svg} and DIR/spp_K.{png,svg} for each admissible SPP K."""
import argparse
import json
import os
import sys
from types import SimpleNamespace

import numpy as np

from ._spp import System


def load_result(path):
    """The system and the solutions (attribute access, numpy x0/v0) of a result JSON."""
    try:
        with open(path) as f:
            r = json.load(f)
    except (OSError, ValueError) as e:
        raise ValueError(f"{path}: cannot read a result JSON: {e}") from None
    if not isinstance(r, dict) or "system" not in r or "solutions" not in r:
        raise ValueError(f'{path}: expected a result of spp solve (fields "system" and "solutions")')
    s = r["system"]
    if "M" not in s or "K" not in s:
        raise ValueError(f'{path}: field "system" has no "M" and "K" (a result from an older spp): run spp solve again')
    system = System(np.array(s["M"], float), np.array(s["K"], float), np.array(s["w"], float), float(s["g0"]),
                    s.get("name", ""))
    sols = []
    for k, o in enumerate(r["solutions"]):
        try:
            sols.append(SimpleNamespace(t1=float(o["t1"]), t2=float(o["t2"]), period=float(o["period"]),
                                        admissible=bool(o["admissible"]), energy=float(o["energy"]),
                                        x0=np.array(o["x0"], float), v0=np.array(o["v0"], float)))
        except (KeyError, TypeError, ValueError) as e:
            raise ValueError(f"{path}: solutions[{k}]: missing or invalid field {e}") from None
    return system, SimpleNamespace(solutions=sols)


def main(argv=None):
    ap = argparse.ArgumentParser(prog="spp plot", description="figures of a result of spp solve")
    ap.add_argument("command", choices=["plot"])
    ap.add_argument("result", help="result JSON of spp solve --json")
    ap.add_argument("--out", required=True, help="output directory (created if missing)")
    ap.add_argument("--formats", default="png,svg", help="comma-separated: png, svg, pdf (default png,svg)")
    a = ap.parse_args(argv)
    try:
        from . import plot
        system, result = load_result(a.result)
        formats = [f.strip() for f in a.formats.split(",") if f.strip()]
        bad = [f for f in formats if f not in ("png", "svg", "pdf")]
        if bad:
            raise ValueError(f"--formats: expected png, svg or pdf, got {', '.join(bad)}")
        os.makedirs(a.out, exist_ok=True)
        written = []
        import matplotlib.pyplot as plt
        for fmt in formats:
            p = os.path.join(a.out, f"frequency_energy.{fmt}")
            plt.close(plot.frequency_energy_figure(result, path=p))
            written.append(p)
            for k, sol in enumerate(result.solutions):
                if sol.admissible:
                    p = os.path.join(a.out, f"spp_{k}.{fmt}")
                    plt.close(plot.spp_figure(system, sol, path=p))
                    written.append(p)
    except ValueError as e:
        print(f"spp: error: {e}", file=sys.stderr)
        return 1
    print(f"wrote {len(written)} figures to {a.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
