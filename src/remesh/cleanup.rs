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
//! 5. the boundary is fitted to the input's ([`super::fit`]): rows are extended over gaps
//!    to the input boundary, boundary vertices snapped onto it (input corners onto corners),
//!    all others onto the surface, with a few rounds of tangential smoothing; faces that
//!    still leave the surface are pulled back, peeled and re-extended, halved along their
//!    quad strip, or (on the rim) dropped; edges are rotated where that makes vertices
//!    regular.

use std::collections::{BTreeMap, HashMap, VecDeque};

use nalgebra::Vector3;

use super::RemeshError;
use super::budget::{Budget, Stop};
use super::extract::Raw;
use super::fit;
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
///
/// The topology repair must finish (a stop there is an error); the fitting rounds after it
/// only improve a valid mesh, so when the time limit passes during them the mesh as it is
/// comes back.
pub(crate) fn pure_quads(raw: Raw, locator: &Locator, t: f64, budget: &mut Budget) -> Result<Quads, RemeshError> {
    let mut pos = raw.positions;
    let mut faces: Vec<Vec<usize>> = raw.faces.into_iter().filter(|f| distinct(f)).collect();
    make_edge_manifold(&mut faces);
    drop_small_components(&mut faces);
    fill_holes(&pos, &mut faces, locator, t);
    make_edge_manifold(&mut faces);
    make_quads(&mut pos, &mut faces, budget);
    budget.check()?;
    let (mut pos, mut faces) = compact(pos, faces);
    for p in pos.iter_mut() {
        *p = locator.closest(p).0;
    }
    let loops = boundary_loops(&faces);
    fit::extend_boundary(&mut pos, &mut faces, &loops, locator, t);
    relax(&mut pos, &faces, locator, t, 6);
    for round in 0..=FIT_ROUNDS {
        if !budget.poll(0.5 + 0.5 * round as f64 / (FIT_ROUNDS + 1) as f64) {
            match budget.stopped() {
                Some(Stop::Cancelled) => budget.check()?,
                _ => break,
            }
        }
        let anchors = Anchors::new(&mut pos, &faces, locator, t);
        fit::conform(&mut pos, &faces, &anchors, locator, t);
        // Faces at the boundary that still leave the surface are peeled off and the gap is
        // closed again by a fresh row extension; in the last round the new boundary vertices
        // are only put onto the input boundary, and the peeling is kept only if it helped.
        let bad: Vec<bool> = faces
            .iter()
            .map(|f| f.iter().any(|&v| !anchors.bnbrs[v].is_empty()) && fit::deviation(&pos, f, locator) > PEEL * t)
            .collect();
        if !bad.iter().any(|&b| b) {
            break;
        }
        let before = (round == FIT_ROUNDS).then(|| (pos.clone(), faces.clone()));
        let mut kept: Vec<Vec<usize>> = faces.iter().zip(&bad).filter(|(_, b)| !**b).map(|(f, _)| f.clone()).collect();
        drop_small_components(&mut kept);
        remove_doublets(&mut kept);
        let (p2, f2) = compact(pos, kept);
        pos = p2;
        faces = f2;
        if let Some((old_pos, old_faces)) = before {
            let anchors = Anchors::new(&mut pos, &faces, locator, t);
            for (v, p) in pos.iter_mut().enumerate() {
                if !anchors.bnbrs[v].is_empty() && !anchors.pinned[v] {
                    *p = anchors.project(locator, v, p);
                }
            }
            fit::conform(&mut pos, &faces, &anchors, locator, t);
            let worst = |pos: &[Vector3<f64>], faces: &[Vec<usize>]| faces.iter().map(|f| fit::deviation(pos, f, locator)).fold(0.0, f64::max);
            let on_boundary = (0..pos.len()).all(|v| {
                anchors.bnbrs[v].is_empty() || locator.closest_boundary(&pos[v]).is_some_and(|q| (q - pos[v]).norm() <= 0.04 * t)
            });
            if !on_boundary || worst(&pos, &faces) >= worst(&old_pos, &old_faces) {
                pos = old_pos;
                faces = old_faces;
            }
        } else {
            let loops = boundary_loops(&faces);
            fit::extend_boundary(&mut pos, &mut faces, &loops, locator, t);
            relax(&mut pos, &faces, locator, t, 2);
        }
    }
    rotate_edges(&pos, &mut faces);
    remove_doublets(&mut faces);
    for _ in 0..SPLIT_ROUNDS {
        if !split_unfit_faces(&mut pos, &mut faces, locator, t) {
            break;
        }
    }
    let anchors = Anchors::new(&mut pos, &faces, locator, t);
    fit::shorten_boundary_chords(&mut pos, &faces, &anchors, locator, FINAL * t);
    drop_unfit_rim_faces(&mut pos, &mut faces, locator, t);
    drop_rim_slivers(&pos, &mut faces, locator, t);
    split_pinched_vertices(&mut pos, &mut faces);
    let (pos, faces) = compact(pos, faces);
    if faces.is_empty() {
        return Err(RemeshError::NothingExtracted(t));
    }
    Ok(Quads { positions: pos.iter().map(|&p| p.into()).collect(), faces })
}

