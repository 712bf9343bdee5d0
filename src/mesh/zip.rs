//! Zipping cracks: closing the T-junctions where two patches meshed apart meet along a seam
//! with vertices at different places (one side cut every 10 cm, the other every 13 cm, as
//! surfaces meshed one by one and then combined give). Welding joins the seam's vertices that
//! coincide, which leaves the patches touching at those vertices alone: pinched vertices no
//! surface may have. Each boundary vertex that lies on a boundary edge of the other side is
//! inserted into that edge, its triangle split into a fan from the corner opposite the edge,
//! so that both sides have the same vertices along the seam and share its edges.

use std::collections::HashMap;

use nalgebra::Point3;

use crate::geom::{HashGrid, closest};

/// How far (as a share of the edge's length) a boundary vertex may lie off a boundary edge to
/// be inserted into it: a seam's two sides follow the same curve, but one side's chords
/// pass the other side's vertices at the curve's sagitta, `chord / (8 radius)` of the chord
/// (0.4 % for 10 cm chords on a 3 m radius, 1.3 % for 22 cm chords on 2 m): 3 % takes
/// chords up to a quarter of the radius. (The shared tubemesh has a boundary vertex 3.8 %
/// of a 1.4 m edge off it, by the tip where its surface crumples: a gap, not a seam.)
pub const ZIP_DISTANCE: f64 = 0.03;

/// Cosine of the largest angle between a seam's two sides (15 degrees): a boundary vertex is
/// inserted into an edge only if a boundary edge leaving it runs against the edge this
/// nearly.
pub const SEAM_COS: f64 = 0.965_925_826_289_068_3;

