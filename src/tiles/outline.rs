//! The joint between two tiles, measured on their outlines: the one rule by which the fit
//! stage places tiles, the report judges joints and the overlap check finds overlaps.
//!
//! Both tiles as solids (the corners of the kept face at the bottom and at the top: for a
//! cut tile the hull of its kept loops) are projected onto their mean plane (the plane
//! through the midpoint of their origins, normal to the mean of their normals) and separated
//! by separating axes ([`crate::geom::polygon::separation`]): a positive value is the width
//! of the joint between them, a negative one how deep they overlap. On a concave surface the
//! tops of two tiles lean together, on a convex one the bottoms: either edge can close a
//! joint.

use nalgebra::{Point3, Vector3};

use super::Tile;
use crate::geom::polygon::{self, Point2};

/// The kept face of `tile` in its own frame, counter-clockwise: its rectangle, or the convex
/// hull of a cut tile's kept loops.
pub fn local_outline(tile: &Tile) -> Vec<Point2> {
    match &tile.cut {
        Some(cut) => polygon::convex_hull(&cut.loops.iter().flatten().copied().collect::<Vec<_>>()),
        None => {
            let (hx, hy) = (tile.size[0] / 2.0, tile.size[1] / 2.0);
            vec![[-hx, -hy], [hx, -hy], [hx, hy], [-hx, hy]]
        }
    }
}

/// The kept face of `tile` in world coordinates, counter-clockwise seen from its `z`.
pub fn world_outline(tile: &Tile) -> Vec<Point3<f64>> {
    local_outline(tile)
        .iter()
        .map(|p| tile.frame.origin + tile.frame.x * p[0] + tile.frame.y * p[1])
        .collect()
}

/// The corners of `tile` as a solid: its kept face ([`world_outline`]) at the bottom and
/// the same at the top, a thickness up.
pub fn world_corners(tile: &Tile) -> Vec<Point3<f64>> {
    let bottom = world_outline(tile);
    let up = tile.frame.z * tile.size[2];
    bottom
        .iter()
        .copied()
        .chain(bottom.iter().map(|p| p + up))
        .collect()
}

/// Whether the surface point `p` lies under `tile`'s kept face grown by `margin`: seen in the
/// tile's frame, within the face's rectangle grown by `margin`, inside the kept loops of a
/// cut tile (or within `margin` of them), and not further from the tile's plane than half
/// the tile's width (the surface a tile stands for, not one behind it).
pub fn covers(tile: &Tile, p: &Point3<f64>, margin: f64) -> bool {
    let local = tile.frame.to_local(p);
    let (hx, hy) = (tile.size[0] / 2.0, tile.size[1] / 2.0);
    if local.x.abs() > hx + margin || local.y.abs() > hy + margin || local.z.abs() > hy {
        return false;
    }
    let q = [local.x, local.y];
    tile.cut.as_ref().is_none_or(|cut| {
        polygon::winding(&cut.loops, q) != 0
            || cut.loops.iter().any(|l| {
                (0..l.len())
                    .any(|i| polygon::point_segment(q, l[i], l[(i + 1) % l.len()]).0 <= margin)
            })
    })
}

/// Whether tiles `a` and `b` can come within `within` of each other at all: their origins
/// are no further apart than their half diagonals, thicknesses and `within` together. Their
/// separation ([`separation`]) is measured in a mean plane, and on a strongly curved surface
/// two tiles on different folds can overlap there though their solids are far apart; only
/// pairs that may touch are neighbours.
pub fn may_touch(a: &Tile, b: &Tile, within: f64) -> bool {
    room_between_balls(a, b) <= within
}

/// The distance between two tiles' bounding balls (about each origin, its half diagonal and
/// thickness): a lower bound on the distance between their solids where positive.
fn room_between_balls(a: &Tile, b: &Tile) -> f64 {
    let reach = |t: &Tile| t.size[0].hypot(t.size[1]) / 2.0 + t.size[2];
    (a.frame.origin - b.frame.origin).norm() - reach(a) - reach(b)
}

/// How two tiles meet.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Separation {
    /// Signed separation: the joint width when positive, the overlap depth when negative.
    pub gap: f64,
    /// Unit direction (in the mean plane) along which it was measured, from the first tile
    /// towards the second.
    pub axis: Vector3<f64>,
    /// Length of the stretch over which the two run along each other across `axis` (the
    /// overlap of their projections onto the direction normal to it): the length of the
    /// joint between them; zero or negative for tiles that only meet at a corner.
    pub along: f64,
}

