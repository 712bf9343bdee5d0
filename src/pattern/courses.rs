//! Courses: tiles laid in rows, all one way, as masons lay a vault.
//!
//! The paper's programs (eqs. 1-3) let a tile lie either way across any quad. The optimum
//! of the staggered bond then often turns tiles by a quarter turn from one region to the
//! next (pinwheels; paper Figure 5). That only fits where a tile's length plus a joint is
//! twice its width plus a joint; for common tiles (280 x 140 with a 10 mm joint: 290 against
//! 300) every course of turned tiles adds 5 mm of misfit, which no placement can take up
//! (the fit stage, [`crate::tiles::fit`]). In courses every tile runs the same way: the
//! quads' edges fall into two classes, *head* edges (a tile spans across them, along its
//! course) and *bed* edges (between courses), and tiles are only allowed across head edges.
//!
//! The classes are propagated face to face: the two edges of a quad that are opposite each
//! other belong to one class, and an edge has the same class in both its faces. Around an
//! irregular vertex of odd valence the propagation meets itself with the classes swapped:
//! some seam of edges where the two faces disagree must run from it to the boundary or to
//! another odd vertex. Edges on the seam are neither class (no tile across them), so
//! courses end there, as they do at a mason's dislocation. The seams are laid first, as
//! short as they can be ([`seams`]: each odd vertex joined by a shortest path to the
//! boundary or to another odd vertex), and the propagation does not cross them; left to
//! itself it would put the seam wherever its fronts happen to meet, tens of edges long
//! across a shell with a single odd vertex beside its edge, and every course crossing it
//! would end there in a half tile or a continuous joint. Of the two ways to label each connected
//! region, the one whose head edges climb most (run along the surface's slope with respect
//! to `up`) is chosen: courses then lie level, the way a vault is built up from its supports.

use std::collections::VecDeque;

use nalgebra::Vector3;

use super::PatternError;
use crate::mesh::{PolyMesh, Topology};

/// Which way tiles may lie.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[non_exhaustive]
pub enum Courses {
    /// Either way across any quad (the paper's eqs. 1-3).
    #[default]
    Free,
    /// All along courses that lie level with respect to `up`: tiles only across head
    /// edges (see the module documentation).
    Level {
        /// The up direction (gravity points the other way).
        up: [f64; 3],
    },
}

/// The mesh edges a tile may lie across when tiles run in level courses: per edge of
/// `topology`, whether it is a head edge in both its faces.
///
/// # Errors
/// [`PatternError::InvalidUp`] when `up` is not a finite non-zero direction.
pub(crate) fn middle_edges(
    mesh: &PolyMesh,
    topology: &Topology,
    up: [f64; 3],
) -> Result<Vec<bool>, PatternError> {
    let up = Vector3::from(up);
    if !(up.iter().all(|c| c.is_finite()) && up.norm() > 0.0) {
        return Err(PatternError::InvalidUp { up: up.into() });
    }
    let up = up.normalize();
    let faces = mesh.face_count();
    let seam = seams(mesh, topology);
    // Per quad: which of its corners' parity starts a head edge (edges 0 and 2, or 1 and 3).
    let mut parity: Vec<Option<usize>> = vec![None; faces];
    let corner = |f: usize, e: usize| {
        topology
            .face_edges(f)
            .iter()
            .position(|&x| x == e)
            .expect("the face has the edge")
    };
    for start in 0..faces {
        if parity[start].is_some() || !mesh.is_quad(start) {
            continue;
        }
        parity[start] = Some(0);
        let mut region = vec![start];
        let mut queue = VecDeque::from([start]);
        while let Some(f) = queue.pop_front() {
            let pf = parity[f].expect("labelled before queued");
            for (i, &e) in topology.face_edges(f).iter().enumerate() {
                let Some(g) = topology.edges()[e].other_face(f) else {
                    continue;
                };
                if !mesh.is_quad(g) || seam[e] {
                    continue;
                }
                // The edge's class in f, carried over to g.
                let head = i % 2 == pf;
                let j = corner(g, e);
                let want = if head { j % 2 } else { 1 - j % 2 };
                // Labels that meet themselves swapped (around a hole, on a surface without
                // boundary) leave the edge in neither class: see the end.
                if parity[g].is_none() {
                    parity[g] = Some(want);
                    region.push(g);
                    queue.push_back(g);
                }
            }
        }
        // Level courses: head edges (along which a tile spans) should climb, bed edges lie
        // level. Flip the region's labels if the other way fits better.
        let mut climb = 0.0;
        for &f in &region {
            let p = parity[f].expect("labelled");
            let normal = mesh.face_area_vector(f).try_normalize(0.0).unwrap_or(up);
            let slope = up - normal * normal.dot(&up);
            let face = &mesh.faces()[f];
            for i in 0..4 {
                let along = mesh.positions()[face[(i + 1) % 4]] - mesh.positions()[face[i]];
                let rise = along.dot(&slope).abs();
                climb += if i % 2 == p { rise } else { -rise };
            }
        }
        if climb < 0.0 {
            for &f in &region {
                parity[f] = parity[f].map(|p| 1 - p);
            }
        }
    }
    Ok(topology
        .edges()
        .iter()
        .enumerate()
        .map(|(e, edge)| match edge.faces[..] {
            [f, g] => match (parity[f], parity[g]) {
                (Some(pf), Some(pg)) => corner(f, e) % 2 == pf && corner(g, e) % 2 == pg,
                _ => false,
            },
            _ => false,
        })
        .collect())
}

