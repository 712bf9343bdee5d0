//! How much of the input surface the tiles cover: the share of the surface's area that lies
//! under a tile's kept face or within half a joint of it.
//!
//! Measured by sampling: every face of the surface is cut into triangles no longer than
//! [`SAMPLES_PER_TILE_SIDE`] samples across the smallest tile side, each contributing its
//! centroid with its area as weight. A coarse input (a 7-triangle pyramid, a box of six
//! faces, Rhino's default render mesh) is then measured as finely as a fine one; one sample
//! per face made the share a coin toss of a few centroids (0.571 for a pyramid of seven
//! triangles that its tiles cover to 0.9). A sample is covered when, seen in some nearby
//! tile's frame, it lies within the tile's face grown by half a joint, inside the kept
//! outline of a cut tile (or within half a joint of it), and not further from the tile's
//! plane than half the tile's width.

use nalgebra::Point3;

use crate::geom::HashGrid;
use crate::geom::polygon::{Point2, point_segment, winding};
use crate::mesh::PolyMesh;
use crate::tiles::Tile;

/// Samples across the smallest tile side: the sampling triangles' longest edges are at most
/// that side over this (70 mm for a 280 x 140 mm tile), finer than any gap worth seeing.
const SAMPLES_PER_TILE_SIDE: f64 = 2.0;

/// Share of `surface`'s area covered by `tiles` with their joints, in `[0, 1]`.
pub fn covered_share(surface: &PolyMesh, tiles: &[Tile], joint: f64) -> f64 {
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
    let spacing = side / SAMPLES_PER_TILE_SIDE;
    let grid = HashGrid::of_points(reach, tiles.iter().map(|t| [t.frame.origin]));
    let (mut covered, mut total) = (0.0, 0.0);
    let p = surface.positions();
    for face in surface.faces() {
        // The tiles near any point of the face, found once; the last tile hit is tried first
        // (neighbouring samples mostly lie under the same tile).
        let radius = face
            .iter()
            .map(|&v| (p[v] - p[face[0]]).norm())
            .fold(0.0, f64::max);
        let near = grid.near(&p[face[0]], reach + radius);
        let mut last = 0;
        for k in 1..face.len().saturating_sub(1) {
            let corners = [p[face[0]], p[face[k]], p[face[k + 1]]];
            for_each_sample(&corners, spacing, |q, area| {
                let hit = near
                    .get(last)
                    .is_some_and(|&t| under(&tiles[t], &q, joint / 2.0))
                    || near
                        .iter()
                        .position(|&t| under(&tiles[t], &q, joint / 2.0))
                        .is_some_and(|i| {
                            last = i;
                            true
                        });
                total += area;
                covered += if hit { area } else { 0.0 };
            });
        }
    }
    if total > 0.0 { covered / total } else { 0.0 }
}

/// Most sampling triangles along one edge of a face: a face is cut into at most this
/// squared samples (a 100 m face at a 70 mm spacing still reads in well under a second).
const MAX_SPLITS: usize = 1024;

/// Calls `visit` with the centroid and area of each of the `k * k` triangles of the regular
/// subdivision of triangle `t`, `k` the least number of splits per edge that keeps every
/// edge at most `spacing` long.
fn for_each_sample(t: &[Point3<f64>; 3], spacing: f64, mut visit: impl FnMut(Point3<f64>, f64)) {
    let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
    let area = e1.cross(&e2).norm() / 2.0;
    let longest = e1.norm().max(e2.norm()).max((t[2] - t[1]).norm());
    let k = if spacing > 0.0 && longest > spacing {
        ((longest / spacing).ceil() as usize).min(MAX_SPLITS)
    } else {
        1
    };
    let (kf, piece) = (k as f64, area / (k * k) as f64);
    for i in 0..k {
        for j in 0..k - i {
            // The triangle pointing the way of `t`, and the one turned over beside it.
            let (u, v) = ((i as f64 + 1.0 / 3.0) / kf, (j as f64 + 1.0 / 3.0) / kf);
            visit(t[0] + e1 * u + e2 * v, piece);
            if i + j + 1 < k {
                let (u, v) = ((i as f64 + 2.0 / 3.0) / kf, (j as f64 + 2.0 / 3.0) / kf);
                visit(t[0] + e1 * u + e2 * v, piece);
            }
        }
    }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tiles::{Frame, TileKind};
    use nalgebra::Vector3;

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
    fn samples_tile_a_triangle_with_its_area() {
        let t = [
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(0.3, 0.8, 0.0),
        ];
        let (mut count, mut area, mut centre) = (0, 0.0, Vector3::zeros());
        // The longest edge is 1.063: 10 splits of at most 0.11 each.
        for_each_sample(&t, 0.11, |q, a| {
            count += 1;
            area += a;
            centre += q.coords * a;
        });
        assert_eq!(count, 100);
        assert!((area - 0.4).abs() < 1e-12);
        // The samples' weighted mean is the triangle's centroid.
        assert!((centre / area - Vector3::new(1.3 / 3.0, 0.8 / 3.0, 0.0)).norm() < 1e-12);
    }

    #[test]
    fn a_coarse_face_is_measured_by_area_not_by_its_centroid() {
        // Two triangles of 1.4 m; one row of 5 tiles (with joints) along the bottom covers
        // 0.15 x 1.4 of the square, about 0.107 of it. Neither triangle's centroid lies under
        // a tile, so sampling centroids only read 0.
        let tiles: Vec<Tile> = (0..5).map(|i| tile(0.14 + 0.29 * i as f64, 0.07)).collect();
        let share = covered_share(&square(1.4), &tiles, 0.01);
        assert!((share - 0.15 * 1.4 / 1.96).abs() < 0.02, "{share}");
    }
}
