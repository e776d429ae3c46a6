#!/usr/bin/env python3
"""Creases kept (--crease-angle) against rounded off, on CAD parts.

The datasets are scans, with no sharp edge to keep. These parts are made with MeshLab's own
filters (pymeshlab): its cube, a cylinder (its cone with equal radii), its dodecahedron, a
block with a round hole through it (boolean difference) and a block with a round boss on
top (boolean union), each remeshed isotropically ("Remeshing: Isotropic Explicit
Remeshing", target length 0.8% of the diagonal, feature angle 30, 8 iterations) into the
irregular triangles of a CAD export. Each is simplified in uniform mode to each count and
in adaptive mode with automatic halting, without creases and with them.

    python3 bench/creases.py [--quadsimp build/src/quadsimp] [--python .venv/bin/python]
                             [--models cube cylinder dodecahedron block_hole block_boss]
                             [--counts 300 1000] [--angle 30]
"""
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paper_table1 import parse_args, run, table_header  # noqa: E402

MODELS = ["cube", "cylinder", "dodecahedron", "block_hole", "block_boss"]
MAKE = """
import sys, pymeshlab
model, out = sys.argv[1], sys.argv[2]
ms = pymeshlab.MeshSet()
if model == "cube":
    ms.create_cube(size=2.0)
elif model == "cylinder":
    ms.create_cone(r0=1.0, r1=1.0, h=2.0, subdiv=96)
elif model == "dodecahedron":
    ms.create_dodecahedron()
elif model == "block_hole":
    ms.create_cube(size=2.0)
    ms.create_cone(r0=0.5, r1=0.5, h=4.0, subdiv=64)
    ms.generate_boolean_difference(first_mesh=0, second_mesh=1)
elif model == "block_boss":
    ms.create_cube(size=2.0)
    ms.create_cone(r0=0.6, r1=0.6, h=3.0, subdiv=64)
    ms.generate_boolean_union(first_mesh=0, second_mesh=1)
ms.meshing_isotropic_explicit_remeshing(targetlen=pymeshlab.PercentageValue(0.8), featuredeg=30, iterations=8)
ms.save_current_mesh(out, binary=True)
print(ms.current_mesh().face_number())
"""


def make_part(python, model, path):
    """Writes CAD part `model` to `path` (binary PLY) with pymeshlab; returns its triangle count."""
    out = subprocess.run([python, "-c", MAKE, model, path], check=True, capture_output=True, text=True)
    return int(out.stdout.strip().splitlines()[-1])


def cells(j):
    return (f"{j['rms_e3']:.3f} | {j['hausdorff_e3']:.2f} | {j['regular_percent']:.1f} | "
            f"{j['homeometry_min']:.2f} | {j['nonconvex_faces'] + j['flipped_faces'] + j['folded_faces']}")


def main():
    args = parse_args(__doc__, MODELS, samples=200000, python=True, datasets=False,
                      extra=[("--counts", {"nargs": "*", "type": int, "default": [300, 1000]}),
                             ("--angle", {"type": float, "default": 30.0})])
    print(f"Crease angle {args.angle:g}; distances in 1e-3 of the bounding-box diagonal; bad = non-convex, "
          "flipped and folded quads.\n")
    table_header("| part | triangles | run | quads | RMS | Hausdorff | reg % | hmin | bad | quads, creases | RMS | "
                 "Hausdorff | reg % | hmin | bad | crease vertices | s, creases |")
    with tempfile.TemporaryDirectory() as tmp:
        for model in args.models:
            mesh = os.path.join(tmp, model + ".ply")
            triangles = make_part(args.python, model, mesh)
            runs = [(f"{n} quads", n, []) for n in args.counts]
            runs.append(("auto-halt", 0, ["--adaptive", "--auto-halt"]))
            for label, faces, extra in runs:
                plain = run(args.quadsimp, mesh, faces, args.samples, extra)
                kept = run(args.quadsimp, mesh, faces, args.samples, [*extra, "--crease-angle", f"{args.angle:g}"])
                print(f"| {model} | {triangles} | {label} | {plain['faces']} | {cells(plain)} | {kept['faces']} | "
                      f"{cells(kept)} | {kept['crease_vertices']} | {kept['seconds']:.2f} |", flush=True)


if __name__ == "__main__":
    main()
