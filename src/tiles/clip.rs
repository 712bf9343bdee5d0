//! Boundary tiles: a tile that crosses the input surface's boundary (its outer edge or an
//! opening) is cut to it.
//!
//! The paper ends with "irregular tiles at the boundary" (Figures 7-8) but does not say which
//! part of each tile to keep. Here the cut is made on the tile's own face: the boundary edges
//! of the surface near the tile are projected into the tile's frame, and the tile's rectangle
//! `[-L/2, L/2] x [-W/2, W/2]` is clipped to the side of them where the surface is. The kept
//! part is a set of loops in the tile's frame (outer loops counter-clockwise, holes
//! clockwise), in model units: the outline a mason marks on the tile before cutting it.

use std::collections::HashMap;

use nalgebra::{Point3, Vector3};

use super::Tile;
pub use crate::geom::polygon::{Point2, signed_area};
use crate::geom::polygon::{clip_to_convex, cross, dist, point_segment, sub};
use crate::geom::{Bvh, HashGrid, closest};
use crate::mesh::{PolyMesh, Topology, crease};

/// The part of a tile kept after cutting.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Cut {
    /// Loops of the kept region in the tile's frame: outer loops counter-clockwise, holes
    /// clockwise.
    pub loops: Vec<Vec<Point2>>,
    /// Kept area over the tile's face area.
    pub kept_fraction: f64,
}

impl Cut {
    /// Kept area in model units squared (holes subtract).
    pub fn area(&self) -> f64 {
        self.loops.iter().map(|l| signed_area(l)).sum()
    }

    /// Length of all loops.
    pub fn perimeter(&self) -> f64 {
        self.loops
            .iter()
            .map(|l| {
                (0..l.len())
                    .map(|i| dist(l[i], l[(i + 1) % l.len()]))
                    .sum::<f64>()
            })
            .sum()
    }

    /// A width of the kept region, `2 area / perimeter`: the width of a long strip, half the
    /// side of a square. Below a minimum the piece is a sliver nobody can cut or lay.
    pub fn kept_width(&self) -> f64 {
        let perimeter = self.perimeter();
        if perimeter > 0.0 {
            2.0 * self.area() / perimeter
        } else {
            0.0
        }
    }
}

/// What clipping did to one tile.
#[derive(Debug, Clone, PartialEq)]
pub enum Clipped {
    /// The tile lies on the surface (it loses less than the tolerance).
    Whole,
    /// The tile crosses the boundary and keeps this part.
    Cut(Cut),
    /// Nothing of the tile lies on the surface.
    Outside,
}

/// One boundary edge of the reference surface, directed so that the surface lies on its left
/// when seen along the normal of its face.
#[derive(Debug, Clone, Copy)]
struct Segment {
    a: Point3<f64>,
    b: Point3<f64>,
    /// Unit normal of the face the edge belongs to.
    normal: Vector3<f64>,
    /// Vertex indices of its start and end.
    from: usize,
    to: usize,
    /// The sheet of its face: a tile is cut by the edges of the sheet it lies on.
    sheet: usize,
}

/// The boundary of a reference surface, indexed for queries near a point, and its faces, to
/// tell a tile far from the boundary on the surface from one far from the surface.
#[derive(Debug, Clone)]
pub struct SurfaceBoundary {
    segments: Vec<Segment>,
    grid: HashGrid,
    /// Each face as its corners and unit normal.
    faces: Vec<(Vec<Point3<f64>>, Vector3<f64>)>,
    /// The faces in a bounding volume hierarchy: the closest one, those within a radius.
    face_bvh: Bvh,
    /// Each face's sheet: the pieces of the surface once cut open along its creases.
    sheet: Vec<usize>,
}

impl SurfaceBoundary {
    /// Collects the boundary edges of `surface` (outer edge and openings) in a grid of cells of
    /// side `cell` (about a tile's size): the surface as one sheet, creases or not.
    pub fn new(surface: &PolyMesh, cell: f64) -> Self {
        Self::build(surface, None, cell, 0.0)
    }

