#!/usr/bin/env python3
"""Shells of the kinds users bring, none of them tuned on: writes them into a folder.

    scripts/shells.py OUT_DIR

Parametric surfaces triangulated on a grid (diagonals alternating), in metres unless the
name says otherwise: a groin vault and a cloister vault (the lower and the upper of two
semicircular barrels crossing, creases along the diagonals), the groin vault again with its
four webs meshed apart (seams that do not match, as a modeller meshes a polysurface face by
face), a catenary barrel in millimetres, an elliptic paraboloid on a rectangle in
centimetres and again as a binary STL triangle soup, a wave, a patch of a torus (both
curvatures), a dome with an oculus, a four-lobed umbrella (creases along its axes), a
corner-supported shell on a triangular plan, a barrel of 64 coarse triangles, a pointed
barrel, and two barrels combined from patches meshed apart (cracks along a seam straight
and curved). README, *Shells nobody tuned on*, has what `tilepattern run` makes of them.
Pure Python, no dependencies; the same files every run.
"""
import math
import os
import struct
import sys


def grid(f, nu, nv, keep=None):
    """Vertices f(u, v) on an nu x nv grid of the unit square, two triangles per cell
    (diagonals alternating), cells whose centre `keep` rejects left out."""
    verts, index = [], {}
    for i in range(nu + 1):
        for j in range(nv + 1):
            index[i, j] = len(verts)
            verts.append(f(i / nu, j / nv))
    faces = []
    for i in range(nu):
        for j in range(nv):
            if keep and not keep((i + 0.5) / nu, (j + 0.5) / nv):
                continue
            a, b, c, d = index[i, j], index[i + 1, j], index[i + 1, j + 1], index[i, j + 1]
            faces += [(a, b, d), (b, c, d)] if (i + j) % 2 else [(a, b, c), (a, c, d)]
    used = sorted({v for t in faces for v in t})
    renumber = {old: new for new, old in enumerate(used)}
    return [verts[v] for v in used], [tuple(renumber[v] for v in t) for t in faces]


def weld(verts, faces):
    """Joins vertices at the same place (six decimals), as a closed grid's seam needs."""
    key, kept, number = {}, [], []
    for p in verts:
        k = tuple(round(c, 6) for c in p)
        if k not in key:
            key[k] = len(kept)
            kept.append(p)
        number.append(key[k])
    return kept, [tuple(number[v] for v in t) for t in faces]


def combined(*patches):
    """Patches in one mesh, each with its own vertices (seams given twice)."""
    verts, faces = [], []
    for vs, fs in patches:
        faces += [tuple(v + len(verts) for v in t) for t in fs]
        verts += vs
    return verts, faces


def fan_web(f, outer_a, outer_b, rows):
    """A triangular web from the plan edge outer_a-outer_b to the centre, in rows parallel to
    that edge (row i has rows - i cells), lifted by f(x, y): as a modeller meshes one face of
    a polysurface on its own."""
    verts, index = [], {}
    for i in range(rows + 1):
        cells = rows - i
        for j in range(cells + 1):
            s = j / cells if cells else 0.5
            x = (1 - i / rows) * (outer_a[0] + (outer_b[0] - outer_a[0]) * s)
            y = (1 - i / rows) * (outer_a[1] + (outer_b[1] - outer_a[1]) * s)
            index[i, j] = len(verts)
            verts.append((x, y, f(x, y)))
    faces = []
    for i in range(rows):
        for j in range(rows - i):
            faces.append((index[i, j], index[i, j + 1], index[i + 1, j]))
            if j < rows - i - 1:
                faces.append((index[i, j + 1], index[i + 1, j + 1], index[i + 1, j]))
    return verts, faces


def write_obj(path, mesh, scale=1.0):
    verts, faces = mesh
    with open(path, "w") as out:
        for p in verts:
            out.write("v %.6f %.6f %.6f\n" % tuple(c * scale for c in p))
        for t in faces:
            out.write("f %d %d %d\n" % tuple(v + 1 for v in t))


def write_stl_soup(path, mesh):
    verts, faces = mesh
    with open(path, "wb") as out:
        out.write(b"shells.py".ljust(80, b" "))
        out.write(struct.pack("<I", len(faces)))
        for t in faces:
            out.write(struct.pack("<3f", 0.0, 0.0, 0.0))
            for v in t:
                out.write(struct.pack("<3f", *verts[v]))
            out.write(b"\0\0")


def groin(u, v):
    # The lower of two semicircular barrels crossing: each web follows the barrel running
    # into it, the groins are salient, the vault stands on its corners.
    x, y = 6 * u - 3, 6 * v - 3
    across = y if abs(x) >= abs(y) else x
    return (x, y, math.sqrt(max(0.0, 9.0 - across * across)))