impl Separation {
    /// Whether the two tiles `a` and `b` it was measured between share a joint: they run
    /// along each other for at least a quarter of the narrower one's width (tiles that only
    /// meet at a corner do not).
    pub fn shares_joint(&self, a: &Tile, b: &Tile) -> bool {
        self.along >= a.size[1].min(b.size[1]) / 4.0
    }
}

/// Separation of the solids of `a` and `b` projected onto their mean plane.
pub fn separation(a: &Tile, b: &Tile) -> Separation {
    separation_of(a, &world_corners(a), b, &world_corners(b))
}

/// [`separation`] with the tiles' [`world_corners`] given (to reuse them over many pairs).
pub fn separation_of(
    a: &Tile,
    outline_a: &[Point3<f64>],
    b: &Tile,
    outline_b: &[Point3<f64>],
) -> Separation {
    // The mean plane of the two, whichever way each tile's thickness axis points (two tiles
    // laid on opposite faces of a folded or overlapping stretch of surface have opposite
    // axes: their plain sum would be a direction along the tiles, not across them).
    let facing = if a.frame.z.dot(&b.frame.z) < 0.0 {
        -1.0
    } else {
        1.0
    };
    let mut n = a.frame.z + b.frame.z * facing;
    if n.norm() < 1e-9 {
        n = a.frame.z;
    }
    let n = n.normalize();
    let origin = nalgebra::center(&a.frame.origin, &b.frame.origin);
    let mut e1 = a.frame.x - n * a.frame.x.dot(&n);
    if e1.norm() < 1e-9 {
        e1 = a.frame.y - n * a.frame.y.dot(&n);
    }
    let e1 = e1.normalize();
    let e2 = n.cross(&e1);
    // The hull of the bottom and top corners: a counter-clockwise convex outline.
    let project = |corners: &[Point3<f64>]| -> Vec<Point2> {
        polygon::convex_hull(
            &corners
                .iter()
                .map(|p| [(p - origin).dot(&e1), (p - origin).dot(&e2)])
                .collect::<Vec<_>>(),
        )
    };
    let (pa, pb) = (project(outline_a), project(outline_b));
    let (gap, axis) = polygon::separation(&pa, &pb);
    let across = [-axis[1], axis[0]];
    let span = |p: &[Point2]| {
        p.iter()
            .map(|&v| polygon::dot(across, v))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                (lo.min(x), hi.max(x))
            })
    };
    let ((a0, a1), (b0, b1)) = (span(&pa), span(&pb));
    // Where the surface bends through a right angle within a tile or two (a crest tighter
    // than a tile), the mean plane of two tiles on its flanks runs across the line between
    // them, and their projections overlap though their solids are apart. Solids whose
    // bounding balls ([`room_between_balls`]) are apart do not
    // overlap: their separation is at least the room between the balls.
    let gap = if gap < 0.0 {
        let room = room_between_balls(a, b);
        if room > 0.0 { room } else { gap }
    } else {
        gap
    };
    Separation {
        gap,
        axis: e1 * axis[0] + e2 * axis[1],
        along: a1.min(b1) - a0.max(b0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tiles::{Frame, TileKind};

    fn tile_at(x: f64, y: f64, angle: f64, tilt: f64) -> Tile {
        let z = Vector3::new(tilt.sin(), 0.0, tilt.cos());
        let along = Vector3::new(angle.cos(), angle.sin(), 0.0);
        let xa = (along - z * along.dot(&z)).normalize();
        let frame = Frame {
            origin: Point3::new(x, y, 0.0),
            x: xa,
            y: z.cross(&xa),
            z,
        };
        Tile::new(TileKind::Full, vec![], frame, [0.28, 0.14, 0.015])
    }

    #[test]
    fn tiles_on_the_flanks_of_a_sharp_crest_do_not_overlap_in_projection() {
        // Two tiles of a wave whose crest is tighter than a tile (radius 140 mm), their
        // thickness axes 92 degrees apart and their origins 355 mm apart: farther than their
        // solids reach (313 mm), but the mean plane of two nearly opposed axes runs across
        // the line between them, and projected onto it the two overlapped by 104 mm.
        let frame = |o: [f64; 3], x: [f64; 3], y: [f64; 3]| {
            let (x, y) = (Vector3::from(x), Vector3::from(y));
            Frame {
                origin: Point3::from(o),
                x,
                y,
                z: x.cross(&y),
            }
        };
        let a = Tile::new(
            TileKind::Full,
            vec![],
            frame(
                [1.0032, 0.6913, 0.6343],
                [0.54357, 0.40369, -0.73591],
                [-0.74985, 0.62752, -0.20964],
            ),
            [0.28, 0.14, 0.015],
        );
        let b = Tile::new(
            TileKind::Full,
            vec![],
            frame(
                [0.9403, 0.3416, 0.6494],
                [0.96476, 0.26312, 0.00194],
                [-0.16044, 0.58238, 0.79693],
            ),
            [0.28, 0.14, 0.015],
        );
        let apart = (a.frame.origin - b.frame.origin).norm();
        let s = separation(&a, &b);
        assert!(s.gap > 0.0, "{s:?}");
        // Never more than the solids' true distance, which their origins bound.
        assert!(s.gap <= apart, "{s:?}");
    }

    #[test]
    fn head_and_bed_joints_of_known_width() {
        let a = tile_at(0.0, 0.0, 0.0, 0.0);
        // End to end, 10 mm apart.
        let s = separation(&a, &tile_at(0.29, 0.0, 0.0, 0.0));
        assert!(
            (s.gap - 0.01).abs() < 1e-12
                && (s.axis.x - 1.0).abs() < 1e-12
                && (s.along - 0.14).abs() < 1e-12
        );
        // Corner to corner, diagonally: a gap, but no stretch of joint between them.
        assert!(separation(&a, &tile_at(0.29, 0.15, 0.0, 0.0)).along <= 0.0);
        // Side by side, offset by half a tile, 7 mm apart.
        assert!((separation(&a, &tile_at(0.145, 0.147, 0.0, 0.0)).gap - 0.007).abs() < 1e-12);
        // Overlapping by 20 mm.
        assert!((separation(&a, &tile_at(0.26, 0.0, 0.0, 0.0)).gap + 0.02).abs() < 1e-12);
        // Symmetric.
        let b = tile_at(0.2, 0.13, 0.1, 0.02);
        assert!((separation(&a, &b).gap - separation(&b, &a).gap).abs() < 1e-12);
    }

    #[test]
    fn tiles_facing_opposite_ways_are_measured_in_their_plane() {
        // Two tiles on one plane, one turned upside down (laid on the other face of a fold)
        // and slightly tilted, overlapping by 200 mm along their length: the sum of their
        // thickness axes runs along the tiles, and an outline projected across it would be a
        // sliver that misses the overlap.
        let a = tile_at(0.0, 0.0, 0.0, 0.0);
        let b = tile_at(0.08, 0.0, 0.0, 0.01);
        let f = b.frame;
        let flipped = Tile::new(
            TileKind::Full,
            vec![],
            Frame {
                origin: f.origin,
                x: f.x,
                y: -f.y,
                z: -f.z,
            },
            b.size,
        );
        for (p, q) in [(&a, &flipped), (&flipped, &a)] {
            let gap = separation(p, q).gap;
            assert!(gap < -0.1, "{gap}");
        }
    }

    #[test]
    fn tilted_neighbours_measure_in_their_mean_plane() {
        // Two tiles tangent to a cylinder of radius 3 about the y axis, 10 mm apart along it.
        let r: f64 = 3.0;
        let half = (0.145 / r).asin();
        let at = |s: f64| {
            let z = Vector3::new((s * half).sin(), 0.0, (s * half).cos());
            let x = Vector3::new((s * half).cos(), 0.0, -(s * half).sin());
            let frame = Frame {
                origin: Point3::from(z * r),
                x,
                y: z.cross(&x),
                z,
            };
            Tile::new(TileKind::Full, vec![], frame, [0.28, 0.14, 0.015])
        };
        let gap = separation(&at(-1.0), &at(1.0)).gap;
        // In the mean (horizontal) plane the origins are 290 mm apart and each tile, tilted by
        // `half`, reaches 140 cos(half) mm towards the other at its bottom; on this convex
        // surface the tops lean apart, so the bottoms close the joint.
        assert!((gap - (0.29 - 0.28 * half.cos())).abs() < 1e-12, "{gap}");
        // Laid inside the barrel instead (a concave surface), the tops lean together and
        // close the joint by the thickness times the tilt.
        let flip = |t: Tile| {
            let f = t.frame;
            Tile::new(
                TileKind::Full,
                vec![],
                crate::tiles::Frame {
                    origin: f.origin,
                    x: f.x,
                    y: -f.y,
                    z: -f.z,
                },
                t.size,
            )
        };
        let inside = separation(&flip(at(-1.0)), &flip(at(1.0))).gap;
        assert!(
            (inside - (0.29 - 0.28 * half.cos() - 2.0 * 0.015 * half.sin())).abs() < 1e-12,
            "{inside}"
        );
    }
}
