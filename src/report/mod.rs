//! Quality report of a tiling: counts, the matching's proof status, and how far each joint
//! between neighbouring tiles is from the nominal mortar width (paper section 4.1 / Figure 8:
//! gaps grow with curvature).

pub mod coverage;
pub mod gaps;
pub mod svg;
pub mod warnings;

pub use gaps::{Joint, JointSummary};
pub use warnings::{Warning, WarningCode};

use serde::Serialize;

use crate::mesh::PolyMesh;
use crate::pattern::{Pattern, PatternSummary, SolveStatus};
use crate::tiles::{
    DropReason, DroppedTile, ExcludedArea, Finished, FitSummary, Sequence, Tile, TileKind, TileSpec,
};

/// Wall-clock seconds per stage.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct StageSeconds {
    /// Pattern (matching) stage.
    pub pattern: f64,
    /// Tile stage (the fit included).
    pub tiles: f64,
    /// The fit stage alone (0 when it did not run).
    pub fit: f64,
}

/// One try of `pipeline::tile_surface_tries`: its figures, as `report.json`'s `tries` lists
/// them.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TryFigures {
    /// The field's renormalisation strength of this try.
    pub renormalisation: f64,
    /// What its field follows besides a designer's field and guide curves: `"curvature"`
    /// (the default), `"smooth"` (nothing: the boundary and smoothness alone, the second
    /// of the automatic tries), `"direction"` or `"angle"`.
    pub field: &'static str,
    /// Whether its quads are laid out for level courses, half a tile and a joint along them
    /// and a course's pitch across (the fifth automatic try; written only for it).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub quads_along_courses: bool,
    /// Whether its quads follow no boundary loop, not even one with corners (the sixth
    /// automatic try, written only for it): the smoothest field there is, parallel on a
    /// developable surface, whose rows meet curved edges at any angle and are cut to them.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub boundary_free: bool,
    /// Faces of its quad mesh.
    pub quads: usize,
    /// Interior irregular vertices of its quad mesh.
    pub interior_irregular_vertices: usize,
    /// Its joints' p95 |gap - joint| after the fit (model units).
    pub p95_deviation: f64,
    /// Tiles cut to fit and pieces cut inside the fit's holes, per full and half tile.
    pub cut_share: f64,
    /// Share of the surface its tiles cover.
    pub coverage: f64,
    /// Whether its report warns that the joints stray (`wide_joints`); tries without the
    /// warning are kept before tries with it.
    pub wide_joints: bool,
    /// Whether its report warns that the fit cut more than 1 % of the tiles (`fit_cuts`);
    /// among tries whose joints are not flagged, tries without this warning are kept first.
    pub fit_cuts: bool,
    /// `pipeline::score`: lower is better (none when the try failed).
    pub score: Option<f64>,
    /// Seconds of this try, all stages.
    pub seconds: f64,
    /// The stage whose time limit this try reached, if one did (`"pattern"` or `"fit"`; a
    /// fit the caller cancelled counts as the fit's): its tiles then depend on the
    /// machine's speed, and a later try that reaches one is not kept.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub limit_reached: Option<&'static str>,
    /// Whether reaching that limit ended the tries (written only when it did): each further
    /// try would take as long, except after the first try's pattern stage when a later
    /// try's pattern stage has a shorter limit (`pipeline::LATER_PATTERN_SECONDS`), where
    /// its quads may be proven though the first's were not (a shell whose curvature asks
    /// rows to end all over it, where the smooth field's quads end few).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub ended_tries: bool,
    /// Why the try gave no tiles (its figures are then 0 and it is not kept), if it failed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub failed: Option<String>,
}

