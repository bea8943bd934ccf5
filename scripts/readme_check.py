#!/usr/bin/python3
"""README's figures, re-run: each claim below names a README line (a regular expression whose groups are the figures
it states), the command that produces them, and how the figure is read from that command's output. Every claim is
checked; each one that no longer holds is named with its README line number, the stated and the measured value.
Exit 0 when every figure holds, 1 otherwise (2 when a command fails or README no longer has the line).

Usage: scripts/readme-check.sh [--readme README.md] [BUILD_DIR]   (default build/: runs BUILD_DIR/spp)
Tolerances: counts and statuses exactly; (t1, t2), k2 and box edges to the digits README prints them with (relative
1e-7, or half a unit of the last printed digit); times are never compared (they depend on the machine's load).
"""
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# The commands, run once each in a temporary directory (files they write are read by the later ones); {spp} is the
# executable, {ex} the examples directory.
COMMANDS = {
    "solve_a": "{spp} solve {ex}/chain5.json --t1-max 12 --t2-max 12 --admissible-only --json c5a.json",
    "solve_all": "{spp} solve {ex}/chain5.json --t1-max 12 --t2-max 12 --json c5.json --quiet",
    "rod": "{spp} solve {ex}/rod4.json --t1-max 12 --t2-max 12 --admissible-only",
    "box": "{spp} solve {ex}/chain5.json --box",
    "dry": "{spp} solve {ex}/chain5.json --t1-max 12 --t2-max 12 --dry-run",
    "verify": "{spp} verify c5.json",
    "verify_periods": "{spp} verify c5a.json --periods 100 --perturb 1e-6 --restitution 0.5",
    "zero_gap": "{spp} solve {ex}/two_dof_zero_gap.json --t1-max 3 --t2-max 1",
    "dry20": "{spp} generate chain --n 20 --out c20.json && {spp} solve c20.json --box --dry-run",
    "modes": "{spp} modes {ex}/chain5.json --k 1..5 --energy-max 150",
    "ctest": "ctest --test-dir {build} -N",
    "sweep": "{spp} generate two-dof --g0 1 --parameter k2 --range 1,10 --out k2.json && mkdir runs && "
             "{spp} sweep k2.json --parameter k2 --values 1:10:0.25 --t1-max 8 --t2-max 8 --out-dir runs",
}


def summary(pattern, group=1):
    """Group `group` of the first output match of `pattern`."""
    def read(out, _group):
        m = re.search(pattern, out, re.M)
        return m.group(group) if m else None
    return read


def summary_or(pattern, default):
    """summary(pattern), or `default` when no output line matches (an event kind absent from the summary)."""
    def read(out, _group):
        m = re.search(pattern, out, re.M)
        return m.group(1) if m else default
    return read


def row(index, column):
    """Column `column` (0-based, after '#') of the table row whose first field is `index`."""
    def read(out, _group):
        for line in out.splitlines():
            f = line.split()
            if len(f) > column and f[0] == str(index):
                return f[column]
        return None
    return read


def count(pattern):
    """How many output lines match `pattern`."""
    return lambda out, _group: str(len(re.findall(pattern, out, re.M)))


