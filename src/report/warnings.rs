//! Warnings: input that is odd but valid, and results a designer must not take at face value.
//! Each has a stable code (its name in `report.json`, its number through the C ABI) and a
//! message that says what to do. The checks read the surface, the quad mesh, the tile and the
//! finished report; they never change a result.

use nalgebra::{Point3, Vector3};
use serde::Serialize;

use super::Report;
use crate::mesh::{PolyMesh, Topology};
use crate::tiles::{Support, TileSpec};

/// Why a result deserves a second look. The numbers are stable: new codes get new numbers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum WarningCode {
    /// The surface has no boundary (a sphere, a torus, a box).
    ClosedSurface = 1,
    /// The surface falls into several pieces that share no edge.
    SeveralPieces = 2,
    /// Most faces' normals point down: tiles are laid on the underside.
    NormalsDown = 3,
    /// The tile does not fit the half-tile model: length is not about 2 x width + joint.
    TileShape = 4,
    /// The surface turns a lot over one tile: its curvature radius is not much larger than a
    /// tile.
    TileVsCurvature = 5,
    /// The tiles cover less than [`MIN_COVERAGE`] of the surface.
    LowCoverage = 6,
    /// Tiles were left out: off the surface, or slivers.
    TilesDropped = 7,
    /// Nothing to lay the tiles from: a closed surface, or a level one lying on the ground.
    NoSupport = 8,
    /// Reading the file joined coincident vertices or removed faces (see
    /// [`crate::mesh::weld`]).
    VerticesWelded = 9,
    /// The fit stage cut more than [`MAX_FIT_CUT_SHARE`] of the tiles, counting the pieces
    /// cut to fill the holes it opened away from the edge: courses converge or diverge
    /// (domes, bends, around singularities) where rigid tiles cannot meet.
    FitCuts = 10,
    /// The joints stray far from the nominal joint: their p95 deviation is more than
    /// [`MAX_P95_DEVIATION_SHARE`] of the joint.
    WideJoints = 11,
    /// The surface folds back on itself: neighbouring faces turn by more than
    /// [`FOLD_ANGLE`] (a crumpled or overlapping stretch of the input mesh).
    FoldedSurface = 12,
    /// Reading the file turned faces over to agree with their neighbours (see
    /// [`crate::mesh::orient`]).
    NormalsUnified = 13,
    /// Fewer than [`MIN_QUAD_EDGES_WITHIN`] of the quad mesh's edges are within 20 % of half
    /// a tile (the paper's section 3.1 quad): its quads are not the tiles' size.
    QuadSize = 14,
    /// Tiles stand off the surface by more than [`MAX_LIFT`] times their thickness: the
    /// surface turns under them where the quads did not follow it (creases across the input's
    /// triangles, facets coarser than a tile).
    TilesOffSurface = 15,
    /// The surface has openings smaller than a tile: a gap in the mesh (a face missing from
    /// an STL) more often than a real opening; tiles are cut around them on site.
    SmallOpenings = 16,
    /// The surface faces along another axis than up and rises along it: a model whose up is
    /// Y (Blender's and Maya's OBJ export, glTF), tiled with up = Z.
    UpAxis = 17,
    /// The quad mesh does not lie on the surface the tiles are cut to: more than
    /// [`MAX_OFF_SURFACE_SHARE`] of its faces are farther than a tile's length from it (quads
    /// made from another surface, or the surface moved, scaled or in other units since).
    QuadsOffSurface = 18,
    /// Faces of more than four corners that are larger than a tile and not flat: the surface
    /// inside them is a guess (the fan of triangles from their first corner every stage
    /// reads them as, [`crate::geom::fan`]).
    CurvedPolygons = 19,
}

/// One warning.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Warning {
    /// What kind of trouble.
    pub code: WarningCode,
    /// What was found and what to do.
    pub message: String,
    /// The face of the surface the message names ([`face_label`]), counted from 0: in the
    /// mesh given, or in its file where the command line read one (welding renumbers faces).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub face: Option<usize>,
}

impl Warning {
    /// A warning with its message.
    pub fn new(code: WarningCode, message: impl Into<String>) -> Self {
        Self {
            code,
            message: message.into(),
            face: None,
        }
    }

    /// A warning whose message names `face` as [`face_label`] writes it.
    fn at_face(code: WarningCode, face: usize, message: String) -> Self {
        debug_assert!(message.contains(&face_label(face)));
        Self {
            face: Some(face),
            ..Self::new(code, message)
        }
    }

    /// The warning with the face it names renumbered by `number` (e.g. the mesh's faces as
    /// their file counts them, [`crate::mesh::FileNumbering::file_face`]), in the message
    /// too.
    pub fn renumbered(self, number: impl Fn(usize) -> usize) -> Self {
        let Some(face) = self.face else {
            return self;
        };
        let renamed = number(face);
        let (old, new) = (face_label(face), face_label(renamed));
        // The label as a word of its own: "face 1" is neither the start of "face 12" nor the
        // end of "surface 1".
        let at = self.message.match_indices(&old).find(|&(i, _)| {
            !self.message[i + old.len()..].starts_with(|c: char| c.is_ascii_digit())
                && !self.message[..i].ends_with(|c: char| c.is_alphanumeric())
        });
        let message = match at {
            Some((i, _)) => format!(
                "{}{new}{}",
                &self.message[..i],
                &self.message[i + old.len()..]
            ),
            None => self.message,
        };
        Self {
            message,
            face: Some(renamed),
            ..self
        }
    }
}

/// How a warning's message names a face: "face 12".
fn face_label(face: usize) -> String {
    format!("face {face}")
}

/// Angle (radians) between the normals of two faces sharing an edge beyond which the
/// surface folds back on itself: 120 degrees, where a crease (a box's edge turns by 90) has
/// become a fold no shell is built with.
pub const FOLD_ANGLE: f64 = 2.0 * std::f64::consts::FRAC_PI_3;

/// Share of the tiles the fit stage may cut before the tiling is flagged (issue 16's limit:
/// cutting is what the method minimises).
pub const MAX_FIT_CUT_SHARE: f64 = 0.01;

pub use crate::tiles::fit::MAX_P95_DEVIATION_SHARE;

/// How far a tile may stand off the surface, in tile thicknesses, before it is counted
/// (`cutting.lifted_tiles`) and flagged: a tile a whole thickness off its bed is not laid on
/// the surface but across it. A flat 280 x 140 mm tile stands off a surface of radius 1.6 m
/// by 6 mm at its corners, under the 15 mm of a usual tile; the shells of the README's table
/// whose creases the remesher splits stand off by at most 26 mm (a sliver of web at a groin
/// vault's springing), a cloister vault whose valleys cross its triangles by 160 mm.
pub const MAX_LIFT: f64 = 1.0;

/// Coverage below which a tiling is flagged.
pub const MIN_COVERAGE: f64 = 0.95;

/// How far a tile's length may be from `2 x width + joint` (as a fraction of the length)
/// before the half-tile model (paper section 3.1: quads of half a tile, square within the
/// joint) stops fitting.
pub const TILE_SHAPE_TOLERANCE: f64 = 0.1;

