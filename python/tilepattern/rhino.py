"""Tiles to a Rhino ``.3dm`` file with the ``rhino3dm`` package (no Rhino needed).

``rhino3dm`` is imported when :func:`export_3dm` is called, not when :mod:`tilepattern` is.
"""

from __future__ import annotations

import os

import numpy as np

__all__ = ["export_3dm", "UNIT_ALIASES"]

#: Short unit names accepted besides ``rhino3dm.UnitSystem`` member names.
UNIT_ALIASES = {"mm": "Millimeters", "cm": "Centimeters", "m": "Meters", "in": "Inches", "ft": "Feet"}

#: Layer colours (RGBA).
_COLOURS = {
    "tiles": (128, 128, 128, 255),
    "full": (196, 120, 80, 255),
    "half": (80, 140, 200, 255),
    "cuts": (220, 40, 40, 255),
}


def _rhino3dm():
    try:
        import rhino3dm
    except ImportError as why:  # pragma: no cover - depends on the environment
        raise ImportError("tilepattern.rhino needs rhino3dm: pip install 'rhino3dm>=8'") from why
    return rhino3dm


def _unit_system(rhino3dm, units):
    name = UNIT_ALIASES.get(str(units).lower(), str(units))
    for member in dir(rhino3dm.UnitSystem):
        if member.lower() == name.lower() and not member.startswith("_"):
            return getattr(rhino3dm.UnitSystem, member)
    raise ValueError("unknown units %r: use a rhino3dm.UnitSystem name such as 'Millimeters' or one of %s" % (units, ", ".join(UNIT_ALIASES)))


def _add_layer(rhino3dm, model, name, parent=None):
    layer = rhino3dm.Layer()
    layer.Name = name
    layer.Color = _COLOURS.get(name, (0, 0, 0, 255))
    if parent is not None:
        layer.ParentLayerId = parent
    index = model.Layers.Add(layer)
    return index, model.Layers[index].Id


def _plane(rhino3dm, frame):
    origin, x, y, _ = (np.asarray(v, dtype=np.float64).tolist() for v in frame)
    return rhino3dm.Plane(rhino3dm.Point3d(*origin), rhino3dm.Vector3d(*x), rhino3dm.Vector3d(*y))


def _box_geometry(rhino3dm, frame, size, corners, geometry="brep"):
    """A Brep box (or, as asked or without Brep support, a closed mesh with the same 8
    corners)."""
    length, width, thickness = (float(s) for s in size)
    brep_from_box = getattr(getattr(rhino3dm, "Brep", None), "CreateFromBox", None) if geometry == "brep" else None
    if brep_from_box is not None:
        local = rhino3dm.BoundingBox(rhino3dm.Point3d(-length / 2, -width / 2, 0.0), rhino3dm.Point3d(length / 2, width / 2, thickness))
        brep = brep_from_box(rhino3dm.Box(local))
        if brep is not None:
            brep.Transform(rhino3dm.Transform.PlaneToPlane(rhino3dm.Plane.WorldXY(), _plane(rhino3dm, frame)))
            return brep
    mesh = rhino3dm.Mesh()
    for x, y, z in np.asarray(corners, dtype=np.float64).tolist():
        mesh.Vertices.Add(x, y, z)
    # Corners: bottom 0-3 counter-clockwise from (-x, -y), top 4-7 likewise; faces outwards.
    for a, b, c, d in ((0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)):
        mesh.Faces.AddFace(a, b, c, d)
    mesh.Normals.ComputeNormals()
    mesh.Compact()
    return mesh


