//! The working triangle surface of the remesher: triangulated input, vertex normals, edge
//! adjacency and boundary loops with their corners and narrow parts, the refinement the
//! position field needs (Instant Meshes samples the lattice on vertices, so edges must be
//! clearly shorter than `t`: midpoint subdivision, then bisection of any edge still longer
//! than 3/4 t, as slivers have), and a closest-point locator (bounding volume hierarchies)
//! on the input surface and along its boundary loops.

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
    /// Boundary vertices where the surface is narrower than the boundary scale: another part
    /// of the boundary, far away along the loop, passes close by (teeth, slivers, acute
    /// tongues). Quads cannot follow such a boundary, so it neither pins nor aligns them.
    pub narrow: Vec<bool>,
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
        let mut edges = Vec::new();
        let mut edge_faces: Vec<u32> = Vec::new();
        let mut directed: Vec<[usize; 2]> = Vec::new();
        let mut adj: Vec<Vec<(usize, usize)>> = vec![Vec::new(); n];
        for tri in &tris {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                let key = [a.min(b), a.max(b)];
                // Vertex neighbourhoods are short: a scan beats hashing.
                let e = match adj[key[0]].iter().find(|&&(w, _)| w == key[1]) {
                    Some(&(_, e)) => e,
                    None => {
                        edges.push(key);
                        edge_faces.push(0);
                        directed.push([a, b]);
                        adj[key[0]].push((key[1], edges.len() - 1));
                        adj[key[1]].push((key[0], edges.len() - 1));
                        edges.len() - 1
                    }
                };
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
            Self { pos, tris, normals, edges, adj, boundary, mean_edge, bdirs: Vec::new(), corner: Vec::new(), narrow: Vec::new() };
        surface.set_boundary_scale(0.0);
        surface
    }

    /// Measures boundary directions and corners over arcs of length `h` (about half a quad):
    /// shell boundaries from subdivided or trimmed meshes zig-zag at the triangle scale, and
    /// quads should follow the boundary's course, not its teeth.
    pub fn set_boundary_scale(&mut self, h: f64) {
        let n = self.len();
        let walk = |v: usize, forward: bool, h: f64| -> usize {
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
                let (back, fwd) = (walk(v, false, h), walk(v, true, h));
                let din = self.pos[v] - self.pos[back];
                let dout = self.pos[fwd] - self.pos[v];
                bdirs[v] = Some((din, dout));
                // Corners are read at the scale of a whole quad: a boundary rounded with a
                // radius of about one quad is a corner for the quads.
                let (back, fwd) = (walk(v, false, CORNER_SCALE * h), walk(v, true, CORNER_SCALE * h));
                turn[v] = (self.pos[v] - self.pos[back]).angle(&(self.pos[fwd] - self.pos[v]));
                if turn[v].is_nan() {
                    turn[v] = 0.0;
                }
            }
        }
        let h = CORNER_SCALE * h;
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
        let mut narrow = if h > 0.0 { self.narrow_parts(h / CORNER_SCALE) } else { vec![false; n] };
        // An acute corner cannot be followed by quads on both sides: rows along both sides
        // would have to end in a point. The boundary near it is left free, so the rows of the
        // wider side run out across the tip instead.
        if h > 0.0 {
            let reach = ACUTE_REACH * h;
            for v in 0..n {
                if !(corner[v] && turn[v] > ACUTE_TURN.to_radians()) {
                    continue;
                }
                for forward in [false, true] {
                    let mut w = v;
                    let mut acc = 0.0;
                    narrow[v] = true;
                    for _ in 0..n {
                        let Some((prev, next)) = self.boundary[w] else { break };
                        let u = if forward { next } else { prev };
                        acc += (self.pos[u] - self.pos[w]).norm();
                        w = u;
                        if w == v || acc > reach {
                            break;
                        }
                        narrow[w] = true;
                    }
                }
            }
        }
        for v in 0..n {
            if narrow[v] {
                corner[v] = false;
            }
        }
        self.bdirs = bdirs;
        self.corner = corner;
        self.narrow = narrow;
    }

    /// Boundary vertices with another boundary stretch within `r` that is much farther away
    /// along the loop than in space (see [`Surface::narrow`]).
    fn narrow_parts(&self, r: f64) -> Vec<bool> {
        let n = self.len();
        // Arc length position and loop of every boundary vertex.
        let mut arc = vec![0.0; n];
        let mut loop_of = vec![usize::MAX; n];
        let mut lengths = Vec::new();
        for start in 0..n {
            if self.boundary[start].is_none() || loop_of[start] != usize::MAX {
                continue;
            }
            let id = lengths.len();
            let mut v = start;
            let mut s = 0.0;
            loop {
                loop_of[v] = id;
                arc[v] = s;
                let Some((_, next)) = self.boundary[v] else { break };
                s += (self.pos[next] - self.pos[v]).norm();
                v = next;
                if v == start || loop_of[v] != usize::MAX {
                    break;
                }
            }
            lengths.push(s);
        }
        let segments: Vec<[usize; 2]> = (0..n).filter_map(|v| self.boundary[v].map(|(_, next)| [v, next])).collect();
        if segments.is_empty() {
            return vec![false; n];
        }
        let boxes: Vec<_> = segments.iter().map(|s| (self.pos[s[0]].inf(&self.pos[s[1]]), self.pos[s[0]].sup(&self.pos[s[1]]))).collect();
        let grid = Grid::new(&boxes, r);
        let mut narrow = vec![false; n];
        for v in (0..n).filter(|&v| self.boundary[v].is_some()) {
            let p = self.pos[v];
            let id = loop_of[v];
            let length = lengths[id];
            narrow[v] = grid.within(&p, r).any(|i| {
                let [a, b] = segments[i];
                if loop_of[a] != id {
                    return false;
                }
                let q = closest_on_segment(&p, &self.pos[a], &self.pos[b]);
                let d = (q - p).norm();
                if d >= r {
                    return false;
                }
                let s = arc[a] + (q - self.pos[a]).norm();
                let along = (s - arc[v]).abs();
                let along = along.min(length - along);
                along > NARROW_RATIO * d.max(0.25 * r) + 1e-12
            });
        }
        narrow
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
                aligned[v] = align && !self.narrow[v];
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

/// Corners are measured over this multiple of the boundary scale.
const CORNER_SCALE: f64 = 2.0;

/// Boundary turning (degrees) above which a corner is acute (interior angle below 60).
const ACUTE_TURN: f64 = 120.0;

/// Arc length, in multiples of the corner scale, left free on each side of an acute corner.
const ACUTE_REACH: f64 = 3.0;

/// Arc-to-chord ratio above which two boundary points face each other across a narrow part.
const NARROW_RATIO: f64 = 2.5;

/// Cosine of the turning angle (50 degrees) above which a boundary vertex is a corner.
pub(crate) const CORNER_COS: f64 = 0.642_787_609_686_539_3;

/// The midpoint of edge `a`-`b` of `surface` with its normal and cross frame (`frames[a]`
/// averaged with `frames[b]` turned to match it), for refining the working surface.
fn edge_midpoint(surface: &Surface, frames: &[Vector3<f64>], a: usize, b: usize) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
    let n = (surface.normals[a] + surface.normals[b]).try_normalize(1e-300).unwrap_or(surface.normals[a]);
    let o = frames[a] + super::field::match_rosy(&frames[a], &frames[b], &surface.normals[b]);
    let o = (o - n * n.dot(&o)).try_normalize(1e-300).unwrap_or_else(|| any_tangent(&n));
    ((surface.pos[a] + surface.pos[b]) * 0.5, n, o)
}

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
            let (p, n, o) = edge_midpoint(&surface, &frames, a, b);
            pos.push(p);
            normals.push(n);
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
    // Slivers (long thin triangles, common where a coarse mesh was subdivided around a
    // support) keep edges far longer than the mean: the lattice cannot be read across an edge
    // several quads long, so such edges are bisected until none is.
    let long = LONG_EDGE * t;
    while surface.tris.len() * 2 <= limit {
        let marked: Vec<bool> = surface.edges.iter().map(|&[a, b]| (surface.pos[a] - surface.pos[b]).norm() > long).collect();
        if !marked.iter().any(|&m| m) {
            break;
        }
        let mut pos = surface.pos.clone();
        let mut normals = surface.normals.clone();
        let mut fine_frames = frames.clone();
        let mut mid = vec![usize::MAX; surface.edges.len()];
        for (e, &[a, b]) in surface.edges.iter().enumerate() {
            if !marked[e] {
                continue;
            }
            mid[e] = pos.len();
            let (p, n, o) = edge_midpoint(&surface, &frames, a, b);
            pos.push(p);
            normals.push(n);
            fine_frames.push(o);
        }
        let mid_of = |a: usize, b: usize| -> usize {
            let list = &surface.adj[a];
            let k = list.partition_point(|&(v, _)| v < b);
            mid[list[k].1]
        };
        let mut tris = Vec::with_capacity(surface.tris.len() * 2);
        for &tri in &surface.tris {
            let m = [0, 1, 2].map(|k| mid_of(tri[k], tri[(k + 1) % 3]));
            let count = m.iter().filter(|&&x| x != usize::MAX).count();
            match count {
                0 => tris.push(tri),
                3 => {
                    let [a, b, c] = tri;
                    let [ab, bc, ca] = m;
                    tris.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
                }
                _ => {
                    // Rotate so the first split edge is tri[0]-tri[1].
                    let k = (0..3).find(|&k| m[k] != usize::MAX && (count == 1 || m[(k + 1) % 3] != usize::MAX)).unwrap_or(0);
                    let (a, b, c) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
                    let (ab, bc) = (m[k], m[(k + 1) % 3]);
                    if count == 1 {
                        tris.extend([[a, ab, c], [ab, b, c]]);
                    } else {
                        // Edges ab and bc split: corner triangle at b, the rest cut along the
                        // shorter diagonal.
                        tris.push([ab, b, bc]);
                        if (pos[ab] - pos[c]).norm() <= (pos[bc] - pos[a]).norm() {
                            tris.extend([[a, ab, c], [ab, bc, c]]);
                        } else {
                            tris.extend([[a, ab, bc], [a, bc, c]]);
                        }
                    }
                }
            }
        }
        surface = Surface::build(pos, tris, Some(normals));
        frames = fine_frames;
    }
    surface.set_boundary_scale(t * 0.5);
    (surface, frames)
}

