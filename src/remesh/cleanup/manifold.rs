//! Keeping the face list a manifold mesh: faces with a repeated vertex or a directed edge
//! used twice are dropped, stray components too, and vertices where two fans of faces touch
//! are split.

use std::collections::{BTreeMap, BTreeSet, HashMap};

use nalgebra::Vector3;

use crate::remesh::quadmesh::{corners_key, edge_faces, key};

/// Components with fewer faces than this are dropped (stray faces of a garbled lattice).
const MIN_COMPONENT: usize = 4;

/// Whether face `f` visits no vertex twice.
pub(super) fn distinct(f: &[usize]) -> bool {
    f.iter().enumerate().all(|(i, v)| !f[i + 1..].contains(v))
}

/// Drops faces that would use a directed edge a second time (crossing links), or that lie on
/// the same corners as an earlier face (a pillow of two faces back to back).
pub(super) fn make_edge_manifold(faces: &mut Vec<Vec<usize>>) {
    let mut seen: HashMap<(usize, usize), ()> = HashMap::new();
    let mut corners_seen: BTreeSet<Vec<usize>> = BTreeSet::new();
    faces.retain(|f| {
        let directed: Vec<(usize, usize)> =
            (0..f.len()).map(|i| (f[i], f[(i + 1) % f.len()])).collect();
        if directed.iter().any(|d| seen.contains_key(d)) {
            return false;
        }
        if !corners_seen.insert(corners_key(f)) {
            return false;
        }
        for d in directed {
            seen.insert(d, ());
        }
        true
    });
}

/// Drops edge-connected components with fewer than [`MIN_COMPONENT`] faces.
pub(super) fn drop_small_components(faces: &mut Vec<Vec<usize>>) {
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
pub(super) fn split_pinched_vertices(pos: &mut Vec<Vector3<f64>>, faces: &mut [Vec<usize>]) {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::remesh::quadmesh::boundary_loops;
    use crate::remesh::quadmesh::samples::{grid, lines};

    #[test]
    fn faces_that_repeat_a_vertex_or_a_directed_edge_go() {
        assert!(distinct(&[0, 1, 2, 3]) && !distinct(&[0, 1, 2, 1]));
        // The third face runs 1 -> 2 as the first does (a crossing link); the second runs
        // 2 -> 1, as a neighbour should.
        let mut faces = vec![vec![0, 1, 2, 3], vec![1, 4, 5, 2], vec![1, 2, 6, 7]];
        make_edge_manifold(&mut faces);
        assert_eq!(faces, vec![vec![0, 1, 2, 3], vec![1, 4, 5, 2]]);
        // The same corners the other way round: no directed edge twice, but a face twice.
        faces.push(vec![2, 5, 4, 1]);
        make_edge_manifold(&mut faces);
        assert_eq!(faces, vec![vec![0, 1, 2, 3], vec![1, 4, 5, 2]]);
    }

    #[test]
    fn components_of_fewer_than_four_faces_go() {
        let (_, mut faces) = grid(&lines(0.0, 2.0, 2), &lines(0.0, 2.0, 2));
        // Three stray faces in a row, apart from the 2 x 2 block.
        faces.extend([
            vec![20, 21, 31, 30],
            vec![21, 22, 32, 31],
            vec![22, 23, 33, 32],
        ]);
        let block = faces[..4].to_vec();
        drop_small_components(&mut faces);
        assert_eq!(faces, block);
        // Faces touching at a vertex only are separate components.
        let mut touching = vec![vec![0, 1, 2, 3], vec![2, 4, 5, 6]];
        drop_small_components(&mut touching);
        assert!(touching.is_empty());
    }

    #[test]
    fn two_fans_at_one_vertex_get_a_vertex_each() {
        // Two 2 x 2 blocks touching at one corner: (2, 2) of the first is (0, 0) of the second.
        let (mut pos, mut faces) = grid(&lines(0.0, 2.0, 2), &lines(0.0, 2.0, 2));
        let (pos2, faces2) = grid(&lines(2.0, 4.0, 2), &lines(2.0, 4.0, 2));
        let shift = pos.len();
        pos.extend(pos2);
        faces.extend(faces2.into_iter().map(|f| {
            f.into_iter()
                .map(|v| if v == 0 { 8 } else { v + shift })
                .collect::<Vec<_>>()
        }));
        assert_eq!(
            boundary_loops(&faces).len(),
            2,
            "one walk through vertex 8, split in two"
        );
        let before = pos.len();
        split_pinched_vertices(&mut pos, &mut faces);
        assert_eq!(pos.len(), before + 1);
        assert_eq!(pos[before], pos[8]);
        assert!(
            faces[..4].iter().any(|f| f.contains(&8)) && faces[4..].iter().all(|f| !f.contains(&8))
        );
        assert!(faces[4..].iter().any(|f| f.contains(&before)));
        // A vertex inside a block is shared by faces that share edges: left alone.
        assert!(faces[..4].iter().filter(|f| f.contains(&4)).count() == 4);
    }
}
