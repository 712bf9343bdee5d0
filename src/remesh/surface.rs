//! The working triangle surface of the remesher: triangulated input, vertex normals, edge
//! adjacency and boundary loops, the midpoint refinement the position field needs (Instant
//! Meshes samples the lattice on vertices, so edges must be clearly shorter than `t`), and a
//! closest-point locator on the input surface and its boundary.

use std::collections::HashMap;

use nalgebra::{Point3, Vector3};

use super::{BoundaryAlignment, RemeshError};
use crate::mesh::PolyMesh;

/// A triangle surface with the adjacency the solvers walk over, always in index order.
#[derive(Debug, Clone)]
pub(crate) struct Surface {
    /// Vertex positions.
    pub pos: Vec<Vector3<f64>>,
    /// Triangles, consistently oriented as in the input.
    pub tris: Vec<[usize; 3]>,
    /// Unit vertex normals.
    pub normals: Vec<Vector3<f64>>,
    /// Undirected edges, smaller vertex first, numbered in order of first appearance.
    pub edges: Vec<[usize; 2]>,
    /// Per vertex: (neighbour, edge) sorted by neighbour.
    pub adj: Vec<Vec<(usize, usize)>>,
    /// Per boundary vertex: the previous and next vertex along its boundary loop.
    pub boundary: Vec<Option<(usize, usize)>>,
    /// Mean edge length.
    pub mean_edge: f64,
    /// Per boundary vertex: incoming and outgoing boundary directions measured over an arc
    /// of the boundary scale (so a zig-zag boundary reads as its overall course).
    pub bdirs: Vec<Option<(Vector3<f64>, Vector3<f64>)>>,
    /// Boundary vertices where the boundary, seen at its scale, turns by more than 50
    /// degrees (the sharpest vertex of each such bend).
    pub corner: Vec<bool>,
}

impl Surface {
    /// Fan-triangulates the input polygons, dropping vertices no face uses.
    pub fn from_polymesh(mesh: &PolyMesh) -> Result<Self, RemeshError> {
        let mut remap = vec![usize::MAX; mesh.positions().len()];
        let mut pos = Vec::new();
        let mut tris = Vec::new();
        for face in mesh.faces() {
            let mut ids = Vec::with_capacity(face.len());
            for &v in face {
                if remap[v] == usize::MAX {
                    remap[v] = pos.len();
                    pos.push(mesh.positions()[v].coords);
                }
                ids.push(remap[v]);
            }
            for k in 1..ids.len() - 1 {
                tris.push([ids[0], ids[k], ids[k + 1]]);
            }
        }
        let surface = Self::build(pos, tris, None);
        if let Some(v) = surface.pinched_vertex() {
            return Err(RemeshError::UnsupportedInput(format!(
                "vertex {v} is where two boundary loops or two surface sheets touch; split it into separate vertices"
            )));
        }
        Ok(surface)
    }