/// Longest edge of the working surface, as a fraction of the target edge.
const LONG_EDGE: f64 = 0.75;

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

    /// Primitives in the cells within `r` of `p` (a superset of those within `r`), each once.
    fn within(&self, p: &Vector3<f64>, r: f64) -> impl Iterator<Item = usize> + '_ {
        let lo = self.cell(&(p - Vector3::repeat(r)));
        let hi = self.cell(&(p + Vector3::repeat(r)));
        let mut ids: Vec<usize> = Vec::new();
        for x in lo[0]..=hi[0] {
            for y in lo[1]..=hi[1] {
                for z in lo[2]..=hi[2] {
                    ids.extend(self.cells[self.id([x, y, z])].iter().map(|&i| i as usize));
                }
            }
        }
        ids.sort_unstable();
        ids.dedup();
        ids.into_iter()
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

}

/// A bounding volume hierarchy over boxes, for nearest-primitive queries that stay fast on
/// slivers (whose boxes would fill many cells of a grid).
#[derive(Debug, Clone)]
struct Bvh {
    nodes: Vec<BvhNode>,
    order: Vec<u32>,
}

#[derive(Debug, Clone)]
struct BvhNode {
    lo: Vector3<f64>,
    hi: Vector3<f64>,
    /// Leaf: range in `order`; inner: `start` is the second child (the first follows).
    start: u32,
    count: u32,
}