/// Everything a designer wants to know about a tiling, serialised as `report.json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// Faces of the quad mesh.
    pub faces: usize,
    /// Tiles over matched pairs (full blanks), whether cut to the boundary or not.
    pub full_tiles: usize,
    /// Half tiles over unmatched quads, each needs a cut.
    pub half_tiles: usize,
    /// Tiles and pieces cut (kind boundary): the tiles above cut to the surface's boundary,
    /// and the filler pieces, cut to the edge or to the room in the fit's tears (the
    /// command line's summary names the tiles above alone).
    pub boundary_tiles: usize,
    /// Faces that are not quads: no tile was placed on them.
    pub non_quad_faces: usize,
    /// Faces excluded by the caller.
    pub excluded_faces: usize,
    /// Continuous joints left in the pattern.
    pub continuous_joints: usize,
    /// Shifted (running-bond) pairs in the pattern.
    pub shifted_pairs: usize,
    /// Objective of the matching.
    pub objective: f64,
    /// Proven bound on the objective.
    pub bound: f64,
    /// Relative gap between objective and bound.
    pub gap: f64,
    /// Whether the matching is proven optimal.
    pub status: SolveStatus,
    /// The pattern stage's result without its pairs, every field of it (the fields above
    /// from `continuous_joints` to `status` are the same figures, kept where scripts read
    /// them).
    pub pattern: PatternSummary,
    /// Tile size used.
    pub tile: TileSpec,
    /// Joint gaps and overlaps, with the figures before the fit stage when it ran.
    pub joints: JointSummary,
    /// What the fit stage did, when it ran.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fit: Option<FitSummary>,
    /// Cutting to the boundary and coverage of the surface, once the tiles are finished.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cutting: Option<CuttingSummary>,
    /// The laying order's summary, once the tiles are finished.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sequence: Option<Sequence>,
    /// Seconds per stage.
    pub seconds: StageSeconds,
    /// Odd input and results to look at twice, each with a stable code and what to do (see
    /// [`warnings`]); empty when all is well.
    pub warnings: Vec<Warning>,
    /// When the pipeline laid tiles on several quad meshes of the surface
    /// (`pipeline::tile_surface_tries`): each try's figures, in order; empty otherwise.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub tries: Vec<TryFigures>,
    /// Which of `tries` these tiles are (counted from 0).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub chosen_try: Option<usize>,
}

/// How much cutting the boundary needs and how well the tiles cover the surface.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CuttingSummary {
    /// Tiles and pieces cut, as [`Report::boundary_tiles`].
    pub boundary_tiles: usize,
    /// Filler pieces (half blanks) laid beyond the quad mesh's boundary, where it falls short
    /// of the surface's edge, and the pieces filling the fit's tears (`tear_pieces`); most
    /// of them are cut.
    pub filler_tiles: usize,
    /// Of `filler_tiles`, the pieces (tile blanks, most of them cut) that fill the holes the
    /// fit left where courses converge or part, and along the edge where the edge's filler
    /// pieces did not reach, with the whole pieces the fit laid in the rooms of its courses
    /// ([`FitSummary::room_pieces`]).
    pub tear_pieces: usize,
    /// Of `tear_pieces`, those cut to the room their neighbours leave away from the
    /// surface's edge (a piece the edge cuts is cut there anyway; a whole piece is no cut):
    /// the cuts the fit's tears ask for, counted with the tiles cut to fit by the
    /// `fit_cuts` warning.
    pub tear_cuts: usize,
    /// Of `tear_pieces`, whole half tiles laid where a hole's room held one with its joints
    /// within half a joint of the nominal one (by the tear fill, or by the fit in the rooms
    /// of its courses), instead of a piece cut to the room: no cut on
    /// site (halves are cut off site, as the pattern's half tiles are; they are in the cut
    /// list's `H`).
    pub tear_halves: usize,
    /// Tiles dropped because no part of them lies on the surface.
    pub outside_tiles: usize,
    /// Pieces too thin to cut or lay, left out: the gap they leave is filled with mortar or a
    /// piece cut on site.
    pub slivers: Vec<DroppedTile>,
    /// Distinct cut shapes of boundary tiles.
    pub boundary_shapes: usize,
    /// Area of the surface the tiles were cut to.
    pub surface_area: f64,
    /// Area of the kept tile faces, each with half a joint around it: more than the surface
    /// where tiles overlap.
    pub tile_area: f64,
    /// Share of the surface's area under a kept tile face or its half joint (see
    /// [`coverage`]).
    pub coverage: f64,
    /// Tiles standing off the surface by more than their own thickness (see
    /// [`warnings::MAX_LIFT`]; the `tiles_off_surface` warning).
    pub lifted_tiles: usize,
    /// The farthest any tile's bottom face stands off the surface, in model units (a flat tile
    /// on a curved surface stands off by `(L^2 + W^2) / 8R` at its corners by itself).
    pub largest_lift: f64,
}

impl Report {
    /// Tiles cut by the fit: tiles cut to fit and pieces cut to the room inside the holes it
    /// opened (`cutting.tear_cuts`), the cuts the method exists to avoid.
    pub fn fit_cut_count(&self) -> usize {
        self.joints.fit_cuts + self.cutting.as_ref().map_or(0, |c| c.tear_cuts)
    }

