#!/usr/bin/env python3
"""Joints between tiles, measured from a tiles.obj alone (independently of the library).

Every object of the OBJ is one tile (a box, or the prisms of a cut tile's pieces). Its plane
is the least-squares plane of its vertices and its outline the convex hull of its vertices
projected onto that plane (top and bottom project onto each other). Two tiles are neighbours
when their outlines come within `--reach` of each other (default: three joints); for each
pair both outlines are projected onto their mean plane and separated by separating axes:
positive = the joint's width, negative = how deep they overlap.

    scripts/check-joints.py DIR/tiles.obj --joint 0.01 [--units-per-mm 0.001] [--json OUT]

Prints pairs, overlapping pairs (deeper than --overlap, default 1 mm), the deepest overlap,
p95 |gap - joint|, the share of pairs within 2 and 5 mm. Exit code 1 when some pair overlaps
deeper than --overlap. Pure Python (no numpy), for runs of a few thousand tiles.

With `--surface SURFACE.obj` (the input surface, same units) it also measures how each tile
lies on the surface, which joints alone do not show (a rigid tile bridging a crease meets its
neighbours well and stands off the surface): the corners of the tile's face nearest the
surface, their signed distances to it, and the spread of those (largest minus smallest; a
flat tile on a sphere of radius R spreads by about (L^2 + W^2) / 8R). Prints the tiles that
spread by more than --lift (default 5 mm) and the largest spread.

With `--up X,Y,Z` it also measures which way the whole tiles run where the surface slopes
(by more than 20 degrees from level): a tile *climbs* when its length runs within 45 degrees
of the slope's direction instead of along the level. Prints the sloped tiles and the share
that climb (`--courses level` asks for none; a mason lays a vault's courses level).
"""
import argparse
import json
import math
import sys


def read_objects(path):
    objects, current, verts = [], None, []
    with open(path) as f:
        for line in f:
            if line.startswith("o "):
                current = {"name": line.split()[1], "v": []}
                objects.append(current)
            elif line.startswith("v "):
                p = tuple(float(x) for x in line.split()[1:4])
                verts.append(p)
                if current is not None:
                    current["v"].append(p)
    return objects


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a):
    return math.sqrt(dot(a, a))


def unit(a):
    n = norm(a)
    return (a[0] / n, a[1] / n, a[2] / n)


def plane(points):
    """Centroid and unit normal of the least-squares plane (smallest principal axis).

    The eigenvectors of the 3 x 3 scatter matrix by cyclic Jacobi rotations, which converge
    whatever the spread: power iteration stalls on a long, narrow piece (a 275 x 44 mm sliver
    left its normal 15 degrees off after 200 steps, and a pair at a right angle to it was
    then projected onto the wrong plane)."""
    n = len(points)
    c = tuple(sum(p[k] for p in points) / n for k in range(3))
    m = [[0.0] * 3 for _ in range(3)]
    for p in points:
        d = sub(p, c)
        for i in range(3):
            for j in range(3):
                m[i][j] += d[i] * d[j]
    v = [[1.0 if i == j else 0.0 for j in range(3)] for i in range(3)]
    for _ in range(50):
        off = m[0][1] ** 2 + m[0][2] ** 2 + m[1][2] ** 2
        if off <= 1e-30 * (m[0][0] ** 2 + m[1][1] ** 2 + m[2][2] ** 2) or off == 0.0:
            break
        for p_, q in ((0, 1), (0, 2), (1, 2)):
            if m[p_][q] == 0.0:
                continue
            theta = (m[q][q] - m[p_][p_]) / (2.0 * m[p_][q])
            t = (1.0 if theta >= 0 else -1.0) / (abs(theta) + math.sqrt(theta * theta + 1.0))
            cs = 1.0 / math.sqrt(t * t + 1.0)
            sn = t * cs
            for k in range(3):
                mkp, mkq = m[k][p_], m[k][q]
                m[k][p_], m[k][q] = cs * mkp - sn * mkq, sn * mkp + cs * mkq
            for k in range(3):
                mpk, mqk = m[p_][k], m[q][k]
                m[p_][k], m[q][k] = cs * mpk - sn * mqk, sn * mpk + cs * mqk
            for k in range(3):
                vkp, vkq = v[k][p_], v[k][q]
                v[k][p_], v[k][q] = cs * vkp - sn * vkq, sn * vkp + cs * vkq
    smallest = min(range(3), key=lambda i: m[i][i])
    return c, unit(tuple(v[k][smallest] for k in range(3)))


