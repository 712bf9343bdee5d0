//! Filling the tears the fit leaves: pieces cut to the holes between fitted tiles.
//!
//! Where courses converge (a dome's crown, around singularities) rigid tiles cannot follow
//! the quads, and the fit (paper section 4.3's "optimisation step") parts them rather than
//! let them overlap: a tear, a gap of several joints or more. A mason closes it with pieces
//! cut to the room left. So does this step, after the tiles and the boundary's filler pieces
//! are placed: the surface is sampled as the report's coverage samples it, and at each
//! sample no tile covers, a tile blank is laid on the surface, centred on the uncovered
//! samples around it and turned as the nearest tile (or across it), or continuing the
//! nearest tile's course into the hole ([`Tears::course_cells`]), whichever keeps most, cut
//! to the surface's boundary and to the room its neighbours leave, a joint from each
//! ([`super::fit::cut_to_room`]). Continued courses lay whole tiles where a hole is wide
//! enough (a dome's crown opened by the fit), as a mason fills it in courses and cuts only
//! at its edges. A piece narrower than the narrowest kept width is not laid: that gap is
//! mortar. The pieces are listed with the filler pieces (label B, no faces) and cut like
//! them.

use nalgebra::{Point3, Vector3};

use super::clip::{Clipped, SurfaceBoundary};
use super::excluded::ExcludedArea;
use super::outline::{self, covers};
use super::{Frame, Tile, TileKind};
use crate::geom::{HashGrid, sample};
use crate::mesh::PolyMesh;

/// How much wider than a joint the lattice of a continued course lays its joints
/// ([`Tears::course_cells`]): a tenth. Measured on five shells (the 3 m cap, two
/// hemispheres, the evenly triangulated one, the tubemesh): pieces cut 1667 without the
/// continued courses, 1516 with them at the nominal joint, 1449 at a tenth wider (63 of
/// the tears' pieces whole), 1489 at three tenths.
const COURSE_PITCH_SLACK: f64 = 0.1;

/// The longest walk to a course cell, in tile widths: the sample lies within a tile's reach
/// of the tile whose course is continued, so a few steps do; more means bad input.
const MAX_WALK_STEPS: f64 = 16.0;

/// How far from the nominal joint the joints around a standard piece laid in a hole may be
/// ([`Tears::standard`]), as a share of the joint: a half (5 mm on a 10 mm joint, the fit's
/// own line for joints that need no look, [`super::fit::MAX_P95_DEVIATION_SHARE`]).
const JOINT_SPREAD: f64 = 0.5;

/// What the tear fill needs to know of the tiles and the surface.
pub(crate) struct Tears<'a> {
    /// The surface (opened where the caller left an area out), sampled.
    pub surface: &'a PolyMesh,
    /// Its boundary, to cut pieces to and to lay them onto the surface.
    pub boundary: &'a SurfaceBoundary,
    /// The blank a piece is cut from (a full tile's size).
    pub blank: [f64; 3],
    /// The mortar joint.
    pub joint: f64,
    /// Pieces narrower than this are not laid.
    pub min_width: f64,
    /// How far the boundary may enter a piece before it is cut ([`SurfaceBoundary::clip`]).
    pub tolerance: f64,
    /// The caller's excluded quads (openings, areas laid by hand): not filled.
    pub excluded: Option<&'a ExcludedArea>,
}

/// Uncovered samples tried between two calls of the fill's `keep_going`.
const POLL_EVERY: usize = 64;

/// What [`Tears::fill`] laid.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Filled {
    /// Pieces appended to the tiles.
    pub pieces: usize,
    /// Of `pieces`, those cut to the room their neighbours leave and not reaching the
    /// surface's edge: cuts the fit's tears alone ask for (a piece at the edge is cut there
    /// anyway, and a whole piece is no cut).
    pub inside_cuts: usize,
    /// Of `pieces`, whole half tiles laid where the room held one ([`Tears::standard`]):
    /// no cut on site, though a half is cut from a tile as the pattern's halves are.
    pub halves: usize,
    /// Whether `keep_going` stopped the fill before every uncovered sample was tried.
    pub stopped: bool,
}

