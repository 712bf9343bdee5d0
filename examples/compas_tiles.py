"""Tile a COMPAS mesh with standard rectangular tiles.

Loads a surface (an OBJ file, or COMPAS's sample hypar: 64 quads of 625 mm), quadrangulates
it unless it already is a mesh of quads of half a tile (as the remesher makes them), matches the quads into tiles (staggered bond by default),
fits them so that the joints come close to the mortar joint (cutting what cannot fit), cuts
them to the surface's boundary, prints the report, and writes a Rhino file (layers
tiles::full, tiles::half, tiles::cuts) and, with --json, the tiles as COMPAS boxes. A surface
it remeshes goes through all three stages in one call (tilepattern.compas.run): on up to 3
quad meshes on surfaces of up to 10,000 quads, keeping the tiles that fit best.

    python examples/compas_tiles.py [MESH.obj] [--units m] [--tile 280x140x15] [--joint 10]
                                    [--bond staggered] [--courses level] [--no-fit]
                                    [--time-limit 10] [--out compas_tiles] [--json]

Needs numpy, compas and rhino3dm (pip install compas rhino3dm) and the TilePattern library
(`cargo build --release --lib` in the repository, or TILEPATTERN_LIB=/path/to/library).
"""

import argparse
import json
import sys
import time
from pathlib import Path

# Run from a source checkout without installing the package.
sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "python"))

import compas  # noqa: E402
from compas.datastructures import Mesh  # noqa: E402

import tilepattern as tp  # noqa: E402
import tilepattern.compas as tpc  # noqa: E402
from tilepattern.rhino import export_3dm  # noqa: E402

#: Mesh units: (model units per millimetre, Rhino unit system).
UNITS = {"m": (0.001, "Meters"), "cm": (0.1, "Centimeters"), "mm": (1.0, "Millimeters")}


def parse_args():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("mesh", nargs="?", help="OBJ surface (triangles, quads or polygons); default: COMPAS's hypar")
    parser.add_argument("--units", choices=sorted(UNITS), default="m", help="units of the mesh coordinates (default m)")
    parser.add_argument("--tile", default="280x140x15", help="tile length x width x thickness in mm (default 280x140x15)")
    parser.add_argument("--joint", type=float, default=10.0, help="mortar joint in mm (default 10)")
    parser.add_argument("--bond", choices=["staggered", "stack", "running"], default="staggered")
    parser.add_argument("--courses", choices=["level", "free"], default="level",
                        help="tiles along level courses (default, fits far better) or either way (the paper's model)")
    parser.add_argument("--no-fit", action="store_true", help="keep the paper's placement (no fit of the joints)")
    parser.add_argument("--time-limit", type=float, default=10.0, help="seconds for the matching (default 10)")
    parser.add_argument("--out", default="compas_tiles", help="output folder (default ./compas_tiles)")
    parser.add_argument("--json", action="store_true", help="also write the tiles as COMPAS boxes (boxes.json)")
    return parser.parse_args()


class Progress:
    """Prints a stage's progress in steps of 10 %; Ctrl-C cancels the stage cleanly."""

    def __init__(self):
        self.shown = None

    def __call__(self, stage, fraction):
        step = (stage, int(10 * fraction))
        if step != self.shown:
            self.shown = step
            print("  %s %3d%%" % (stage, 10 * step[1]), end="\n" if fraction >= 1 else "\r", flush=True)
        return False  # True would cancel

    def done(self):
        """Ends the progress line of a stage that stopped short of 100 % (the fit stops
        when it converges)."""
        if self.shown is not None and self.shown[1] < 10:
            print()
        self.shown = None


