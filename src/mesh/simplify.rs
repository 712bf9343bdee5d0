//! Simplifying an input much finer than the quads it is to get, before remeshing: a scanned
//! shell or a surface meshed at a few millimetres has a hundred triangles or more per quad,
//! and every stage after reading works on each of them (a 6 m sail of a million triangles
//! took 42 s to remesh and 13 s to tile where the same sail at 50 mm edges takes 2 s).
//!
//! Half-edge collapses in order of the quadric error (Garland and Heckbert, "Surface
//! simplification using quadric error metrics", SIGGRAPH 1997): each collapse removes one
//! vertex, moving its triangles onto a neighbour, so every vertex kept is an input vertex
//! and lies on the input surface. A collapse is made only while every edge it makes is at
//! most `max_edge`, no triangle it moves turns by more than 30 degrees or becomes a sliver
//! ([`MAX_TURN_COS`], [`MIN_SHAPE`]), and the mesh stays a manifold of the same topology
//! (the link condition). The vertices of the boundary and of the creases that part the
//! surface into sheets are never removed, so the boundary and the creases stay the input's.
//! Ties go to the lower vertex indices: the same input gives the same mesh.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use nalgebra::{Matrix4, Point3, Vector3, Vector4};

use super::{PolyMesh, Topology};

/// Most a moved triangle's normal may turn in one collapse: 30 degrees (cosine).
const MAX_TURN_COS: f64 = 0.866;

/// Least share of its area a moved triangle keeps against its longest edge squared (a
/// sliver of an equilateral triangle's 0.43 is refused below a tenth of that).
const MIN_SHAPE: f64 = 0.04;

/// Collapses made between two questions to `keep_going`.
const POLL_EVERY: usize = 4096;

/// `mesh` (triangles, or polygons fanned into triangles) with vertices removed while the
/// edges stay at most `max_edge` (see the module documentation). Returns the mesh and the
/// number of vertices removed. `keep_going` is asked now and then; when it says no, the
/// collapses stop and the mesh so far is returned (a valid one: each collapse keeps it so).
pub fn simplify(
    mesh: &PolyMesh,
    max_edge: f64,
    keep_going: &mut dyn FnMut() -> bool,
) -> (PolyMesh, usize) {
    let (simplified, kept) = simplify_mapped(mesh, max_edge, keep_going);
    (simplified, mesh.positions().len() - kept.len())
}

