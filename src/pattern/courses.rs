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
//! irregular vertex of odd valence the propagation meets itself with the classes swapped;
//! edges where the two faces disagree are neither (no tile across them), so courses end
//! there, as they do at a mason's dislocation. Of the two ways to label each connected
//! region, the one whose head edges climb most (run along the surface's slope with respect
//! to `up`) is chosen: courses then lie level, the way a vault is built up from its supports.

use std::collections::VecDeque;

use nalgebra::Vector3;

use super::PatternError;
use crate::mesh::{PolyMesh, Topology};

/// Which way tiles may lie.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
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
    // Per quad: which of its corners' parity starts a head edge (edges 0 and 2, or 1 and 3).
    let mut parity: Vec<Option<usize>> = vec![None; faces];
    let mut disagree = vec![false; topology.edges().len()];
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
                if !mesh.is_quad(g) {
                    continue;
                }
                // The edge's class in f, carried over to g.
                let head = i % 2 == pf;
                let j = corner(g, e);
                let want = if head { j % 2 } else { 1 - j % 2 };
                match parity[g] {
                    None => {
                        parity[g] = Some(want);
                        region.push(g);
                        queue.push_back(g);
                    }
                    Some(p) if p != want => disagree[e] = true,
                    Some(_) => {}
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
            [f, g] if !disagree[e] => match (parity[f], parity[g]) {
                (Some(pf), Some(pg)) => corner(f, e) % 2 == pf && corner(g, e) % 2 == pg,
                _ => false,
            },
            _ => false,
        })
        .collect())
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
