//! What the placement could not fit is cut, not left overlapping: every pair of tiles whose
//! outlines still overlap by more than the tolerance loses, on one of the two, the strip
//! beyond the other tile's outline plus a joint, with one straight cut along the axis that
//! separates them ([`crate::tiles::outline::separation`]), as a mason would saw it.

use nalgebra::{Point3, Vector3};

use crate::geom::{HashGrid, polygon};
use crate::tiles::outline::{self, Separation};
use crate::tiles::{Cut, Tile, TileKind};

/// Cuts tiles until no two overlap by more than `tolerance`, leaving a `joint` between each
/// cut tile and the tile it was cut against. Of two overlapping tiles the one cut is, in this
/// order, a filler piece (it is cut anyway), a tile already cut to the boundary, a half tile
/// (cut from a blank anyway), and of two alike the one that loses less area. Returns the
/// indices of the tiles cut, in order. Moves no tile: see [`resolve_overlaps_nudging`].
pub fn resolve_overlaps(tiles: &mut [Tile], joint: f64, tolerance: f64) -> Vec<usize> {
    resolve_overlaps_nudging(tiles, joint, tolerance, &|_: &Tile| false)
}

/// [`resolve_overlaps`], except that where the cut would fall on a whole tile of the pattern
/// (a counted fit cut) and the two overlap by at most half a joint, one of them that is whole
/// is first tapped away from the other along the axis that separates them, as a mason taps a
/// tile over rather than cut it: to half a joint from it, or failing that just clear of it,
/// if the moved tile still `stays_whole` (on the surface, uncut by its boundary) and comes no
/// closer to any other tile than it was or than touching it (than the joint, for a filler
/// piece, whose joints are the joint by construction). Measured on the tubemesh: 36 tiles cut
/// to fit become 26 (README, fit stage).
pub fn resolve_overlaps_nudging(
    tiles: &mut [Tile],
    joint: f64,
    tolerance: f64,
    stays_whole: &dyn Fn(&Tile) -> bool,
) -> Vec<usize> {
    let mut outlines: Vec<Vec<Point3<f64>>> = tiles.iter().map(outline::world_corners).collect();
    let reach = tiles
        .iter()
        .map(|t| t.size[0].hypot(t.size[1]))
        .fold(0.0, f64::max);
    if reach <= 0.0 {
        return Vec::new();
    }
    let grid = HashGrid::of_points(reach, tiles.iter().map(|t| [t.frame.origin]));
    let mut cut: Vec<usize> = Vec::new();
    for a in 0..tiles.len() {
        // A joint beyond the reach: tiles tapped over have moved by up to a joint since the
        // grid was built.
        for b in grid.near(&tiles[a].frame.origin, reach + joint) {
            if b <= a {
                continue;
            }
            let s = outline::separation_of(&tiles[a], &outlines[a], &tiles[b], &outlines[b]);
            if s.gap >= -tolerance {
                continue;
            }
            // The cut that each choice would make, and what it would keep.
            let keep_b = beyond(&tiles[b], &outlines[a], &s, joint);
            let flipped = Separation { axis: -s.axis, ..s };
            let keep_a = beyond(&tiles[a], &outlines[b], &flipped, joint);
            let area = |c: &Option<Cut>| c.as_ref().map_or(0.0, Cut::area);
            let loss_a = tiles[a].kept_area() - area(&keep_a);
            let loss_b = tiles[b].kept_area() - area(&keep_b);
            let cut_b = (rank(&tiles[b]), loss_b) <= (rank(&tiles[a]), loss_a);
            let (victim, kept) = if cut_b { (b, keep_b) } else { (a, keep_a) };
            if rank(&tiles[victim]) >= 2 && -s.gap <= joint / 2.0 {
                let reach = reach + joint;
                let tapped = [(joint / 2.0, b, s.axis), (joint / 2.0, a, -s.axis)]
                    .into_iter()
                    .chain([(tolerance / 2.0, b, s.axis), (tolerance / 2.0, a, -s.axis)])
                    .find_map(|(gap, t, away)| {
                        tap(tiles, &outlines, &grid, reach, t, away, gap - s.gap, joint)
                            .filter(|(moved, _)| stays_whole(moved))
                            .map(|m| (t, m))
                    });
                if let Some((t, (moved, corners))) = tapped {
                    tiles[t] = moved;
                    outlines[t] = corners;
                    continue;
                }
            }
            let tile = &mut tiles[victim];
            tile.fit_cut = true;
            if tile.kind != TileKind::Boundary {
                tile.kind = TileKind::FitCut;
            }
            tile.cut = Some(kept.unwrap_or(Cut {
                loops: Vec::new(),
                kept_fraction: 0.0,
            }));
            outlines[victim] = outline::world_corners(tile);
            if !cut.contains(&victim) {
                cut.push(victim);
            }
        }
    }
    cut
}

