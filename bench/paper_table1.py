#!/usr/bin/env python3
"""Reproduces the paper's Table 1 (uniform simplification) on ../shared/datasets.

Runs `quadsimp simplify --faces N --json` at the paper's face counts and prints a
markdown table with the paper's columns beside the paper's own numbers.

    python3 bench/paper_table1.py [--quadsimp build/src/quadsimp] [--datasets ../shared/datasets]
"""
import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile

# model -> [(faces, paper time s, paper val max, paper reg %, hmin, hmax, dist e-3)]
PAPER = {
    "moai": [(8200, 13.38, 6, 71, 0.34, 1.87, 0.4), (3300, 4.16, 5, 71, 0.53, 1.77, 0.5),
             (600, 2.31, 5, 72, 0.59, 1.71, 3.0)],
    "pensatore": [(15000, 33.97, 6, 71, 0.43, 1.82, 0.6), (10000, 5.31, 5, 71, 0.43, 1.79, 0.8),
                  (5000, 5.23, 5, 72, 0.55, 1.76, 1.3), (2000, 3.11, 5, 72, 0.44, 1.85, 2.4),
                  (1000, 1.02, 5, 72, 0.44, 1.67, 3.7)],
    "gargoyle": [(11000, 15.01, 7, 70, 0.44, 2.84, 0.8), (4000, 8.05, 5, 73, 0.54, 1.76, 1.8),
                 (2000, 2.31, 5, 72, 0.58, 1.81, 3.1)],
    "bunny": [(11000, 11.41, 8, 75, 0.48, 2.64, 0.3), (5000, 6.43, 5, 72, 0.44, 1.89, 0.7),
              (3000, 2.16, 5, 72, 0.58, 1.76, 1.2)],
    "fertility": [(22000, 6.39, 7, 73, 0.39, 2.13, 0.1), (5000, 18.53, 5, 72, 0.51, 1.88, 0.7),
                  (3300, 1.98, 5, 72, 0.54, 1.75, 1.0), (2000, 1.50, 5, 72, 0.57, 1.69, 1.6)],
    "rampart": [(20000, 23.91, 7, 68, 0.23, 10.49, 0.4), (10000, 13.01, 7, 71, 0.52, 7.45, 0.7)],
}


def run(quadsimp, mesh, faces, samples, extra=()):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out.ply")
        cmd = [quadsimp, "simplify", mesh, out, "--json", "-q", "--samples", str(samples), *extra]
        if faces:
            cmd += ["--faces", str(faces)]
        res = subprocess.run(cmd, capture_output=True, text=True)
        if res.returncode != 0:
            raise RuntimeError(f"{' '.join(cmd)} failed: {res.stderr.strip()}")
        return json.loads(res.stdout.strip().splitlines()[-1])


def stats(quadsimp, mesh, quads, samples):
    """`quadsimp stats` of another simplifier's result against its input: the JSON, or
    {"not_measured": why} when stats refuses the file (not a valid pure quad mesh)."""
    res = subprocess.run([quadsimp, "stats", mesh, quads, "--json", "--samples", str(samples)],
                         capture_output=True, text=True)
    if res.returncode != 0:
        return {"not_measured": res.stderr.strip().split(": ", 2)[-1]}
    return json.loads(res.stdout)


def table_header(header):
    """Prints a markdown table's header row and the rule under it; returns its column count."""
    columns = header.count("|") - 1
    print(header)
    print("|" + "---|" * columns)
    return columns


def dataset(args, model):
    """The model's PLY in the datasets folder, or None when it is not there."""
    mesh = os.path.join(args.datasets, model + ".ply")
    return mesh if os.path.exists(mesh) else None


def meshes(args, columns=0):
    """(model, PLY) for each of args.models in the datasets folder. A model that is not
    there gets a table row saying so when the table's column count is given."""
    for model in args.models:
        mesh = dataset(args, model)
        if mesh:
            yield model, mesh
        elif columns:
            print(f"| {model} | not in {args.datasets} |" + " |" * (columns - 2))


def machine():
    cpu = "unknown CPU"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return f"{cpu}, {os.cpu_count()} cores, {platform.system()} {platform.release()}"


def parse_args(doc, models, draws=0, samples=1000000, adaptive_args=False, both_args=False, python=False, extra=(),
               datasets=True):
    """The options the bench scripts take (--draws: Tables 2 and 3 only; --adaptive-args:
    the fixed counts only; --both-args: Tables 2 and 3 and the fixed counts; --python, a
    Python with pymeshlab: the MeshLab comparison and
    the open scans; extra: (flag, argparse keywords) of one script's own; datasets=False
    for a script that makes its inputs instead of reading the shared datasets)."""
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quadsimp", default=os.path.join(here, "..", "build", "src", "quadsimp"))
    if datasets:
        ap.add_argument("--datasets", default=os.path.join(here, "..", "..", "shared", "datasets"))
    ap.add_argument("--samples", type=int, default=samples, help="distance samples per surface")
    ap.add_argument("--models", nargs="*", default=models)
    if draws:
        ap.add_argument("--draws", type=int, default=draws, help="automatic halting: the file and re-rounded copies")
    if python:
        ap.add_argument("--python", default=os.path.join(here, "..", ".venv", "bin", "python"),
                        help="a Python with pymeshlab (scripts/setup.sh makes .venv)")
    if adaptive_args:
        ap.add_argument("--adaptive-args", default="", type=str.split,
                        help='more options for the adaptive runs, e.g. --adaptive-args="--m-factor 0.8"')
    if both_args:
        ap.add_argument("--both-args", default="", type=str.split,
                        help='more options for the runs of both modes, e.g. --both-args="--keep-tips"')
    for flag, keywords in extra:
        ap.add_argument(flag, **keywords)
    return ap.parse_args()


def main():
    args = parse_args(__doc__, list(PAPER))

    print(f"Machine: {machine()}; single-threaded simplification, distances sampled with "
          f"{args.samples} points per surface plus vertices.\n")
    columns = table_header("| model | input quads | #faces | time s (paper) | val max (paper) | reg % (paper) "
                           "| reg % val-4 only | homeo min (paper) | homeo max (paper) | Hausdorff e-3 | RMS e-3 "
                           "| mean out->in e-3 (paper Dist) | non-convex / flipped / folded |")
    for model, mesh in meshes(args, columns):
        for faces, t, val, reg, hmin, hmax, dist in PAPER[model]:
            r = run(args.quadsimp, mesh, faces, args.samples)
            if r["input_faces"] <= faces:
                print(f"| {model} | {r['input_faces']} | {faces} | input has fewer quads than this row | | | | | | | | | |")
                continue
            print(f"| {model} | {r['input_faces']} | {r['faces']} | {r['seconds']:.2f} ({t}) | {r['max_valence']} ({val}) "
                  f"| {r['regular_percent']:.1f} ({reg}) | {r['valence4_percent']:.1f} "
                  f"| {r['homeometry_min']:.2f} ({hmin}) | {r['homeometry_max']:.2f} ({hmax}) "
                  f"| {r['hausdorff_e3']:.2f} | {r['rms_e3']:.2f} | {r['mean_to_ref_e3']:.2f} ({dist}) "
                  f"| {r['nonconvex_faces']} / {r['flipped_faces']} / {r['folded_faces']} |")
            sys.stdout.flush()


if __name__ == "__main__":
    main()
