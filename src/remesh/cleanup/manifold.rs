//! Keeping the face list a manifold mesh: faces with a repeated vertex or a directed edge
//! used twice are dropped, stray components too, and vertices where two fans of faces touch
//! are split.

use std::collections::{BTreeMap, HashMap};

use nalgebra::Vector3;

use crate::remesh::quadmesh::{edge_faces, key};

/// Components with fewer faces than this are dropped (stray faces of a garbled lattice).
pub(super) const MIN_COMPONENT: usize = 4;

pub(super) fn distinct(f: &[usize]) -> bool {
    f.iter().enumerate().all(|(i, v)| !f[i + 1..].contains(v))
}

/// Drops faces that would use a directed edge a second time (crossing links).
pub(super) fn make_edge_manifold(faces: &mut Vec<Vec<usize>>) {
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