/// Turning angle (radians) over one tile length, at the 90th percentile of the quad mesh's
/// edges, above which tiles gape: about 29 degrees, a curvature radius of twice the tile
/// length.
pub const MAX_TURN_PER_TILE: f64 = 0.5;

/// Share of quad edges within 20 % of the quads' target ([`TileSpec::quad_edge`]) below which the
/// quads are flagged. The remesher promises 95 % on surfaces that allow it, and a patch of
/// a torus, curved both ways, gets 82 % with tiles that still fit (p95 2.1 mm); QuadriFlow's
/// quads of the shared shells have 90-97 %; a direction field whose rows converge all over a
/// dome left 25-45 % until such lattices were solved again from a coarse start (84 % since),
/// a strip narrower than a tile leaves 66 %, quads made for another tile far less.
pub const MIN_QUAD_EDGES_WITHIN: f64 = 0.7;

/// Quads far from half a tile: tiles on them overlap, gape or are cut, whatever the fit does.
/// Measured against both edges the quads may have been made for ([`TileSpec::quad_edge`]:
/// half a tile, or a course's height in level courses), the better share counting.
pub fn quad_size(quads: &PolyMesh, spec: &TileSpec) -> Option<Warning> {
    if quads.face_count() == 0 {
        return None;
    }
    let (share, t) = [spec.quad_edge(false), spec.quad_edge(true)]
        .map(|t| (crate::remesh::edges_within_20pct(quads, t), t))
        .into_iter()
        .fold((f64::NEG_INFINITY, 0.0), |best, x| {
            if x.0 > best.0 { x } else { best }
        });
    quad_size_of(share, t)
}

/// The [`WarningCode::QuadSize`] warning for quads of which `share` of the edges are within
/// 20 % of the target edge `t` (the remesher's own figure, `Metrics::edges_within_20pct`).
pub fn quad_size_of(share: f64, t: f64) -> Option<Warning> {
    (share < MIN_QUAD_EDGES_WITHIN).then(|| {
        Warning::new(
            WarningCode::QuadSize,
            format!(
                "only {:.0} % of the quad edges are within 20 % of the target edge ({t}): tiles on quads this far from their size overlap, gape or are cut; usual causes are a direction field whose rows converge everywhere (--direction or --field along a dome's rings or meridians), quads made for another tile, or units; remesh with the curvature field (no --direction or --field) or look at the quads",
                (100.0 * share).floor(),
                t = (t * 1e6).round() / 1e6
            ),
        )
    })
}

/// The checks of the joints a tiling leaves: cuts by the fit stage, and joints far from
/// the nominal one (both measured as the report measures them, after the fit when it ran).
pub fn joint_checks(report: &Report) -> Vec<Warning> {
    let mut out = Vec::new();
    let j = &report.joints;
    let tiles = report.full_tiles + report.half_tiles;
    // Pieces cut to fill the fit's tears away from the edge are cuts of the fit too.
    let tear_cuts = report.cutting.as_ref().map_or(0, |c| c.tear_cuts);
    let cut = report.fit_cut_count();
    if tiles > 0 && cut as f64 > MAX_FIT_CUT_SHARE * tiles as f64 {
        out.push(Warning::new(
            WarningCode::FitCuts,
            format!(
                "{} tiles had to be cut to fit (cut list: C labels) and {tear_cuts} pieces cut to fill the holes it opened (cutting.tear_cuts): {:.1} % of the {tiles} full and half tiles; courses converge or diverge here (a dome's crown, a bend, around the quad mesh's singularities) and rigid tiles cannot meet; look at gaps.svg, and try another field direction (--direction, --field) or another placement of its cones (--renormalisation 1 or 0.25; run tries both unless told --tries 1), or lay those parts by hand (--exclude)",
                j.fit_cuts,
                100.0 * cut as f64 / tiles as f64
            ),
        ));
    }
    if j.contacts > 0 && j.joint > 0.0 && j.p95_deviation > MAX_P95_DEVIATION_SHARE * j.joint {
        out.push(Warning::new(
            WarningCode::WideJoints,
            format!(
                "the joints stray from the nominal joint: p95 |gap - joint| is {:.2} joint widths and the widest gap {:.0} joint widths (report: joints, in model units); wedge-shaped joints open where courses converge, and a course closed on itself (a ring round a tower, a drum or a dome) whose length is not a whole number of tiles spreads the difference over its head joints, so look at gaps.svg before laying, and fill or cut where it is red",
                j.p95_deviation / j.joint,
                j.max_gap / j.joint
            ),
        ));
    }
    out
}

/// The checks of the input and of a finished tiling: `surface` is the surface the tiles were
/// cut to (the quad mesh when there is none), `up` the laying order's up direction.
pub fn check(
    quads: &PolyMesh,
    surface: &PolyMesh,
    spec: &TileSpec,
    up: &Vector3<f64>,
    report: &Report,
) -> Vec<Warning> {
    let mut out = Vec::new();
    out.extend(surface_checks(surface, up, spec));
    if !std::ptr::eq(quads, surface) {
        out.extend(quads_off_surface(quads, surface, spec));
    }
    out.extend(tile_shape(spec));
    out.extend(curvature(quads, spec));
    out.extend(quad_size(quads, spec));
    if let Some(c) = &report.cutting {
        if c.coverage < MIN_COVERAGE {
            out.push(Warning::new(
                WarningCode::LowCoverage,
                format!(
                    "the tiles cover {:.3} of the surface (below {MIN_COVERAGE}): look at the pattern picture; usual causes are quads far from half a tile (remesh), mesh and tile in different units, a surface in pieces or full of holes, or quads made from another surface than the one given to cut the tiles to",
                    c.coverage
                ),
            ));
        }
        if c.lifted_tiles > 0 {
            out.push(Warning::new(
                WarningCode::TilesOffSurface,
                format!(
                    "{} tiles stand off the surface by more than their thickness ({}), the farthest by {:.3} (report: cutting.lifted_tiles, cutting.largest_lift, model units): the surface turns under them where the quads did not, usually a crease that crosses the input's triangles (creases are split only along mesh edges) or facets coarser than a tile; remesh the input with its edges along the creases, or finer, or split it at the creases and tile each part",
                    c.lifted_tiles,
                    report.tile.thickness,
                    c.largest_lift
                ),
            ));
        }
        let dropped = c.outside_tiles + c.slivers.len();
        if dropped > 0 {
            // After the fit, holes wide enough for a piece are filled with pieces cut to the
            // room left (the tear fill); without it, or where a piece would be a sliver, by
            // hand.
            let filled = if report.fit.is_some() {
                "holes wide enough for a piece are filled with pieces cut to the room left (cutting.tear_pieces), narrower ones with mortar or by hand"
            } else {
                "the gaps they leave are filled by hand"
            };
            out.push(Warning::new(
                WarningCode::TilesDropped,
                format!(
                    "{dropped} tiles were left out ({} off the surface, {} slivers narrower than the smallest kept width): {filled} (report: cutting.slivers)",
                    c.outside_tiles,
                    c.slivers.len()
                ),
            ));
        }
    }
    out.extend(joint_checks(report));
    if let Some(s) = &report.sequence {
        let closed = out.iter().any(|w| w.code == WarningCode::ClosedSurface);
        out.extend(no_support(s.support, closed));
    }
    out.sort_by_key(|w| w.code);
    out
}

