//! How much of the input surface the tiles cover: the share of the surface's area that lies
//! under a tile's kept face or within half a joint of it.
//!
//! Measured by sampling: every face of the surface contributes its centroid with its area as
//! weight (input surfaces are fine triangle meshes, with faces much smaller than a tile). A
//! sample is covered when, seen in some nearby tile's frame, it lies within the tile's face
//! grown by half a joint, inside the kept outline of a cut tile (or within half a joint of
//! it), and not further from the tile's plane than half the tile's width.

use std::collections::HashMap;

use nalgebra::Point3;

use crate::mesh::PolyMesh;
use crate::tiles::Tile;
use crate::tiles::clip::Point2;

/// Share of `surface`'s area covered by `tiles` with their joints, in `[0, 1]`.
pub fn covered_share(surface: &PolyMesh, tiles: &[Tile], joint: f64) -> f64 {
    let Some(reach) = tiles.iter().map(|t| t.size[0].hypot(t.size[1]) / 2.0 + joint).reduce(f64::max) else { return 0.0 };
    let cell_of = |p: &Point3<f64>| [p.x, p.y, p.z].map(|c| (c / reach).floor() as i64);
    let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    for (t, tile) in tiles.iter().enumerate() {
        grid.entry(cell_of(&tile.frame.origin)).or_default().push(t);
    }
    let (mut covered, mut total) = (0.0, 0.0);
    for f in 0..surface.face_count() {
        let area = surface.face_area_vector(f).norm();
        let p = surface.face_centroid(f);
        let c = cell_of(&p);
        let near = (-1..=1).flat_map(|x| (-1..=1).flat_map(move |y| (-1..=1).map(move |z| [c[0] + x, c[1] + y, c[2] + z])));
        let hit = near.filter_map(|k| grid.get(&k)).flatten().any(|&t| under(&tiles[t], &p, joint / 2.0));
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
    tile.cut.as_ref().is_none_or(|cut| winding(&cut.loops, q) != 0 || cut.loops.iter().any(|l| near_loop(l, q, margin)))
}

/// Winding number of `loops` around `q` (holes count against their outer loop).
fn winding(loops: &[Vec<Point2>], q: Point2) -> i32 {
    let mut w = 0;
    for l in loops {
        for i in 0..l.len() {
            let (a, b) = (l[i], l[(i + 1) % l.len()]);
            let side = (b[0] - a[0]) * (q[1] - a[1]) - (b[1] - a[1]) * (q[0] - a[0]);
            if a[1] <= q[1] && b[1] > q[1] && side > 0.0 {
                w += 1;
            } else if a[1] > q[1] && b[1] <= q[1] && side < 0.0 {
                w -= 1;
            }
        }
    }
    w
}

/// Whether `q` lies within `margin` of the loop's edges.
fn near_loop(l: &[Point2], q: Point2, margin: f64) -> bool {
    (0..l.len()).any(|i| {
        let (a, b) = (l[i], l[(i + 1) % l.len()]);
        let d = [b[0] - a[0], b[1] - a[1]];
        let len2 = d[0] * d[0] + d[1] * d[1];
        let t = if len2 > 0.0 { (((q[0] - a[0]) * d[0] + (q[1] - a[1]) * d[1]) / len2).clamp(0.0, 1.0) } else { 0.0 };
        (q[0] - a[0] - t * d[0]).hypot(q[1] - a[1] - t * d[1]) <= margin
    })
}
