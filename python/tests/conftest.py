"""Fixtures: the meshes of meshes.py."""

import numpy as np
import pytest

from meshes import grid, triangulated


@pytest.fixture
def quads():
    return grid(10, 8)


@pytest.fixture
def shell():
    """A doubly curved triangle mesh, 2 x 1.6 m, fine enough to remesh at 0.145."""
    return triangulated(*grid(40, 32, edge=0.05, height=lambda x, y: 0.15 * np.sin(x) * np.sin(1.5 * y)))