/// Share of the quad mesh's faces that may lie farther than a tile's length from the surface
/// before [`WarningCode::QuadsOffSurface`] is raised: a twentieth. Quads made from the surface
/// lie on it (the remesher's farthest vertex is about half a quad edge off it, where quads
/// close over a notch); a few may stand out past its edge.
pub const MAX_OFF_SURFACE_SHARE: f64 = 0.05;

/// Faces of the quad mesh whose distance to the surface [`quads_off_surface`] measures at
/// most (every k-th face on larger meshes), so that the check stays a small part of a run.
const OFF_SURFACE_SAMPLES: usize = 20_000;

/// The [`WarningCode::QuadsOffSurface`] check: the centres of (at most
/// [`OFF_SURFACE_SAMPLES`] of) the faces of `quads` are measured to `surface`, and a share
/// beyond [`MAX_OFF_SURFACE_SHARE`] farther than the tile's length raises the warning, with
/// the farthest centre.
pub fn quads_off_surface(quads: &PolyMesh, surface: &PolyMesh, spec: &TileSpec) -> Option<Warning> {
    if quads.face_count() == 0 || surface.face_count() == 0 {
        return None;
    }
    let index = crate::geom::SurfaceIndex::from_polymesh(surface);
    let step = quads.face_count().div_ceil(OFF_SURFACE_SAMPLES).max(1);
    let (mut sampled, mut off) = (0usize, 0usize);
    let mut farthest = (0.0_f64, Point3::origin());
    for f in (0..quads.face_count()).step_by(step) {
        let centre = quads.face_centroid(f);
        let distance = index
            .closest(&centre.coords)
            .map_or(f64::INFINITY, |q| (q.point - centre.coords).norm());
        sampled += 1;
        if distance > spec.length {
            off += 1;
        }
        if distance > farthest.0 {
            farthest = (distance, centre);
        }
    }
    let share = off as f64 / sampled as f64;
    (share > MAX_OFF_SURFACE_SHARE).then(|| {
        let (d, at) = farthest;
        Warning::new(
            WarningCode::QuadsOffSurface,
            format!(
                "{:.0} % of the quads lie farther than a tile's length ({}) from the surface the tiles are cut to, the farthest {d:.3} away (its centre at ({:.3}, {:.3}, {:.3})): the quads were not made from this surface, or it was moved, scaled or changed to other units since; give the surface the quads were remeshed from, or remesh this one (the tiles here are cut to a surface they do not lie on)",
                100.0 * share,
                spec.length,
                at.x,
                at.y,
                at.z
            ),
        )
    })
}

/// What the laying order stands on, when it is nothing a vault stands on: a surface without
/// boundary (`closed`, or an open one whose openings the quads closed over) or a level one.
fn no_support(support: Support, closed: bool) -> Option<Warning> {
    let message = match support {
        Support::Edges => return None,
        Support::NoBoundary if closed => {
            "the quad mesh has no boundary, so no tile stands on a support and the laying order's props mean nothing: open the surface where the vault stands"
        }
        Support::NoBoundary => {
            "the quad mesh has no boundary although the surface has: its openings are too small for the quads, which closed over them (the tiles are still cut to them), so no tile stands on a support and the laying order's props mean nothing; open the surface where the vault stands, at least a few tiles wide, or remesh with smaller quads"
        }
        Support::Level => {
            "the surface is level (it rises less than the support band): every tile lies on the ground or formwork and none needs a prop; give --up (up) if the vault stands another way"
        }
    };
    Some(Warning::new(WarningCode::NoSupport, message))
}

/// Checks of the surface alone, against the tile of `spec`: closed, in pieces (and whether
/// the pieces are layers closer than a tile's width), with openings smaller than a tile,
/// folded, facing sideways or upside down.
pub fn surface_checks(surface: &PolyMesh, up: &Vector3<f64>, spec: &TileSpec) -> Vec<Warning> {
    let mut out = Vec::new();
    let topology = Topology::new(surface).expect("a PolyMesh is manifold by construction");
    if !topology.edges().iter().any(|e| e.is_boundary()) {
        out.push(Warning::new(
            WarningCode::ClosedSurface,
            "the surface is closed (it has no boundary edge): a vault needs an edge to stand on, and quads on sharp edges leave the surface; remove the faces where the shell stands or meets the ground, and tile the shell only",
        ));
    }
    let areas = topology.piece_areas(surface);
    let (piece, pieces) = (&areas.piece, areas.areas.len());
    if pieces > 1 {
        let mut sizes = vec![0usize; pieces];
        piece.iter().for_each(|&p| sizes[p] += 1);
        // The piece of the most area, and its faces.
        let main = areas.main();
        let largest = sizes[main];
        let width = spec.width;
        let debris = 1.0 - areas.main_share();
        let advice = match stacked(surface, piece, width) {
            // Stray faces around one surface: debris of an export or a scan. Pieces that
            // meet the main one at a vertex are patches to weld, not strays.
            None if pieces > 2
                && debris < DEBRIS_SHARE
                && !meets_main_piece(surface, piece, main) =>
            {
                let share = 100.0 * debris;
                let share = if share < 0.01 {
                    "under 0.01".to_owned()
                } else {
                    format!("{share:.2}")
                };
                format!(
                    "all but the largest are small, together {share} % of the area: stray faces an export or a scan left around the surface, most too small for a tile; delete them unless they belong to the shell (Rhino: SplitDisjointMesh, then delete the small pieces)"
                )
            }
            Some(layers) => format!(
                "{:.0} % of its area lies within a tile's width ({width}) of another piece across the surface (on average {:.3} apart, e.g. near ({:.3}, {:.3}, {:.3})): the pieces are layers on top of each other, such as a thick shell's two faces or a surface exported twice, and the tiles fall on both; keep only the layer the tiles are laid on",
                100.0 * layers.share,
                layers.gap,
                layers.at.x,
                layers.at.y,
                layers.at.z
            ),
            None => "if they should be one surface, weld them (a mesh of a polysurface or of joined meshes keeps each face's own vertices along the seams: in Rhino Weld it, or Join and Weld; the command line welds coincident vertices unless --weld off, raise the tolerance with --weld; from arrays: tp_mesh_new_welded, Python tp.weld, C# PolyMesh.Welded); otherwise tile each piece on its own".to_string(),
        };
        out.push(Warning::new(
            WarningCode::SeveralPieces,
            format!(
                "the surface has {pieces} separate pieces (the largest {largest} of {} faces) that share no edge: {advice}",
                surface.face_count()
            ),
        ));
    }
    out.extend(small_openings(
        surface,
        &topology,
        (piece, pieces),
        spec.length,
    ));
    out.extend(folds(surface, &topology));
    out.extend(curved_polygons(surface, spec));
    out.extend(up_axis(surface, up));
    if let Some(up) = up.try_normalize(0.0) {
        let (mut signed, mut projected, mut area) = (0.0, 0.0, 0.0);
        for f in 0..surface.face_count() {
            let a = surface.face_area_vector(f);
            signed += a.dot(&up);
            projected += a.dot(&up).abs();
            area += a.norm();
        }
        if projected > 0.1 * area && signed < -0.5 * projected {
            out.push(Warning::new(
                WarningCode::NormalsDown,
                "most face normals point down (against up): tiles are laid on the side the normals point to, the underside here; flip the mesh (Rhino: Flip) unless the tiles belong underneath",
            ));
        }
    }
    out
}

