#!/usr/bin/env python3
"""Markdown table of criterion results: time per element (ns) for each group.

Reads target/criterion/<group>/<param>/new/{estimates,benchmark}.json, where
the benches set Throughput::Elements (output points, or patches). Usage:
    python3 scripts/bench-table.py GROUP [GROUP ...]
Columns are the groups, rows the parameter (valence); cells are the mean time
per element in ns, "—" where a group has no such row.
"""
import json
import pathlib
import sys

root = pathlib.Path(__file__).resolve().parent.parent / "target" / "criterion"
groups = sys.argv[1:]
rows = {}
for g in groups:
    for d in (root / g).glob("*/new"):
        bench = json.loads((d / "benchmark.json").read_text())
        est = json.loads((d / "estimates.json").read_text())
        thr = bench.get("throughput") or {}
        elems = thr.get("Elements") or thr.get("elements") or 1
        rows.setdefault(int(d.parent.name), {})[g] = est["mean"]["point_estimate"] / elems
print("| n | " + " | ".join(f"{g} (ns/elem)" for g in groups) + " |")
print("|---:|" + "---:|" * len(groups))
for n in sorted(rows):
    cells = [f"{rows[n][g]:.2f}" if g in rows[n] else "—" for g in groups]
    print(f"| {n} | " + " | ".join(cells) + " |")
