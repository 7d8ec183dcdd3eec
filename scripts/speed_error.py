#!/usr/bin/python3
"""Speed against error: runs the study of tests/verification/convergence_speed_error.cpp at full scale
and prints a Markdown table (problem, zones, cycles, CPU seconds, error, ns per zone-cycle)
for docs/performance.md, and with --plot FILE a log-log plot of error against seconds (matplotlib).

    scripts/speed_error.py [--tests build/tests/krug_convergence_tests] [--scale 1] [--plot speed_error.png]
                           [--cfl C] [--growth G] [--viscosity edge|tensor|scalar|auto]

--cfl and --growth override every run's CFL numbers (controls.cfl and controls.cfl_fluid) and
controls.time_step_growth (to compare the
time-step control against accuracy side by side); --viscosity sets every run's controls.viscosity.model.

The error is the L1 density error against the exact profile for the gas problems and, for the Taylor
bar, the mean relative error of its length and impact-face radius against their converged values.
The seconds are the runs' own clock (one thread); run on a quiet machine.
"""
import argparse
import os
import re
import subprocess
import sys


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--tests", default=os.path.join(here, "..", "build", "tests", "krug_convergence_tests"))
    parser.add_argument("--scale", default="1")
    parser.add_argument("--plot")
    parser.add_argument("--cfl")
    parser.add_argument("--growth")
    parser.add_argument("--viscosity", choices=["edge", "tensor", "scalar", "auto"])
    args = parser.parse_args()
    env = dict(os.environ, KRUG_VERIFICATION_REPORT="1", KRUG_CONVERGENCE_SCALE=args.scale)
    if args.cfl:
        env["KRUG_STUDY_CFL"] = args.cfl
    if args.growth:
        env["KRUG_STUDY_GROWTH"] = args.growth
    if args.viscosity:
        env["KRUG_STUDY_VISCOSITY"] = args.viscosity
    run = subprocess.run([args.tests, "[speed_error]"], env=env, capture_output=True, text=True)
    rows = []
    for line in run.stdout.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) != 7 or not cells[0].startswith("speed-error "):
            continue
        problem = cells[0][len("speed-error "):]
        cycles = int(re.search(r"(\d+) cycles", cells[1]).group(1))
        seconds = float(re.search(r", ([0-9.eE+-]+) s$", cells[4]).group(1))
        rows.append((problem, int(cells[5]), cycles, seconds, float(cells[3])))
    if run.returncode != 0:
        print(run.stdout[-3000:], file=sys.stderr)
        print("speed_error.py: the study failed (exit %d)" % run.returncode, file=sys.stderr)
    print("| problem | zones | cycles | seconds | error | ns per zone-cycle |")
    print("|---|---:|---:|---:|---:|---:|")
    for problem, zones, cycles, seconds, error in rows:
        ns = 1e9 * seconds / (zones * cycles) if seconds > 0 else float("nan")
        print(f"| {problem} | {zones} | {cycles} | {seconds:.3g} | {error:.4g} | {ns:.0f} |")
    if args.plot and rows:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(7, 5))
        for problem in dict.fromkeys(r[0] for r in rows):
            points = [(r[3], r[4]) for r in rows if r[0] == problem and r[3] > 0]
            if points:
                ax.loglog(*zip(*points), "o-", label=problem)
        ax.set_xlabel("CPU seconds (one thread)")
        ax.set_ylabel("L1 density error (Taylor bar: mean relative error)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(args.plot, dpi=120)
    return run.returncode


if __name__ == "__main__":
    sys.exit(main())
