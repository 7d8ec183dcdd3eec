#!/usr/bin/python3
"""The validation study of the paper's case (docs/validation.md), generated, run and tabulated.

    scripts/paper_study.py OUTDIR [--krug build/apps/krug/krug] [--jobs 2] [--zones-per-mm 10]
                                  [--groups converged,ordering,fig6,mesh,default,velocity,sensitivity,knobs,johnson_cook]
                                  [--generate-options "--hourglass 0.02"] [--members N] [--only REGEX]

Every scenario comes from scripts/paper_case.py; each run goes to OUTDIR/runs/NAME (a run whose
directory exists is not repeated, so the study resumes where it stopped: delete the directory of an
interrupted run to repeat it). Per group,
OUTDIR/GROUP.csv holds the report rows (scripts/paper_case.py report); OUTDIR/fig6.png plots the
Fig. 6 group. Groups:
  converged    2.6 g, the three 3 mm targets at 5, 10 and 20 zones per mm (the mesh study of the headline)
  ordering     2.6 g, monolithic and layered at 10 zones per mm: the default numerics, the paper's summation
               contact, and conversion by loosening alone, each with eps_* = 0.3, 0.4, 0.5
  mesh         both bullets, the three 3 mm targets at 5, 7 and 10 zones per mm
  default      11 g bullet, the three 3 mm targets at 10 zones per mm (examples/paper/)
  fig6         dU/U0 against H = 1..5 mm, three kinds, 2.6 g and 11 g (n 1-mm plates in contact, one
               n-mm plate, n spaced 1-mm plates); at H = 1 the three kinds are the same target
  velocity     the three 3 mm targets at 350, 370 and 390 m/s, 2.6 g
  knobs        2.6 g, monolithic and layered 3 mm: the reference and one numerical control changed at a
               time (lead erosion 0.05 / 0.2; hourglass 0.02 / 0.15, both parts and each alone; c_l 0.15 / 0.25 / 1;
               c_q 0.5 / 0.75 / 1.5; gap tolerance; the physical hourglass stiffness, with viscous 0.05 / 0.02 / 0.15)
  johnson_cook 2.6 g, monolithic 3 mm, end time doubled: the paper's elongation criterion, Johnson-Cook
               damage (6061-T6 D1..D5) on the paper's plate, and the library's whole 6061-T6 set
  sensitivity  the monolithic 3 mm target, 2.6 g, one parameter changed at a time; the spaced target
               for the gap
The study resolution (--zones-per-mm, default 5) applies to all but the mesh group.
With --members N each case runs N times, NAME_d0 .. NAME_d(N-1), at impact speeds (1 + k 1e-9) times
its own: the case is chaotic (docs/validation.md, "The case's own scatter"), and OUTDIR/GROUP_scatter.csv
gives each case's mean, standard deviation and range over its members (scripts/paper_case.py scatter).
"""
import argparse
import concurrent.futures
import csv
import json
import os
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
PAPER_CASE = os.path.join(HERE, "paper_case.py")


