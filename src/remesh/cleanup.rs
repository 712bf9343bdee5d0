//! From extracted polygons to a pure, manifold quad mesh on the input surface.
//!
//! Instant Meshes' pure-quad mode subdivides everything once (Catmull-Clark-like), which
//! halves the edge and so is useless for tiles. Instead the few non-quads are repaired
//! locally at the target size:
//!
//! 1. holes left by extraction (cycles too long to be faces, away from the input boundary)
//!    become polygons;
//! 2. adjacent triangle pairs merge into quads;
//! 3. faces with an odd number of sides are paired along shortest dual paths (or led to the
//!    boundary) and the crossed edges split, which makes every face even (the classic parity
//!    argument: a polygon mesh can be quadrangulated without subdivision everywhere exactly
//!    when each component has an even number of odd faces, and a boundary edge split fixes
//!    the parity otherwise);
//! 4. even polygons are cut into quads by their best diagonals;
//! 5. boundary vertices are snapped onto the input boundary (input corners onto corners),
//!    all others onto the surface, with a few rounds of tangential smoothing.

use std::collections::{BTreeMap, HashMap, VecDeque};

use nalgebra::Vector3;

use super::RemeshError;
use super::extract::Raw;
use super::surface::Locator;

/// A quad mesh in progress.
#[derive(Debug, Clone)]
pub(crate) struct Quads {
    /// Vertex positions.
    pub positions: Vec<nalgebra::Point3<f64>>,
    /// Faces (all quads unless repair failed somewhere).
    pub faces: Vec<Vec<usize>>,
}

/// Runs the repair steps listed in the module documentation.
pub(crate) fn pure_quads(raw: Raw, locator: &Locator, t: f64) -> Result<Quads, RemeshError> {
    let mut pos = raw.positions;
    let mut faces: Vec<Vec<usize>> = raw.faces.into_iter().filter(|f| distinct(f)).collect();
    make_edge_manifold(&mut faces);
    fill_holes(&pos, &mut faces, locator, t);
    make_edge_manifold(&mut faces);
    merge_triangles(&pos, &mut faces);
    pair_odd_faces(&mut pos, &mut faces);
    split_even(&pos, &mut faces);
    let (mut pos, faces) = compact(pos, faces);
    relax(&mut pos, &faces, locator, t, 6);
    if faces.is_empty() {
        return Err(RemeshError::NothingExtracted(t));
    }
    Ok(Quads { positions: pos.iter().map(super::surface::point).collect(), faces })
}

fn distinct(f: &[usize]) -> bool {
    f.iter().enumerate().all(|(i, v)| !f[i + 1..].contains(v))
}

/// Drops faces that would use a directed edge a second time (crossing links).
fn make_edge_manifold(faces: &mut Vec<Vec<usize>>) {
    let mut seen: HashMap<(usize, usize), ()> = HashMap::new();
    faces.retain(|f| {
        let directed: Vec<(usize, usize)> = (0..f.len()).map(|i| (f[i], f[(i + 1) % f.len()])).collect();
        if directed.iter().any(|d| seen.contains_key(d)) {
            return false;
        }
        for d in directed {
            seen.insert(d, ());
        }
        true
    });
}

/// Undirected edge key.
fn key(a: usize, b: usize) -> (usize, usize) {
    (a.min(b), a.max(b))
}

/// Undirected edge -> faces containing it, in face order.
fn edge_faces(faces: &[Vec<usize>]) -> BTreeMap<(usize, usize), Vec<usize>> {
    let mut map: BTreeMap<(usize, usize), Vec<usize>> = BTreeMap::new();
    for (fi, f) in faces.iter().enumerate() {
        for i in 0..f.len() {
            map.entry(key(f[i], f[(i + 1) % f.len()])).or_default().push(fi);
        }
    }
    map
}

