#!/usr/bin/env python3
"""Read-back of Krug's VTK files with meshio (Debian: python3-meshio), as ParaView users would load
them. Runs the krug app on a small fracture scenario, then checks:
  * final.vtu and every snapshots/state_*.vtu read by meshio: one quad cell per active zone
    (summary.json bodies.*.zones), the cell fields and point fields Krug documents, finite values,
    densities within the materials' range, body ids of the right bodies;
  * final_particles.vtp (VTK PolyData, which meshio does not read: parsed as XML): one point per
    particle of summary.json particles.count, their mass summing to particles.mass;
  * run.pvd (a ParaView collection, plain XML): increasing times ending at summary.json time,
    every listed file present and readable.
Exit code 77 (skipped) when meshio is missing.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

try:
    import meshio
except ImportError:
    print("read_back.py: meshio is not available (install python3-meshio); skipped")
    sys.exit(77)

CELL_FIELDS = ["body", "density", "pressure", "specific_internal_energy", "sound_speed",
               "deviatoric_stress_xx_yy_xy_zz", "equivalent_plastic_strain", "damaged",
               "damage_onset_time", "damage_criterion"]
POINT_FIELDS = ["velocity", "body"]
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAILED:", message)


def read_vtu(path, zones=None, bodies=None):
    mesh = meshio.read(path)
    quads = sum(len(block.data) for block in mesh.cells if block.type == "quad")
    others = [block.type for block in mesh.cells if block.type != "quad"]
    check(not others, f"{path}: only quad cells expected, found {others}")
    if zones is not None:
        check(quads == zones, f"{path}: {quads} cells, summary.json says {zones} active zones")
    for name in CELL_FIELDS:
        check(name in mesh.cell_data, f"{path}: cell field {name} missing")
    for name in POINT_FIELDS:
        check(name in mesh.point_data, f"{path}: point field {name} missing")
    velocity = mesh.point_data["velocity"]
    check(velocity.shape == (len(mesh.points), 3), f"{path}: velocity has shape {velocity.shape}")
    check(all(math.isfinite(v) for v in velocity.flatten()), f"{path}: non-finite velocity")
    density = [d for block in mesh.cell_data["density"] for d in block]
    check(all(d > 0 and math.isfinite(d) for d in density), f"{path}: a density not positive and finite")
    stress = mesh.cell_data["deviatoric_stress_xx_yy_xy_zz"][0]
    check(stress.shape[1] == 4, f"{path}: the deviator has {stress.shape[1]} components")
    if bodies is not None:
        ids = sorted({int(b) for block in mesh.cell_data["body"] for b in block})
        check(all(0 <= i < bodies for i in ids), f"{path}: body ids {ids} outside 0..{bodies - 1}")
    return mesh


def read_vtp(path):
    root = ET.parse(path).getroot()
    check(root.get("type") == "PolyData", f"{path}: not VTK PolyData")
    piece = root.find("PolyData/Piece")
    count = int(piece.get("NumberOfPoints"))
    arrays = {a.get("Name"): [float(x) for x in (a.text or "").split()] for a in piece.iter("DataArray")}
    check(len(arrays["coordinates"]) == 3 * count, f"{path}: {len(arrays['coordinates'])} coordinates for {count} points")
    for name in ("velocity", "radius", "mass", "body", "birth_time"):
        check(name in arrays, f"{path}: particle field {name} missing")
    check(all(r > 0 for r in arrays["radius"]), f"{path}: a radius not positive")
    return count, arrays


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--krug", required=True)
    parser.add_argument("--scenario", required=True)
    parser.add_argument("--work", required=True)
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    run = subprocess.run([args.krug, "run", args.scenario, "--out", args.work, "--quiet", "--no-plots",
                          "--no-pictures"], capture_output=True, text=True)
    check(run.returncode == 0, f"krug run exited with {run.returncode}: {run.stderr}")
    with open(os.path.join(args.work, "summary.json")) as f:
        summary = json.load(f)
    zones = sum(body["zones"] for body in summary["bodies"].values())
    bodies = len(summary["bodies"])

    final = read_vtu(os.path.join(args.work, "final.vtu"), zones, bodies)
    print(f"final.vtu: {len(final.points)} points, {zones} quads, fields {sorted(final.cell_data)}")

    count, arrays = read_vtp(os.path.join(args.work, "final_particles.vtp"))
    check(count == summary["particles"]["count"], f"final_particles.vtp: {count} particles, summary says "
          f"{summary['particles']['count']}")
    check(count > 0, "the scenario should make particles")
    # Planar: masses per unit thickness, as in summary.json.
    mass = sum(arrays["mass"])
    check(abs(mass - summary["particles"]["mass"]) <= 1e-9 * max(mass, 1e-30),
          f"particle mass {mass} vs summary {summary['particles']['mass']}")
    print(f"final_particles.vtp: {count} particles, mass {mass:.6g}")

    pvd = ET.parse(os.path.join(args.work, "run.pvd")).getroot()
    check(pvd.get("type") == "Collection", "run.pvd: not a Collection")
    sets = pvd.findall("Collection/DataSet")
    meshes = [(float(d.get("timestep")), d.get("file")) for d in sets if d.get("part") == "0"]
    particles = [(float(d.get("timestep")), d.get("file")) for d in sets if d.get("part") == "1"]
    times = [t for t, _ in meshes]
    check(len(meshes) >= 3, f"run.pvd: {len(meshes)} mesh snapshots")
    check(all(a < b for a, b in zip(times, times[1:])), f"run.pvd: times not increasing: {times}")
    check(times[0] == 0.0, "run.pvd: the first snapshot is not at t = 0")
    check(abs(times[-1] - summary["time"]) <= 1e-6 * summary["time"], "run.pvd: the last snapshot is not the end")
    for _, name in meshes:
        read_vtu(os.path.join(args.work, name), bodies=bodies)
    for _, name in particles:
        read_vtp(os.path.join(args.work, name))
    print(f"run.pvd: {len(meshes)} mesh and {len(particles)} particle snapshots, t = {times[0]} .. {times[-1]}")
    if failures:
        print(f"{len(failures)} checks failed")
        return 1
    print("all read-back checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