    /// Pieces cut to the surface's edge: the tiles and filler pieces cut (kind boundary,
    /// [`Self::boundary_tiles`]) less those cut inside the fit's holes, which
    /// [`Self::fit_cut_count`] counts.
    pub fn edge_cut_count(&self) -> usize {
        let inside = self.cutting.as_ref().map_or(0, |c| c.tear_cuts);
        self.boundary_tiles.saturating_sub(inside)
    }

    /// Whether the report warns with `code`.
    pub fn warns(&self, code: WarningCode) -> bool {
        self.warnings.iter().any(|w| w.code == code)
    }

    /// Summarises a tiling built from `pattern` on `mesh`, in metres (see [`Report::measured`]).
    pub fn new(mesh: &PolyMesh, pattern: &Pattern, tiles: &[Tile], spec: &TileSpec) -> Self {
        Self::measured(
            mesh,
            pattern,
            tiles,
            &gaps::joints(mesh, tiles, spec.joint),
            spec,
            0.001,
        )
    }

    /// Summarises a tiling built from `pattern` on `mesh`, whose `joints` were measured with
    /// [`gaps::joints`], in a model with `mm` model units per millimetre (for the joint
    /// figures stated in millimetres).
    pub fn measured(
        mesh: &PolyMesh,
        pattern: &Pattern,
        tiles: &[Tile],
        joints: &[Joint],
        spec: &TileSpec,
        mm: f64,
    ) -> Self {
        let count = |kind| tiles.iter().filter(|t| t.kind == kind).count();
        let blanks = |faces: usize| tiles.iter().filter(|t| t.faces.len() == faces).count();
        let summary = pattern.summary();
        Self {
            faces: mesh.face_count(),
            full_tiles: blanks(2),
            half_tiles: blanks(1),
            boundary_tiles: count(TileKind::Boundary),
            non_quad_faces: summary.non_quad,
            excluded_faces: summary.excluded,
            continuous_joints: summary.continuous_joints,
            shifted_pairs: summary.shifted_pairs,
            objective: summary.objective,
            bound: summary.bound,
            gap: summary.gap,
            status: summary.status,
            pattern: summary,
            tile: *spec,
            joints: JointSummary {
                fit_cuts: count(TileKind::FitCut),
                ..JointSummary::of(joints, spec.joint, mm)
            },
            fit: None,
            cutting: None,
            sequence: None,
            seconds: StageSeconds {
                pattern: summary.seconds,
                tiles: 0.0,
                fit: 0.0,
            },
            warnings: Vec::new(),
            tries: Vec::new(),
            chosen_try: None,
        }
    }

    /// Adds what [`crate::tiles::finish`] found on `surface`, the surface the tiles were cut
    /// to; the coverage leaves the `excluded` quads' area out.
    pub fn add_finish(
        &mut self,
        tiles: &[Tile],
        finished: &Finished,
        surface: &PolyMesh,
        excluded: Option<&ExcludedArea>,
    ) {
        let joint = self.tile.joint;
        let tile_area: f64 = tiles
            .iter()
            .map(|t| {
                let nominal = t.size[0] * t.size[1];
                t.kept_area() * (t.size[0] + joint) * (t.size[1] + joint) / nominal
            })
            .sum();
        self.cutting = Some(CuttingSummary {
            boundary_tiles: self.boundary_tiles,
            filler_tiles: finished.fillers,
            tear_pieces: finished.tear_pieces,
            tear_cuts: finished.tear_cuts,
            tear_halves: finished.tear_halves,
            outside_tiles: finished
                .dropped
                .iter()
                .filter(|d| d.reason == DropReason::Outside)
                .count(),
            slivers: finished
                .dropped
                .iter()
                .filter(|d| d.reason == DropReason::Sliver)
                .cloned()
                .collect(),
            boundary_shapes: finished
                .cut_list
                .iter()
                .filter(|g| g.kind == TileKind::Boundary)
                .count(),
            surface_area: surface.area(),
            tile_area,
            coverage: coverage::covered_share(surface, tiles, joint, excluded),
            lifted_tiles: finished
                .lifts
                .iter()
                .filter(|&&l| l > warnings::MAX_LIFT * self.tile.thickness)
                .count(),
            largest_lift: finished.lifts.iter().copied().fold(0.0, f64::max),
        });
        self.sequence = Some(finished.sequence.clone());
    }
}
