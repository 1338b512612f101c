#!/usr/bin/env python3
"""Markdown tables of criterion results.

Reads <target>/criterion/... (<target> = $CARGO_TARGET_DIR, else target/).

    python3 scripts/bench-table.py GROUP [GROUP ...]
        Columns are the groups, rows the parameter (valence); cells are the
        mean time per element in ns (the benches set Throughput::Elements:
        output points, or patches), "—" where a group has no such row.

    python3 scripts/bench-table.py eg-vs-cc [BASELINE]
        benches/eg_vs_cc.rs: per valence and type, one EG step, one CcCap
        step and subdiv-kernels' Catmull-Clark step of the same c-net (both
        of its paths), and the ratios EG / Catmull-Clark, all from one run
        (criterion's "new" results, or a --save-baseline BASELINE).

    python3 scripts/bench-table.py c2ps-vs-cc [BASELINE]
        benches/c2ps_step.rs: per output valence, capdiv's C²PS step per
        output point (f64, f32) against subdiv-kernels' Catmull-Clark
        refinement of the same polar net per output vertex, from one run.

    python3 scripts/bench-table.py header TITLE
        The header line every section of docs/benchmarks.md starts with:
        "## TITLE — <CPU model>, <cores> cores, rustc <version>, load
        average <L>, <date>". L is $BENCH_LOAD when set (the range measured
        while the benchmark ran), else the current 1-minute load average;
        the date is today's (UTC).
"""
import datetime
import json
import os
import pathlib
import subprocess
import sys

repo = pathlib.Path(__file__).resolve().parent.parent
root = pathlib.Path(os.environ.get("CARGO_TARGET_DIR", repo / "target")) / "criterion"


def result(path, baseline="new"):
    """(mean ns, elements) of one benchmark directory, or None."""
    d = path / baseline
    if not (d / "estimates.json").exists():
        return None
    bench = json.loads((d / "benchmark.json").read_text())
    est = json.loads((d / "estimates.json").read_text())
    thr = bench.get("throughput") or {}
    elems = thr.get("Elements") or thr.get("elements") or 1
    return est["mean"]["point_estimate"], elems


def groups_table(groups):
    rows = {}
    for g in groups:
        for d in (root / g).glob("*/new"):
            mean, elems = result(d.parent)
            rows.setdefault(int(d.parent.name), {})[g] = mean / elems
    print("| n | " + " | ".join(f"{g} (ns/elem)" for g in groups) + " |")
    print("|---:|" + "---:|" * len(groups))
    for n in sorted(rows):
        cells = [f"{rows[n][g]:.2f}" if g in rows[n] else "—" for g in groups]
        print(f"| {n} | " + " | ".join(cells) + " |")


def eg_vs_cc(baseline):
    kinds = ["eg_step", "eg_fourier_step", "cc_cap_step", "sk_cc_step", "sk_cc_step_rows"]
    print(
        "| n | type | EG step (ns) | EG `step_fourier` (ns) | CcCap step (ns)"
        " | subdiv-kernels `interpolate` (ns) | subdiv-kernels `interpolate_rows` (ns)"
        " | EG / CcCap | Fourier / CcCap | EG / subdiv-kernels rows"
        " | Fourier / subdiv-kernels rows |"
    )
    print("|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    worst = 0.0
    for n in (3, 5):
        for prec in ("f64", "f32"):
            t = {}
            for k in kinds:
                r = result(root / f"eg_vs_cc_{prec}" / k / str(n), baseline)
                if r:
                    t[k] = r[0]
            if len(t) < len(kinds):
                continue
            ratios = [
                t["eg_step"] / t["cc_cap_step"],
                t["eg_fourier_step"] / t["cc_cap_step"],
                t["eg_step"] / t["sk_cc_step_rows"],
                t["eg_fourier_step"] / t["sk_cc_step_rows"],
            ]
            worst = max(worst, ratios[1], ratios[3])
            cells = [f"{t[k]:.0f}" for k in kinds] + [f"{r:.2f}" for r in ratios]
            print(f"| {n} | {prec} | " + " | ".join(cells) + " |")
    print(f"\nworst ratio EG (step_fourier) / Catmull-Clark: {worst:.2f} (goal <= 2)")


def c2ps_vs_cc(baseline):
    cols = [
        ("c2ps_step_f64", "capdiv f64 (ns/point)"),
        ("c2ps_step_f32", "capdiv f32 (ns/point)"),
        ("c2ps_step_sk_cc_f64", "subdiv-kernels CC f64 (ns/vertex)"),
        ("c2ps_step_sk_cc_f32", "subdiv-kernels CC f32 (ns/vertex)"),
    ]
    rows = {}
    for g, _ in cols:
        for d in (root / g).glob("*"):
            r = result(d, baseline)
            if r:
                rows.setdefault(int(d.name), {})[g] = r[0] / r[1]
    print("| output valence n | " + " | ".join(h for _, h in cols) + " |")
    print("|---:|" + "---:|" * len(cols))
    for n in sorted(rows):
        cells = [f"{rows[n][g]:.2f}" if g in rows[n] else "—" for g, _ in cols]
        print(f"| {n} | " + " | ".join(cells) + " |")


def header(title):
    model = "unknown CPU"
    try:
        for line in pathlib.Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    try:
        rustc = subprocess.run(
            ["rustc", "--version"], capture_output=True, text=True, cwd=repo
        ).stdout.split()[1]
    except (OSError, IndexError):
        rustc = "?"
    load = os.environ.get("BENCH_LOAD") or f"{os.getloadavg()[0]:.1f}"
    date = datetime.datetime.now(datetime.timezone.utc).date().isoformat()
    print(f"## {title} — {model}, {os.cpu_count()} cores, rustc {rustc}, load average {load}, {date}")


args = sys.argv[1:]
if args and args[0] == "header":
    header(" ".join(args[1:]))
elif args and args[0] == "eg-vs-cc":
    eg_vs_cc(args[1] if len(args) > 1 else "new")
elif args and args[0] == "c2ps-vs-cc":
    c2ps_vs_cc(args[1] if len(args) > 1 else "new")
else:
    groups_table(args)