/// Openings of the surface smaller than a tile of `length` (every vertex of the boundary
/// around one within that distance of every other, and of half the size of its piece): a
/// face missing from the input (STL soups lose them) more often than a real opening, and the
/// tiles over it are cut around it. Named with the largest one's size and place.
/// `pieces` is [`Topology::face_pieces`] of `topology`, the surface's.
fn small_openings(
    surface: &PolyMesh,
    topology: &Topology,
    (piece, pieces): (&[usize], usize),
    length: f64,
) -> Option<Warning> {
    let edges = topology.edges();
    let positions = surface.positions();
    // Each piece's size: a boundary as large as half its piece is the piece's outline (a
    // loose triangle of an unwelded soup), not an opening in it.
    let mut extent = vec![
        (
            Vector3::repeat(f64::INFINITY),
            Vector3::repeat(f64::NEG_INFINITY)
        );
        pieces
    ];
    for (f, face) in surface.faces().iter().enumerate() {
        let (lo, hi) = &mut extent[piece[f]];
        for &v in face {
            *lo = lo.inf(&positions[v].coords);
            *hi = hi.sup(&positions[v].coords);
        }
    }
    let mut seen = vec![false; edges.len()];
    let mut small: Vec<(f64, Point3<f64>, usize)> = Vec::new();
    for start in 0..edges.len() {
        if seen[start] || !edges[start].is_boundary() {
            continue;
        }
        // The boundary edges connected to this one: one opening (or the outer edge).
        seen[start] = true;
        let (mut stack, mut vertices, mut count) = (vec![start], Vec::new(), 0usize);
        while let Some(e) = stack.pop() {
            count += 1;
            for &v in &edges[e].vertices {
                vertices.push(v);
                for &next in topology.vertex_edges(v) {
                    if !seen[next] && edges[next].is_boundary() {
                        seen[next] = true;
                        stack.push(next);
                    }
                }
            }
        }
        vertices.sort_unstable();
        vertices.dedup();
        let points: Vec<Point3<f64>> = vertices.iter().map(|&v| positions[v]).collect();
        let (lo, hi) = extent[piece[edges[start].faces[0]]];
        let limit = length.min(0.5 * (hi - lo).norm());
        if let Some(across) = diameter_within(&points, limit) {
            let centre = points
                .iter()
                .fold(Vector3::zeros(), |acc, p| acc + p.coords)
                / points.len() as f64;
            small.push((across, Point3::from(centre), count));
        }
    }
    let (across, at, count) = *small.iter().max_by(|a, b| a.0.total_cmp(&b.0))?;
    let (openings, largest, it, gap) = match small.len() {
        1 => (
            "an opening".to_string(),
            "",
            "it",
            "it is a gap in the mesh (a face missing from an STL)",
        ),
        n => (
            format!("{n} openings"),
            "the largest ",
            "them",
            "they are gaps in the mesh (faces missing from an STL)",
        ),
    };
    Some(Warning::new(
        WarningCode::SmallOpenings,
        format!(
            "the surface has {openings} smaller than a tile (its length {length}), {largest}{across:.3} across, bounded by {count} edges, near ({:.3}, {:.3}, {:.3}): the tiles over {it} are cut around {it} on site; if {gap}, fill {it} (Rhino: FillMeshHoles) and tile again",
            at.x, at.y, at.z
        ),
    ))
}

/// The largest distance between two of `points` when it is below `limit`, else `None`.
fn diameter_within(points: &[Point3<f64>], limit: f64) -> Option<f64> {
    let mut largest = 0.0_f64;
    for (i, p) in points.iter().enumerate() {
        for q in &points[i + 1..] {
            largest = largest.max((p - q).norm());
            if largest >= limit {
                return None;
            }
        }
    }
    Some(largest)
}

/// A surface that faces sideways along a coordinate axis and rises along it, as a vault
/// modelled with Y up (Blender's and Maya's OBJ export, glTF) and tiled with up = Z: its
/// courses run level to the wrong axis and its laying order starts from the wrong edge. Said
/// when the faces' summed area vector is over [`FACING_SHARE`] of their area, within 37
/// degrees of the axis's positive side and more than 73 degrees from `up`, and the surface's
/// extent along the axis is over a twentieth of its largest (a flat wall has none). A wall
/// bent in plan has the same shape as such a vault, so the message says what to do in both
/// cases.
fn up_axis(surface: &PolyMesh, up: &Vector3<f64>) -> Option<Warning> {
    let up = up.try_normalize(0.0)?;
    let (mut sum, mut area) = (Vector3::zeros(), 0.0);
    for f in 0..surface.face_count() {
        let a = surface.face_area_vector(f);
        sum += a;
        area += a.norm();
    }
    if !(area > 0.0 && sum.norm() > FACING_SHARE * area) {
        return None;
    }
    let facing = sum.normalize();
    let k = facing.iamax();
    let axis = Vector3::ith(k, 1.0);
    if facing[k] < 0.8 || facing.dot(&up).abs() > 0.3 || axis.dot(&up).abs() > 0.9 {
        return None;
    }
    let (lo, hi) = surface.positions().iter().fold(
        (
            Vector3::repeat(f64::INFINITY),
            Vector3::repeat(f64::NEG_INFINITY),
        ),
        |(lo, hi), q| (lo.inf(&q.coords), hi.sup(&q.coords)),
    );
    let extent = hi - lo;
    if extent[k] <= 0.05 * extent.max() {
        return None;
    }
    let name = ["X", "Y", "Z"][k];
    let mut given = [0.0; 3];
    given[k] = 1.0;
    Some(Warning::new(
        WarningCode::UpAxis,
        format!(
            "the surface faces sideways, along {name} (its area seen along {name} is {:.0} % of its area; up ({:.2}, {:.2}, {:.2}) is {:.0} degrees from that), and rises along {name}: if it is a vault modelled with {name} up (Blender's and Maya's OBJ export, glTF), give --up {},{},{} (up), or its courses run level to the wrong axis and the laying order starts from the wrong edge; a wall standing on its foot is tiled as it is",
            100.0 * sum.norm() / area,
            up.x,
            up.y,
            up.z,
            facing.dot(&up).clamp(-1.0, 1.0).acos().to_degrees(),
            given[0],
            given[1],
            given[2]
        ),
    ))
}

