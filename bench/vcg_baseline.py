#!/usr/bin/env python3
"""Ours against vcglib's implementation of the same paper, on the same quads.

DESIGN.md names vcglib's quad_diag_collapse.h as the baseline to beat on every model.
`build/bench/qs_vcg_baseline` drives it from our cleaned input and quad conversion (see
its header); both results are then measured by `quadsimp stats`. Uniform runs at the
paper's Table 1 counts, adaptive runs at its Table 2 counts (vcglib's loop fed with our
fitmaps: its own fitmaps.h no longer compiles against Eigen 3.4). vcglib runs twice: on
the file as it is, and scaled to a bounding-box diagonal of 1, since its loop depends on
the model's absolute size (bench/RESULTS.md).

    python3 bench/vcg_baseline.py [--quadsimp build/src/quadsimp] [--datasets ../shared/datasets]
                                  [--samples 300000] [--models bunny gargoyle]
"""
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paper_table1 import PAPER as TABLE1, machine, meshes, parse_args, run, stats, table_header  # noqa: E402
from paper_tables23 import PAPER as TABLE2  # noqa: E402

MODELS = ["moai", "pensatore", "gargoyle", "bunny", "fertility", "armadillo"]


def counts(model):
    """(mode, target) pairs: Table 1's uniform counts, then Table 2's count in both modes."""
    runs = [("uniform", row[0]) for row in TABLE1.get(model, [])]
    if model in TABLE2:
        faces = TABLE2[model][0][0]
        runs += [("uniform", faces), ("adaptive", faces)]
    return runs


def vcglib_run(args, mesh, mode, faces, extra=()):
    """vcglib's result: its own JSON line, plus our stats of it, or why stats refused it."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "vcglib.off")
        cmd = [args.baseline, mesh, out, "--faces", str(faces), *extra] + (["--adaptive"] if mode == "adaptive" else [])
        res = subprocess.run(cmd, capture_output=True, text=True)
        if res.returncode != 0:
            return {"failed": (res.stderr.strip().splitlines() or [f"exit {res.returncode}"])[-1]}
        r = json.loads(res.stdout.strip().splitlines()[-1])
        r.update({k: v for k, v in stats(args.quadsimp, mesh, out, args.samples).items() if k != "faces"})
        return r


def defects(r):
    """What made vcglib's result not a manifold pure quad mesh (none for ours)."""
    found = [(r.get("nonmanifold_vertices", 0), "non-manifold vertices (split to measure)"),
             (r.get("not_quads", 0), "faces that are not quads"),
             (r.get("repeated_vertex", 0), "quads repeating a vertex"),
             (r.get("edges_over_two_faces", 0), "edges in 3+ quads"),
             (r.get("edges_same_direction", 0), "edges twice in one direction")]
    text = ", ".join(f"{n} {what}" for n, what in found if n)
    return f"; {text}" if text else ""


def cells(r):
    if "failed" in r:
        return f"failed: {r['failed']} |" + " |" * 7
    if "not_measured" in r:
        return (f"{r['faces']} | {r['seconds']:.2f} | not measured: `quadsimp stats` refuses it ({r['not_measured']}) "
                f"| | | | | -{defects(r)} |")
    return (f"{r['faces']} | {r['seconds']:.2f} | {r['max_valence']} | {r['regular_percent']:.1f} "
            f"| {r['homeometry_min']:.2f}-{r['homeometry_max']:.2f} | {r['hausdorff_e3']:.2f} | {r['rms_e3']:.2f} "
            f"| {r['nonconvex_faces']} / {r['flipped_faces']} / {r['folded_faces']}{defects(r)} |")


def main():
    args = parse_args(__doc__, MODELS, samples=300000)
    args.baseline = os.path.join(os.path.dirname(args.quadsimp), "..", "bench", "qs_vcg_baseline")
    print(f"Machine: {machine()}; both simplifiers single-threaded (our fitmaps use both cores). Distances "
          f"sampled with {args.samples} points per surface plus vertices.\n")
    columns = table_header("| model | mode | target | simplifier | #faces | time s | val max | reg % | homeometry "
                           "| Hausdorff e-3 | RMS e-3 | non-convex / flipped / folded |")
    for model, mesh in meshes(args, columns):
        for mode, faces in counts(model):
            extra = ["--adaptive"] if mode == "adaptive" else []
            ours = run(args.quadsimp, mesh, faces, args.samples, extra)
            if ours["input_faces"] <= faces:
                continue  # Table 1's larger counts are above what these inputs convert to
            print(f"| {model} | {mode} | {faces} | vcglib | {cells(vcglib_run(args, mesh, mode, faces))}")
            print(f"| {model} | {mode} | {faces} | vcglib, diagonal 1 "
                  f"| {cells(vcglib_run(args, mesh, mode, faces, ['--unit-diagonal']))}")
            print(f"| {model} | {mode} | {faces} | quadsimp | {cells(ours)}")
            sys.stdout.flush()


if __name__ == "__main__":
    main()