    /// Builds adjacency, boundary loops and (unless given) area-weighted vertex normals.
    pub fn build(pos: Vec<Vector3<f64>>, tris: Vec<[usize; 3]>, normals: Option<Vec<Vector3<f64>>>) -> Self {
        let n = pos.len();
        let mut index: HashMap<[usize; 2], usize> = HashMap::new();
        let mut edges = Vec::new();
        let mut edge_faces: Vec<u8> = Vec::new();
        let mut directed: Vec<[usize; 2]> = Vec::new();
        let mut adj = vec![Vec::new(); n];
        for tri in &tris {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                let key = [a.min(b), a.max(b)];
                let e = *index.entry(key).or_insert_with(|| {
                    edges.push(key);
                    edge_faces.push(0);
                    directed.push([a, b]);
                    adj[key[0]].push((key[1], edges.len() - 1));
                    adj[key[1]].push((key[0], edges.len() - 1));
                    edges.len() - 1
                });
                edge_faces[e] += 1;
            }
        }
        for list in &mut adj {
            list.sort_unstable();
        }
        let mut boundary: Vec<Option<(usize, usize)>> = vec![None; n];
        let mut next = vec![usize::MAX; n];
        let mut prev = vec![usize::MAX; n];
        for (e, &[a, b]) in directed.iter().enumerate() {
            if edge_faces[e] == 1 {
                if next[a] == usize::MAX {
                    next[a] = b;
                }
                if prev[b] == usize::MAX {
                    prev[b] = a;
                }
            }
        }
        for v in 0..n {
            if next[v] != usize::MAX && prev[v] != usize::MAX {
                boundary[v] = Some((prev[v], next[v]));
            }
        }
        let normals = normals.unwrap_or_else(|| {
            let mut acc = vec![Vector3::zeros(); n];
            for tri in &tris {
                let w = (pos[tri[1]] - pos[tri[0]]).cross(&(pos[tri[2]] - pos[tri[0]]));
                for &v in tri {
                    acc[v] += w;
                }
            }
            acc.into_iter().map(|a| a.try_normalize(1e-300).unwrap_or_else(Vector3::z)).collect()
        });
        let mean_edge = if edges.is_empty() {
            0.0
        } else {
            edges.iter().map(|&[a, b]| (pos[a] - pos[b]).norm()).sum::<f64>() / edges.len() as f64
        };
        let mut surface =
            Self { pos, tris, normals, edges, adj, boundary, mean_edge, bdirs: Vec::new(), corner: Vec::new() };
        surface.set_boundary_scale(0.0);
        surface
    }

    /// Measures boundary directions and corners over arcs of length `h` (about half a quad):
    /// shell boundaries from subdivided or trimmed meshes zig-zag at the triangle scale, and
    /// quads should follow the boundary's course, not its teeth.
    pub fn set_boundary_scale(&mut self, h: f64) {
        let n = self.len();
        let walk = |v: usize, forward: bool| -> usize {
            let mut w = v;
            let mut acc = 0.0;
            for _ in 0..n {
                let Some((prev, next)) = self.boundary[w] else { break };
                let u = if forward { next } else { prev };
                acc += (self.pos[u] - self.pos[w]).norm();
                w = u;
                if acc >= h || w == v {
                    break;
                }
            }
            w
        };
        let mut bdirs = vec![None; n];
        let mut turn = vec![0.0; n];
        for v in 0..n {
            if self.boundary[v].is_some() {
                let (back, fwd) = (walk(v, false), walk(v, true));
                let din = self.pos[v] - self.pos[back];
                let dout = self.pos[fwd] - self.pos[v];
                turn[v] = din.angle(&dout);
                if turn[v].is_nan() {
                    turn[v] = 0.0;
                }
                bdirs[v] = Some((din, dout));
            }
        }
        let threshold = CORNER_COS.acos();
        let mut corner = vec![false; n];
        for v in 0..n {
            if self.boundary[v].is_none() || turn[v] <= threshold {
                continue;
            }
            // Non-maximum suppression along the arc of length h on both sides.
            let mut best = true;
            for forward in [false, true] {
                let mut w = v;
                let mut acc = 0.0;
                for _ in 0..n {
                    let Some((prev, next)) = self.boundary[w] else { break };
                    let u = if forward { next } else { prev };
                    acc += (self.pos[u] - self.pos[w]).norm();
                    w = u;
                    if w == v || acc > h {
                        break;
                    }
                    if turn[w] > turn[v] || (turn[w] == turn[v] && w < v) {
                        best = false;
                    }
                }
            }
            corner[v] = best;
        }
        self.bdirs = bdirs;
        self.corner = corner;
    }

    /// A vertex with more than one boundary edge pair (two loops touching), if any.
    fn pinched_vertex(&self) -> Option<usize> {
        let mut count = vec![0usize; self.pos.len()];
        let mut uses: HashMap<[usize; 2], u8> = HashMap::new();
        for tri in &self.tris {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                *uses.entry([a.min(b), a.max(b)]).or_insert(0) += 1;
            }
        }
        for &[a, b] in &self.edges {
            if uses.get(&[a, b]) == Some(&1) {
                count[a] += 1;
                count[b] += 1;
            }
        }
        count.iter().position(|&c| c > 2)
    }

    /// Per vertex: true on boundary loops the quads should follow under `mode` (see
    /// [`BoundaryAlignment`]).
    pub fn aligned_boundary(&self, mode: BoundaryAlignment) -> Vec<bool> {
        let n = self.len();
        let mut aligned = vec![false; n];
        let mut seen = vec![false; n];
        for start in 0..n {
            if seen[start] || self.boundary[start].is_none() {
                continue;
            }
            let mut lp = Vec::new();
            let mut v = start;
            while !seen[v] {
                seen[v] = true;
                lp.push(v);
                match self.boundary[v] {
                    Some((_, next)) => v = next,
                    None => break,
                }
            }
            let has_corner = lp.iter().any(|&v| self.is_corner(v));
            let align = match mode {
                BoundaryAlignment::Always => true,
                BoundaryAlignment::Never => false,
                BoundaryAlignment::Auto => has_corner,
            };
            for v in lp {
                aligned[v] = align;
            }
        }
        aligned
    }

    /// True at boundary corners (see [`Surface::set_boundary_scale`]).
    pub fn is_corner(&self, v: usize) -> bool {
        self.corner[v]
    }

    /// Number of vertices.
    pub fn len(&self) -> usize {
        self.pos.len()
    }

    /// The 3D edge vector from `a` to `b`.
    pub fn edge_vec(&self, a: usize, b: usize) -> Vector3<f64> {
        self.pos[b] - self.pos[a]
    }
}