/// Drops faces with (almost) no area whose corners all lie on the input boundary: slivers
/// that row extension and strip splitting can leave along a ragged rim. Nothing is exposed
/// that is off the boundary.
fn drop_rim_slivers(pos: &[Vector3<f64>], faces: &mut Vec<Vec<usize>>, locator: &Locator, t: f64) {
    let on_rim = |v: usize| locator.closest_boundary(&pos[v]).is_some_and(|q| (q - pos[v]).norm() <= 0.04 * t);
    let area = |f: &[usize]| {
        let k = f.len();
        (0..k).fold(Vector3::zeros(), |acc: Vector3<f64>, i| acc + pos[f[i]].cross(&pos[f[(i + 1) % k]])).norm() * 0.5
    };
    let before = faces.len();
    faces.retain(|f| !(area(f) < SLIVER * t * t && f.iter().all(|&v| on_rim(v))));
    if faces.len() != before {
        drop_small_components(faces);
    }
}

/// Area (times `t` squared) below which a rim face is a sliver.
const SLIVER: f64 = 0.05;

/// Rounds of peeling and re-extending boundary faces that leave the surface.
const FIT_ROUNDS: usize = 4;

/// Faces that still leave the surface after fitting span more surface than a quad can follow
/// there (a crumpled support). Each is halved across its long sides together with the rest of
/// its quad strip (chord), when that strip runs to the boundary within a few faces both
/// ways: splitting a whole strip keeps every face a quad and adds no irregular vertex.
/// Returns whether anything changed.
fn split_unfit_faces(pos: &mut Vec<Vector3<f64>>, faces: &mut Vec<Vec<usize>>, locator: &Locator, t: f64) -> bool {
    let limit = FINAL * t;
    let map = edge_faces(faces);
    let other = |e: (usize, usize), f: usize| -> Option<usize> { map.get(&e).and_then(|l| l.iter().copied().find(|&g| g != f)) };
    let edge = |f: &[usize], i: usize| key(f[i % 4], f[(i + 1) % 4]);
    let mut in_chord = vec![false; faces.len()];
    // (face, index of its first split edge) for every face of every accepted chord.
    let mut splits: Vec<(usize, usize)> = Vec::new();
    for f0 in 0..faces.len() {
        if in_chord[f0] || faces[f0].len() != 4 || fit::deviation(pos, &faces[f0], locator) <= limit {
            continue;
        }
        // Split across the sides whose midpoints leave the surface most, or across the
        // longer sides when only the centre does.
        let q = &faces[f0];
        let len = |i: usize| (pos[q[i]] - pos[q[(i + 1) % 4]]).norm() + (pos[q[(i + 2) % 4]] - pos[q[(i + 3) % 4]]).norm();
        let off = |i: usize| locator.distance(&((pos[q[i % 4]] + pos[q[(i + 1) % 4]]) * 0.5));
        let worst = |i: usize| off(i).max(off(i + 2));
        let i0 = if worst(0).max(worst(1)) > limit {
            if worst(0) >= worst(1) { 0 } else { 1 }
        } else if len(0) >= len(1) {
            0
        } else {
            1
        };
        let mut chord = vec![(f0, i0)];
        let mut ok = true;
        // Walk across the split edges both ways.
        for start_edge in [i0, i0 + 2] {
            let (mut f, mut e) = (f0, edge(&faces[f0], start_edge));
            while let Some(g) = other(e, f) {
                if g == f0 || faces[g].len() != 4 || in_chord[g] || chord.iter().any(|&(h, _)| h == g) || chord.len() >= MAX_CHORD {
                    ok = false;
                    break;
                }
                let Some(k) = (0..4).find(|&k| edge(&faces[g], k) == e) else {
                    ok = false;
                    break;
                };
                chord.push((g, k % 2));
                f = g;
                e = edge(&faces[g], k + 2);
            }
            if !ok {
                break;
            }
        }
        if !ok {
            continue;
        }
        for &(g, k) in &chord {
            in_chord[g] = true;
            splits.push((g, k));
        }
    }
    if splits.is_empty() {
        return false;
    }
    let mut mids: BTreeMap<(usize, usize), usize> = BTreeMap::new();
    let mut mid = |pos: &mut Vec<Vector3<f64>>, a: usize, b: usize| -> usize {
        *mids.entry(key(a, b)).or_insert_with(|| {
            let m = (pos[a] + pos[b]) * 0.5;
            let boundary = map.get(&key(a, b)).is_some_and(|l| l.len() == 1);
            let q = if boundary { locator.closest_boundary(&m).unwrap_or_else(|| locator.closest(&m).0) } else { locator.closest(&m).0 };
            pos.push(q);
            pos.len() - 1
        })
    };
    let mut added = Vec::new();
    for &(g, k) in &splits {
        let f = faces[g].clone();
        let v = |i: usize| f[(k + i) % 4];
        let ma = mid(pos, v(0), v(1));
        let mb = mid(pos, v(2), v(3));
        faces[g] = vec![v(0), ma, mb, v(3)];
        added.push(vec![ma, v(1), v(2), mb]);
    }
    faces.extend(added);
    let anchors = Anchors::new(pos, faces, locator, t);
    fit::conform(pos, faces, &anchors, locator, t);
    true
}

