//! The cut list: tiles grouped by the shape they must be cut to, so that a site cuts each
//! shape once per count rather than tile by tile.
//!
//! Full tiles need no cut and half tiles are one shape each; a boundary tile's shape is its
//! kept outline in its own frame. Two outlines are the same shape when one maps onto the
//! other, vertex by vertex within the tolerance, under a symmetry of the blank (turning it
//! end for end, or over: a tile has no up side).

use serde::Serialize;

use super::clip::{Cut, Point2};
use super::{Tile, TileKind};

/// Tiles that share one cut shape.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CutGroup {
    /// `F` (full tiles), `H` (half tiles), `B1`, `B2`, ... (boundary shapes, most common
    /// first) or `C1`, `C2`, ... (shapes cut by the fit stage, most common first).
    pub label: String,
    /// Kind of the tiles in the group.
    pub kind: TileKind,
    /// Number of tiles.
    pub count: usize,
    /// Blank the shape is cut from: length and width.
    pub blank: [f64; 2],
    /// Kept area of one tile.
    pub area: f64,
    /// The shape's loops in the blank's frame (boundary groups only; one representative).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub outline: Vec<Vec<Point2>>,
}

/// Groups `tiles` by cut shape (within `tolerance`, model units), labels every tile with its
/// group's label, and returns the groups: `F`, `H`, then boundary shapes and fit-cut shapes,
/// each by falling count.
pub fn cut_list(tiles: &mut [Tile], tolerance: f64) -> Vec<CutGroup> {
    // Representative tile and members of each group, in order of first appearance.
    let mut groups: Vec<(usize, Vec<usize>)> = Vec::new();
    for t in 0..tiles.len() {
        let same = groups
            .iter_mut()
            .find(|(rep, _)| same_shape(&tiles[*rep], &tiles[t], tolerance));
        match same {
            Some((_, members)) => members.push(t),
            None => groups.push((t, vec![t])),
        }
    }
    let rank = |kind: TileKind| match kind {
        TileKind::Full => 0,
        TileKind::Half => 1,
        TileKind::Boundary => 2,
        TileKind::FitCut => 3,
    };
    groups.sort_by(|(a, am), (b, bm)| {
        rank(tiles[*a].kind)
            .cmp(&rank(tiles[*b].kind))
            .then(bm.len().cmp(&am.len()))
            .then(a.cmp(b))
    });
    let (mut boundary_shapes, mut fit_shapes) = (0, 0);
    groups
        .into_iter()
        .map(|(rep, members)| {
            let tile = &tiles[rep];
            let label = match tile.kind {
                TileKind::Full => "F".to_string(),
                TileKind::Half => "H".to_string(),
                TileKind::Boundary => {
                    boundary_shapes += 1;
                    format!("B{boundary_shapes}")
                }
                TileKind::FitCut => {
                    fit_shapes += 1;
                    format!("C{fit_shapes}")
                }
            };
            let group = CutGroup {
                label: label.clone(),
                kind: tile.kind,
                count: members.len(),
                blank: [tile.size[0], tile.size[1]],
                area: tile.kept_area(),
                outline: tile
                    .cut
                    .as_ref()
                    .map(|c| c.loops.clone())
                    .unwrap_or_default(),
            };
            for m in members {
                tiles[m].label = label.clone();
            }
            group
        })
        .collect()
}

/// Whether two tiles are cut to the same shape from the same blank.
fn same_shape(a: &Tile, b: &Tile, tolerance: f64) -> bool {
    if a.kind != b.kind
        || (a.size[0] - b.size[0]).abs() > tolerance
        || (a.size[1] - b.size[1]).abs() > tolerance
    {
        return false;
    }
    match (&a.cut, &b.cut) {
        (None, None) => true,
        (Some(ca), Some(cb)) => same_outline(ca, cb, tolerance),
        _ => false,
    }
}

/// Whether `b` maps onto `a` under one of the blank's four symmetries.
fn same_outline(a: &Cut, b: &Cut, tolerance: f64) -> bool {
    if a.loops.len() != b.loops.len()
        || (a.area() - b.area()).abs() > tolerance * (a.perimeter() + b.perimeter())
    {
        return false;
    }
    let symmetries: [(f64, f64); 4] = [(1.0, 1.0), (-1.0, -1.0), (-1.0, 1.0), (1.0, -1.0)];
    symmetries.iter().any(|&(sx, sy)| {
        let mirrored = sx * sy < 0.0;
        let moved: Vec<Vec<Point2>> = b
            .loops
            .iter()
            .map(|l| {
                let mut m: Vec<Point2> = l.iter().map(|p| [sx * p[0], sy * p[1]]).collect();
                if mirrored {
                    m.reverse();
                }
                m
            })
            .collect();
        // Loops may come in any order: each loop of `a` needs its own match in `b`.
        let mut taken = vec![false; moved.len()];
        a.loops.iter().all(|la| {
            let hit = (0..moved.len()).find(|&k| !taken[k] && same_loop(la, &moved[k], tolerance));
            hit.map(|k| taken[k] = true).is_some()
        })
    })
}

/// Whether two closed loops have the same corners, starting anywhere, within `tolerance`.
fn same_loop(a: &[Point2], b: &[Point2], tolerance: f64) -> bool {
    let (a, b) = (corners(a, tolerance), corners(b, tolerance));
    if a.len() != b.len() {
        return false;
    }
    let close = |p: Point2, q: Point2| (p[0] - q[0]).hypot(p[1] - q[1]) <= tolerance;
    (0..b.len()).any(|shift| (0..a.len()).all(|i| close(a[i], b[(i + shift) % b.len()])))
}

/// The loop without points that lie within `tolerance` of the line through their neighbours
/// (duplicates and points on straight runs), so equal shapes have equal corner lists.
fn corners(points: &[Point2], tolerance: f64) -> Vec<Point2> {
    let mut kept: Vec<Point2> = points.to_vec();
    let mut changed = true;
    while changed && kept.len() > 3 {
        changed = false;
        for i in 0..kept.len() {
            let n = kept.len();
            let (p, q, r) = (kept[(i + n - 1) % n], kept[i], kept[(i + 1) % n]);
            let (dx, dy) = (r[0] - p[0], r[1] - p[1]);
            let len = dx.hypot(dy);
            let off = if len > 0.0 {
                ((q[0] - p[0]) * dy - (q[1] - p[1]) * dx).abs() / len
            } else {
                (q[0] - p[0]).hypot(q[1] - p[1])
            };
            if off <= tolerance {
                kept.remove(i);
                changed = true;
                break;
            }
        }
    }
    kept
}