/// Boundary loops of the face set, each as the sequence of vertices along boundary
/// half-edges (faces on the left).
fn boundary_loops(faces: &[Vec<usize>]) -> Vec<Vec<usize>> {
    let mut directed: BTreeMap<(usize, usize), usize> = BTreeMap::new();
    for f in faces {
        for i in 0..f.len() {
            *directed.entry((f[i], f[(i + 1) % f.len()])).or_default() += 1;
        }
    }
    let mut out: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for &(a, b) in directed.keys() {
        if !directed.contains_key(&(b, a)) {
            out.entry(a).or_default().push(b);
        }
    }
    let mut loops = Vec::new();
    let starts: Vec<usize> = out.keys().copied().collect();
    for s in starts {
        while out.get(&s).is_some_and(|l| !l.is_empty()) {
            let mut walk = vec![s];
            let mut cur = s;
            while let Some(next) = out.get_mut(&cur).and_then(|list| list.pop()) {
                if next == s {
                    break;
                }
                walk.push(next);
                cur = next;
                if walk.len() > faces.len() * 4 + 8 {
                    break;
                }
            }
            // Split figure-eights at repeated vertices into simple loops.
            let mut stack: Vec<usize> = Vec::new();
            for v in walk {
                if let Some(p) = stack.iter().position(|&w| w == v) {
                    let sub: Vec<usize> = stack.drain(p..).collect();
                    if sub.len() >= 3 {
                        loops.push(sub);
                    }
                }
                stack.push(v);
            }
            if stack.len() >= 3 {
                loops.push(stack);
            }
        }
    }
    loops
}

/// Turns extraction holes (short boundary loops, mostly away from the input boundary) into
/// polygons. Long loops are the outline (or openings) of the shell and stay open.
fn fill_holes(pos: &[Vector3<f64>], faces: &mut Vec<Vec<usize>>, locator: &Locator, t: f64) {
    for lp in boundary_loops(faces) {
        if lp.len() > MAX_HOLE {
            continue;
        }
        let near = lp
            .iter()
            .filter(|&&v| locator.closest_boundary(&pos[v]).is_some_and(|q| (q - pos[v]).norm() < 0.75 * t))
            .count();
        if near * 2 >= lp.len() {
            continue;
        }
        let mut face = lp;
        face.reverse();
        faces.push(face);
    }
}

/// Longest boundary loop that can be an extraction hole.
const MAX_HOLE: usize = 24;

/// Quality of a quad: summed corner deviation from 90 degrees (radians), plus a penalty for
/// reflex corners with respect to the quad's own normal.
fn quad_cost(pos: &[Vector3<f64>], q: [usize; 4]) -> f64 {
    let p: Vec<Vector3<f64>> = q.iter().map(|&v| pos[v]).collect();
    let normal = (p[2] - p[0]).cross(&(p[3] - p[1]));
    let mut cost = 0.0;
    for i in 0..4 {
        let a = p[(i + 3) % 4] - p[i];
        let b = p[(i + 1) % 4] - p[i];
        let angle = a.angle(&b);
        cost += (angle - std::f64::consts::FRAC_PI_2).abs();
        if b.cross(&a).dot(&normal) < 0.0 {
            cost += std::f64::consts::PI;
        }
    }
    cost
}

/// Merges adjacent triangles into quads, best pairs first.
fn merge_triangles(pos: &[Vector3<f64>], faces: &mut Vec<Vec<usize>>) {
    let map = edge_faces(faces);
    let mut candidates: Vec<(f64, usize, usize, [usize; 4])> = Vec::new();
    for (&(a, b), list) in &map {
        if let [f, g] = list.as_slice() {
            if faces[*f].len() == 3 && faces[*g].len() == 3 {
                let tri = &faces[*f];
                let i = (0..3).find(|&i| key(tri[i], tri[(i + 1) % 3]) == (a, b)).unwrap_or(0);
                let (x, y, z) = (tri[i], tri[(i + 1) % 3], tri[(i + 2) % 3]);
                let Some(&d) = faces[*g].iter().find(|&&v| v != x && v != y) else { continue };
                if d == z {
                    continue;
                }
                let quad = [x, d, y, z];
                candidates.push((quad_cost(pos, quad), *f, *g, quad));
            }
        }
    }
    candidates.sort_by(|p, q| p.0.total_cmp(&q.0).then(p.1.cmp(&q.1)).then(p.2.cmp(&q.2)));
    let mut gone = vec![false; faces.len()];
    let mut added = Vec::new();
    for (_, f, g, quad) in candidates {
        if !gone[f] && !gone[g] {
            gone[f] = true;
            gone[g] = true;
            added.push(quad.to_vec());
        }
    }
    let mut kept: Vec<Vec<usize>> = faces.iter().enumerate().filter(|(i, _)| !gone[*i]).map(|(_, f)| f.clone()).collect();
    kept.extend(added);
    *faces = kept;
}

