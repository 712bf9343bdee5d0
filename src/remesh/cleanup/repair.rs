//! Topology repair (steps 1 to 4 of the [cleanup](super)): extraction holes become polygons,
//! adjacent triangles merge into quads, odd faces are paired along shortest dual paths and
//! the crossed edges split, even polygons are cut into quads by their best diagonals.

use std::collections::{BTreeSet, VecDeque};

use nalgebra::Vector3;

use super::valence::remove_doublets;
use crate::remesh::budget::Budget;
use crate::remesh::quadmesh::{
    boundary_loops, corners_key, edge_faces, key, quad_cost, replace_faces,
};
use crate::remesh::surface::Locator;

/// Turns extraction holes (short boundary loops, mostly away from the input boundary) into
/// polygons. Long loops are the outline (or openings) of the shell and stay open.
pub(super) fn fill_holes(
    pos: &[Vector3<f64>],
    faces: &mut Vec<Vec<usize>>,
    locator: &Locator,
    t: f64,
) {
    for lp in boundary_loops(faces) {
        if lp.len() > MAX_HOLE {
            continue;
        }
        let near = lp
            .iter()
            .filter(|&&v| {
                locator
                    .closest_boundary(&pos[v])
                    .is_some_and(|q| (q - pos[v]).norm() < 0.75 * t)
            })
            .count();
        if near * 2 >= lp.len() {
            continue;
        }
        // A loop around a single face (a stray face) is not a hole.
        let sorted = corners_key(&lp);
        if faces
            .iter()
            .any(|f| f.len() == sorted.len() && corners_key(f) == sorted)
        {
            continue;
        }
        let mut face = lp;
        face.reverse();
        faces.push(face);
    }
}

/// Longest boundary loop that can be an extraction hole.
const MAX_HOLE: usize = 24;

/// Topology repair: triangles paired, odd faces evened, even polygons cut, doublets merged.
pub(super) fn make_quads(
    pos: &mut Vec<Vector3<f64>>,
    faces: &mut Vec<Vec<usize>>,
    budget: &mut Budget,
) {
    merge_triangles(pos, faces);
    pair_odd_faces(pos, faces, budget);
    split_even(pos, faces);
    remove_doublets(faces);
}

