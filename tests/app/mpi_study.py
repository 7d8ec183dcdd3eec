#!/usr/bin/env python3
"""`krug sweep` and `krug ballistic` under mpirun on this machine (label `app`, registered when the app
is built with MPI): the tables equal those of `--jobs` row for row (every column but wall_seconds),
a failed variant is survived and reported, a long variant does not hold the others back, and a study whose folder was left half-done (summaries
deleted or truncated; an mpirun killed after its first round) resumes to the same table without
running the finished variants again.

    mpi_study.py --krug build/apps/krug/krug --mpirun /usr/bin/mpirun --examples examples \
                 --data tests/app/data --work build/tests/app/work/mpi
"""
import argparse
import csv
import json
import os
import shutil
import signal
import subprocess
import sys
import time

TIMEOUT = 600
failures = []


def check(condition, what):
    print(("ok: " if condition else "FAILED: ") + what, flush=True)
    if not condition:
        failures.append(what)


def mpi_environment():
    env = dict(os.environ)
    env.update({
        "OMPI_ALLOW_RUN_AS_ROOT": "1",            # CI runs as root
        "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
        "OMPI_MCA_rmaps_base_oversubscribe": "1",  # more ranks than cores
        "OMPI_MCA_btl": "self,vader",              # one machine: shared memory only
        "OMPI_MCA_btl_vader_single_copy_mechanism": "none",  # containers refuse ptrace (CMA)
        "OMPI_MCA_plm_rsh_agent": "",              # never ssh
    })
    return env


def run(arguments, log, env=None):
    with open(log, "w") as out:
        result = subprocess.run(arguments, stdout=out, stderr=subprocess.STDOUT, env=env, timeout=TIMEOUT)
    with open(log) as f:
        text = f.read()
    return result.returncode, text


def mpirun(args, n):
    return [args.mpirun, "--oversubscribe", "--allow-run-as-root", "--bind-to", "none", "-np", str(n), args.krug]


def table(path, timing=("wall_seconds",)):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header = rows[0]
    keep = [i for i, name in enumerate(header) if name not in timing]
    return [[row[i] for i in keep] for row in rows]


def same_table(a, b, what):
    ta, tb = table(a), table(b)
    equal = ta == tb
    if not equal:
        for ra, rb in zip(ta, tb):
            if ra != rb:
                print("  differs:\n   ", ra, "\n   ", rb)
        if len(ta) != len(tb):
            print("  rows:", len(ta), len(tb))
    check(equal and len(ta) > 1, f"{what}: {len(ta) - 1} rows equal, every column but wall_seconds")