/// Pairs odd faces along shortest dual paths (or to the boundary) and splits the crossed
/// edges at their midpoints, so every face gets an even number of sides.
fn pair_odd_faces(pos: &mut Vec<Vector3<f64>>, faces: &mut [Vec<usize>]) {
    loop {
        let Some(f0) = faces.iter().position(|f| f.len() % 2 == 1) else { return };
        let map = edge_faces(faces);
        // BFS over faces; `from[g]` = (previous face, edge crossed).
        let mut from: Vec<Option<(usize, (usize, usize))>> = vec![None; faces.len()];
        let mut seen = vec![false; faces.len()];
        seen[f0] = true;
        let mut queue = VecDeque::from([f0]);
        let mut end: Option<(usize, Option<(usize, usize)>)> = None;
        'search: while let Some(g) = queue.pop_front() {
            if g != f0 && faces[g].len() % 2 == 1 {
                end = Some((g, None));
                break;
            }
            let f = &faces[g];
            for i in 0..f.len() {
                let e = key(f[i], f[(i + 1) % f.len()]);
                if map.get(&e).is_some_and(|l| l.len() == 1) {
                    end = Some((g, Some(e)));
                    break 'search;
                }
            }
            for i in 0..f.len() {
                let e = key(f[i], f[(i + 1) % f.len()]);
                for &h in map.get(&e).into_iter().flatten() {
                    if !seen[h] {
                        seen[h] = true;
                        from[h] = Some((g, e));
                        queue.push_back(h);
                    }
                }
            }
        }
        let Some((last, boundary_edge)) = end else {
            // A closed component with a single odd face cannot occur (parity); give up on
            // this face rather than loop.
            return;
        };
        let mut cut: Vec<(usize, usize)> = boundary_edge.into_iter().collect();
        let mut g = last;
        while let Some((prev, e)) = from[g] {
            cut.push(e);
            g = prev;
        }
        for (a, b) in cut {
            let m = pos.len();
            pos.push((pos[a] + pos[b]) * 0.5);
            for &fi in map.get(&(a, b)).into_iter().flatten() {
                let f = &mut faces[fi];
                let n = f.len();
                if let Some(i) = (0..n).find(|&i| key(f[i], f[(i + 1) % n]) == (a, b)) {
                    f.insert(i + 1, m);
                }
            }
        }
    }
}

/// Cuts even polygons with six or more sides into quads, best ear first.
fn split_even(pos: &[Vector3<f64>], faces: &mut Vec<Vec<usize>>) {
    let mut existing: std::collections::BTreeSet<(usize, usize)> = edge_faces(faces).into_keys().collect();
    let mut out = Vec::with_capacity(faces.len());
    for f in faces.drain(..) {
        let mut rest = f;
        while rest.len() >= 6 && rest.len() % 2 == 0 {
            let n = rest.len();
            let best = (0..n)
                .filter(|&i| !existing.contains(&key(rest[i], rest[(i + 3) % n])))
                .map(|i| {
                    let q = [rest[i], rest[(i + 1) % n], rest[(i + 2) % n], rest[(i + 3) % n]];
                    (quad_cost(pos, q), i, q)
                })
                .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
            let Some((_, i, q)) = best else { break };
            existing.insert(key(q[0], q[3]));
            out.push(q.to_vec());
            // Remove the two ear vertices i+1, i+2.
            let (r1, r2) = ((i + 1) % n, (i + 2) % n);
            rest = rest.iter().enumerate().filter(|(k, _)| *k != r1 && *k != r2).map(|(_, &v)| v).collect();
        }
        out.push(rest);
    }
    *faces = out;
}

