//! Fitting the extracted quads to the input's boundary.
//!
//! Where the lattice could not be read right up to the shell's edge (crumpled supports,
//! slivers, teeth narrower than a quad), extraction leaves the quad mesh's boundary short of
//! the input boundary. Snapping those boundary vertices outwards would stretch their quads
//! across the gap (and off the surface where the gap is not convex), so deep gaps are closed
//! by extending the boundary quad row instead: every boundary vertex of the short stretch
//! sends a spoke to the input boundary, consecutive spokes bound new quads (one row per quad
//! length of gap), and the two ends fan onto the boundary.

use nalgebra::Vector3;

use super::anchors::Anchors;
use super::surface::Locator;

/// Boundary vertices farther than this (times `t`) from the input boundary start a row
/// extension instead of being snapped.
const SNAP: f64 = 0.9;

/// Most rows one extension adds.
const MAX_ROWS: usize = 3;

/// Extends the boundary rows of `faces` over the gaps to the input boundary (see the module
/// documentation). `loops` are the boundary loops of `faces` (faces on the left).
pub(crate) fn extend_boundary(
    pos: &mut Vec<Vector3<f64>>,
    faces: &mut Vec<Vec<usize>>,
    loops: &[Vec<usize>],
    locator: &Locator,
    t: f64,
) {
    // Faces at each vertex, counted once: a far vertex belongs to one run only, so the
    // faces earlier extensions add never change its count.
    let faces_at = faces_at(pos.len(), faces);
    for lp in loops {
        let n = lp.len();
        if n < 3 {
            continue;
        }
        let places: Vec<_> = lp
            .iter()
            .map(|&v| locator.closest_boundary_at(&pos[v]))
            .collect();
        let near: Vec<bool> = lp
            .iter()
            .zip(&places)
            .map(|(&v, b)| b.is_some_and(|b| (b.point - pos[v]).norm() <= SNAP * t))
            .collect();
        let Some(start) = (0..n).find(|&i| near[i] && !near[(i + 1) % n]) else {
            continue;
        };
        // Walk the loop once from `start`, collecting runs of far vertices.
        let mut i = start;
        let mut walked = 0;
        while walked < n {
            if near[i] && !near[(i + 1) % n] {
                let mut run = vec![lp[i]];
                let mut j = (i + 1) % n;
                let mut steps = 1;
                while !near[j] && steps < n {
                    run.push(lp[j]);
                    j = (j + 1) % n;
                    steps += 1;
                }
                run.push(lp[j]);
                let (Some(first), Some(last)) = (places[i], places[j]) else {
                    break;
                };
                extend_run(
                    pos, faces, &faces_at, &run, first.lp, first.arc, last.arc, locator, t,
                );
                walked += steps;
                i = j;
            } else {
                i = (i + 1) % n;
                walked += 1;
            }
        }
    }
}