def half_tile_quads(mesh, edge, tolerance=0.25):
    """Why ``mesh`` must be remeshed for quads of ``edge`` (half a tile), or None when it
    already is such a quad mesh: every face a quad, 90 % of the edges within ``tolerance``
    of ``edge``. Quads of another size would give tiles over pairs far larger or smaller
    than a tile (COMPAS's hypar: 625 mm quads, 1.25 m "tiles", coverage 0)."""
    sizes = [len(mesh.face_vertices(face)) for face in mesh.faces()]
    if any(n != 4 for n in sizes):
        return "%d of %d faces are not quads" % (sum(n != 4 for n in sizes), len(sizes))
    lengths = [mesh.edge_length(e) for e in mesh.edges()]
    near = sum(abs(length / edge - 1.0) <= tolerance for length in lengths)
    if near < 0.9 * len(lengths):
        lengths.sort()
        return "its quads are not half a tile: median edge %.4g, half a tile %.4g (%d of %d edges within %d %%)" % (
            lengths[len(lengths) // 2], edge, near, len(lengths), round(100 * tolerance))
    return None


def main():
    args = parse_args()
    per_mm, rhino_units = UNITS[args.units]
    length, width, thickness = (float(d) * per_mm for d in args.tile.lower().split("x"))
    joint = args.joint * per_mm

    if args.mesh:
        surface = Mesh.from_obj(args.mesh)
    else:
        surface = Mesh.from_obj(compas.get("hypar.obj"))  # 5 x 5 x 3 in 64 quads, read as metres
    print("surface: %d vertices, %d faces" % (surface.number_of_vertices(), surface.number_of_faces()))

    start = time.perf_counter()
    edge = tp.quad_edge(length, width, joint, courses=args.courses)
    tile = dict(length=length, width=width, thickness=thickness, joint=joint, fit=not args.no_fit, units_per_mm=per_mm)
    pattern_options = dict(bond=args.bond, courses=args.courses, time_limit=args.time_limit)
    reason = half_tile_quads(surface, edge)
    if reason is None:
        print("the surface's quads are half a tile: matched as they are")
        pattern = tpc.match(surface, progress=Progress(), **pattern_options)
        progress = Progress()
        boxes = tpc.tiles(surface, pattern, surface=surface, progress=progress, **tile)
        progress.done()
    else:
        # All three stages in one call, on up to 3 quad meshes (the field's cones placed by
        # other strengths), keeping the tiles that fit best, as the command line's `run`.
        print("remeshing: " + reason)
        progress = Progress()
        quads, pattern, boxes = tpc.run(surface, target_edge=edge, progress=progress, **pattern_options, **tile)
        progress.done()
        tries = boxes.report.get("tries", [])
        kept = " (try %d of %d kept)" % (boxes.report["chosen_try"] + 1, len(tries)) if tries else ""
        print("remeshed into %d quads%s" % (quads.number_of_faces(), kept))

    print(
        "pattern: %d pairs, %d unpaired quads, %d continuous joints; objective %.1f, bound %.1f (%s)"
        % (len(pattern.pairs), len(pattern.unpaired), pattern.continuous_joints, pattern.objective, pattern.bound, pattern.status)
    )
    report = tpc.report(boxes)
    cutting, joints = report["cutting"], report["joints"]
    print("tiles: %d full, %d half, %d cut to the boundary in %d shapes, %d filler pieces; coverage %.3f" % (
        report["full_tiles"], report["half_tiles"], cutting["boundary_tiles"], cutting["boundary_shapes"],
        cutting["filler_tiles"], cutting["coverage"]))
    for name, figures in (("before the fit", joints.get("before_fit")), ("joints", joints)):
        if figures:
            print("%s: %d contacts, gap %.1f..%.1f mm (nominal %.1f), p95 |gap - joint| %.1f mm, %.0f %% within 2 mm, "
                  "%d overlaps (deepest %.1f mm)" % (
                      name, figures["contacts"], figures["min_gap"] / per_mm, figures["max_gap"] / per_mm,
                      figures["joint"] / per_mm, figures["p95_deviation"] / per_mm, 100 * figures["within_2mm"],
                      figures["overlaps"], figures["max_overlap"] / per_mm))
    if "fit" in report:
        fit = report["fit"]
        print("fit: %s after %d steps, %d tiles cut to fit, mean move %.1f mm, largest %.1f mm" % (
            fit["status"], fit["iterations"], joints["fit_cuts"], fit["mean_move"] / per_mm, fit["max_move"] / per_mm))
    for w in report.get("warnings", []):
        print("warning [%s]: %s" % (w["code"], w["message"]))
    print("cut list:")
    for entry in boxes.tiles.cutlist:
        print("  %-4s %-8s x %4d   blank %s" % (entry["label"], entry["kind"], entry["count"], " x ".join("%.0f" % (b / per_mm) for b in entry["blank"])))
    print("done in %.1f s" % (time.perf_counter() - start))

    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    export_3dm(boxes, out / "tiles.3dm", units=rhino_units)
    (out / "report.json").write_text(json.dumps(report, indent=2))
    written = [out / "tiles.3dm", out / "report.json"]
    if args.json:
        compas.json_dump(list(boxes), str(out / "boxes.json"))
        written.append(out / "boxes.json")
    print("wrote " + ", ".join(str(p) for p in written))


if __name__ == "__main__":
    main()
