#!/usr/bin/env python3
"""Plots of a Krug run's history.csv against time (called by `krug run` when output.plots is on).

usage: plot_history.py DIR/history.csv OUTDIR

Writes OUTDIR/energy.png (the energy ledger: kinetic, internal, contact, contact_overlap, converted, boundary,
total; and, dotted, the parts of internal energy that are plastic, viscous and hourglass work), OUTDIR/velocity.png (each body's mass-weighted velocity, both components),
OUTDIR/time_step.png and OUTDIR/energy_drift.png. Needs matplotlib (Debian: python3-matplotlib);
exits with code 3 when it is missing, 2 on a bad file, so the caller can say why.
"""
import csv
import os
import sys


def main(argv):
    if len(argv) != 3:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    history, out = argv[1], argv[2]
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError as error:
        print(f"plot_history.py: matplotlib is not available ({error}); install python3-matplotlib",
              file=sys.stderr)
        return 3
    try:
        with open(history, newline="") as f:
            rows = list(csv.reader(f))
    except OSError as error:
        print(f"plot_history.py: cannot read {history}: {error}", file=sys.stderr)
        return 2
    if len(rows) < 2:
        print(f"plot_history.py: {history} has no rows", file=sys.stderr)
        return 2
    header, data = rows[0], rows[1:]
    columns = {}
    for i, name in enumerate(header):
        values = []
        for row in data:
            try:
                values.append(float(row[i]))
            except (ValueError, IndexError):
                values.append(float("nan"))
        columns[name] = values
    time = columns["time"]
    # Time axis in a readable unit.
    end = max(abs(t) for t in time) or 1.0
    unit, factor = next((u, f) for u, f, limit in
                        (("ns", 1e9, 1e-6), ("\u00b5s", 1e6, 1e-3), ("ms", 1e3, 1.0), ("s", 1.0, float("inf")))
                        if end < limit)
    t = [x * factor for x in time]
    os.makedirs(out, exist_ok=True)

    def figure(name, title, series, ylabel, log=False):
        fig, ax = plt.subplots(figsize=(8, 4.5), dpi=110)
        for label, values, style in series:
            ax.plot(t, values, style, label=label, linewidth=1.4)
        ax.set_xlabel(f"time ({unit})")
        ax.set_ylabel(ylabel)
        ax.set_title(title)
        if log:
            ax.set_yscale("log")
        ax.grid(True, alpha=0.3)
        if len(series) > 1:
            ax.legend(fontsize=8, ncol=2)
        fig.tight_layout()
        fig.savefig(os.path.join(out, name))
        plt.close(fig)

    energy = [(name, columns[name], "-") for name in
              ("kinetic", "internal", "contact", "contact_overlap", "converted", "boundary") if name in columns]
    if "total" in columns:
        energy.append(("total", columns["total"], "k--"))
    # Parts of the internal energy (booked inside it, not added to the total).
    energy += [(f"{name} (part of internal)", columns[name], ":") for name in ("plastic", "viscous", "hourglass")
               if name in columns]
    figure("energy.png", "Energy ledger", energy, "energy (J)")

    bodies = [name[:-3] for name in header if name.endswith(("_vx", "_vz"))]
    velocity = []
    for body in bodies:
        for axis in ("x", "y", "z", "r"):
            column = f"{body}_v{axis}"
            if column in columns:
                velocity.append((f"{body} v{axis}", columns[column], "-"))
    if velocity:
        figure("velocity.png", "Mass-weighted body velocities", velocity, "velocity (m/s)")
    if "dt" in columns:
        figure("time_step.png", "Time step", [("dt", columns["dt"], "-")], "dt (s)", log=True)
    if "relative_drift" in columns:
        drift = [max(d, 1e-17) for d in columns["relative_drift"]]
        figure("energy_drift.png", "Relative energy drift", [("drift", drift, "-")], "|E(t) - E(0)| / scale", log=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