/// One extension: `run` = near vertex, far vertices, near vertex (along the quad boundary,
/// faces on the left); the input boundary loop `lp` runs the same way from arc `from` to `to`.
#[allow(clippy::too_many_arguments)]
fn extend_run(
    pos: &mut Vec<Vector3<f64>>,
    faces: &mut Vec<Vec<usize>>,
    faces_at: &[usize],
    run: &[usize],
    lp: usize,
    from: f64,
    to: f64,
    locator: &Locator,
    t: f64,
) {
    let m = run.len() - 2;
    if m == 0 {
        return;
    }
    let length = locator.loop_length(lp);
    let span = (to - from).rem_euclid(length);
    let mut chain = vec![0.0];
    for k in 1..run.len() {
        chain.push(chain[k - 1] + (pos[run[k]] - pos[run[k - 1]]).norm());
    }
    let total = chain[run.len() - 1];
    // The stretch of boundary must be comparable to the quad boundary it faces; otherwise
    // the two ends were matched to different parts of the boundary.
    if !(span > 0.2 * t && span < 3.0 * total + 2.0 * t && total > 0.0) {
        return;
    }
    // Spokes land where the boundary is nearest, in order along it (so a tooth between two
    // spokes is skipped rather than fanned into); where that order cannot be kept, in
    // proportion to the quad boundary.
    let gap = (0.25 * t).min(span / (m + 1) as f64);
    let mut offsets: Vec<f64> = Vec::with_capacity(m + 2);
    offsets.push(0.0);
    for k in 1..=m {
        let (o, _) = locator.closest_on_arc(lp, from, span, &pos[run[k]]);
        offsets.push(o.max(offsets[k - 1] + gap));
    }
    if offsets[m] > span - gap {
        for (k, o) in offsets.iter_mut().enumerate() {
            *o = span * chain[k] / total;
        }
    }
    offsets.push(span);
    let arc_at = |k: usize| from + offsets[k];
    let spokes: Vec<Vector3<f64>> = (1..=m)
        .map(|k| locator.boundary_point(lp, arc_at(k)))
        .collect();
    let longest = (1..=m)
        .map(|k| (pos[run[k]] - spokes[k - 1]).norm())
        .fold(0.0, f64::max);
    let rows = ((longest / t).round() as usize).clamp(1, MAX_ROWS);
    if rows == 1 {
        let fans = [
            locator.boundary_point(lp, from + offsets[1] * 0.5),
            locator.boundary_point(lp, to - (span - offsets[m]) * 0.5),
        ];
        if single_row(pos, faces, faces_at, run, &spokes, fans) {
            return;
        }
    }
    fn add(pos: &mut Vec<Vector3<f64>>, p: Vector3<f64>) -> usize {
        pos.push(p);
        pos.len() - 1
    }
    // p[k][r]: spoke of far vertex k (1-based in run), r = 0 at the vertex, rows at the boundary.
    let mut spoke: Vec<Vec<usize>> = Vec::with_capacity(m + 2);
    spoke.push(Vec::new());
    for k in 1..=m {
        let v = run[k];
        let a = pos[v];
        let b = spokes[k - 1];
        let mut column = vec![v];
        for r in 1..rows {
            let q = a + (b - a) * (r as f64 / rows as f64);
            column.push(add(pos, locator.closest(&q).0));
        }
        column.push(add(pos, b));
        spoke.push(column);
    }
    // Middle quads between consecutive spokes.
    for k in 1..m {
        for r in 0..rows {
            faces.push(vec![
                spoke[k + 1][r],
                spoke[k][r],
                spoke[k][r + 1],
                spoke[k + 1][r + 1],
            ]);
        }
    }
    // First end: fan from spoke 1 onto the boundary between the first near vertex and it.
    let first_arc = offsets[1];
    let mut y = vec![run[0]];
    for r in 1..=rows {
        y.push(add(
            pos,
            locator.boundary_point(lp, from + first_arc * r as f64 / (rows + 1) as f64),
        ));
    }
    for r in 0..rows {
        faces.push(vec![spoke[1][r], y[r], y[r + 1], spoke[1][r + 1]]);
    }
    // Last end: fan from spoke m onto the boundary between it and the last near vertex.
    let last_arc = span - offsets[m];
    let mut z = vec![run[m + 1]];
    for r in 1..=rows {
        z.push(add(
            pos,
            locator.boundary_point(lp, to - last_arc * r as f64 / (rows + 1) as f64),
        ));
    }
    for r in 0..rows {
        faces.push(vec![z[r], spoke[m][r], spoke[m][r + 1], z[r + 1]]);
    }
}

