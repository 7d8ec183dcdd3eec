#!/usr/bin/env python3
"""Read-back of Krug's VTK files with meshio (Debian: python3-meshio), as ParaView users would load
them. Runs the krug app on a small fracture scenario, then checks:
  * final.vtu and every snapshots/state_*.vtu read by meshio: one quad cell per active zone
    (summary.json bodies.*.zones), the cell fields and point fields Krug documents, finite values,
    densities within the materials' range, body ids of the right bodies;
  * the von Mises stress written equals sqrt(3/2 s:s) of the deviator written (independent formula);
  * final_particles.vtp (VTK PolyData, which meshio does not read: decoded here, compressed binary or
    text): one point per particle of summary.json particles.count, their mass summing to particles.mass;
  * the same run with output.vtk_format "ascii" gives the same values, array by array;
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
import struct
import xml.etree.ElementTree as ET
import zlib

try:
    import meshio
except ImportError:
    print("read_back.py: meshio is not available (install python3-meshio); skipped")
    sys.exit(77)

CELL_FIELDS = ["body", "density", "pressure", "specific_internal_energy", "sound_speed", "von_mises_stress",
               "equivalent_plastic_strain", "damaged", "damage_onset_time", "damage_criterion", "stable_time_step"]
DEVIATOR = {"planar": ["deviatoric_stress_xx", "deviatoric_stress_yy", "deviatoric_stress_xy", "deviatoric_stress_zz"],
            "axisymmetric": ["deviatoric_stress_zz", "deviatoric_stress_rr", "deviatoric_stress_zr",
                             "deviatoric_stress_tt"]}
POINT_FIELDS = ["velocity", "body"]
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAILED:", message)


def check_field_data(path, field_data, names, time=None):
    """Data set fields: TimeValue (s) and one array "body I: NAME (MATERIAL)" holding I per body."""
    check("TimeValue" in field_data, f"{path}: field data TimeValue missing")
    if time is not None and "TimeValue" in field_data:
        value = float(field_data["TimeValue"][0])
        check(abs(value - time) <= 1e-9 * max(time, 1e-30), f"{path}: TimeValue {value}, expected {time}")  # run.pvd: 10 digits
    if names is None:
        return
    labels = sorted(k for k in field_data if k.startswith("body "))
    check(len(labels) == len(names), f"{path}: {len(labels)} body labels for {len(names)} bodies")
    for i, name in enumerate(names):
        label = [k for k in labels if k.startswith(f"body {i}: {name} (")]
        check(len(label) == 1, f"{path}: no field data array names body {i} ({name}); found {labels}")
        if label:
            check(int(field_data[label[0]][0]) == i, f"{path}: {label[0]} holds {field_data[label[0]][0]}")


def read_vtu(path, zones=None, bodies=None, geometry=None, names=None, time=None):
    mesh = meshio.read(path)
    check_field_data(path, mesh.field_data, names, time)
    quads = sum(len(block.data) for block in mesh.cells if block.type == "quad")
    others = [block.type for block in mesh.cells if block.type != "quad"]
    check(not others, f"{path}: only quad cells expected, found {others}")
    if zones is not None:
        check(quads == zones, f"{path}: {quads} cells, summary.json says {zones} active zones")
    deviator = DEVIATOR["axisymmetric" if "deviatoric_stress_rr" in mesh.cell_data else "planar"]
    if geometry is not None:
        deviator = DEVIATOR[geometry]
    for name in CELL_FIELDS + deviator:
        check(name in mesh.cell_data, f"{path}: cell field {name} missing")
    for name in POINT_FIELDS:
        check(name in mesh.point_data, f"{path}: point field {name} missing")
    velocity = mesh.point_data["velocity"]
    check(velocity.shape == (len(mesh.points), 3), f"{path}: velocity has shape {velocity.shape}")
    check(all(math.isfinite(v) for v in velocity.flatten()), f"{path}: non-finite velocity")
    density = [d for block in mesh.cell_data["density"] for d in block]
    check(all(d > 0 and math.isfinite(d) for d in density), f"{path}: a density not positive and finite")
    s = [mesh.cell_data[name][0] for name in deviator]
    vm = mesh.cell_data["von_mises_stress"][0]
    for i in range(len(vm)):
        expected = math.sqrt(1.5 * (s[0][i] ** 2 + s[1][i] ** 2 + s[3][i] ** 2 + 2 * s[2][i] ** 2))
        check(abs(vm[i] - expected) <= 1e-12 * max(expected, 1.0), f"{path}: von Mises {vm[i]} vs {expected}")
    if bodies is not None:
        ids = sorted({int(b) for block in mesh.cell_data["body"] for b in block})
        check(all(0 <= i < bodies for i in ids), f"{path}: body ids {ids} outside 0..{bodies - 1}")
    return mesh


TYPES = {"Float64": "d", "Int32": "i", "UInt8": "B", "Int64": "q"}


def vtk_arrays(path):
    """Every DataArray of a VTK XML file, text or appended zlib-compressed binary (UInt64 headers)."""
    with open(path, "rb") as f:
        data = f.read()
    split = data.find(b"<AppendedData")
    head = data if split < 0 else data[:split] + b"</VTKFile>"
    root = ET.fromstring(head)
    appended = b""
    if split >= 0:
        start = data.index(b"_", data.index(b">", split)) + 1
        appended = data[start:]
    arrays = {}
    for a in root.iter("DataArray"):
        name, code = a.get("Name"), TYPES[a.get("type")]
        if a.get("format") == "ascii":
            values = [float(x) for x in (a.text or "").split()]
        else:
            check(root.get("compressor") == "vtkZLibDataCompressor", f"{path}: appended data without zlib")
            at = int(a.get("offset"))
            blocks = struct.unpack_from("<Q", appended, at)[0]
            header = struct.unpack_from(f"<{3 + blocks}Q", appended, at)
            at += 8 * (3 + blocks)
            raw = b""
            for size in header[3:]:
                raw += zlib.decompress(appended[at:at + size])
                at += size
            values = list(struct.unpack(f"<{len(raw) // struct.calcsize(code)}{code}", raw))
        arrays[name] = values
    return root, arrays


def read_vtp(path, names=None, time=None):
    root, arrays = vtk_arrays(path)
    check_field_data(path, {k: v for k, v in arrays.items() if k == "TimeValue" or k.startswith("body ")}, names, time)
    check(root.get("type") == "PolyData", f"{path}: not VTK PolyData")
    count = int(root.find("PolyData/Piece").get("NumberOfPoints"))
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

    names = list(summary["bodies"])  # in the scenario's order
    final = read_vtu(os.path.join(args.work, "final.vtu"), zones, bodies, names=names, time=summary["time"])
    print(f"final.vtu: {len(final.points)} points, {zones} quads, fields {sorted(final.cell_data)}")

    count, arrays = read_vtp(os.path.join(args.work, "final_particles.vtp"), names, summary["time"])
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
    for t, name in meshes:
        read_vtu(os.path.join(args.work, name), bodies=bodies, names=names, time=t)
    for t, name in particles:
        read_vtp(os.path.join(args.work, name), names, t)
    print(f"run.pvd: {len(meshes)} mesh and {len(particles)} particle snapshots, t = {times[0]} .. {times[-1]}")
    # The same run written as text: every array of final.vtu and final_particles.vtp equal, value by value
    # (the text holds 10 significant digits).
    with open(args.scenario) as f:
        document = json.load(f)
    document.setdefault("output", {})["vtk_format"] = "ascii"
    ascii_dir = args.work.rstrip("/") + "_ascii"
    os.makedirs(ascii_dir, exist_ok=True)
    ascii_scenario = os.path.join(ascii_dir, "scenario.json")
    with open(ascii_scenario, "w") as f:
        json.dump(document, f)
    run = subprocess.run([args.krug, "run", ascii_scenario, "--out", ascii_dir, "--quiet", "--no-plots",
                          "--no-pictures"], capture_output=True, text=True)
    check(run.returncode == 0, f"krug run (ascii) exited with {run.returncode}: {run.stderr}")
    for name in ("final.vtu", "final_particles.vtp"):
        _, binary = vtk_arrays(os.path.join(args.work, name))
        _, text = vtk_arrays(os.path.join(ascii_dir, name))
        check(sorted(binary) == sorted(text), f"{name}: binary and text files name different arrays")
        for key in binary:
            same = len(binary[key]) == len(text[key]) and all(
                abs(a - b) <= 1e-9 * max(abs(a), abs(b), 1e-300) for a, b in zip(binary[key], text[key]))
            check(same, f"{name}: array {key} differs between the binary and the text file")
    sizes = [os.path.getsize(os.path.join(d, "final.vtu")) for d in (args.work, ascii_dir)]
    print(f"final.vtu: {sizes[0]} bytes binary, {sizes[1]} bytes text; the same values")
    if failures:
        print(f"{len(failures)} checks failed")
        return 1
    print("all read-back checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