def cases(groups, zones):
    """(group, name, paper_case.py generate options) for every run of the chosen groups."""
    out = []
    if "default" in groups:
        for kind in ("monolithic", "layered", "spaced"):
            out.append(("default", f"default_{kind}_11g", ["--mass", "11", "--kind", kind]))
    if "mesh" in groups:
        for mass in ("2.6", "11"):
            for z in (5, 7, 10):
                for kind in ("monolithic", "layered", "spaced"):
                    out.append(("mesh", f"mesh_{kind}_{mass}g_z{z}",
                                ["--mass", mass, "--kind", kind, "--zones-per-mm", str(z)]))
    if "velocity" in groups:
        for v in (350, 370, 390):
            for kind in ("monolithic", "layered", "spaced"):
                out.append(("velocity", f"velocity_{kind}_{v}",
                            ["--mass", "2.6", "--kind", kind, "--velocity", str(v), "--zones-per-mm", str(zones)]))
    if "sensitivity" in groups:
        base = ["--mass", "2.6", "--zones-per-mm", str(zones)]
        variants = [
            ("reference", ["--kind", "monolithic"]),
            ("particles_2x2", ["--kind", "monolithic", "--particles", "4"]),
            ("f_h_0.1", ["--kind", "monolithic", "--altitude-ratio", "0.1"]),
            ("f_h_0.5", ["--kind", "monolithic", "--altitude-ratio", "0.5"]),
            ("f_i_0.05", ["--kind", "monolithic", "--interior-altitude-ratio", "0.05"]),
            ("f_i_0.2", ["--kind", "monolithic", "--interior-altitude-ratio", "0.2"]),
            ("radius_50mm", ["--kind", "monolithic", "--target-radius", "50"]),
            ("rim_free", ["--kind", "monolithic", "--rim", "free"]),
            ("eps_0.3", ["--kind", "monolithic", "--elongation", "0.3"]),
            ("eps_0.5", ["--kind", "monolithic", "--elongation", "0.5"]),
            ("friction_0.1", ["--kind", "monolithic", "--friction", "0.1"]),
            ("erosion_0.1", ["--kind", "monolithic", "--erosion", "0.1"]),
            ("gap_tolerance_1e-6", ["--kind", "monolithic", "--gap-tolerance", "1e-6"]),
            ("spaced_gap_1mm", ["--kind", "spaced", "--gap", "1"]),
            ("spaced_gap_5mm", ["--kind", "spaced", "--gap", "5"]),
            ("spaced_gap_20mm", ["--kind", "spaced", "--gap", "20"]),
        ]
        for name, options in variants:
            out.append(("sensitivity", f"sensitivity_{name}", base + options))
    if "knobs" in groups:
        # The headline against the numerical knobs (2.6 g, monolithic and layered, at the study
        # resolution): each variant changes one control of the generated scenario (JSON path=value).
        knobs = [
            ("reference", []),
            ("erosion_0.05", ["--erosion", "0.05"]),
            ("erosion_0.2", ["--erosion", "0.2"]),
            ("hourglass_0.02", ["--set", "controls.hourglass.viscous=0.02", "--set", "controls.hourglass.stiffness=0.02"]),
            ("hourglass_0.15", ["--set", "controls.hourglass.viscous=0.15", "--set", "controls.hourglass.stiffness=0.15"]),
            ("linear_viscosity_0.15", ["--set", "controls.viscosity.linear=0.15"]),
            ("quadratic_viscosity_0.5", ["--set", "controls.viscosity.quadratic=0.5"]),
            ("gap_tolerance_1e-6", ["--gap-tolerance", "1e-6"]),
            ("hourglass_viscous_0.02", ["--set", "controls.hourglass.viscous=0.02"]),
            ("hourglass_viscous_0.15", ["--set", "controls.hourglass.viscous=0.15"]),
            ("hourglass_stiffness_0.02", ["--set", "controls.hourglass.stiffness=0.02"]),
            ("hourglass_stiffness_0.15", ["--set", "controls.hourglass.stiffness=0.15"]),
            ("linear_viscosity_0.25", ["--set", "controls.viscosity.linear=0.25"]),
            ("linear_viscosity_1.0", ["--set", "controls.viscosity.linear=1.0"]),
            ("quadratic_viscosity_0.75", ["--set", "controls.viscosity.quadratic=0.75"]),
            ("quadratic_viscosity_1.5", ["--set", "controls.viscosity.quadratic=1.5"]),
            ("solve_stalled", ["--set", "contact.solve_stalled=true"]),
            ("physical", ["--set", "controls.hourglass.stiffness_form=\"physical\""]),
            ("physical_viscous_0.02", ["--set", "controls.hourglass.stiffness_form=\"physical\"",
                                       "--set", "controls.hourglass.viscous=0.02"]),
            ("physical_viscous_0.15", ["--set", "controls.hourglass.stiffness_form=\"physical\"",
                                       "--set", "controls.hourglass.viscous=0.15"]),
        ]
        for kind in ("monolithic", "layered"):
            for name, options in knobs:
                out.append(("knobs", f"knobs_{kind}_{name}",
                            ["--mass", "2.6", "--kind", kind, "--zones-per-mm", str(zones)] + options))
    if "johnson_cook" in groups:
        # The monolithic 3 mm target, 2.6 g, at the study resolution, the end time doubled: the paper's
        # elongation criterion; Johnson-Cook damage with the library's 6061-T6 constants on the paper's
        # plate; the library's whole 6061-T6 set (strength, EOS and damage).
        jc = '{"base": "paper-al6061-t6", "fracture": {"model": "johnson_cook", "d1": -0.77, "d2": 1.45, "d3": -0.47, "d4": 0.0, "d5": 1.6}}'
        library = '{"base": "al6061-t6", "fracture": {"model": "johnson_cook"}}'
        base = ["--mass", "2.6", "--kind", "monolithic", "--zones-per-mm", str(zones), "--scale", "end_time=2"]
        out.append(("johnson_cook", f"elongation_z{zones}", base))
        out.append(("johnson_cook", f"jcpaper_z{zones}", base + ["--set", f"materials.al6061={jc}"]))
        out.append(("johnson_cook", f"jclib_z{zones}", base + ["--set", f"materials.al6061={library}"]))
    if "ordering" in groups:
        # A: the target's numerics as the paper's (2.6 g, 10 zones per mm): the paper's summation contact,
        # or conversion by loosening alone (the altitude rules f_h and f_i made inactive), each crossed with
        # the elongation limit; the default numerics with the same limits beside them.
        loosening_only = ["--altitude-ratio", "1e-6", "--interior-altitude-ratio", "1e-6"]
        for kind in ("monolithic", "layered"):
            for eps in ("0.3", "0.4", "0.5"):
                base = ["--mass", "2.6", "--kind", kind, "--zones-per-mm", "10", "--elongation", eps]
                out.append(("ordering", f"ordering_{kind}_default_eps{eps}", base))
                out.append(("ordering", f"ordering_{kind}_summation_eps{eps}", base + ["--contact-method", "summation"]))
                out.append(("ordering", f"ordering_{kind}_loosening_eps{eps}", base + loosening_only))
    if "converged" in groups:
        # B: the three 3 mm targets at 5, 10 and 20 zones per mm, default numerics.
        for mass in ("2.6",):
            for z in (5, 10, 20):
                for kind in ("monolithic", "layered", "spaced"):
                    out.append(("converged", f"converged_{kind}_{mass}g_z{z}",
                                ["--mass", mass, "--kind", kind, "--zones-per-mm", str(z)]))
    if "fig6" in groups:
        for mass in ("2.6", "11"):
            for h in (1, 2, 3, 4, 5):
                for kind in ("monolithic", "layered", "spaced"):
                    out.append(("fig6", f"fig6_{kind}_H{h}_{mass}g",
                                ["--mass", mass, "--kind", kind, "--thickness", str(h), "--zones-per-mm", str(zones)]))
    return out


