//! Closers: tiles taken out of the over-full courses the fit's first placement could not fit,
//! before its second, as a mason leaves out a tile of a course that will not fit and cuts a
//! closer to the gap that remains.
//!
//! Where the quads along a course are shorter than the tile (the paper's Figure 3: quads near
//! singularities and in curved regions are not the half tile's size), the section 3.5
//! placement overlaps tiles along the course. A course over-full by several centimetres can
//! only be fitted by sliding its tiles along it, and the surplus travels to the course's
//! ends, dragging the courses beside it and tearing joints open elsewhere (a 3 m dome's
//! crown: tiles moved 324 mm on average). Taking out one tile per tile length of surplus lets
//! its neighbours close up a short way; the tile taken out stays where the pattern put it and
//! is cut to the room left ([`super::resolve_overlaps`] cuts it before any tile of the
//! pattern). Only courses the fit could not fit lose tiles: elsewhere sliding along the
//! course spreads the surplus well (the shared shells), and a closer would be a cut more.

use super::contacts::{Contact, Side};
use crate::tiles::outline;
use crate::tiles::{Frame, Tile, TileSpec};

/// Per contact, the gap the placement `frames` leaves between its tiles (negative: how deep
/// they overlap), measured as the report measures joints ([`outline::separation`]).
pub(crate) fn gaps(tiles: &[Tile], frames: &[Frame], contacts: &[Contact]) -> Vec<f64> {
    contacts
        .iter()
        .map(|c| {
            let [a, b] = c
                .tiles
                .map(|t| Tile::new(tiles[t].kind, Vec::new(), frames[t], tiles[t].size));
            outline::separation(&a, &b).gap
        })
        .collect()
}

/// Whether a joint of width `gap` is one the tiles cannot keep: an overlap deeper than
/// `tolerance` (to be cut) or a tear wider than `tear` (to take a cut piece).
pub(crate) fn misfit(gap: f64, tolerance: f64, tear: f64) -> bool {
    gap < -tolerance || gap > tear
}

/// Whether the joints `after` a placement done again (per contact, [`gaps`]) fit better
/// than those `before` it, so that it is kept: fewer [`misfit`] joints (overlaps deeper than
/// `tolerance`, gaps wider than `tear`) and a p95 deviation from `joint`, as the cuts to fit
/// will leave them ([`p95_deviation_after_cuts`]), no higher. The rule of the rooms' rounds
/// and of closing tears ([`super::rooms`], [`super::close`]).
pub(crate) fn fits_better(
    before: &[f64],
    after: &[f64],
    joint: f64,
    tolerance: f64,
    tear: f64,
) -> bool {
    let misfits = |gaps: &[f64]| gaps.iter().filter(|&&g| misfit(g, tolerance, tear)).count();
    let deviation = |gaps: &[f64]| p95_deviation_after_cuts(gaps, joint, tolerance);
    misfits(after) < misfits(before) && deviation(after) <= deviation(before)
}

/// Per tile, whether `gaps` (per contact, [`gaps`]) leave it with a [`misfit`] joint.
pub(crate) fn failing(
    tiles: usize,
    contacts: &[Contact],
    gaps: &[f64],
    tolerance: f64,
    tear: f64,
) -> Vec<bool> {
    let mut out = vec![false; tiles];
    for (c, &gap) in contacts.iter().zip(gaps) {
        if misfit(gap, tolerance, tear) {
            c.tiles.iter().for_each(|&t| out[t] = true);
        }
    }
    out
}

/// The 95th percentile of `|gap - joint|` over `gaps` as the cuts to fit leave them: an
/// overlap deeper than `tolerance` is cut back to a joint ([`super::resolve_overlaps`]), so
/// it counts as one (0 when there are no gaps).
pub(crate) fn p95_deviation_after_cuts(gaps: &[f64], joint: f64, tolerance: f64) -> f64 {
    let mut d: Vec<f64> = gaps
        .iter()
        .map(|&g| {
            if g < -tolerance {
                0.0
            } else {
                (g - joint).abs()
            }
        })
        .collect();
    if d.is_empty() {
        return 0.0;
    }
    d.sort_by(f64::total_cmp);
    d[(d.len() * 95).div_ceil(100) - 1]
}

/// Tiles to take out of the fit, in increasing order. Each course (a chain of full tiles end
/// to end, through their head joints) in which some tile is `failing` (the first fit left it
/// overlapping or torn from a neighbour) is walked, summing the surplus `joint - gap` of its
/// head joints as the section 3.5 placement leaves them (`tiles`), gaps counting against
/// overlaps; each time the sum reaches half a tile length plus a joint, the tile after that
/// joint is taken out and a tile length plus a joint is taken off the sum. Courses the fit
/// could fit lose nothing, nor does a course over-full by less than half a tile.
pub(crate) fn closers(
    tiles: &[Tile],
    contacts: &[Contact],
    spec: &TileSpec,
    failing: &[bool],
) -> Vec<usize> {
    let step = spec.length + spec.joint;
    let mut out = Vec::new();
    for chain in courses(tiles, contacts) {
        if !chain.iter().any(|&(t, _)| failing[t]) {
            continue;
        }
        let mut surplus = 0.0;
        for &(t, gap) in &chain[1..] {
            surplus += spec.joint - gap;
            if surplus >= step / 2.0 {
                out.push(t);
                surplus -= step;
            }
        }
    }
    out.sort_unstable();
    out
}