/// The order in which tiles are cut: a filler piece (0), a tile already cut or a closer (1),
/// a half tile (2), a full tile (3).
fn rank(t: &Tile) -> u8 {
    match (
        t.faces.is_empty(),
        t.cut.is_some() || t.fit_cut,
        t.kind == TileKind::Half,
    ) {
        (true, _, _) => 0,
        (false, true, _) => 1,
        (false, false, true) => 2,
        (false, false, false) => 3,
    }
}

/// Tile `t` moved by `distance` along `away` (laid into its tangent plane), with its solid's
/// corners, if it is a whole tile of the pattern and the move brings it closer than before
/// to no other tile within `reach` that it is already closer to than touching, or, for a
/// filler piece, than the `joint`.
#[allow(clippy::too_many_arguments)]
fn tap(
    tiles: &[Tile],
    outlines: &[Vec<Point3<f64>>],
    grid: &HashGrid,
    reach: f64,
    t: usize,
    away: Vector3<f64>,
    distance: f64,
    joint: f64,
) -> Option<(Tile, Vec<Point3<f64>>)> {
    let tile = &tiles[t];
    if tile.faces.is_empty() || tile.cut.is_some() {
        return None;
    }
    let along = away - tile.frame.z * tile.frame.z.dot(&away);
    // The gap grows by the move's share along `away`: a steep axis would need a long move.
    if along.norm() < 0.5 {
        return None;
    }
    let mut moved = tile.clone();
    moved.move_to(crate::tiles::Frame {
        origin: tile.frame.origin + along * (distance / along.norm_squared()),
        ..tile.frame
    });
    let corners = outline::world_corners(&moved);
    let clear = grid.near(&moved.frame.origin, reach).into_iter().all(|c| {
        if c == t {
            return true;
        }
        let floor = if tiles[c].faces.is_empty() {
            joint
        } else {
            0.0
        };
        let after = outline::separation_of(&moved, &corners, &tiles[c], &outlines[c]).gap;
        after >= floor
            || after >= outline::separation_of(tile, &outlines[t], &tiles[c], &outlines[c]).gap
    });
    clear.then_some((moved, corners))
}

/// Cuts `piece` (a filler piece, placed after the tiles `placed` with their
/// [`outline::world_corners`] in `outlines`) back to the room they leave: from every tile of
/// `near` (indices into `placed`) that shares a joint with it (see
/// [`Separation::shares_joint`]) or overlaps it, and that comes closer than `joint`, it keeps
/// exactly a `joint` away, with one straight cut each, as a mason cuts a closing piece to the
/// gap it fills. Returns `false` when nothing of it is left.
pub(crate) fn cut_to_room(
    piece: &mut Tile,
    placed: &[Tile],
    outlines: &[Vec<Point3<f64>>],
    near: &[usize],
    joint: f64,
) -> bool {
    let mut own = outline::world_corners(piece);
    // A joint this much short of the nominal one is left as it is (a rounding error).
    let slack = joint * 1e-6;
    for &other in near {
        let s = outline::separation_of(&placed[other], &outlines[other], piece, &own);
        if s.gap >= joint - slack || (s.gap >= 0.0 && !s.shares_joint(&placed[other], piece)) {
            continue;
        }
        match beyond(piece, &outlines[other], &s, joint) {
            Some(cut) => {
                piece.cut = Some(cut);
                own = outline::world_corners(piece);
            }
            None => return false,
        }
    }
    true
}

/// What remains of `tile` beyond `other` (the corners of a solid) along `s.axis` (pointing
/// from `other` towards `tile`) plus `joint`: `None` when nothing does.
fn beyond(tile: &Tile, other: &[Point3<f64>], s: &Separation, joint: f64) -> Option<Cut> {
    let n = s.axis;
    // Beyond the other solid plus a joint, with the tile's top edge as well as its bottom.
    let lean = tile.size[2] * (-n.dot(&tile.frame.z)).max(0.0);
    let reach = other
        .iter()
        .map(|p| n.dot(&p.coords))
        .fold(f64::NEG_INFINITY, f64::max)
        + joint
        + lean;
    // In the tile's frame the kept side is k . (x, y) >= c.
    let k = [n.dot(&tile.frame.x), n.dot(&tile.frame.y)];
    let c = reach - n.dot(&tile.frame.origin.coords);
    let k2 = k[0] * k[0] + k[1] * k[1];
    if k2 <= 1e-24 {
        return None;
    }
    let on_line = [k[0] * c / k2, k[1] * c / k2];
    let along = [k[1], -k[0]];
    let loops: Vec<Vec<polygon::Point2>> = match &tile.cut {
        Some(cut) => cut.loops.clone(),
        None => vec![outline::local_outline(tile)],
    };
    let full = tile.size[0] * tile.size[1];
    let kept: Vec<Vec<polygon::Point2>> = loops
        .iter()
        .map(|l| polygon::clip_left_of(l, on_line, [on_line[0] + along[0], on_line[1] + along[1]]))
        .filter(|l| l.len() >= 3 && polygon::signed_area(l).abs() > full * 1e-12)
        .collect();
    let area: f64 = kept.iter().map(|l| polygon::signed_area(l)).sum();
    (area > 0.0).then(|| Cut {
        loops: kept,
        kept_fraction: (area / full).min(1.0),
    })
}