/// Per edge of `topology`: whether it lies on a seam, the edges the course labels may not be
/// carried across.
///
/// An interior vertex with an odd number of faces, all of them quads, swaps the labels of a
/// loop around it; so does any loop around an odd number of such vertices. Joining every odd
/// vertex to the boundary (or to a face that is not a quad, which the labels do not enter)
/// or to another odd vertex leaves no such loop. Greedily, in vertex order: a component of
/// seam edges holding an odd number of odd vertices and touching no boundary grows by a
/// shortest path (in edges, breadth first from all its vertices) to the nearest vertex on a
/// boundary, or in a component that touches one, or in another unbalanced component. A
/// mason's dislocation (a valence-3 and a valence-5 vertex side by side) becomes a seam of
/// one edge.
fn seams(mesh: &PolyMesh, topology: &Topology) -> Vec<bool> {
    let vertices = mesh.positions().len();
    let edges = topology.edges();
    let mut seam = vec![false; edges.len()];
    // A vertex on the boundary or on a face the labels do not enter.
    let sink: Vec<bool> = (0..vertices)
        .map(|v| {
            topology.is_boundary_vertex(v)
                || topology
                    .vertex_edges(v)
                    .iter()
                    .any(|&e| edges[e].faces.iter().any(|&f| !mesh.is_quad(f)))
        })
        .collect();
    let odd: Vec<bool> = (0..vertices)
        .map(|v| !sink[v] && topology.vertex_edges(v).len() % 2 == 1)
        .collect();
    // Components of seam edges: members, odd vertices held, and whether one is a sink.
    let mut component: Vec<usize> = (0..vertices).collect();
    let mut members: Vec<Vec<usize>> = (0..vertices).map(|v| vec![v]).collect();
    let mut odd_count: Vec<usize> = odd.iter().map(|&o| usize::from(o)).collect();
    let mut grounded = sink.clone();
    let unbalanced =
        |c: usize, odd_count: &[usize], grounded: &[bool]| odd_count[c] % 2 == 1 && !grounded[c];
    let mut reached = vec![usize::MAX; vertices];
    let mut via = vec![usize::MAX; vertices];
    for start in 0..vertices {
        let own = component[start];
        if !odd[start] || !unbalanced(own, &odd_count, &grounded) {
            continue;
        }
        // Breadth first from the whole component, to the nearest vertex that balances it.
        let mut queue: VecDeque<usize> = members[own].iter().copied().collect();
        for &v in &members[own] {
            reached[v] = start;
            via[v] = usize::MAX;
        }
        let mut target = None;
        while let Some(v) = queue.pop_front() {
            let c = component[v];
            if c != own && (grounded[c] || unbalanced(c, &odd_count, &grounded)) {
                target = Some(v);
                break;
            }
            for &e in topology.vertex_edges(v) {
                let [a, b] = edges[e].vertices;
                let w = if a == v { b } else { a };
                if reached[w] != start {
                    reached[w] = start;
                    via[w] = e;
                    queue.push_back(w);
                }
            }
        }
        // Only a surface without boundary can leave a component unbalanced; its labels then
        // meet themselves wherever the propagation's fronts do, as without seams.
        let Some(mut v) = target else { continue };
        let mut path = vec![v];
        while via[v] != usize::MAX {
            let e = via[v];
            seam[e] = true;
            let [a, b] = edges[e].vertices;
            v = if a == v { b } else { a };
            path.push(v);
        }
        for v in path {
            let (into, from) = (component[start], component[v]);
            if into == from {
                continue;
            }
            // Merge the smaller member list into the larger.
            let (keep, gone) = if members[into].len() >= members[from].len() {
                (into, from)
            } else {
                (from, into)
            };
            let moved = std::mem::take(&mut members[gone]);
            for &m in &moved {
                component[m] = keep;
            }
            members[keep].extend(moved);
            odd_count[keep] += odd_count[gone];
            grounded[keep] |= grounded[gone];
        }
    }
    seam
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generate;

    /// A grid of unit quads tilted up along `y`: courses must run along `x` (level).
    #[test]
    fn on_a_slope_courses_run_level() {
        let flat = generate::grid(4, 3);
        let tilted: Vec<nalgebra::Point3<f64>> = flat
            .positions()
            .iter()
            .map(|p| nalgebra::Point3::new(p.x, p.y, 0.5 * p.y))
            .collect();
        let mesh = PolyMesh::new(tilted, flat.faces().to_vec()).unwrap();
        let topology = Topology::new(&mesh).unwrap();
        let allowed = middle_edges(&mesh, &topology, [0.0, 0.0, 1.0]).unwrap();
        for (e, edge) in topology.edges().iter().enumerate() {
            let [a, b] = edge.vertices.map(|v| mesh.positions()[v]);
            let interior = edge.faces.len() == 2;
            // A tile across an edge parallel to y (a head edge) runs along x.
            let head = (a.x - b.x).abs() < 1e-12;
            assert_eq!(allowed[e], interior && head, "edge {e}: {a} - {b}");
        }
        // Up along x instead: courses turn with it.
        let allowed = middle_edges(&mesh, &topology, [1.0, 0.0, 0.0]).unwrap();
        assert!(topology.edges().iter().enumerate().all(|(e, edge)| {
            let [a, b] = edge.vertices.map(|v| mesh.positions()[v]);
            allowed[e] == (edge.faces.len() == 2 && (a.y - b.y).abs() < 1e-12)
        }));
    }

    /// Around a valence-3 vertex the classes cannot agree: some edge is left out, and every
    /// allowed edge is a head edge of both its faces.
    #[test]
    fn an_odd_vertex_ends_courses_without_contradiction() {
        // Three quads around a centre vertex (a hexagon split into three).
        let points: Vec<nalgebra::Point3<f64>> = (0..6)
            .map(|k| {
                let a = std::f64::consts::PI / 3.0 * k as f64;
                nalgebra::Point3::new(a.cos(), a.sin(), 0.0)
            })
            .chain([nalgebra::Point3::origin()])
            .collect();
        let faces = vec![vec![6, 0, 1, 2], vec![6, 2, 3, 4], vec![6, 4, 5, 0]];
        let mesh = PolyMesh::new(points, faces).unwrap();
        let topology = Topology::new(&mesh).unwrap();
        let allowed = middle_edges(&mesh, &topology, [0.0, 1.0, 0.0]).unwrap();
        let interior = topology
            .edges()
            .iter()
            .filter(|e| e.faces.len() == 2)
            .count();
        assert_eq!(interior, 3);
        assert!(allowed.iter().filter(|&&a| a).count() < interior);
    }

    /// A 12 x 12 grid tilted up along `y` with the quad whose lower left corner is `corner`
    /// collapsed across that corner's diagonal: inside the grid the quad's two other corners
    /// are left with three edges each (the odd vertices of a dislocation) and the merged
    /// corner with six; on its lower edge only the upper left corner is left odd.
    fn collapsed_grid(corner: [f64; 3]) -> PolyMesh {
        let flat = generate::grid(12, 12);
        let points: Vec<nalgebra::Point3<f64>> = flat
            .positions()
            .iter()
            .map(|p| nalgebra::Point3::new(p.x, p.y, 0.5 * p.y))
            .collect();
        let centre = flat
            .faces()
            .iter()
            .position(|f| flat.positions()[f[0]] == corner.into())
            .expect("a face at that corner");
        let [a, _, c, _] = [0, 1, 2, 3].map(|k| flat.faces()[centre][k]);
        let faces: Vec<Vec<usize>> = flat
            .faces()
            .iter()
            .enumerate()
            .filter(|&(f, _)| f != centre)
            .map(|(_, face)| face.iter().map(|&v| if v == c { a } else { v }).collect())
            .collect();
        PolyMesh::new(points, faces).unwrap()
    }

    /// The seam of a dislocation joins its two odd vertices (two edges through the merged
    /// corner), instead of running wherever the propagation's fronts meet; every other
    /// course stays whole.
    #[test]
    fn a_dislocation_gets_the_shortest_seam() {
        let mesh = collapsed_grid([6.0, 6.0, 0.0]);
        let topology = Topology::new(&mesh).unwrap();
        let odd: Vec<usize> = (0..mesh.positions().len())
            .filter(|&v| !topology.is_boundary_vertex(v) && topology.vertex_edges(v).len() % 2 == 1)
            .collect();
        assert_eq!(odd.len(), 2);
        let seam = seams(&mesh, &topology);
        let on_seam: Vec<usize> = (0..seam.len()).filter(|&e| seam[e]).collect();
        assert_eq!(on_seam.len(), 2, "seam edges {on_seam:?}");
        for v in odd {
            assert!(
                on_seam
                    .iter()
                    .any(|&e| topology.edges()[e].vertices.contains(&v))
            );
        }
        // The regular tilted grid has 11 x 12 head edges; the collapse removes the quad's
        // own and leaves the courses through it to end at the seam, no more.
        let allowed = middle_edges(&mesh, &topology, [0.0, 0.0, 1.0]).unwrap();
        let count = allowed.iter().filter(|&&a| a).count();
        assert!((124..=132).contains(&count), "{count} head edges allowed");
    }

    /// An odd vertex one edge inside the boundary is joined to it by one seam edge, and the
    /// courses elsewhere stay whole (left to the propagation the seam ran from it across
    /// the grid to where the fronts met).
    #[test]
    fn an_odd_vertex_beside_the_boundary_is_joined_to_it() {
        let mesh = collapsed_grid([5.0, 0.0, 0.0]);
        let topology = Topology::new(&mesh).unwrap();
        let seam = seams(&mesh, &topology);
        assert_eq!(seam.iter().filter(|&&s| s).count(), 1);
        let allowed = middle_edges(&mesh, &topology, [0.0, 0.0, 1.0]).unwrap();
        let count = allowed.iter().filter(|&&a| a).count();
        assert!((129..=132).contains(&count), "{count} head edges allowed");
    }

    /// A surface without boundary: the eight corners of a cube (three quads each) pair up
    /// with each other, one edge apart.
    #[test]
    fn the_odd_corners_of_a_closed_cube_pair_up() {
        let mesh = generate::closed_box(1.0, 1);
        let topology = Topology::new(&mesh).unwrap();
        let seam = seams(&mesh, &topology);
        assert_eq!(seam.iter().filter(|&&s| s).count(), 4);
        let mut ends: Vec<usize> = (0..seam.len())
            .filter(|&e| seam[e])
            .flat_map(|e| topology.edges()[e].vertices)
            .collect();
        ends.sort_unstable();
        assert_eq!(ends, (0..8).collect::<Vec<_>>());
        assert!(middle_edges(&mesh, &topology, [0.0, 0.0, 1.0]).is_ok());
    }

    #[test]
    fn a_bad_up_is_refused() {
        let mesh = generate::grid(2, 2);
        let topology = Topology::new(&mesh).unwrap();
        assert!(matches!(
            middle_edges(&mesh, &topology, [0.0, 0.0, 0.0]),
            Err(PatternError::InvalidUp { .. })
        ));
        assert!(matches!(
            middle_edges(&mesh, &topology, [f64::NAN, 0.0, 1.0]),
            Err(PatternError::InvalidUp { .. })
        ));
    }
}
