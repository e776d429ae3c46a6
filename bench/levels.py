#!/usr/bin/env python3
"""Levels of detail in one run (`simplify --faces 5000,2000,1000,500`) against separate
runs to the same counts, in both modes, on ../shared/datasets.

Prints one markdown row per level after the first (the first is a separate run's, byte for
byte): symmetric RMS, regular share, homeometry and folded quads, level against separate
run; then, per mode, the RMS change's median and range, the folded quads, and the time of
the one run (through its last level, sampling left out) against the separate runs' sum.

    python3 bench/levels.py [--quadsimp build/src/quadsimp] [--datasets ../shared/datasets]
"""
import json
import os
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paper_table1 import PAPER, dataset, machine, parse_args, run, table_header  # noqa: E402

LEVELS = {"uniform": [5000, 2000, 1000, 500], "adaptive": [2000, 1000, 500]}


def levels(quadsimp, mesh, counts, samples, extra):
    """The JSON line of each level of one run, most quads first."""
    with tempfile.TemporaryDirectory() as tmp:
        cmd = [quadsimp, "simplify", mesh, os.path.join(tmp, "out.ply"), "--json", "-q", "--samples", str(samples),
               "--faces", ",".join(map(str, counts)), *extra]
        res = subprocess.run(cmd, capture_output=True, text=True)
        if res.returncode != 0:
            raise RuntimeError(f"{' '.join(cmd)} failed: {res.stderr.strip()}")
        return [json.loads(line) for line in res.stdout.splitlines() if line.startswith("{")]


def main():
    args = parse_args(__doc__, list(PAPER) + ["armadillo"], samples=200000)
    print(f"Machine: {machine()}; distances sampled with {args.samples} points per surface plus vertices.\n")
    table_header("| model | mode | quads (level / separate) | RMS e-3: level / separate | change "
                 "| regular %: level / separate | homeometry: level / separate | folded: level / separate |")
    summary = {}
    for mode, counts in LEVELS.items():
        extra = ["--adaptive"] if mode == "adaptive" else []
        changes, folded, times = [], [0, 0], [0.0, 0.0]
        for model in args.models:
            mesh = dataset(args, model)
            if not mesh:
                continue
            chain = levels(args.quadsimp, mesh, counts, args.samples, extra)
            times[0] += chain[-1]["seconds"]
            for count, a in zip(counts, chain):
                b = run(args.quadsimp, mesh, count, args.samples, extra)
                times[1] += b["seconds"]
                if count == counts[0]:
                    continue
                changes.append(a["rms_e3"] / b["rms_e3"] - 1)
                folded[0] += a["folded_faces"]
                folded[1] += b["folded_faces"]
                print(f"| {model} | {mode} | {a['faces']} / {b['faces']} | {a['rms_e3']:.3f} / {b['rms_e3']:.3f} "
                      f"| {100 * changes[-1]:+.1f}% | {a['regular_percent']:.1f} / {b['regular_percent']:.1f} "
                      f"| {a['homeometry_min']:.2f}-{a['homeometry_max']:.2f} / "
                      f"{b['homeometry_min']:.2f}-{b['homeometry_max']:.2f} "
                      f"| {a['folded_faces']} / {b['folded_faces']} |")
                sys.stdout.flush()
        summary[mode] = changes, folded, times
    print()
    for mode, (changes, folded, times) in summary.items():
        if not changes:
            continue
        print(f"- {mode}, levels {','.join(map(str, LEVELS[mode]))}: RMS against separate runs median "
              f"{100 * statistics.median(changes):+.1f}%, from {100 * min(changes):+.1f}% to "
              f"{100 * max(changes):+.1f}% ({len(changes)} levels); folded quads {folded[0]} against {folded[1]}; "
              f"time {times[0]:.1f} s in one run per model against {times[1]:.1f} s in separate runs")


if __name__ == "__main__":
    main()