/// Faces of five corners or more that span more than a tile's length and whose corners stand
/// off their mean plane by more than a tile's thickness. Every stage reads a polygon as the
/// fan of triangles from its first corner ([`crate::geom::fan`]), which is the surface only
/// where the polygon is flat; a large curved one (a vault's whole rim drawn as one face)
/// folds into needles, its quads and tiles with it (one such 40-gon: coverage 0.137 and no
/// word but the coverage). A small face of a vault meshed in hexagons bends less than a
/// tile's thickness, and one smaller than a tile cannot mislead a tile much.
fn curved_polygons(surface: &PolyMesh, spec: &TileSpec) -> Option<Warning> {
    let mut count = 0usize;
    let mut worst: Option<(f64, usize, f64)> = None;
    for (f, face) in surface.faces().iter().enumerate() {
        if face.len() < 5 {
            continue;
        }
        let corners: Vec<Vector3<f64>> = face
            .iter()
            .map(|&v| surface.positions()[v].coords)
            .collect();
        let centre = corners.iter().sum::<Vector3<f64>>() / corners.len() as f64;
        let across = 2.0
            * corners
                .iter()
                .map(|c| (c - centre).norm())
                .fold(0.0, f64::max);
        let Some(normal) = surface.face_area_vector(f).try_normalize(0.0) else {
            continue;
        };
        let off = corners
            .iter()
            .map(|c| (c - centre).dot(&normal).abs())
            .fold(0.0, f64::max);
        if across > spec.length && off > spec.thickness {
            count += 1;
            if worst.is_none_or(|(o, _, _)| off > o) {
                worst = Some((off, f, across));
            }
        }
    }
    let (off, face, across) = worst?;
    let corners = surface.faces()[face].len();
    Some(Warning::at_face(
        WarningCode::CurvedPolygons,
        face,
        format!(
            "{count} {} of more than four corners {} larger than a tile and not flat ({}, counted from 0: {corners} corners, {across:.3} across, standing up to {off:.3} off its plane): the surface inside such a face is read as a fan of triangles from its first corner, which is not the shell you drew and folds where the face is large; give the surface as triangles or quads (mesh it in the modeller, e.g. Rhino's Mesh with a small maximum edge, or triangulate those faces)",
            if count == 1 { "face" } else { "faces" },
            if count == 1 { "is" } else { "are" },
            face_label(face)
        ),
    ))
}

/// Share of the surface's area its summed area vector must reach for [`up_axis`] to read
/// which way it faces (a hemisphere's is a half, a barrel vault's two thirds).
const FACING_SHARE: f64 = 0.3;

/// Pieces of a surface lying on top of each other ([`stacked`]).
struct Layers {
    /// Share of the surface's area over or under another piece.
    share: f64,
    /// Mean distance between them there.
    gap: f64,
    /// A face centroid there.
    at: Point3<f64>,
}

/// Whether pieces of `surface` (`piece` per face) lie on top of each other: faces with a
/// point of another piece within `reach` along their normal (within 37 degrees of it), more
/// than [`STACKED_SHARE`] of the area. A thick shell exported with both its faces, or a
/// surface exported twice a little apart, has its tiles laid on both layers.
fn stacked(surface: &PolyMesh, piece: &[usize], reach: f64) -> Option<Layers> {
    let pos: Vec<Vector3<f64>> = surface.positions().iter().map(|p| p.coords).collect();
    let (face_of, tris): (Vec<usize>, Vec<[usize; 3]>) = crate::geom::fan(surface).unzip();
    let bvh = crate::geom::Bvh::of_simplices(&pos, &tris);
    let (mut over, mut total, mut gaps) = (0.0, 0.0, 0.0);
    let mut at = None;
    // Every face up to STACKED_SAMPLES, evenly spread beyond (a fine mesh in two layers asks
    // hundreds of closest points per face).
    let step = surface.face_count().div_ceil(STACKED_SAMPLES).max(1);
    for f in (0..surface.face_count()).step_by(step) {
        let area = surface.face_area_vector(f);
        total += area.norm();
        let Some(normal) = area.try_normalize(0.0) else {
            continue;
        };
        let c = surface.face_centroid(f).coords;
        let nearest = bvh
            .within(&c, reach)
            .into_iter()
            .filter(|&t| piece[face_of[t]] != piece[f])
            .map(|t| {
                let [a, b, d] = tris[t];
                crate::geom::closest::on_triangle(&c, &pos[a], &pos[b], &pos[d]) - c
            })
            .filter(|d| d.norm() <= reach && d.dot(&normal).abs() >= 0.8 * d.norm())
            .map(|d| d.norm())
            .reduce(f64::min);
        if let Some(gap) = nearest {
            over += area.norm();
            gaps += gap * area.norm();
            at.get_or_insert(Point3::from(c));
        }
    }
    (total > 0.0 && over > STACKED_SHARE * total).then(|| Layers {
        share: over / total,
        gap: gaps / over,
        at: at.expect("some face is over another"),
    })
}

/// Whether a vertex of a piece other than `main` lies on a vertex of piece `main` (within
/// the command line's weld tolerance of the mesh's size): unwelded patches of one surface
/// meet so along their seams, stray faces do not.
fn meets_main_piece(surface: &PolyMesh, piece: &[usize], main: usize) -> bool {
    let (lo, hi) = surface.bounding_box();
    let reach = crate::mesh::weld::DEFAULT_RELATIVE_TOLERANCE * (hi - lo).norm();
    let mut of_main = vec![false; surface.positions().len()];
    let mut of_others = vec![false; surface.positions().len()];
    for (f, face) in surface.faces().iter().enumerate() {
        let on = if piece[f] == main {
            &mut of_main
        } else {
            &mut of_others
        };
        face.iter().for_each(|&v| on[v] = true);
    }
    let positions = surface.positions();
    let main_points: Vec<usize> = (0..positions.len()).filter(|&v| of_main[v]).collect();
    let grid = crate::geom::HashGrid::of_points(
        reach.max(f64::MIN_POSITIVE) * 4.0,
        main_points.iter().map(|&v| [positions[v]]),
    );
    (0..positions.len()).filter(|&v| of_others[v]).any(|v| {
        of_main[v]
            || grid
                .near(&positions[v], reach)
                .into_iter()
                .any(|k| (positions[main_points[k]] - positions[v]).norm() <= reach)
    })
}

/// Share of the area that all pieces but the largest may hold together for the
/// several-pieces warning to call them debris around one surface rather than parts to weld.
const DEBRIS_SHARE: f64 = 0.02;

/// Share of a surface's area over or under another of its pieces from which [`stacked`]
/// calls the pieces layers.
const STACKED_SHARE: f64 = 0.05;

/// The most faces [`stacked`] looks at.
const STACKED_SAMPLES: usize = 20_000;

/// Edges where the surface folds back on itself ([`FOLD_ANGLE`]), with the sharpest one's
/// place: quads and tiles there fold over each other, and the fit cuts them.
fn folds(surface: &PolyMesh, topology: &Topology) -> Option<Warning> {
    let normals = unit_normals(surface);
    let limit = FOLD_ANGLE.cos();
    let mut count = 0usize;
    let mut sharpest: Option<(f64, usize)> = None;
    for e in topology.edges() {
        let [f, g] = e.faces[..] else { continue };
        let (Some(a), Some(b)) = (normals[f], normals[g]) else {
            continue;
        };
        let turn = a.dot(&b);
        if turn < limit {
            count += 1;
            if sharpest.is_none_or(|(worst, _)| turn < worst) {
                sharpest = Some((turn, f));
            }
        }
    }
    let (turn, face) = sharpest?;
    let at = surface.face_centroid(face);
    let edges = if count == 1 { "edge" } else { "edges" };
    Some(Warning::at_face(
        WarningCode::FoldedSurface,
        face,
        format!(
            "the surface folds back on itself at {count} {edges} (neighbouring faces turned by more than {:.0} degrees; the sharpest, {:.0} degrees, at {} near ({:.3}, {:.3}, {:.3})): quads and tiles there fold over each other and are cut or left out; smooth or rebuild the mesh there",
            FOLD_ANGLE.to_degrees(),
            turn.clamp(-1.0, 1.0).acos().to_degrees(),
            face_label(face),
            at.x,
            at.y,
            at.z
        ),
    ))
}