/// Most primitives in a leaf.
const BVH_LEAF: usize = 4;

impl Bvh {
    fn new(boxes: &[(Vector3<f64>, Vector3<f64>)]) -> Self {
        let mut order: Vec<u32> = (0..boxes.len() as u32).collect();
        let centres: Vec<Vector3<f64>> = boxes.iter().map(|(lo, hi)| (lo + hi) * 0.5).collect();
        let mut bvh = Self { nodes: Vec::with_capacity(2 * boxes.len() / BVH_LEAF + 1), order: Vec::new() };
        if !boxes.is_empty() {
            bvh.build(boxes, &centres, &mut order, 0);
        }
        bvh.order = order;
        bvh
    }

    fn build(&mut self, boxes: &[(Vector3<f64>, Vector3<f64>)], centres: &[Vector3<f64>], order: &mut [u32], offset: usize) -> usize {
        let mut lo = Vector3::repeat(f64::INFINITY);
        let mut hi = Vector3::repeat(f64::NEG_INFINITY);
        let mut clo = Vector3::repeat(f64::INFINITY);
        let mut chi = Vector3::repeat(f64::NEG_INFINITY);
        for &i in order.iter() {
            let (a, b) = &boxes[i as usize];
            lo = lo.inf(a);
            hi = hi.sup(b);
            clo = clo.inf(&centres[i as usize]);
            chi = chi.sup(&centres[i as usize]);
        }
        let id = self.nodes.len();
        self.nodes.push(BvhNode { lo, hi, start: offset as u32, count: order.len() as u32 });
        if order.len() <= BVH_LEAF {
            return id;
        }
        let extent = chi - clo;
        let axis = if extent.x >= extent.y && extent.x >= extent.z { 0 } else if extent.y >= extent.z { 1 } else { 2 };
        let mid = order.len() / 2;
        order.select_nth_unstable_by(mid, |&a, &b| centres[a as usize][axis].total_cmp(&centres[b as usize][axis]).then(a.cmp(&b)));
        let (left, right) = order.split_at_mut(mid);
        self.build(boxes, centres, left, offset);
        let second = self.build(boxes, centres, right, offset + mid);
        self.nodes[id].start = second as u32;
        self.nodes[id].count = 0;
        id
    }