/// Longest quad strip [`split_unfit_faces`] halves.
const MAX_CHORD: usize = 12;

/// Rounds of [`split_unfit_faces`].
const SPLIT_ROUNDS: usize = 2;

/// Drops faces at the rim that still leave the surface (a quad spanning a fold of slivers
/// at a support), one at a time and only where the vertices this exposes can go onto the
/// input boundary without pushing a neighbouring face off the surface.
fn drop_unfit_rim_faces(pos: &mut [Vector3<f64>], faces: &mut Vec<Vec<usize>>, locator: &Locator, t: f64) {
    let limit = FINAL * t;
    let mut candidates: Vec<usize> = (0..faces.len()).filter(|&f| fit::deviation(pos, &faces[f], locator) > limit).collect();
    if candidates.is_empty() {
        return;
    }
    let mut gone = vec![false; faces.len()];
    let mut incident: Vec<Vec<usize>> = vec![Vec::new(); pos.len()];
    for (fi, f) in faces.iter().enumerate() {
        for &v in f {
            incident[v].push(fi);
        }
    }
    let mut count: BTreeMap<(usize, usize), usize> = BTreeMap::new();
    for f in faces.iter() {
        for i in 0..f.len() {
            *count.entry(key(f[i], f[(i + 1) % f.len()])).or_default() += 1;
        }
    }
    let on_boundary = |v: usize, count: &BTreeMap<(usize, usize), usize>, gone: &[bool]| {
        incident[v].iter().filter(|&&g| !gone[g]).any(|&g| {
            let f = &faces[g];
            let i = f.iter().position(|&w| w == v).unwrap_or(0);
            let k = f.len();
            count.get(&key(v, f[(i + 1) % k])) == Some(&1) || count.get(&key(v, f[(i + k - 1) % k])) == Some(&1)
        })
    };
    candidates.sort_unstable();
    for fi in candidates {
        let f = faces[fi].clone();
        if !f.iter().any(|&v| on_boundary(v, &count, &gone)) {
            continue;
        }
        let exposed: Vec<usize> = f.iter().copied().filter(|&v| !on_boundary(v, &count, &gone)).collect();
        let mut moves = Vec::new();
        let mut ok = true;
        for &v in &exposed {
            match locator.closest_boundary(&pos[v]) {
                Some(q) if (q - pos[v]).norm() <= 0.35 * t => moves.push((v, pos[v], q)),
                _ => ok = false,
            }
        }
        if !ok {
            continue;
        }
        gone[fi] = true;
        let around: Vec<usize> = {
            let mut list: Vec<usize> = moves.iter().flat_map(|&(v, _, _)| incident[v].iter().copied()).filter(|&g| !gone[g]).collect();
            list.sort_unstable();
            list.dedup();
            list
        };
        let before: Vec<f64> = around.iter().map(|&g| fit::deviation(pos, &faces[g], locator)).collect();
        for &(v, _, q) in &moves {
            pos[v] = q;
        }
        let fine = around.iter().zip(&before).all(|(&g, &b)| fit::deviation(pos, &faces[g], locator) <= limit.max(b + 0.01 * t));
        if fine {
            for i in 0..f.len() {
                if let Some(c) = count.get_mut(&key(f[i], f[(i + 1) % f.len()])) {
                    *c -= 1;
                }
            }
        } else {
            gone[fi] = false;
            for &(v, old, _) in &moves {
                pos[v] = old;
            }
        }
    }
    let mut k = 0;
    faces.retain(|_| {
        k += 1;
        !gone[k - 1]
    });
    drop_small_components(faces);
}

