//! Rooms: standard pieces laid where the placement parts two tiles of a course by about a
//! piece and its joints.
//!
//! Where a course's quads are longer than its tiles (courses that fan out, the paper's
//! Figure 3), the placement gathers the surplus into tears ([`super::solve`]'s capped joint
//! cost) rather than open every head joint a little. A tear about a half tile long is a room
//! a mason fills with a standard half, closing or opening the head joints along the course
//! by a few millimetres each so that it fits, instead of cutting a piece to it. This step
//! finds those rooms between the heads of two tiles of a course, lays the standard piece in
//! each, and the placement is done again with the piece's joints among the others, so the
//! difference spreads over the course ([`super::fit`]). A piece whose joints still stray
//! is taken out again, and its room is filled as before ([`crate::tiles`]' tear fill).

use std::collections::BTreeSet;

use nalgebra::Vector3;

use super::contacts::{Contact, Side};
use super::solve::{BondBand, Problem, Weights, place, side_line};
use super::{FitOptions, MAX_P95_DEVIATION_SHARE, bond_band, closers, tear_gap};
use crate::geom::SurfaceIndex;
use crate::tiles::{Frame, Tile, TileKind, TileSpec, outline};

/// How far a room may be longer or shorter than a standard piece and its two joints, as a
/// share of the half tile's length: two fifths (56 mm on a 280 mm tile), which the joints of
/// the course spread to a few millimetres each where they can (a piece whose joints the
/// placement cannot bring within the flagged deviation is taken out again). Measured on the
/// tubemesh at 260, 280 and 300 mm tiles: pieces cut inside tears 32, 17, 30 at a quarter,
/// 30, 17, 30 at two fifths (38, 23, 30 without rooms).
pub(crate) const SPREAD: f64 = 0.4;

/// The shortest room that takes a standard piece: a half tile and its two joints, less
/// [`SPREAD`] of the half ([`rooms`]' window). A tear narrower than this and wider than a
/// joint is one to close ([`super::close`]).
pub(crate) fn shortest_room(spec: &TileSpec) -> f64 {
    let half = spec.length / 2.0;
    half + 2.0 * spec.joint - SPREAD * half
}

/// Rounds of rooms: after a placement done again around pieces, rooms may open elsewhere
/// in the courses they pushed.
const ROUNDS: usize = 3;

/// Most steps of a placement done again around a round's pieces (it starts from a placement
/// that fits everywhere else): the tubemesh's took 13-23, the 20 m cap's up to 40.
pub(crate) const ROUND_STEPS: usize = 40;

/// Most turn, in degrees, between the two heads facing across a room: a wedge-shaped room
/// (where a course bends or ends) takes no standard piece. At 10 degrees the 3 m cap's
/// pieces cut inside holes fall 151 -> 141, but a 4 m hemisphere's p95 |gap - joint| rises
/// 7.0 -> 8.3 mm (with 286 -> 307 pieces cut inside holes, 54 -> 25 tiles cut to fit).
const MAX_TURN_DEGREES: f64 = 5.0;

/// A room between the heads of two tiles of a course, and the piece that fills it.
#[derive(Debug, Clone)]
pub(crate) struct Room {
    /// The contact (an index into the contacts searched) across which the room opened.
    pub across: usize,
    /// The standard piece to lay in it, on the surface in the middle of the room and turned
    /// as the course: the two tiles no longer face each other, the piece stands between
    /// them.
    pub piece: Tile,
    /// The piece's joints with the tiles around it, the piece numbered as given to [`rooms`].
    pub contacts: Vec<Contact>,
}

/// A placement of tiles with what the fit's least squares need of them, as the rooms' pieces
/// extend it.
pub(crate) struct Placement {
    /// The tiles: the pattern's, then the pieces laid.
    pub tiles: Vec<Tile>,
    /// Where each lies.
    pub frames: Vec<Frame>,
    /// Their joints.
    pub contacts: Vec<Contact>,
    /// Per tile, the frame its weak anchor pulls towards ([`Problem::anchors`]).
    pub anchors: Vec<Frame>,
    /// Per tile, how far beyond the surface's edge it started ([`Problem::beyond_start`]).
    pub beyond_start: Vec<Vector3<f64>>,
    /// Per tile, its box.
    pub sizes: Vec<[f64; 3]>,
}