impl Tears<'_> {
    /// Appends to `tiles` the pieces that fill the holes between them. `keep_going` is asked
    /// every [`POLL_EVERY`] uncovered samples; `false` stops the fill with the pieces laid so
    /// far (a surface far larger than its tiles, e.g. a tile in the wrong units, can ask for
    /// tens of thousands of pieces).
    pub(crate) fn fill(
        &self,
        tiles: &mut Vec<Tile>,
        keep_going: &mut dyn FnMut() -> bool,
    ) -> Filled {
        let before = tiles.len();
        let mut inside_cuts = 0;
        let laid = |tiles: &Vec<Tile>, inside_cuts, stopped| Filled {
            pieces: tiles.len() - before,
            inside_cuts,
            halves: tiles[before..]
                .iter()
                .filter(|t| t.kind == TileKind::Half)
                .count(),
            stopped,
        };
        // Every piece continues a tile near it: with none there is nothing to continue.
        if tiles.is_empty() {
            return laid(tiles, 0, false);
        }
        let mut outlines: Vec<Vec<Point3<f64>>> =
            tiles.iter().map(outline::world_corners).collect();
        let half_diagonal = tiles
            .iter()
            .map(|t| t.size[0].hypot(t.size[1]) / 2.0)
            .fold(self.blank[0].hypot(self.blank[1]) / 2.0, f64::max);
        // Tiles that may cover a point, and those that may touch a piece.
        let reach = half_diagonal + self.joint;
        let touching = 2.0 * half_diagonal + self.joint;
        let mut placed = HashGrid::of_points(reach, tiles.iter().map(|t| [t.frame.origin]));
        let margin = self.joint / 2.0;
        let covered = |tiles: &[Tile], placed: &HashGrid, q: &Point3<f64>| {
            placed
                .near(q, reach)
                .into_iter()
                .any(|t| covers(&tiles[t], q, margin))
        };
        // The samples no tile covers, with their face's normal and sheet.
        let spacing = self.blank[1] / sample::SAMPLES_PER_TILE_SIDE;
        let normals: Vec<Vector3<f64>> = (0..self.surface.face_count())
            .map(|f| {
                self.surface
                    .face_area_vector(f)
                    .try_normalize(0.0)
                    .unwrap_or_else(Vector3::z)
            })
            .collect();
        // Each face's on its own (on the threads of `parallel`), gathered in face order.
        let faces = self.surface.faces();
        type Open = (Point3<f64>, Vector3<f64>, f64, usize);
        let open: Vec<Open> = crate::parallel::map(faces.len(), |f| {
            let mut open = Vec::new();
            let sheet = self.boundary.face_sheet(f);
            sample::face(self.surface.positions(), &faces[f], spacing, |q, area| {
                if !covered(tiles, &placed, &q) && !self.excluded.is_some_and(|e| e.contains(&q)) {
                    open.push((q, normals[f], area, sheet));
                }
            });
            open
        })
        .into_iter()
        .flatten()
        .collect();
        let holes = HashGrid::of_points(self.blank[1], open.iter().map(|s| [s.0]));
        // Samples found covered: tiles are only added, so a covered sample stays covered and
        // need not be asked again (on a surface where the tiles leave wide holes, each
        // sample is otherwise asked once for every sample within half a width of it).
        let mut done = vec![false; open.len()];
        let mut tried = 0;
        // Holes are filled from their edges in, as a mason fills them: the samples nearest a
        // tile first (by the distance to the nearest origin within a piece's touch, as the
        // tiles stand before the fill; ties, and samples beyond a piece's touch of every
        // tile, in face order), so that each piece continues a course from a tile beside it
        // and the pieces next in continue those. With the slide of [`Tears::standard`],
        // measured on 27 shells (docs/journal.md, *Holes filled from their edges*, which also
        // has the order kept up to date as pieces are laid, which cut more): pieces cut in
        // the holes 1136 -> 1025 of about 34,000 tiles, the drum's share cut 21.4 -> 18.0 %.
        let from_edges = |i: usize| {
            placed
                .near(&open[i].0, touching)
                .into_iter()
                .map(|t| (tiles[t].frame.origin - open[i].0).norm())
                .fold(f64::INFINITY, f64::min)
        };
        let mut order: Vec<(f64, usize)> = (0..open.len()).map(|i| (from_edges(i), i)).collect();
        order.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        for i in order.into_iter().map(|(_, i)| i) {
            let (q, normal, _, sheet) = open[i];
            if done[i] || covered(tiles, &placed, &q) {
                done[i] = true;
                continue;
            }
            tried += 1;
            if tried % POLL_EVERY == 0 && !keep_going() {
                return laid(tiles, inside_cuts, true);
            }
            // The nearest tile sets the piece's turn and which way is up.
            let near = placed.near(&q, reach);
            let Some(&nearest) = near.iter().min_by(|&&a, &&b| {
                let d = |t: usize| (tiles[t].frame.origin - q).norm_squared();
                d(a).total_cmp(&d(b)).then(a.cmp(&b))
            }) else {
                continue;
            };
            let up = if normal.dot(&tiles[nearest].frame.z) < 0.0 {
                -normal
            } else {
                normal
            };
            // Centred on the hole around the sample, as far as a piece's half width reaches,
            // on the sample's own sheet (a piece is cut to the crease between two).
            let (mut sum, mut weight) = (Vector3::zeros(), 0.0);
            for s in holes.near(&q, self.blank[1] / 2.0) {
                let (p, _, area, on) = open[s];
                if done[s] || on != sheet || (p - q).norm() > self.blank[1] / 2.0 {
                    continue;
                }
                if covered(tiles, &placed, &p) {
                    done[s] = true;
                } else {
                    sum += p.coords * area;
                    weight += area;
                }
            }
            let centre = if weight > 0.0 {
                Point3::from(sum / weight)
            } else {
                q
            };
            let centre = self
                .boundary
                .closest_on(&centre, self.blank[1], sheet)
                .unwrap_or(q);
            let from = tiles[nearest].frame;
            // The candidate keeping most area, the first of equals; a whole piece keeps all
            // a piece can, so the candidates after it are not cut.
            let mut best: Option<(Tile, bool)> = None;
            for frame in [from.x, from.y]
                .iter()
                .map(|along| Frame::from_normal(centre, up, along))
                .chain(self.course_cells(&from, &q, &up))
            {
                // A piece lies on the sample's sheet: a course continued over a crease would
                // lay it across, turned as the other sheet.
                if self.boundary.sheet_at(&frame.origin, self.blank[1]) != Some(sheet) {
                    continue;
                }
                let near = placed.near(&frame.origin, touching);
                let Some((piece, at_edge)) = self.piece(frame, tiles, &outlines, &near, &q) else {
                    continue;
                };
                if best
                    .as_ref()
                    .is_none_or(|b| piece.kept_area() > b.0.kept_area())
                {
                    best = Some((piece, at_edge));
                }
                if best.as_ref().is_some_and(|b| b.0.cut.is_none()) {
                    break;
                }
            }
            // A piece cut inside a hole whose room holds a standard piece is laid whole.
            let best = best.map(|(piece, at_edge)| {
                if piece.cut.is_none() || at_edge {
                    return (piece, at_edge);
                }
                // A whole tile may slide up to a blank's length from the piece.
                let near = placed.near(&piece.frame.origin, touching + self.blank[0]);
                match self.standard(&piece, tiles, &outlines, &near, &q) {
                    Some(whole) => (whole, false),
                    None => (piece, at_edge),
                }
            });
            if let Some((piece, at_edge)) = best {
                inside_cuts += usize::from(piece.cut.is_some() && !at_edge);
                placed.insert(tiles.len(), &piece.frame.origin, &piece.frame.origin);
                outlines.push(outline::world_corners(&piece));
                tiles.push(piece);
            }
        }
        laid(tiles, inside_cuts, false)
    }

    /// Frames for a piece continuing the course of the tile on `from` to the sample `q`: the
    /// cell of its course lattice (a blank plus a joint along it and across it, the
    /// courses' pitch) that holds `q`, and the cell in the same course shifted half a tile
    /// along that holds it (as a staggered neighbour course's cells lie), each reached by
    /// walking over the surface from `from` a tile's width at a time, so that the surface's
    /// curvature does not draw the cells together. The cell is chosen from `q`'s offset in
    /// `from`'s plane, so on a strongly curved surface it may miss `q`; such a piece is then
    /// not laid ([`Tears::piece`] asks that it cover `q`). The lattice is
    /// [`COURSE_PITCH_SLACK`] of a joint wider than nominal: the walk's projections shorten
    /// each step a little, and a piece trimmed by a millimetre is a cut.
    fn course_cells(
        &self,
        from: &Frame,
        q: &Point3<f64>,
        up: &Vector3<f64>,
    ) -> impl Iterator<Item = Frame> + use<'_> {
        let extra = (1.0 + COURSE_PITCH_SLACK) * self.joint;
        let (along, across) = (self.blank[0] + extra, self.blank[1] + extra);
        let d = q - from.origin;
        let row = (d.dot(&from.y) / across).round();
        let column = d.dot(&from.x) / along;
        let (from, up) = (*from, *up);
        [column.round(), (column - 0.5).round() + 0.5]
            .into_iter()
            .filter_map(move |cell| {
                let origin = self.walk(&from, &up, cell * along, row * across)?;
                Some(Frame::from_normal(origin, up, &from.x))
            })
    }

    /// The point of the surface reached from `from`'s origin by `dx` along its `x` and then
    /// `dy` along its `y`, in steps of at most a tile's width, each laid in the plane
    /// across `up`, brought back onto the surface and lengthened once so that the chord it
    /// spans is the step's length; `None` where the walk leaves the surface (or the
    /// lengths are not finite, or longer than [`MAX_WALK_STEPS`] widths).
    fn walk(&self, from: &Frame, up: &Vector3<f64>, dx: f64, dy: f64) -> Option<Point3<f64>> {
        let mut at = from.origin;
        for (axis, length) in [(from.x, dx), (from.y, dy)] {
            let steps = (length.abs() / self.blank[1]).ceil();
            if !steps.is_finite() || steps > MAX_WALK_STEPS {
                return None;
            }
            if steps == 0.0 {
                continue;
            }
            let step = length / steps;
            let dir = (axis - up * axis.dot(up)).try_normalize(1e-12)?;
            for _ in 0..steps as usize {
                let reached = self.boundary.closest(&(at + dir * step), self.blank[1])?;
                let got = (reached - at).norm();
                at = if got > 0.0 {
                    let scaled = at + dir * (step * step.abs() / got);
                    self.boundary.closest(&scaled, self.blank[1])?
                } else {
                    reached
                };
            }
        }
        Some(at)
    }

    /// The piece on `frame` cut to the surface and to the room the tiles `near` leave, if it
    /// is wide enough, overlaps none of them and still covers the sample `q` it is laid for;
    /// with whether the surface's edge cut it.
    fn piece(
        &self,
        frame: Frame,
        tiles: &[Tile],
        outlines: &[Vec<Point3<f64>>],
        near: &[usize],
        q: &Point3<f64>,
    ) -> Option<(Tile, bool)> {
        let mut piece = Tile::new(TileKind::Full, Vec::new(), frame, self.blank);
        let at_edge = match self.boundary.clip(&piece, self.tolerance) {
            Clipped::Outside => return None,
            Clipped::Whole => false,
            Clipped::Cut(cut) => {
                piece.cut = Some(cut);
                true
            }
        };
        if !super::fit::cut_to_room(&mut piece, tiles, outlines, near, self.joint) {
            return None;
        }
        if let Some(cut) = &piece.cut {
            if cut.kept_width() < self.min_width {
                return None;
            }
            piece.kind = TileKind::Boundary;
        }
        // On a strongly curved surface a straight cut in the piece's plane may leave it
        // overlapping a neighbour turned away from it: such a piece is not laid.
        (clear_of(&piece, tiles, outlines, near) && covers(&piece, q, 0.0))
            .then_some((piece, at_edge))
    }

    /// A standard piece (a whole tile, or else a half) laid instead of `cut`, a piece cut to
    /// the room inside a hole, where that room holds one with every joint at most
    /// [`JOINT_SPREAD`] of a joint from the nominal one: a mason opens or closes the joints
    /// around a gap a little rather than cut a tile a few millimetres short. The piece is
    /// centred on the room `cut` keeps (its outline's extent in its own frame); a whole
    /// tile may also keep the one end of the blank that was cut and slide away from it, into
    /// the hole beyond the blank's other end, as a mason lays the next tile of a course a
    /// joint from the last rather than cut it to where a lattice put it. It must lie wholly
    /// on the surface, clear of its neighbours by the narrowest joint allowed, and still
    /// cover the sample `q` it is laid for (within a joint). `near` must hold every tile
    /// that may touch a piece up to a blank's length from `cut`.
    fn standard(
        &self,
        cut: &Tile,
        tiles: &[Tile],
        outlines: &[Vec<Point3<f64>>],
        near: &[usize],
        q: &Point3<f64>,
    ) -> Option<Tile> {
        let loops = &cut.cut.as_ref()?.loops;
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in loops.iter().flatten() {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let room = [hi[0] - lo[0], hi[1] - lo[1]];
        // Each of the two joints across the room takes half of what the piece leaves.
        let spread = JOINT_SPREAD * self.joint;
        if !room[1].is_finite() || room[1] < self.blank[1] - 2.0 * spread {
            return None;
        }
        let across = (lo[1] + hi[1]) / 2.0;
        // Where a piece of `length` may lie along the room: centred on it, where the room is
        // about as long (each joint along it takes half of the difference); or, for a whole
        // tile where the cut took one end of the blank only, with that end kept and the tile
        // slid away from it into the room the blank did not reach. (A half slid so would
        // leave a room short of a half behind it: another cut.)
        let (hx, tolerance) = (self.blank[0] / 2.0, self.tolerance.max(self.joint * 1e-3));
        let places = |kind: TileKind, length: f64| {
            let centred =
                ((room[0] - length).abs() <= 2.0 * spread).then_some((lo[0] + hi[0]) / 2.0);
            let slides = kind == TileKind::Full;
            let from_low = (slides && lo[0] > -hx + tolerance && hi[0] >= hx - tolerance)
                .then_some(lo[0] + length / 2.0);
            let from_high = (slides && hi[0] < hx - tolerance && lo[0] <= -hx + tolerance)
                .then_some(hi[0] - length / 2.0);
            [centred, from_low, from_high].into_iter().flatten()
        };
        for (kind, length) in [
            (TileKind::Full, self.blank[0]),
            (TileKind::Half, self.blank[0] / 2.0),
        ] {
            for along in places(kind, length) {
                let centre = cut.frame.origin + cut.frame.x * along + cut.frame.y * across;
                let Some(centre) = self.boundary.closest(&centre, self.blank[1]) else {
                    continue;
                };
                let frame = Frame::from_normal(centre, cut.frame.z, &cut.frame.x);
                let mut piece = Tile::new(
                    kind,
                    Vec::new(),
                    frame,
                    [length, self.blank[1], self.blank[2]],
                );
                if !matches!(self.boundary.clip(&piece, self.tolerance), Clipped::Whole) {
                    continue;
                }
                if !super::fit::cut_to_room(&mut piece, tiles, outlines, near, self.joint - spread)
                    || piece.cut.is_some()
                {
                    continue;
                }
                if clear_of(&piece, tiles, outlines, near) && covers(&piece, q, self.joint) {
                    return Some(piece);
                }
            }
        }
        None
    }
}

