//! The quad mesh in progress as a list of faces (vertex indices, counter-clockwise): its
//! edges and their faces, its boundary loops, compaction, and the shape of a quad.

use std::collections::BTreeMap;

use nalgebra::Vector3;

/// Undirected edge key.
pub(super) fn key(a: usize, b: usize) -> (usize, usize) {
    (a.min(b), a.max(b))
}

/// A face's corners, sorted: the same for a face and for that face the other way round (or
/// from another first corner).
pub(super) fn corners_key(face: &[usize]) -> Vec<usize> {
    let mut k = face.to_vec();
    k.sort_unstable();
    k
}

/// Undirected edge -> faces containing it, in face order.
pub(super) fn edge_faces(faces: &[Vec<usize>]) -> BTreeMap<(usize, usize), Vec<usize>> {
    let mut map: BTreeMap<(usize, usize), Vec<usize>> = BTreeMap::new();
    for (fi, f) in faces.iter().enumerate() {
        for i in 0..f.len() {
            map.entry(key(f[i], f[(i + 1) % f.len()]))
                .or_default()
                .push(fi);
        }
    }
    map
}

/// Boundary loops of the face set, each as the sequence of vertices along boundary
/// half-edges (faces on the left).
pub(super) fn boundary_loops(faces: &[Vec<usize>]) -> Vec<Vec<usize>> {
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

/// Drops the faces marked `gone` (keeping the order of the rest) and appends `added`.
pub(super) fn replace_faces(faces: &mut Vec<Vec<usize>>, gone: &[bool], added: Vec<Vec<usize>>) {
    let mut k = 0;
    faces.retain(|_| {
        k += 1;
        !gone[k - 1]
    });
    faces.extend(added);
}

/// Drops unused vertices, keeping order.
pub(super) fn compact(
    pos: Vec<Vector3<f64>>,
    faces: Vec<Vec<usize>>,
) -> (Vec<Vector3<f64>>, Vec<Vec<usize>>) {
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

/// Quality of a quad: summed corner deviation from 90 degrees (radians), plus a penalty for
/// reflex corners with respect to the quad's own normal.
pub(super) fn quad_cost(pos: &[Vector3<f64>], q: [usize; 4]) -> f64 {
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

/// Quad meshes for the remesher's unit tests.
#[cfg(test)]
pub(crate) mod samples {
    use nalgebra::Vector3;

    /// A grid of quads in the plane z = 0 over the lines `x = xs[i]` and `y = ys[j]`,
    /// counter-clockwise seen from above; vertex `(i, j)` is `j * xs.len() + i`, face `(i, j)`
    /// is `j * (xs.len() - 1) + i`.
    pub fn grid(xs: &[f64], ys: &[f64]) -> (Vec<Vector3<f64>>, Vec<Vec<usize>>) {
        let nx = xs.len();
        let pos = ys
            .iter()
            .flat_map(|&y| xs.iter().map(move |&x| Vector3::new(x, y, 0.0)))
            .collect();
        let at = |i: usize, j: usize| j * nx + i;
        let faces = (0..ys.len() - 1)
            .flat_map(|j| {
                (0..nx - 1)
                    .map(move |i| vec![at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)])
            })
            .collect();
        (pos, faces)
    }

    /// `n + 1` evenly spaced lines from `from` to `to`.
    pub fn lines(from: f64, to: f64, n: usize) -> Vec<f64> {
        (0..=n)
            .map(|k| from + (to - from) * k as f64 / n as f64)
            .collect()
    }

    /// Per vertex: how many edges meet there.
    pub fn valences(n: usize, faces: &[Vec<usize>]) -> Vec<usize> {
        let mut valence = vec![0; n];
        for &(a, b) in super::edge_faces(faces).keys() {
            valence[a] += 1;
            valence[b] += 1;
        }
        valence
    }
}

#[cfg(test)]
mod tests {
    use super::samples::{grid, lines};
    use super::*;

    #[test]
    fn edges_know_their_faces() {
        let (_, faces) = grid(&lines(0.0, 2.0, 2), &lines(0.0, 2.0, 2));
        let map = edge_faces(&faces);
        assert_eq!(map.len(), 12);
        assert_eq!(map.values().filter(|l| l.len() == 2).count(), 4);
        assert_eq!(map[&key(4, 1)], vec![0, 1]);
        assert_eq!(key(7, 3), (3, 7));
    }

    #[test]
    fn boundary_loops_of_a_ring_and_of_a_figure_eight() {
        // 3 x 3 quads without the middle one: the outline and the hole.
        let (_, mut faces) = grid(&lines(0.0, 3.0, 3), &lines(0.0, 3.0, 3));
        faces.remove(4);
        let mut loops = boundary_loops(&faces);
        loops.sort_by_key(Vec::len);
        assert_eq!(loops.iter().map(Vec::len).collect::<Vec<_>>(), vec![4, 12]);
        // Faces on the left: the outline runs 0 -> 1 -> 2, the hole 5 -> 9 -> 10.
        let follows = |lp: &[usize], a: usize, b: usize| {
            (0..lp.len()).any(|i| lp[i] == a && lp[(i + 1) % lp.len()] == b)
        };
        assert!(follows(&loops[1], 0, 1) && follows(&loops[1], 1, 2));
        assert!(follows(&loops[0], 5, 9) && follows(&loops[0], 9, 10));
        // Two quads touching at vertex 2: one walk, split into two simple loops.
        let faces = vec![vec![0, 1, 2, 3], vec![2, 4, 5, 6]];
        let mut loops = boundary_loops(&faces);
        loops.iter_mut().for_each(|lp| lp.sort_unstable());
        loops.sort();
        assert_eq!(loops, vec![vec![0, 1, 2, 3], vec![2, 4, 5, 6]]);
    }

    #[test]
    fn compaction_drops_unused_vertices_in_order_of_use() {
        let pos: Vec<Vector3<f64>> = (0..6).map(|k| Vector3::new(k as f64, 0.0, 0.0)).collect();
        let (pos, faces) = compact(pos, vec![vec![5, 1, 3, 4]]);
        assert_eq!(faces, vec![vec![0, 1, 2, 3]]);
        assert_eq!(
            pos.iter().map(|p| p.x).collect::<Vec<_>>(),
            vec![5.0, 1.0, 3.0, 4.0]
        );
    }

    #[test]
    fn a_square_costs_nothing_a_skewed_quad_its_angles_a_folded_one_more() {
        let pos = vec![
            Vector3::new(0.0, 0.0, 0.0),
            Vector3::new(1.0, 0.0, 0.0),
            Vector3::new(1.0, 1.0, 0.0),
            Vector3::new(0.0, 1.0, 0.0),
            Vector3::new(1.5, 1.0, 0.0),
            Vector3::new(0.5, 1.0, 0.0),
            Vector3::new(0.3, 0.3, 0.0),
        ];
        assert!(quad_cost(&pos, [0, 1, 2, 3]).abs() < 1e-12);
        // A parallelogram with corners of 63.4 and 116.6 degrees: four times 26.6 degrees.
        let skew = quad_cost(&pos, [0, 1, 4, 5]);
        assert!((skew - 4.0 * (0.5f64).atan()).abs() < 1e-12);
        // A dart: its reflex corner costs a half turn on top of its angles.
        assert!(quad_cost(&pos, [0, 1, 6, 3]) > std::f64::consts::PI);
    }
}