impl Placement {
    /// Takes out the tiles from `n` on (whose joints must already be gone); the frames are
    /// those of the first `n`.
    fn truncate(&mut self, n: usize) {
        self.tiles.truncate(n);
        self.frames.truncate(n);
        self.anchors.truncate(n);
        self.beyond_start.truncate(n);
        self.sizes.truncate(n);
    }

    /// Per joint, the band of centre offsets its bond allows ([`bond_band`], around the
    /// anchors).
    pub(crate) fn bands(&self, spec: &TileSpec, options: &FitOptions) -> Vec<Option<BondBand>> {
        self.contacts
            .iter()
            .map(|c| bond_band(c, &self.tiles, &self.anchors, spec, options))
            .collect()
    }

    /// The least-squares placement of these tiles on `setting`'s surface, with the bond
    /// `bands` of their joints ([`Placement::bands`]) and the joints flagged in `closing`
    /// closed ([`Problem::closing`]; empty: none).
    pub(crate) fn problem<'a>(
        &'a self,
        bands: &'a [Option<BondBand>],
        setting: &Setting<'a>,
        closing: &'a [bool],
    ) -> Problem<'a> {
        Problem {
            sizes: &self.sizes,
            contacts: &self.contacts,
            bands,
            anchors: &self.anchors,
            beyond_start: &self.beyond_start,
            joint: setting.spec.joint,
            weights: setting.weights,
            surface: setting.surface,
            closing,
        }
    }

    /// Keeps the tiles whose flag in `keep` is set, renumbering the joints (those of a tile
    /// taken out go with it).
    fn retain(&mut self, keep: &[bool]) {
        let mut renumber = vec![None; keep.len()];
        let mut next = 0;
        for (t, &k) in keep.iter().enumerate() {
            if k {
                renumber[t] = Some(next);
                next += 1;
            }
        }
        self.contacts = self
            .contacts
            .iter()
            .filter_map(|c| {
                let [a, b] = c.tiles.map(|t| renumber[t]);
                Some(Contact {
                    tiles: [a?, b?],
                    ..*c
                })
            })
            .collect();
        fn by<T>(v: &mut Vec<T>, keep: &[bool]) {
            let mut k = keep.iter();
            v.retain(|_| *k.next().expect("one flag per tile"));
        }
        by(&mut self.tiles, keep);
        by(&mut self.frames, keep);
        by(&mut self.anchors, keep);
        by(&mut self.beyond_start, keep);
        by(&mut self.sizes, keep);
    }
}

/// What the placements done again need besides the tiles.
pub(crate) struct Setting<'a> {
    /// The tile.
    pub spec: &'a TileSpec,
    /// The fit's options.
    pub options: &'a FitOptions,
    /// The residuals' weights.
    pub weights: Weights,
    /// The surface the tiles stay on.
    pub surface: &'a SurfaceIndex,
}

/// What [`lay`] did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Laid {
    /// Steps of the placements done again.
    pub iterations: usize,
    /// Whether `keep_going` stopped one (its round is then undone).
    pub stopped: bool,
    /// The least-squares objective of the last placement kept, if any was.
    pub end: Option<f64>,
}

