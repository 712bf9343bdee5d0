//! How much of the input surface the tiles cover: the share of the surface's area that lies
//! under a tile's kept face or within half a joint of it.
//!
//! Measured by sampling: every face of the surface is cut into triangles no longer than
//! [`sample::SAMPLES_PER_TILE_SIDE`] samples across the smallest tile side, each contributing its
//! centroid with its area as weight. A coarse input (a 7-triangle pyramid, a box of six
//! faces, Rhino's default render mesh) is then measured as finely as a fine one; one sample
//! per face made the share a coin toss of a few centroids (0.571 for a pyramid of seven
//! triangles that its tiles cover to 0.9). A sample is covered when, seen in some nearby
//! tile's frame, it lies within the tile's face grown by half a joint, inside the kept
//! outline of a cut tile (or within half a joint of it), and not further from the tile's
//! plane than half the tile's width.

use crate::geom::{HashGrid, sample};
use crate::mesh::PolyMesh;
use crate::tiles::outline::covers;
use crate::tiles::{ExcludedArea, Tile};

/// Share of `surface`'s area covered by `tiles` with their joints, in `[0, 1]`, the area
/// over the `excluded` quads (openings, areas laid by hand) left out of both.
pub fn covered_share(
    surface: &PolyMesh,
    tiles: &[Tile],
    joint: f64,
    excluded: Option<&ExcludedArea>,
) -> f64 {
    let Some(reach) = tiles
        .iter()
        .map(|t| t.size[0].hypot(t.size[1]) / 2.0 + joint)
        .reduce(f64::max)
    else {
        return 0.0;
    };
    let side = tiles
        .iter()
        .map(|t| t.size[0].min(t.size[1]))
        .fold(f64::INFINITY, f64::min);
    let spacing = side / sample::SAMPLES_PER_TILE_SIDE;
    let grid = HashGrid::of_points(reach, tiles.iter().map(|t| [t.frame.origin]));
    let p = surface.positions();
    let faces = surface.faces();
    // Per face (each on its own, so on the threads of `parallel`), its samples' areas and
    // whether a tile covers each; summed below in face and sample order.
    let samples = crate::parallel::map(faces.len(), |f| {
        let face = &faces[f];
        // The tiles near any point of the face, found once; the last tile hit is tried first
        // (neighbouring samples mostly lie under the same tile).
        let radius = face
            .iter()
            .map(|&v| (p[v] - p[face[0]]).norm())
            .fold(0.0, f64::max);
        let near = grid.near(&p[face[0]], reach + radius);
        let mut last = 0;
        let mut found = Vec::new();
        sample::face(p, face, spacing, |q, area| {
            if excluded.is_some_and(|e| e.contains(&q)) {
                return;
            }
            let hit = near
                .get(last)
                .is_some_and(|&t| covers(&tiles[t], &q, joint / 2.0))
                || near
                    .iter()
                    .position(|&t| covers(&tiles[t], &q, joint / 2.0))
                    .is_some_and(|i| {
                        last = i;
                        true
                    });
            found.push((area, hit));
        });
        found
    });
    let (mut covered, mut total) = (0.0, 0.0);
    for &(area, hit) in samples.iter().flatten() {
        total += area;
        covered += if hit { area } else { 0.0 };
    }
    if total > 0.0 { covered / total } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tiles::{Frame, TileKind};
    use nalgebra::{Point3, Vector3};

    /// A square of side `side` in the plane z = 0 as two triangles.
    fn square(side: f64) -> PolyMesh {
        let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
        PolyMesh::new(
            vec![p(0.0, 0.0), p(side, 0.0), p(side, side), p(0.0, side)],
            vec![vec![0, 1, 2], vec![0, 2, 3]],
        )
        .unwrap()
    }

    fn tile(x: f64, y: f64) -> Tile {
        let frame = Frame {
            origin: Point3::new(x, y, 0.0),
            x: Vector3::x(),
            y: Vector3::y(),
            z: Vector3::z(),
        };
        Tile::new(TileKind::Full, vec![], frame, [0.28, 0.14, 0.015])
    }

    #[test]
    fn a_coarse_face_is_measured_by_area_not_by_its_centroid() {
        // Two triangles of 1.4 m; one row of 5 tiles (with joints) along the bottom covers
        // 0.15 x 1.4 of the square, about 0.107 of it. Neither triangle's centroid lies under
        // a tile, so sampling centroids only read 0.
        let tiles: Vec<Tile> = (0..5).map(|i| tile(0.14 + 0.29 * i as f64, 0.07)).collect();
        let share = covered_share(&square(1.4), &tiles, 0.01, None);
        assert!((share - 0.15 * 1.4 / 1.96).abs() < 0.02, "{share}");
    }
}