def hull(points):
    pts = sorted(set(points))
    if len(pts) < 3:
        return pts

    def turn(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower, upper = [], []
    for p in pts:
        while len(lower) >= 2 and turn(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and turn(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return lower[:-1] + upper[:-1]


def separation(p, q):
    best = -math.inf
    for a, b in ((p, q), (q, p)):
        for i in range(len(a)):
            e = (a[(i + 1) % len(a)][0] - a[i][0], a[(i + 1) % len(a)][1] - a[i][1])
            length = math.hypot(*e)
            if length == 0:
                continue
            n = (e[1] / length, -e[0] / length)
            reach = max(n[0] * v[0] + n[1] * v[1] for v in a)
            start = min(n[0] * v[0] + n[1] * v[1] for v in b)
            best = max(best, start - reach)
    return best


def read_mesh(path):
    verts, faces = [], []
    with open(path) as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                verts.append(tuple(float(x) for x in parts[1:4]))
            elif parts[0] == "f":
                ids = [int(x.split("/")[0]) for x in parts[1:]]
                ids = [i - 1 if i > 0 else len(verts) + i for i in ids]
                for k in range(1, len(ids) - 1):
                    faces.append((verts[ids[0]], verts[ids[k]], verts[ids[k + 1]]))
    return faces


def closest_on_triangle(p, a, b, c):
    """The point of triangle abc closest to p (Ericson, Real-Time Collision Detection, 5.1.5)."""
    ab, ac, ap = sub(b, a), sub(c, a), sub(p, a)
    d1, d2 = dot(ab, ap), dot(ac, ap)
    if d1 <= 0 and d2 <= 0:
        return a
    bp = sub(p, b)
    d3, d4 = dot(ab, bp), dot(ac, bp)
    if d3 >= 0 and d4 <= d3:
        return b
    vc = d1 * d4 - d3 * d2
    if vc <= 0 and d1 >= 0 and d3 <= 0:
        t = d1 / (d1 - d3)
        return tuple(a[k] + t * ab[k] for k in range(3))
    cp = sub(p, c)
    d5, d6 = dot(ab, cp), dot(ac, cp)
    if d6 >= 0 and d5 <= d6:
        return c
    vb = d5 * d2 - d1 * d6
    if vb <= 0 and d2 >= 0 and d6 <= 0:
        t = d2 / (d2 - d6)
        return tuple(a[k] + t * ac[k] for k in range(3))
    va = d3 * d6 - d5 * d4
    if va <= 0 and (d4 - d3) >= 0 and (d5 - d6) >= 0:
        t = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        return tuple(b[k] + t * (c[k] - b[k]) for k in range(3))
    denom = 1.0 / (va + vb + vc)
    v, w = vb * denom, vc * denom
    return tuple(a[k] + ab[k] * v + ac[k] * w for k in range(3))


class Surface:
    """Triangles in a grid of cubes, for signed distances of points near the surface."""

    def __init__(self, triangles, cell):
        self.triangles, self.cell, self.grid = triangles, cell, {}
        for i, tri in enumerate(triangles):
            lo = [int(math.floor(min(p[k] for p in tri) / cell)) for k in range(3)]
            hi = [int(math.floor(max(p[k] for p in tri) / cell)) for k in range(3)]
            for x in range(lo[0], hi[0] + 1):
                for y in range(lo[1], hi[1] + 1):
                    for z in range(lo[2], hi[2] + 1):
                        self.grid.setdefault((x, y, z), []).append(i)

    def signed_distance(self, p):
        """Distance to the nearest triangle within a cell, positive on its normal's side;
        None when no triangle is that near."""
        k = [int(math.floor(p[i] / self.cell)) for i in range(3)]
        best = None
        seen = set()
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for i in self.grid.get((k[0] + dx, k[1] + dy, k[2] + dz), ()):
                        if i in seen:
                            continue
                        seen.add(i)
                        a, b, c = self.triangles[i]
                        q = closest_on_triangle(p, a, b, c)
                        d = norm(sub(p, q))
                        if best is None or d < best[0]:
                            n = cross(sub(b, a), sub(c, a))
                            best = (d, 1.0 if dot(sub(p, q), n) >= 0 else -1.0)
        return None if best is None or best[0] > self.cell else best[0] * best[1]


def lifts(tiles, surface):
    """Per tile: the spread of the signed distances of its face nearest the surface."""
    out = []
    for t in tiles:
        # The tile's two faces are its vertices below and above its own mid-plane.
        sides = ([], [])
        for p in t["v"]:
            sides[dot(sub(p, t["c"]), t["n"]) > 0].append(p)
        faces = []
        for side in sides:
            d = [surface.signed_distance(p) for p in side]
            d = [x for x in d if x is not None]
            if d:
                faces.append((sum(abs(x) for x in d) / len(d), max(d) - min(d)))
        out.append(min(faces)[1] if faces else None)
    return out


def climbing(tiles, up):
    """Whole tiles (a rectangle in their own plane, longer than wide) on slopes steeper than
    20 degrees, and how many of them run up the slope (length within 45 degrees of it)."""
    sloped = climbs = 0
    for t in tiles:
        n = t["n"]
        slope = tuple(up[k] - n[k] * dot(n, up) for k in range(3))
        if norm(slope) < math.sin(math.radians(20)):
            continue
        e1 = unit(cross(n, (1.0, 0.0, 0.0)) if abs(n[0]) < 0.9 else cross(n, (0.0, 1.0, 0.0)))
        e2 = cross(n, e1)
        outline = []
        for q in hull([(dot(sub(p, t["c"]), e1), dot(sub(p, t["c"]), e2)) for p in t["v"]]):
            # Top and bottom corners project onto each other up to rounding: one corner.
            if not outline or math.hypot(q[0] - outline[-1][0], q[1] - outline[-1][1]) > 0.02 * t["r"]:
                outline.append(q)
        if len(outline) > 1 and math.hypot(outline[0][0] - outline[-1][0], outline[0][1] - outline[-1][1]) <= 0.02 * t["r"]:
            outline.pop()
        if len(outline) != 4:
            continue
        sides = [(outline[(i + 1) % 4][0] - outline[i][0], outline[(i + 1) % 4][1] - outline[i][1]) for i in range(4)]
        lengths = [math.hypot(*e) for e in sides]
        if max(lengths) < 1.5 * min(lengths):
            continue
        e = sides[lengths.index(max(lengths))]
        along = unit(tuple(e1[k] * e[0] + e2[k] * e[1] for k in range(3)))
        sloped += 1
        if abs(dot(along, unit(slope))) > math.cos(math.radians(45)):
            climbs += 1
    return {"sloped_tiles": sloped, "climbing_tiles": climbs, "climbing_share": climbs / max(1, sloped)}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("obj")
    ap.add_argument("--joint", type=float, required=True, help="nominal joint in model units")
    ap.add_argument("--units-per-mm", type=float, default=0.001)
    ap.add_argument("--reach", type=float, help="neighbours within this separation (default 3 joints)")
    ap.add_argument("--overlap", type=float, help="overlaps deeper than this fail (default 1 mm)")
    ap.add_argument("--json", help="write the figures here")
    ap.add_argument("--surface", help="the input surface (OBJ): measure how the tiles lie on it")
    ap.add_argument("--lift", type=float, help="tiles spreading more than this off the surface are counted (default 5 mm)")
    ap.add_argument("--up", help="up direction X,Y,Z: count the whole tiles on slopes whose length climbs")
    args = ap.parse_args()
    mm = args.units_per_mm
    reach = args.reach if args.reach is not None else 3 * args.joint
    limit = args.overlap if args.overlap is not None else 1.0 * mm
    tiles = []
    for o in read_objects(args.obj):
        c, n = plane(o["v"])
        radius = max(norm(sub(p, c)) for p in o["v"])
        tiles.append({"name": o["name"], "v": o["v"], "c": c, "n": n, "r": radius})
    cell = 2 * max(t["r"] for t in tiles) + reach
    grid = {}
    for i, t in enumerate(tiles):
        grid.setdefault(tuple(int(math.floor(x / cell)) for x in t["c"]), []).append(i)
    gaps = []
    for i, t in enumerate(tiles):
        k = tuple(int(math.floor(x / cell)) for x in t["c"])
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for j in grid.get((k[0] + dx, k[1] + dy, k[2] + dz), []):
                        if j <= i:
                            continue
                        u = tiles[j]
                        if norm(sub(t["c"], u["c"])) > t["r"] + u["r"] + reach:
                            continue
                        n = t["n"] if dot(t["n"], u["n"]) >= 0 else tuple(-x for x in t["n"])
                        m = unit(tuple(n[x] + u["n"][x] * (1 if dot(n, u["n"]) >= 0 else -1) for x in range(3)))
                        o = tuple((t["c"][x] + u["c"][x]) / 2 for x in range(3))
                        e1 = unit(cross(m, (1.0, 0.0, 0.0)) if abs(m[0]) < 0.9 else cross(m, (0.0, 1.0, 0.0)))
                        e2 = cross(m, e1)
                        proj = lambda pts: hull([(dot(sub(p, o), e1), dot(sub(p, o), e2)) for p in pts])
                        g = separation(proj(t["v"]), proj(u["v"]))
                        if g < reach:
                            gaps.append((i, j, g))
    deviations = sorted(abs(g - args.joint) for _, _, g in gaps)
    p95 = deviations[max(0, math.ceil(len(deviations) * 0.95) - 1)] if deviations else 0.0
    deep = [(tiles[i]["name"], tiles[j]["name"], g) for i, j, g in gaps if g < -limit]
    figures = {
        "tiles": len(tiles),
        "pairs": len(gaps),
        "overlapping": sum(1 for _, _, g in gaps if g < 0),
        "overlapping_beyond_limit": len(deep),
        "deepest_overlap_mm": max([0.0] + [-g for _, _, g in gaps]) / mm,
        "p95_deviation_mm": p95 / mm,
        "within_2mm": sum(1 for d in deviations if d <= 2 * mm) / max(1, len(deviations)),
        "within_5mm": sum(1 for d in deviations if d <= 5 * mm) / max(1, len(deviations)),
    }
    if args.surface:
        lift = args.lift if args.lift is not None else 5.0 * mm
        cell = max(max(t["r"] for t in tiles), 4 * lift)
        spread = [x for x in lifts(tiles, Surface(read_mesh(args.surface), cell)) if x is not None]
        figures["tiles_lifted"] = sum(1 for x in spread if x > lift)
        figures["largest_lift_mm"] = max(spread, default=0.0) / mm
    if args.up:
        figures.update(climbing(tiles, unit(tuple(float(x) for x in args.up.split(",")))))
    print(json.dumps(figures))
    for a, b, g in deep[:10]:
        print("overlap %s %s %.2f mm" % (a, b, -g / mm), file=sys.stderr)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(figures, f, indent=1)
    return 1 if deep else 0


if __name__ == "__main__":
    sys.exit(main())