/// Every face's unit normal (`None` for a face of no area).
fn unit_normals(mesh: &PolyMesh) -> Vec<Option<Vector3<f64>>> {
    (0..mesh.face_count())
        .map(|f| mesh.face_area_vector(f).try_normalize(0.0))
        .collect()
}

/// The half-tile model: a tile over two quads of side `(length + joint) / 2` that are also
/// `width + joint` wide, so `length = 2 x width + joint`.
pub fn tile_shape(spec: &TileSpec) -> Option<Warning> {
    let fits = 2.0 * spec.width + spec.joint;
    if (spec.length - fits).abs() <= TILE_SHAPE_TOLERANCE * spec.length {
        return None;
    }
    let hint = if spec.length < spec.width {
        "the length is shorter than the width: are they swapped? Give the length first"
    } else {
        "the tiles will overlap or leave wide gaps; use a tile about twice as long as wide (plus a joint)"
    };
    Some(Warning::new(
        WarningCode::TileShape,
        format!(
            "tile {} x {} with joint {} does not fit the half-tile model (length = 2 x width + joint = {}, off by more than {:.0} %): {hint}",
            size(spec.length),
            size(spec.width),
            size(spec.joint),
            size(fits),
            100.0 * TILE_SHAPE_TOLERANCE
        ),
    ))
}

/// A size as a person writes it: six digits at most, those before the point included, and no
/// trailing zeros (0.29, not 0.29000000000000004 as 2 x 0.14 + 0.01 sums).
fn size(value: f64) -> String {
    // Digits before the point (none below 1), the rest of the six after it.
    let whole = if value.abs() >= 1.0 {
        value.abs().log10().floor() as usize + 1
    } else {
        0
    };
    let text = format!("{value:.*}", 6usize.saturating_sub(whole));
    let text = if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        text
    };
    if text == "-0" { "0".into() } else { text }
}

