"""The .3dm export reads back with the right objects, layers and names."""

import rhino3dm

import tilepattern as tp
from tilepattern.rhino import export_3dm

from meshes import grid, triangulated


def test_export_reads_back(tmp_path):
    v, f = grid(9, 7)
    surface = triangulated(*grid(24, 20, edge=0.05))
    placed = tp.tiles(v, f, tp.match(v, f, time_limit=3), surface=surface)
    path = tmp_path / "tiles.3dm"
    assert export_3dm(placed, path, units="Meters") == len(placed)
    model = rhino3dm.File3dm.Read(str(path))
    layers = [layer.FullPath for layer in model.Layers]
    assert {"tiles", "tiles::full", "tiles::half", "tiles::boundary", "tiles::cuts"} <= set(layers)
    breps = [o for o in model.Objects if isinstance(o.Geometry, rhino3dm.Brep)]
    cuts = sum(len(loops) for loops in placed.outlines)
    assert len(breps) == len(placed) and len(model.Objects) == len(placed) + cuts
    names = sorted(o.Attributes.Name for o in breps)
    assert names == sorted(placed.labels)
    kinds = {layers[o.Attributes.LayerIndex].split("::")[1] for o in breps}
    assert kinds <= {"full", "half", "boundary"} and "full" in kinds
    assert model.Settings.ModelUnitSystem == rhino3dm.UnitSystem.Meters