/// Cosine of the turning angle (50 degrees) above which a boundary vertex is a corner.
pub(crate) const CORNER_COS: f64 = 0.642_787_609_686_539_3;

/// Midpoint-subdivides `base` (flat, so the surface does not move) until the mean edge is at
/// most `t / 2`, interpolating the orientation field `frames` (one tangent vector per vertex,
/// a 4-RoSy representative) and the normals onto the new vertices.
pub(crate) fn refine(base: &Surface, frames: &[Vector3<f64>], t: f64) -> (Surface, Vec<Vector3<f64>>) {
    let limit = 3_000_000usize;
    let mut surface = base.clone();
    let mut frames = frames.to_vec();
    while surface.mean_edge > t / 2.0 && surface.tris.len() * 4 <= limit {
        let mut pos = surface.pos.clone();
        let mut normals = surface.normals.clone();
        let mut fine_frames = frames.clone();
        let mut mid = vec![0usize; surface.edges.len()];
        for (e, &[a, b]) in surface.edges.iter().enumerate() {
            mid[e] = pos.len();
            pos.push((surface.pos[a] + surface.pos[b]) * 0.5);
            let n = (surface.normals[a] + surface.normals[b]).try_normalize(1e-300).unwrap_or(surface.normals[a]);
            normals.push(n);
            let ob = super::field::match_rosy(&frames[a], &frames[b], &surface.normals[b]);
            let o = frames[a] + ob;
            let o = (o - n * n.dot(&o)).try_normalize(1e-300).unwrap_or_else(|| any_tangent(&n));
            fine_frames.push(o);
        }
        let edge_of = |a: usize, b: usize| -> usize {
            let list = &surface.adj[a];
            let k = list.partition_point(|&(v, _)| v < b);
            mid[list[k].1]
        };
        let mut tris = Vec::with_capacity(surface.tris.len() * 4);
        for &[a, b, c] in &surface.tris {
            let (ab, bc, ca) = (edge_of(a, b), edge_of(b, c), edge_of(c, a));
            tris.push([a, ab, ca]);
            tris.push([ab, b, bc]);
            tris.push([ca, bc, c]);
            tris.push([ab, bc, ca]);
        }
        surface = Surface::build(pos, tris, Some(normals));
        frames = fine_frames;
    }
    surface.set_boundary_scale(t * 0.5);
    (surface, frames)
}

/// Some unit vector orthogonal to `n`.
pub(crate) fn any_tangent(n: &Vector3<f64>) -> Vector3<f64> {
    let axis = if n.x.abs() < 0.9 { Vector3::x() } else { Vector3::y() };
    (axis - n * n.dot(&axis)).normalize()
}

/// A uniform grid of primitives' bounding boxes for nearest queries.
#[derive(Debug, Clone)]
struct Grid {
    min: Vector3<f64>,
    h: f64,
    dims: [usize; 3],
    cells: Vec<Vec<u32>>,
}

impl Grid {
    fn new(boxes: &[(Vector3<f64>, Vector3<f64>)], h: f64) -> Self {
        let mut min = Vector3::repeat(f64::INFINITY);
        let mut max = Vector3::repeat(f64::NEG_INFINITY);
        for (lo, hi) in boxes {
            min = min.inf(lo);
            max = max.sup(hi);
        }
        if boxes.is_empty() {
            min = Vector3::zeros();
            max = Vector3::zeros();
        }
        let mut h = h.max(1e-12);
        let extent = max - min;
        // Keep the cell count proportional to the primitives.
        loop {
            let cells: f64 = (0..3).map(|k| (extent[k] / h).floor() + 1.0).product();
            if cells <= 8.0 * boxes.len() as f64 + 64.0 {
                break;
            }
            h *= 1.5;
        }
        let dims = [0, 1, 2].map(|k| (extent[k] / h).floor() as usize + 1);
        let mut grid = Self { min, h, dims, cells: vec![Vec::new(); dims[0] * dims[1] * dims[2]] };
        for (i, (lo, hi)) in boxes.iter().enumerate() {
            let a = grid.cell(lo);
            let b = grid.cell(hi);
            for x in a[0]..=b[0] {
                for y in a[1]..=b[1] {
                    for z in a[2]..=b[2] {
                        let id = grid.id([x, y, z]);
                        grid.cells[id].push(i as u32);
                    }
                }
            }
        }
        grid
    }