    /// [`Self::new`], with the creases that part the surface into sheets
    /// ([`crease::split_at_creases`]) as boundary edges too, of both sheets, each moved
    /// `seam_gap` into its own sheet: half a joint, so that the tiles of two webs cut to
    /// their groin leave a joint between them. A tile is cut by the edges of its own sheet.
    pub fn with_creases(surface: &PolyMesh, cell: f64, seam_gap: f64) -> Self {
        Self::build(surface, crease::split_at_creases(surface), cell, seam_gap)
    }

    fn build(surface: &PolyMesh, sheets: Option<crease::Sheets>, cell: f64, seam_gap: f64) -> Self {
        let surface = sheets.as_ref().map_or(surface, |s| &s.mesh);
        let topology = Topology::new(surface).expect("a PolyMesh is manifold by construction");
        let (sheet, seam_moves) = match &sheets {
            Some(sheets) => (
                sheets.sheet.clone(),
                seam_moves(surface, &topology, &sheets.seams, seam_gap),
            ),
            None => (topology.face_pieces().0, HashMap::new()),
        };
        let at =
            |v: usize| surface.positions()[v] + seam_moves.get(&v).copied().unwrap_or_default();
        let mut segments = Vec::new();
        for (f, face) in surface.faces().iter().enumerate() {
            let normal = surface
                .face_area_vector(f)
                .try_normalize(0.0)
                .unwrap_or_else(Vector3::z);
            for (i, &e) in topology.face_edges(f).iter().enumerate() {
                if topology.edges()[e].is_boundary() {
                    let (from, to) = (face[i], face[(i + 1) % face.len()]);
                    segments.push(Segment {
                        a: at(from),
                        b: at(to),
                        normal,
                        from,
                        to,
                        sheet: sheet[f],
                    });
                }
            }
        }
        let grid = HashGrid::of_points(cell, segments.iter().map(|s| [s.a, s.b]));
        let faces: Vec<(Vec<Point3<f64>>, Vector3<f64>)> = (0..surface.face_count())
            .map(|f| {
                (
                    surface.face_points(f).collect(),
                    surface
                        .face_area_vector(f)
                        .try_normalize(0.0)
                        .unwrap_or_else(Vector3::z),
                )
            })
            .collect();
        let coords: Vec<Vector3<f64>> = surface.positions().iter().map(|p| p.coords).collect();
        Self {
            segments,
            grid,
            faces,
            face_bvh: Bvh::of_simplices(&coords, surface.faces()),
            sheet,
        }
    }

    /// The sheet face `f` of the surface lies on (its piece when no crease parts it).
    pub(crate) fn face_sheet(&self, f: usize) -> usize {
        self.sheet[f]
    }

    /// The sheet of the face closest to `p` within `radius`.
    pub(crate) fn sheet_at(&self, p: &Point3<f64>, radius: f64) -> Option<usize> {
        self.closest_face(p, radius, None)
            .map(|(f, _)| self.sheet[f])
    }

    /// The sheet `tile` lies on: of the faces within `radius` of its centre and within
    /// [`SHEET_SLACK`] of its half width of the closest, one of those facing most as the tile
    /// does. At a crease the centre of a tile laid on one web can be closer to the other web
    /// by a millimetre (a groin vault's corner, where the webs meet at a sharp angle): cut by
    /// that web's edges, the tile kept the part that runs on past the groin, 100 mm off the
    /// surface.
    pub(crate) fn sheet_of(&self, tile: &Tile, radius: f64) -> Option<usize> {
        let p = &tile.frame.origin;
        // The closest face by a nearest query, then only the faces near enough to it to be
        // chosen, in index order. (Gathering every face within `radius` first cost thousands
        // of faces per tile on a fine input: a million triangles, 8 mm edges, took 13 s of
        // the tiles' 18.)
        let (_, foot) = self.closest_face(p, radius, None)?;
        let slack = (foot - p).norm() + SHEET_SLACK * tile.size[1] / 2.0;
        let near: Vec<(f64, usize)> = self
            .face_bvh
            .within(&p.coords, slack.min(radius))
            .into_iter()
            .filter_map(|f| Some(((self.closest_on_face(f, p)? - p).norm(), f)))
            .filter(|&(d, _)| d <= radius && d <= slack)
            .collect();
        let mut best: Option<(f64, f64, usize)> = None;
        for &(d, f) in &near {
            let facing = self.faces[f].1.dot(&tile.frame.z).abs();
            if best.is_none_or(|(bf, bd, _)| facing > bf + 1e-9 || (facing > bf - 1e-9 && d < bd)) {
                best = Some((facing, d, f));
            }
        }
        best.map(|(_, _, f)| self.sheet[f])
    }

