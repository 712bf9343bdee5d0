"""Meshes for the tests, generated here (no files, no network): quad grids, triangulated
and curved surfaces, and a mesh mixing triangles, quads and a pentagon."""

import numpy as np


def grid(nx, ny, edge=0.145, height=None):
    """An nx x ny grid of square quads of side ``edge``, lifted by ``height(x, y)``.

    Returns ``(vertices (V, 3) array, faces list of lists)``; faces counter-clockwise seen
    from +z, numbered row by row.
    """
    x, y = np.meshgrid(np.arange(nx + 1) * edge, np.arange(ny + 1) * edge)
    x, y = x.ravel(), y.ravel()
    z = np.zeros_like(x) if height is None else height(x, y)
    vertices = np.c_[x, y, z]

    def at(i, j):
        return i + (nx + 1) * j

    faces = [[at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)] for j in range(ny) for i in range(nx)]
    return vertices, faces


def triangulated(vertices, faces):
    """Each quad split into two triangles."""
    return vertices, [t for a, b, c, d in faces for t in ([a, b, c], [a, c, d])]


def shell(nx=40, ny=32, edge=0.05):
    """A doubly curved triangle surface of 2 x 1.6 m, fine enough to remesh at 0.145."""
    return triangulated(*grid(nx, ny, edge=edge, height=lambda x, y: 0.15 * np.sin(x) * np.sin(1.5 * y)))


def mixed():
    """A 3 x 2 grid whose face 0 is split into two triangles and whose face 2 is a pentagon
    (a vertex added in the middle of its boundary edge): 7 faces of sizes 3, 3, 4, 5, 4,
    4, 4."""
    vertices, faces = grid(3, 2)
    a, b, c, d = faces[0]
    middle = len(vertices)
    vertices = np.vstack([vertices, (vertices[faces[2][0]] + vertices[faces[2][1]]) / 2])
    p = faces[2]
    return vertices, [[a, b, c], [a, c, d], faces[1], [p[0], middle, p[1], p[2], p[3]], faces[3], faces[4], faces[5]]


def round_dome(rings=12, sectors=48):
    """A spherical cap of radius 2 over a disk of radius 1.3: a centre, rings of triangles."""
    V = [[0.0, 0.0, 2.0]]
    for i in range(1, rings + 1):
        r = 1.3 * i / rings
        for j in range(sectors):
            a = 2 * np.pi * j / sectors
            V.append([r * np.cos(a), r * np.sin(a), np.sqrt(4.0 - r * r)])

    def at(i, j):
        return 0 if i == 0 else 1 + (i - 1) * sectors + j % sectors

    F = [[0, at(1, j), at(1, j + 1)] for j in range(sectors)]
    for i in range(1, rings):
        for j in range(sectors):
            F += [[at(i, j), at(i + 1, j), at(i + 1, j + 1)], [at(i, j), at(i + 1, j + 1), at(i, j + 1)]]
    return np.array(V), F
