//! From extracted polygons to a pure, manifold quad mesh on the input surface.
//!
//! Instant Meshes' pure-quad mode subdivides everything once (Catmull-Clark-like), which
//! halves the edge and so is useless for tiles. Instead the few non-quads are repaired
//! locally at the target size:
//!
//! 1. holes left by extraction (cycles too long to be faces, away from the input boundary)
//!    become polygons ([`repair`]);
//! 2. adjacent triangle pairs merge into quads ([`repair`]);
//! 3. faces with an odd number of sides are paired along shortest dual paths (or led to the
//!    boundary) and the crossed edges split, which makes every face even (the classic parity
//!    argument: a polygon mesh can be quadrangulated without subdivision everywhere exactly
//!    when each component has an even number of odd faces, and a boundary edge split fixes
//!    the parity otherwise) ([`repair`]);
//! 4. even polygons are cut into quads by their best diagonals ([`repair`]);
//! 5. the boundary is fitted to the input's ([`super::fit`]): rows are extended over gaps
//!    to the input boundary, boundary vertices snapped onto it (input corners onto corners),
//!    all others onto the surface, with a few rounds of tangential smoothing; faces that
//!    still leave the surface are pulled back, peeled and re-extended ([`peel`]), halved
//!    along their quad strip, or (on the rim) dropped ([`trim`]); edges are rotated and quads
//!    collapsed across a diagonal where that makes vertices regular, and doublets merged
//!    ([`valence`]).
//!
//! Throughout, the face list is kept a manifold mesh ([`manifold`]).

mod manifold;
mod peel;
mod repair;
mod trim;
mod valence;

use nalgebra::Point3;

use super::RemeshError;
use super::anchors::Anchors;
use super::budget::Budget;
use super::extract::Raw;
use super::fit;
use super::quadmesh::compact;
use super::surface::Locator;
use manifold::{distinct, drop_small_components, make_edge_manifold, split_pinched_vertices};
use repair::{fill_holes, make_quads};
use trim::{FINAL, SPLIT_ROUNDS, drop_rim_slivers, drop_unfit_rim_faces, split_unfit_faces};
use valence::{collapse_diagonals, remove_doublets, rotate_edges};

/// A quad mesh in progress.
#[derive(Debug, Clone)]
pub(crate) struct Quads {
    /// Vertex positions.
    pub positions: Vec<Point3<f64>>,
    /// Faces (all quads unless repair failed somewhere).
    pub faces: Vec<Vec<usize>>,
}

/// Runs the repair steps listed in the module documentation.
///
/// The topology repair must finish (a stop there is an error); the fitting rounds after it
/// only improve a valid mesh, so when the time limit passes during them the mesh as it is
/// comes back.
pub(crate) fn pure_quads(
    raw: Raw,
    locator: &Locator,
    t: f64,
    budget: &mut Budget,
) -> Result<Quads, RemeshError> {
    let mut pos = raw.positions;
    let mut faces: Vec<Vec<usize>> = raw.faces.into_iter().filter(|f| distinct(f)).collect();
    make_edge_manifold(&mut faces);
    drop_small_components(&mut faces);
    fill_holes(&pos, &mut faces, locator, t);
    make_edge_manifold(&mut faces);
    make_quads(&mut pos, &mut faces, budget);
    budget.check()?;
    let (mut pos, mut faces) = compact(pos, faces);
    peel::snap_and_peel(&mut pos, &mut faces, locator, t, budget)?;
    rotate_edges(&pos, &mut faces);
    collapse_diagonals(&mut pos, &mut faces, |p| locator.closest(p).0);
    rotate_edges(&pos, &mut faces);
    remove_doublets(&mut faces);
    for _ in 0..SPLIT_ROUNDS {
        if !split_unfit_faces(&mut pos, &mut faces, locator, t) {
            break;
        }
    }
    let anchors = Anchors::new(&mut pos, &faces, locator, t);
    fit::shorten_boundary_chords(&mut pos, &faces, &anchors, locator, FINAL * t);
    drop_unfit_rim_faces(&mut pos, &mut faces, locator, t);
    drop_rim_slivers(&pos, &mut faces, locator, t);
    // No step above should leave a face twice; should one, the mesh still holds.
    make_edge_manifold(&mut faces);
    split_pinched_vertices(&mut pos, &mut faces);
    let (pos, faces) = compact(pos, faces);
    if faces.is_empty() {
        return Err(RemeshError::NothingExtracted(t));
    }
    Ok(Quads {
        positions: pos.into_iter().map(Point3::from).collect(),
        faces,
    })
}