#[cfg(test)]
mod tests {
    use nalgebra::Vector3;

    use super::*;
    use crate::tiles::Frame;

    fn tile(x: f64, y: f64, angle: f64, faces: Vec<usize>) -> Tile {
        let xa = Vector3::new(angle.cos(), angle.sin(), 0.0);
        let frame = Frame {
            origin: Point3::new(x, y, 0.0),
            x: xa,
            y: Vector3::z().cross(&xa),
            z: Vector3::z(),
        };
        let kind = if faces.len() == 1 {
            TileKind::Half
        } else {
            TileKind::Full
        };
        let size = if faces.len() == 1 {
            [0.14, 0.14, 0.015]
        } else {
            [0.28, 0.14, 0.015]
        };
        Tile::new(kind, faces, frame, size)
    }

    #[test]
    fn an_overlap_is_cut_back_to_a_joint_on_the_cheaper_tile() {
        // A full tile and a half tile overlapping by 30 mm end to end: the half tile is cut.
        let mut tiles = vec![
            tile(0.0, 0.0, 0.0, vec![0, 1]),
            tile(0.18, 0.0, 0.0, vec![2]),
        ];
        let cut = resolve_overlaps(&mut tiles, 0.01, 0.0005);
        assert_eq!(cut, vec![1]);
        assert!(tiles[1].fit_cut && tiles[1].kind == TileKind::FitCut && tiles[0].cut.is_none());
        let gap = outline::separation(&tiles[0], &tiles[1]).gap;
        assert!((gap - 0.01).abs() < 1e-9, "{gap}");
        // 140 mm wide half tile keeps 140 - 30 - 10 = 100 mm.
        assert!((tiles[1].kept_area() - 0.10 * 0.14).abs() < 1e-9);
    }

    #[test]
    fn a_filler_piece_is_cut_to_the_room_its_neighbours_leave() {
        // A full tile at the origin and a half tile placed over its end's corner.
        let placed = vec![
            tile(0.0, 0.0, 0.0, vec![0, 1]),
            tile(0.215, 0.13, 0.0, vec![2]),
        ];
        let outlines: Vec<_> = placed.iter().map(outline::world_corners).collect();
        let near = [0, 1];
        let gap = |piece: &Tile, t: usize| outline::separation(&placed[t], piece).gap;
        // A 140 mm piece 5 mm beyond the full tile's end and 10 mm under the half tile: cut
        // back to a joint from both.
        let mut piece = tile(0.215, 0.0, 0.0, vec![9]);
        assert!(cut_to_room(&mut piece, &placed, &outlines, &near, 0.01));
        assert!((gap(&piece, 0) - 0.01).abs() < 1e-9, "{}", gap(&piece, 0));
        assert!((gap(&piece, 1) - 0.01).abs() < 1e-9, "{}", gap(&piece, 1));
        assert!((piece.kept_area() - 0.135 * 0.12).abs() < 1e-9);
        // A piece 15 mm from the full tile, and one meeting it only at a corner 3 mm off:
        // left whole.
        for (x, y) in [(0.225, -0.05), (0.213, -0.143)] {
            let mut piece = tile(x, y, 0.0, vec![9]);
            assert!(cut_to_room(&mut piece, &placed, &outlines, &near, 0.01));
            assert!(piece.cut.is_none(), "{x} {y}");
        }
        // A piece on top of a tile: nothing is left.
        let mut piece = tile(0.0, 0.0, 0.0, vec![9]);
        assert!(!cut_to_room(&mut piece, &placed, &outlines, &near, 0.01));
    }

