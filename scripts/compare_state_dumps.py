#!/usr/bin/env python3
"""Compares two directories of state dumps written by `state_digest EXAMPLES_DIR --dump DIR`
(benchmarks/state_digest.cpp): per problem, whether the values are bitwise identical, and otherwise
the largest difference relative to the largest magnitude of the values (the dump holds positions,
velocities, zone fields and the ledger, in that order; see state_values() there).

    scripts/compare_state_dumps.py BEFORE_DIR AFTER_DIR
"""
import pathlib
import sys

import numpy as np


def main(before: str, after: str) -> int:
    status = 0
    for path in sorted(pathlib.Path(before).glob("*.bin")):
        other = pathlib.Path(after) / path.name
        a = np.fromfile(path, dtype=np.float64)
        if not other.exists():
            print(f"{path.stem:26s} missing in {after}")
            status = 1
            continue
        b = np.fromfile(other, dtype=np.float64)
        if a.shape != b.shape:
            print(f"{path.stem:26s} different sizes {a.size} / {b.size}")
            status = 1
            continue
        if a.tobytes() == b.tobytes():
            print(f"{path.stem:26s} bitwise identical")
            continue
        finite = np.isfinite(a) & np.isfinite(b)
        scale = np.max(np.abs(a[finite])) if finite.any() else 1.0
        print(f"{path.stem:26s} differ in {np.count_nonzero(a != b)} of {a.size} values, "
              f"max |difference| / max |value| = {np.max(np.abs(a[finite] - b[finite])) / scale:.3e}")
        status = 1
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
