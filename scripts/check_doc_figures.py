#!/usr/bin/env python3
"""Checks that the figures a Markdown page quotes from its CSV tables are the tables' figures.

    scripts/check_doc_figures.py docs/validation.md [--require-section "HEADING" ...]

A quoted figure carries its source right after it, as an HTML comment (invisible when rendered):

    the layered target takes 0.177<!-- converged.csv converged_layered_2.6g_z10 piece_dU_over_U0 -->

FILE is relative to the page's folder's `validation/` subfolder (or to the page itself when it has a
`/`); RUN is the value of the CSV's first column; COLUMN a column name. The figure must equal the CSV
value rounded to the figure's own number of decimals (a figure written 0.18 is checked to 2
decimals). RUN may be `r1:r2`, the difference of two rows' values (r1 minus r2); COLUMN may end in
`xN`, the value times N (x100: a fraction in per cent; x1000: g from kg). Every number inside a section named
with --require-section must carry a source, except years, counts written with a thin space, and
numbers inside a `<!-- no-csv -->` ... `<!-- /no-csv -->` span; so a headline cannot quote a figure that
no table backs.

Exit status 0 when every figure matches, 1 otherwise (each mismatch printed with its line).
"""
import argparse
import csv
import os
import re
import sys

SOURCE = re.compile(r"(?P<number>[-+−]?\d+(?:\.\d+)?)(?P<unit>\s?[a-zA-Z%/]*)?<!--\s*(?P<file>\S+\.csv)\s+(?P<run>\S+)\s+(?P<column>\S+)\s*-->")
NUMBER = re.compile(r"(?<![\w.])[-+−]?\d+\.\d+(?!\w)(?!\.\d)")


def load(path, cache):
    if path not in cache:
        with open(path, newline="") as f:
            reader = csv.reader(f)
            header = next(reader)
            rows = {}
            for row in reader:
                if row:
                    rows[row[0]] = dict(zip(header, row))
            cache[path] = rows
    return cache[path]


def value_of(rows, run, column):
    if ":" in run:
        a, b = run.split(":", 1)
        return value_of(rows, a, column) - value_of(rows, b, column)
    if run not in rows:
        raise KeyError(f"no row {run!r}")
    scale = 1.0
    suffix = re.search(r"x(\d+)$", column)
    if suffix:
        column, scale = column[: suffix.start()], float(suffix.group(1))
    if column not in rows[run]:
        raise KeyError(f"no column {column!r}")
    return scale * float(rows[run][column])


def decimals(text):
    return len(text.split(".")[1]) if "." in text else 0


def check(page, required_sections):
    folder = os.path.dirname(os.path.abspath(page))
    cache = {}
    failures = []
    checked = 0
    section = ""
    in_no_csv = False
    with open(page) as f:
        lines = f.read().split("\n")
    for number, line in enumerate(lines, start=1):
        if line.startswith("#"):
            section = line.lstrip("#").strip()
        for m in SOURCE.finditer(line):
            file = m.group("file")
            path = os.path.join(folder, file if "/" in file else os.path.join("validation", file))
            quoted = m.group("number").replace("−", "-")
            try:
                value = value_of(load(path, cache), m.group("run"), m.group("column"))
            except (OSError, KeyError, ValueError) as error:
                failures.append(f"{page}:{number}: {quoted} <- {file} {m.group('run')} {m.group('column')}: {error}")
                continue
            checked += 1
            places = decimals(quoted)
            if round(value, places) != round(float(quoted), places) and abs(value - float(quoted)) > 0.5 * 10 ** -places * (1 + 1e-9):
                failures.append(f"{page}:{number}: quotes {quoted}, {file} {m.group('run')} {m.group('column')} is "
                                f"{value:.{places + 2}f}")
        if any(section.startswith(s) for s in required_sections):
            stripped = line
            if "<!-- no-csv -->" in stripped:
                in_no_csv = True
            if in_no_csv:
                if "<!-- /no-csv -->" in stripped:
                    in_no_csv = False
                    stripped = stripped.split("<!-- /no-csv -->", 1)[1]
                else:
                    continue
            stripped = SOURCE.sub("", stripped)
            stripped = re.sub(r"<!--.*?-->", "", stripped)
            stripped = re.sub(r"`[^`]*`", "", stripped)  # code: file names, commands, JSON paths
            for n in NUMBER.finditer(stripped):
                failures.append(f"{page}:{number}: {n.group(0)} in section '{section}' has no CSV source")
    return checked, failures


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("page")
    parser.add_argument("--require-section", action="append", default=[])
    args = parser.parse_args()
    checked, failures = check(args.page, args.require_section)
    for f in failures:
        print(f)
    print(f"{args.page}: {checked} quoted figures checked against their CSV, {len(failures)} problems")
    return 1 if failures or checked == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