    /// Boundary edges within `radius` of `p`, in index order.
    fn near(&self, p: &Point3<f64>, radius: f64) -> Vec<usize> {
        let mut found = self.grid.near(p, radius);
        found.retain(|&s| {
            (closest::on_segment(
                &p.coords,
                &self.segments[s].a.coords,
                &self.segments[s].b.coords,
            ) - p.coords)
                .norm()
                <= radius
        });
        found
    }

    /// How far the farthest of `points` lies from the surface (of `sheet` when given), or
    /// `radius` where no surface lies within it: a tile's lift, with `points` its bottom
    /// face's corners ([`super::lifts`]).
    pub(crate) fn lift(&self, points: &[Point3<f64>], radius: f64, sheet: Option<usize>) -> f64 {
        points
            .iter()
            .map(|p| {
                self.closest_face(p, radius, sheet)
                    .map_or(radius, |(_, q)| (q - p).norm())
            })
            .fold(0.0, f64::max)
    }

    /// Whether some face of the surface passes within `radius` of `p`.
    fn touches(&self, p: &Point3<f64>, radius: f64) -> bool {
        self.closest(p, radius).is_some()
    }

    /// The point of the surface closest to `p`, if one lies within `radius`.
    pub fn closest(&self, p: &Point3<f64>, radius: f64) -> Option<Point3<f64>> {
        self.closest_face(p, radius, None).map(|(_, q)| q)
    }

    /// [`Self::closest`] on one sheet ([`Self::sheet_at`]).
    pub(crate) fn closest_on(
        &self,
        p: &Point3<f64>,
        radius: f64,
        sheet: usize,
    ) -> Option<Point3<f64>> {
        self.closest_face(p, radius, Some(sheet)).map(|(_, q)| q)
    }

    /// The face closest to `p` (of `sheet` when given) and its point closest to `p`, if one
    /// lies within `radius`.
    fn closest_face(
        &self,
        p: &Point3<f64>,
        radius: f64,
        sheet: Option<usize>,
    ) -> Option<(usize, Point3<f64>)> {
        // Faces of other sheets are infinitely far; ties go to the smaller index.
        let (f, d2, q) =
            self.face_bvh
                .nearest(&p.coords, |f| match self.closest_on_face(f, p) {
                    Some(q) if sheet.is_none_or(|s| self.sheet[f] == s) => {
                        ((q - p).norm_squared(), q.coords)
                    }
                    _ => (f64::INFINITY, p.coords),
                })?;
        (d2 <= radius * radius).then(|| (f, Point3::from(q)))
    }

    /// The point of face `f` closest to `p`: over the face (inside every edge's side plane)
    /// its foot on the face's plane, beside it the nearest point of its nearest edge.
    fn closest_on_face(&self, f: usize, p: &Point3<f64>) -> Option<Point3<f64>> {
        let (corners, normal) = &self.faces[f];
        let n = corners.len();
        let over = (0..n).all(|i| {
            (corners[(i + 1) % n] - corners[i])
                .cross(&(p - corners[i]))
                .dot(normal)
                >= 0.0
        });
        if over {
            return Some(p - normal * (p - corners[0]).dot(normal));
        }
        (0..n)
            .map(|i| {
                Point3::from(closest::on_segment(
                    &p.coords,
                    &corners[i].coords,
                    &corners[(i + 1) % n].coords,
                ))
            })
            .min_by(|a, b| (a - p).norm_squared().total_cmp(&(b - p).norm_squared()))
    }