/// The surface's turning over one tile length, from the angles between neighbouring quads.
pub fn curvature(quads: &PolyMesh, spec: &TileSpec) -> Option<Warning> {
    let topology = Topology::new(quads).expect("a PolyMesh is manifold by construction");
    let normals = unit_normals(quads);
    let mut curvatures: Vec<f64> = topology
        .edges()
        .iter()
        .filter_map(|e| match e.faces[..] {
            [f, g] => {
                let (a, b) = (normals[f]?, normals[g]?);
                let distance = (quads.face_centroid(f) - quads.face_centroid(g)).norm();
                (distance > 0.0).then(|| a.angle(&b) / distance)
            }
            _ => None,
        })
        .collect();
    if curvatures.is_empty() {
        return None;
    }
    curvatures.sort_by(f64::total_cmp);
    let p90 = curvatures[(curvatures.len() * 9 / 10).min(curvatures.len() - 1)];
    let turn = p90 * spec.length;
    (turn > MAX_TURN_PER_TILE).then(|| {
        Warning::new(
            WarningCode::TileVsCurvature,
            format!(
                "the surface turns by {:.0} degrees over one tile length (curvature radius about {:.3} against a tile {} long, at the 90th percentile of the quads' edges): tiles will gape and leave the surface; use smaller tiles or a smoother surface",
                turn.to_degrees(),
                1.0 / p90,
                spec.length
            ),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generate;

    const TILE: TileSpec = TileSpec {
        length: 1.9,
        width: 0.95,
        thickness: 0.1,
        joint: 0.1,
    };

    /// A 280 x 140 x 15 mm tile with a 10 mm joint, in metres.
    const BRICK: TileSpec = TileSpec {
        length: 0.28,
        width: 0.14,
        thickness: 0.015,
        joint: 0.01,
    };

    /// [`small_openings`] of `mesh` for a tile of `length`.
    fn openings(mesh: &PolyMesh, length: f64) -> Option<Warning> {
        let topology = Topology::new(mesh).expect("a manifold mesh");
        let (piece, pieces) = topology.face_pieces();
        small_openings(mesh, &topology, (&piece, pieces), length)
    }

    #[test]
    fn the_half_tile_model_is_checked() {
        assert!(tile_shape(&TILE).is_none());
        let swapped = TileSpec {
            length: 0.95,
            width: 1.9,
            ..TILE
        };
        let w = tile_shape(&swapped).unwrap();
        assert!(w.message.starts_with("tile 0.95 x 1.9 with joint 0.1 does not fit the half-tile model (length = 2 x width + joint = 3.9,"), "{}", w.message);
        assert!(w.message.contains("swapped"), "{}", w.message);
        let long = TileSpec {
            length: 3.0,
            width: 1.0,
            ..TILE
        };
        assert_eq!(tile_shape(&long).unwrap().code, WarningCode::TileShape);
        assert_eq!(
            [
                size(2.0 * 0.14 + 0.01),
                size(280.0),
                size(1234.5678),
                size(0.000_123_456_7),
                size(-0.0)
            ],
            ["0.29", "280", "1234.57", "0.000123", "0"]
        );
    }

    /// Half a cylinder of `radius` in quads of about unit size.
    fn half_cylinder(radius: f64) -> PolyMesh {
        let grid = generate::grid(4, (std::f64::consts::PI * radius).ceil() as usize);
        let ny = grid.faces().len() / 4;
        let positions = grid
            .positions()
            .iter()
            .map(|p| {
                let a = std::f64::consts::PI * p.y / ny as f64;
                nalgebra::Point3::new(p.x, radius * a.cos(), radius * a.sin())
            })
            .collect();
        PolyMesh::new(positions, grid.faces().to_vec()).unwrap()
    }

    #[test]
    fn a_tile_much_larger_than_the_curvature_radius_is_flagged() {
        let tight = curvature(&half_cylinder(1.5), &TILE).expect("1.9 long on radius 1.5");
        assert_eq!(tight.code, WarningCode::TileVsCurvature);
        assert!(
            tight.message.contains("curvature radius"),
            "{}",
            tight.message
        );
        assert!(curvature(&half_cylinder(10.0), &TILE).is_none());
    }

    #[test]
    fn a_laying_order_on_nothing_says_why() {
        assert!(no_support(Support::Edges, false).is_none());
        let closed = no_support(Support::NoBoundary, true).expect("closed");
        assert_eq!(closed.code, WarningCode::NoSupport);
        assert!(
            closed.message.contains("open the surface"),
            "{}",
            closed.message
        );
        // An open surface whose small opening the quads closed over is not told to open
        // itself as if it had none (it said "open the surface where the vault stands").
        let closed_over = no_support(Support::NoBoundary, false).expect("closed over");
        assert!(
            closed_over.message.contains("although the surface has"),
            "{}",
            closed_over.message
        );
        let level = no_support(Support::Level, false).expect("level");
        assert!(level.message.contains("level"), "{}", level.message);
    }

    #[test]
    fn a_hole_smaller_than_a_tile_is_named_and_a_larger_one_is_not() {
        // A 12 x 12 grid of unit squares with the squares of `holes` left out.
        let with_holes = |holes: &[usize]| {
            let grid = generate::grid(12, 12);
            let faces = (0..grid.face_count())
                .filter(|f| !holes.contains(f))
                .map(|f| grid.faces()[f].clone())
                .collect();
            PolyMesh::new(grid.positions().to_vec(), faces).expect("a grid with holes")
        };
        assert!(openings(&with_holes(&[]), 2.0).is_none());
        // One square missing at (3..4, 5..6): 1.414 across, smaller than a tile of 2.
        let one = openings(&with_holes(&[3 + 12 * 5]), 2.0).expect("a pinhole");
        assert_eq!(one.code, WarningCode::SmallOpenings);
        assert!(
            one.message.contains("an opening smaller than a tile (its length 2), 1.414 across, bounded by 4 edges, near (3.500, 5.500, 0.000)"),
            "{}",
            one.message
        );
        // Two: one square and a 2 x 1 hole (2.236 across, the larger); the 2 x 2 hole and the
        // grid's own edge are larger than a tile of 2.4.
        let two = openings(&with_holes(&[3 + 12 * 5, 7 + 12 * 7, 8 + 12 * 7]), 2.4).expect("two");
        assert!(two.message.contains("2 openings"), "{}", two.message);
        assert!(two.message.contains("the largest"), "{}", two.message);
        assert!(
            two.message.contains("2.236 across, bounded by 6 edges"),
            "{}",
            two.message
        );
        let square = [3 + 12 * 5, 4 + 12 * 5, 3 + 12 * 6, 4 + 12 * 6];
        assert!(openings(&with_holes(&square), 2.4).is_none());
        // Loose triangles (an unwelded soup): their outlines are no openings.
        let loose = PolyMesh::new(
            vec![
                Point3::new(0.0, 0.0, 0.0),
                Point3::new(0.5, 0.0, 0.0),
                Point3::new(0.0, 0.5, 0.0),
                Point3::new(3.0, 0.0, 0.0),
                Point3::new(3.5, 0.0, 0.0),
                Point3::new(3.0, 0.5, 0.0),
            ],
            vec![vec![0, 1, 2], vec![3, 4, 5]],
        )
        .expect("two triangles");
        assert!(openings(&loose, 2.0).is_none());
    }

    #[test]
    fn pieces_on_top_of_each_other_are_called_layers_and_pieces_side_by_side_are_not() {
        // Two 10 x 10 grids of 0.1 squares, the second moved by `shift`.
        let two = |shift: Vector3<f64>| {
            let grid = generate::grid(10, 10);
            let scaled: Vec<Point3<f64>> = grid.positions().iter().map(|p| p * 0.1).collect();
            let n = scaled.len();
            let mut positions = scaled.clone();
            positions.extend(scaled.iter().map(|p| p + shift));
            let mut faces = grid.faces().to_vec();
            faces.extend(
                grid.faces()
                    .iter()
                    .map(|f| f.iter().map(|v| v + n).collect()),
            );
            PolyMesh::new(positions, faces).expect("two grids")
        };
        let pieces = |mesh: &PolyMesh| {
            surface_checks(mesh, &Vector3::z(), &BRICK)
                .into_iter()
                .find(|w| w.code == WarningCode::SeveralPieces)
                .expect("two pieces")
                .message
        };
        // A thick shell's two faces, 30 mm apart: layers, all of them.
        let layers = pieces(&two(Vector3::new(0.0, 0.0, 0.03)));
        assert!(layers.contains("100 % of its area"), "{layers}");
        assert!(layers.contains("on average 0.030 apart"), "{layers}");
        assert!(layers.contains("keep only the layer"), "{layers}");
        // Half overlapping, 50 mm apart: half the area.
        let half = pieces(&two(Vector3::new(0.5, 0.0, 0.05)));
        assert!(half.contains("50 % of its area"), "{half}");
        // Side by side, or farther apart than a tile's width: pieces to weld or tile apart.
        for shift in [Vector3::new(1.05, 0.0, 0.0), Vector3::new(0.0, 0.0, 0.3)] {
            let apart = pieces(&two(shift));
            assert!(apart.contains("weld them"), "{shift:?}: {apart}");
        }
    }

    #[test]
    fn a_vault_modelled_with_y_up_is_named_and_one_with_z_up_is_not() {
        // A barrel vault 2 x 2 rising 0.5 in the middle, its grid's (x, y) laid out as
        // (x, rise, -y): Y up, facing +Y; and the same as (x, y, rise): Z up.
        let grid = generate::grid(10, 10);
        let rise = |y: f64| 0.5 * (1.0 - (y - 1.0).powi(2));
        let vault = |map: &dyn Fn(f64, f64) -> Point3<f64>| {
            let positions = grid
                .positions()
                .iter()
                .map(|p| map(p.x * 0.2, p.y * 0.2))
                .collect();
            PolyMesh::new(positions, grid.faces().to_vec()).expect("a vault")
        };
        let y_up = vault(&|x, y| Point3::new(x, rise(y), -y));
        let z_up = vault(&|x, y| Point3::new(x, y, rise(y)));
        let named = up_axis(&y_up, &Vector3::z()).expect("Y up, tiled with Z up");
        assert_eq!(named.code, WarningCode::UpAxis);
        assert!(
            named.message.contains("give --up 0,1,0"),
            "{}",
            named.message
        );
        assert!(up_axis(&y_up, &Vector3::y()).is_none());
        assert!(up_axis(&z_up, &Vector3::z()).is_none());
        // A flat wall facing Y has no rise along it: nothing to say.
        let wall = vault(&|x, y| Point3::new(x, 0.0, -y));
        assert!(up_axis(&wall, &Vector3::z()).is_none());
    }

    #[test]
    fn quads_from_another_surface_are_named_and_quads_on_it_are_not() {
        // Unit quads, 12 x 10, against the same grid: on it.
        let grid = generate::grid(12, 10);
        assert!(quads_off_surface(&grid, &grid, &TILE).is_none());
        // Moved up by a tile's length and a little: every centre is off it.
        let moved = |dz: f64| {
            let positions = grid
                .positions()
                .iter()
                .map(|p| Point3::new(p.x, p.y, p.z + dz))
                .collect();
            PolyMesh::new(positions, grid.faces().to_vec()).unwrap()
        };
        let w = quads_off_surface(&moved(2.0), &grid, &TILE).expect("2 above a 1.9 tile");
        assert_eq!(w.code, WarningCode::QuadsOffSurface);
        assert!(w.message.starts_with("100 % of the quads"), "{}", w.message);
        assert!(
            w.message.contains("the farthest 2.000 away"),
            "{}",
            w.message
        );
        // Within a tile's length: quads a little off it (a remesher's) are not named.
        assert!(quads_off_surface(&moved(1.8), &grid, &TILE).is_none());
        // The quads reach beyond the surface's edge by a few rows: moved 3 along x, the last
        // of the 12 columns (centres 2.5 beyond the edge) is more than 1.9 off it.
        let shifted: Vec<Point3<f64>> = grid
            .positions()
            .iter()
            .map(|p| Point3::new(p.x + 3.0, p.y, p.z))
            .collect();
        let shifted = PolyMesh::new(shifted, grid.faces().to_vec()).unwrap();
        let w = quads_off_surface(&shifted, &grid, &TILE).expect("a twelfth beyond the edge");
        assert!(w.message.starts_with("8 % of the quads"), "{}", w.message);
    }

    #[test]
    fn a_large_curved_polygon_is_named_and_flat_or_small_ones_are_not() {
        // A 40-gon round a circle of radius `r`, its corners rising `rise` and falling as
        // cos(2a) (a saddle's rim drawn as one face).
        let polygon = |r: f64, rise: f64| {
            let positions = (0..40)
                .map(|k| {
                    let a = std::f64::consts::TAU * k as f64 / 40.0;
                    Point3::new(r * a.cos(), r * a.sin(), rise * (2.0 * a).cos())
                })
                .collect();
            PolyMesh::new(positions, vec![(0..40).collect()]).unwrap()
        };
        let w = curved_polygons(&polygon(2.5, 0.9), &BRICK).expect("5 m across, 0.9 off");
        assert_eq!(w.code, WarningCode::CurvedPolygons);
        assert!(
            w.message
                .starts_with("1 face of more than four corners is larger than a tile"),
            "{}",
            w.message
        );
        assert!(
            w.message.contains(
                "face 0, counted from 0: 40 corners, 5.314 across, standing up to 0.900 off"
            ),
            "{}",
            w.message
        );
        // Flat: read as drawn.
        assert!(curved_polygons(&polygon(2.5, 0.0), &BRICK).is_none());
        // Bent by less than a tile's thickness (15 mm), or smaller than a tile.
        assert!(curved_polygons(&polygon(2.5, 0.01), &BRICK).is_none());
        assert!(curved_polygons(&polygon(0.1, 0.05), &BRICK).is_none());
        // Quads are never named: a fan of a quad is one of its two triangulations.
        assert!(curved_polygons(&generate::corner_supported_shell(2.0, 0.5), &BRICK).is_none());
        // Renumbered (as the command line does to its file's numbers), in the message too.
        assert_eq!(w.face, Some(0));
        let w = w.renumbered(|f| f + 12);
        assert_eq!(w.face, Some(12));
        assert!(w.message.contains("(face 12, counted from 0: 40 corners"));
    }

    #[test]
    fn renumbering_a_warning_replaces_the_face_it_names_and_no_other_number() {
        let w = Warning::at_face(
            WarningCode::FoldedSurface,
            1,
            "surface 1, face 17 and face 1 near face 10, face 1".into(),
        );
        let w = w.renumbered(|f| 100 * f);
        assert_eq!(
            w.message,
            "surface 1, face 17 and face 100 near face 10, face 1"
        );
        assert_eq!(w.face, Some(100));
        // A warning naming no face is left as it is.
        let plain = Warning::new(WarningCode::FoldedSurface, "face 3");
        assert_eq!(plain.clone().renumbered(|f| f + 1), plain);
    }

    #[test]
    fn a_grid_is_open_whole_and_faces_up() {
        let grid = generate::grid(4, 3);
        assert!(surface_checks(&grid, &Vector3::z(), &BRICK).is_empty());
        let codes: Vec<_> = surface_checks(&grid, &-Vector3::z(), &BRICK)
            .iter()
            .map(|w| w.code)
            .collect();
        assert_eq!(codes, vec![WarningCode::NormalsDown]);
        assert!(curvature(&grid, &TILE).is_none());
    }

    #[test]
    fn quads_far_from_half_a_tile_are_flagged() {
        // Unit quads are half of TILE (target edge 1): no word.
        assert!(quad_size(&generate::grid(4, 3), &TILE).is_none());
        // Stretched to 1.5 along x: 4 x 4 of the 31 edges run along x, so 15 of 31 fit.
        let grid = generate::grid(4, 3);
        let stretched = grid
            .positions()
            .iter()
            .map(|p| nalgebra::Point3::new(1.5 * p.x, p.y, p.z))
            .collect();
        let stretched = PolyMesh::new(stretched, grid.faces().to_vec()).unwrap();
        let w = quad_size(&stretched, &TILE).expect("half the edges 50 % long");
        assert_eq!(w.code, WarningCode::QuadSize);
        assert!(w.message.contains("only 48 %"), "{}", w.message);
        assert!(w.message.contains("target edge (1)"), "{}", w.message);
        // The remesher's own figure gives the same word.
        assert_eq!(quad_size_of(15.0 / 31.0, 1.0), Some(w));
        assert!(quad_size_of(MIN_QUAD_EDGES_WITHIN, 1.0).is_none());
    }

    /// A strip of three unit quads along x whose last quad is turned back over the middle
    /// one by `angle` (radians, 0 = flat) about their shared edge.
    fn strip_turned_by(angle: f64) -> PolyMesh {
        let back = nalgebra::Point3::new(2.0 + angle.cos(), 0.0, angle.sin());
        let mut positions = Vec::new();
        for y in [0.0, 1.0] {
            for p in [
                nalgebra::Point3::new(0.0, 0.0, 0.0),
                nalgebra::Point3::new(1.0, 0.0, 0.0),
                nalgebra::Point3::new(2.0, 0.0, 0.0),
                back,
            ] {
                positions.push(p + Vector3::y() * y);
            }
        }
        let faces = (0..3).map(|i| vec![i, i + 1, i + 5, i + 4]).collect();
        PolyMesh::new(positions, faces).unwrap()
    }

    #[test]
    fn a_surface_folded_back_on_itself_is_flagged_and_a_crease_is_not() {
        let codes = |mesh: &PolyMesh| -> Vec<WarningCode> {
            surface_checks(mesh, &Vector3::z(), &BRICK)
                .iter()
                .map(|w| w.code)
                .collect()
        };
        // Turned by 90 degrees (a box's edge) and by 115: creases, not folds.
        assert!(codes(&strip_turned_by(std::f64::consts::FRAC_PI_2)).is_empty());
        assert!(codes(&strip_turned_by(115f64.to_radians())).is_empty());
        let folded = surface_checks(&strip_turned_by(160f64.to_radians()), &Vector3::z(), &BRICK);
        let fold = folded
            .iter()
            .find(|w| w.code == WarningCode::FoldedSurface)
            .expect("a fold of 160 degrees");
        assert!(
            fold.message.contains("at 1 edge (") && fold.message.contains("160 degrees"),
            "{}",
            fold.message
        );
        // A closed box has creases only.
        assert!(!codes(&generate::closed_box(1.0, 3)).contains(&WarningCode::FoldedSurface));
    }
}