/// The courses: chains of full tiles linked end to end (each tile's neighbour through an end
/// is the contact with the most mesh edges there, and a link needs each to be the other's),
/// each as its tiles in order with the gap from the previous one (the first's is 0). Open
/// chains are walked from an end, closed rings from their lowest tile.
fn courses(tiles: &[Tile], contacts: &[Contact]) -> Vec<Vec<(usize, f64)>> {
    let full = |t: usize| tiles[t].faces.len() == 2 && tiles[t].cut.is_none();
    // Per tile, its neighbour through each end (`+x`, `-x`), the gap and the edges.
    let mut ends: Vec<[Option<(usize, f64, usize)>; 2]> = vec![[None; 2]; tiles.len()];
    for c in contacts {
        let [a, b] = c.tiles;
        if c.sides[0].is_long() || c.sides[1].is_long() || !full(a) || !full(b) {
            continue;
        }
        let gap = outline::separation(&tiles[a], &tiles[b]).gap;
        for (k, (t, other)) in [(a, b), (b, a)].into_iter().enumerate() {
            let slot = &mut ends[t][usize::from(c.sides[k] != Side::PosX)];
            if slot.is_none_or(|(_, _, edges)| c.edges > edges) {
                *slot = Some((other, gap, c.edges));
            }
        }
    }
    let link = |t: usize, end: usize| -> Option<(usize, f64)> {
        let (other, gap, _) = ends[t][end]?;
        ends[other]
            .iter()
            .any(|e| e.is_some_and(|(back, _, _)| back == t))
            .then_some((other, gap))
    };
    let mut seen = vec![false; tiles.len()];
    let starts: Vec<usize> = (0..tiles.len())
        .filter(|&t| full(t) && (link(t, 0).is_none() || link(t, 1).is_none()))
        .chain((0..tiles.len()).filter(|&t| full(t)))
        .collect();
    let mut chains = Vec::new();
    for start in starts {
        if seen[start] {
            continue;
        }
        seen[start] = true;
        let mut chain = vec![(start, 0.0)];
        let (mut at, mut end) = (start, usize::from(link(start, 0).is_none()));
        while let Some((next, gap)) = link(at, end) {
            if seen[next] {
                break;
            }
            seen[next] = true;
            chain.push((next, gap));
            // Leave `next` through its other end.
            end = usize::from(ends[next][0].is_some_and(|(back, _, _)| back == at));
            at = next;
        }
        chains.push(chain);
    }
    chains
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{Topology, generate};
    use crate::tiles::fit::contacts::{contacts, tests::pattern};

    /// One course of `n` quads paired along x into tiles, on quads of edge `edge`.
    fn course(n: usize, edge: f64) -> (Vec<Tile>, Vec<Contact>) {
        let mesh = generate::grid(n, 1);
        let mesh = crate::mesh::PolyMesh::new(
            mesh.positions().iter().map(|p| p * edge).collect(),
            mesh.faces().to_vec(),
        )
        .unwrap();
        let pairs: Vec<[usize; 2]> = (0..n / 2).map(|k| [2 * k, 2 * k + 1]).collect();
        let tiles = crate::tiles::build(&mesh, &pattern(n, pairs, vec![]), &SPEC).unwrap();
        let found = contacts(&mesh, &Topology::new(&mesh).unwrap(), &tiles);
        (tiles, found)
    }

    const SPEC: TileSpec = TileSpec {
        length: 0.28,
        width: 0.14,
        thickness: 0.015,
        joint: 0.01,
    };

    #[test]
    fn a_course_that_fits_keeps_every_tile() {
        let (tiles, found) = course(20, 0.145);
        assert!(closers(&tiles, &found, &SPEC, &vec![true; tiles.len()]).is_empty());
    }

    #[test]
    fn an_over_full_course_loses_a_tile_per_tile_of_surplus() {
        // Quads of 125 mm: each head joint overlaps by 30 mm (a 250 mm pitch for 290 mm of
        // tile and joint), 9 joints of surplus 40 mm each: 360 mm, one closer (after the
        // fourth joint the surplus reaches 160 mm >= 145 mm).
        let (tiles, found) = course(20, 0.125);
        let out = closers(&tiles, &found, &SPEC, &vec![true; tiles.len()]);
        // Not where the fit coped.
        assert!(closers(&tiles, &found, &SPEC, &vec![false; tiles.len()]).is_empty());
        assert_eq!(out.len(), 1, "{out:?}");
        // Twice as long: 19 joints, 760 mm, three closers.
        let (tiles, found) = course(40, 0.125);
        assert_eq!(
            closers(&tiles, &found, &SPEC, &vec![true; tiles.len()]).len(),
            3
        );
    }

    #[test]
    fn overlaps_count_as_the_joints_their_cuts_leave() {
        // 20 gaps: 18 on the joint, one 7 mm too wide, one overlapping by 40 mm.
        let mut gaps = vec![0.01; 18];
        gaps.push(0.017);
        gaps.push(-0.04);
        // The p95 of 20 values is the 19th smallest: the overlap, cut back to a joint,
        // counts as 0, so the 7 mm is the largest and the 19th is 0.
        assert_eq!(p95_deviation_after_cuts(&gaps, 0.01, 0.001), 0.0);
        // Within the tolerance the overlap is left and counts as 50 mm.
        let d = p95_deviation_after_cuts(&gaps, 0.01, 0.05);
        assert!((d - 0.007).abs() < 1e-12, "{d}");
        assert_eq!(p95_deviation_after_cuts(&[], 0.01, 0.001), 0.0);
    }
}
