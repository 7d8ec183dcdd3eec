#!/usr/bin/python3
"""The paper's case (Gulidov & Shabalin 1996): a lead bullet through 6061-T6 targets.

Writes Krug scenarios for the three target kinds and their variants, so that every run of the
validation study comes from one definition (docs/validation.md):

    scripts/paper_case.py generate OUTDIR [--mass 11|2.6] [--kind monolithic|layered|spaced]
                                          [--thickness H_MM] [--zones-per-mm N] [--gap MM]
                                          [--target-radius MM] [--rim fixed|free] [--elongation E]
                                          [--friction F] [--particles 1|4] [--velocity V]
                                          [--altitude-ratio F] [--interior-altitude-ratio F]
                                          [--erosion F] [--gap-tolerance T] [--velocity-window-only]
                                          [--contact-method gauss_seidel|summation]
                                          [--name NAME]

    scripts/paper_case.py report RUN... --csv FILE          (one row per run)
    scripts/paper_case.py figures RUN PNG [--count N] [--field F] [--vmax V]
    scripts/paper_case.py velocity-history RUN... --csv FILE (core and body velocity per snapshot)

Units in the options are mm, g, m/s; the scenarios are SI. Facts (docs/validation.md): lead rho0 11340,
K 50 GPa, mu 5.7 GPa, Y0 0.03 GPa, no fracture; 6061-T6 rho0 2700, K 73 GPa, mu 24.6 GPa, Y0 0.28 GPa,
elongation criterion eps_* = 0.4, chi_* = 0.03; bullet radius 2.78 mm, hemispherical nose.
"""
import argparse
import json
import math
import os
import re
import sys

import numpy as np

import krug_vtk  # scripts/krug_vtk.py

LEAD_DENSITY = 11340.0  # the library set "paper-lead"
PAPER_ELONGATION = 0.4  # the library set "paper-al6061-t6"
BULLET_RADIUS = 2.78e-3


def bullet_length(mass_g):
    """Length of a hemispherical-nosed lead cylinder of radius 2.78 mm with the given mass."""
    volume = mass_g * 1e-3 / LEAD_DENSITY
    nose = 2.0 / 3.0 * math.pi * BULLET_RADIUS ** 3
    return BULLET_RADIUS + (volume - nose) / (math.pi * BULLET_RADIUS ** 2)


def plate_layout(kind, thickness_mm, gap_mm):
    """(front z, back z) of each plate in m; the front face of the target at z = 0, bullet moving -z."""
    n = int(round(thickness_mm))
    if kind == "monolithic":
        return [(0.0, -thickness_mm * 1e-3)]
    plates = []
    front = 0.0
    for _ in range(n):
        plates.append((front, front - 1e-3))
        front -= 1e-3 + (gap_mm * 1e-3 if kind == "spaced" else 0.0)
    return plates


def radial_axis(zones_per_mm, target_radius):
    """Near-square zones out to two bullet radii, then graded to the rim (first graded zone ~ the fine size)."""
    fine = 1e-3 / zones_per_mm
    inner = 2.0 * BULLET_RADIUS
    inner_zones = int(round(inner / fine))
    outer = target_radius - inner
    ratio = 1.1
    # h0 (ratio^n - 1) / (ratio - 1) = outer with h0 ~ fine
    outer_zones = max(1, int(round(math.log(1.0 + outer * (ratio - 1.0) / fine) / math.log(ratio))))
    return {"from": 0.0, "segments": [{"to": inner, "zones": inner_zones},
                                       {"to": target_radius, "zones": outer_zones, "ratio": ratio}]}


