"""Meshes for the tests: small quad grids and triangulated curved surfaces."""

import numpy as np


def grid(nx, ny, edge=0.145, height=lambda x, y: 0.0 * x):
    """An nx x ny quad grid of edge ``edge`` lifted by ``height``: (V, F)."""
    x, y = np.meshgrid(np.arange(nx + 1) * edge, np.arange(ny + 1) * edge)
    x, y = x.ravel(), y.ravel()
    vertices = np.c_[x, y, height(x, y)]
    at = lambda i, j: i + (nx + 1) * j  # noqa: E731
    faces = [[at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)] for j in range(ny) for i in range(nx)]
    return vertices, faces


def triangulated(vertices, faces):
    """Each quad split into two triangles."""
    return vertices, [t for a, b, c, d in faces for t in ([a, b, c], [a, c, d])]
