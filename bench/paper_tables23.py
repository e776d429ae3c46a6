#!/usr/bin/env python3
"""Reproduces the paper's Tables 2 and 3 on ../shared/datasets.

Table 2: adaptive simplification with automatic halting (fitmaps included in the time).
Table 3: uniform simplification stopped at the face count the adaptive run reached.
The same again with the paper's own halting rule (--halt-share 1), and adaptive mode
with the paper's Table 2 face counts as targets, each beside uniform at the same counts.
Then both modes at seven counts around each automatic halting count (2% apart): one
run's RMS can jump by a fifth between counts 1% apart, the median of seven much less.
Last, automatic halting on re-rounded copies of each input (every coordinate moved by
at most one float32 step): where it halts depends on rounding, so the table gives the
spread of the halting counts and the median gain over the draws.

    python3 bench/paper_tables23.py [--quadsimp build/src/quadsimp] [--datasets ../shared/datasets] [--draws 8]
                                    [--both-args="--keep-tips"]
"""
import os
import random
import statistics
import struct
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paper_table1 import dataset, machine, meshes, parse_args, run, table_header  # noqa: E402

# model -> (adaptive: faces, time, val, reg, hmin, hmax, dist; uniform: same)
PAPER = {
    "moai": ((94, 23.97, 5, 70, 0.39, 1.73, 14.52), (94, 20.72, 5, 72, 0.62, 1.57, 14.24)),
    "pensatore": ((116, 75.08, 6, 68, 0.12, 2.32, 16.29), (116, 50.30, 5, 72, 0.55, 1.82, 13.64)),
    "gargoyle": ((1500, 38.46, 6, 69, 0.17, 3.60, 4.21), (1500, 26.04, 5, 72, 0.52, 1.80, 3.83)),
    "bunny": ((681, 33.64, 6, 69, 0.17, 4.27, 8.71), (680, 22.77, 5, 71, 0.06, 2.15, 10.28)),
    "rampart": ((1400, 73.21, 6, 71, 0.10, 6.08, 4.62), (1400, 49.09, 6, 71, 0.29, 2.37, 12.82)),
    "armadillo": ((1500, 141.64, 6, 69, 0.09, 3.79, 4.32), (1500, 90.82, 6, 73, 0.50, 1.93, 5.96)),
}

HEADER = ("| model | mode | #faces (paper) | time s (paper) | val max (paper) | reg % (paper) | homeo min (paper) "
          "| homeo max (paper) | Hausdorff e-3 | RMS e-3 (paper Dist) | mean out->in e-3 | projectability % | folded |")


def row(model, mode, r, p):
    return (f"| {model} | {mode} | {r['faces']} ({p[0]}) | {r['seconds']:.2f} ({p[1]}) | {r['max_valence']} ({p[2]}) "
            f"| {r['regular_percent']:.1f} ({p[3]}) | {r['homeometry_min']:.2f} ({p[4]}) | {r['homeometry_max']:.2f} ({p[5]}) "
            f"| {r['hausdorff_e3']:.2f} | {r['rms_e3']:.2f} ({p[6]}) | {r['mean_to_ref_e3']:.2f} "
            f"| {100 * r['projectability']:.2f} | {r['folded_faces']} |")


def gain(a, u, key):
    return f"{100 * (1 - a[key] / u[key]):+.0f}%"


def main():
    args = parse_args(__doc__, list(PAPER), draws=8, both_args=True)

    print(f"Machine: {machine()}; fitmaps use both cores, simplification one. Distances sampled with "
          f"{args.samples} points per surface plus vertices.\n")
    tables = (("Automatic halting (Table 2) and uniform at the same count (Table 3)", ["--auto-halt"]),
              ("The paper's halting rule (run until no feasible collapse remains: --halt-share 1), and uniform "
               "at the same count", ["--auto-halt", "--halt-share", "1"]),
              ("Adaptive with the paper's Table 2 face counts as targets, and uniform at the same count", None))
    halted = {}
    for title, halting in tables:
        print(f"### {title}\n")
        columns = table_header(HEADER)
        summary = []
        for model, mesh in meshes(args, columns):
            pa, pu = PAPER[model]
            if halting is None:
                a = run(args.quadsimp, mesh, pa[0], args.samples, ["--adaptive", *args.both_args])
            else:
                a = run(args.quadsimp, mesh, 0, args.samples, ["--adaptive", *halting, *args.both_args])
            u = run(args.quadsimp, mesh, a["faces"], args.samples, args.both_args)
            print(row(model, "adaptive", a, pa))
            print(row(model, "uniform", u, pu))
            summary.append(f"{model}: adaptive vs uniform at {a['faces']} faces: RMS {gain(a, u, 'rms_e3')} "
                           f"(output->input {gain(a, u, 'rms_to_ref_e3')}, input->output "
                           f"{gain(a, u, 'rms_from_ref_e3')}), Hausdorff {gain(a, u, 'hausdorff_e3')}, "
                           f"mean {gain(a, u, 'mean_to_ref_e3')} (negative = worse)")
            if halting == ["--auto-halt"]:
                halted[model] = a["faces"]
            sys.stdout.flush()
        print()
        for line in summary:
            print(f"- {line}")
        print()
    window(args, halted)
    draws(args)