    /// Cuts `tile` to the surface. A tile the boundary enters by no more than `tolerance`
    /// from its edges stays whole.
    pub fn clip(&self, tile: &Tile, tolerance: f64) -> Clipped {
        let (hx, hy) = (tile.size[0] / 2.0, tile.size[1] / 2.0);
        let rect = Rect { hx, hy };
        // Far enough that a boundary chain leaving this ball cannot come back over the tile,
        // close enough not to pick up another part of the shell above or below it.
        let reach = hx.hypot(hy) + hy;
        let mut near = self.near(&tile.frame.origin, reach);
        let sheet = self.sheet_of(tile, reach);
        near.retain(|&s| {
            sheet.is_none_or(|own| self.segments[s].sheet == own)
                && [self.segments[s].a, self.segments[s].b]
                    .iter()
                    .any(|p| tile.frame.to_local(p).z.abs() <= hx)
        });
        // Whatever is kept must lie on the surface: the side tests below see the boundary in
        // the tile's plane only, and where the surface turns steeply away at its edge (a
        // wall, a tube's crumpled end) a tile flat beyond the edge passes them. A tile tangent
        // to a surface curved to a radius of a tile length stands off by a sixth of its width
        // at its corners; half a width off is no tile of this surface.
        let lies_on = |loops: &[Vec<Point2>]| {
            let points: Vec<Point3<f64>> = loops
                .iter()
                .flatten()
                .map(|c| tile.frame.origin + tile.frame.x * c[0] + tile.frame.y * c[1])
                .collect();
            self.lift(&points, reach, sheet) <= hy
        };
        if near.is_empty() {
            return if self.touches(&tile.frame.origin, hy) && lies_on(&[rect.corners().to_vec()]) {
                Clipped::Whole
            } else {
                Clipped::Outside
            };
        }
        let chains = self.chains(&near, tile);
        let mut loops: Vec<Vec<Point2>> = Vec::new();
        let mut pieces: Vec<Vec<Point2>> = Vec::new();
        for chain in &chains {
            if chain.closed {
                // Start the ring outside the rectangle so that no piece wraps around its start.
                match chain.points.iter().position(|p| !rect.contains(*p)) {
                    None => loops.push(chain.points.clone()),
                    Some(outside) => {
                        let mut ring = chain.points[outside..].to_vec();
                        ring.extend_from_slice(&chain.points[..=outside]);
                        pieces.extend(rect.clip_polyline(&ring));
                    }
                }
            } else {
                pieces.extend(rect.clip_polyline(&chain.points));
            }
        }
        pieces.retain(|p| p.len() >= 2 && rect.on_border(p[0]) && rect.on_border(p[p.len() - 1]));
        let shallow = loops.is_empty() && pieces.iter().all(|p| rect.depth(p) <= tolerance);
        if pieces.is_empty() {
            if inside(&chains, rect.corners()[0]) {
                loops.insert(0, rect.corners().to_vec());
            }
        } else {
            loops.splice(0..0, rect.join(pieces));
        }
        let full = 4.0 * hx * hy;
        let area: f64 = loops.iter().map(|l| signed_area(l)).sum();
        if area <= tolerance * tile.size[0] + full * 1e-9 || !lies_on(&loops) {
            // Nothing, or a strip thinner than the tolerance along the boundary, or off the
            // surface.
            Clipped::Outside
        } else if shallow && area >= full / 2.0 {
            // The boundary only grazes the tile, and the surface is on the tile's side of it.
            Clipped::Whole
        } else {
            Clipped::Cut(Cut {
                loops,
                kept_fraction: (area / full).min(1.0),
            })
        }
    }