def scenario(args):
    length = bullet_length(args.mass)
    velocity = args.velocity
    plates = plate_layout(args.kind, args.thickness, args.gap)
    depth = -plates[-1][1]
    # An upper bound: the whole bullet past the rear face, its tail 5 mm beyond, at half its speed. The
    # stop rule ends the run once the bullet has cleared the plates (or has stopped) and felt no contact
    # for a while.
    end_time = (depth + length + 0.005) / (0.5 * velocity)
    # The paper's data are the library's sets "paper-al6061-t6" (with its fracture criterion, elongation
    # 0.4 and loosening 0.03) and "paper-lead" (`krug materials paper-lead`); only what differs is written.
    aluminium = "paper-al6061-t6"
    if args.elongation != PAPER_ELONGATION:
        aluminium = {"base": "paper-al6061-t6", "fracture": {"elongation": args.elongation}}
    lead = "paper-lead"
    if args.erosion > 0.0:
        # Numerical erosion (not fracture; the paper's lead does not fracture): a lead zone thinned below
        # this fraction of its initial altitude leaves the mesh as a free element, with its mass,
        # momentum and energy. It removes the thin sheet that the hole's edge shaves off the nose
        # (docs/validation.md, "Lead erosion").
        lead = {"base": "paper-lead", "erosion": {"altitude_ratio": args.erosion}}
    radial_zones = max(2, int(round(BULLET_RADIUS * 1e3 * args.zones_per_mm)))
    bodies = [{
        "name": "bullet",
        "material": "lead",
        "mesh": {"type": "nosed_cylinder", "radius": BULLET_RADIUS, "length": length, "nose": "hemispherical",
                 "tip": 1e-3 / args.zones_per_mm, "points": "-z", "radial_zones": radial_zones,
                 "shank_ratio": 1.04},
        "initial": {"velocity": [-velocity, 0.0]},
    }]
    for i, (front, back) in enumerate(plates):
        zones = max(1, int(round((front - back) * 1e3 * args.zones_per_mm)))
        body = {
            "name": f"plate{i + 1}" if len(plates) > 1 else "plate",
            "material": "al6061",
            "mesh": {"type": "rectangle", "z": {"from": back, "to": front, "zones": zones},
                     "r": radial_axis(args.zones_per_mm, args.target_radius * 1e-3)},
        }
        if args.rim == "fixed":
            body["boundary"] = {"r_max": "fixed"}
        bodies.append(body)
    controls = {"fracture": {"particles_per_zone": args.particles, "altitude_ratio": args.altitude_ratio,
                             "interior_altitude_ratio": args.interior_altitude_ratio}}
    if args.hourglass is not None:
        # Both hourglass coefficients (the library's default is 0.05 for both): docs/validation.md,
        # "Hourglass coefficients 0.02".
        controls["hourglass"] = {"viscous": args.hourglass, "stiffness": args.hourglass}
    pairs = []
    names = [b["name"] for b in bodies]
    for i in range(len(names)):
        for j in range(i, len(names)):
            if i == j and names[i] == "bullet":
                continue
            pairs.append({"bodies": [names[i], names[j]], "friction": args.friction})
    # The run ends once the bullet has cleared every plate (or stopped) and its mean velocity has stayed
    # within 0.5 % of U0 over `no_contact_time`: longer than a plate's transit (1 mm at U0: 3 us) and, for
    # spaced plates, than the flight across a gap at half the speed. --velocity-window-only keeps the
    # window alone (the bullet's tail may then still be in the hole).
    stop = {"body": "bullet", "velocity_change": 0.005,
            "no_contact_time": max(10e-6, (2.0 * args.gap * 1e-3 / velocity + 5e-6) if args.kind == "spaced" else 0.0),
            "clear_of_targets": not args.velocity_window_only}
    return {
        "title": f"Lead bullet {args.mass} g at {velocity} m/s, {args.kind} 6061-T6 target, H = {args.thickness} mm",
        "description": "The case of Gulidov & Shabalin (1996), generated by scripts/paper_case.py "
                       f"({' '.join(sys.argv[1:])}). See docs/validation.md.",
        "geometry": "axisymmetric",
        "end_time": end_time,
        "materials": {"lead": lead, "al6061": aluminium},
        "bodies": bodies,
        # Reactions converged to 1e-4 of a segment per step (the library's default is 1e-5, which
        # crowds of particles need); docs/validation.md gives the effect of 1e-6.
        "contact": {"pairs": pairs, "gap_tolerance": args.gap_tolerance, "method": args.contact_method},
        "controls": controls,
        "penetration": {"projectile": "bullet"},
        "output": {"snapshot_interval": (args.snapshot_interval * 1e-6 if args.snapshot_interval
                                         else end_time / 20.0), "history_interval": end_time / 2000.0,
                   "pictures": {"field": "equivalent_plastic_strain"}},
        "stop": stop,
    }


def hourglass_share(body):
    """A body's hourglass work over the energy put into its zones (summary.json bodies.<name>.energy)."""
    e = body.get("energy", {})
    put_in = e.get("internal", 0.0) + e.get("converted", 0.0)
    return e.get("hourglass", 0.0) / put_in if put_in > 0.0 else 0.0


