#!/usr/bin/env python3
"""Two suites' results compared metric by metric: the evidence that a change of the code changed no result.

    bench/compare_runs.py BEFORE_FOLDER AFTER_FOLDER [--relative 1e-12]

Compares runs.csv (and steps.csv when both have one) row by row, matched on job_id (and the search key for
steps.csv), or a sweep's sweep.csv and poincare.csv, matched on id (and period_index): the same job ids on both sides, and in every column that is not a measurement of the machine
(times, costs, the load average, the timed runs) the same text, or numbers within --relative of each other
(0: exactly the same text). Prints every difference with its job, column and both values, then a count;
exit 0 when there is none, 1 otherwise, 2 for unreadable input.
"""
import argparse
import csv
import math
import os
import sys

# What the machine measured, not what the simulation computed: differs from run to run by design.
MACHINE_COLUMNS = {"wall_time_s", "cpu_time_s", "wall_time_per_simulated_s", "cpu_time_per_simulated_s", "load_average",
                   "wall_time_min_s", "wall_time_max_s", "cpu_time_min_s", "cpu_time_max_s", "logged_wall_time_s",
                   "logged_cpu_time_s", "probes_wall_time_s"}


def read(path, key_columns):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    table = {}
    for row in rows:
        table[tuple(row[k] for k in key_columns)] = row
    return table, (rows[0].keys() if rows else [])


def same(a, b, relative):
    if a == b:
        return True
    try:
        x, y = float(a), float(b)
    except ValueError:
        return False
    if math.isnan(x) and math.isnan(y):
        return True
    return relative > 0 and abs(x - y) <= relative * max(abs(x), abs(y))


def compare(name, before_folder, after_folder, key_columns, relative):
    before_path, after_path = os.path.join(before_folder, name), os.path.join(after_folder, name)
    if not (os.path.exists(before_path) and os.path.exists(after_path)):
        return [], 0, 0
    before, columns = read(before_path, key_columns)
    after, after_columns = read(after_path, key_columns)
    differences = []
    for column in sorted(set(columns) ^ set(after_columns)):
        differences.append(f"{name}: column {column} only in {'before' if column in columns else 'after'}")
    for key in sorted(before.keys() - after.keys()):
        differences.append(f"{name}: {'/'.join(key)} only before")
    for key in sorted(after.keys() - before.keys()):
        differences.append(f"{name}: {'/'.join(key)} only after")
    compared = 0
    for key in sorted(before.keys() & after.keys()):
        for column in columns:
            if column in MACHINE_COLUMNS or column not in after_columns:
                continue
            compared += 1
            if not same(before[key][column], after[key][column], relative):
                differences.append(f"{name}: {'/'.join(key)}: {column}: {before[key][column]!r} before, "
                                   f"{after[key][column]!r} after")
    return differences, len(before.keys() & after.keys()), compared


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("before")
    parser.add_argument("after")
    parser.add_argument("--relative", type=float, default=0.0, help="allowed relative difference of numbers (0: same text)")
    args = parser.parse_args()
    sweep = all(os.path.exists(os.path.join(folder, "sweep.csv")) for folder in (args.before, args.after))
    table = "sweep.csv" if sweep else "runs.csv"
    for folder in (args.before, args.after):
        if not os.path.exists(os.path.join(folder, table)):
            print(f"compare_runs: {folder}/{table}: no such file (a suite's output folder holds a runs.csv, a sweep's a "
                  "sweep.csv)", file=sys.stderr)
            return 2
    total = []
    tables = ((("sweep.csv", ["id"]), ("poincare.csv", ["id", "period_index"])) if sweep else
              (("runs.csv", ["job_id"]), ("steps.csv", ["group_id"])))
    for name, keys in tables:
        differences, rows, cells = compare(name, args.before, args.after, keys, args.relative)
        total += differences
        if rows:
            print(f"{name}: {rows} rows matched, {cells} values compared (machine measurements left out), "
                  f"{len(differences)} differences")
    for d in total:
        print(d)
    return 1 if total else 0


if __name__ == "__main__":
    sys.exit(main())