# (README pattern with one group per stated figure, command, [reader per group], comparison per group)
# comparison: "exact" (counts, statuses) or "digits" (as many significant digits as README prints).
CLAIMS = [
    # Quick start: setup.sh's solve (the summary line and the 7 rows)
    (r"^spp: (\w+), (\d+) SPPs \((\d+) admissible\) in \(0\.0409278, 12\] x \(0\.0412908, 12\]; (\d+) rectangles, "
     r"(\d+) curve pieces, (\d+) evaluations",
     "solve_a",
     [summary(r"^spp: (\w+), (\d+) SPPs \((\d+) admissible\).*?; (\d+) rectangles, (\d+) curve pieces, (\d+) "
              r"evaluations", g) for g in range(1, 7)], ["exact"] * 6),
] + [
    (r"^   %d\s+(\S+)\s+(\S+)\s+(\S+)\s+yes\s+\S+\s+\S+\s+(\S+)\s+(yes|no)$" % i, "solve_a",
     [row(i, 1), row(i, 2), row(i, 3), row(i, 7), row(i, 8)], ["digits", "digits", "digits", "digits", "exact"])
    for i in range(7)
] + [
    (r"^Without `--admissible-only` the same window holds (\d+) potential SPPs", "solve_all",
     [summary(r"^spp: \w+, (\d+) SPPs")], ["exact"]),
    (r"^has (\d+) admissible SPPs in `\(0, 12\]\^2`, at `\(t1, t2\) = \((\S+), (\S+)\)` and `\((\S+), (\S+)\)`", "rod",
     [summary(r"^spp: \w+, \d+ SPPs \((\d+) admissible\)"), row(0, 1), row(0, 2), row(1, 1), row(1, 2)],
     ["exact", "digits", "digits", "digits", "digits"]),
    (r"^   0\s+(5\.4\S+)\s+(\S+)\s+\S+\s+yes\s+\S+\s+\S+\s+(\S+)\s+(yes|no)$", "rod",
     [row(0, 1), row(0, 2), row(0, 7), row(0, 8)], ["digits", "digits", "digits", "exact"]),
    (r"^   1\s+(7\.2\S+)\s+(\S+)\s+\S+\s+yes\s+\S+\s+\S+\s+(\S+)\s+(yes|no)$", "rod",
     [row(1, 1), row(1, 2), row(1, 7), row(1, 8)], ["digits", "digits", "digits", "exact"]),
    # Fundamental box
    (r"t1 <= (\S+),$", "box", [summary(r"t1 <= pi / omega_1 = (\S+),")], ["digits"]),
    (r"^t2 <= (\S+), (\d+) potential SPPs, (\d+) admissible\.", "box",
     [summary(r"t2 <= pi / d_1 = (\S+)$"), summary(r"^spp: \w+, (\d+) SPPs"),
      summary(r"^spp: \w+, \d+ SPPs \((\d+) admissible\)")], ["digits", "exact", "exact"]),
    # --dry-run
    (r"of magnitude\), then stops and writes nothing: for the paper's chain in `\(0, 12\]\^2`, (\d+) cells", "dry",
     [summary(r", (\d+) cells$")], ["exact"]),
    (r"fundamental box \(`spp generate chain --n 20`, `--box`\), (\d+) (\d+) cells", "dry20",
     [lambda out, g: (summary(r", (\d+) cells$")(out, 0) or "")[:-3], lambda out, g: (summary(r", (\d+) cells$")(out, 0)
                                                                                       or "")[-3:]],
     ["exact", "exact"]),
    # Nonsmooth modes (the CLI runs what README's Python line runs)
    (r"energy_max=150\)`: (\d+) families, (\d+) genuine, \S+ s, status `(\w+)`:$", "modes",
     [summary(r"^spp modes: (\w+), (\d+) families \((\d+) genuine", g) for g in (2, 3, 1)], ["exact"] * 3),
    (r"^(\d+) families end in closed loops, (\d+) stalled; markers", "modes",
     [summary_or(r" closed_loop (\d+)", "0"), summary_or(r" stalled (\d+)", "0")], ["exact", "exact"]),
    # Sweeps
    (r"--values 1:10:0\.25 --t1-max 8 --t2-max 8 --out-dir runs   # (\d+) values", "sweep",
     [summary(r"^sweep over k2: (\d+) values, \1 done")], ["exact"]),
    # The verify block
    (r"^verify: (\w+), (\d+) SPPs, (\d+) return to their initial state, (\d+) leave the orbit; (\d+) disagree",
     "verify",
     [summary(r"^verify: (\w+), (\d+) SPPs, (\d+) return to their initial state, (\d+) leave the orbit; (\d+) "
              r"disagree", g) for g in range(1, 6)], ["exact"] * 5),
    (r"^The (\d+) inadmissible SPPs of the chain leave in all three ways", "verify",
     [summary(r"(\d+) leave the orbit")], ["exact"]),
    (r"^impact, (\d+) early releases, (\d+) missing onsets\)", "verify",
     [count(r"release at t = .*before the end"), count(r"no contact onset at t = 0")], ["exact", "exact"]),
    (r"lists them: (\d+)\nimpact, \d+ early releases", "verify", [count(r"impact at t = ")], ["exact"]),
] + [
    (r"^   %d\s+(\S+)\s+(\S+)\s+yes\s+\S+\s+(returns|leaves)\s+(\d+/\d+)\s" % i, "verify_periods",
     [row(i, 1), row(i, 2), row(i, 5), row(i, 6)], ["digits", "digits", "exact", "exact"])
    for i in range(7)
] + [
    (r"^verify: (\w+), (\d+) SPPs, (\d+) return to their initial state, (\d+) leave the orbit; (\d+) disagree.*$"
     r"(?![\s\S]*^verify: )", "verify_periods",
     [summary(r"^verify: (\w+), (\d+) SPPs, (\d+) return to their initial state, (\d+) leave the orbit; (\d+) "
              r"disagree", g) for g in range(1, 6)], ["exact"] * 5),
    (r"simulator from their own rounded initial state for only (\d+), (\d+) and (\d+) periods", "verify_periods",
     [lambda out, g, i=i: (row(i, 6)(out, 0) or "").split("/")[0] for i in (0, 4, 6)], ["exact"] * 3),
    # §6.1 zero gap
    (r"^   0\s+(1\.6\S+)\s+(\S+)\s+(\S+)\s+\S+\s+(yes|no)\s", "zero_gap", [row(0, 1), row(0, 2), row(0, 3), row(0, 5)],
     ["digits", "digits", "digits", "exact"]),
    (r"^   1\s+(5\.7\S+)\s+(\S+)\s+(\S+)\s+\S+\s+(yes|no)\s", "zero_gap", [row(1, 1), row(1, 2), row(1, 3), row(1, 5)],
     ["digits", "digits", "digits", "exact"]),
]


