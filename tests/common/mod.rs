//! Helpers shared by the integration tests: small irregular quad meshes and brute force.
#![allow(dead_code)]

use nalgebra::Point3;
use tilepattern::mesh::PolyMesh;

/// Splits every face into quads through its centroid and edge midpoints (one Catmull-Clark
/// topology step without smoothing): an n-gon becomes n quads, and its centre an interior
/// vertex of valence n.
pub fn split_into_quads(mesh: &PolyMesh) -> PolyMesh {
    let mut positions: Vec<Point3<f64>> = mesh.positions().to_vec();
    let mut midpoint = std::collections::BTreeMap::new();
    let mut faces = Vec::new();
    for (f, face) in mesh.faces().iter().enumerate() {
        let centre = positions.len();
        positions.push(mesh.face_centroid(f));
        let n = face.len();
        let mut mid = |a: usize, b: usize, positions: &mut Vec<Point3<f64>>| -> usize {
            *midpoint.entry((a.min(b), a.max(b))).or_insert_with(|| {
                positions.push(nalgebra::center(&positions[a], &positions[b]));
                positions.len() - 1
            })
        };
        for i in 0..n {
            let prev = face[(i + n - 1) % n];
            let (v, next) = (face[i], face[(i + 1) % n]);
            let m_in = mid(prev, v, &mut positions);
            let m_out = mid(v, next, &mut positions);
            faces.push(vec![v, m_out, centre, m_in]);
        }
    }
    PolyMesh::new(positions, faces).unwrap()
}

/// A regular polygon with `n` corners as one face, in the xy plane.
pub fn polygon(n: usize) -> PolyMesh {
    let positions = (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            Point3::new(a.cos(), a.sin(), 0.0)
        })
        .collect();
    PolyMesh::new(positions, vec![(0..n).collect()]).unwrap()
}

/// Every matching of the candidate tiles `tiles` (as face pairs) over `face_count` faces.
pub fn all_matchings(face_count: usize, tiles: &[[usize; 2]]) -> Vec<Vec<bool>> {
    fn go(k: usize, tiles: &[[usize; 2]], used: &mut [bool], chosen: &mut Vec<bool>, out: &mut Vec<Vec<bool>>) {
        if k == tiles.len() {
            out.push(chosen.clone());
            return;
        }
        chosen.push(false);
        go(k + 1, tiles, used, chosen, out);
        chosen.pop();
        let [a, b] = tiles[k];
        if !used[a] && !used[b] {
            used[a] = true;
            used[b] = true;
            chosen.push(true);
            go(k + 1, tiles, used, chosen, out);
            chosen.pop();
            used[a] = false;
            used[b] = false;
        }
    }
    let mut out = Vec::new();
    go(0, tiles, &mut vec![false; face_count], &mut Vec::new(), &mut out);
    out
}

/// True when every pair shares an edge of `mesh` and no face is used twice.
pub fn is_valid_matching(mesh: &PolyMesh, pairs: &[[usize; 2]]) -> bool {
    let mut used = vec![false; mesh.face_count()];
    pairs.iter().all(|&[a, b]| {
        let shared = mesh.faces()[a].iter().filter(|v| mesh.faces()[b].contains(v)).count();
        shared == 2 && !std::mem::replace(&mut used[a], true) && !std::mem::replace(&mut used[b], true)
    })
}
