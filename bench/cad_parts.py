#!/usr/bin/env python3
"""Adaptive against uniform on the CAD parts of creases.py (no creases kept).

The datasets are scans; these parts (a cube, a cylinder, a dodecahedron, a block with a
hole and one with a boss, remeshed into a CAD export's irregular triangles: creases.py
says how they are made) are flat-sided, where the fitmaps behave otherwise: F_S is near
zero away from the edges (the block with a hole: its 20% quantile 1/650 of its median),
and across a right-angled edge no normal turns away from a fitted plane, so F_M does not
fall there. Each part gets adaptive mode with automatic halting and at each count, and
uniform mode at the count each adaptive run reached.

    python3 bench/cad_parts.py [--quadsimp build/src/quadsimp] [--python .venv/bin/python]
                               [--models cube cylinder dodecahedron block_hole block_boss] [--counts 300 1000]
"""
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from creases import MODELS, make_part  # noqa: E402
from paper_table1 import parse_args, run, table_header  # noqa: E402


def main():
    args = parse_args(__doc__, MODELS, samples=200000, python=True, datasets=False,
                      extra=[("--counts", {"nargs": "*", "type": int, "default": [300, 1000]})])
    print("Distances in 1e-3 of the bounding-box diagonal.\n")
    table_header("| part | adaptive run | quads | adaptive RMS, regular % | uniform RMS, regular % "
                 "| adaptive closer by | adaptive projectable % |")
    with tempfile.TemporaryDirectory() as tmp:
        for model in args.models:
            mesh = os.path.join(tmp, model + ".ply")
            make_part(args.python, model, mesh)
            runs = [("automatic halting", 0, ["--auto-halt"])] + [(f"{n} quads", n, []) for n in args.counts]
            for label, faces, extra in runs:
                a = run(args.quadsimp, mesh, faces, args.samples, ["--adaptive", *extra])
                u = run(args.quadsimp, mesh, a["faces"], args.samples)
                print(f"| {model} | {label} | {a['faces']} | {a['rms_e3']:.3f}, {a['regular_percent']:.1f} | "
                      f"{u['rms_e3']:.3f}, {u['regular_percent']:.1f} | {100 * (1 - a['rms_e3'] / u['rms_e3']):.1f}% | "
                      f"{100 * a['projectability']:.2f} |", flush=True)


if __name__ == "__main__":
    main()