/// Deviation (times `t`) above which [`drop_unfit_rim_faces`] drops a rim face.
const FINAL: f64 = 0.095;

/// Deviation from the surface (times `t`) at which a boundary face is peeled off.
const PEEL: f64 = 0.08;

/// Components with fewer faces than this are dropped (stray faces of a garbled lattice).
const MIN_COMPONENT: usize = 4;

/// Topology repair: triangles paired, odd faces evened, even polygons cut, doublets merged.
fn make_quads(pos: &mut Vec<Vector3<f64>>, faces: &mut Vec<Vec<usize>>, budget: &mut Budget) {
    merge_triangles(pos, faces);
    pair_odd_faces(pos, faces, budget);
    split_even(pos, faces);
    remove_doublets(faces);
}

/// Drops edge-connected components with fewer than [`MIN_COMPONENT`] faces.
fn drop_small_components(faces: &mut Vec<Vec<usize>>) {
    let map = edge_faces(faces);
    let mut component = vec![usize::MAX; faces.len()];
    let mut sizes = Vec::new();
    for seed in 0..faces.len() {
        if component[seed] != usize::MAX {
            continue;
        }
        let id = sizes.len();
        component[seed] = id;
        let mut stack = vec![seed];
        let mut size = 0;
        while let Some(f) = stack.pop() {
            size += 1;
            let face = &faces[f];
            for i in 0..face.len() {
                for &g in &map[&key(face[i], face[(i + 1) % face.len()])] {
                    if component[g] == usize::MAX {
                        component[g] = id;
                        stack.push(g);
                    }
                }
            }
        }
        sizes.push(size);
    }
    let mut k = 0;
    faces.retain(|_| {
        let keep = sizes[component[k]] >= MIN_COMPONENT;
        k += 1;
        keep
    });
}

