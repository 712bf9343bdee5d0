//! Mesh extraction from the lattice (Instant Meshes section 6).
//!
//! Vertices whose lattice corners coincide (integer offset zero along an edge) are collapsed
//! into one quad vertex; edges whose offset is one lattice step become quad edges; faces are
//! then traced as the cycles of this graph in each vertex's tangent plane (the next edge is
//! the one turning right-most), which closes quads where the lattice is regular and short
//! polygons around singularities and defects. Loops longer than [`MAX_FACE`] are left open
//! as holes for the cleanup to fill.

use nalgebra::Vector3;

use super::position::Lattice;
use super::surface::{Surface, any_tangent};

/// Longest cycle kept as a face; longer ones are the outer boundary or holes.
pub(crate) const MAX_FACE: usize = 8;

/// A polygon mesh straight out of extraction.
#[derive(Debug, Clone)]
pub(crate) struct Raw {
    /// Vertex positions (near the surface, not yet projected).
    pub positions: Vec<Vector3<f64>>,
    /// Polygon faces, oriented like the input.
    pub faces: Vec<Vec<usize>>,
}

fn find(parent: &mut [usize], mut x: usize) -> usize {
    while parent[x] != x {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    x
}

/// Collapses, links and traces the lattice into polygons.
pub(crate) fn extract(s: &Surface, lattice: &Lattice) -> Raw {
    let n = s.len();
    let mut parent: Vec<usize> = (0..n).collect();
    for (e, &[a, b]) in s.edges.iter().enumerate() {
        if lattice.offset[e] == [0, 0] {
            let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
            if ra != rb {
                let (lo, hi) = (ra.min(rb), ra.max(rb));
                parent[hi] = lo;
            }
        }
    }
    let mut cluster = vec![usize::MAX; n];
    let mut count = 0;
    for v in 0..n {
        let r = find(&mut parent, v);
        if cluster[r] == usize::MAX {
            cluster[r] = count;
            count += 1;
        }
        cluster[v] = cluster[r];
    }
    // Position: mean of the lattice corners; boundary clusters use their pinned members only,
    // so the corner lands on the boundary line.
    let mut level = vec![0u8; count];
    for (&c, &p) in cluster.iter().zip(&lattice.pinned) {
        level[c] = level[c].max(p);
    }
    let mut sum = vec![Vector3::zeros(); count];
    let mut nsum = vec![Vector3::zeros(); count];
    let mut weight = vec![0.0; count];
    for (v, &c) in cluster.iter().enumerate() {
        nsum[c] += s.normals[v];
        if lattice.pinned[v] == level[c] {
            sum[c] += lattice.origin[v];
            weight[c] += 1.0;
        }
    }
    let positions: Vec<Vector3<f64>> = (0..count).map(|c| sum[c] / weight[c]).collect();
    let normals: Vec<Vector3<f64>> = nsum
        .iter()
        .map(|m| m.try_normalize(1e-300).unwrap_or_else(Vector3::z))
        .collect();

    let mut links: Vec<[usize; 2]> = Vec::new();
    for (e, &[a, b]) in s.edges.iter().enumerate() {
        let [x, y] = lattice.offset[e];
        if x.abs() + y.abs() == 1 {
            let (ca, cb) = (cluster[a], cluster[b]);
            if ca != cb {
                links.push([ca.min(cb), ca.max(cb)]);
            }
        }
    }
    links.sort_unstable();
    links.dedup();
    let mut around: Vec<Vec<(f64, usize)>> = vec![Vec::new(); count];
    for &[a, b] in &links {
        around[a].push((0.0, b));
        around[b].push((0.0, a));
    }
    for c in 0..count {
        let nrm = normals[c];
        let e = any_tangent(&nrm);
        let f = nrm.cross(&e);
        for item in &mut around[c] {
            let d = positions[item.1] - positions[c];
            item.0 = d.dot(&f).atan2(d.dot(&e));
        }
        around[c].sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
    }
    // Half-edge (a -> k-th neighbour of a) visited flags.
    let mut used: Vec<Vec<bool>> = around.iter().map(|l| vec![false; l.len()]).collect();
    let mut faces = Vec::new();
    for start in 0..count {
        for k0 in 0..around[start].len() {
            if used[start][k0] {
                continue;
            }
            let mut face = vec![start];
            let (mut a, mut k) = (start, k0);
            let mut closed = false;
            for _ in 0..4 * MAX_FACE {
                used[a][k] = true;
                let b = around[a][k].1;
                if b == start {
                    closed = true;
                    break;
                }
                face.push(b);
                // At b, the neighbour just before a in counter-clockwise order.
                let list = &around[b];
                let pos = list.iter().position(|&(_, w)| w == a).unwrap_or(0);
                let next = (pos + list.len() - 1) % list.len();
                a = b;
                k = next;
                if used[a][k] {
                    break;
                }
            }
            if closed && face.len() >= 3 && face.len() <= MAX_FACE {
                faces.push(face);
            }
        }
    }
    Raw { positions, faces }
}
