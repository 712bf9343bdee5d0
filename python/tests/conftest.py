"""Test setup: the package from this checkout, shared meshes."""

import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
sys.path.insert(0, str(HERE))

from meshes import grid, shell  # noqa: E402

#: The C header, when the tests run in a source checkout.
HEADER = HERE.parent.parent / "include" / "tilepattern.h"


@pytest.fixture
def quads():
    """A flat 10 x 8 grid of 145 mm quads."""
    return grid(10, 8)


@pytest.fixture(scope="session")
def curved():
    """A doubly curved triangle surface (2 x 1.6 m)."""
    return shell()