def bullet_tip(run_dir):
    """Axial position of the bullet's tip (lowest z of its nodes) in the final state."""
    mesh = krug_vtk.read(os.path.join(run_dir, "final.vtu"))
    body = mesh.point_data["body"].ravel()
    z = mesh.points[:, 0]
    return float(z[body == 0].min())


def cell_geometry(mesh):
    """Per quad cell: centroid (z, r) and mass per radian (density x area x centroid r)."""
    import numpy as np
    quads = mesh.cells_dict["quad"]
    corners = mesh.points[quads][:, :, :2]
    z, r = corners[:, :, 0], corners[:, :, 1]
    area = 0.5 * np.abs((z[:, 2] - z[:, 0]) * (r[:, 3] - r[:, 1]) - (z[:, 3] - z[:, 1]) * (r[:, 2] - r[:, 0]))
    centroid = corners.mean(axis=1)
    density = mesh.cell_data_dict["density"]["quad"].ravel()
    return quads, centroid, density * area * centroid[:, 1]


def core_velocity(run_dir):
    """Axial velocity of the bullet's core: its cells within the initial bullet radius, mass-weighted.

    The bullet body's own mean velocity includes the lead squeezed out at the rim of the mushroom
    (a thin sheet that the hole's edge shaves off and throws back); the core is what a chronograph
    behind the target would time."""
    mesh = krug_vtk.read(os.path.join(run_dir, "final.vtu"))
    quads, centroid, mass = cell_geometry(mesh)
    body = mesh.cell_data_dict["body"]["quad"].ravel()
    velocity_z = mesh.point_data["velocity"][:, 0][quads].mean(axis=1)
    core = (body == 0) & (centroid[:, 1] < BULLET_RADIUS)
    return float((mass[core] * velocity_z[core]).sum() / mass[core].sum())


def damage_onsets(run_dir, scenario):
    """Per plate: the earliest damage onset among its zones near the axis (r < 1 mm) and anywhere,
    with where it happened as a fraction of the plate's thickness from its front face (0) to its rear
    face (1), between the centroids of the plate's cells at that radius in that snapshot. From every snapshot (a zone converted before a snapshot is missed: snapshots come every
    end_time / 20)."""
    import xml.etree.ElementTree as ET
    collection = ET.parse(os.path.join(run_dir, "run.pvd")).getroot().find("Collection")
    files = [os.path.join(run_dir, ds.get("file")) for ds in collection if ds.get("part") == "0"]
    plates = scenario["bodies"][1:]
    best = {}
    for f in files:
        mesh = krug_vtk.read(f)
        _, centroid, _ = cell_geometry(mesh)
        body = mesh.cell_data_dict["body"]["quad"].ravel()
        onset = mesh.cell_data_dict["damage_onset_time"]["quad"].ravel()
        for i, plate in enumerate(plates, start=1):
            front, back = plate["mesh"]["z"]["to"], plate["mesh"]["z"]["from"]  # initial faces
            for where, near in (("axis", centroid[:, 1] < 1e-3), ("any", centroid[:, 1] >= 0.0)):
                pick = (body == i) & near & (onset >= 0.0)
                if not pick.any():
                    continue
                k = int(onset[pick].argmin())
                t = float(onset[pick][k])
                key = (plate["name"], where)
                if key not in best or t < best[key][0]:
                    # Depth within the plate as it is now (it moves and bends): its cells at that radius.
                    r = float(centroid[pick][k, 1])
                    column = (body == i) & (abs(centroid[:, 1] - r) < 0.1 * (front - back) + 1e-4)
                    top, bottom = float(centroid[column, 0].max()), float(centroid[column, 0].min())
                    depth = (top - float(centroid[pick][k, 0])) / max(top - bottom, 1e-12)
                    best[key] = (t, depth, float(centroid[pick][k, 1]))
    return best


# What the report says when no snapshot shows a damaged zone there: damage is read from the snapshots,
# and a zone damaged and converted between two of them is not seen.
NOT_SEEN = "none seen in the snapshots (a zone damaged and converted between two snapshots is missed)"