/// Gives every fan of faces around a vertex its own copy of the vertex, so two boundary
/// loops touching at a vertex (after peeling) leave a manifold mesh.
fn split_pinched_vertices(pos: &mut Vec<Vector3<f64>>, faces: &mut [Vec<usize>]) {
    let n = pos.len();
    // Corners (face, index) around each vertex.
    let mut around: Vec<Vec<(usize, usize)>> = vec![Vec::new(); n];
    for (fi, f) in faces.iter().enumerate() {
        for (i, &v) in f.iter().enumerate() {
            around[v].push((fi, i));
        }
    }
    for v in 0..n {
        let corners = &around[v];
        if corners.len() < 2 {
            continue;
        }
        // Union corners that share an edge at v.
        let mut parent: Vec<usize> = (0..corners.len()).collect();
        fn root(parent: &mut [usize], mut x: usize) -> usize {
            while parent[x] != x {
                parent[x] = parent[parent[x]];
                x = parent[x];
            }
            x
        }
        let neighbours = |&(fi, i): &(usize, usize)| {
            let f = &faces[fi];
            let k = f.len();
            [f[(i + 1) % k], f[(i + k - 1) % k]]
        };
        for a in 0..corners.len() {
            for b in a + 1..corners.len() {
                let (na, nb) = (neighbours(&corners[a]), neighbours(&corners[b]));
                if na.iter().any(|w| nb.contains(w)) {
                    let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
                    parent[ra.max(rb)] = ra.min(rb);
                }
            }
        }
        let roots: Vec<usize> = (0..corners.len()).map(|a| root(&mut parent, a)).collect();
        let mut copies: BTreeMap<usize, usize> = BTreeMap::new();
        for (a, &(fi, i)) in corners.iter().enumerate() {
            if roots[a] == roots[0] {
                continue;
            }
            let copy = *copies.entry(roots[a]).or_insert_with(|| {
                pos.push(pos[v]);
                pos.len() - 1
            });
            faces[fi][i] = copy;
        }
    }
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
        // A loop around a single face (a stray face) is not a hole.
        let mut sorted = lp.clone();
        sorted.sort_unstable();
        if faces.iter().any(|f| f.len() == sorted.len() && {
            let mut g = f.clone();
            g.sort_unstable();
            g == sorted
        }) {
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
fn pair_odd_faces(pos: &mut Vec<Vector3<f64>>, faces: &mut [Vec<usize>], budget: &mut Budget) {
    // Kept up to date as edges are split (each half keeps the edge's faces, in order).
    let mut map = edge_faces(faces);
    loop {
        let Some(f0) = faces.iter().position(|f| f.len() % 2 == 1) else { return };
        if !budget.poll(0.25) {
            return;
        }
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
            let list = map.remove(&(a, b)).unwrap_or_default();
            for &fi in &list {
                let f = &mut faces[fi];
                let n = f.len();
                if let Some(i) = (0..n).find(|&i| key(f[i], f[(i + 1) % n]) == (a, b)) {
                    f.insert(i + 1, m);
                }
            }
            map.insert(key(a, m), list.clone());
            map.insert(key(m, b), list);
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

/// Rotates interior edges between two quads where that brings the valences of the four
/// vertices involved closer to four (Bommes et al.'s quad mesh "edge rotation"): a 5 next
/// to a 3 across a quad, left by the lattice at a crumpled spot, becomes two regular
/// vertices. Only rotations whose two new quads are no worse shaped than a bound are made.
fn rotate_edges(pos: &[Vector3<f64>], faces: &mut [Vec<usize>]) {
    for _ in 0..ROTATION_PASSES {
        let map = edge_faces(faces);
        let mut valence = vec![0i64; pos.len()];
        let mut boundary = vec![false; pos.len()];
        for (&(a, b), list) in &map {
            valence[a] += 1;
            valence[b] += 1;
            if list.len() != 2 {
                boundary[a] = true;
                boundary[b] = true;
            }
        }
        let mut changed = false;
        let mut touched = vec![false; faces.len()];
        for (&(a, b), list) in &map {
            let [f1, f2] = list.as_slice() else { continue };
            let (f1, f2) = (*f1, *f2);
            if touched[f1] || touched[f2] || faces[f1].len() != 4 || faces[f2].len() != 4 {
                continue;
            }
            // Orient: f1 has a -> b, f2 has b -> a.
            let has = |f: &[usize], x: usize, y: usize| (0..4).any(|i| f[i] == x && f[(i + 1) % 4] == y);
            let (f1, f2) = if has(&faces[f1], a, b) { (f1, f2) } else { (f2, f1) };
            if !has(&faces[f1], a, b) || !has(&faces[f2], b, a) {
                continue;
            }
            let turn = |f: &[usize], start: usize| -> [usize; 4] {
                let i = f.iter().position(|&v| v == start).unwrap_or(0);
                [f[i], f[(i + 1) % 4], f[(i + 2) % 4], f[(i + 3) % 4]]
            };
            let [_, _, c, d] = turn(&faces[f1], a);
            let [_, _, e, f] = turn(&faces[f2], b);
            // Hexagon a e f b c d; the edge ab may rotate to e-c or to f-d.
            let hexagon = [a, e, f, b, c, d];
            if hexagon.iter().enumerate().any(|(i, v)| hexagon[i + 1..].contains(v)) {
                continue;
            }
            let cost = |v: usize, delta: i64| -> i64 {
                if boundary[v] { 0 } else { (valence[v] + delta - 4).pow(2) }
            };
            let now = cost(a, 0) + cost(b, 0) + cost(c, 0) + cost(d, 0) + cost(e, 0) + cost(f, 0);
            if [a, b].iter().any(|&v| boundary[v]) {
                continue;
            }
            let shape_now = quad_cost(pos, [a, b, c, d]) + quad_cost(pos, [b, a, e, f]);
            let options = [
                ([e, c], [[e, f, b, c], [c, d, a, e]]),
                ([f, d], [[f, b, c, d], [d, a, e, f]]),
            ];
            let mut best: Option<(i64, f64, [[usize; 4]; 2])> = None;
            for ([p, q], quads) in options {
                if boundary[p] || boundary[q] || map.contains_key(&key(p, q)) {
                    continue;
                }
                let after = cost(a, -1) + cost(b, -1) + cost(p, 1) + cost(q, 1)
                    + [c, d, e, f].iter().filter(|&&v| v != p && v != q).map(|&v| cost(v, 0)).sum::<i64>();
                let shape = quad_cost(pos, quads[0]) + quad_cost(pos, quads[1]);
                if after < now && shape <= shape_now + ROTATION_SHAPE_SLACK && best.is_none_or(|(c0, s0, _)| (after, shape) < (c0, s0)) {
                    best = Some((after, shape, quads));
                }
            }
            if let Some((_, _, [q1, q2])) = best {
                faces[f1] = q1.to_vec();
                faces[f2] = q2.to_vec();
                touched[f1] = true;
                touched[f2] = true;
                changed = true;
            }
        }
        if !changed {
            return;
        }
    }
}

/// Passes of [`rotate_edges`].
const ROTATION_PASSES: usize = 6;

/// How much worse (summed corner deviation, radians) two quads may get by a rotation.
const ROTATION_SHAPE_SLACK: f64 = 0.6;

/// Merges the two quads around every interior vertex of valence two (a doublet, left where
/// rows from two sides meet along a seam) into one quad, which makes both ends of the seam
/// edge regular again.
fn remove_doublets(faces: &mut Vec<Vec<usize>>) {
    loop {
        let mut around: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
        for (fi, f) in faces.iter().enumerate() {
            for &v in f {
                around.entry(v).or_default().push(fi);
            }
        }
        let map = edge_faces(faces);
        let mut gone = vec![false; faces.len()];
        let mut added = Vec::new();
        for (&v, list) in &around {
            let [f1, f2] = list.as_slice() else { continue };
            if gone[*f1] || gone[*f2] || faces[*f1].len() != 4 || faces[*f2].len() != 4 {
                continue;
            }
            let turn = |f: &[usize]| -> Option<[usize; 3]> {
                let i = f.iter().position(|&w| w == v)?;
                Some([f[(i + 1) % 4], f[(i + 2) % 4], f[(i + 3) % 4]])
            };
            let (Some([p1, q1, r1]), Some([p2, q2, r2])) = (turn(&faces[*f1]), turn(&faces[*f2])) else { continue };
            // Interior: both edges at v are shared by exactly these two faces.
            let interior = [p1, r1].iter().all(|&w| map.get(&key(v, w)).is_some_and(|l| l.len() == 2));
            if !interior || p1 != r2 || r1 != p2 || q1 == q2 {
                continue;
            }
            gone[*f1] = true;
            gone[*f2] = true;
            added.push(vec![p1, q1, p2, q2]);
        }
        if added.is_empty() {
            return;
        }
        let mut kept: Vec<Vec<usize>> = faces.iter().enumerate().filter(|(i, _)| !gone[*i]).map(|(_, f)| f.clone()).collect();
        kept.extend(added);
        *faces = kept;
    }
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

