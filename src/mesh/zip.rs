//! Zipping cracks: closing the T-junctions where two patches meshed apart meet along a seam
//! with vertices at different places (one side cut every 10 cm, the other every 13 cm, as
//! surfaces meshed one by one and then combined give). Welding joins the seam's vertices that
//! coincide, which leaves the patches touching at those vertices alone: pinched vertices no
//! surface may have. Each boundary vertex that lies on a boundary edge of the other side is
//! inserted into that edge, its triangle split into a fan from the corner opposite the edge,
//! so that both sides have the same vertices along the seam and share its edges.

use std::collections::HashMap;

use foldhash::fast::FixedState;
use nalgebra::{Point3, Vector3};

use super::FileNumbering;
use crate::geom::{HashGrid, closest};

/// How far (as a share of the edge's length) a boundary vertex may lie off a boundary edge to
/// be inserted into it: a seam's two sides follow the same curve, but one side's chords
/// pass the other side's vertices at the curve's sagitta, `chord / (8 radius)` of the chord
/// (0.4 % for 10 cm chords on a 3 m radius, 1.3 % for 22 cm chords on 2 m): 3 % takes
/// chords up to a quarter of the radius. (The shared tubemesh has a boundary vertex 3.8 %
/// of a 1.4 m edge off it, by the tip where its surface crumples: a gap, not a seam.)
pub const ZIP_DISTANCE: f64 = 0.03;

/// Cosine of the largest angle between a seam's two sides (15 degrees): a boundary vertex is
/// inserted into an edge only if a boundary edge at it runs along the edge this nearly.
pub const SEAM_COS: f64 = 0.965_925_826_289_068_3;

/// A triangle edge to split: its face and its first corner's place in the face.
type Split = (usize, usize);

/// A boundary edge: its face, its place in the face (from corner `k` to `k + 1`), its ends,
/// and the unit direction from the edge into its face, across it.
struct Side {
    face: usize,
    k: usize,
    ends: [usize; 2],
    inward: Vector3<f64>,
}

/// Inserts every boundary vertex of `faces` that lies within [`ZIP_DISTANCE`] of a boundary
/// edge of a triangle (and not within that of its ends) into the edge, splitting the
/// triangle into a fan from its third corner, when the vertex is the end of a boundary edge
/// that runs along the edge ([`SEAM_COS`], either way: the patches may be wound either way,
/// orientation comes later) with its face on the other side (a seam; a patch folded over
/// the edge, on the same side, is left). Such a vertex within [`ZIP_DISTANCE`] of an end of
/// the edge is joined to that end instead (the two sides' vertices nearly coincide there).
/// Returns the faces and the number of vertices inserted or joined. Each split triangle
/// keeps its place (its first part) and the other parts are appended after the file's faces,
/// so face numbers do not move unless a joined pair collapses a sliver (then it is left
/// out). Faces of more than three corners are left as they are: a crack along them is not
/// closed.
pub fn zip(positions: &[Point3<f64>], faces: Vec<Vec<usize>>) -> (Vec<Vec<usize>>, usize) {
    let (faces, count, _) = zip_traced(positions, faces);
    (faces, count)
}