def report(run_dirs, csv_path):
    """One row per run: residual velocity, loss, perforation, plug, debris ahead, eroded mass, ledgers."""
    rows = []
    for run in run_dirs:
        summary = json.load(open(os.path.join(run, "summary.json")))
        scenario = json.load(open(os.path.join(run, "scenario.resolved.json")))
        u0 = -scenario["bodies"][0]["initial"]["velocity"][0]
        bullet = summary["bodies"]["bullet"]
        residual = -bullet["velocity"][0]
        plates = [b for name, b in summary["bodies"].items() if name != "bullet"]
        rear = min(b["mesh"]["z"]["from"] for b in scenario["bodies"][1:])
        tip = bullet_tip(run)
        # Debris ahead of the bullet: fragments and particles moving faster than it (axially, towards -z).
        debris_momentum = 0.0
        pieces = []
        for b in plates:
            for f in b.get("fracture", {}).get("fragments", [])[1:]:
                pieces.append(f)
                if -f["velocity"][0] > 0.5 * residual:
                    debris_momentum += -f["mass"] * f["velocity"][0]
        particles = summary["particles"]
        energy = summary["ledger"]["energy"]
        eroded = bullet.get("fracture", {}).get("eroded_mass", 0.0)
        onsets = damage_onsets(run, scenario)
        first_on_axis = ";".join(f"{name}:{1e6 * onsets[(name, 'axis')][0]:.2f}us@{onsets[(name, 'axis')][1]:.2f}"
                                 for name in (b["name"] for b in scenario["bodies"][1:]) if (name, "axis") in onsets)
        first_anywhere = ";".join(f"{name}:{1e6 * onsets[(name, 'any')][0]:.2f}us@r={1e3 * onsets[(name, 'any')][2]:.2f}mm"
                                  for name in (b["name"] for b in scenario["bodies"][1:]) if (name, "any") in onsets)
        core = -core_velocity(run)
        # The library's penetration figures (summary.json "penetration"): the largest connected piece of
        # the bullet, the plug, the energy the plates absorbed.
        pen = summary.get("penetration") or {}
        piece = pen.get("residual_velocity", float("nan"))
        plug = pen.get("plug") or {}
        rows.append({
            "run": os.path.basename(os.path.normpath(run)),
            "status": summary["status"],
            "time_us": summary["time"] * 1e6,
            "U0": u0,
            "piece_residual": piece,
            "piece_dU_over_U0": (u0 - piece) / u0,
            "piece_mass_g": pen.get("residual_mass", float("nan")) * 1e3,
            # The whole bullet (summary.json penetration.whole): every node and free element of its lead.
            "whole_residual": (pen.get("whole") or {}).get("velocity", float("nan")),
            "whole_dU_over_U0": (pen.get("whole") or {}).get("velocity_loss", float("nan")),
            "free_element_mass_g": (pen.get("whole") or {}).get("free_element_mass", float("nan")) * 1e3,
            "free_element_velocity": (pen.get("whole") or {}).get("free_element_velocity", float("nan")),
            "backward_mass_g": (pen.get("whole") or {}).get("backward_mass", float("nan")) * 1e3,
            "mass_lost_g": pen.get("mass_lost", float("nan")) * 1e3,
            "target_energy_J": pen.get("target_energy_absorbed", float("nan")),
            "target_plastic_J": pen.get("target_plastic_work", float("nan")),
            "perforation_time_us": (pen.get("perforation_time") or float("nan")) * 1e6,
            "final": pen.get("final", False),
            "library_plug_g": plug.get("mass", 0.0) * 1e3,
            "residual": residual,
            "dU_over_U0": (u0 - residual) / u0,
            "core_residual": core,
            "core_dU_over_U0": (u0 - core) / u0,
            "perforated": pen["perforated"] if "perforated" in pen else (tip < rear and residual > 0.0),
            "tip_depth_mm": -tip * 1e3,
            "plug_mass_g": max((p["mass"] for p in pieces), default=0.0) * 1e3,
            "debris_fragment_momentum": debris_momentum,
            "particle_count": particles["count"],
            "particle_momentum_z": -particles["momentum"][0],
            "bullet_mass_g": bullet["mass"] * 1e3,
            "eroded_fraction": eroded / (bullet["mass"] + eroded) if bullet["mass"] + eroded > 0 else 0.0,
            # Hourglass work as a share of the energy put into a body's zones (internal plus converted):
            # the bullet's, and the largest of the plates'.
            "bullet_hourglass_share": hourglass_share(bullet),
            "plates_hourglass_share": max((hourglass_share(b) for b in plates), default=0.0),
            "energy_drift": energy["relative_drift"],
            "contact_work": energy["contact"],
            "mass_error": summary["ledger"]["mass"]["relative_error"],
            "cycles": summary["cycles"],
            "wall_seconds": summary["wall_seconds"],
            "first_damage_on_axis": first_on_axis,
            "first_damage": first_anywhere,
        })
    keys = list(rows[0].keys())
    with open(csv_path, "w") as f:
        f.write(",".join(keys) + "\n")
        for r in rows:
            f.write(",".join(f"{r[k]:.6g}" if isinstance(r[k], float) else str(r[k]) for k in keys) + "\n")
    for r in rows:
        print(f"{r['run']:40s} {r['status']:9s} U0 {r['U0']:.0f} largest piece {r['piece_residual']:.1f} m/s "
              f"(dU/U0 {r['piece_dU_over_U0']:.3f}, {r['piece_mass_g']:.3f} g) whole dU/U0 {r['whole_dU_over_U0']:.3f} target energy {r['target_energy_J']:.2f} J; "
              f"body {r['residual']:.1f} dU/U0 {r['dU_over_U0']:.3f} "
              f"core {r['core_residual']:.1f} perforated {r['perforated']} plug {r['plug_mass_g']:.3f} g eroded {100 * r['eroded_fraction']:.2f} % "
              f"drift {r['energy_drift']:.1e} wall {r['wall_seconds']:.0f} s\n    first damage on the axis (time @ depth fraction): "
              f"{r['first_damage_on_axis'] or NOT_SEEN}\n    first damage: {r['first_damage'] or NOT_SEEN}")