/// [`simplify`], returning with the mesh, per vertex of it, the vertex of `mesh` it is (in
/// `mesh`'s order; every vertex of `mesh` when none was removed).
pub fn simplify_mapped(
    mesh: &PolyMesh,
    max_edge: f64,
    keep_going: &mut dyn FnMut() -> bool,
) -> (PolyMesh, Vec<usize>) {
    let pos = mesh.positions();
    let mut tris: Vec<[usize; 3]> = mesh
        .faces()
        .iter()
        .flat_map(|f| (1..f.len() - 1).map(move |k| [f[0], f[k], f[k + 1]]))
        .collect();
    let mut alive = vec![true; tris.len()];
    let n = pos.len();
    let mut around: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (t, tri) in tris.iter().enumerate() {
        tri.iter().for_each(|&v| around[v].push(t));
    }
    // Vertices on the boundary (an edge of one triangle) stay, and so do those on the
    // creases that part the surface into sheets (`crease`: the remesh splits it there, and
    // a crease fading out towards a groin vault's crown is carried on along the input's
    // edges, which must stay for it to be found again).
    let topology = Topology::new(mesh).expect("a PolyMesh is manifold by construction");
    let mut fixed: Vec<bool> = (0..n).map(|v| topology.is_boundary_vertex(v)).collect();
    if let Some(sheets) = super::crease::split_at_creases(mesh) {
        for &v in sheets.seams.iter().flatten() {
            fixed[sheets.source[v]] = true;
        }
    }
    // Quadrics: the planes of each vertex's triangles, weighted by area.
    let mut quadric = vec![Matrix4::<f64>::zeros(); n];
    for tri in &tris {
        let [a, b, c] = tri.map(|v| pos[v]);
        let cross = (b - a).cross(&(c - a));
        let area = cross.norm() / 2.0;
        let Some(normal) = cross.try_normalize(1e-300) else {
            continue;
        };
        let plane = Vector4::new(normal.x, normal.y, normal.z, -normal.dot(&a.coords));
        let q = plane * plane.transpose() * area;
        tri.iter().for_each(|&v| quadric[v] += q);
    }
    let mut removed = vec![false; n];
    let cost = |q: &[Matrix4<f64>], v: usize, w: usize| {
        let p = pos[w].to_homogeneous();
        (p.transpose() * (q[v] + q[w]) * p)[(0, 0)].max(0.0)
    };
    // The neighbours `v` may collapse onto (within `max_edge`), cheapest first.
    let targets = |around: &[Vec<usize>],
                   tris: &[[usize; 3]],
                   alive: &[bool],
                   quadric: &[Matrix4<f64>],
                   v: usize| {
        let mut out: Vec<(u64, usize)> = around[v]
            .iter()
            .filter(|&&t| alive[t])
            .flat_map(|&t| tris[t])
            .filter(|&u| u != v && (pos[v] - pos[u]).norm() <= max_edge)
            .map(|u| (cost(quadric, v, u).to_bits(), u))
            .collect();
        out.sort_unstable();
        out.dedup();
        out
    };
    // One entry per vertex that may go, keyed by its cheapest collapse. A vertex whose
    // neighbourhood changed is marked, and its entry, when it comes up, is put back with its
    // new cost before it is collapsed: the heap never holds more than one entry per vertex.
    let mut heap: BinaryHeap<Reverse<(u64, usize)>> = BinaryHeap::new();
    for v in (0..n).filter(|&v| !fixed[v]) {
        if let Some(&(c, _)) = targets(&around, &tris, &alive, &quadric, v).first() {
            heap.push(Reverse((c, v)));
        }
    }
    let mut changed = vec![false; n];
    let mut asked = 0;
    while let Some(Reverse((_, v))) = heap.pop() {
        asked += 1;
        if asked % POLL_EVERY == 0 && !keep_going() {
            break;
        }
        if removed[v] {
            continue;
        }
        if changed[v] {
            changed[v] = false;
            if let Some(&(c, _)) = targets(&around, &tris, &alive, &quadric, v).first() {
                heap.push(Reverse((c, v)));
            }
            continue;
        }
        let found = targets(&around, &tris, &alive, &quadric, v)
            .into_iter()
            .find_map(|(_, w)| {
                collapsible(pos, &tris, &alive, &around, v, w, max_edge).map(|m| (w, m))
            });
        let Some((w, moved)) = found else {
            continue;
        };
        // Collapse v onto w: triangles on the edge vanish, the others take w for v; the
        // lists of the vertices around keep live triangles only.
        let on_edge: Vec<usize> = around[v]
            .iter()
            .copied()
            .filter(|&t| alive[t] && tris[t].contains(&w))
            .collect();
        for &t in &on_edge {
            alive[t] = false;
        }
        for &t in &moved {
            tris[t] = tris[t].map(|u| if u == v { w } else { u });
            around[w].push(t);
        }
        for &u in on_edge.iter().flat_map(|&t| &tris[t]) {
            around[u].retain(|&t| alive[t]);
        }
        around[v].clear();
        removed[v] = true;
        let qv = quadric[v];
        quadric[w] += qv;
        let mut touched: Vec<usize> = around[w]
            .iter()
            .filter(|&&t| alive[t])
            .flat_map(|&t| tris[t])
            .collect();
        touched.sort_unstable();
        touched.dedup();
        for u in touched.into_iter().filter(|&u| !fixed[u]) {
            changed[u] = true;
        }
    }
    // Keep the vertices left, in order, and the triangles.
    let mut index = vec![usize::MAX; n];
    let kept: Vec<usize> = (0..n).filter(|&v| !removed[v]).collect();
    for (k, &v) in kept.iter().enumerate() {
        index[v] = k;
    }
    let faces: Vec<Vec<usize>> = tris
        .iter()
        .zip(&alive)
        .filter(|&(_, &a)| a)
        .map(|(t, _)| t.iter().map(|&v| index[v]).collect())
        .collect();
    // Each collapse keeps a manifold mesh of valid faces; should one not, the input stays.
    match PolyMesh::new(kept.iter().map(|&v| pos[v]).collect(), faces) {
        Ok(simplified) => (simplified, kept),
        Err(_) => (mesh.clone(), (0..n).collect()),
    }
}

