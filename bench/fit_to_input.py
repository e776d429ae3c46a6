#!/usr/bin/env python3
"""What `--fit-to-input` buys: the paper's Table 1 rows (uniform) and the adaptive runs
with automatic halting, each without and with the fit, on ../shared/datasets.

Prints one markdown row per run: distances (symmetric RMS and Hausdorff, and the RMS of
each direction), time, and the faces the quality report flags (non-convex, flipped against the input,
bent past 90 degrees), before -> after.

    python3 bench/fit_to_input.py [--quadsimp build/src/quadsimp] [--datasets ../shared/datasets]
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paper_table1 import PAPER, dataset, machine, parse_args, run, table_header  # noqa: E402

ADAPTIVE = ["moai", "pensatore", "gargoyle", "bunny", "armadillo"]


def change(a, b):
    return f"{100 * (b / a - 1):+.0f}%" if a > 0 else "-"


def main():
    args = parse_args(__doc__, list(PAPER) + ["armadillo"])
    print(f"Machine: {machine()}; distances sampled with {args.samples} points per surface plus vertices.\n")
    table_header("| model | mode | #faces | RMS e-3 | Hausdorff e-3 | RMS in->out e-3 | RMS out->in e-3 | time s "
                 "| non-convex / flipped / folded |")
    runs = [(m, "uniform", row[0]) for m in args.models if m in PAPER for row in PAPER[m]]
    runs += [(m, "adaptive", 0) for m in ADAPTIVE if m in args.models]
    gains = []
    for model, mode, faces in runs:
        mesh = dataset(args, model)
        if not mesh:
            continue
        extra = ["--adaptive", "--auto-halt"] if mode == "adaptive" else []
        a = run(args.quadsimp, mesh, faces, args.samples, extra)
        if mode == "uniform" and a["input_faces"] <= faces:
            continue
        b = run(args.quadsimp, mesh, faces, args.samples, extra + ["--fit-to-input"])
        gains.append(b["rms_e3"] / a["rms_e3"] - 1)

        def pair(key, digits=2):
            return f"{a[key]:.{digits}f} -> {b[key]:.{digits}f} ({change(a[key], b[key])})"

        print(f"| {model} | {mode} | {b['faces']} | {pair('rms_e3')} | {pair('hausdorff_e3')} "
              f"| {pair('rms_from_ref_e3')} | {pair('rms_to_ref_e3')} | {a['seconds']:.2f} -> {b['seconds']:.2f} "
              f"| {a['nonconvex_faces']} / {a['flipped_faces']} / {a['folded_faces']} "
              f"-> {b['nonconvex_faces']} / {b['flipped_faces']} / {b['folded_faces']} |")
        sys.stdout.flush()
    if gains:
        print(f"\nRMS change over {len(gains)} runs: mean {100 * sum(gains) / len(gains):+.1f}%, "
              f"from {100 * min(gains):+.1f}% to {100 * max(gains):+.1f}%")


if __name__ == "__main__":
    main()