def with_speed_factor(options, factor):
    """The options with the impact speed (--velocity, default 355 m/s) multiplied by `factor`; the last
    --velocity given wins, as in argparse."""
    speed = 355.0
    kept = []
    i = 0
    while i < len(options):
        if options[i] == "--velocity":
            speed = float(options[i + 1])
            i += 2
            continue
        kept.append(options[i])
        i += 1
    return kept + ["--velocity", repr(speed * factor)]


def generate(outdir, name, options):
    """Writes the scenario; returns its physics (the scenario without title and description) as text.
    Options "--set PATH=VALUE" (a dotted JSON path, a JSON value) edit the generated scenario;
    "--scale KEY=FACTOR" multiplies a top-level number (end_time=2 doubles the end time)."""
    edits = [options[i + 1] for i, o in enumerate(options) if o == "--set"]
    scales = [options[i + 1] for i, o in enumerate(options) if o == "--scale"]
    ours = ("--set", "--scale")
    options = [o for i, o in enumerate(options) if o not in ours and (i == 0 or options[i - 1] not in ours)]
    subprocess.run([sys.executable, PAPER_CASE, "generate", os.path.join(outdir, "scenarios"), "--name", name] + options,
                   check=True, stdout=subprocess.DEVNULL)
    path = os.path.join(outdir, "scenarios", f"{name}.json")
    scenario = json.load(open(path))
    if edits or scales:
        for scale in scales:
            key, factor = scale.split("=", 1)
            scenario[key] *= float(factor)
        for edit in edits:
            keys, value = edit.split("=", 1)
            at = scenario
            keys = keys.split(".")
            for key in keys[:-1]:
                at = at.setdefault(key, {})
            at[keys[-1]] = json.loads(value)
        with open(path, "w") as f:
            json.dump(scenario, f, indent=2)
    scenario.pop("title", None)
    scenario.pop("description", None)
    return json.dumps(scenario, sort_keys=True)