def velocity_history(run_dirs, csv_path):
    """Per snapshot of each run: the axial velocity of the bullet's core (its cells within the initial
    bullet radius) and of the whole bullet body (all its cells), mass-weighted, towards the target.
    Runs with the same end time have their snapshots at the same moments, so runs with and without
    lead erosion compare moment by moment."""
    import xml.etree.ElementTree as ET
    with open(csv_path, "w") as out:
        out.write("run,time_us,core_velocity,body_velocity,bullet_cells\n")
        for run in run_dirs:
            collection = ET.parse(os.path.join(run, "run.pvd")).getroot().find("Collection")
            for ds in collection:
                if ds.get("part") != "0":
                    continue
                mesh = krug_vtk.read(os.path.join(run, ds.get("file")))
                quads, centroid, mass = cell_geometry(mesh)
                body = mesh.cell_data_dict["body"]["quad"].ravel()
                velocity_z = mesh.point_data["velocity"][:, 0][quads].mean(axis=1)
                bullet = body == 0
                core = bullet & (centroid[:, 1] < BULLET_RADIUS)
                out.write(f"{os.path.basename(os.path.normpath(run))},{float(ds.get('timestep')) * 1e6:.3f},"
                          f"{-(mass[core] * velocity_z[core]).sum() / mass[core].sum():.3f},"
                          f"{-(mass[bullet] * velocity_z[bullet]).sum() / mass[bullet].sum():.3f},{int(bullet.sum())}\n")
    print(csv_path)