/// One row of quads from `run` (near vertex, far vertices, near vertex) to the boundary
/// points `spokes` (one per far vertex; `fans` are the boundary points of the two end
/// quads), where a far vertex next to an end is the inner
/// corner of a staircase (three quads already meet there, as where the lattice crosses the
/// boundary at a slant): that vertex gets no spoke, so it keeps four edges instead of five,
/// and the quad between it and the end reaches the boundary directly. Returns false (and
/// adds nothing) where no end has such a corner; the caller then fans both ends.
/// `faces_at` counts the faces at each vertex of `faces`.
fn single_row(
    pos: &mut Vec<Vector3<f64>>,
    faces: &mut Vec<Vec<usize>>,
    faces_at: &[usize],
    run: &[usize],
    spokes: &[Vector3<f64>],
    fans: [Vector3<f64>; 2],
) -> bool {
    let m = run.len() - 2;
    let corner = |v: usize| faces_at[v] >= 3;
    let (near0, near1) = (run[0], run[m + 1]);
    let first = corner(run[1]);
    // With one far vertex the quad is the tooth itself; with two, one of them keeps its
    // spoke so the quad between them reaches the boundary.
    let last = m >= 2 && corner(run[m]) && !(m == 2 && first);
    if !first && !last {
        return false;
    }
    if m == 1 {
        let s = pos.len();
        pos.push(spokes[0]);
        faces.push(vec![run[1], near0, s, near1]);
        return true;
    }
    // Spoke ends of the far vertices that keep one.
    let mut end = vec![usize::MAX; m + 2];
    for k in 1..=m {
        if !(k == 1 && first || k == m && last) {
            end[k] = pos.len();
            pos.push(spokes[k - 1]);
        }
    }
    let (lo, hi) = (if first { 2 } else { 1 }, if last { m - 1 } else { m });
    for k in lo..hi {
        faces.push(vec![run[k + 1], run[k], end[k], end[k + 1]]);
    }
    if first {
        faces.push(vec![run[2], run[1], near0, end[2]]);
    } else {
        // Fan from the first spoke onto the boundary: as in the general case, one quad
        // through a boundary point between the end and the spoke.
        let y = pos.len();
        pos.push(fans[0]);
        faces.push(vec![run[1], near0, y, end[1]]);
    }
    if last {
        faces.push(vec![run[m], run[m - 1], end[m - 1], near1]);
    } else {
        let z = pos.len();
        pos.push(fans[1]);
        faces.push(vec![near1, run[m], end[m], z]);
    }
    true
}

/// How many of `faces` meet at each of `n` vertices.
fn faces_at(n: usize, faces: &[Vec<usize>]) -> Vec<usize> {
    let mut count = vec![0; n];
    for &v in faces.iter().flatten() {
        count[v] += 1;
    }
    count
}

/// Deviation above which [`conform`] works on a face, times `t`.
const CONFORM_FROM: f64 = 0.05;

/// A sample point of a face, the (vertex, weight) pairs that make it and how many of them.
type Sample = (Vector3<f64>, [(usize, f64); 4], usize);

/// Sample points of a face (centroid and edge midpoints) with the vertex weights that make
/// them.
fn face_samples(pos: &[Vector3<f64>], f: &[usize]) -> Vec<Sample> {
    let k = f.len();
    let mut out = Vec::with_capacity(k + 1);
    if k == 4 {
        let c = (pos[f[0]] + pos[f[1]] + pos[f[2]] + pos[f[3]]) * 0.25;
        out.push((
            c,
            [(f[0], 0.25), (f[1], 0.25), (f[2], 0.25), (f[3], 0.25)],
            4,
        ));
    }
    for i in 0..k {
        let (a, b) = (f[i], f[(i + 1) % k]);
        out.push((
            (pos[a] + pos[b]) * 0.5,
            [(a, 0.5), (b, 0.5), (a, 0.0), (a, 0.0)],
            2,
        ));
    }
    out
}

/// Largest distance to the surface of a face's centroid and edge midpoints.
pub(crate) fn deviation(pos: &[Vector3<f64>], f: &[usize], locator: &Locator) -> f64 {
    face_samples(pos, f)
        .iter()
        .map(|(p, _, _)| locator.distance(p))
        .fold(0.0, f64::max)
}