def run_one(krug, outdir, name):
    scenario = os.path.join(outdir, "scenarios", f"{name}.json")
    run_dir = os.path.join(outdir, "runs", name)
    if os.path.exists(run_dir):
        return name, "kept", 0.0  # done, or running in another study process: delete the directory to repeat it
    start = time.time()
    with open(os.path.join(outdir, "logs", f"{name}.log"), "w") as log:
        code = subprocess.run([krug, "run", scenario, "--out", run_dir, "--quiet", "--no-plots", "--no-pictures"],
                              stdout=log, stderr=subprocess.STDOUT).returncode
    return name, f"exit {code}", time.time() - start


def mesh_spread(outdir):
    """Per target kind: the relative change of the largest piece's dU/U0 between 10 and 20 zones per mm
    in the converged group (2.6 g, H = 3 mm), |d(10) - d(20)| / d(10); {} without that group. Fig. 6
    draws it as a relative error bar on every point (the only mesh study made: an assumption that the
    relative mesh error of the 3 mm, 2.6 g case holds for the other H and the 11 g bullet)."""
    path = os.path.join(outdir, "converged.csv")
    if not os.path.exists(path):
        return {}
    values = {}
    for r in csv.DictReader(open(path)):
        kind, zones = r["run"].split("_")[1], r["run"].split("_z")[-1]
        values.setdefault(kind, {})[zones] = float(r["piece_dU_over_U0"])
    return {k: abs(v["10"] - v["20"]) / v["10"] for k, v in values.items() if "10" in v and "20" in v}


