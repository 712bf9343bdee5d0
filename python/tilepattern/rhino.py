"""Tiles to a Rhino ``.3dm`` file with ``rhino3dm``, for Rhino users without the plugin."""

import rhino3dm

__all__ = ["export_3dm"]

LAYERS = ("full", "half", "boundary")


def export_3dm(placed, path, units="Millimeters"):
    """Write tiles as Breps on layers ``tiles::full``, ``tiles::half`` and
    ``tiles::boundary``, each named by its cut-list label; the kept outline of every cut
    tile goes on ``tiles::cuts`` as a polyline.

    Parameters
    ----------
    placed : tilepattern.Tiles
    path : str or os.PathLike
    units : str
        Name of a ``rhino3dm.UnitSystem`` member: the units of the tile coordinates.

    Returns
    -------
    int
        The number of tile Breps written.
    """
    model = rhino3dm.File3dm()
    model.Settings.ModelUnitSystem = getattr(rhino3dm.UnitSystem, units)
    parent = rhino3dm.Layer()
    parent.Name = "tiles"
    parent_id = model.Layers[model.Layers.Add(parent)].Id
    layer_index = {}
    for name in LAYERS + ("cuts",):
        layer = rhino3dm.Layer()
        layer.Name = name
        layer.ParentLayerId = parent_id
        layer_index[name] = model.Layers.Add(layer)

    written = 0
    for kind, frame, size, label, outline in zip(placed.kinds, placed.frames, placed.sizes, placed.labels, placed.outlines):
        origin, x, y, _ = (rhino3dm.Point3d(*p) if i == 0 else rhino3dm.Vector3d(*p) for i, p in enumerate(frame))
        plane = rhino3dm.Plane(origin, x, y)
        box = rhino3dm.Box(rhino3dm.BoundingBox(rhino3dm.Point3d(-size[0] / 2, -size[1] / 2, 0.0), rhino3dm.Point3d(size[0] / 2, size[1] / 2, size[2])))
        brep = rhino3dm.Brep.CreateFromBox(box)
        brep.Transform(rhino3dm.Transform.PlaneToPlane(rhino3dm.Plane.WorldXY(), plane))
        attributes = rhino3dm.ObjectAttributes()
        attributes.LayerIndex = layer_index.get(kind, layer_index["full"])
        attributes.Name = label
        model.Objects.AddBrep(brep, attributes)
        written += 1
        for loop in outline:
            points = [plane.PointAt(float(u), float(v)) for u, v in loop]
            polyline = rhino3dm.Polyline([*points, points[0]])
            cut = rhino3dm.ObjectAttributes()
            cut.LayerIndex = layer_index["cuts"]
            cut.Name = label
            model.Objects.AddPolyline(polyline, cut)
    if not model.Write(str(path), 7):
        raise OSError("rhino3dm could not write %s" % path)
    return written