    /// The near boundary edges as chains of points in the tile's frame, oriented so that
    /// the surface lies on their left seen from the tile's `+z`.
    fn chains(&self, near: &[usize], tile: &Tile) -> Vec<Chain> {
        let local = |p: &Point3<f64>| {
            let v = tile.frame.to_local(p);
            [v.x, v.y]
        };
        // Near edges leaving each vertex, and vertices some near edge enters. A vertex where
        // two openings touch has two of each; any pairing of them traces the same region.
        let mut leaving: HashMap<usize, Vec<usize>> = HashMap::new();
        let mut entered: HashMap<usize, usize> = HashMap::new();
        for (i, &s) in near.iter().enumerate() {
            leaving.entry(self.segments[s].from).or_default().push(i);
            *entered.entry(self.segments[s].to).or_default() += 1;
        }
        // The surface's orientation against the tile's: the boundary keeps the surface on
        // its left seen along the surface's own normals.
        let facing: f64 = near
            .iter()
            .map(|&s| {
                self.segments[s].normal.dot(&tile.frame.z)
                    * (self.segments[s].b - self.segments[s].a).norm()
            })
            .sum();
        let mut seen = vec![false; near.len()];
        let mut chains = Vec::new();
        // Open chains first (from where no near edge arrives), then the closed ones.
        let starts = (0..near.len())
            .filter(|&i| !entered.contains_key(&self.segments[near[i]].from))
            .chain(0..near.len());
        for first in starts {
            if seen[first] {
                continue;
            }
            let mut points = vec![local(&self.segments[near[first]].a)];
            let mut at = first;
            let closed = loop {
                seen[at] = true;
                let seg = &self.segments[near[at]];
                points.push(local(&seg.b));
                match leaving
                    .get(&seg.to)
                    .and_then(|out| out.iter().copied().find(|&n| !seen[n]))
                {
                    Some(n) => at = n,
                    None => break seg.to == self.segments[near[first]].from,
                }
            };
            if closed {
                points.pop();
            }
            if facing < 0.0 {
                points.reverse();
            }
            chains.push(Chain { points, closed });
        }
        chains
    }
}

/// How much farther than the closest face (in half tile widths) a face of another sheet may
/// lie from a tile's centre and still be the tile's own ([`SurfaceBoundary::sheet_of`]): a
/// tenth, 7 mm for a 140 mm tile, well inside the half joint a crease's seams are set back.
const SHEET_SLACK: f64 = 0.1;

/// How far each vertex on a seam moves into its own sheet so that the seam's edges lie `gap`
/// inside it: along the mean of its seam edges' inward normals (on their faces), by `gap`
/// over the cosine of half the seam's turn there.
fn seam_moves(
    mesh: &PolyMesh,
    topology: &Topology,
    seams: &[[usize; 2]],
    gap: f64,
) -> HashMap<usize, Vector3<f64>> {
    let p = mesh.positions();
    let mut inward: HashMap<usize, Vec<Vector3<f64>>> = HashMap::new();
    for &[a, b] in seams {
        // The face left of a -> b (its own orientation), whose normal turns the edge inward.
        let Some(face) = topology
            .vertex_edges(a)
            .iter()
            .map(|&e| &topology.edges()[e])
            .find(|e| e.vertices == [a.min(b), a.max(b)])
            .map(|e| e.faces[0])
        else {
            continue;
        };
        let normal = mesh.face_area_vector(face);
        if let Some(d) = normal.cross(&(p[b] - p[a])).try_normalize(0.0) {
            inward.entry(a).or_default().push(d);
            inward.entry(b).or_default().push(d);
        }
    }
    inward
        .into_iter()
        .filter_map(|(v, ds)| {
            let mean = ds.iter().sum::<Vector3<f64>>().try_normalize(0.0)?;
            let cos = ds.iter().map(|d| d.dot(&mean)).fold(1.0, f64::min).max(0.5);
            Some((v, mean * (gap / cos)))
        })
        .collect()
}

impl Cut {
    /// The part of `loops` (a tile's kept region, in its frame) inside the convex polygon
    /// `window` (counter-clockwise), as a cut of a tile face of area `full`; `None` when
    /// nothing is left. Each loop is clipped on its own (Sutherland-Hodgman), which keeps the
    /// area exact.
    pub(crate) fn within(loops: &[Vec<Point2>], window: &[Point2], full: f64) -> Option<Cut> {
        let kept: Vec<Vec<Point2>> = loops
            .iter()
            .map(|l| clip_to_convex(l, window))
            .filter(|poly| poly.len() >= 3 && signed_area(poly).abs() > 0.0)
            .collect();
        let area: f64 = kept.iter().map(|l| signed_area(l)).sum();
        (area > 0.0).then(|| Cut {
            loops: kept,
            kept_fraction: (area / full).min(1.0),
        })
    }
}