/// The triangles around `v` that a collapse of `v` onto `w` would move (those without `w`),
/// or `None` where it may not be made: an edge longer than `max_edge` would result, a moved
/// triangle would turn by more than 30 degrees or become a sliver, or the mesh would stop
/// being a manifold of the same topology (the link condition: `v` and `w` share exactly
/// the neighbours of the two triangles on their edge).
fn collapsible(
    pos: &[Point3<f64>],
    tris: &[[usize; 3]],
    alive: &[bool],
    around: &[Vec<usize>],
    v: usize,
    w: usize,
    max_edge: f64,
) -> Option<Vec<usize>> {
    let live = |x: usize| around[x].iter().copied().filter(|&t| alive[t]);
    let on_edge: Vec<usize> = live(v).filter(|&t| tris[t].contains(&w)).collect();
    if on_edge.len() != 2 {
        return None;
    }
    let ring = |x: usize| {
        let mut r: Vec<usize> = live(x).flat_map(|t| tris[t]).filter(|&u| u != x).collect();
        r.sort_unstable();
        r.dedup();
        r
    };
    let (rv, rw) = (ring(v), ring(w));
    let shared = rv.iter().filter(|u| rw.binary_search(u).is_ok()).count();
    if shared != 2 {
        return None;
    }
    let moved: Vec<usize> = live(v).filter(|t| !on_edge.contains(t)).collect();
    for &t in &moved {
        let before = tris[t].map(|u| pos[u]);
        let after = tris[t].map(|u| if u == v { pos[w] } else { pos[u] });
        let normal = |[a, b, c]: [Point3<f64>; 3]| -> Vector3<f64> { (b - a).cross(&(c - a)) };
        let (n0, n1) = (normal(before), normal(after));
        let longest = (0..3)
            .map(|k| (after[(k + 1) % 3] - after[k]).norm())
            .fold(0.0, f64::max);
        if longest > max_edge
            || n1.norm() / 2.0 < MIN_SHAPE * longest * longest
            || n0.dot(&n1) < MAX_TURN_COS * n0.norm() * n1.norm()
        {
            return None;
        }
    }
    Some(moved)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generate;

    /// A shell of fine triangles: the paper's corner-supported shell at `edge`.
    fn fine(edge: f64) -> PolyMesh {
        generate::triangulate_quads(&generate::corner_supported_shell(3.0, edge))
    }

    #[test]
    fn a_fine_shell_keeps_its_shape_boundary_and_topology_with_far_fewer_vertices() {
        let mesh = fine(0.02);
        let (out, removed) = simplify(&mesh, 0.08, &mut || true);
        assert_eq!(out.positions().len() + removed, mesh.positions().len());
        // Edges of up to 4 input edges (2.8 diagonals): a quarter of the vertices are left
        // (6327 of 24649).
        assert!(
            out.positions().len() * 3 < mesh.positions().len(),
            "{} of {}",
            out.positions().len(),
            mesh.positions().len()
        );
        // Area and boundary length as the input's, to a fraction of a per cent.
        let (a0, a1) = (mesh.area(), out.area());
        assert!((a0 - a1).abs() < 2e-3 * a0, "{a0} {a1}");
        let boundary = |m: &PolyMesh| {
            let topology = Topology::new(m).unwrap();
            topology
                .edges()
                .iter()
                .filter(|e| e.faces.len() == 1)
                .map(|e| (m.positions()[e.vertices[0]] - m.positions()[e.vertices[1]]).norm())
                .sum::<f64>()
        };
        assert!((boundary(&mesh) - boundary(&out)).abs() < 1e-9);
        // Still a disk: V - E + F = 1, and every edge at most the limit.
        let topology = Topology::new(&out).unwrap();
        let p = out.positions();
        let euler = p.len() as i64 - topology.edges().len() as i64 + out.face_count() as i64;
        assert_eq!(euler, 1);
        for e in topology.edges() {
            assert!((p[e.vertices[0]] - p[e.vertices[1]]).norm() <= 0.08 + 1e-12);
        }
        // Every vertex kept is an input vertex, in the input's order.
        let mut at = 0;
        for q in p {
            at += mesh.positions()[at..].iter().position(|r| r == q).unwrap();
        }
        // Deterministic.
        let (again, _) = simplify(&mesh, 0.08, &mut || true);
        assert_eq!(again.positions(), out.positions());
        assert_eq!(again.faces(), out.faces());
    }

    #[test]
    fn a_mesh_already_as_coarse_as_the_limit_is_left_alone() {
        let mesh = fine(0.1);
        let (out, removed) = simplify(&mesh, 0.1, &mut || true);
        assert_eq!(removed, 0);
        assert_eq!(out.positions(), mesh.positions());
    }

    #[test]
    fn a_groin_vaults_creases_stay_where_they_were() {
        // Two barrels of radius 2 crossing, the lower one kept: creases along the
        // diagonals, on mesh edges; 10 mm cells (at 20 mm the creases near the crown were
        // found again from the larger turns alone).
        let groin = generate::diagonal_grid(400, 2.0, |x, y| {
            (4.0 - x * x).sqrt().min((4.0 - y * y).sqrt())
        });
        let (out, removed) = simplify(&groin, 0.145, &mut || true);
        // 149,059 of 160,801 vertices go.
        assert!(removed * 5 > groin.positions().len() * 4, "{removed}");
        let sheets = |m: &PolyMesh| crate::mesh::crease::split_at_creases(m).map_or(1, |s| s.count);
        assert_eq!(sheets(&groin), 4);
        assert_eq!(sheets(&out), 4);
        // Every crease vertex of the input is kept: those on the diagonals, up to the crown
        // (where the webs meet level and the creases are carried on).
        let on_diagonal = |p: &Point3<f64>| (p.x.abs() - p.y.abs()).abs() < 1e-12;
        let count = |m: &PolyMesh| m.positions().iter().filter(|p| on_diagonal(p)).count();
        assert_eq!(count(&out), count(&groin));
    }

    #[test]
    fn a_stop_ends_the_collapses_with_a_valid_mesh() {
        let mesh = fine(0.02);
        let mut asked = 0;
        let (out, removed) = simplify(&mesh, 0.08, &mut || {
            asked += 1;
            asked < 2
        });
        assert_eq!(asked, 2);
        assert!(
            removed > 0 && removed < mesh.positions().len() / 2,
            "{removed}"
        );
        assert_eq!(out.positions().len() + removed, mesh.positions().len());
        Topology::new(&out).unwrap();
    }
}