/// Drops unused vertices, keeping order.
fn compact(pos: Vec<Vector3<f64>>, faces: Vec<Vec<usize>>) -> (Vec<Vector3<f64>>, Vec<Vec<usize>>) {
    let mut remap = vec![usize::MAX; pos.len()];
    let mut out = Vec::new();
    let faces = faces
        .into_iter()
        .map(|f| {
            f.into_iter()
                .map(|v| {
                    if remap[v] == usize::MAX {
                        remap[v] = out.len();
                        out.push(pos[v]);
                    }
                    remap[v]
                })
                .collect()
        })
        .collect();
    (out, faces)
}

/// Which quad vertices slide on the input boundary and which sit on input corners, with the
/// neighbourhoods smoothing and shape-up need.
#[derive(Debug, Clone)]
pub(crate) struct Anchors {
    /// Neighbours along edges.
    pub nbrs: Vec<Vec<usize>>,
    /// Neighbours along boundary edges (empty for interior vertices).
    pub bnbrs: Vec<Vec<usize>>,
    /// Vertices held on an input corner.
    pub pinned: Vec<bool>,
}

impl Anchors {
    /// Finds the boundary of `faces` and moves the nearest boundary vertex onto each input
    /// corner (within 0.75 t).
    pub fn new(pos: &mut [Vector3<f64>], faces: &[Vec<usize>], locator: &Locator, t: f64) -> Self {
        let n = pos.len();
        let map = edge_faces(faces);
        let mut nbrs: Vec<Vec<usize>> = vec![Vec::new(); n];
        let mut bnbrs: Vec<Vec<usize>> = vec![Vec::new(); n];
        for (&(a, b), list) in &map {
            nbrs[a].push(b);
            nbrs[b].push(a);
            if list.len() == 1 {
                bnbrs[a].push(b);
                bnbrs[b].push(a);
            }
        }
        let mut pinned = vec![false; n];
        for c in locator.corners() {
            let best = (0..n)
                .filter(|&v| !bnbrs[v].is_empty() && !pinned[v])
                .map(|v| ((pos[v] - c).norm(), v))
                .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
            if let Some((d, v)) = best {
                if d < 0.75 * t {
                    pos[v] = *c;
                    pinned[v] = true;
                }
            }
        }
        Self { nbrs, bnbrs, pinned }
    }

    /// Where vertex `v` wanting to be at `p` may go: the closest boundary point for boundary vertices, the closest surface point otherwise.
    pub fn project(&self, locator: &Locator, v: usize, p: &Vector3<f64>) -> Vector3<f64> {
        if self.bnbrs[v].is_empty() {
            locator.closest(p).0
        } else {
            locator.closest_boundary(p).unwrap_or_else(|| locator.closest(p).0)
        }
    }
}

/// Snaps boundary vertices onto the input boundary (input corners onto corners), the rest
/// onto the surface, with `rounds` of damped Laplacian smoothing in between.
fn relax(pos: &mut [Vector3<f64>], faces: &[Vec<usize>], locator: &Locator, t: f64, rounds: usize) {
    let n = pos.len();
    let anchors = Anchors::new(pos, faces, locator, t);
    for (v, p) in pos.iter_mut().enumerate() {
        if !anchors.pinned[v] {
            *p = anchors.project(locator, v, p);
        }
    }
    for _ in 0..rounds {
        let old = pos.to_vec();
        for v in 0..n {
            if anchors.pinned[v] {
                continue;
            }
            let list = if anchors.bnbrs[v].is_empty() { &anchors.nbrs[v] } else { &anchors.bnbrs[v] };
            if list.is_empty() {
                continue;
            }
            let mean = list.iter().fold(Vector3::zeros(), |acc, &w| acc + old[w]) / list.len() as f64;
            pos[v] = anchors.project(locator, v, &(old[v] * 0.5 + mean * 0.5));
        }
    }
}