/// Boundary edges joined end to end, in a tile's frame.
struct Chain {
    points: Vec<Point2>,
    closed: bool,
}

/// Whether `q` lies on the surface's side of the nearest chain (the side test of the closest
/// feature: an edge's left side, or at a vertex the wedge between its two edges).
fn inside(chains: &[Chain], q: Point2) -> bool {
    let mut best = (f64::INFINITY, false);
    for chain in chains {
        let n = chain.points.len();
        let edges = if chain.closed { n } else { n - 1 };
        for i in 0..edges {
            let (a, b) = (chain.points[i], chain.points[(i + 1) % n]);
            let (d, at_end) = point_segment(q, a, b);
            if d >= best.0 {
                continue;
            }
            let left = cross(sub(b, a), sub(q, a)) > 0.0;
            let side = match at_end {
                // At a shared vertex the wedge of the two edges decides: inside a convex
                // corner means left of both edges, at a reflex corner left of either.
                Some(end) => {
                    let (prev, next) = if end == 0 {
                        (
                            if i > 0 || chain.closed {
                                Some(chain.points[(i + n - 1) % n])
                            } else {
                                None
                            },
                            Some(b),
                        )
                    } else {
                        (
                            Some(a),
                            if i + 1 < edges || chain.closed {
                                Some(chain.points[(i + 2) % n])
                            } else {
                                None
                            },
                        )
                    };
                    let v = if end == 0 { a } else { b };
                    match (prev, next) {
                        (Some(p), Some(nx)) => {
                            let (d1, d2) = (sub(v, p), sub(nx, v));
                            let (l1, l2) = (cross(d1, sub(q, v)) > 0.0, cross(d2, sub(q, v)) > 0.0);
                            if cross(d1, d2) >= 0.0 {
                                l1 && l2
                            } else {
                                l1 || l2
                            }
                        }
                        _ => left,
                    }
                }
                None => left,
            };
            best = (d, side);
        }
    }
    best.1
}

/// A tile's face in its own frame: `[-hx, hx] x [-hy, hy]`.
#[derive(Debug, Clone, Copy)]
struct Rect {
    hx: f64,
    hy: f64,
}

impl Rect {
    fn eps(&self) -> f64 {
        1e-9 * (self.hx + self.hy)
    }

    fn corners(&self) -> [Point2; 4] {
        let (x, y) = (self.hx, self.hy);
        [[-x, -y], [x, -y], [x, y], [-x, y]]
    }

    fn contains(&self, p: Point2) -> bool {
        p[0].abs() <= self.hx && p[1].abs() <= self.hy
    }

    fn on_border(&self, p: Point2) -> bool {
        let e = self.eps();
        self.contains([p[0].abs().min(self.hx), p[1].abs().min(self.hy)])
            && ((p[0].abs() - self.hx).abs() <= e || (p[1].abs() - self.hy).abs() <= e)
    }

    /// Position of a border point along the border, counter-clockwise from `(-hx, -hy)`.
    fn border_position(&self, p: Point2) -> f64 {
        let (x, y, e) = (self.hx, self.hy, self.eps());
        if (p[1] + y).abs() <= e && p[0] < x - e {
            p[0] + x
        } else if (p[0] - x).abs() <= e && p[1] < y - e {
            2.0 * x + (p[1] + y)
        } else if (p[1] - y).abs() <= e && p[0] > -x + e {
            2.0 * x + 2.0 * y + (x - p[0])
        } else {
            4.0 * x + 2.0 * y + (y - p[1])
        }
    }