def plot_fig6(outdir, zones):
    """dU/U0 of the bullet's largest piece against H, with the relative 10-to-20 zones per mm change of
    the 2.6 g, 3 mm case as error bars (mesh_spread). Open markers: runs whose bullet had not cleared
    the plates when they ended (summary "penetration.final" false)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = list(csv.DictReader(open(os.path.join(outdir, "fig6.csv"))))
    spread = mesh_spread(outdir)
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2))
    styles = (("layered", "s", -0.08, "tab:blue"), ("monolithic", "o", 0.0, "tab:orange"), ("spaced", "^", 0.08, "tab:green"))
    for ax, mass in zip(axes, ("2.6g", "11g")):
        for kind, marker, shift, colour in styles:
            points = sorted((int(r["run"].split("_H")[1].split("_")[0]), float(r["piece_dU_over_U0"]), r["final"] == "True")
                            for r in rows if r["run"].startswith(f"fig6_{kind}_") and r["run"].endswith(mass))
            if not points:
                continue
            ax.errorbar([p[0] + shift for p in points], [p[1] for p in points],
                        yerr=[spread.get(kind, 0.0) * p[1] for p in points], marker=marker, color=colour, capsize=3,
                        label=kind)
            open_points = [p for p in points if not p[2]]
            if open_points:
                ax.plot([p[0] + shift for p in open_points], [p[1] for p in open_points], marker, ms=11, mfc="white",
                        mec=colour, ls="none", label=f"{kind}: not final (ended before clearing)")
        ax.set_xlabel("total thickness H (mm)")
        ax.set_ylabel("dU / U0 (bullet's largest piece)")
        ax.set_title(f"{mass.replace('g', ' g')} lead bullet, 355 m/s, {zones} zones per mm")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(outdir, "fig6.png"), dpi=110)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("outdir")
    parser.add_argument("--krug", default=os.path.join(HERE, "..", "build", "apps", "krug", "krug"))
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--zones-per-mm", type=int, default=10)
    parser.add_argument("--groups", default="converged,ordering,fig6")
    parser.add_argument("--generate-options", default="",
                        help="options of scripts/paper_case.py generate put before every case's own, e.g. "
                             "\"--hourglass 0.02\" (a case's own option of the same name wins)")
    parser.add_argument("--only", default=None, help="run only the cases whose name matches this regular expression")
    parser.add_argument("--members", type=int, default=1,
                        help="runs per case at impact speeds (1 + k 1e-9) times the case's, k = 0..N-1 (default 1)")
    args = parser.parse_args()
    groups = args.groups.split(",")
    for sub in ("scenarios", "runs", "logs"):
        os.makedirs(os.path.join(args.outdir, sub), exist_ok=True)
    base = args.generate_options.split()
    todo = [(group, name, base + options) for group, name, options in cases(groups, args.zones_per_mm)]
    if args.only:
        todo = [(group, name, options) for group, name, options in todo if re.search(args.only, name)]
    if args.members > 1:
        todo = [(group, f"{name}_d{k}", with_speed_factor(options, 1.0 + k * 1e-9))
                for group, name, options in todo for k in range(args.members)]
    # The same physics under two names (the 3 mm, 5 zones/mm monolithic case is in three groups) runs
    # once; the other names link to it.
    first_of = {}
    duplicates = {}
    for _, name, options in todo:
        key = generate(args.outdir, name, options)
        if key in first_of:
            duplicates[name] = first_of[key]
        else:
            first_of[key] = name
    unique = [name for _, name, _ in todo if name not in duplicates]
    start = time.time()
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futures = [pool.submit(run_one, args.krug, args.outdir, name) for name in unique]
        for f in concurrent.futures.as_completed(futures):
            name, status, seconds = f.result()
            print(f"{name:40s} {status:8s} {seconds:7.1f} s", flush=True)
    for name, original in duplicates.items():
        link = os.path.join(args.outdir, "runs", name)
        if not os.path.lexists(link):
            os.symlink(original, link)
    print(f"study: {len(unique)} runs ({len(todo)} cases) in {time.time() - start:.0f} s of wall time with "
          f"{args.jobs} jobs", flush=True)
    for group in groups:
        runs = [os.path.join(args.outdir, "runs", name) for g, name, _ in todo if g == group]
        runs = [r for r in runs if os.path.exists(os.path.join(r, "summary.json"))]
        if runs:
            subprocess.run([sys.executable, PAPER_CASE, "report", *runs, "--csv", os.path.join(args.outdir, f"{group}.csv")],
                           check=True)
            if args.members > 1:
                subprocess.run([sys.executable, PAPER_CASE, "scatter", *runs, "--csv",
                                os.path.join(args.outdir, f"{group}_scatter.csv")], check=True)
    if "fig6" in groups and os.path.exists(os.path.join(args.outdir, "fig6.csv")):
        plot_fig6(args.outdir, args.zones_per_mm)


if __name__ == "__main__":
    main()
