"""Tile a COMPAS mesh: remesh (if it is made of triangles), match, place tiles, cut them to
the surface, print the report, write a Rhino file and a COMPAS JSON of the boxes.

    python examples/compas_tiles.py [MESH.obj] [--tile 280x140x15] [--joint 10] [--units m]

Without a mesh it uses COMPAS's sample hypar (triangulated). Needs `pip install compas
rhino3dm` and the TilePattern library (`cargo build --release`, or TILEPATTERN_LIB).
"""

import argparse
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "python"))

import compas  # noqa: E402
from compas.datastructures import Mesh  # noqa: E402

import tilepattern.compas as tpc  # noqa: E402
from tilepattern.rhino import export_3dm  # noqa: E402

UNITS = {"m": (0.001, "Meters"), "cm": (0.1, "Centimeters"), "mm": (1.0, "Millimeters")}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("mesh", nargs="?", help="OBJ surface (triangles or quads)")
    parser.add_argument("--tile", default="280x140x15", help="tile size LxWxT in millimetres")
    parser.add_argument("--joint", type=float, default=10.0, help="mortar joint in millimetres")
    parser.add_argument("--units", choices=UNITS, default="m", help="units of the mesh coordinates")
    parser.add_argument("--time-limit", type=float, default=10.0)
    parser.add_argument("--out", default="compas_tiles", help="output folder")
    args = parser.parse_args()

    per_mm, rhino_units = UNITS[args.units]
    length, width, thickness = (float(d) * per_mm for d in args.tile.split("x"))
    joint = args.joint * per_mm
    if args.mesh:
        surface = Mesh.from_obj(args.mesh)
    else:
        surface = Mesh.from_obj(compas.get("hypar.obj"))
        surface.quads_to_triangles()

    quads = surface
    if any(len(surface.face_vertices(f)) != 4 for f in surface.faces()):
        quads = tpc.remesh(surface, target_edge=(length + joint) / 2)
        print("remeshed %d faces into %d quads" % (surface.number_of_faces(), quads.number_of_faces()))

    pattern = tpc.match(quads, bond="staggered", time_limit=args.time_limit)
    print("%d tiles, %d half tiles, objective %.1f, bound %.1f (%s)" % (len(pattern.pairs), len(pattern.unpaired), pattern.objective, pattern.bound, pattern.status))
    placed = tpc.tiles(quads, pattern, surface=surface, length=length, width=width, thickness=thickness, joint=joint)
    report = tpc.report(placed)
    cutting = report["cutting"]
    print("%d tiles placed: %d cut to the boundary in %d shapes, coverage %.3f" % (len(placed), cutting["boundary_tiles"] + cutting["filler_tiles"], cutting["boundary_shapes"], cutting["coverage"]))

    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    written = export_3dm(placed, out / "tiles.3dm", units=rhino_units)
    compas.json_dump(tpc.boxes(placed), out / "boxes.json")
    (out / "report.json").write_text(json.dumps(report, indent=2))
    print("wrote %d tiles to %s, boxes.json and report.json" % (written, out / "tiles.3dm"))


if __name__ == "__main__":
    main()