/// Merges adjacent triangles into quads, best pairs first.
fn merge_triangles(pos: &[Vector3<f64>], faces: &mut Vec<Vec<usize>>) {
    let map = edge_faces(faces);
    let mut candidates: Vec<(f64, usize, usize, [usize; 4])> = Vec::new();
    for (&(a, b), list) in &map {
        if let [f, g] = list.as_slice() {
            if faces[*f].len() == 3 && faces[*g].len() == 3 {
                let tri = &faces[*f];
                let i = (0..3)
                    .find(|&i| key(tri[i], tri[(i + 1) % 3]) == (a, b))
                    .unwrap_or(0);
                let (x, y, z) = (tri[i], tri[(i + 1) % 3], tri[(i + 2) % 3]);
                let Some(&d) = faces[*g].iter().find(|&&v| v != x && v != y) else {
                    continue;
                };
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
    replace_faces(faces, &gone, added);
}

/// Pairs odd faces along shortest dual paths (or to the boundary) and splits the crossed
/// edges at their midpoints, so every face gets an even number of sides.
fn pair_odd_faces(pos: &mut Vec<Vector3<f64>>, faces: &mut [Vec<usize>], budget: &mut Budget) {
    // Kept up to date as edges are split (each half keeps the edge's faces, in order).
    let mut map = edge_faces(faces);
    loop {
        let Some(f0) = faces.iter().position(|f| f.len() % 2 == 1) else {
            return;
        };
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
    let mut existing: BTreeSet<(usize, usize)> = edge_faces(faces).into_keys().collect();
    let mut out = Vec::with_capacity(faces.len());
    for f in faces.drain(..) {
        let mut rest = f;
        while rest.len() >= 6 && rest.len() % 2 == 0 {
            let n = rest.len();
            let best = (0..n)
                .filter(|&i| !existing.contains(&key(rest[i], rest[(i + 3) % n])))
                .map(|i| {
                    let q = [
                        rest[i],
                        rest[(i + 1) % n],
                        rest[(i + 2) % n],
                        rest[(i + 3) % n],
                    ];
                    (quad_cost(pos, q), i, q)
                })
                .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
            let Some((_, i, q)) = best else { break };
            existing.insert(key(q[0], q[3]));
            out.push(q.to_vec());
            // Remove the two ear vertices i+1, i+2.
            let (r1, r2) = ((i + 1) % n, (i + 2) % n);
            rest = rest
                .iter()
                .enumerate()
                .filter(|(k, _)| *k != r1 && *k != r2)
                .map(|(_, &v)| v)
                .collect();
        }
        out.push(rest);
    }
    *faces = out;
}

#[cfg(test)]
mod tests {
    use std::time::{Duration, Instant};

    use super::*;
    use crate::control::Control;
    use crate::remesh::quadmesh::samples::{grid, lines};
    use crate::remesh::surface::samples::sheet;

    /// Summed area of `faces` (planar, counter-clockwise).
    fn area(pos: &[Vector3<f64>], faces: &[Vec<usize>]) -> f64 {
        faces
            .iter()
            .map(|f| {
                (0..f.len())
                    .map(|i| pos[f[i]].cross(&pos[f[(i + 1) % f.len()]]).z)
                    .sum::<f64>()
                    / 2.0
            })
            .sum()
    }

    #[test]
    fn an_extraction_hole_is_filled_an_opening_of_the_input_is_not() {
        // A 4 x 4 input with an opening over [1.5, 2.5]^2, and a grid of quads of 0.5 on it
        // without the faces over the opening and without face (6, 1): an extraction hole.
        let input = sheet(8, 0.5, (3..5, 3..5), |_, _| 0.0);
        let locator = Locator::new(&input);
        let (pos, all) = grid(&lines(0.0, 4.0, 8), &lines(0.0, 4.0, 8));
        let gone =
            |i: usize, j: usize| (3..5).contains(&i) && (3..5).contains(&j) || (i, j) == (6, 1);
        let mut faces: Vec<Vec<usize>> = all
            .iter()
            .enumerate()
            .filter(|(k, _)| !gone(k % 8, k / 8))
            .map(|(_, f)| f.clone())
            .collect();
        let before = faces.len();
        fill_holes(&pos, &mut faces, &locator, 0.5);
        assert_eq!(
            faces.len(),
            before + 1,
            "only the extraction hole is filled"
        );
        // The same face as the one missing, the same way round.
        let (filled, missing) = (&faces[before], &all[8 + 6]);
        let k = filled.iter().position(|&v| v == missing[0]).unwrap();
        assert_eq!(
            (0..4).map(|i| filled[(k + i) % 4]).collect::<Vec<_>>(),
            *missing
        );
    }

    #[test]
    fn triangles_odd_faces_and_polygons_become_quads() {
        let (mut pos, mut faces) = grid(&lines(0.0, 4.0, 4), &lines(0.0, 4.0, 4));
        let at = |i: usize, j: usize| j * 5 + i;
        // Face (1, 1) as two triangles.
        let [a, b, c, d] = [at(1, 1), at(2, 1), at(2, 2), at(1, 2)];
        faces[4 + 1] = vec![a, b, c];
        faces.push(vec![a, c, d]);
        // Faces (2, 2) and (3, 2) as one hexagon.
        faces[8 + 2] = vec![at(2, 2), at(3, 2), at(4, 2), at(4, 3), at(3, 3), at(2, 3)];
        faces.remove(8 + 3);
        // Face (0, 3) with a vertex bulging out of its top edge, on the boundary: a pentagon.
        pos.push(Vector3::new(0.5, 4.2, 0.0));
        let m = pos.len() - 1;
        let f = faces
            .iter()
            .position(|f| f == &vec![at(0, 3), at(1, 3), at(1, 4), at(0, 4)])
            .unwrap();
        faces[f] = vec![at(0, 3), at(1, 3), at(1, 4), m, at(0, 4)];
        assert_eq!(faces.iter().filter(|f| f.len() % 2 == 1).count(), 3);
        let mut control = Control::none();
        let mut budget = Budget::new(&mut control, Instant::now(), Duration::from_secs(60));
        make_quads(&mut pos, &mut faces, &mut budget);
        assert!(faces.iter().all(|f| f.len() == 4), "{faces:?}");
        assert_eq!(faces.len(), 17);
        // The same surface, covered once, by quads that are not flat.
        assert!((area(&pos, &faces) - 16.1).abs() < 1e-12);
        assert!(
            faces
                .iter()
                .all(|f| area(&pos, std::slice::from_ref(f)) > 0.05)
        );
        assert!(edge_faces(&faces).values().all(|l| l.len() <= 2));
        // The triangles and the hexagon are back to squares.
        let squares = faces
            .iter()
            .filter(|f| quad_cost(&pos, [f[0], f[1], f[2], f[3]]) < 1e-12)
            .count();
        assert!(squares >= 15, "{squares} squares");
    }
}
