#!/usr/bin/env python3
"""The L1 density error of a polar-mesh run against an exact radial profile, as the speed-against-error
study defines it (tests/verification/convergence_speed_error.cpp): on every ray, the sum over its zones
of |rho - the exact density averaged over the zone's radial extent| x that extent; the mean over the
rays. Each zone belongs to one ray, so the sum over all zones divided by the number of rays is the same.

Reads a Krug final.vtu, or a text file of zones for another code (docs/performance.md, "Peer codes"):
lines "zone density", then after a line "# sides", lines "zone x y", one per corner of each zone.

  scripts/ray_l1.py OUT/final.vtu RAYS tests/data/exact/noh_spherical_t0.6.csv
  scripts/ray_l1.py --zones zones.txt RAYS tests/data/exact/sedov_spherical_t1.csv
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))


def exact_profile(path):
    data = np.genfromtxt(path, delimiter=",", names=True, skip_header=1)
    return data["r"], data["density"]


def zone_mean(position, density, low, high, samples=32):
    # The midpoint rule on 32 sub-intervals over linear interpolation, as ExactProfile::mean.
    x = low + (high - low) * (np.arange(samples) + 0.5) / samples
    return np.interp(x, position, density).mean()


def krug_zones(path):
    import krug_vtk
    data = krug_vtk.read(path)
    density = data.cell_data_dict["density"]["quad"]
    radius = np.hypot(data.points[:, 0], data.points[:, 1])
    return [(density[i], radius[cell]) for i, cell in enumerate(data.cells_dict["quad"])]


def text_zones(path):
    density, corners, section = {}, {}, "density"
    for line in open(path):
        if line.startswith("#"):
            section = "sides" if "sides" in line else section
            continue
        fields = line.split()
        if not fields:
            continue
        if section == "density":
            density[int(fields[0])] = float(fields[1])
        else:
            corners.setdefault(int(fields[0]), []).append(np.hypot(float(fields[1]), float(fields[2])))
    return [(density[z], np.array(corners[z])) for z in sorted(density)]


def main():
    parser = argparse.ArgumentParser(description=" ".join(__doc__.split("\n\n")[0].split()))
    parser.add_argument("run", help="a Krug final.vtu, or with --zones a text file of zones")
    parser.add_argument("rays", type=int, help="the mesh's number of rays (angular zones)")
    parser.add_argument("exact", help="the exact profile (CSV with columns r and density)")
    parser.add_argument("--zones", action="store_true", help="RUN is a text file of zones, not a VTU file")
    args = parser.parse_args()
    position, density = exact_profile(args.exact)
    zones = text_zones(args.run) if args.zones else krug_zones(args.run)
    total = sum(abs(rho - zone_mean(position, density, r.min(), r.max())) * (r.max() - r.min()) for rho, r in zones)
    print(f"L1 {total / args.rays:.4g} over {len(zones)} zones")


if __name__ == "__main__":
    main()