def export_3dm(tiles, path, units="Millimeters", outlines=True, geometry="brep", version=7):
    """Write tiles to a Rhino ``.3dm`` file.

    Each tile becomes a box (a Brep) on layer ``tiles::full`` or ``tiles::half`` (children
    of ``tiles``) by the blank it is cut from, named by its cut-list label (``F``, ``H``,
    ``B1``..., ``C1``...). Its user text holds ``index``, ``kind``, ``step`` (laying
    order), ``faces``, ``kept_fraction`` and ``joint_deviation`` (its worst joint's
    ``|gap - joint|``, model units). With ``outlines``, the part to keep of every cut
    tile goes on layer ``tiles::cuts`` as closed polylines on the tile's bottom face.

    Parameters
    ----------
    tiles : tilepattern.Tiles or tilepattern.compas.TileBoxes
        What :func:`tilepattern.tiles` or :func:`tilepattern.compas.tiles` returned.
    path : str or os.PathLike
        The file to write.
    units : str, optional
        The unit system of the tile coordinates: a ``rhino3dm.UnitSystem`` name
        (``"Millimeters"``, default, ``"Meters"``...) or ``"mm"``, ``"cm"``, ``"m"``.
        Nothing is scaled; this only tells Rhino what the numbers mean.
    outlines : bool, optional
        Also write the kept outlines of cut tiles (default True).
    geometry : {"brep", "mesh"}, optional
        Write each tile as a Brep (default; a closed mesh when this rhino3dm cannot make
        Breps) or as a closed 6-face mesh.
    version : int, optional
        The ``.3dm`` version to write (default 7).

    Returns
    -------
    int
        The number of tiles written.

    Raises
    ------
    OSError
        When rhino3dm cannot write the file.

    Examples
    --------
    >>> import os, tempfile
    >>> import rhino3dm
    >>> from tilepattern import match, tiles
    >>> from tilepattern.rhino import export_3dm
    >>> V = [[0.145 * i, 0.145 * j, 0.0] for j in range(3) for i in range(4)]
    >>> F = [[i + 4 * j, i + 1 + 4 * j, i + 5 + 4 * j, i + 4 + 4 * j] for j in range(2) for i in range(3)]
    >>> placed = tiles(V, F, match(V, F, time_limit=5))
    >>> path = os.path.join(tempfile.mkdtemp(), "tiles.3dm")
    >>> export_3dm(placed, path, units="m")
    3
    >>> len(rhino3dm.File3dm.Read(path).Objects)
    3
    """
    if geometry not in ("brep", "mesh"):
        raise ValueError("geometry must be 'brep' or 'mesh', got %r" % (geometry,))
    rhino3dm = _rhino3dm()
    placed = getattr(tiles, "tiles", tiles)
    model = rhino3dm.File3dm()
    model.Settings.ModelUnitSystem = _unit_system(rhino3dm, units)

    _, parent = _add_layer(rhino3dm, model, "tiles")
    layers = {name: _add_layer(rhino3dm, model, name, parent)[0] for name in ("full", "half")}
    cut_layer = _add_layer(rhino3dm, model, "cuts", parent)[0] if outlines and any(len(loops) for loops in placed.outlines) else None

    blanks = placed.blanks
    for index in range(len(placed)):
        frame, size = placed.frames[index], placed.sizes[index]
        shape = _box_geometry(rhino3dm, frame, size, placed.corners[index], geometry)
        attributes = rhino3dm.ObjectAttributes()
        attributes.LayerIndex = layers[str(blanks[index])]
        attributes.Name = placed.labels[index]
        attributes.SetUserString("index", str(index))
        attributes.SetUserString("kind", str(placed.kinds[index]))
        attributes.SetUserString("step", str(int(placed.steps[index])))
        attributes.SetUserString("faces", " ".join(str(int(f)) for f in placed.faces[index] if f >= 0))
        attributes.SetUserString("kept_fraction", repr(float(placed.kept_fractions[index])))
        if index < len(placed.joint_deviations):
            attributes.SetUserString("joint_deviation", repr(float(placed.joint_deviations[index])))
        if isinstance(shape, rhino3dm.Mesh):
            model.Objects.AddMesh(shape, attributes)
        else:
            model.Objects.AddBrep(shape, attributes)
        if cut_layer is not None and placed.outlines[index]:
            plane = _plane(rhino3dm, frame)
            for loop in placed.outlines[index]:
                points = [plane.PointAt(float(u), float(v)) for u, v in loop]
                cut = rhino3dm.ObjectAttributes()
                cut.LayerIndex = cut_layer
                cut.Name = placed.labels[index]
                cut.SetUserString("index", str(index))
                model.Objects.AddPolyline(points + points[:1], cut)

    if not model.Write(os.fspath(path), int(version)):
        raise OSError("rhino3dm could not write %s" % os.fspath(path))
    return len(placed)