/// Lays standard pieces in the rooms of `placement` ([`rooms`]; `skip` as there) and places
/// the tiles again from where they are, for at most [`ROUNDS`] rounds of at most
/// [`ROUND_STEPS`] steps each, a round begun only while the tile steps of the fit so far
/// (`work`, updated) and of the round at most stay within `budget`: a count of work, not the
/// clock, so that the same input gives the same tiles on any machine. A round is kept only
/// when it lays a piece whose joints are within [`MAX_P95_DEVIATION_SHARE`] of the joint
/// and leaves fewer joints the tiles cannot keep (overlaps beyond the tolerance, or gaps a
/// piece will be cut for) with a p95 deviation from the joint no higher (as the cuts to fit
/// will leave them, [`closers::p95_deviation_after_cuts`]); its pieces whose joints stray
/// are taken out again, and the tiles they stood between face each other as before.
/// `keep_going` is asked as the fit's placements ask it (with the share of the steps done).
pub(crate) fn lay(
    placement: &mut Placement,
    skip: &[usize],
    setting: &Setting<'_>,
    (work, budget): (&mut usize, usize),
    keep_going: &mut dyn FnMut(f64) -> bool,
) -> Laid {
    let &Setting {
        spec,
        options,
        surface,
        ..
    } = setting;
    let mut laid = Laid {
        iterations: 0,
        stopped: false,
        end: None,
    };
    let strays = |g: f64| {
        g < -options.overlap_tolerance
            || (g - spec.joint).abs() > MAX_P95_DEVIATION_SHARE * spec.joint
    };
    let mut tried: Vec<[usize; 2]> = Vec::new();
    let steps = ROUND_STEPS.min(options.max_iterations);
    for _ in 0..ROUNDS {
        let p = &mut *placement;
        if *work + p.tiles.len() * steps > budget {
            break;
        }
        let gaps = closers::gaps(&p.tiles, &p.frames, &p.contacts);
        let n = p.tiles.len();
        let found = rooms(p, &gaps, skip, &tried, spec, surface);
        if found.is_empty() {
            break;
        }
        tried.extend(found.iter().map(|r| p.contacts[r.across].tiles));
        tried.sort_unstable();
        let before = p.contacts.clone();
        p.contacts = before
            .iter()
            .enumerate()
            .filter(|(i, _)| !found.iter().any(|r| r.across == *i))
            .map(|(_, c)| *c)
            .collect();
        let mut frames = p.frames.clone();
        for r in &found {
            p.contacts.extend(r.contacts.iter().copied());
            p.anchors.push(r.piece.frame);
            p.beyond_start.push(Vector3::zeros());
            p.sizes.push(r.piece.size);
            p.tiles.push(r.piece.clone());
            frames.push(r.piece.frame);
        }
        let bands = p.bands(spec, options);
        let progress = p
            .problem(&bands, setting, &[])
            .solve(&mut frames, steps, keep_going);
        laid.iterations += progress.iterations;
        *work += p.tiles.len() * progress.iterations;
        let after = closers::gaps(&p.tiles, &frames, &p.contacts);
        let mut keep = vec![true; p.tiles.len()];
        for (c, &g) in p.contacts.iter().zip(&after) {
            if c.tiles[1] >= n && strays(g) {
                keep[c.tiles[1]] = false;
            }
        }
        if progress.stopped
            || !keep[n..].contains(&true)
            || !closers::fits_better(
                &gaps,
                &after,
                spec.joint,
                options.overlap_tolerance,
                tear_gap(spec),
            )
        {
            // Cut short (time limit, cancel: the placement before it, whole), done again for
            // nothing, or for joints that fit no better (fewer misfits, and a p95 deviation
            // no higher): the round is undone.
            p.contacts = before;
            p.truncate(n);
            laid.stopped = progress.stopped;
            break;
        }
        // The tiles a piece taken out stood between face each other again.
        p.contacts.extend(
            found
                .iter()
                .enumerate()
                .filter(|&(k, _)| !keep[n + k])
                .map(|(_, r)| before[r.across]),
        );
        p.frames = frames;
        p.retain(&keep);
        laid.end = Some(progress.end);
    }
    laid
}