def erosion_origin(run_dirs, csv_path, speed_fraction):
    """Where the projectile's eroded mass comes from and where it goes, from a run's particle snapshots.

    Each eroded particle of the projectile is followed from the first snapshot that holds it (its
    velocity there is taken as its velocity at birth: write snapshots densely, 0.5 us or less) to the
    last. Classes, as fractions of the projectile's initial mass:
    cut: born moving along the flight faster than `speed_fraction` x U0, i.e. cut from the moving
    bullet's flank or nose; held: born slower (the ring of lead the target's hole holds back);
    born_backward: born moving against the flight; turned_backward: born moving forward, moving
    backward in the last snapshot (pushed back after it left the mesh). The delay columns give the
    mean and largest time between a particle's birth and its first snapshot.
    """
    import xml.etree.ElementTree as ET
    fields = ["run", "zones_per_mm", "eroded_fraction", "cut_fraction", "held_fraction", "born_backward_fraction",
              "turned_backward_fraction", "backward_fraction", "particles", "mean_delay_us", "max_delay_us"]
    with open(csv_path, "w") as out:
        out.write(",".join(fields) + "\n")
        for run in run_dirs:
            scen = json.load(open(os.path.join(run, "scenario.resolved.json")))
            summary = json.load(open(os.path.join(run, "summary.json")))
            name = scen["penetration"]["projectile"]
            index = [b["name"] for b in scen["bodies"]].index(name)
            v0 = np.array(scen["bodies"][index]["initial"]["velocity"], dtype=float)
            u0 = float(np.hypot(*v0))
            flight = v0 / u0
            per_radian = 2.0 * math.pi if scen.get("geometry") == "axisymmetric" else 1.0
            initial_mass = summary["penetration"]["initial_mass"]
            pvd = ET.parse(os.path.join(run, "run.pvd")).getroot()
            files = [(float(ds.get("timestep")), ds.get("file")) for ds in pvd.iter("DataSet")
                     if ds.get("file").endswith(".vtp")]
            first, last = {}, {}
            for time, rel in sorted(files):
                data = krug_vtk.read(os.path.join(run, rel))
                if len(data.points) == 0:
                    continue
                pd = data.point_data
                seen = {}
                for j in np.flatnonzero(np.ravel(pd["body"]) == index):
                    key = (float(pd["birth_time"][j]), float(pd["mass"][j]))
                    k = seen.get(key, 0)
                    seen[key] = k + 1
                    key = key + (k,)
                    speed = float(np.dot(pd["velocity"][j, :2], flight))
                    if key not in first:
                        first[key] = (time, speed)
                    last[key] = speed
            total = {c: 0.0 for c in ("cut", "held", "born_backward", "turned_backward", "backward", "all")}
            delays = []
            for key, (time, speed) in first.items():
                mass = key[1] * per_radian / initial_mass
                delays.append(time - key[0])
                total["all"] += mass
                total["cut" if speed > speed_fraction * u0 else "held"] += mass
                if speed < 0.0:
                    total["born_backward"] += mass
                elif last[key] < 0.0:
                    total["turned_backward"] += mass
                if last[key] < 0.0:
                    total["backward"] += mass
            zones_per_mm = scen["bodies"][index]["mesh"].get("radial_zones", 0) / (
                scen["bodies"][index]["mesh"].get("radius", 1.0) * 1e3)
            row = [os.path.basename(os.path.normpath(run)), f"{zones_per_mm:.1f}"] + [
                f"{total[c]:.4f}" for c in ("all", "cut", "held", "born_backward", "turned_backward", "backward")] + [
                str(len(first)), f"{np.mean(delays) * 1e6 if delays else 0.0:.3f}",
                f"{np.max(delays) * 1e6 if delays else 0.0:.3f}"]
            out.write(",".join(row) + "\n")
            print(",".join(row))
    print(csv_path)


def scatter(run_dirs, csv_path):
    """The spread of the headline figures over runs that differ by a perturbation that should not
    matter (`generate --velocity` 355 x (1 + k 1e-9), k = 0..N): runs are grouped by their name without
    the trailing `_d<k>`, and each group gets the mean, sample standard deviation, smallest and largest
    of each figure (bullet_hourglass: the projectile's hourglass work over the energy put into its zones).
    Writes one row per group."""
    groups = {}
    for run in run_dirs:
        name = os.path.basename(os.path.normpath(run))
        match = re.match(r"(.*)_d\d+$", name)
        group = match.group(1) if match else name
        summary = json.load(open(os.path.join(run, "summary.json")))
        p = summary["penetration"]
        w = p["whole"]
        groups.setdefault(group, []).append({
            "piece": p["piece_velocity_loss"], "whole": w["velocity_loss"],
            "eroded": p["eroded_mass"] / p["initial_mass"], "backward": w["backward_mass"] / p["initial_mass"],
            "cycles": float(summary["cycles"]),
            "bullet_hourglass": hourglass_share(summary.get("bodies", {}).get(p["projectile"], {}))})
    figures = ["piece", "whole", "eroded", "backward", "cycles", "bullet_hourglass"]
    fields = ["run", "runs"] + [f"{f}_{s}" for f in figures for s in ("mean", "std", "min", "max")]
    with open(csv_path, "w") as out:
        out.write(",".join(fields) + "\n")
        for group, rows in sorted(groups.items()):
            row = [group, str(len(rows))]
            for f in figures:
                values = np.array([r[f] for r in rows])
                std = float(values.std(ddof=1)) if len(values) > 1 else 0.0
                row += [f"{values.mean():.6g}", f"{std:.6g}", f"{values.min():.6g}", f"{values.max():.6g}"]
            out.write(",".join(row) + "\n")
            print(",".join(row))
    print(csv_path)


