#!/usr/bin/env python3
"""Peak memory and time of whole CLI runs on large meshes: each dataset split into four
`--splits` times (every triangle at its edges' midpoints, pymeshlab's midpoint subdivision;
2 takes bunny.ply's 69,451 triangles to 1.1 million, 3 to 4.4 million), then `convert`,
`fitmap`, and `simplify` to `--faces` quads in uniform and adaptive mode, each in a
process of its own, whose peak resident memory the kernel reports (wait4's ru_maxrss).

Prints one markdown row per run: the peak in MB (10^6 bytes) and the wall-clock time.

    python3 bench/peak_memory.py [--quadsimp build/src/quadsimp] [--datasets ../shared/datasets]
                                 [--python .venv/bin/python] [--models bunny] [--splits 2] [--faces 10000]
"""
import os
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paper_table1 import machine, meshes, parse_args, table_header  # noqa: E402

SPLIT = """
import sys, pymeshlab
ms = pymeshlab.MeshSet()
ms.load_new_mesh(sys.argv[1])
if int(sys.argv[3]) > 0:
    ms.meshing_surface_subdivision_midpoint(iterations=int(sys.argv[3]), threshold=pymeshlab.PercentageValue(0))
ms.save_current_mesh(sys.argv[2], binary=True, save_vertex_normal=False, save_vertex_color=False,
                     save_face_color=False, save_wedge_texcoord=False)
print(ms.current_mesh().face_number())
"""


def measured(cmd):
    """Runs cmd alone; returns (its peak resident memory in MB, seconds)."""
    with tempfile.TemporaryFile() as err:
        start = time.monotonic()
        child = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=err)
        _, status, usage = os.wait4(child.pid, 0)
        seconds = time.monotonic() - start
        child.returncode = os.waitstatus_to_exitcode(status)
        if child.returncode != 0:
            err.seek(0)
            raise RuntimeError(f"{' '.join(cmd)} failed: {err.read().decode().strip()}")
    return usage.ru_maxrss * 1024 / 1e6, seconds  # ru_maxrss is in KiB on Linux


def main():
    args = parse_args(__doc__, ["bunny"], python=True,
                      extra=[("--splits", dict(type=int, default=2, help="times each triangle is split into four")),
                             ("--faces", dict(type=int, default=10000, help="the simplifications' target"))])
    print(f"Machine: {machine()}; each run alone, its peak resident memory and wall-clock time.\n")
    columns = table_header("| model | triangles | run | peak MB | seconds |")
    for model, source in meshes(args, columns):
        with tempfile.TemporaryDirectory() as tmp:
            mesh = os.path.join(tmp, f"{model}_split{args.splits}.ply")
            made = subprocess.run([args.python, "-c", SPLIT, source, mesh, str(args.splits)],
                                  capture_output=True, text=True)
            if made.returncode != 0:
                raise RuntimeError(f"splitting {source} failed: {made.stderr.strip()}")
            triangles = int(made.stdout.split()[-1])
            out = os.path.join(tmp, "out.ply")
            faces = str(args.faces)
            runs = [("convert", ["convert", mesh, out]),
                    ("fitmap", ["fitmap", mesh, out]),
                    (f"simplify to {args.faces:,} quads, uniform", ["simplify", mesh, out, "--faces", faces]),
                    (f"simplify to {args.faces:,} quads, adaptive", ["simplify", mesh, out, "--faces", faces,
                                                                      "--adaptive"])]
            for name, cmd in runs:
                mb, seconds = measured([args.quadsimp, *cmd, "-q"])
                print(f"| {model} | {triangles:,} | {name} | {mb:.0f} | {seconds:.1f} |", flush=True)


if __name__ == "__main__":
    main()