/// The rooms `placement` leaves between heads facing each other across its contacts (with
/// their `gaps`, [`closers::gaps`]), for a half or a whole tile of `spec` with its two
/// joints within [`SPREAD`]; tiles in `skip` (closers, to be cut) bound none, nor do the
/// pairs `tried` before (sorted). The `k`-th room's piece is numbered after the tiles, `k`
/// on. A tile bounds at most one room a round.
fn rooms(
    placement: &Placement,
    gaps: &[f64],
    skip: &[usize],
    tried: &[[usize; 2]],
    spec: &TileSpec,
    surface: &SurfaceIndex,
) -> Vec<Room> {
    let Placement {
        tiles,
        frames,
        contacts,
        ..
    } = placement;
    let first = tiles.len();
    let half = spec.length / 2.0;
    let spread = SPREAD * half;
    let parallel = MAX_TURN_DEGREES.to_radians().cos();
    // Each tile's neighbours across its long sides (bed joints), to join a piece to the
    // courses beside it.
    let mut beside: Vec<BTreeSet<usize>> = vec![BTreeSet::new(); tiles.len()];
    for c in contacts {
        let [a, b] = c.tiles;
        if c.sides[0].is_long() {
            beside[a].insert(b);
        }
        if c.sides[1].is_long() {
            beside[b].insert(a);
        }
    }
    let skipped = |t: usize| skip.binary_search(&t).is_ok();
    let mut found: Vec<Room> = Vec::new();
    let mut used = vec![false; tiles.len()];
    for (i, (c, &gap)) in contacts.iter().zip(gaps).enumerate() {
        let [a, b] = c.tiles;
        let [sa, sb] = c.sides;
        if sa.is_long()
            || sb.is_long()
            || skipped(a)
            || skipped(b)
            || used[a]
            || used[b]
            || tried.binary_search(&[a, b]).is_ok()
        {
            continue;
        }
        let off = |l: f64| (gap - l - 2.0 * spec.joint).abs();
        let Some(length) = [half, spec.length]
            .into_iter()
            .filter(|&l| off(l) <= spread)
            .min_by(|&l, &m| off(l).total_cmp(&off(m)))
        else {
            continue;
        };
        // The heads' normals and mid-points: the room runs from one to the other.
        let (na, pa, _, _) = side_line(&frames[a], &tiles[a].size, sa);
        let (nb, pb, _, _) = side_line(&frames[b], &tiles[b].size, sb);
        if na.dot(&-nb) < parallel {
            continue;
        }
        let d = pb - pa;
        if (d - na * d.dot(&na)).norm() > spec.width / 4.0 {
            continue;
        }
        let Some(along) = (na - nb).try_normalize(1e-12) else {
            continue;
        };
        let (frame, beyond) = place(surface, &((pa + pb) / 2.0), &along, &frames[a].z);
        if beyond.norm() > 0.0 {
            continue;
        }
        let kind = if length < spec.length {
            TileKind::Half
        } else {
            TileKind::Full
        };
        let piece = Tile::new(
            kind,
            Vec::new(),
            frame,
            [length, spec.width, spec.thickness],
        );
        let at = first + found.len();
        // Its x runs from `a` to `b`: its -x end faces `a`, its +x end `b`.
        let mut joints = vec![
            Contact {
                tiles: [a, at],
                sides: [sa, Side::NegX],
                edges: 1,
            },
            Contact {
                tiles: [b, at],
                sides: [sb, Side::PosX],
                edges: 1,
            },
        ];
        let neighbours: BTreeSet<usize> = beside[a].union(&beside[b]).copied().collect();
        for t in neighbours {
            if t == a || t == b || skipped(t) {
                continue;
            }
            let other = Tile::new(tiles[t].kind, Vec::new(), frames[t], tiles[t].size);
            let s = outline::separation(&piece, &other);
            if s.along <= spec.joint || s.gap > 2.0 * spec.joint + spread {
                continue;
            }
            let facing = |f: &Frame, towards: &Vector3<f64>| {
                Side::CCW
                    .into_iter()
                    .max_by(|x, y| {
                        x.normal(f)
                            .dot(towards)
                            .total_cmp(&y.normal(f).dot(towards))
                    })
                    .expect("four sides")
            };
            joints.push(Contact {
                tiles: [t, at],
                sides: [facing(&frames[t], &-s.axis), facing(&frame, &s.axis)],
                edges: 1,
            });
        }
        used[a] = true;
        used[b] = true;
        found.push(Room {
            across: i,
            piece,
            contacts: joints,
        });
    }
    found
}

#[cfg(test)]
pub(super) mod tests {
    use super::super::weights_for;
    use super::*;
    use crate::mesh::{PolyMesh, Topology, generate};
    use crate::tiles::fit::contacts::{contacts, tests::pattern};

