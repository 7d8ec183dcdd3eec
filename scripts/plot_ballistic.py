#!/usr/bin/env python3
"""The picture of a ballistic-limit study (called by `krug ballistic`).

usage: plot_ballistic.py DIR

Reads DIR/ballistic.csv and DIR/ballistic.json and writes DIR/ballistic.png: the residual speed of
the projectile's largest piece (filled) and of the whole projectile (open) against the impact speed,
stopped runs at 0, runs without an answer (failed, unfinished) as crosses on the axis, the
Lambert-Jonas fit and the Recht-Ipson reference curves, and the ballistic limit with its bracket.
Needs matplotlib (Debian: python3-matplotlib); exits with code 3 when it is missing, 2 on a bad file.
"""
import csv
import json
import os
import sys


def curve(a, p, v_bl, speeds):
    return [a * (v ** p - v_bl ** p) ** (1.0 / p) if v > v_bl else 0.0 for v in speeds]


def main(argv):
    if len(argv) != 2:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    directory = argv[1]
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError as error:
        print(f"plot_ballistic.py: matplotlib is not available ({error}); install python3-matplotlib", file=sys.stderr)
        return 3
    try:
        with open(os.path.join(directory, "ballistic.csv"), newline="") as f:
            rows = list(csv.DictReader(f))
        with open(os.path.join(directory, "ballistic.json")) as f:
            study = json.load(f)
    except (OSError, ValueError) as error:
        print(f"plot_ballistic.py: cannot read the study in {directory}: {error}", file=sys.stderr)
        return 2

    def number(text):
        try:
            return float(text)
        except (TypeError, ValueError):
            return None

    fig, ax = plt.subplots(figsize=(7.5, 5.0))
    v_low, v_high = study["range"]
    if study.get("bracket"):
        low, high = study["bracket"]
        ax.axvspan(low, high, color="0.85", label=f"bracket {low:.1f}–{high:.1f} m/s")
        ax.axvline(study["v_bl"], color="0.3", linestyle=":", label=f"V_bl = {study['v_bl']:.1f} m/s (bracket midpoint)")
    kinds = {"perforated": [], "stopped": [], "other": []}
    for row in rows:
        v = number(row["velocity"])
        if row["result"] == "perforated":
            kinds["perforated"].append((v, number(row["residual_velocity"]), number(row["whole_velocity"])))
        elif row["result"] == "stopped":
            kinds["stopped"].append(v)
        else:
            kinds["other"].append(v)
    if kinds["perforated"]:
        ax.plot([p[0] for p in kinds["perforated"]], [p[1] for p in kinds["perforated"]], "o", color="C0",
                label="perforated: largest piece")
        whole = [p for p in kinds["perforated"] if p[2] is not None]
        ax.plot([p[0] for p in whole], [p[2] for p in whole], "o", mfc="none", color="C0",
                label="perforated: whole projectile")
    if kinds["stopped"]:
        ax.plot(kinds["stopped"], [0.0] * len(kinds["stopped"]), "s", color="C3", label="stopped")
    if kinds["other"]:
        ax.plot(kinds["other"], [0.0] * len(kinds["other"]), "x", color="k", markersize=9,
                label="failed or unfinished (not counted)")
    speeds = [v_low + (v_high - v_low) * i / 400.0 for i in range(401)]
    fit = study.get("lambert_jonas") or {}
    if fit.get("valid"):
        ax.plot(speeds, curve(fit["a"], fit["p"], fit["v_bl"], speeds), "-", color="C1",
                label=(f"Lambert–Jonas: v_bl = {fit['v_bl']:.1f} ± {fit['sigma_v_bl'] or 0:.1f} m/s, "
                       f"a = {fit['a']:.3f}, p = {fit['p']:.2f}"))
    ri = study.get("recht_ipson") or {}
    if ri.get("valid"):
        ax.plot(speeds, curve(ri["a"], 2.0, ri["v_bl"], speeds), "--", color="C2",
                label=f"Recht–Ipson: a = m_p/(m_p+m_plug) = {ri['a']:.3f}, v_bl = {ri['v_bl']:.1f} m/s")
    ax.set_xlabel("impact speed (m/s)")
    ax.set_ylabel("residual speed (m/s)")
    ax.set_xlim(v_low - 0.02 * (v_high - v_low), v_high + 0.02 * (v_high - v_low))
    ax.set_ylim(bottom=-0.03 * max(1.0, ax.get_ylim()[1]))
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, loc="upper left")
    title = os.path.basename(os.path.normpath(study.get("scenario", "")))
    ax.set_title(f"Ballistic limit: {title}", fontsize=9)
    fig.tight_layout()
    out = os.path.join(directory, "ballistic.png")
    fig.savefig(out + ".part.png", dpi=120)
    os.replace(out + ".part.png", out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