/// Pulls faces whose centroid or edge midpoints leave the surface back onto it by moving
/// their vertices (each towards the surface points its samples should reach), keeping
/// boundary vertices on the boundary and corners in place. Works only where needed.
pub(crate) fn conform(
    pos: &mut [Vector3<f64>],
    faces: &[Vec<usize>],
    anchors: &Anchors,
    locator: &Locator,
    t: f64,
) {
    let n = pos.len();
    let mut incident: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (fi, f) in faces.iter().enumerate() {
        for &v in f {
            incident[v].push(fi);
        }
    }
    let threshold = CONFORM_FROM * t;
    // Each face's deviation on its own (on the threads of `parallel`).
    let off = crate::parallel::map(faces.len(), |fi| {
        deviation(pos, &faces[fi], locator) > threshold
    });
    let mut active: Vec<usize> = (0..faces.len()).filter(|&fi| off[fi]).collect();
    let mut disp = vec![Vector3::zeros(); n];
    let mut weight = vec![0.0; n];
    let mut stamp = vec![usize::MAX; faces.len()];
    for round in 0..CONFORM_ROUNDS {
        if active.is_empty() {
            break;
        }
        let mut touched: Vec<usize> = Vec::new();
        for &fi in &active {
            for (p, members, count) in face_samples(pos, &faces[fi]) {
                let d = locator.closest(&p).0 - p;
                if d.norm() <= 0.5 * threshold {
                    continue;
                }
                for &(v, w) in &members[..count] {
                    if weight[v] == 0.0 {
                        touched.push(v);
                    }
                    disp[v] += d * w;
                    weight[v] += w * w;
                }
            }
        }
        touched.sort_unstable();
        let mut next: Vec<usize> = Vec::new();
        for &v in &touched {
            if !anchors.pinned[v] {
                let target = pos[v] + disp[v] / weight[v] * 0.5;
                pos[v] = anchors.project(locator, v, &target);
            }
            disp[v] = Vector3::zeros();
            weight[v] = 0.0;
            for &fi in &incident[v] {
                if stamp[fi] != round {
                    stamp[fi] = round;
                    next.push(fi);
                }
            }
        }
        next.sort_unstable();
        active = next
            .into_iter()
            .filter(|&fi| deviation(pos, &faces[fi], locator) > threshold)
            .collect();
    }
}

/// Rounds of [`conform`].
const CONFORM_ROUNDS: usize = 40;

/// Rounds of [`shorten_boundary_chords`].
const CHORD_ROUNDS: usize = 3;

