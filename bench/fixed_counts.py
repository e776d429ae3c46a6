#!/usr/bin/env python3
"""Adaptive against uniform at twelve fixed face counts (bunny, gargoyle, armadillo).

A run with automatic halting is one draw: where it stops, and the uniform run at that
count, move with rounding and with any change to the loop, and one uniform run's RMS can
jump by a fifth between counts 1% apart. Four counts per model, far apart and the same
for every version of the code, move much less; bench/RESULTS.md judges changes to the
adaptive mode's keys and sizes on their mean gain and regular share.

    python3 bench/fixed_counts.py [--quadsimp build/src/quadsimp] [--datasets ../shared/datasets] [--samples 300000]
                                  [--adaptive-args="--m-factor 0.8"] [--both-args="--keep-tips"]
"""
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paper_table1 import meshes, parse_args, run, table_header  # noqa: E402

COUNTS = {"bunny": (600, 900, 1300, 2000), "gargoyle": (800, 1100, 1500, 2000), "armadillo": (1000, 1500, 2000, 3000)}


def main():
    args = parse_args(__doc__, list(COUNTS), samples=300000, adaptive_args=True, both_args=True)
    print(f"Distances sampled with {args.samples} points per surface plus vertices.\n")
    columns = table_header("| model | quads | uniform RMS e-3 | adaptive RMS e-3 | adaptive lower by | adaptive regular % |")
    gains, regular, per_model = [], [], {}
    for model, mesh in meshes(args, columns):
        for faces in COUNTS[model]:
            u = run(args.quadsimp, mesh, faces, args.samples, args.both_args)
            a = run(args.quadsimp, mesh, faces, args.samples, ["--adaptive", *args.adaptive_args, *args.both_args])
            g = 100 * (1 - a["rms_e3"] / u["rms_e3"])
            gains.append(g)
            regular.append(a["regular_percent"])
            per_model.setdefault(model, []).append(g)
            print(f"| {model} | {faces} | {u['rms_e3']:.4f} | {a['rms_e3']:.4f} | {g:.1f}% | {a['regular_percent']:.1f} |")
            sys.stdout.flush()
    if gains:
        models = ", ".join(f"{m} {statistics.mean(g):.1f}%" for m, g in per_model.items())
        print(f"\nMean gain {statistics.mean(gains):.1f}% ({models}); adaptive regular {statistics.mean(regular):.1f}%.")


if __name__ == "__main__":
    main()
