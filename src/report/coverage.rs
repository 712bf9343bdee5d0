//! How much of the input surface the tiles cover: the share of the surface's area that lies
//! under a tile's kept face or within half a joint of it.
//!
//! Measured by sampling: every face of the surface contributes its centroid with its area as
//! weight (input surfaces are fine triangle meshes, with faces much smaller than a tile). A
//! sample is covered when, seen in some nearby tile's frame, it lies within the tile's face
//! grown by half a joint, inside the kept outline of a cut tile (or within half a joint of
//! it), and not further from the tile's plane than half the tile's width.

use nalgebra::Point3;

use crate::geom::HashGrid;
use crate::geom::polygon::{Point2, point_segment, winding};
use crate::mesh::PolyMesh;
use crate::tiles::Tile;

/// Share of `surface`'s area covered by `tiles` with their joints, in `[0, 1]`.
pub fn covered_share(surface: &PolyMesh, tiles: &[Tile], joint: f64) -> f64 {
    let Some(reach) = tiles
        .iter()
        .map(|t| t.size[0].hypot(t.size[1]) / 2.0 + joint)
        .reduce(f64::max)
    else {
        return 0.0;
    };
    let grid = HashGrid::of_points(reach, tiles.iter().map(|t| [t.frame.origin]));
    let (mut covered, mut total) = (0.0, 0.0);
    for f in 0..surface.face_count() {
        let area = surface.face_area_vector(f).norm();
        let p = surface.face_centroid(f);
        let hit = grid
            .near(&p, reach)
            .into_iter()
            .any(|t| under(&tiles[t], &p, joint / 2.0));
        total += area;
        covered += if hit { area } else { 0.0 };
    }
    if total > 0.0 { covered / total } else { 0.0 }
}

/// Whether `p` lies under `tile`'s kept face grown by `margin`.
fn under(tile: &Tile, p: &Point3<f64>, margin: f64) -> bool {
    let local = tile.frame.to_local(p);
    let (hx, hy) = (tile.size[0] / 2.0, tile.size[1] / 2.0);
    if local.x.abs() > hx + margin || local.y.abs() > hy + margin || local.z.abs() > hy {
        return false;
    }
    let q = [local.x, local.y];
    tile.cut.as_ref().is_none_or(|cut| {
        winding(&cut.loops, q) != 0 || cut.loops.iter().any(|l| near_loop(l, q, margin))
    })
}

/// Whether `q` lies within `margin` of the loop's edges.
fn near_loop(l: &[Point2], q: Point2, margin: f64) -> bool {
    (0..l.len()).any(|i| point_segment(q, l[i], l[(i + 1) % l.len()]).0 <= margin)
}