    /// How far a polyline inside the rectangle reaches in from the border (sampled: the
    /// distance to the border is not linear along a segment that cuts a corner).
    fn depth(&self, points: &[Point2]) -> f64 {
        const SAMPLES: usize = 8;
        let inward = |p: Point2| (self.hx - p[0].abs()).min(self.hy - p[1].abs());
        points
            .windows(2)
            .flat_map(|w| {
                (0..=SAMPLES).map(move |k| {
                    let t = k as f64 / SAMPLES as f64;
                    [
                        w[0][0] + t * (w[1][0] - w[0][0]),
                        w[0][1] + t * (w[1][1] - w[0][1]),
                    ]
                })
            })
            .map(inward)
            .fold(0.0, f64::max)
    }

    fn border_length(&self) -> f64 {
        4.0 * (self.hx + self.hy)
    }

    /// The parts of a polyline inside the rectangle (Liang-Barsky on each segment).
    fn clip_polyline(&self, points: &[Point2]) -> Vec<Vec<Point2>> {
        let mut pieces: Vec<Vec<Point2>> = Vec::new();
        let mut open = false;
        for w in points.windows(2) {
            let Some((t0, t1)) = self.clip_segment(w[0], w[1]) else {
                open = false;
                continue;
            };
            let at = |t: f64| {
                [
                    w[0][0] + t * (w[1][0] - w[0][0]),
                    w[0][1] + t * (w[1][1] - w[0][1]),
                ]
            };
            if !(open && t0 == 0.0) {
                pieces.push(vec![at(t0)]);
            }
            let piece = pieces.last_mut().expect("pushed above");
            piece.push(at(t1));
            open = t1 == 1.0;
        }
        pieces
    }

