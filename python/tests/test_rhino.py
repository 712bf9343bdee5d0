"""The .3dm export reads back with its objects, layers, names and geometry."""

import numpy as np
import pytest

rhino3dm = pytest.importorskip("rhino3dm")

import tilepattern as tp  # noqa: E402
import tilepattern.compas as tpc  # noqa: E402
from tilepattern.rhino import export_3dm  # noqa: E402

from meshes import grid, triangulated  # noqa: E402


@pytest.fixture(scope="module")
def placed():
    """Full, half and boundary tiles: 63 quads cut to a smaller surface."""
    v, f = grid(9, 7)
    surface = triangulated(*grid(24, 20, edge=0.05))
    result = tp.tiles(v, f, tp.match(v, f, time_limit=3), surface=surface)
    assert {"full", "half", "boundary"} <= set(result.kinds.tolist())
    return result


def layer_paths(model):
    return [layer.FullPath for layer in model.Layers]


def test_export_reads_back(tmp_path, placed):
    path = tmp_path / "tiles.3dm"
    assert export_3dm(placed, path, units="Meters") == len(placed)
    model = rhino3dm.File3dm.Read(str(path))
    assert model.Settings.ModelUnitSystem == rhino3dm.UnitSystem.Meters
    layers = layer_paths(model)
    assert layers == ["tiles", "tiles::full", "tiles::half", "tiles::cuts"]
    tiles = [o for o in model.Objects if isinstance(o.Geometry, rhino3dm.Brep)]
    cuts = [o for o in model.Objects if not isinstance(o.Geometry, rhino3dm.Brep)]
    assert len(tiles) == len(placed)
    assert len(cuts) == sum(len(loops) for loops in placed.outlines)
    assert len(model.Objects) == len(placed) + len(cuts)
    by_index = {int(o.Attributes.GetUserString("index")): o for o in tiles}
    assert sorted(by_index) == list(range(len(placed)))
    for i, obj in by_index.items():
        assert obj.Attributes.Name == placed.labels[i]
        assert layers[obj.Attributes.LayerIndex] == "tiles::" + placed.blanks[i]
        assert obj.Attributes.GetUserString("kind") == placed.kinds[i]
        assert int(obj.Attributes.GetUserString("step")) == placed.steps[i]
        assert float(obj.Attributes.GetUserString("joint_deviation")) == placed.joint_deviations[i]
        brep = obj.Geometry
        assert brep.IsSolid and len(brep.Faces) == 6 and len(brep.Vertices) == 8
        points = np.array([[v.Location.X, v.Location.Y, v.Location.Z] for v in brep.Vertices])
        distance = np.linalg.norm(points[:, None, :] - placed.corners[i][None, :, :], axis=2)
        assert np.all(distance.min(axis=0) < 1e-9) and np.all(distance.min(axis=1) < 1e-9)
    for obj in cuts:
        assert layers[obj.Attributes.LayerIndex] == "tiles::cuts"
        assert placed.kinds[int(obj.Attributes.GetUserString("index"))] in ("boundary", "fit_cut")
    # Filler pieces (on no quad) are not counted as full or half tiles by the report.
    on_quads = [o for o in tiles if placed.faces[int(o.Attributes.GetUserString("index")), 0] >= 0]
    full = sum(layers[o.Attributes.LayerIndex] == "tiles::full" for o in on_quads)
    assert full == placed.report["full_tiles"]


def test_meshes_and_no_outlines(tmp_path, placed):
    path = tmp_path / "mesh.3dm"
    export_3dm(placed, path, units="mm", outlines=False, geometry="mesh")
    model = rhino3dm.File3dm.Read(str(path))
    assert model.Settings.ModelUnitSystem == rhino3dm.UnitSystem.Millimeters
    assert layer_paths(model) == ["tiles", "tiles::full", "tiles::half"]
    assert len(model.Objects) == len(placed)
    for obj in model.Objects:
        mesh = obj.Geometry
        assert isinstance(mesh, rhino3dm.Mesh) and len(mesh.Faces) == 6 and mesh.IsClosed
        i = int(obj.Attributes.GetUserString("index"))
        points = np.array([[p.X, p.Y, p.Z] for p in mesh.Vertices])
        assert np.allclose(points, placed.corners[i])


def test_compas_boxes_export_and_bad_units(tmp_path, placed):
    boxes = tpc.boxes(placed)
    assert export_3dm(boxes, tmp_path / "boxes.3dm") == len(placed)
    with pytest.raises(ValueError, match="units"):
        export_3dm(placed, tmp_path / "x.3dm", units="furlongs")
    with pytest.raises(ValueError, match="geometry"):
        export_3dm(placed, tmp_path / "x.3dm", geometry="nurbs")