/// Boundary edges whose midpoint leaves the surface by more than `limit` cut across an
/// inward curve of the input boundary; the chord's sagitta grows with its length squared, so
/// its two ends slide towards each other along the boundary until it keeps to `limit`
/// (neighbouring chords grow a little, where the boundary is straighter). A move is kept only
/// if it lowers the worst deviation of the faces around the two ends. Corners stay.
pub(crate) fn shorten_boundary_chords(
    pos: &mut [Vector3<f64>],
    faces: &[Vec<usize>],
    anchors: &Anchors,
    locator: &Locator,
    limit: f64,
) {
    let mut incident: Vec<Vec<usize>> = vec![Vec::new(); pos.len()];
    for (fi, f) in faces.iter().enumerate() {
        f.iter().for_each(|&v| incident[v].push(fi));
    }
    let worst_around = |pos: &[Vector3<f64>], ends: [usize; 2]| -> f64 {
        ends.iter()
            .flat_map(|&v| incident[v].iter())
            .map(|&fi| deviation(pos, &faces[fi], locator))
            .fold(0.0, f64::max)
    };
    for _ in 0..CHORD_ROUNDS {
        let mut moved = false;
        for a in 0..pos.len() {
            for &b in anchors.bnbrs[a].iter().filter(|&&b| b > a) {
                let off = locator.distance(&((pos[a] + pos[b]) * 0.5));
                if off <= limit || (anchors.pinned[a] && anchors.pinned[b]) {
                    continue;
                }
                let (Some(pa), Some(pb)) = (
                    locator.closest_boundary_at(&pos[a]),
                    locator.closest_boundary_at(&pos[b]),
                ) else {
                    continue;
                };
                if pa.lp != pb.lp {
                    continue;
                }
                let length = locator.loop_length(pa.lp);
                // Along the loop from `a` to `b` the short way (`sign` -1 when that runs backwards).
                let forward = (pb.arc - pa.arc).rem_euclid(length);
                let (span, sign) = if forward <= length / 2.0 {
                    (forward, 1.0)
                } else {
                    (length - forward, -1.0)
                };
                // Sagitta ~ span^2: the span that keeps to the limit, with a small margin.
                let shrink = span * (1.0 - 0.97 * (limit / off).sqrt());
                let (step_a, step_b) = match (anchors.pinned[a], anchors.pinned[b]) {
                    (true, _) => (0.0, shrink),
                    (_, true) => (shrink, 0.0),
                    _ => (shrink / 2.0, shrink / 2.0),
                };
                let before = (pos[a], pos[b]);
                let worst_before = worst_around(pos, [a, b]);
                pos[a] = locator.boundary_point(pa.lp, pa.arc + sign * step_a);
                pos[b] = locator.boundary_point(pb.lp, pb.arc - sign * step_b);
                if worst_around(pos, [a, b]) < worst_before {
                    moved = true;
                } else {
                    (pos[a], pos[b]) = before;
                }
            }
        }
        if !moved {
            break;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::remesh::quadmesh::samples::{grid, lines, valences};

    #[test]
    fn a_staircase_tooth_becomes_one_quad_and_its_corner_stays_regular() {
        // An L of three unit quads; its inner corner f = (1, 1) is a tooth of a staircase
        // whose ends (2, 1) and (1, 2) are near the boundary and f is not.
        let (mut pos, mut faces) = grid(&lines(0.0, 2.0, 2), &lines(0.0, 2.0, 2));
        faces.remove(3);
        let at = |i: usize, j: usize| j * 3 + i;
        let (near0, far, near1) = (at(2, 1), at(1, 1), at(1, 2));
        let spoke = Vector3::new(1.8, 1.8, 0.0);
        let fans = [Vector3::new(2.0, 1.5, 0.0), Vector3::new(1.5, 2.0, 0.0)];
        let at = faces_at(pos.len(), &faces);
        assert!(single_row(
            &mut pos,
            &mut faces,
            &at,
            &[near0, far, near1],
            &[spoke],
            fans
        ));
        assert_eq!(faces.len(), 4, "one quad for the tooth");
        assert_eq!(faces[3], vec![far, near0, pos.len() - 1, near1]);
        assert_eq!(valences(pos.len(), &faces)[far], 4);
        // Counter-clockwise like the others: no directed edge twice.
        let mut directed: Vec<(usize, usize)> = faces
            .iter()
            .flat_map(|f| (0..4).map(move |i| (f[i], f[(i + 1) % 4])))
            .collect();
        let total = directed.len();
        directed.sort_unstable();
        directed.dedup();
        assert_eq!(directed.len(), total);
    }

    #[test]
    fn a_run_whose_ends_are_not_corners_is_left_to_the_fans() {
        // A straight row: its far vertices have two quads each, so every one needs a spoke.
        let (mut pos, mut faces) = grid(&lines(0.0, 3.0, 3), &lines(0.0, 1.0, 1));
        let before = faces.clone();
        let run = [3, 7, 6, 5, 4];
        let spokes = [Vector3::new(2.0, 2.0, 0.0); 3];
        let fans = [Vector3::zeros(); 2];
        let at = faces_at(pos.len(), &faces);
        assert!(!single_row(&mut pos, &mut faces, &at, &run, &spokes, fans));
        assert_eq!(faces, before);
    }
}
