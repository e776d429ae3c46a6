#!/usr/bin/env python3
"""Ours against what a MeshLab user would do without us: quadric edge collapse decimation
to twice the quads asked for, then MeshLab's smart triangle pairing (both with MeshLab's
default settings, in pymeshlab). At the paper's Table 1 counts on ../shared/datasets, with
ours in uniform and adaptive mode, each without and with `--fit-to-input`.

Every result is measured by `quadsimp stats` (the other tables' metrics). The MeshLab
time is decimation and pairing only; ours is the CLI's, loading and conversion included.

    python3 bench/meshlab_quadric.py [--quadsimp build/src/quadsimp] [--python .venv/bin/python]
"""
import os
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paper_table1 import PAPER, machine, meshes, parse_args, run, stats, table_header  # noqa: E402

MESHLAB = """
import sys, time, pymeshlab
ms = pymeshlab.MeshSet()
ms.load_new_mesh(sys.argv[1])
start = time.perf_counter()
ms.meshing_decimation_quadric_edge_collapse(targetfacenum=2 * int(sys.argv[3]))
ms.meshing_tri_to_quad_by_smart_triangle_pairing()
print(time.perf_counter() - start)
ms.save_current_mesh(sys.argv[2], save_face_flag=True, binary=True)
"""

OURS = [("ours uniform", []), ("ours uniform, fit", ["--fit-to-input"]),
        ("ours adaptive", ["--adaptive"]), ("ours adaptive, fit", ["--adaptive", "--fit-to-input"])]


def meshlab_run(args, mesh, faces):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "quads.ply")
        res = subprocess.run([args.python, "-c", MESHLAB, mesh, out, str(faces)], capture_output=True, text=True)
        if res.returncode != 0:
            raise RuntimeError(f"pymeshlab failed on {mesh}: {res.stderr.strip()}")
        r = stats(args.quadsimp, mesh, out, args.samples)
        r["seconds"] = float(res.stdout.split()[0])
        return r


def main():
    args = parse_args(__doc__, [m for m in PAPER if m != "rampart"], samples=300000, python=True)
    print(f"Machine: {machine()}; distances sampled with {args.samples} points per surface plus vertices.\n")
    columns = table_header("| model | #faces | method | reg % | val max | homeo min-max | non-convex / flipped / folded "
                           "| RMS e-3 | Hausdorff e-3 | time s |")
    ratios = {name: [] for name, _ in OURS}
    for model, mesh in meshes(args, columns):
        for faces, *_ in PAPER[model]:
            ours = [(OURS[0][0], run(args.quadsimp, mesh, faces, args.samples, OURS[0][1]))]
            if ours[0][1]["input_faces"] <= faces:
                continue  # above what the input converts to
            ours += [(name, run(args.quadsimp, mesh, faces, args.samples, extra)) for name, extra in OURS[1:]]
            rows = [("MeshLab: quadric + pairing", meshlab_run(args, mesh, faces))] + ours
            for name, r in rows:
                if "not_measured" in r:
                    print(f"| {model} | {faces} | {name} | not measured: {r['not_measured']} |" + " |" * (columns - 4))
                    continue
                print(f"| {model} | {r['faces']} | {name} | {r['regular_percent']:.1f} | {r['max_valence']} "
                      f"| {r['homeometry_min']:.2f}-{r['homeometry_max']:.2f} "
                      f"| {r['nonconvex_faces']} / {r['flipped_faces']} / {r['folded_faces']} "
                      f"| {r['rms_e3']:.2f} | {r['hausdorff_e3']:.2f} | {r['seconds']:.2f} |")
                if name in ratios and "rms_e3" in rows[0][1]:
                    ratios[name].append(r["rms_e3"] / rows[0][1]["rms_e3"])
            sys.stdout.flush()
    print()
    for name, values in ratios.items():
        if values:
            print(f"{name}: RMS {statistics.median(values):.2f} times MeshLab's (median over {len(values)} rows; "
                  f"{min(values):.2f} to {max(values):.2f})")


if __name__ == "__main__":
    main()