def read_particles(vtp_path):
    """Centres (z, r), radii and bodies of origin from Krug's VTK PolyData particle file."""
    data = krug_vtk.read(vtp_path)
    centres = [(float(p[0]), float(p[1])) for p in data.points]
    radius = data.point_data.get("radius")
    body = data.point_data.get("body")
    return (centres, [] if radius is None else [float(r) for r in np.ravel(radius)],
            [0] * len(centres) if body is None else [int(b) for b in np.ravel(body)])


def figures(run_dir, png_path, count, field, vmax=None):
    """Meshes and particles at `count` snapshot times, like the paper's Figs. 3-5, oriented as the app's
    own pictures: z horizontal, r up, mirrored below the axis; one view window and one colour range for
    every moment (the colour bar on the right); particles drawn in the colour of their origin body
    (bullet: grey, plates: black)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PatchCollection, PolyCollection
    from matplotlib.patches import Circle
    import numpy as np
    import xml.etree.ElementTree as ET
    collection = ET.parse(os.path.join(run_dir, "run.pvd")).getroot().find("Collection")
    meshes, particles = {}, {}
    for ds in collection:
        t = float(ds.get("timestep"))
        (meshes if ds.get("part") == "0" else particles)[t] = os.path.join(run_dir, ds.get("file"))
    times = sorted(meshes)
    picks = [times[round(i * (len(times) - 1) / max(count - 1, 1))] for i in range(count)]
    data = {t: krug_vtk.read(meshes[t]) for t in picks}
    # One window for all moments: the union of the pictured meshes, clipped to 10 mm behind the rear
    # face and 5 bullet radii off the axis (the plates' graded outer parts carry nothing to see).
    scenario = json.load(open(os.path.join(run_dir, "scenario.resolved.json")))
    bullet_z = [m.points[m.point_data["body"].ravel() == 0, 0] for m in data.values()]
    z_lo = min(float(z.min()) for z in bullet_z if z.size) * 1e3 - 1.0
    z_hi = max(float(z.max()) for z in bullet_z if z.size) * 1e3 + 1.0
    r_hi = 3.0 * BULLET_RADIUS * 1e3
    if vmax is None:
        vmax = 1.0 if field == "damaged" else 2.0 if field == "equivalent_plastic_strain" else max(
            float(np.nanmax(m.cell_data_dict[field]["quad"])) for m in data.values())
    panel = 1.75  # inches per moment; the width follows the window's aspect, plus the colour bar
    width = panel * (z_hi - z_lo) / (2.0 * r_hi) + 2.2
    fig, axes = plt.subplots(count, 1, figsize=(width, panel * count), sharex=True, constrained_layout=True)
    for ax, t in zip(np.atleast_1d(axes), picks):
        mesh = data[t]
        quads = mesh.cells_dict["quad"]
        values = mesh.cell_data_dict[field]["quad"].ravel()
        for sign in (1.0, -1.0):
            xy = np.column_stack([mesh.points[:, 0], sign * mesh.points[:, 1]]) * 1e3  # z right, r up, mm
            poly = PolyCollection(xy[quads], array=values, cmap="viridis", edgecolors="k", linewidths=0.03)
            poly.set_clim(0.0, vmax)
            ax.add_collection(poly)
        if t in particles:
            centres, radii, origin = read_particles(particles[t])
            circles = [Circle((c[0] * 1e3, sign * c[1] * 1e3), r * 1e3) for sign in (1.0, -1.0)
                       for c, r in zip(centres, radii)]
            colours = ["0.55" if o == 0 else "k" for _ in (1.0, -1.0) for o in origin]
            if circles:
                ax.add_collection(PatchCollection(circles, facecolor=colours, edgecolor="none", alpha=0.9))
        ax.axhline(0.0, color="0.3", lw=0.5, ls="--")
        ax.set_xlim(z_lo, z_hi)
        ax.set_ylim(-r_hi, r_hi)
        ax.set_aspect("equal")
        ax.set_ylabel("r (mm)")
        ax.text(0.01, 0.92, f"t = {t * 1e6:.1f} us", transform=ax.transAxes, fontsize=9, va="top")
    np.atleast_1d(axes)[-1].set_xlabel("z (mm); the bullet moves to the left")
    bar = fig.colorbar(poly, ax=axes, shrink=0.6, pad=0.01, extend="max" if field != "damaged" else "neither")
    bar.set_label({"equivalent_plastic_strain": "equivalent plastic strain (-)", "damaged": "damaged (0/1)"}.get(field, field))
    fig.suptitle(f"{os.path.basename(os.path.normpath(run_dir))}\n{field}; particles: lead grey, aluminium black",
                 fontsize=9)
    fig.savefig(png_path, dpi=110)
    print(png_path)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    g = sub.add_parser("generate")
    g.add_argument("outdir")
    g.add_argument("--mass", type=float, default=11.0, help="bullet mass (g): 11 as printed, 2.6 .22 LR-like")
    g.add_argument("--kind", choices=["monolithic", "layered", "spaced"], default="monolithic")
    g.add_argument("--thickness", type=float, default=3.0, help="total thickness H (mm); n plates of 1 mm")
    g.add_argument("--zones-per-mm", type=int, default=10)
    g.add_argument("--gap", type=float, default=5.0, help="spacing of spaced plates (mm)")
    g.add_argument("--target-radius", type=float, default=25.0, help="mm")
    g.add_argument("--rim", choices=["fixed", "free"], default="fixed")
    g.add_argument("--elongation", type=float, default=PAPER_ELONGATION)
    g.add_argument("--friction", type=float, default=0.0)
    g.add_argument("--particles", type=int, choices=[1, 4], default=1)
    g.add_argument("--altitude-ratio", type=float, default=0.25)
    g.add_argument("--velocity", type=float, default=355.0)
    g.add_argument("--interior-altitude-ratio", type=float, default=0.1, help="f_i")
    g.add_argument("--gap-tolerance", type=float, default=1e-4, help="contact.gap_tolerance")
    g.add_argument("--erosion", type=float, default=0.1,
                   help="lead erosion altitude ratio (default 0.1; 0: off, the paper's non-fracturing lead)")
    g.add_argument("--hourglass", type=float, default=None,
                   help="both hourglass coefficients, controls.hourglass.viscous and .stiffness (default: the library's 0.05)")
    g.add_argument("--velocity-window-only", action="store_true",
                   help="stop on the velocity window alone, without waiting for the bullet to clear the plates")
    g.add_argument("--contact-method", choices=["gauss_seidel", "summation"], default="gauss_seidel")
    g.add_argument("--snapshot-interval", type=float, default=None,
                   help="us between snapshots (default: the run's end time / 20); erosion-origin wants 0.5 or less")
    g.add_argument("--name", default=None)
    r = sub.add_parser("report")
    r.add_argument("runs", nargs="+")
    r.add_argument("--csv", required=True)
    fg = sub.add_parser("figures")
    fg.add_argument("run")
    fg.add_argument("png")
    fg.add_argument("--count", type=int, default=4)
    fg.add_argument("--field", default="equivalent_plastic_strain")
    fg.add_argument("--vmax", type=float, default=None, help="top of the colour range (plastic strain: 2)")
    vh = sub.add_parser("velocity-history")
    vh.add_argument("runs", nargs="+")
    vh.add_argument("--csv", required=True)
    eo = sub.add_parser("erosion-origin")
    eo.add_argument("runs", nargs="+")
    eo.add_argument("--csv", required=True)
    eo.add_argument("--speed-fraction", type=float, default=0.5,
                    help="eroded lead born faster than this fraction of U0 along the flight counts as cut "
                         "from the moving bullet, the rest as held back by the target")
    sc = sub.add_parser("scatter")
    sc.add_argument("runs", nargs="+")
    sc.add_argument("--csv", required=True)
    args = parser.parse_args()
    if args.command == "scatter":
        return scatter(args.runs, args.csv)
    if args.command == "erosion-origin":
        return erosion_origin(args.runs, args.csv, args.speed_fraction)
    if args.command == "velocity-history":
        return velocity_history(args.runs, args.csv)
    if args.command == "report":
        return report(args.runs, args.csv)
    if args.command == "figures":
        return figures(args.run, args.png, args.count, args.field, args.vmax)
    os.makedirs(args.outdir, exist_ok=True)
    name = args.name or f"{args.kind}_{args.thickness:g}mm_{args.mass:g}g"
    path = os.path.join(args.outdir, name + ".json")
    with open(path, "w") as f:
        json.dump(scenario(args), f, indent=2)
        f.write("\n")
    print(path)


if __name__ == "__main__":
    main()