def sweep(args, work):
    scenario = os.path.join(args.examples, "verification", "slab_impact.json")
    base = ["sweep", scenario, "--set", "bodies[0].initial.velocity[0]=10,20", "--set",
            "materials.aluminium.density=2785,3000", "--set", "controls.time_step_floor=0,1e-6", "--set",
            'output={"plots": false, "pictures": {"enabled": false}}', "--quiet"]
    jobs_dir, mpi_dir = os.path.join(work, "sweep_jobs"), os.path.join(work, "sweep_mpi")
    code, text = run([args.krug] + base + ["--jobs", "2", "--out", jobs_dir], os.path.join(work, "sweep_jobs.log"))
    check(code == 1, f"krug sweep --jobs 2 with failing variants exits 1 (got {code})")
    code, text = run(mpirun(args, 3) + base + ["--out", mpi_dir], os.path.join(work, "sweep_mpi.log"), mpi_environment())
    check(code == 1, f"mpirun -np 3 krug sweep with failing variants exits 1 (got {code}): {text[-400:]}")
    check("4 completed, 4 failed" in text, "the MPI sweep reports 4 completed and 4 failed")
    same_table(os.path.join(jobs_dir, "sweep.csv"), os.path.join(mpi_dir, "sweep.csv"), "sweep: MPI table = --jobs table")
    with open(os.path.join(mpi_dir, "sweep.csv"), newline="") as f:
        failed = [r for r in csv.DictReader(f) if r["status"] == "failed"]
    check(len(failed) == 4 and all("floor" in r["message"] for r in failed),
          "the failed variants are in the table with their diagnostic")

    # Half-done: one summary deleted, one summary and history truncated; the rest must be kept as they are.
    variants = sorted(d for d in os.listdir(mpi_dir) if os.path.isdir(os.path.join(mpi_dir, d)))
    deleted, truncated = variants[0], variants[2]
    os.remove(os.path.join(mpi_dir, deleted, "summary.json"))
    for name in ("summary.json", "history.csv"):
        path = os.path.join(mpi_dir, truncated, name)
        size = os.path.getsize(path)
        with open(path, "r+b") as f:
            f.truncate(size // 2)
    untouched = {v: os.path.getmtime(os.path.join(mpi_dir, v, "summary.json")) for v in variants if v not in (deleted, truncated)}
    time.sleep(0.05)
    code, text = run(mpirun(args, 2) + base[:-1] + ["--out", mpi_dir], os.path.join(work, "sweep_resume.log"), mpi_environment())
    check(code == 1, f"the resumed MPI sweep exits 1 (failing variants) (got {code})")
    check("6 of them finished in an earlier sweep into this folder (kept); 2 to run" in text,
          "the resumed sweep keeps 6 finished variants and runs 2")
    check(all(os.path.getmtime(os.path.join(mpi_dir, v, "summary.json")) == t for v, t in untouched.items()),
          "the finished variants were not run again")
    same_table(os.path.join(jobs_dir, "sweep.csv"), os.path.join(mpi_dir, "sweep.csv"), "sweep: resumed MPI table = --jobs table")

    # The same resume without MPI (--jobs).
    os.remove(os.path.join(jobs_dir, variants[1], "summary.json"))
    shutil.copy(os.path.join(jobs_dir, "sweep.csv"), os.path.join(work, "sweep_jobs_first.csv"))
    code, text = run([args.krug] + base[:-1] + ["--jobs", "2", "--out", jobs_dir], os.path.join(work, "sweep_jobs_resume.log"))
    check("7 of them finished in an earlier sweep into this folder (kept); 1 to run" in text, "krug sweep --jobs resumes too")
    same_table(os.path.join(work, "sweep_jobs_first.csv"), os.path.join(jobs_dir, "sweep.csv"), "sweep: resumed --jobs table = first")


def long_run(args, work):
    """A long variant holds only its own rank: the short ones go on around it."""
    scenario = os.path.join(args.examples, "verification", "slab_impact.json")
    code, text = run(mpirun(args, 2) + ["sweep", scenario, "--set", "end_time=1.5e-3,4e-6,4e-6,4e-6,4e-6,4e-6", "--set",
                                        'output={"plots": false, "pictures": {"enabled": false}, "history_interval": 1e-6}',
                                        "--out", os.path.join(work, "sweep_long")],
                     os.path.join(work, "sweep_long.log"), mpi_environment())
    check(code == 0, f"a sweep with one long variant completes (got {code})")
    ended = [line.split()[2] for line in text.splitlines() if line.startswith("krug: ") and "/6 " in line]
    check(len(ended) == 6 and ended[-1].startswith("000_") and all(not e.startswith("000_") for e in ended[:-1]),
          f"the five short variants ended while the long one (77 000 cycles) ran: {ended}")


def ballistic(args, work):
    scenario = os.path.join(args.data, "ballistic_plate.json")
    base = ["ballistic", scenario, "--velocity", "60,400", "--tolerance", "10"]
    jobs_dir, mpi_dir, kill_dir = (os.path.join(work, n) for n in ("ballistic_jobs", "ballistic_mpi", "ballistic_killed"))
    code, _ = run([args.krug] + base + ["--jobs", "2", "--out", jobs_dir], os.path.join(work, "ballistic_jobs.log"))
    check(code == 0, f"krug ballistic --jobs 2 converges (got {code})")
    code, text = run(mpirun(args, 2) + base + ["--out", mpi_dir], os.path.join(work, "ballistic_mpi.log"), mpi_environment())
    check(code == 0, f"mpirun -np 2 krug ballistic converges (got {code}): {text[-400:]}")
    check("2 runs per round (one at a time on each of 2 MPI ranks)" in text, "two runs per round, on the two ranks")
    same_table(os.path.join(jobs_dir, "ballistic.csv"), os.path.join(mpi_dir, "ballistic.csv"),
               "ballistic: MPI table = --jobs table")
    with open(os.path.join(jobs_dir, "ballistic.json")) as f:
        a = json.load(f)
    with open(os.path.join(mpi_dir, "ballistic.json")) as f:
        b = json.load(f)
    check(all(a[k] == b[k] for k in ("bracket", "v_bl", "v50", "runs", "counts", "lambert_jonas")),
          "ballistic.json: the same bracket, limit and fit")

    # Killed after its first round, then started again: it resumes to the same table.
    log = open(os.path.join(work, "ballistic_killed.log"), "w")
    process = subprocess.Popen(mpirun(args, 2) + base + ["--out", kill_dir], stdout=log, stderr=subprocess.STDOUT,
                               env=mpi_environment())
    table_file = os.path.join(kill_dir, "ballistic.csv")
    start = time.time()
    while process.poll() is None and not os.path.exists(table_file) and time.time() - start < TIMEOUT:
        time.sleep(0.02)
    killed = process.poll() is None
    if killed:
        process.send_signal(signal.SIGTERM)
    process.wait(timeout=TIMEOUT)
    log.close()
    print(f"  the first study {'was killed after its first round' if killed else 'ended before it could be killed'}")
    code, text = run(mpirun(args, 2) + base + ["--out", kill_dir], os.path.join(work, "ballistic_resume.log"), mpi_environment())
    check(code == 0, f"the resumed ballistic study converges (got {code})")
    check("kept from an earlier study" in text, "the resumed study keeps the runs finished before the kill")
    same_table(os.path.join(jobs_dir, "ballistic.csv"), table_file, "ballistic: resumed MPI table = --jobs table")


def main():
    parser = argparse.ArgumentParser()
    for name in ("krug", "mpirun", "examples", "data", "work"):
        parser.add_argument("--" + name, required=True)
    args = parser.parse_args()
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    sweep(args, args.work)
    long_run(args, args.work)
    ballistic(args, args.work)
    if failures:
        print(f"{len(failures)} checks failed")
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