    /// Nearest primitive by `dist2` (squared distance and closest point); ties go to the
    /// smaller index.
    fn nearest(&self, p: &Vector3<f64>, dist2: impl Fn(usize) -> (f64, Vector3<f64>)) -> Option<(usize, f64, Vector3<f64>)> {
        if self.nodes.is_empty() {
            return None;
        }
        let box_d2 = |n: &BvhNode| -> f64 {
            let mut d2 = 0.0;
            for k in 0..3 {
                let d = (n.lo[k] - p[k]).max(p[k] - n.hi[k]).max(0.0);
                d2 += d * d;
            }
            d2
        };
        let mut best: Option<(usize, f64, Vector3<f64>)> = None;
        let mut stack: Vec<(f64, usize)> = Vec::with_capacity(64);
        stack.push((box_d2(&self.nodes[0]), 0));
        while let Some((d2, id)) = stack.pop() {
            if best.is_some_and(|(_, bd, _)| d2 > bd) {
                continue;
            }
            let node = &self.nodes[id];
            if node.count > 0 {
                let start = node.start as usize;
                for &i in &self.order[start..start + node.count as usize] {
                    let i = i as usize;
                    let (d2, q) = dist2(i);
                    if best.is_none_or(|(bi, bd, _)| d2 < bd || (d2 == bd && i < bi)) {
                        best = Some((i, d2, q));
                    }
                }
            } else {
                let (a, b) = (id + 1, node.start as usize);
                let (da, db) = (box_d2(&self.nodes[a]), box_d2(&self.nodes[b]));
                // Nearer child on top of the stack.
                if da <= db {
                    stack.push((db, b));
                    stack.push((da, a));
                } else {
                    stack.push((da, a));
                    stack.push((db, b));
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
    tri_grid: Bvh,
    seg_grid: Bvh,
    /// Per segment: its boundary loop and the arc length of its start along that loop.
    seg_place: Vec<(usize, f64)>,
    /// Per boundary loop: its segments in order and its length.
    loops: Vec<(Vec<usize>, f64)>,
}

/// A point on the input boundary: which loop, how far along it, where.
#[derive(Debug, Clone, Copy)]
pub(crate) struct BoundaryPoint {
    /// The boundary loop.
    pub lp: usize,
    /// Arc length from the loop's start, in `[0, length)`.
    pub arc: f64,
    /// The point.
    pub point: Vector3<f64>,
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
        let _ = h;
        let tri_grid = Bvh::new(&boxes);
        let seg_boxes: Vec<_> = segments.iter().map(|s| (pos[s[0]].inf(&pos[s[1]]), pos[s[0]].sup(&pos[s[1]]))).collect();
        let seg_grid = Bvh::new(&seg_boxes);
        // Chain the segments into loops (each vertex starts at most one segment).
        let mut starting = vec![usize::MAX; pos.len()];
        for (i, sg) in segments.iter().enumerate() {
            starting[sg[0]] = i;
        }
        let mut seg_place = vec![(usize::MAX, 0.0); segments.len()];
        let mut loops = Vec::new();
        for first in 0..segments.len() {
            if seg_place[first].0 != usize::MAX {
                continue;
            }
            let id = loops.len();
            let mut order = Vec::new();
            let mut arc = 0.0;
            let mut i = first;
            while seg_place[i].0 == usize::MAX {
                seg_place[i] = (id, arc);
                order.push(i);
                let [a, b] = segments[i];
                arc += (pos[b] - pos[a]).norm();
                i = starting[b];
                if i == usize::MAX {
                    break;
                }
            }
            loops.push((order, arc));
        }
        Self { pos, tris, segments, corners, tri_grid, seg_grid, seg_place, loops }
    }

    /// Closest point on the boundary curves with its place along its loop.
    pub fn closest_boundary_at(&self, p: &Vector3<f64>) -> Option<BoundaryPoint> {
        let (i, _, point) = self.seg_grid.nearest(p, |i| {
            let [a, b] = self.segments[i];
            let q = closest_on_segment(p, &self.pos[a], &self.pos[b]);
            ((q - p).norm_squared(), q)
        })?;
        let (lp, start) = self.seg_place[i];
        let arc = start + (point - self.pos[self.segments[i][0]]).norm();
        Some(BoundaryPoint { lp, arc: arc.min(self.loops[lp].1).max(0.0), point })
    }

    /// Length of boundary loop `lp`.
    pub fn loop_length(&self, lp: usize) -> f64 {
        self.loops[lp].1
    }

    /// The point at arc length `arc` (taken modulo the length) along boundary loop `lp`.
    pub fn boundary_point(&self, lp: usize, arc: f64) -> Vector3<f64> {
        let (order, length) = &self.loops[lp];
        if order.is_empty() || *length <= 0.0 {
            return order.first().map_or_else(Vector3::zeros, |&i| self.pos[self.segments[i][0]]);
        }
        let arc = arc.rem_euclid(*length);
        let k = order.partition_point(|&i| self.seg_place[i].1 <= arc).max(1) - 1;
        let i = order[k];
        let [a, b] = self.segments[i];
        let l = (self.pos[b] - self.pos[a]).norm();
        if l <= 0.0 {
            return self.pos[a];
        }
        self.pos[a] + (self.pos[b] - self.pos[a]) * ((arc - self.seg_place[i].1) / l).clamp(0.0, 1.0)
    }

    /// The point of loop `lp` nearest to `p` among those between arc `from` and `from +
    /// span` (going forward, wrapping), as (offset from `from`, point).
    pub fn closest_on_arc(&self, lp: usize, from: f64, span: f64, p: &Vector3<f64>) -> (f64, Vector3<f64>) {
        let (order, length) = &self.loops[lp];
        let mut best = (f64::INFINITY, 0.0, self.boundary_point(lp, from));
        for &i in order {
            let [a, b] = self.segments[i];
            let l = (self.pos[b] - self.pos[a]).norm();
            let start = (self.seg_place[i].1 - from).rem_euclid(*length);
            // Parts of this segment inside the window, as offsets.
            let (lo, hi) = if start + l <= *length { (start, start + l) } else { (start - *length, start - *length + l) };
            let (lo, hi) = (lo.max(0.0), hi.min(span));
            if lo > hi {
                continue;
            }
            let (qa, qb) = (self.boundary_point(lp, from + lo), self.boundary_point(lp, from + hi));
            let q = closest_on_segment(p, &qa, &qb);
            let d = (q - p).norm_squared();
            if d < best.0 {
                let along = if hi > lo { lo + (q - qa).norm() } else { lo };
                best = (d, along, q);
            }
        }
        (best.1, best.2)
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