    fn clip_segment(&self, a: Point2, b: Point2) -> Option<(f64, f64)> {
        let d = sub(b, a);
        let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
        for (p, q) in [
            (-d[0], a[0] + self.hx),
            (d[0], self.hx - a[0]),
            (-d[1], a[1] + self.hy),
            (d[1], self.hy - a[1]),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    return None;
                }
            } else if p < 0.0 {
                t0 = t0.max(q / p);
            } else {
                t1 = t1.min(q / p);
            }
        }
        (t0 < t1).then_some((t0, t1))
    }

    /// Closes the pieces of boundary that cross the rectangle into loops: after a piece
    /// leaves the rectangle, the kept region follows the border counter-clockwise to where the
    /// next piece enters.
    fn join(&self, pieces: Vec<Vec<Point2>>) -> Vec<Vec<Point2>> {
        let length = self.border_length();
        let entry: Vec<f64> = pieces.iter().map(|p| self.border_position(p[0])).collect();
        let exit: Vec<f64> = pieces
            .iter()
            .map(|p| self.border_position(p[p.len() - 1]))
            .collect();
        let corner_positions: Vec<(f64, Point2)> = self
            .corners()
            .iter()
            .map(|&c| (self.border_position(c), c))
            .collect();
        let mut used = vec![false; pieces.len()];
        let mut loops = Vec::new();
        for start in 0..pieces.len() {
            if used[start] {
                continue;
            }
            let mut outline: Vec<Point2> = Vec::new();
            let mut at = start;
            for _ in 0..pieces.len() {
                used[at] = true;
                outline.extend(&pieces[at]);
                let from = exit[at];
                let ahead = |s: f64| (s - from).rem_euclid(length);
                let next = (0..pieces.len())
                    .min_by(|&i, &j| ahead(entry[i]).total_cmp(&ahead(entry[j])).then(i.cmp(&j)))
                    .expect("not empty");
                let mut corners: Vec<&(f64, Point2)> = corner_positions
                    .iter()
                    .filter(|(s, _)| ahead(*s) > 0.0 && ahead(*s) < ahead(entry[next]))
                    .collect();
                corners.sort_by(|a, b| ahead(a.0).total_cmp(&ahead(b.0)));
                outline.extend(corners.iter().map(|(_, c)| *c));
                if next == start || used[next] {
                    break;
                }
                at = next;
            }
            loops.push(outline);
        }
        loops
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tiles::{Frame, TileKind};

    /// A plate folded along `x = 0`: flat for `x < 0`, rising at `angle` degrees beyond,
    /// meshed in squares of 0.1 over `[-1, 1] x [0, 1]`.
    fn folded(angle: f64) -> PolyMesh {
        let slope = angle.to_radians().tan();
        let grid = crate::mesh::generate::grid(20, 10);
        let positions = grid
            .positions()
            .iter()
            .map(|p| {
                let x = -1.0 + 0.1 * p.x;
                Point3::new(x, 0.1 * p.y, x.max(0.0) * slope)
            })
            .collect();
        PolyMesh::new(positions, grid.faces().to_vec()).unwrap()
    }

    #[test]
    fn a_tile_is_cut_by_the_edges_of_the_sheet_it_lies_on() {
        // A tile lying flat on the flat web, its centre 3 mm past the fold: 1.9 mm from the
        // rising web's faces, 3 mm from the flat web's edge. It belongs to the flat web and
        // keeps the part short of the fold (less the half joint), not the part beyond it.
        let boundary = SurfaceBoundary::with_creases(&folded(40.0), 0.2, 0.005);
        let frame = Frame {
            origin: Point3::new(0.003, 0.5, 0.0),
            x: Vector3::x(),
            y: Vector3::y(),
            z: Vector3::z(),
        };
        let tile = Tile::new(TileKind::Full, vec![], frame, [0.28, 0.14, 0.015]);
        let flat = boundary.sheet_at(&Point3::new(-0.5, 0.5, 0.0), 0.1);
        let rising = boundary.sheet_at(&Point3::new(0.5, 0.5, 0.5 * 40f64.to_radians().tan()), 0.1);
        assert_ne!(flat, rising);
        assert_eq!(
            boundary.sheet_at(&tile.frame.origin, 0.3),
            rising,
            "the closer web"
        );
        assert_eq!(boundary.sheet_of(&tile, 0.3), flat);
        let Clipped::Cut(cut) = boundary.clip(&tile, 0.0) else {
            panic!("the fold crosses the tile");
        };
        let xs: Vec<f64> = cut.loops.iter().flatten().map(|p| p[0]).collect();
        let (lo, hi) = xs
            .iter()
            .fold((f64::MAX, f64::MIN), |(l, h), &x| (l.min(x), h.max(x)));
        // Local x: from the tile's end at -0.14 to the fold's seam at -0.003 - 0.005.
        assert!((lo + 0.14).abs() < 1e-9, "kept from {lo}");
        assert!((hi + 0.008).abs() < 1e-6, "kept to {hi}");
    }

    /// A plate `[0, 1] x [0, 1]` at `z = 0`, meshed in squares of 0.1, folded back under
    /// itself at `x = 1` into a hem 5 cm wide (as at a crumpled end of a scanned or
    /// hand-modelled tube): the hem's faces face down, its free edge runs at `x = 0.95`.
    fn hemmed() -> PolyMesh {
        let grid = crate::mesh::generate::grid(11, 10);
        let positions = grid
            .positions()
            .iter()
            .map(|p| match p.x {
                x if x <= 10.0 => Point3::new(0.1 * x, 0.1 * p.y, 0.0),
                _ => Point3::new(0.95, 0.1 * p.y, -0.02),
            })
            .collect();
        PolyMesh::new(positions, grid.faces().to_vec()).unwrap()
    }

    #[test]
    fn a_tile_flat_beyond_a_folded_edge_is_off_the_surface() {
        // A tile lying flat 1 cm beyond the fold: no boundary edge crosses it, and the edge
        // it sees (the hem's) keeps the surface on its far side, seen along the hem's normals
        // from above, so the side test alone put the tile on the surface. Its far corners
        // stand 29 cm off it.
        let boundary = SurfaceBoundary::new(&hemmed(), 0.3);
        let flat = |x: f64| Frame {
            origin: Point3::new(x, 0.5, 0.0),
            x: Vector3::x(),
            y: Vector3::y(),
            z: Vector3::z(),
        };
        let tile = |x| Tile::new(TileKind::Full, vec![], flat(x), [0.28, 0.14, 0.015]);
        assert!(matches!(boundary.clip(&tile(1.15), 0.0), Clipped::Outside));
        // On the plate it is whole.
        assert!(matches!(boundary.clip(&tile(0.5), 0.0), Clipped::Whole));
    }
}