    fn cell(&self, p: &Vector3<f64>) -> [usize; 3] {
        [0, 1, 2].map(|k| {
            let c = ((p[k] - self.min[k]) / self.h).floor();
            if c.is_nan() || c < 0.0 { 0 } else { (c as usize).min(self.dims[k] - 1) }
        })
    }

    fn id(&self, c: [usize; 3]) -> usize {
        (c[2] * self.dims[1] + c[1]) * self.dims[0] + c[0]
    }

    /// Nearest primitive by `dist2` (squared distance and closest point), ring by ring.
    fn nearest(&self, p: &Vector3<f64>, dist2: impl Fn(usize) -> (f64, Vector3<f64>)) -> Option<(usize, f64, Vector3<f64>)> {
        let c = self.cell(p);
        let mut best: Option<(usize, f64, Vector3<f64>)> = None;
        let max_ring = self.dims.iter().copied().max().unwrap_or(1);
        // Distance from p to the grid box, so rings outside the box are measured fairly.
        let outside = {
            let mut d2 = 0.0;
            for k in 0..3 {
                let hi = self.min[k] + self.dims[k] as f64 * self.h;
                let d = (self.min[k] - p[k]).max(p[k] - hi).max(0.0);
                d2 += d * d;
            }
            d2.sqrt()
        };
        for r in 0..=max_ring {
            if let Some((_, d2, _)) = best {
                let reach = outside + (r as f64 - 1.0).max(0.0) * self.h;
                if reach * reach > d2 {
                    break;
                }
            }
            let lo = [0, 1, 2].map(|k| c[k].saturating_sub(r));
            let hi = [0, 1, 2].map(|k| (c[k] + r).min(self.dims[k] - 1));
            for x in lo[0]..=hi[0] {
                for y in lo[1]..=hi[1] {
                    for z in lo[2]..=hi[2] {
                        let ring = (x.abs_diff(c[0])).max(y.abs_diff(c[1])).max(z.abs_diff(c[2]));
                        if ring != r {
                            continue;
                        }
                        for &i in &self.cells[self.id([x, y, z])] {
                            let (d2, q) = dist2(i as usize);
                            if best.is_none_or(|(bi, bd, _)| d2 < bd || (d2 == bd && (i as usize) < bi)) {
                                best = Some((i as usize, d2, q));
                            }
                        }
                    }
                }
            }
        }
        best
    }
}

/// Closest points on the input surface and on its boundary curves.
#[derive(Debug, Clone)]
pub(crate) struct Locator {
    pos: Vec<Vector3<f64>>,
    tris: Vec<[usize; 3]>,
    segments: Vec<[usize; 2]>,
    corners: Vec<Vector3<f64>>,
    tri_grid: Grid,
    seg_grid: Grid,
}

impl Locator {
    /// Indexes the triangles and boundary edges of `surface` (whose corners are those of
    /// its boundary scale).
    pub fn new(surface: &Surface, t: f64) -> Self {
        let segments: Vec<[usize; 2]> =
            (0..surface.len()).filter_map(|v| surface.boundary[v].map(|(_, next)| [v, next])).collect();
        let corners = (0..surface.len()).filter(|&v| surface.is_corner(v)).map(|v| surface.pos[v]).collect();
        Self::from_parts(surface.pos.clone(), surface.tris.clone(), segments, corners, (surface.mean_edge * 2.0).max(t * 0.5))
    }

    /// Boundary vertices where the boundary turns by more than 50 degrees.
    pub fn corners(&self) -> &[Vector3<f64>] {
        &self.corners
    }

    /// Indexes any polygon mesh (fan-triangulated), for metrics on foreign quad meshes.
    pub fn from_polymesh(mesh: &PolyMesh, t: f64) -> Self {
        let surface = Surface::build(
            mesh.positions().iter().map(|p| p.coords).collect(),
            mesh.faces().iter().flat_map(|f| (1..f.len() - 1).map(move |k| [f[0], f[k], f[k + 1]])).collect(),
            None,
        );
        Self::new(&surface, t)
    }

