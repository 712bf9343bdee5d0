//! Making vertices regular: edges between two quads rotated where that brings valences
//! closer to four, and the two quads around a valence-two vertex merged.

use std::collections::{BTreeMap, BTreeSet};

use nalgebra::Vector3;

use crate::remesh::quadmesh::{corners_key, edge_faces, key, quad_cost, replace_faces};

/// Rotates interior edges between two quads where that brings the valences of the four
/// vertices involved closer to four (Bommes et al.'s quad mesh "edge rotation"): a 5 next
/// to a 3 across a quad, left by the lattice at a crumpled spot, becomes two regular
/// vertices. Only rotations whose two new quads are no worse shaped than a bound are made.
pub(super) fn rotate_edges(pos: &[Vector3<f64>], faces: &mut [Vec<usize>]) {
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
            let has =
                |f: &[usize], x: usize, y: usize| (0..4).any(|i| f[i] == x && f[(i + 1) % 4] == y);
            let (f1, f2) = if has(&faces[f1], a, b) {
                (f1, f2)
            } else {
                (f2, f1)
            };
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
            if hexagon
                .iter()
                .enumerate()
                .any(|(i, v)| hexagon[i + 1..].contains(v))
            {
                continue;
            }
            let cost = |v: usize, delta: i64| -> i64 {
                if boundary[v] {
                    0
                } else {
                    (valence[v] + delta - 4).pow(2)
                }
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
                let after = cost(a, -1)
                    + cost(b, -1)
                    + cost(p, 1)
                    + cost(q, 1)
                    + [c, d, e, f]
                        .iter()
                        .filter(|&&v| v != p && v != q)
                        .map(|&v| cost(v, 0))
                        .sum::<i64>();
                let shape = quad_cost(pos, quads[0]) + quad_cost(pos, quads[1]);
                if after < now
                    && shape <= shape_now + ROTATION_SHAPE_SLACK
                    && best.is_none_or(|(c0, s0, _)| (after, shape) < (c0, s0))
                {
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

/// Collapses quads across a diagonal where that brings the valences of its four corners
/// closer to four (the "diagonal collapse" of Bozzo, Panozzo, Puppo, Pietroni and Rocca,
/// "Adaptive quad mesh simplification", 2010; Tarini et al., "Practical quad mesh
/// simplification", 2010): two valence-three corners opposite each other, left by extraction
/// around a cone of the field, merge into one regular vertex and the two other corners each
/// lose an edge. The merged vertex goes to the mean of its neighbours, on the surface.
///
/// Only interior quads are collapsed, never one whose diagonal ends already share another
/// neighbour or face (that would pinch the mesh), and only where the quads around the merged
/// vertex stay no worse shaped than a bound.
pub(super) fn collapse_diagonals(
    pos: &mut [Vector3<f64>],
    faces: &mut Vec<Vec<usize>>,
    closest: impl Fn(&Vector3<f64>) -> Vector3<f64>,
) {
    for _ in 0..ROTATION_PASSES {
        let map = edge_faces(faces);
        let mut valence = vec![0i64; pos.len()];
        let mut boundary = vec![false; pos.len()];
        let mut neighbours: Vec<Vec<usize>> = vec![Vec::new(); pos.len()];
        for (&(a, b), list) in &map {
            valence[a] += 1;
            valence[b] += 1;
            neighbours[a].push(b);
            neighbours[b].push(a);
            if list.len() != 2 {
                boundary[a] = true;
                boundary[b] = true;
            }
        }
        let mut around: Vec<Vec<usize>> = vec![Vec::new(); pos.len()];
        for (fi, f) in faces.iter().enumerate() {
            for &v in f {
                around[v].push(fi);
            }
        }
        let cost = |v: i64| (v - 4).pow(2);
        let mut gone = vec![false; faces.len()];
        let mut touched = vec![false; pos.len()];
        let mut changed = false;
        for fi in 0..faces.len() {
            let f = &faces[fi];
            if f.len() != 4 || f.iter().any(|&v| boundary[v] || touched[v]) {
                continue;
            }
            let mut best: Option<(i64, f64, usize, usize, Vector3<f64>)> = None;
            for i in 0..2 {
                let [a, b, c, d] = [f[i], f[i + 1], f[(i + 2) % 4], f[(i + 3) % 4]];
                let now = cost(valence[a]) + cost(valence[b]) + cost(valence[c]) + cost(valence[d]);
                let after =
                    cost(valence[a] + valence[c] - 2) + cost(valence[b] - 1) + cost(valence[d] - 1);
                if after >= now || valence[b] < 4 || valence[d] < 4 {
                    continue;
                }
                let shared = neighbours[a]
                    .iter()
                    .filter(|w| neighbours[c].contains(w))
                    .count();
                let common_faces = around[a].iter().filter(|g| around[c].contains(g)).count();
                if shared != 2 || common_faces != 1 {
                    continue;
                }
                // The merged vertex's neighbours: a's and c's, less b and d counted twice.
                let ring: Vec<usize> = neighbours[a]
                    .iter()
                    .chain(&neighbours[c])
                    .copied()
                    .filter(|&w| w != b && w != d)
                    .chain([b, d])
                    .collect();
                let mean = ring.iter().map(|&w| pos[w]).sum::<Vector3<f64>>() / ring.len() as f64;
                let m = closest(&mean);
                let quads: Vec<[usize; 4]> = around[a]
                    .iter()
                    .chain(&around[c])
                    .filter(|&&g| g != fi && faces[g].len() == 4)
                    .map(|&g| [faces[g][0], faces[g][1], faces[g][2], faces[g][3]])
                    .collect();
                let shape_now: f64 = quads.iter().map(|&q| quad_cost(pos, q)).sum::<f64>()
                    + quad_cost(pos, [a, b, c, d]);
                let (pa, pc) = (pos[a], pos[c]);
                pos[a] = m;
                pos[c] = m;
                let shape: f64 = quads.iter().map(|&q| quad_cost(pos, q)).sum();
                pos[a] = pa;
                pos[c] = pc;
                if shape <= shape_now + ROTATION_SHAPE_SLACK
                    && best.is_none_or(|(c0, s0, ..)| (after - now, shape) < (c0, s0))
                {
                    best = Some((after - now, shape, a, c, m));
                }
            }
            if let Some((_, _, a, c, m)) = best {
                for &g in &around[c] {
                    for v in &mut faces[g] {
                        if *v == c {
                            *v = a;
                        }
                    }
                }
                pos[a] = m;
                gone[fi] = true;
                for &v in faces[fi].iter() {
                    touched[v] = true;
                }
                for &w in neighbours[a].iter().chain(&neighbours[c]) {
                    touched[w] = true;
                }
                changed = true;
            }
        }
        if !changed {
            return;
        }
        replace_faces(faces, &gone, Vec::new());
    }
}

/// Passes of [`rotate_edges`].
const ROTATION_PASSES: usize = 6;

/// How much worse (summed corner deviation, radians) two quads may get by a rotation.
const ROTATION_SHAPE_SLACK: f64 = 0.6;

/// Merges the two quads around every interior vertex of valence two (a doublet, left where
/// rows from two sides meet along a seam) into one quad, which makes both ends of the seam
/// edge regular again. A merge that would give a quad on the same four vertices as a face
/// already there (the doublet and that face then close a pillow, as where a filled hole
/// folded over its rim) is left undone: the mesh keeps a doublet rather than a face twice.
pub(super) fn remove_doublets(faces: &mut Vec<Vec<usize>>) {
    loop {
        let mut present: BTreeSet<Vec<usize>> = faces.iter().map(|f| corners_key(f)).collect();
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
            let (Some([p1, q1, r1]), Some([p2, q2, r2])) = (turn(&faces[*f1]), turn(&faces[*f2]))
            else {
                continue;
            };
            // Interior: both edges at v are shared by exactly these two faces.
            let interior = [p1, r1]
                .iter()
                .all(|&w| map.get(&key(v, w)).is_some_and(|l| l.len() == 2));
            if !interior || p1 != r2 || r1 != p2 || q1 == q2 {
                continue;
            }
            let merged = vec![p1, q1, p2, q2];
            if !present.insert(corners_key(&merged)) {
                continue;
            }
            gone[*f1] = true;
            gone[*f2] = true;
            added.push(merged);
        }
        if added.is_empty() {
            return;
        }
        replace_faces(faces, &gone, added);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::remesh::quadmesh::samples::{grid, lines, valences};

    /// Interior vertices (not on a boundary edge) of `faces`.
    fn interior(n: usize, faces: &[Vec<usize>]) -> Vec<bool> {
        let mut inside = vec![true; n];
        for (&(a, b), list) in &edge_faces(faces) {
            if list.len() == 1 {
                inside[a] = false;
                inside[b] = false;
            }
        }
        inside
    }

    #[test]
    fn a_rotated_edge_in_a_regular_grid_is_rotated_back() {
        let (pos, regular) = grid(&lines(0.0, 6.0, 6), &lines(0.0, 6.0, 6));
        let n = pos.len();
        let at = |i: usize, j: usize| j * 7 + i;
        // Faces (3, 3) = [a, b, c, d] and (3, 2) = [e, f, b, a] share edge a-b; turning it into
        // e-c leaves a and b with three edges, e and c with five.
        let (f1, f2) = (3 * 6 + 3, 2 * 6 + 3);
        let (a, b, c, d, e, f) = (at(3, 3), at(4, 3), at(4, 4), at(3, 4), at(3, 2), at(4, 2));
        assert_eq!(
            (regular[f1].clone(), regular[f2].clone()),
            (vec![a, b, c, d], vec![e, f, b, a])
        );
        let mut faces = regular.clone();
        faces[f1] = vec![e, f, b, c];
        faces[f2] = vec![c, d, a, e];
        let v = valences(n, &faces);
        assert_eq!([v[a], v[b], v[c], v[e]], [3, 3, 5, 5]);
        rotate_edges(&pos, &mut faces);
        let inside = interior(n, &faces);
        let v = valences(n, &faces);
        assert!(
            (0..n).filter(|&k| inside[k]).all(|k| v[k] == 4),
            "every interior vertex regular again"
        );
        let cost: f64 = faces
            .iter()
            .map(|q| quad_cost(&pos, [q[0], q[1], q[2], q[3]]))
            .sum();
        assert!(cost < 1e-9, "squares again");
        // A regular grid stays as it is.
        let mut same = regular.clone();
        rotate_edges(&pos, &mut same);
        assert_eq!(same, regular);
    }

    #[test]
    fn a_vertex_split_into_two_valence_three_corners_is_collapsed_back() {
        let (mut pos, regular) = grid(&lines(0.0, 6.0, 6), &lines(0.0, 6.0, 6));
        let n = pos.len();
        let at = |i: usize, j: usize| j * 7 + i;
        // Split vertex (3, 3) along the row: `a` keeps the two quads above, a new vertex `c`
        // takes the two below, and a new quad a-b-c-d fills the slit between the row's
        // neighbours b = (2, 3) and d = (4, 3). a and c get three edges, b and d five.
        let (a, b, d) = (at(3, 3), at(2, 3), at(4, 3));
        let c = n;
        pos.push(Vector3::new(3.0, 2.8, 0.0));
        pos[a] = Vector3::new(3.0, 3.2, 0.0);
        let mut faces = regular.clone();
        for f in faces.iter_mut() {
            let below = f.iter().any(|&v| v == at(3, 2));
            for v in f.iter_mut() {
                if *v == a && below {
                    *v = c;
                }
            }
        }
        faces.push(vec![a, b, c, d]);
        let v = valences(n + 1, &faces);
        assert_eq!([v[a], v[b], v[c], v[d]], [3, 5, 3, 5]);
        collapse_diagonals(&mut pos, &mut faces, |p| *p);
        let inside = interior(pos.len(), &faces);
        let v = valences(pos.len(), &faces);
        assert!(
            (0..pos.len())
                .filter(|&k| inside[k] && v[k] > 0)
                .all(|k| v[k] == 4),
            "every interior vertex regular again: {v:?}"
        );
        assert_eq!(faces.len(), regular.len(), "the slit quad is gone");
        assert!(
            (pos[a] - Vector3::new(3.0, 3.0, 0.0)).norm() < 1e-9,
            "{:?}",
            pos[a]
        );
        // A regular grid stays as it is.
        let (mut pos, regular) = grid(&lines(0.0, 6.0, 6), &lines(0.0, 6.0, 6));
        let mut same = regular.clone();
        collapse_diagonals(&mut pos, &mut same, |p| *p);
        assert_eq!(same, regular);
    }

    #[test]
    fn the_two_quads_around_a_valence_two_vertex_become_one() {
        // A diamond C D A B cut into two quads through its centre v (valence two).
        let (v, c, d, a, b) = (0, 1, 2, 3, 4);
        let mut faces = vec![vec![v, c, d, a], vec![v, a, b, c]];
        remove_doublets(&mut faces);
        assert_eq!(faces, vec![vec![c, d, a, b]]);
        // On the boundary, a vertex of valence two is a corner, not a doublet.
        let (_, regular) = grid(&lines(0.0, 2.0, 2), &lines(0.0, 2.0, 2));
        let mut same = regular.clone();
        remove_doublets(&mut same);
        assert_eq!(same, regular);
    }

    #[test]
    fn a_doublet_whose_merge_would_repeat_a_face_is_left() {
        // Vertex 0 has two quads round it, [0, 1, 2, 3] and [0, 3, 4, 1]; merged they give
        // [1, 2, 3, 4], the face already there the other way round (as a filled hole left
        // it, folded over the doublet): the merge would put a face twice.
        let pillow = vec![vec![0, 1, 2, 3], vec![0, 3, 4, 1], vec![4, 3, 2, 1]];
        let mut faces = pillow.clone();
        remove_doublets(&mut faces);
        assert_eq!(faces, pillow);
        // A doublet elsewhere in the same list is still merged.
        let mut faces = pillow.clone();
        faces.extend([vec![5, 6, 7, 8], vec![5, 8, 9, 6]]);
        remove_doublets(&mut faces);
        assert_eq!(faces.len(), 4);
        assert!(faces.contains(&vec![6, 7, 8, 9]), "{faces:?}");
    }
}