# Reported beside README's, never compared: times (they depend on the machine and its load), and the number of CTest
# tests (it depends on which targets the build tree holds: a partial build lists fewer).
REPORTED = [
    (r"runs (\d+) CTest tests", "ctest", summary(r"^Total Tests: (\d+)")),
    (r"^spp: success, 7 SPPs \(7 admissible\) in .* evaluations, (\S+) s$", "solve_a",
     summary(r"^spp: \w+, 7 SPPs .* evaluations, (\S+) s$")),
    (r"energy_max=150\)`: \d+ families, \d+ genuine, (\S+) s,", "modes", summary(r"corrector solves, (\S+) s$")),
]


# README's Python API block (the one that starts with PYTHON_BLOCK_START) is run as it is, from the repository's root
# (its paths are relative to it) with the build's package: it was never run, so it could rot unseen (found by an
# independent attack). It takes seconds (a few solves of the paper's chain); PYTHON_BLOCK_TIMEOUT bounds it.
PYTHON_BLOCK_START = "import numpy as np, pickle, spp"
PYTHON_BLOCK_TIMEOUT = 120  # seconds; it runs in ~10 s on an idle 2-core machine


def python_blocks(readme):
    """(line number, code) of each ```python block of README that starts with PYTHON_BLOCK_START."""
    out = []
    for m in re.finditer(r"^```python\n(.*?)^```$", readme, re.M | re.S):
        if m.group(1).startswith(PYTHON_BLOCK_START):
            out.append((readme.count("\n", 0, m.start()) + 2, m.group(1)))
    return out