def rerounded(src, dst, seed):
    """Copies a binary little-endian PLY whose vertices start with float x, y, z and have
    4-byte properties only, moving each coordinate by -1, 0 or +1 float32 step."""
    with open(src, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii").splitlines()
    if "format binary_little_endian 1.0" not in header:
        raise ValueError(f"{src}: not a binary little-endian PLY")
    count, props, in_vertex = 0, [], False
    for line in header:
        words = line.split()
        if words[:2] == ["element", "vertex"]:
            count, in_vertex = int(words[2]), True
        elif words and words[0] == "element":
            in_vertex = False
        elif in_vertex and words[0] == "property":
            props.append(words)
    if [p[1:] for p in props[:3]] != [["float", "x"], ["float", "y"], ["float", "z"]] or \
            any(p[1] not in ("float", "int", "uint", "float32", "int32", "uint32") for p in props):
        raise ValueError(f"{src}: vertices must start with float x, y, z and have 4-byte properties only")
    bits = list(struct.unpack_from(f"<{count * len(props)}i", data, end))
    rng = random.Random(seed)
    for v in range(count):
        for c in range(3):
            i = v * len(props) + c
            if bits[i] & 0x7FFFFFFF:  # zero stays zero
                bits[i] += rng.choice((-1, 0, 1))
    with open(dst, "wb") as f:
        f.write(data[:end])
        f.write(struct.pack(f"<{len(bits)}i", *bits))
        f.write(data[end + 4 * len(bits):])


def draws(args):
    print(f"### Automatic halting on {args.draws} draws of each input: the file itself, then copies re-rounded "
          "(each coordinate moved by at most one float32 step)\n")
    table_header("| model | halting counts (the file first) | adaptive RMS e-3: median (range) "
                 "| uniform at the same counts | adaptive lower by, per draw | median | projectability %: min, median "
                 "| regular %: min, median | max valence |")
    for model, mesh in meshes(args):
        counts, a, u, gains, proj, reg, val = [], [], [], [], [], [], []
        with tempfile.TemporaryDirectory() as tmp:
            for k in range(args.draws):
                src = mesh
                if k:
                    src = os.path.join(tmp, f"{model}-{k}.ply")
                    rerounded(mesh, src, k)
                ra = run(args.quadsimp, src, 0, args.samples, ["--adaptive", "--auto-halt", *args.both_args])
                ru = run(args.quadsimp, src, ra["faces"], args.samples, args.both_args)
                counts.append(ra["faces"])
                a.append(ra["rms_e3"])
                u.append(ru["rms_e3"])
                gains.append(100 * (1 - ra["rms_e3"] / ru["rms_e3"]))
                proj.append(100 * ra["projectability"])
                reg.append(ra["regular_percent"])
                val.append(ra["max_valence"])
        print(f"| {model} | {', '.join(map(str, counts))} | {statistics.median(a):.2f} ({min(a):.2f}-{max(a):.2f}) "
              f"| {statistics.median(u):.2f} ({min(u):.2f}-{max(u):.2f}) | {', '.join(f'{g:.0f}%' for g in gains)} "
              f"| {statistics.median(gains):.1f}% | {min(proj):.2f}, {statistics.median(proj):.2f} "
              f"| {min(reg):.1f}, {statistics.median(reg):.1f} | {max(val)} |")
        sys.stdout.flush()
    print()


def window(args, halted):
    print("### RMS around the automatic halting count: seven counts 2% apart, median of each mode\n")
    table_header("| model | counts | uniform RMS e-3: median (range) | adaptive RMS e-3: median (range) "
                 "| adaptive lower by (medians) | single counts |")
    for model, faces in halted.items():
        if model not in ("bunny", "gargoyle", "rampart", "armadillo"):
            continue  # the models with a distance target
        mesh = dataset(args, model)
        counts = [round(faces * (1 + 0.02 * i)) for i in range(-3, 4)]
        u = [run(args.quadsimp, mesh, n, args.samples, args.both_args)["rms_e3"] for n in counts]
        a = [run(args.quadsimp, mesh, n, args.samples, ["--adaptive", *args.both_args])["rms_e3"] for n in counts]
        singles = ", ".join(f"{100 * (1 - x / y):.0f}%" for x, y in zip(a, u))
        print(f"| {model} | {counts[0]}-{counts[-1]} | {statistics.median(u):.2f} ({min(u):.2f}-{max(u):.2f}) "
              f"| {statistics.median(a):.2f} ({min(a):.2f}-{max(a):.2f}) "
              f"| {100 * (1 - statistics.median(a) / statistics.median(u)):.1f}% | {singles} |")
        sys.stdout.flush()
    print()


if __name__ == "__main__":
    main()
