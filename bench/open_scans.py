#!/usr/bin/env python3
"""Adaptive against uniform on open scans: range scans and height fields.

The paper's Rampart is not in the datasets, and every model there but the bunny is
closed. These inputs are open scans reachable here:
  face        pymeshlab's sample range map of a statue's face (tests/sample_meshes/
              rangemaps/face000.ply in its wheel: 166,259 triangles, 22 pieces, 44 holes);
  face_clean  the same after pymeshlab's own cleaning: pieces under 1,000 triangles
              removed, non-manifold edges and vertices repaired, holes up to 100 edges
              closed;
  dem, dem4, dem_full  matplotlib's sample DEM (datasets/make_terrain.py): every second
              post at true scale, the same with heights x4, every post.
Each gets adaptive mode with automatic halting and uniform mode at the count it reached,
then both at fixed counts.

    python3 bench/open_scans.py [--quadsimp build/src/quadsimp] [--python .venv/bin/python]
                                [--models face face_clean dem dem4 dem_full] [--counts 400 1400] [--npz DEM.npz]
"""
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paper_table1 import parse_args, run, table_header  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
MODELS = ["face", "face_clean", "dem", "dem4", "dem_full"]
CLEAN = """
import sys, pymeshlab
ms = pymeshlab.MeshSet()
ms.load_new_mesh(sys.argv[1])
ms.meshing_remove_connected_component_by_face_number(mincomponentsize=1000)
ms.meshing_repair_non_manifold_edges()
ms.meshing_repair_non_manifold_vertices()
ms.meshing_close_holes(maxholesize=100)
ms.save_current_mesh(sys.argv[2], binary=True, save_vertex_color=False, save_vertex_quality=False)
"""


def face_scan(python):
    where = subprocess.run([python, "-c", "import os, pymeshlab; print(os.path.dirname(pymeshlab.__file__))"],
                           check=True, capture_output=True, text=True).stdout.strip()
    return os.path.join(where, "tests", "sample_meshes", "rangemaps", "face000.ply")


def make(model, args, tmp):
    """The input's path, made in tmp where it is not a file already."""
    out = os.path.join(tmp, model + ".ply")
    if model == "face":
        return face_scan(args.python)
    if model == "face_clean":
        subprocess.run([args.python, "-c", CLEAN, face_scan(args.python), out], check=True, capture_output=True)
        return out
    options = {"dem": [], "dem4": ["--exaggeration", "4"], "dem_full": ["--step", "1"]}[model]
    npz = ["--npz", args.npz] if args.npz else []
    subprocess.run([args.python, os.path.join(HERE, "..", "datasets", "make_terrain.py"), out, *options, *npz],
                   check=True, capture_output=True)
    return out


def row(model, how, a, u):
    gain = 100 * (1 - a["rms_e3"] / u["rms_e3"])
    print(f"| {model} | {how} | {a['faces']} / {u['faces']} | {a['rms_e3']:.3f} / {u['rms_e3']:.3f} | {gain:.1f}% "
          f"| {a['hausdorff_e3']:.2f} / {u['hausdorff_e3']:.2f} "
          f"| {a['regular_percent']:.1f} / {u['regular_percent']:.1f} "
          f"| {100 * a['projectability']:.2f} / {100 * u['projectability']:.2f} | {a['seconds']:.1f} |")
    sys.stdout.flush()


def main():
    args = parse_args(__doc__, MODELS, python=True, datasets=False, extra=[
        ("--counts", dict(nargs="*", type=int, default=[400, 1400], help="fixed face counts")),
        ("--npz", dict(help="jacksboro_fault_dem.npz (without it make_terrain.py fetches matplotlib's wheel)"))])
    print(f"Distances sampled with {args.samples} points per surface plus vertices.\n")
    table_header("| input | adaptive run | quads adaptive / uniform | RMS e-3 adaptive / uniform | adaptive lower by "
                 "| Hausdorff e-3 | regular % | projectable % | time s (adaptive) |")
    with tempfile.TemporaryDirectory() as tmp:
        for model in args.models:
            mesh = make(model, args, tmp)
            a = run(args.quadsimp, mesh, 0, args.samples, ["--adaptive", "--auto-halt"])
            row(model, "automatic halting", a, run(args.quadsimp, mesh, a["faces"], args.samples))
            for faces in args.counts:
                a = run(args.quadsimp, mesh, faces, args.samples, ["--adaptive"])
                row(model, f"{faces} quads", a, run(args.quadsimp, mesh, faces, args.samples))


if __name__ == "__main__":
    main()