def run_python_blocks(readme, name, build):
    """Runs each block of python_blocks(); returns how many failed (each named with its line and the error)."""
    blocks = python_blocks(readme)
    if not blocks:
        print(f"{name}: no ```python block starts with {PYTHON_BLOCK_START!r} (README changed: update "
              f"scripts/readme_check.py)")
        return 1
    env = dict(os.environ, PYTHONPATH=os.path.join(build, "python") + os.pathsep + os.environ.get("PYTHONPATH", ""),
               MPLBACKEND="Agg")
    failed = 0
    for line_no, code in blocks:
        try:
            r = subprocess.run(["/usr/bin/python3", "-c", code], cwd=ROOT, env=env, capture_output=True, text=True,
                               timeout=PYTHON_BLOCK_TIMEOUT)
            ok, why = r.returncode == 0, (r.stderr.strip().splitlines() or ["(no message)"])[-1]
        except subprocess.TimeoutExpired:
            ok, why = False, f"still running after {PYTHON_BLOCK_TIMEOUT} s"
        if not ok:
            failed += 1
            print(f"{name}:{line_no}: the Python block fails: {why}")
    return failed


def agrees(stated, measured, how):
    if measured is None:
        return False
    if how == "exact":
        return stated == measured
    try:
        s, m = float(stated), float(measured)
    except ValueError:
        return stated == measured
    digits = len(re.sub(r"[^0-9]", "", stated.split("e")[0]).lstrip("0")) or 1
    return abs(s - m) <= max(1e-7 * abs(s), 0.5 * 10 ** (-digits + 1) * abs(s) * 1.0000001)


def main():
    args = sys.argv[1:]
    readme_path = os.path.join(ROOT, "README.md")
    if len(args) >= 2 and args[0] == "--readme":  # another README (the script's own test: a changed figure is named)
        readme_path, args = args[1], args[2:]
    build = os.path.abspath(args[0] if args else os.path.join(ROOT, "build"))
    spp = os.path.join(build, "spp")
    readme = open(readme_path, encoding="utf-8").read()
    name = os.path.relpath(readme_path)
    lines = readme.splitlines()
    outputs, failed = {}, 0
    with tempfile.TemporaryDirectory(prefix="readme-check-") as tmp:
        for key, cmd in COMMANDS.items():
            text = cmd.format(spp=spp, ex=os.path.join(ROOT, "examples"), build=build)
            r = subprocess.run(text, shell=True, cwd=tmp, capture_output=True, text=True, timeout=300)
            if r.returncode not in (0, 3):
                print(f"readme-check: command failed (exit {r.returncode}): {text}\n{r.stderr}", file=sys.stderr)
                return 2
            outputs[key] = r.stdout + r.stderr
        failed += run_python_blocks(readme, name, build)
    checked = 0
    for pattern, key, readers, hows in CLAIMS:
        m = re.search(pattern, readme, re.M)
        if not m:
            print(f"{name}: no line matches the claim /{pattern}/ (README changed: update scripts/readme_check.py)")
            failed += 1
            continue
        line_no = readme.count("\n", 0, m.start()) + 1
        for g, (read, how) in enumerate(zip(readers, hows), start=1):
            stated, measured = m.group(g), read(outputs[key], g)
            checked += 1
            if not agrees(stated, measured, how):
                failed += 1
                shown = COMMANDS[key].format(spp="spp", ex="examples", build="build")
                print(f"{name}:{line_no}: states {stated!r}, `{shown}` gives {measured!r}\n"
                      f"    {lines[line_no - 1].strip()[:160]}")
    for pattern, key, read in REPORTED:
        m = re.search(pattern, readme, re.M)
        if m:
            line_no = readme.count("\n", 0, m.start()) + 1
            print(f"{name}:{line_no}: reported, not compared: README {m.group(1)}, this run {read(outputs[key], 1)} "
                  f"({m.group(0)[:60]!r})")
    print(f"readme-check: {checked} figures in {len(CLAIMS)} README lines, {failed} no longer hold")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
