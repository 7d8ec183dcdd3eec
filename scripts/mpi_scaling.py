#!/usr/bin/env python3
"""How a sweep's time scales with MPI ranks on this machine (docs/cluster.md): eight variants of the
coarse paper case (the bullet's speed varied), run by `mpirun -np N krug sweep` for each N given and
by `krug sweep --jobs 2`, the configurations interleaved and repeated (--repeat) so that a change in
the machine's other load falls on all of them. Prints and writes (--csv) per configuration the wall
time (min, median, max), the CPU time of everything it started (user + system, from the OS), the
sum of the runs' own wall seconds, and the load average before the runs.

    scripts/mpi_scaling.py --krug build/apps/krug/krug [--ranks 1,2,3] [--repeat 3]
                           [--out /tmp/krug-mpi-scaling] [--csv docs/validation/mpi_scaling.csv]
"""
import argparse
import csv
import os
import resource
import shutil
import statistics
import subprocess
import time

here = os.path.dirname(os.path.abspath(__file__))
scenario = os.path.join(here, "..", "examples", "paper", "coarse", "monolithic_3mm_2.6g_z5.json")
sets = ["--set", "bodies[0].initial.velocity[0]=-300,-320,-340,-360,-380,-400,-420,-440",
        "--set", 'output={"plots": false, "pictures": {"enabled": false}}', "--quiet"]
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1", OMPI_MCA_btl="self,vader",
           OMPI_MCA_btl_vader_single_copy_mechanism="none")


def measure(command, out):
    shutil.rmtree(out, ignore_errors=True)
    load = os.getloadavg()[0]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.monotonic()
    subprocess.run(command + ["--out", out], env=env, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wall = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    with open(os.path.join(out, "sweep.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    runs = sum(float(r["wall_seconds"]) for r in rows)
    completed = sum(r["status"] == "completed" for r in rows)
    return {"wall": wall, "cpu": cpu, "runs": runs, "completed": completed, "variants": len(rows), "load": load}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--krug", required=True)
    parser.add_argument("--mpirun", default="mpirun")
    parser.add_argument("--ranks", default="1,2,3")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--out", default="/tmp/krug-mpi-scaling")
    parser.add_argument("--csv", help="also write the table here")
    args = parser.parse_args()
    configurations = []
    for n in (int(x) for x in args.ranks.split(",")):
        configurations.append((f"np{n}", f"mpirun -np {n}", [args.mpirun, "--oversubscribe", "--allow-run-as-root", "--bind-to",
                                                             "none", "-np", str(n), args.krug, "sweep", scenario] + sets))
    configurations.append(("jobs2", "krug sweep --jobs 2", [args.krug, "sweep", scenario] + sets + ["--jobs", "2"]))
    results = {name: [] for name, _, _ in configurations}
    for r in range(args.repeat):
        for name, label, command in configurations:
            m = measure(command, os.path.join(args.out, name))
            results[name].append(m)
            print(f"round {r + 1}: {label}: {m['wall']:.1f} s wall, {m['cpu']:.1f} s CPU, load {m['load']:.1f}", flush=True)
    header = ["run", "how", "wall_min_s", "wall_median_s", "wall_max_s", "cpu_median_s", "runs_wall_median_s", "completed",
              "variants", "load_min", "load_max", "repeats", "cores"]
    table = []
    for name, label, _ in configurations:
        ms = results[name]
        walls = [m["wall"] for m in ms]
        table.append([name, label, f"{min(walls):.1f}", f"{statistics.median(walls):.1f}", f"{max(walls):.1f}",
                      f"{statistics.median(m['cpu'] for m in ms):.1f}", f"{statistics.median(m['runs'] for m in ms):.1f}",
                      min(m["completed"] for m in ms), ms[0]["variants"], f"{min(m['load'] for m in ms):.1f}",
                      f"{max(m['load'] for m in ms):.1f}", len(ms), os.cpu_count()])
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for row in table:
        print("| " + " | ".join(str(c) for c in row) + " |")
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            writer = csv.writer(f, lineterminator="\n")
            writer.writerow(header)
            writer.writerows(table)


if __name__ == "__main__":
    main()
