"""Zones (issue 20): a bond per face reaches the pattern stage from names, codes or numpy
arrays; bad zones are refused with the face or the count at fault."""

import numpy as np
import pytest

import tilepattern as tp
from tilepattern import _native as nat

from meshes import grid


def band(n=8, rows=(3, 4), bond="herringbone"):
    """Zones of an n x n grid: the faces of ``rows`` in ``bond``, the rest None."""
    return [bond if f // n in rows else None for f in range(n * n)]


def test_default_zones_give_the_optimum_without_zones():
    v, f = grid(8, 8)
    plain = tp.match(v, f, time_limit=10)
    assert plain.optimal
    results = [tp.match(v, f, time_limit=10, zones=zones) for zones in ([None] * 64, np.full(64, -1), ["staggered"] * 64, np.full(64, nat.TP_BOND_STAGGERED, dtype=np.int64))]
    for zoned in results:
        # Proven, the same optimum (the patterns may differ among equal optima) ...
        assert zoned.optimal and zoned.objective == plain.objective
        # ... and the same options however the zones are spelt: the same pattern.
        assert zoned.pairs.tolist() == results[0].pairs.tolist()


def test_a_herringbone_band_reaches_the_solve():
    v, f = grid(8, 8)
    # Level courses refuse a herringbone zone: proof that the zones reach the options.
    with pytest.raises(tp.InvalidArgumentError, match="courses free"):
        tp.match(v, f, zones=band(), courses="level")
    by_name = tp.match(v, f, zones=band(), time_limit=10)
    codes = np.array([nat.TP_BOND_HERRINGBONE if z else -1 for z in band()], dtype=np.int32)
    by_code = tp.match(v, f, zones=codes, time_limit=10)
    mixed = tp.match(v, f, zones=[nat.TP_BOND_HERRINGBONE if z else None for z in band()], time_limit=10)
    assert by_name.pairs.tolist() == by_code.pairs.tolist() == mixed.pairs.tolist()
    assert len(by_name.pairs) > 0 and by_name.bound >= by_name.objective
    a, b = by_name.pairs[:, 0], by_name.pairs[:, 1]
    assert np.all(((b == a + 1) & (a % 8 != 7)) | (b == a + 8))


def test_bad_zones_name_the_face_or_the_count():
    v, f = grid(4, 4)
    with pytest.raises(tp.InvalidArgumentError, match="15 bonds for a mesh of 16 faces"):
        tp.match(v, f, zones=[None] * 15)
    with pytest.raises(tp.InvalidArgumentError, match=r"zones\[3\] is 'zigzag'"):
        tp.match(v, f, zones=[None, None, None, "zigzag"] + [None] * 12)
    with pytest.raises(tp.InvalidArgumentError, match=r"zones\[2\] is 9"):
        tp.match(v, f, zones=np.array([-1, -1, 9] + [-1] * 13))
    with pytest.raises(tp.InvalidArgumentError, match=r"zones\[0\] is 1.5"):
        tp.match(v, f, zones=[1.5] * 16)
    with pytest.raises(tp.InvalidArgumentError, match="one bond per face"):
        tp.match(v, f, zones="herringbone")
    with pytest.raises(tp.InvalidArgumentError, match="one bond per face"):
        tp.match(v, f, zones=[])
    with pytest.raises(tp.InvalidArgumentError, match="one bond per face"):
        tp.match(v, f, zones=np.zeros((4, 4), dtype=np.int32))