/// Inserts every boundary vertex of `faces` that lies within [`ZIP_DISTANCE`] of a boundary
/// edge of a triangle (and not within that of its ends), and has a boundary edge running
/// against it ([`SEAM_COS`]), into the edge, splitting the
/// triangle. Returns the faces (split triangles replace theirs in place, in order) and the
/// number of insertions. Faces of more than three corners are left as they are: a crack
/// along them is not closed.
pub fn zip(positions: &[Point3<f64>], faces: Vec<Vec<usize>>) -> (Vec<Vec<usize>>, usize) {
    // Meshes validation will refuse are left to it.
    let readable = positions.iter().all(|p| {
        p.coords
            .iter()
            .all(|c| c.is_finite() && c.abs() <= super::MAX_COORDINATE)
    }) && faces.iter().flatten().all(|&v| v < positions.len());
    if !readable {
        return (faces, 0);
    }
    // Directed edges of faces whose undirected edge only one face has.
    let mut uses: HashMap<(usize, usize), usize> = HashMap::new();
    for face in &faces {
        for k in 0..face.len() {
            let (a, b) = (face[k], face[(k + 1) % face.len()]);
            *uses.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    let mut boundary: Vec<(usize, usize, usize)> = Vec::new();
    for (f, face) in faces.iter().enumerate() {
        for k in 0..face.len() {
            let (a, b) = (face[k], face[(k + 1) % face.len()]);
            if uses[&(a.min(b), a.max(b))] == 1 {
                boundary.push((f, a, b));
            }
        }
    }
    if boundary.is_empty() {
        return (faces, 0);
    }
    let mut on_boundary: Vec<usize> = boundary.iter().flat_map(|&(_, a, b)| [a, b]).collect();
    on_boundary.sort_unstable();
    on_boundary.dedup();
    let length = |a: usize, b: usize| (positions[b] - positions[a]).norm();
    let longest = boundary
        .iter()
        .map(|&(_, a, b)| length(a, b))
        .fold(0.0, f64::max);
    let mean = boundary.iter().map(|&(_, a, b)| length(a, b)).sum::<f64>() / boundary.len() as f64;
    let grid = HashGrid::of_points(
        mean.max(f64::MIN_POSITIVE),
        boundary
            .iter()
            .map(|&(_, a, b)| [positions[a], positions[b]]),
    );
    // Per boundary vertex: the directions of the boundary edges leaving it (faces on their
    // left). Across a crack the two sides' edges run opposite ways along the seam; a vertex
    // near an edge it does not run against (a fold, a corner) is no T-junction.
    let mut leaving: HashMap<usize, Vec<nalgebra::Vector3<f64>>> = HashMap::new();
    for &(_, a, b) in &boundary {
        if let Some(d) = (positions[b] - positions[a]).try_normalize(0.0) {
            leaving.entry(a).or_default().push(d);
        }
    }
    // Per triangle edge (face, start corner): the vertices to insert, by their parameter.
    let mut inserts: HashMap<(usize, usize), Vec<(f64, usize)>> = HashMap::new();
    for &v in &on_boundary {
        let p = positions[v].coords;
        for e in grid.near(&positions[v], ZIP_DISTANCE * longest) {
            let (f, a, b) = boundary[e];
            if faces[f].len() != 3 || v == a || v == b {
                continue;
            }
            let (pa, pb) = (positions[a].coords, positions[b].coords);
            let reach = ZIP_DISTANCE * (pb - pa).norm();
            let s = closest::segment_parameter(&p, &pa, &pb);
            let off = (pa + (pb - pa) * s - p).norm();
            let against = (pb - pa).try_normalize(0.0).is_some_and(|d| {
                leaving
                    .get(&v)
                    .is_some_and(|out| out.iter().any(|o| o.dot(&d) < -SEAM_COS))
            });
            if against && off <= reach && (p - pa).norm() > reach && (p - pb).norm() > reach {
                inserts.entry((f, a)).or_default().push((s, v));
            }
        }
    }
    if inserts.is_empty() {
        return (faces, 0);
    }
    let mut count = 0;
    let mut out = Vec::with_capacity(faces.len() + 2 * inserts.len());
    for (f, face) in faces.into_iter().enumerate() {
        let mut triangles = vec![face.clone()];
        for k in 0..face.len() {
            let (a, b) = (face[k], face[(k + 1) % face.len()]);
            let Some(points) = inserts.get_mut(&(f, a)) else {
                continue;
            };
            points.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
            points.dedup_by_key(|x| x.1);
            count += points.len();
            // The triangle that holds the directed edge a -> b now (an earlier split of
            // another edge may have made it smaller), fanned from its third corner.
            let t = triangles
                .iter()
                .position(|t| (0..3).any(|i| t[i] == a && t[(i + 1) % 3] == b))
                .expect("a split keeps every other edge of the triangle");
            let old = triangles.remove(t);
            let i = (0..3).find(|&i| old[i] == a).expect("the triangle has a");
            let apex = old[(i + 2) % 3];
            let chain: Vec<usize> = std::iter::once(a)
                .chain(points.iter().map(|&(_, v)| v))
                .chain(std::iter::once(b))
                .collect();
            for (j, pair) in chain.windows(2).enumerate() {
                triangles.insert(t + j, vec![pair[0], pair[1], apex]);
            }
        }
        out.extend(triangles);
    }
    (out, count)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: f64, y: f64) -> Point3<f64> {
        Point3::new(x, y, 0.0)
    }

    #[test]
    fn a_seam_cut_in_two_and_in_three_is_closed() {
        // Left: one triangle pair over 0..1 x 0..2 with the seam x = 1 in one edge; right: the
        // seam in two edges, its middle vertex 4 a T-junction on the left's seam edge.
        let positions = vec![
            p(0.0, 0.0),
            p(1.0, 0.0),
            p(1.0, 2.0),
            p(0.0, 2.0),
            p(1.0, 1.0 + 1e-4),
            p(2.0, 0.0),
            p(2.0, 2.0),
        ];
        let faces = vec![
            vec![0, 1, 2],
            vec![0, 2, 3],
            vec![1, 5, 4],
            vec![4, 5, 6],
            vec![4, 6, 2],
        ];
        let (zipped, count) = zip(&positions, faces);
        assert_eq!(count, 1);
        // The left triangle with the seam edge 1 -> 2 is split at 4, fanned from 0.
        assert_eq!(
            zipped,
            vec![
                vec![1, 4, 0],
                vec![4, 2, 0],
                vec![0, 2, 3],
                vec![1, 5, 4],
                vec![4, 5, 6],
                vec![4, 6, 2],
            ]
        );
        // Every edge is now shared by two faces or on the outline.
        let mut uses: HashMap<(usize, usize), usize> = HashMap::new();
        for f in &zipped {
            for k in 0..3 {
                let (a, b) = (f[k], f[(k + 1) % 3]);
                *uses.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
        assert_eq!(uses[&(1, 4)], 2);
        assert_eq!(uses[&(2, 4)], 2);
        assert!(!uses.contains_key(&(1, 2)));
    }

    #[test]
    fn a_boundary_without_cracks_is_left_alone() {
        let positions = vec![p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)];
        let faces = vec![vec![0, 1, 2], vec![0, 2, 3]];
        assert_eq!(zip(&positions, faces.clone()), (faces, 0));
        // A patch below the edge 0 -> 1 whose boundary runs back along it from vertex 3 at
        // (0.5, -off) to 4: within ZIP_DISTANCE of the edges' lengths 3 is inserted into
        // 0 -> 1 and 0 into 3 -> 4; beyond it they are left apart.
        let below = |off: f64, faces: Vec<Vec<usize>>| {
            let positions = vec![
                p(0.0, 0.0),
                p(1.0, 0.0),
                p(0.5, 1.0),
                p(0.5, -off),
                p(-0.2, -off),
                p(0.2, -1.0),
                p(0.9, -1.0),
            ];
            zip(&positions, faces).1
        };
        let seam = || vec![vec![0, 1, 2], vec![3, 4, 5]];
        assert_eq!(below(0.01, seam()), 2);
        assert_eq!(below(0.05, seam()), 0);
        // The same patch turned over: its boundary runs along the edge, not against it (a
        // fold, no seam), and the corner of a triangle touching the edge is no seam either.
        assert_eq!(below(0.01, vec![vec![0, 1, 2], vec![3, 5, 4]]), 0);
        assert_eq!(below(0.01, vec![vec![0, 1, 2], vec![3, 5, 6]]), 0);
    }
}