def cloister(u, v):
    # The upper of the two barrels (a domical vault): four webs rising from walls on all
    # four sides, meeting in valleys along the diagonals.
    x, y = 6 * u - 3, 6 * v - 3
    across = x if abs(x) >= abs(y) else y
    return (x, y, math.sqrt(max(0.0, 9.0 - across * across)))


def catenary(u, v):
    a = 1.2
    x = 5 * u - 2.5
    top = a * math.cosh(2.5 / a)
    return (x, 8 * v, (top - a * math.cosh(x / a)) * 2.5 / (top - a))


def paraboloid(u, v):
    x, y = 7 * u - 3.5, 4.5 * v - 2.25
    return (x, y, 1.6 * (1 - (x / 3.5) ** 2) * (1 - (y / 2.25) ** 2))


def wave(u, v):
    return (10 * u, 4 * v, 0.6 * math.sin(2 * math.pi * u) * math.sin(math.pi * v)
            + 0.8 * math.sin(math.pi * v))


def torus(u, v):
    around, tube = -1.0 + 2.0 * u, 0.3 + 2.3 * v
    ring = 4 + 1.5 * math.cos(tube)
    return (ring * math.cos(around), ring * math.sin(around), 1.5 * math.sin(tube))


def oculus(u, v):
    polar, around = math.radians(15 + 65 * v), 2 * math.pi * u
    return (4 * math.sin(polar) * math.cos(around), 4 * math.sin(polar) * math.sin(around),
            4 * math.cos(polar))


def umbrella(u, v):
    x, y = 8 * u - 4, 8 * v - 4
    return (x, y, 0.12 * abs(x * y))


def triangular(u, v):
    return (9 * u - 4.5, 7 * v, 2.2 * math.sin(math.pi * u) * math.sin(math.pi * min(1.0, 1.05 * v))
            + 0.3 * math.sin(3 * u + 2 * v))


def on_triangular_plan(u, v):
    return v < 0.95 * (1 - abs(2 * u - 1)) + 0.05 * math.sin(6 * u)


def coarse_barrel(u, v):
    return (2 * math.cos(math.pi * u), 6 * v, 2 * math.sin(math.pi * u))


def pointed(u, v):
    # Two arcs of radius 3 from springings 3 m apart, meeting at the apex 2.6 m up.
    s = 2 * u - 1
    angle = math.radians(60) * (1 - abs(s))
    x = 1.5 - 3 * math.cos(angle) if s < 0 else -1.5 + 3 * math.cos(angle)
    return (x, 5 * v, 3 * math.sin(angle))


def barrel(u, v):
    return (2 * math.cos(math.pi * u), 6 * v, 2.2 * math.sin(math.pi * u))


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    path = lambda name: os.path.join(out, name)
    write_obj(path("groin.obj"), grid(groin, 80, 80))
    write_obj(path("cloister.obj"), grid(cloister, 80, 80))
    # The groin vault's four webs meshed apart, 40 and 47 rows: their seams along the groins
    # do not match.
    on_plan = lambda x, y: groin((x + 3) / 6, (y + 3) / 6)[2]
    write_obj(path("groin_webs.obj"), combined(
        fan_web(on_plan, (3, -3), (3, 3), 40), fan_web(on_plan, (3, 3), (-3, 3), 47),
        fan_web(on_plan, (-3, 3), (-3, -3), 40), fan_web(on_plan, (-3, -3), (3, -3), 47)))
    write_obj(path("catbarrel_mm.obj"), grid(catenary, 60, 90), scale=1000)
    write_obj(path("ellpara_cm.obj"), grid(paraboloid, 90, 60), scale=100)
    write_stl_soup(path("ellpara_soup.stl"), grid(paraboloid, 70, 45))
    write_obj(path("wave.obj"), grid(wave, 110, 45))
    write_obj(path("torus_patch.obj"), grid(torus, 100, 50))
    write_obj(path("oculus.obj"), weld(*grid(oculus, 160, 40)))
    write_obj(path("umbrella.obj"), grid(umbrella, 80, 80))
    write_obj(path("triangle_shell.obj"), grid(triangular, 100, 80, keep=on_triangular_plan))
    write_obj(path("coarse_barrel.obj"), grid(coarse_barrel, 8, 4))
    write_obj(path("gothic.obj"), grid(pointed, 70, 60))
    # Halves meshed apart: the crown seam cut into 60 and 45, the arch seam into 40 and 29.
    write_obj(path("crack.obj"), combined(grid(lambda u, v: barrel(0.5 * u, v), 30, 60),
                                          grid(lambda u, v: barrel(0.5 + 0.5 * u, v), 30, 45)))
    write_obj(path("crack_arch.obj"), combined(grid(lambda u, v: barrel(u, 0.5 * v), 40, 30),
                                               grid(lambda u, v: barrel(u, 0.5 + 0.5 * v), 29, 30)))


if __name__ == "__main__":
    main()