    fn from_parts(pos: Vec<Vector3<f64>>, tris: Vec<[usize; 3]>, segments: Vec<[usize; 2]>, corners: Vec<Vector3<f64>>, h: f64) -> Self {
        let boxes: Vec<_> = tris
            .iter()
            .map(|t| {
                let (a, b, c) = (pos[t[0]], pos[t[1]], pos[t[2]]);
                (a.inf(&b).inf(&c), a.sup(&b).sup(&c))
            })
            .collect();
        let tri_grid = Grid::new(&boxes, h);
        let seg_boxes: Vec<_> = segments.iter().map(|s| (pos[s[0]].inf(&pos[s[1]]), pos[s[0]].sup(&pos[s[1]]))).collect();
        let seg_grid = Grid::new(&seg_boxes, h);
        Self { pos, tris, segments, corners, tri_grid, seg_grid }
    }

    /// Closest point on the surface, and its triangle's unit normal.
    pub fn closest(&self, p: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
        match self.tri_grid.nearest(p, |i| {
            let [a, b, c] = self.tris[i];
            let q = closest_on_triangle(p, &self.pos[a], &self.pos[b], &self.pos[c]);
            ((q - p).norm_squared(), q)
        }) {
            Some((i, _, q)) => {
                let [a, b, c] = self.tris[i];
                let n = (self.pos[b] - self.pos[a]).cross(&(self.pos[c] - self.pos[a]));
                (q, n.try_normalize(1e-300).unwrap_or_else(Vector3::z))
            }
            None => (*p, Vector3::z()),
        }
    }

    /// Distance to the surface.
    pub fn distance(&self, p: &Vector3<f64>) -> f64 {
        (self.closest(p).0 - p).norm()
    }

    /// Closest point on the boundary curves, if the surface has a boundary.
    pub fn closest_boundary(&self, p: &Vector3<f64>) -> Option<Vector3<f64>> {
        self.seg_grid
            .nearest(p, |i| {
                let [a, b] = self.segments[i];
                let q = closest_on_segment(p, &self.pos[a], &self.pos[b]);
                ((q - p).norm_squared(), q)
            })
            .map(|(_, _, q)| q)
    }

    }

/// Closest point on segment `ab` to `p`.
pub(crate) fn closest_on_segment(p: &Vector3<f64>, a: &Vector3<f64>, b: &Vector3<f64>) -> Vector3<f64> {
    let d = b - a;
    let l2 = d.norm_squared();
    if l2 <= 0.0 {
        return *a;
    }
    a + d * ((p - a).dot(&d) / l2).clamp(0.0, 1.0)
}

/// Closest point on triangle `abc` to `p` (Ericson, Real-Time Collision Detection, 5.1.5).
pub(crate) fn closest_on_triangle(p: &Vector3<f64>, a: &Vector3<f64>, b: &Vector3<f64>, c: &Vector3<f64>) -> Vector3<f64> {
    let ab = b - a;
    let ac = c - a;
    let ap = p - a;
    let d1 = ab.dot(&ap);
    let d2 = ac.dot(&ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return *a;
    }
    let bp = p - b;
    let d3 = ab.dot(&bp);
    let d4 = ac.dot(&bp);
    if d3 >= 0.0 && d4 <= d3 {
        return *b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return a + ab * v;
    }
    let cp = p - c;
    let d5 = ab.dot(&cp);
    let d6 = ac.dot(&cp);
    if d6 >= 0.0 && d5 <= d6 {
        return *c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return a + ac * w;
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return b + (c - b) * w;
    }
    let denom = va + vb + vc;
    if denom.abs() < 1e-300 {
        // Degenerate triangle: fall back to its longest edge.
        let candidates = [closest_on_segment(p, a, b), closest_on_segment(p, b, c), closest_on_segment(p, c, a)];
        return candidates
            .into_iter()
            .min_by(|x, y| (x - p).norm_squared().total_cmp(&(y - p).norm_squared()))
            .unwrap_or(*a);
    }
    let v = vb / denom;
    let w = vc / denom;
    a + ab * v + ac * w
}

/// Converts a point to nalgebra's point type.
pub(crate) fn point(v: &Vector3<f64>) -> Point3<f64> {
    Point3::from(*v)
}