/// [`zip`], with where each face of the result comes from (vertices keep their numbers: a
/// joined one is left unused).
pub fn zip_traced(
    positions: &[Point3<f64>],
    mut faces: Vec<Vec<usize>>,
) -> (Vec<Vec<usize>>, usize, FileNumbering) {
    let file_faces = faces.len();
    let same = |faces: usize| FileNumbering::identity(faces, positions.len());
    // Meshes validation will refuse are left to it.
    if !super::readable(positions, &faces) {
        let n = faces.len();
        return (faces, 0, same(n));
    }
    // Fixed-seed hashers: only lookups, and the sorted keys, shape the result.
    let mut uses: HashMap<(usize, usize), usize, FixedState> =
        HashMap::with_capacity_and_hasher(faces.len() * 2, FixedState::default());
    for face in &faces {
        for k in 0..face.len() {
            let (a, b) = (face[k], face[(k + 1) % face.len()]);
            *uses.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    let at = |v: usize| positions[v].coords;
    let mut sides: Vec<Side> = Vec::new();
    for (f, face) in faces.iter().enumerate() {
        let centre = face.iter().map(|&v| at(v)).sum::<Vector3<f64>>() / face.len() as f64;
        for k in 0..face.len() {
            let (a, b) = (face[k], face[(k + 1) % face.len()]);
            if uses[&(a.min(b), a.max(b))] != 1 {
                continue;
            }
            let Some(d) = (at(b) - at(a)).try_normalize(0.0) else {
                continue;
            };
            let to_centre = centre - at(a);
            let Some(inward) = (to_centre - d * d.dot(&to_centre)).try_normalize(0.0) else {
                continue;
            };
            sides.push(Side {
                face: f,
                k,
                ends: [a, b],
                inward,
            });
        }
    }
    if sides.is_empty() {
        let n = faces.len();
        return (faces, 0, same(n));
    }
    // Boundary vertices in a grid of points, and the sides at each.
    let mut at_vertex: HashMap<usize, Vec<usize>, FixedState> = HashMap::default();
    for (i, side) in sides.iter().enumerate() {
        for v in side.ends {
            at_vertex.entry(v).or_default().push(i);
        }
    }
    let mut vertices: Vec<usize> = at_vertex.keys().copied().collect();
    vertices.sort_unstable();
    let mean = sides
        .iter()
        .map(|s| (at(s.ends[1]) - at(s.ends[0])).norm())
        .sum::<f64>()
        / sides.len() as f64;
    let grid = HashGrid::of_points(
        mean.max(f64::MIN_POSITIVE),
        vertices.iter().map(|&v| [positions[v]]),
    );
    // Per split edge (face, corner): the vertices to insert, by their parameter along it.
    let mut inserts: Vec<(Split, Vec<(f64, usize)>)> = Vec::new();
    // Seam vertices of the two sides nearer than the reach to one another, to join.
    let mut joins: Vec<(usize, usize)> = Vec::new();
    for side in sides.iter().filter(|s| faces[s.face].len() == 3) {
        let [a, b] = side.ends;
        let (pa, pb) = (at(a), at(b));
        let d = (pb - pa).normalize();
        let reach = ZIP_DISTANCE * (pb - pa).norm();
        let widen = Vector3::repeat(reach);
        let lo = Point3::from(pa.inf(&pb) - widen);
        let hi = Point3::from(pa.sup(&pb) + widen);
        let mut points = Vec::new();
        for v in grid.in_box(&lo, &hi).into_iter().map(|i| vertices[i]) {
            if faces[side.face].contains(&v) {
                continue;
            }
            let p = at(v);
            let s = closest::segment_parameter(&p, &pa, &pb);
            let off = (pa + (pb - pa) * s - p).norm();
            if off > reach {
                continue;
            }
            let seam = at_vertex[&v].iter().any(|&o| {
                let other = &sides[o];
                let e = (at(other.ends[1]) - at(other.ends[0])).normalize();
                e.dot(&d).abs() > SEAM_COS && other.inward.dot(&side.inward) < 0.0
            });
            if !seam {
                continue;
            }
            // Within reach of an end, the two are one vertex of the seam; else v splits it.
            if (p - pa).norm() <= reach {
                joins.push((v, a));
            } else if (p - pb).norm() <= reach {
                joins.push((v, b));
            } else {
                points.push((s, v));
            }
        }
        if !points.is_empty() {
            points.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
            inserts.push(((side.face, side.k), points));
        }
    }
    let mut inserted: Vec<usize> = Vec::new();
    // Split, face by face (a face's edges in order), each edge in the part that holds it.
    let mut appended = Vec::new();
    let mut source: Vec<usize> = (0..file_faces).collect();
    let mut i = 0;
    while i < inserts.len() {
        let f = inserts[i].0.0;
        let face = faces[f].clone();
        let mut parts = vec![face.clone()];
        while i < inserts.len() && inserts[i].0.0 == f {
            let ((_, k), points) = &inserts[i];
            i += 1;
            let (a, b) = (face[*k], face[(k + 1) % 3]);
            let t = parts
                .iter()
                .position(|t| (0..3).any(|j| t[j] == a && t[(j + 1) % 3] == b))
                .expect("a split keeps every other edge of the triangle");
            let j = parts[t]
                .iter()
                .position(|&x| x == a)
                .expect("the part has a");
            let apex = parts[t][(j + 2) % 3];
            // No corner of the part is inserted into its own edge.
            let middle: Vec<usize> = points
                .iter()
                .map(|&(_, v)| v)
                .filter(|v| !parts[t].contains(v))
                .collect();
            inserted.extend(&middle);
            let chain: Vec<usize> = std::iter::once(a)
                .chain(middle)
                .chain(std::iter::once(b))
                .collect();
            let fan: Vec<Vec<usize>> = chain.windows(2).map(|w| vec![w[0], w[1], apex]).collect();
            parts.splice(t..=t, fan);
        }
        let mut parts = parts.into_iter();
        faces[f] = parts.next().expect("a split leaves a part");
        for part in parts {
            appended.push(part);
            source.push(f);
        }
    }
    faces.extend(appended);
    // Joined vertices become the lowest of their group (a vertex no face uses is left).
    let mut same: Vec<usize> = (0..positions.len()).collect();
    let find = |same: &mut Vec<usize>, mut v: usize| {
        while same[v] != v {
            same[v] = same[same[v]];
            v = same[v];
        }
        v
    };
    for &(v, w) in &joins {
        let (x, y) = (find(&mut same, v), find(&mut same, w));
        if x != y {
            same[x.max(y)] = x.min(y);
            inserted.push(x.max(y));
        }
    }
    if !joins.is_empty() {
        for face in &mut faces {
            for v in face.iter_mut() {
                *v = find(&mut same, *v);
            }
        }
        // A sliver between two joined vertices collapses.
        let whole = |face: &Vec<usize>| {
            let mut corners = face.clone();
            corners.sort_unstable();
            corners.dedup();
            corners.len() == face.len()
        };
        source = source
            .into_iter()
            .zip(&faces)
            .filter(|(_, face)| whole(face))
            .map(|(s, _)| s)
            .collect();
        faces.retain(whole);
    }
    inserted.sort_unstable();
    inserted.dedup();
    let numbering = FileNumbering::new(file_faces, source, (0..positions.len()).collect());
    (faces, inserted.len(), numbering)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: f64, y: f64) -> Point3<f64> {
        Point3::new(x, y, 0.0)
    }

    /// Left: one triangle pair over 0..1 x 0..2 with the seam x = 1 in one edge, 1 -> 2;
    /// right: the seam in two edges, its middle vertex 4 (at `middle`) a T-junction on the
    /// left's seam edge, its top end 2 itself or, with `top`, a vertex 7 of its own there.
    fn two_sides(
        middle: Point3<f64>,
        top: Option<Point3<f64>>,
    ) -> (Vec<Point3<f64>>, Vec<Vec<usize>>) {
        let mut positions = vec![
            p(0.0, 0.0),
            p(1.0, 0.0),
            p(1.0, 2.0),
            p(0.0, 2.0),
            middle,
            p(2.0, 0.0),
            p(2.0, 2.0),
        ];
        positions.extend(top);
        let end = if top.is_some() { 7 } else { 2 };
        let faces = vec![
            vec![0, 1, 2],
            vec![0, 2, 3],
            vec![1, 5, 4],
            vec![4, 5, 6],
            vec![4, 6, end],
        ];
        (positions, faces)
    }

    /// [`two_sides`] zipped: the left triangle with the seam edge 1 -> 2 split at 4, fanned
    /// from 0, its first part in its place and the second after the file's faces.
    fn zipped_two_sides() -> Vec<Vec<usize>> {
        vec![
            vec![1, 4, 0],
            vec![0, 2, 3],
            vec![1, 5, 4],
            vec![4, 5, 6],
            vec![4, 6, 2],
            vec![4, 2, 0],
        ]
    }

    #[test]
    fn a_seam_cut_in_two_and_in_three_is_closed() {
        let (positions, faces) = two_sides(p(1.0, 1.0 + 1e-4), None);
        let (zipped, count) = zip(&positions, faces);
        assert_eq!(count, 1);
        assert_eq!(zipped, zipped_two_sides());
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
    fn seam_vertices_that_nearly_coincide_are_joined() {
        // The right side's seam ends at 7, 2 cm below the left side's corner 2 on a 2 m
        // edge (within ZIP_DISTANCE, farther than any weld): 7 becomes 2, and 4 splits the
        // left side's edge as before.
        let (positions, faces) = two_sides(p(1.001, 1.0), Some(p(1.0, 1.98)));
        let (zipped, count) = zip(&positions, faces);
        assert_eq!(count, 2);
        assert_eq!(zipped, zipped_two_sides());
    }

    #[test]
    fn a_boundary_without_cracks_is_left_alone() {
        let positions = vec![p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)];
        let faces = vec![vec![0, 1, 2], vec![0, 2, 3]];
        assert_eq!(zip(&positions, faces.clone()), (faces, 0));
        // A patch below the edge 0 -> 1 whose boundary runs back along it from vertex 3 at
        // (0.5, -off) to 4: within ZIP_DISTANCE of the edges' lengths 3 is inserted into
        // 0 -> 1 and 0 into 3 -> 4, whichever way the patch is wound; beyond it they are
        // left apart.
        let zipped = |off: f64, faces: Vec<Vec<usize>>| {
            let positions = vec![
                p(0.0, 0.0),
                p(1.0, 0.0),
                p(0.5, 1.0),
                p(0.5, -off),
                p(-0.2, -off),
                p(0.2, -1.0),
                p(0.9, -1.0),
                p(0.5, off),
                p(-0.2, off),
                p(0.2, 1.0),
            ];
            zip(&positions, faces).1
        };
        let top = vec![0, 1, 2];
        assert_eq!(zipped(0.01, vec![top.clone(), vec![3, 4, 5]]), 2);
        assert_eq!(zipped(0.01, vec![top.clone(), vec![3, 5, 4]]), 2);
        assert_eq!(zipped(0.05, vec![top.clone(), vec![3, 4, 5]]), 0);
        // A corner of a triangle touching the edge is no seam, nor a patch folded over the
        // edge onto the same side (7, 8, 9 above it).
        assert_eq!(zipped(0.01, vec![top.clone(), vec![3, 5, 6]]), 0);
        assert_eq!(zipped(0.01, vec![top, vec![7, 8, 9]]), 0);
        // A sliver's own corner near its own edge is left (no face with a corner twice).
        let sliver = vec![vec![0, 1, 2]];
        let positions = [p(0.0, 0.0), p(1.0, 0.0), p(0.5, 0.01)];
        assert_eq!(zip(&positions, sliver.clone()), (sliver, 0));
    }
}
