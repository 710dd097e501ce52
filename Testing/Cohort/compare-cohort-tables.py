#!/usr/bin/env python3
"""Usage: compare-cohort-tables.py A B

Fails unless the merged tables of the cohort folders A and B (table.json and
table.csv, as `vimlop cohort merge` writes them) are identical once the
columns both list as volatile (times, hosts, thread counts, Slurm task ids)
are taken out: the same rows must give the same figures and provenance
wherever and however they ran. Prints the first difference.
"""
import csv
import io
import json
import sys


def load(folder):
    with open(f"{folder}/table.json", encoding="utf-8") as f:
        table = json.load(f)
    with open(f"{folder}/table.csv", encoding="utf-8", newline="") as f:
        text = f.read()
    return table, text


def steady_csv(text, volatile):
    rows = list(csv.reader(io.StringIO(text)))
    keep = [i for i, name in enumerate(rows[0]) if name not in volatile]
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    for row in rows:
        writer.writerow([row[i] for i in keep])
    return out.getvalue()


def main():
    (a_table, a_csv), (b_table, b_csv) = load(sys.argv[1]), load(sys.argv[2])
    volatile = set(a_table["volatile_columns"]) | set(b_table["volatile_columns"])
    a_rows = [{k: v for k, v in r.items() if k not in volatile} for r in a_table["rows"]]
    b_rows = [{k: v for k, v in r.items() if k not in volatile} for r in b_table["rows"]]
    for a, b in zip(a_rows, b_rows):
        for key in sorted(set(a) | set(b)):
            if a.get(key) != b.get(key):
                sys.exit(f"row '{a.get('id')}', column '{key}': {a.get(key)!r} against {b.get(key)!r}")
    if len(a_rows) != len(b_rows):
        sys.exit(f"{len(a_rows)} rows against {len(b_rows)}")
    if steady_csv(a_csv, volatile) != steady_csv(b_csv, volatile):
        sys.exit("table.csv differs outside the volatile columns")
    print(f"identical: {len(a_rows)} rows, {len(a_table['columns']) - len(volatile)} columns "
          f"outside the {len(volatile)} volatile ones")


if __name__ == "__main__":
    main()