    #[test]
    fn a_shallow_overlap_is_tapped_apart_where_there_is_room_and_cut_where_not() {
        let gap =
            |tiles: &[Tile], a: usize, b: usize| outline::separation(&tiles[a], &tiles[b]).gap;
        // Two full tiles end to end, 3 mm into each other: the second is tapped to half a joint.
        let pair = || {
            vec![
                tile(0.0, 0.0, 0.0, vec![0, 1]),
                tile(0.277, 0.0, 0.0, vec![2, 3]),
            ]
        };
        let mut tiles = pair();
        assert!(resolve_overlaps_nudging(&mut tiles, 0.01, 0.0005, &|_: &Tile| true).is_empty());
        assert!(tiles.iter().all(|t| t.cut.is_none()));
        assert!(
            (gap(&tiles, 0, 1) - 0.005).abs() < 1e-9,
            "{}",
            gap(&tiles, 0, 1)
        );
        // The tapped tile's box corners moved with it.
        for t in &tiles {
            let placed = tile(t.frame.origin.x, t.frame.origin.y, 0.0, t.faces.clone());
            for (a, b) in t.corners.iter().zip(&placed.corners) {
                assert!((0..3).all(|k| (a[k] - b[k]).abs() < 1e-12), "{a:?} {b:?}");
            }
        }
        // Not where the moved tile would leave the surface, nor with plain resolve_overlaps.
        for nudging in [true, false] {
            let mut tiles = pair();
            let cut = if nudging {
                resolve_overlaps_nudging(&mut tiles, 0.01, 0.0005, &|_: &Tile| false)
            } else {
                resolve_overlaps(&mut tiles, 0.01, 0.0005)
            };
            assert_eq!(cut.len(), 1);
            assert!((tiles[0].frame.origin.x, tiles[1].frame.origin.x) == (0.0, 0.277));
        }
        // Neighbours 4 mm beyond either end: tapped just clear (0.25 mm), the neighbour's joint
        // narrower but open.
        let mut tiles = pair();
        tiles.push(tile(0.561, 0.0, 0.0, vec![4, 5]));
        tiles.push(tile(-0.284, 0.0, 0.0, vec![6, 7]));
        assert!(resolve_overlaps_nudging(&mut tiles, 0.01, 0.0005, &|_: &Tile| true).is_empty());
        assert!(
            (gap(&tiles, 0, 1) - 0.00025).abs() < 1e-9,
            "{}",
            gap(&tiles, 0, 1)
        );
        assert!(gap(&tiles, 1, 2) > 0.0 && gap(&tiles, 0, 3) > 0.0);
        // Neighbours 2 mm beyond: no room, the overlap is cut.
        let mut tiles = pair();
        tiles.push(tile(0.559, 0.0, 0.0, vec![4, 5]));
        tiles.push(tile(-0.282, 0.0, 0.0, vec![6, 7]));
        let cut = resolve_overlaps_nudging(&mut tiles, 0.01, 0.0005, &|_: &Tile| true);
        assert_eq!(cut.len(), 1);
        assert!(
            (gap(&tiles, 0, 1) - 0.01).abs() < 1e-9,
            "{}",
            gap(&tiles, 0, 1)
        );
        assert!(
            (gap(&tiles, 1, 2) - 0.002).abs() < 1e-9 && (gap(&tiles, 0, 3) - 0.002).abs() < 1e-9
        );
    }

    #[test]
    fn shallow_overlaps_and_joints_are_left_alone() {
        let mut tiles = vec![
            tile(0.0, 0.0, 0.0, vec![0, 1]),
            tile(0.2898, 0.0, 0.01, vec![2, 3]),
            tile(0.0, 0.1502, 0.0, vec![4, 5]),
        ];
        assert!(resolve_overlaps(&mut tiles, 0.01, 0.0005).is_empty());
        assert!(tiles.iter().all(|t| t.cut.is_none()));
    }

    #[test]
    fn after_resolving_no_pair_overlaps() {
        // A jumble of tiles pushed into each other.
        let mut tiles: Vec<Tile> = (0..30)
            .map(|i| {
                let k = i as f64;
                tile(
                    (k % 6.0) * 0.25,
                    (k / 6.0).floor() * 0.13,
                    0.2 * (k * 1.3).sin(),
                    vec![2 * i, 2 * i + 1],
                )
            })
            .collect();
        let cut = resolve_overlaps(&mut tiles, 0.01, 0.0005);
        assert!(!cut.is_empty());
        for a in 0..tiles.len() {
            for b in a + 1..tiles.len() {
                let gap = outline::separation(&tiles[a], &tiles[b]).gap;
                assert!(
                    gap >= -0.0005 - 1e-12
                        || tiles[a].kept_area() == 0.0
                        || tiles[b].kept_area() == 0.0,
                    "{a} {b} {gap}"
                );
            }
        }
    }
}
