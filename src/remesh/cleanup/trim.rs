//! Faces that still leave the surface after fitting: halved along their quad strip, or, on
//! the rim, dropped; and rim slivers dropped.

use std::collections::BTreeMap;

use nalgebra::Vector3;

use super::manifold::drop_small_components;
use crate::remesh::anchors::Anchors;
use crate::remesh::fit;
use crate::remesh::quadmesh::{edge_faces, key};
use crate::remesh::surface::Locator;

/// Faces that still leave the surface after fitting span more surface than a quad can follow
/// there (a crumpled support). Each is halved across its long sides together with the rest of
/// its quad strip (chord), when that strip runs to the boundary within a few faces both
/// ways: splitting a whole strip keeps every face a quad and adds no irregular vertex.
/// Returns whether anything changed.
pub(super) fn split_unfit_faces(
    pos: &mut Vec<Vector3<f64>>,
    faces: &mut Vec<Vec<usize>>,
    locator: &Locator,
    t: f64,
) -> bool {
    let limit = FINAL * t;
    let map = edge_faces(faces);
    let other = |e: (usize, usize), f: usize| -> Option<usize> {
        map.get(&e)
            .and_then(|l| l.iter().copied().find(|&g| g != f))
    };
    let edge = |f: &[usize], i: usize| key(f[i % 4], f[(i + 1) % 4]);
    let mut in_chord = vec![false; faces.len()];
    // (face, index of its first split edge) for every face of every accepted chord.
    let mut splits: Vec<(usize, usize)> = Vec::new();
    for f0 in 0..faces.len() {
        if in_chord[f0] || faces[f0].len() != 4 || fit::deviation(pos, &faces[f0], locator) <= limit
        {
            continue;
        }
        // Split across the sides whose midpoints leave the surface most, or across the
        // longer sides when only the centre does.
        let q = &faces[f0];
        let len = |i: usize| {
            (pos[q[i]] - pos[q[(i + 1) % 4]]).norm()
                + (pos[q[(i + 2) % 4]] - pos[q[(i + 3) % 4]]).norm()
        };
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
                if g == f0
                    || faces[g].len() != 4
                    || in_chord[g]
                    || chord.iter().any(|&(h, _)| h == g)
                    || chord.len() >= MAX_CHORD
                {
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
            let q = if boundary {
                locator
                    .closest_boundary(&m)
                    .unwrap_or_else(|| locator.closest(&m).0)
            } else {
                locator.closest(&m).0
            };
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
pub(super) const SPLIT_ROUNDS: usize = 2;

/// Drops faces at the rim that still leave the surface (a quad spanning a fold of slivers
/// at a support), one at a time and only where the vertices this exposes can go onto the
/// input boundary without pushing a neighbouring face off the surface.
pub(super) fn drop_unfit_rim_faces(
    pos: &mut [Vector3<f64>],
    faces: &mut Vec<Vec<usize>>,
    locator: &Locator,
    t: f64,
) {
    let limit = FINAL * t;
    let mut candidates: Vec<usize> = (0..faces.len())
        .filter(|&f| fit::deviation(pos, &faces[f], locator) > limit)
        .collect();
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
            count.get(&key(v, f[(i + 1) % k])) == Some(&1)
                || count.get(&key(v, f[(i + k - 1) % k])) == Some(&1)
        })
    };
    candidates.sort_unstable();
    for fi in candidates {
        let f = faces[fi].clone();
        if !f.iter().any(|&v| on_boundary(v, &count, &gone)) {
            continue;
        }
        let exposed: Vec<usize> = f
            .iter()
            .copied()
            .filter(|&v| !on_boundary(v, &count, &gone))
            .collect();
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
            let mut list: Vec<usize> = moves
                .iter()
                .flat_map(|&(v, _, _)| incident[v].iter().copied())
                .filter(|&g| !gone[g])
                .collect();
            list.sort_unstable();
            list.dedup();
            list
        };
        let before: Vec<f64> = around
            .iter()
            .map(|&g| fit::deviation(pos, &faces[g], locator))
            .collect();
        for &(v, _, q) in &moves {
            pos[v] = q;
        }
        let fine = around
            .iter()
            .zip(&before)
            .all(|(&g, &b)| fit::deviation(pos, &faces[g], locator) <= limit.max(b + 0.01 * t));
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

/// Deviation (times `t`) a face may keep in the end: above it a face is halved along its strip
/// ([`split_unfit_faces`]) or, on the rim, dropped ([`drop_unfit_rim_faces`]), and boundary
/// chords are shortened to it.
pub(super) const FINAL: f64 = 0.095;

/// Drops faces with (almost) no area whose corners all lie on the input boundary: slivers
/// that row extension and strip splitting can leave along a ragged rim. Nothing is exposed
/// that is off the boundary.
pub(super) fn drop_rim_slivers(
    pos: &[Vector3<f64>],
    faces: &mut Vec<Vec<usize>>,
    locator: &Locator,
    t: f64,
) {
    let on_rim = |v: usize| {
        locator
            .closest_boundary(&pos[v])
            .is_some_and(|q| (q - pos[v]).norm() <= 0.04 * t)
    };
    let area = |f: &[usize]| {
        let k = f.len();
        (0..k)
            .fold(Vector3::zeros(), |acc: Vector3<f64>, i| {
                acc + pos[f[i]].cross(&pos[f[(i + 1) % k]])
            })
            .norm()
            * 0.5
    };
    let before = faces.len();
    faces.retain(|f| !(area(f) < SLIVER * t * t && f.iter().all(|&v| on_rim(v))));
    if faces.len() != before {
        drop_small_components(faces);
    }
}

/// Area (times `t` squared) below which a rim face is a sliver.
const SLIVER: f64 = 0.05;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::remesh::quadmesh::samples::{grid, lines};
    use crate::remesh::surface::samples::sheet;

    /// Largest deviation of `faces` from the surface.
    fn worst(pos: &[Vector3<f64>], faces: &[Vec<usize>], locator: &Locator) -> f64 {
        faces
            .iter()
            .map(|f| fit::deviation(pos, f, locator))
            .fold(0.0, f64::max)
    }

    #[test]
    fn a_strip_across_a_ridge_is_halved_along_the_ridge() {
        // A roof over [0, 2]^2 with its ridge along x = 1; a strip of four quads of t = 0.5
        // straddles the ridge from the input's front edge to its back edge.
        let roof = sheet(8, 0.25, (0..0, 0..0), |x, _| 0.3 * (1.0 - (x - 1.0).abs()));
        let locator = Locator::new(&roof);
        let t = 0.5;
        let (mut pos, mut faces) = grid(&[0.75, 1.25], &lines(0.0, 2.0, 4));
        for p in pos.iter_mut() {
            p.z = 0.3 * (1.0 - (p.x - 1.0).abs());
        }
        assert!(
            faces
                .iter()
                .all(|f| fit::deviation(&pos, f, &locator) > FINAL * t)
        );
        let old = pos.len();
        assert!(split_unfit_faces(&mut pos, &mut faces, &locator, t));
        assert_eq!(faces.len(), 8);
        assert!(faces.iter().all(|f| f.len() == 4));
        // One new vertex per crossed edge, on the surface next to the ridge (the nearest
        // point to a chord's midpoint under it lies on a slope), and the halves follow the
        // roof.
        assert_eq!(pos.len(), old + 5);
        assert!(
            pos[old..]
                .iter()
                .all(|p| (p.x - 1.0).abs() < 0.05 && locator.distance(p) < 1e-12),
            "{:?}",
            &pos[old..]
        );
        assert!(
            worst(&pos, &faces, &locator) < 0.2 * FINAL * t,
            "{}",
            worst(&pos, &faces, &locator)
        );
        assert!(
            !split_unfit_faces(&mut pos, &mut faces, &locator, t),
            "nothing left to split"
        );
    }

    #[test]
    fn flat_faces_on_the_rim_go_flat_faces_inside_stay() {
        // Rows of quads over a flat 2 x 2 input: the first and third rows are 0.01 high, the
        // first lies along the input's edge.
        let input = sheet(4, 0.5, (0..0, 0..0), |_, _| 0.0);
        let locator = Locator::new(&input);
        let (pos, mut faces) = grid(&lines(0.0, 2.0, 4), &[0.0, 0.01, 0.51, 0.52, 1.02]);
        let kept: Vec<Vec<usize>> = faces[4..].to_vec();
        drop_rim_slivers(&pos, &mut faces, &locator, 0.5);
        assert_eq!(faces, kept);
    }
}