/// Whether `piece` overlaps none of the tiles `near` (indices into `tiles`, with their
/// [`outline::world_corners`] in `outlines`).
fn clear_of(piece: &Tile, tiles: &[Tile], outlines: &[Vec<Point3<f64>>], near: &[usize]) -> bool {
    let own = outline::world_corners(piece);
    near.iter().all(|&t| {
        !outline::may_touch(&tiles[t], piece, 0.0)
            || outline::separation_of(&tiles[t], &outlines[t], piece, &own).gap >= 0.0
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::sample;

    /// A flat rectangle `w` x `h` at z = 0, as two triangles.
    fn rectangle(w: f64, h: f64) -> PolyMesh {
        let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
        PolyMesh::new(
            vec![p(0.0, 0.0), p(w, 0.0), p(w, h), p(0.0, h)],
            vec![vec![0, 1, 2], vec![0, 2, 3]],
        )
        .unwrap()
    }

    /// Two rows of four 280 x 140 tiles with 10 mm joints, along the bottom and the top of a
    /// sheet of height `h`, each tangent to it: `at(x, s)` gives the sheet's point and normal
    /// at `x` along it and `s` across.
    fn rows_along(h: f64, at: impl Fn(f64, f64) -> (Point3<f64>, Vector3<f64>)) -> Vec<Tile> {
        let tile = |x: f64, s: f64| {
            let (origin, normal) = at(x, s);
            let frame = Frame::from_normal(origin, normal, &Vector3::x());
            Tile::new(TileKind::Full, vec![], frame, [0.28, 0.14, 0.015])
        };
        (0..4)
            .flat_map(|i| {
                let x = 0.14 + 0.29 * i as f64;
                [tile(x, 0.07), tile(x, h - 0.07)]
            })
            .collect()
    }

    /// [`rows_along`] a flat rectangle of height `h`.
    fn rows(h: f64) -> Vec<Tile> {
        rows_along(h, |x, y| (Point3::new(x, y, 0.0), Vector3::z()))
    }

    /// The point at `x` and arc length `s` across a `w` x `h` sheet bent over a cylinder of
    /// radius `r` (its axis along x, the sheet's middle at its top), and its normal.
    fn on_bent(x: f64, s: f64, h: f64, r: f64) -> (Point3<f64>, Vector3<f64>) {
        let a = (s - h / 2.0) / r;
        (
            Point3::new(x, r * a.sin(), r * a.cos() - r),
            Vector3::new(0.0, a.sin(), a.cos()),
        )
    }

    /// That sheet as a 24 x 30 grid ([`crate::mesh::generate::grid`]) bent onto it and split
    /// into triangles.
    fn bent(w: f64, h: f64, r: f64) -> PolyMesh {
        use crate::mesh::generate;
        let (nu, nv) = (24.0, 30.0);
        let flat = generate::grid(24, 30);
        let positions = flat
            .positions()
            .iter()
            .map(|p| on_bent(w * p.x / nu, h * p.y / nv, h, r).0)
            .collect();
        let sheet = PolyMesh::new(positions, flat.faces().to_vec()).unwrap();
        generate::triangulate_quads(&sheet)
    }

    fn fill(surface: &PolyMesh, tiles: &mut Vec<Tile>) -> usize {
        filled(surface, tiles).pieces
    }

    /// The tear fill of 280 x 140 x 15 blanks with 10 mm joints on `surface`, cut to
    /// `boundary` (its own).
    fn tears_on<'a>(surface: &'a PolyMesh, boundary: &'a SurfaceBoundary) -> Tears<'a> {
        Tears {
            surface,
            boundary,
            blank: [0.28, 0.14, 0.015],
            joint: 0.01,
            min_width: 0.028,
            tolerance: 0.001,
            excluded: None,
        }
    }

    fn filled(surface: &PolyMesh, tiles: &mut Vec<Tile>) -> Filled {
        let boundary = SurfaceBoundary::new(surface, 0.28);
        tears_on(surface, &boundary).fill(tiles, &mut || true)
    }

    #[test]
    fn pieces_cut_to_the_room_inside_are_told_from_those_the_edge_cuts() {
        // Rows 360 mm apart on a sheet 0.95 m wide, the rows running 200 mm past its right
        // edge: the courses continued into the hole leave pieces cut to the room between the
        // rows, and at the right end pieces the sheet's edge cuts.
        let (w, h) = (0.95, 0.64);
        let surface = rectangle(w, h);
        let mut tiles = rows(h);
        let filled = filled(&surface, &mut tiles);
        let pieces = &tiles[tiles.len() - filled.pieces..];
        // Read independently: a cut piece whose whole blank would cross the edge (x = 0 or
        // x = w) by more than the cut tolerance was cut there; any other cut piece was cut
        // to the room only, even where it touches the edge.
        let at_edge = |t: &Tile| {
            let blank = Tile::new(TileKind::Full, Vec::new(), t.frame, t.size);
            outline::world_corners(&blank)
                .iter()
                .any(|p| p.x < -0.001 - 1e-9 || p.x > w + 0.001 + 1e-9)
        };
        let cut = pieces.iter().filter(|t| t.cut.is_some());
        let inside = cut.clone().filter(|t| !at_edge(t)).count();
        assert!(inside > 0, "no piece cut inside of {}", filled.pieces);
        assert!(cut.count() > inside, "no piece cut at the edge");
        assert_eq!(filled.inside_cuts, inside);
    }

    /// Share of the rectangle's area between the rows that some tile covers.
    fn between_covered(surface: &PolyMesh, tiles: &[Tile], h: f64) -> f64 {
        let (mut covered, mut total) = (0.0, 0.0);
        for face in surface.faces() {
            sample::face(surface.positions(), face, 0.02, |q, a| {
                if q.y > 0.15 && q.y < h - 0.15 && q.x < 1.15 {
                    total += a;
                    if tiles.iter().any(|t| covers(t, &q, 0.005)) {
                        covered += a;
                    }
                }
            });
        }
        covered / total
    }

    #[test]
    fn a_tear_is_filled_with_pieces_a_joint_from_the_tiles() {
        // Rows 320 mm apart: two courses of pieces (140 + 140 + three joints fit 310 mm).
        let h = 0.6;
        let surface = rectangle(1.16, h);
        let mut tiles = rows(h);
        assert!(between_covered(&surface, &tiles, h) < 0.01);
        let added = fill(&surface, &mut tiles);
        assert!(added >= 8, "{added}");
        let share = between_covered(&surface, &tiles, h);
        assert!(share > 0.85, "{share}");
        // No piece overlaps anything, each leaves a joint where it runs along another (not
        // where they only meet at a corner), and none is narrower than the narrowest kept
        // width.
        for (i, a) in tiles.iter().enumerate() {
            for b in &tiles[i + 1..] {
                let s = outline::separation(a, b);
                assert!(s.gap > 0.0, "{}", s.gap);
                assert!(!s.shares_joint(a, b) || s.gap > 0.01 - 1e-6, "{}", s.gap);
            }
            assert!(a.cut.as_ref().is_none_or(|c| c.kept_width() >= 0.028));
        }
        // The same input gives the same pieces.
        let mut again = rows(h);
        fill(&surface, &mut again);
        assert_eq!(again, tiles);
    }

    #[test]
    fn a_hole_wide_enough_is_filled_with_whole_tiles_continuing_the_courses() {
        // Rows 320 mm apart: two courses of whole tiles fit (140 + 140 + three joints of up
        // to 13 mm); pieces centred on the hole around each sample would be cut.
        let h = 0.6;
        let surface = rectangle(1.16, h);
        let mut tiles = rows(h);
        fill(&surface, &mut tiles);
        let whole = tiles[8..].iter().filter(|t| t.cut.is_none()).count();
        assert!(whole >= 5, "{whole} whole of {}", tiles.len() - 8);
        // The same on a curved sheet: the course is walked over the surface, so the
        // curvature does not draw its cells into each other (a cylinder of radius 1 m
        // across the rows).
        let curved = bent(1.16, h, 1.0);
        let mut on_curve = rows_along(h, |x, s| on_bent(x, s, h, 1.0));
        fill(&curved, &mut on_curve);
        let whole = on_curve[8..].iter().filter(|t| t.cut.is_none()).count();
        assert!(
            whole >= 6,
            "{whole} whole of {} on the curve",
            on_curve.len() - 8
        );
    }

    /// Three courses of 280 x 140 tiles with 10 mm joints on a flat sheet 1.15 x 0.44 m: the
    /// bottom and top ones whole, the middle one with a gap `g` between its first tile and
    /// the next two.
    fn course_with_a_gap(g: f64) -> (PolyMesh, Vec<Tile>) {
        let tile = |x: f64, y: f64| {
            let frame = Frame::from_normal(Point3::new(x, y, 0.0), Vector3::z(), &Vector3::x());
            Tile::new(TileKind::Full, vec![], frame, [0.28, 0.14, 0.015])
        };
        let mut tiles: Vec<Tile> = (0..4)
            .flat_map(|i| {
                let x = 0.14 + 0.29 * i as f64;
                [tile(x, 0.07), tile(x, 0.37)]
            })
            .collect();
        tiles.extend([tile(0.14, 0.22), tile(0.42 + g, 0.22), tile(0.71 + g, 0.22)]);
        (rectangle(1.15, 0.44), tiles)
    }

    /// Whether the centre of what `t` keeps lies within `reach` of `(x, y)` in both axes.
    fn kept_at(t: &Tile, x: f64, y: f64, reach: f64) -> bool {
        let c = outline::world_corners(t);
        let c = c.iter().fold(Vector3::zeros(), |s, p| s + p.coords) / c.len() as f64;
        (c.x - x).abs() < reach && (c.y - y).abs() < reach
    }

    #[test]
    fn a_hole_that_holds_a_half_takes_a_whole_half_with_its_joints_opened() {
        // A gap of 166 mm: a piece cut to the room would be 146 mm long; a half (140 mm)
        // leaves joints of 13 mm, within half a joint of the nominal one.
        let (surface, mut tiles) = course_with_a_gap(0.166);
        let before = tiles.len();
        let filled = filled(&surface, &mut tiles);
        let in_gap = |t: &Tile| kept_at(t, 0.363, 0.22, 0.05);
        let laid: Vec<&Tile> = tiles[before..].iter().filter(|t| in_gap(t)).collect();
        assert_eq!(laid.len(), 1, "{laid:?}");
        let half = laid[0];
        assert_eq!(half.kind, TileKind::Half);
        assert!(half.cut.is_none());
        assert_eq!(half.size, [0.14, 0.14, 0.015]);
        assert!(filled.halves >= 1);
        // Its joints, read independently: to the course's tiles beside it and the courses
        // above and below, every one within 5 mm of the joint and none narrower than 5 mm.
        for other in &tiles[..before] {
            let s = outline::separation(half, other);
            if s.gap < 0.03 {
                assert!((s.gap - 0.01).abs() <= 0.005 + 1e-9, "joint {}", s.gap);
            }
        }
        // The hole's piece is no cut on site.
        assert!(
            tiles[before..]
                .iter()
                .filter(|t| t.cut.is_some())
                .all(|t| !in_gap(t))
        );
    }

    #[test]
    fn a_hole_too_short_for_a_half_takes_a_piece_cut_to_it() {
        // A gap of 130 mm: 110 mm of room, 30 mm short of a half, is cut to the room.
        let (surface, mut tiles) = course_with_a_gap(0.13);
        let before = tiles.len();
        let filled = filled(&surface, &mut tiles);
        // The pieces whose kept outline's centre lies in the gap.
        let cut: Vec<&Tile> = tiles[before..]
            .iter()
            .filter(|t| kept_at(t, 0.345, 0.22, 0.03))
            .collect();
        assert_eq!(cut.len(), 1, "{cut:?}");
        assert_ne!(cut[0].kind, TileKind::Half);
        assert!(cut[0].cut.is_some());
        assert!(filled.inside_cuts >= 1);
        let s = outline::separation(cut[0], &tiles[8]);
        assert!((s.gap - 0.01).abs() < 1e-6, "{}", s.gap);
    }

    #[test]
    fn a_gap_too_narrow_for_a_piece_is_left_to_the_mortar() {
        // 40 mm between the rows: a piece would keep 20 mm between its joints.
        let h = 0.32;
        let surface = rectangle(1.16, h);
        let mut tiles = rows(h);
        assert_eq!(fill(&surface, &mut tiles), 0);
    }

    /// A flat sheet 0.44 m high and `w` long, courses of 280 x 140 tiles at the bottom and the
    /// top filled to `w` from its left edge, and a middle course, staggered half a tile, with
    /// a tile at each end and a gap of `g` between them.
    fn middle_course_with_a_gap(w: f64, g: f64) -> (PolyMesh, Vec<Tile>) {
        let tile = |x: f64, y: f64| {
            let frame = Frame::from_normal(Point3::new(x, y, 0.0), Vector3::z(), &Vector3::x());
            Tile::new(TileKind::Full, vec![], frame, [0.28, 0.14, 0.015])
        };
        let count = ((w + 0.01) / 0.29).floor() as usize;
        let mut tiles: Vec<Tile> = (0..count)
            .flat_map(|i| {
                let x = 0.14 + 0.29 * i as f64;
                [tile(x, 0.07), tile(x, 0.37)]
            })
            .collect();
        tiles.extend([tile(0.285, 0.22), tile(0.425 + g + 0.14, 0.22)]);
        (rectangle(w, 0.44), tiles)
    }

    #[test]
    fn a_long_hole_in_a_staggered_course_takes_standard_pieces_and_one_closer() {
        // 1.56 m between the course's two tiles, its courses staggered by half a tile: five
        // standard lengths and their joints take at most 1.46 m, and one piece cut to what is
        // left closes the course, as a mason lays it; every joint within half a joint of the
        // nominal one.
        let (w, g) = (2.35, 1.56);
        let (surface, mut tiles) = middle_course_with_a_gap(w, g);
        let before = tiles.len();
        filled(&surface, &mut tiles);
        let in_gap = |t: &&Tile| kept_at(t, 0.425 + g / 2.0, 0.22, g / 2.0);
        let laid: Vec<&Tile> = tiles[before..].iter().filter(in_gap).collect();
        let cut = laid.iter().filter(|t| t.cut.is_some()).count();
        let whole = laid.iter().filter(|t| t.cut.is_none()).count();
        assert_eq!(cut, 1, "{laid:?}");
        assert!(whole >= 4, "{whole} whole pieces");
        let length: f64 = laid.iter().map(|t| t.kept_area() / 0.14).sum();
        assert!(
            length >= g - 0.02 * (laid.len() as f64 + 1.0) - 1e-6,
            "{length}"
        );
        for piece in &laid {
            for other in &tiles {
                let s = outline::separation(piece, other);
                if !std::ptr::eq(*piece, other) && s.gap < 0.03 {
                    assert!(s.gap >= 0.005 - 1e-9, "joint {}", s.gap);
                }
            }
        }
    }

    #[test]
    fn a_piece_cut_at_one_end_only_is_slid_whole_into_the_room_beyond_the_other() {
        let surface = rectangle(1.2, 0.44);
        let boundary = SurfaceBoundary::new(&surface, 0.28);
        let tears = tears_on(&surface, &boundary);
        let at =
            |x: f64| Frame::from_normal(Point3::new(x, 0.22, 0.0), Vector3::z(), &Vector3::x());
        // A tile on [0, 0.28], and a piece laid on [0.21, 0.49]: cut a joint from the tile,
        // it keeps 200 mm, no standard length, and the room beyond its right end is free.
        let tiles = vec![Tile::new(
            TileKind::Full,
            vec![],
            at(0.14),
            [0.28, 0.14, 0.015],
        )];
        let outlines: Vec<_> = tiles.iter().map(outline::world_corners).collect();
        let q = Point3::new(0.4, 0.22, 0.0);
        let (cut, at_edge) = tears.piece(at(0.35), &tiles, &outlines, &[0], &q).unwrap();
        assert!(!at_edge);
        assert!(
            (cut.kept_area() - 0.2 * 0.14).abs() < 1e-9,
            "{}",
            cut.kept_area()
        );
        let whole = tears
            .standard(&cut, &tiles, &outlines, &[0], &q)
            .expect("a whole tile slid away from the cut");
        assert_eq!(
            (whole.kind, whole.size),
            (TileKind::Full, [0.28, 0.14, 0.015])
        );
        assert!(whole.cut.is_none());
        let s = outline::separation(&tiles[0], &whole);
        assert!((s.gap - 0.01).abs() < 1e-6, "joint {}", s.gap);
        // With a tile 0.20 m on beyond the piece's kept end, the room is cut at both ends and
        // holds no standard piece: nothing slides.
        let mut closed = tiles.clone();
        closed.push(Tile::new(
            TileKind::Full,
            vec![],
            at(0.64),
            [0.28, 0.14, 0.015],
        ));
        let outlines: Vec<_> = closed.iter().map(outline::world_corners).collect();
        let (cut, _) = tears
            .piece(at(0.35), &closed, &outlines, &[0, 1], &q)
            .unwrap();
        assert!(
            tears
                .standard(&cut, &closed, &outlines, &[0, 1], &q)
                .is_none()
        );
    }
}
