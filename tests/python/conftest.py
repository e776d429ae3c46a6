# quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
import os
import pathlib
import sys

import numpy as np
import pymeshlab
import pytest

import quadsimp_pymeshlab

ROOT = pathlib.Path(__file__).resolve().parents[2]
SHARED = ROOT.parent / "shared" / "datasets"
GLMARK_BUNNY = pathlib.Path("/usr/share/glmark2/models/bunny.obj")


@pytest.fixture(scope="session", autouse=True)
def plugin():
    return quadsimp_pymeshlab.load()


@pytest.fixture(scope="session")
def bunny_path():
    for p in (SHARED / "bunny.ply", GLMARK_BUNNY):
        if p.exists():
            return str(p)
    pytest.skip("no bunny: neither ../shared/datasets/bunny.ply nor glmark2-data")


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("QUADSIMP_CLI", str(ROOT / "build" / "src" / "quadsimp"))
    if not os.path.exists(path):
        pytest.skip(f"quadsimp CLI not built at {path}")
    return path


def open_grid(n=60, bump=0.25):
    """A generated open surface: an n x n grid over the unit square with a bump."""
    xs, ys = np.meshgrid(np.linspace(0, 1, n + 1), np.linspace(0, 1, n + 1))
    z = bump * np.exp(-20 * ((xs - 0.5) ** 2 + (ys - 0.5) ** 2))
    v = np.column_stack([xs.ravel(), ys.ravel(), z.ravel()])
    faces = []
    for j in range(n):
        for i in range(n):
            a, b, c, d = j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1, (j + 1) * (n + 1) + i
            faces += [(a, b, c), (a, c, d)] if (i + j) % 2 else [(a, b, d), (b, c, d)]
    return pymeshlab.Mesh(vertex_matrix=v, face_matrix=np.array(faces, dtype=np.int32))


def is_pure_quad(mesh):
    polys = mesh.polygonal_face_list()
    return len(polys) > 0 and all(len(p) == 4 for p in polys)



def textured_sphere(folder):
    """tests/integration/textured_sphere.py's sphere in `folder`: its OBJ's path."""
    sys.path.insert(0, str(pathlib.Path(__file__).parents[1] / "integration"))
    import textured_sphere as sphere
    return sphere.write(pathlib.Path(folder))