    pub(in crate::tiles::fit) const SPEC: TileSpec = TileSpec {
        length: 0.28,
        width: 0.14,
        thickness: 0.015,
        joint: 0.01,
    };

    fn scaled(mesh: PolyMesh, edge: f64) -> PolyMesh {
        PolyMesh::new(
            mesh.positions().iter().map(|p| p * edge).collect(),
            mesh.faces().to_vec(),
        )
        .unwrap()
    }

    /// One course of 6 tiles on quads of 145 mm, laid at the joint, with the three last
    /// moved `shift` further along it and turned `turn` radians: a room of 10 mm + `shift`
    /// between the third and the fourth, on a flat surface longer than the course.
    pub(in crate::tiles::fit) fn course(shift: f64, turn: f64) -> (Placement, SurfaceIndex) {
        let mesh = scaled(generate::grid(12, 1), 0.145);
        let pairs: Vec<[usize; 2]> = (0..6).map(|k| [2 * k, 2 * k + 1]).collect();
        let tiles = crate::tiles::build(&mesh, &pattern(12, pairs, vec![]), &SPEC).unwrap();
        let found = contacts(&mesh, &Topology::new(&mesh).unwrap(), &tiles);
        let surface = SurfaceIndex::from_polymesh(&scaled(generate::grid(20, 1), 0.145));
        let frames: Vec<Frame> = tiles
            .iter()
            .map(|t| {
                let f = t.frame;
                if f.origin.x < 0.87 {
                    return f;
                }
                let x = f.x * turn.cos() + f.y * turn.sin();
                place(&surface, &(f.origin.coords + f.x * shift), &x, &f.z).0
            })
            .collect();
        let placement = Placement {
            anchors: tiles.iter().map(|t| t.frame).collect(),
            beyond_start: vec![Vector3::zeros(); tiles.len()],
            sizes: tiles.iter().map(|t| t.size).collect(),
            tiles,
            frames,
            contacts: found,
        };
        (placement, surface)
    }

    fn laid(placement: &mut Placement, surface: &SurfaceIndex) -> Laid {
        let options = FitOptions::for_spec(&SPEC);
        let setting = Setting {
            spec: &SPEC,
            options: &options,
            weights: weights_for(&SPEC),
            surface,
        };
        lay(placement, &[], &setting, (&mut 0, usize::MAX), &mut |_| {
            true
        })
    }

    #[test]
    fn a_room_a_little_longer_than_a_half_takes_a_whole_half_and_the_course_closes_round_it() {
        // 180 mm of room: a half and its two joints would take 160.
        let (mut placement, surface) = course(0.17, 0.0);
        let result = laid(&mut placement, &surface);
        assert!(!result.stopped && result.end.is_some());
        assert_eq!(placement.tiles.len(), 7);
        let piece = &placement.tiles[6];
        assert_eq!(piece.kind, TileKind::Half);
        assert!(piece.faces.is_empty());
        // It stands between the third tile and the fourth, every joint of the course at the
        // mortar joint within a millimetre.
        let gaps = closers::gaps(&placement.tiles, &placement.frames, &placement.contacts);
        assert_eq!(gaps.len(), 6);
        for (c, g) in placement.contacts.iter().zip(&gaps) {
            assert!((g - SPEC.joint).abs() < 1e-3, "{c:?}: {g}");
        }
        let x = placement.frames[6].origin.x;
        assert!(placement.frames[2].origin.x < x && x < placement.frames[3].origin.x);
    }

    #[test]
    fn a_room_too_short_for_a_half_or_wedge_shaped_takes_none() {
        // 70 mm: nearer a joint than a half by more than the spread.
        for (shift, turn) in [(0.06, 0.0), (0.17, 0.2)] {
            let (mut placement, surface) = course(shift, turn);
            let frames = placement.frames.clone();
            let result = laid(&mut placement, &surface);
            assert_eq!(result.end, None, "shift {shift}, turn {turn}");
            assert_eq!(placement.tiles.len(), 6);
            assert_eq!(placement.frames, frames);
        }
    }
}
