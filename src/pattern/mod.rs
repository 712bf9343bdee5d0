//! Stage 2 (paper sections 3.2-3.4): match adjacent quads into tiles.
//!
//! [`solve`] builds the [`DualGraph`] of a quad mesh and solves one of the paper's binary
//! integer programs with CBC (`solver::cbc`), written once in `program`:
//!
//! * [`Bond::Stack`]: maximum matching, eq. (1);
//! * [`Bond::Staggered`]: eq. (2), each continuous joint costs `weight`;
//! * [`Bond::RunningBond`]: eq. (3), each shifted pair earns `weight`;
//! * [`Bond::Herringbone`], [`Bond::BasketWeave`]: the other patterns of section 3.4 and
//!   Figure 1, each pair of their [`Relation`]s costs `weight`.
//!
//! [`PatternOptions::zones`] gives a bond per face (a herringbone band in a staggered vault);
//! the objective's pair terms, of one bond or of zones, are built once per solve (`terms`)
//! and read by everything below.
//!
//! The answer says honestly how good it is: the objective of the returned pattern, a
//! proven bound and where it came from ([`BoundSource`]), and [`SolveStatus::Optimal`] only
//! when the two meet.
//!
//! [`Method::Auto`] gets there much faster than the paper's whole program: patterns from
//! constructive starts (`construct`) refined by simulated annealing (`anneal`) and exact
//! windows (`search`), bounds from a maximum matching (`bound`), from the linear relaxation
//! of the whole program (`linear`) and from patch relaxations (`decompose`).

mod anneal;
mod bound;
mod construct;
mod courses;
mod decompose;
mod dual;
mod engine;
mod error;
mod linear;
mod mip;
mod program;
mod score;
mod search;
mod terms;
mod worker;

pub use courses::Courses;
pub use dual::{CandidateTile, DualGraph};
pub use error::PatternError;
pub use score::{Score, score};

use terms::Terms;

use std::time::{Duration, Instant};

use serde::{Deserialize, Serialize};

use crate::control::{Control, relative_gap};
use crate::mesh::{PolyMesh, Topology};

/// Which laying pattern the objective asks for.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Bond {
    /// Eq. (1): as many tiles as possible, nothing else.
    Stack,
    /// Eq. (2): as many tiles as possible, minus `weight` per continuous joint.
    Staggered {
        /// The paper's w (default 0.5): above 1 a continuous joint is worse than two half tiles.
        weight: f64,
    },
    /// Eq. (3): as many tiles as possible, plus `weight` per pair shifted by one face.
    RunningBond {
        /// The paper's w_R (default 0.5).
        weight: f64,
    },
    /// Herringbone (the paper's Figure 1, its other objective terms of section 3.4): as many
    /// tiles as possible, minus `weight` per continuous joint and per pair of tiles laid end
    /// to end. On a regular grid the only tilings with neither are the 90-degree zig-zag, in
    /// which each tile's ends abut the sides of perpendicular tiles.
    Herringbone {
        /// The penalty per pair (default 0.5).
        weight: f64,
    },
    /// Basket weave (the paper's Figure 1): as many tiles as possible, minus `weight` per
    /// shifted pair, per pair laid end to end and per pair of parallel tiles one course
    /// apart. On a regular grid the only tiling with none is the checkerboard of 2 x 2
    /// squares, each two parallel tiles, alternating in direction.
    BasketWeave {
        /// The penalty per pair (default 0.5).
        weight: f64,
    },
}

/// A relation between candidate tiles of a quad mesh, found from its topology alone
/// (see [`DualGraph`]); each bond scores the pairs of some of them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Relation {
    /// Side by side and aligned: middle edges opposite at a regular vertex (eq. 2's y).
    ContinuousJoints,
    /// Side by side, shifted by one face (eq. 3's z).
    ShiftedPairs,
    /// End to end along one quad strip: an end face of each shares the other's end edge.
    EndToEnd,
    /// Parallel and aligned one course apart: middle edges two steps apart along one line
    /// of edges through regular vertices.
    OneCourseApart,
}

impl Bond {
    /// What a pair of the bond's relation ([`DualGraph::bond_pairs`]) adds to the objective
    /// when both its tiles are chosen: `-w` per continuous joint (eq. 2), `+w` per shifted
    /// pair (eq. 3), `-w` per pair of the herringbone's and the basket weave's relations,
    /// nothing for the stack bond (eq. 1). A tile adds one in every bond; the score, the
    /// program, the bounds and the heuristics all read the bond's terms from here and from
    /// [`Bond::relations`].
    pub fn pair_weight(self) -> f64 {
        match self {
            Bond::Stack => 0.0,
            Bond::RunningBond { weight } => weight,
            Bond::Staggered { weight }
            | Bond::Herringbone { weight }
            | Bond::BasketWeave { weight } => -weight,
        }
    }

    /// The relations whose pairs the bond scores, each at [`Bond::pair_weight`]: the rule
    /// of each bond, written once. A pair in several counts once.
    pub fn relations(self) -> &'static [Relation] {
        match self {
            Bond::Stack => &[],
            Bond::Staggered { .. } => &[Relation::ContinuousJoints],
            Bond::RunningBond { .. } => &[Relation::ShiftedPairs],
            Bond::Herringbone { .. } => &[Relation::ContinuousJoints, Relation::EndToEnd],
            Bond::BasketWeave { .. } => &[
                Relation::ShiftedPairs,
                Relation::EndToEnd,
                Relation::OneCourseApart,
            ],
        }
    }

    /// The bond's weight (`None` for the stack bond).
    pub fn weight(self) -> Option<f64> {
        match self {
            Bond::Stack => None,
            Bond::Staggered { weight }
            | Bond::RunningBond { weight }
            | Bond::Herringbone { weight }
            | Bond::BasketWeave { weight } => Some(weight),
        }
    }

    /// True for the bonds that lay tiles both ways (the herringbone and the basket weave):
    /// they need tiles free to lie either way ([`Courses::Free`]).
    pub fn lays_both_ways(self) -> bool {
        matches!(self, Bond::Herringbone { .. } | Bond::BasketWeave { .. })
    }

    /// Its name on the command line and in messages.
    pub fn name(self) -> &'static str {
        match self {
            Bond::Stack => "stack",
            Bond::Staggered { .. } => "staggered",
            Bond::RunningBond { .. } => "running-bond",
            Bond::Herringbone { .. } => "herringbone",
            Bond::BasketWeave { .. } => "basket-weave",
        }
    }

    /// True when the bond's relation starts with the continuous joints at a penalty: then
    /// the compact joint form of eq. (2) (one column and one star row per regular vertex,
    /// see `program`) holds for them.
    pub fn penalises_continuous_joints(self) -> bool {
        self.relations().first() == Some(&Relation::ContinuousJoints) && self.pair_weight() < 0.0
    }
}

/// The paper's default weight for the staggered and running-bond objectives.
pub const DEFAULT_WEIGHT: f64 = 0.5;

/// Largest bond weight accepted. Weights above 1 already make one joint or shifted pair
/// outweigh a whole tile; far larger ones only break the solver's numerics (CBC reports
/// valid programs infeasible from about 1e20 and aborts the process from about 1e25).
pub const MAX_WEIGHT: f64 = 1000.0;

/// Longest time limit: longer limits (up to any finite number of seconds) are cut to this
/// many seconds (about 31 years), which keeps deadlines representable.
pub const MAX_TIME_LIMIT_SECONDS: u64 = 1_000_000_000;

/// How the integer program is written for the solver.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum Formulation {
    /// The constraints exactly as printed in the paper.
    Paper,
    /// The paper's program plus valid inequalities that cut off fractional points but no
    /// integer solution, so the optimum is the same: for eq. (2), one "star" row per regular
    /// interior vertex, `x_a + x_b + x_c + x_d - y_ac - y_bd <= 1` (two opposite tiles fit
    /// only together with their continuous joint); and every other penalty pair's row takes
    /// the tiles bridging its two tiles, `x_a + x_b + x_c - y <= 1` (e.g. the tile across the
    /// shared end edge of two tiles laid end to end). Proves optimality far sooner. Eq. (1)
    /// and (3) are passed as printed.
    #[default]
    Strengthened,
}

/// Options of the pattern stage.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct PatternOptions {
    /// The objective.
    pub bond: Bond,
    /// Wall-clock limit for the solver. Zero skips the solver and returns the greedy start;
    /// limits over [`MAX_TIME_LIMIT_SECONDS`] count as that limit.
    pub time_limit: Duration,
    /// Face pairs that must become tiles (0-based face indices).
    pub forced_pairs: Vec<[usize; 2]>,
    /// Faces that take part in no tile, e.g. openings.
    pub excluded_faces: Vec<usize>,
    /// How the program is written; both give the same optimum.
    pub formulation: Formulation,
    /// Which route to the optimum.
    pub method: Method,
    /// Which way tiles may lie: any way (the paper's model) or only along courses.
    pub courses: Courses,
    /// Relative gap at which the search stops, like a MIP solver's: once `(bound -
    /// objective) / bound` (the pattern's [`Pattern::gap`]) is at most this. From 0 (the
    /// default: prove optimality or reach the time limit) to 1. A pattern stopped by the gap
    /// has [`SolveStatus::Feasible`] (or [`SolveStatus::Optimal`] when proven).
    pub gap: f64,
    /// Zones: a bond per face (one per face of the mesh, in face order), e.g. a band of
    /// herringbone in a staggered vault as in Guastavino soffits; `None` (the default) lays
    /// every face in [`PatternOptions::bond`]. A pair inside a zone scores as the zone's
    /// bond scores it; tiles across a zone border are allowed, and a pair across it scores
    /// as each zone would, in proportion to its four faces in each. Non-quad or excluded
    /// faces may carry any bond.
    pub zones: Option<Vec<Bond>>,
}

/// How the pattern stage searches.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum Method {
    /// The fastest route to a proven optimum: a maximum-matching bound and three
    /// constructive starts (courses along the boundary, a running bond along quad strips, the
    /// maximum matching), simulated annealing from the best, the linear relaxation of the
    /// whole program by Clp's barrier when it is expected to finish in the time left (then,
    /// if solved, annealing again with most of the time; else a decomposition bound from the
    /// linear relaxations of ever larger patches), then rounds of a decomposition bound from
    /// exactly solved patches, ever larger (each round's made of the last one's and centred
    /// on the forced defects it found), exact re-solves of windows around the defects and
    /// cooler annealing; the last round solves the whole program on CBC. Every bound is
    /// rounded down to the next objective value a pattern can take.
    #[default]
    Auto,
    /// The whole program on CBC, as in the paper (slow on large meshes; a reference).
    Mip,
}

impl Default for PatternOptions {
    fn default() -> Self {
        Self {
            bond: Bond::Staggered {
                weight: DEFAULT_WEIGHT,
            },
            time_limit: Duration::from_secs(60),
            forced_pairs: Vec::new(),
            excluded_faces: Vec::new(),
            formulation: Formulation::default(),
            method: Method::default(),
            courses: Courses::Free,
            gap: 0.0,
            zones: None,
        }
    }
}

impl PatternOptions {
    /// Checks what does not depend on the mesh, so that a pipeline can refuse bad options
    /// before its remesh: the weights (of the bond and of every zone), the gap, and bonds
    /// that lay tiles both ways (in any zone) with level courses. [`solve`] checks this too,
    /// and that the zones give one bond per face.
    ///
    /// # Errors
    /// [`PatternError::InvalidWeight`], [`PatternError::WeightTooLarge`],
    /// [`PatternError::InvalidZone`] (the first face at fault), [`PatternError::InvalidGap`]
    /// or [`PatternError::BondAcrossCourses`].
    pub fn check(&self) -> Result<(), PatternError> {
        validate_weights(self.bond)?;
        for (face, &bond) in self.zones.iter().flatten().enumerate() {
            validate_weights(bond).map_err(|error| PatternError::InvalidZone {
                face,
                reason: error.to_string(),
            })?;
        }
        if !(0.0..=1.0).contains(&self.gap) {
            return Err(PatternError::InvalidGap { gap: self.gap });
        }
        if let Some(bond) = self.bonds().find(|b| b.lays_both_ways())
            && self.courses != Courses::Free
        {
            return Err(PatternError::BondAcrossCourses { bond: bond.name() });
        }
        Ok(())
    }

    /// Every bond the options lay: [`PatternOptions::bond`], or the zones' bonds (in face
    /// order, repeated).
    pub fn bonds(&self) -> impl Iterator<Item = Bond> + '_ {
        let zoned = self.zones.as_deref();
        zoned
            .unwrap_or(std::slice::from_ref(&self.bond))
            .iter()
            .copied()
    }

    /// Converts seconds (as typed on a command line or passed through the C ABI) into a time
    /// limit. Finite limits longer than [`MAX_TIME_LIMIT_SECONDS`] become that limit.
    ///
    /// # Errors
    /// [`PatternError::InvalidTimeLimit`] for negative, NaN or infinite values.
    pub fn time_limit_from_secs(seconds: f64) -> Result<Duration, PatternError> {
        if !(seconds.is_finite() && seconds >= 0.0) {
            return Err(PatternError::InvalidTimeLimit { seconds });
        }
        // `abs` turns -0.0 into 0.0; only values beyond `Duration` fail to convert.
        Ok(Duration::try_from_secs_f64(seconds.abs())
            .unwrap_or(Duration::MAX)
            .min(Duration::from_secs(MAX_TIME_LIMIT_SECONDS)))
    }
}

/// How far the solver got.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum SolveStatus {
    /// The objective equals the proven bound.
    Optimal,
    /// The time limit stopped the search; the pattern is valid, the gap is open.
    TimeLimit,
    /// The solver stopped for another reason with a valid pattern and an open gap.
    Feasible,
}

/// Which argument gave a pattern's proven bound.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum BoundSource {
    /// A maximum-cardinality matching (blossom): no pattern has more tiles; for a running
    /// bond with at most two shifted pairs per tile.
    #[default]
    Matching,
    /// The sum of the patch relaxations of a decomposition of the faces (each solved exactly,
    /// or as a linear program).
    Patches,
    /// CBC's branch and bound on the whole program.
    WholeProgram,
    /// The linear relaxation of the whole program (with the star rows), from the prices
    /// Clp's barrier found for its rows.
    LinearRelaxation,
}

/// A matching of faces into tiles, with its quality and proof status. Serialised, it is the
/// JSON that `tilepattern match` writes and `tilepattern tiles` reads.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Pattern {
    /// Number of faces in the mesh.
    pub faces: usize,
    /// Matched face pairs `[a, b]` with `a < b`, sorted.
    pub pairs: Vec<[usize; 2]>,
    /// Quads in no pair: each becomes a half tile that needs a cut.
    pub unpaired: Vec<usize>,
    /// Faces excluded by the caller.
    #[serde(default)]
    pub excluded: Vec<usize>,
    /// Faces that are not quads: never paired, reported for manual treatment.
    #[serde(default)]
    pub non_quad: Vec<usize>,
    /// Continuous joints in the pattern (pairs of chosen tiles counted by eq. 2's y).
    pub continuous_joints: usize,
    /// Shifted pairs in the pattern (pairs of chosen tiles counted by eq. 3's z).
    pub shifted_pairs: usize,
    /// Pairs of the bond's own relation in the pattern ([`DualGraph::bond_pairs`]: for the
    /// herringbone its continuous joints and end-to-end pairs, for the basket weave its
    /// shifted, end-to-end and one-course-apart pairs), each at the bond's weight.
    #[serde(default)]
    pub bond_pairs: usize,
    /// Objective value of this pattern under the chosen bond.
    pub objective: f64,
    /// Proven upper bound on the objective.
    pub bound: f64,
    /// Relative gap `(bound - objective) / max(|bound|, 1)`.
    pub gap: f64,
    /// Whether optimality was proven.
    pub status: SolveStatus,
    /// Which argument gave `bound` (with `status` optimal: which one closed the gap).
    #[serde(default)]
    pub bound_source: BoundSource,
    /// Wall-clock seconds spent in this stage.
    pub seconds: f64,
}

/// A [`Pattern`] without its pairs: its counts, its quality and how far it is proven, as the
/// tiling report embeds it (`report.json`'s `pattern`), one field per field of the pattern so
/// that none is lost on the way (the report once dropped `bound_source`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PatternSummary {
    /// Number of faces in the mesh.
    pub faces: usize,
    /// Matched face pairs: full tiles.
    pub pairs: usize,
    /// Quads in no pair: half tiles.
    pub unpaired: usize,
    /// Faces excluded by the caller.
    pub excluded: usize,
    /// Faces that are not quads.
    pub non_quad: usize,
    /// See [`Pattern::continuous_joints`].
    pub continuous_joints: usize,
    /// See [`Pattern::shifted_pairs`].
    pub shifted_pairs: usize,
    /// See [`Pattern::bond_pairs`].
    pub bond_pairs: usize,
    /// See [`Pattern::objective`].
    pub objective: f64,
    /// See [`Pattern::bound`].
    pub bound: f64,
    /// See [`Pattern::gap`].
    pub gap: f64,
    /// See [`Pattern::status`].
    pub status: SolveStatus,
    /// See [`Pattern::bound_source`].
    pub bound_source: BoundSource,
    /// See [`Pattern::seconds`].
    pub seconds: f64,
}

impl Pattern {
    /// This pattern's [`PatternSummary`].
    pub fn summary(&self) -> PatternSummary {
        // Destructured so that a field added to `Pattern` must be placed here (or named
        // as left out) for this to compile.
        let Pattern {
            faces,
            pairs,
            unpaired,
            excluded,
            non_quad,
            continuous_joints,
            shifted_pairs,
            bond_pairs,
            objective,
            bound,
            gap,
            status,
            bound_source,
            seconds,
        } = self;
        PatternSummary {
            faces: *faces,
            pairs: pairs.len(),
            unpaired: unpaired.len(),
            excluded: excluded.len(),
            non_quad: non_quad.len(),
            continuous_joints: *continuous_joints,
            shifted_pairs: *shifted_pairs,
            bond_pairs: *bond_pairs,
            objective: *objective,
            bound: *bound,
            gap: *gap,
            status: *status,
            bound_source: *bound_source,
            seconds: *seconds,
        }
    }
}

/// Matches the faces of `mesh` into tiles under `options`.
///
/// # Errors
/// Invalid options (weights, excluded faces, forced pairs) or a solver failure.
pub fn solve(mesh: &PolyMesh, options: &PatternOptions) -> Result<Pattern, PatternError> {
    solve_with(mesh, options, &mut Control::none())
}

/// [`solve`], reporting progress (the share of the time limit used) to `control`, which can
/// cancel the search.
///
/// # Errors
/// As [`solve`], and [`PatternError::Cancelled`] when `control` asked to stop.
pub fn solve_with(
    mesh: &PolyMesh,
    options: &PatternOptions,
    control: &mut Control<'_>,
) -> Result<Pattern, PatternError> {
    let started = Instant::now();
    options.check()?;
    if let Some(zones) = &options.zones {
        check_zone_count(zones.len(), mesh.face_count())?;
    }
    let mut excluded = vec![false; mesh.face_count()];
    for &f in &options.excluded_faces {
        *excluded.get_mut(f).ok_or(PatternError::FaceOutOfRange {
            face: f,
            face_count: mesh.face_count(),
        })? = true;
    }
    let topology = Topology::new(mesh).expect("a PolyMesh is manifold by construction");
    let middle = match options.courses {
        Courses::Free => None,
        Courses::Level { up } => Some(courses::middle_edges(mesh, &topology, up)?),
    };
    let graph = DualGraph::restricted(mesh, &topology, &excluded, middle.as_deref());
    let forced = forced_tiles(mesh, &topology, &graph, &excluded, &options.forced_pairs)?;

    // A longer limit (e.g. `Duration::MAX` from a Rust caller) would overflow the deadline.
    let time_limit = options
        .time_limit
        .min(Duration::from_secs(MAX_TIME_LIMIT_SECONDS));
    let deadline = started + time_limit;
    let limit = time_limit.as_secs_f64().max(1e-9);
    let progress = move || started.elapsed().as_secs_f64() / limit;
    if !control.keep_going(0.0) {
        return Err(PatternError::Cancelled);
    }
    let terms = match &options.zones {
        Some(zones) => Terms::zoned(&graph, zones),
        None => Terms::uniform(&graph, options.bond),
    };
    let found = engine::Engine::new(
        &graph, &topology, options, &terms, &forced, deadline, control, &progress,
    )
    .run()?;
    control.keep_going(1.0);
    let chosen = &found.chosen;
    let s = score::evaluate(&graph, chosen, &terms);
    let bound = found.bound.value.max(s.objective);
    let gap = relative_gap(s.objective, bound);
    let status = if gap <= 1e-9 {
        SolveStatus::Optimal
    } else if found.timed_out || Instant::now() >= deadline {
        SolveStatus::TimeLimit
    } else {
        SolveStatus::Feasible
    };

    let mut paired = vec![false; mesh.face_count()];
    let mut pairs: Vec<[usize; 2]> = Vec::new();
    for (t, _) in chosen.iter().enumerate().filter(|(_, c)| **c) {
        let faces = graph.tiles()[t].faces;
        faces.iter().for_each(|&f| paired[f] = true);
        pairs.push(faces);
    }
    pairs.sort_unstable();
    let unpaired = (0..mesh.face_count())
        .filter(|&f| mesh.is_quad(f) && !excluded[f] && !paired[f])
        .collect();
    let non_quad = (0..mesh.face_count())
        .filter(|&f| !mesh.is_quad(f))
        .collect();
    let excluded = (0..mesh.face_count()).filter(|&f| excluded[f]).collect();
    Ok(Pattern {
        faces: mesh.face_count(),
        pairs,
        unpaired,
        excluded,
        non_quad,
        continuous_joints: s.continuous_joints,
        shifted_pairs: s.shifted_pairs,
        bond_pairs: s.bond_pairs,
        objective: s.objective,
        bound,
        gap,
        status,
        bound_source: found.bound.source,
        seconds: started.elapsed().as_secs_f64(),
    })
}

/// A proven upper bound and where it came from.
#[derive(Clone, Copy)]
struct Bound {
    value: f64,
    source: BoundSource,
}

impl Bound {
    /// Keeps `value` if it is tighter.
    fn tighten(&mut self, value: f64, source: BoundSource) {
        if value < self.value {
            *self = Self { value, source };
        }
    }
}

/// A valid pattern and a proven bound on its objective.
struct Found {
    chosen: Vec<bool>,
    bound: Bound,
    /// A solver stopped on the time limit (CBC stops a little before the caller's deadline).
    timed_out: bool,
}

/// Zones give one bond per face of a mesh of `faces` faces (the quads to match, or in a
/// pipeline the surface they are remeshed from).
///
/// # Errors
/// [`PatternError::ZoneCount`] otherwise.
pub fn check_zone_count(given: usize, faces: usize) -> Result<(), PatternError> {
    if given == faces {
        Ok(())
    } else {
        Err(PatternError::ZoneCount { given, faces })
    }
}

fn validate_weights(bond: Bond) -> Result<(), PatternError> {
    match bond.weight() {
        Some(weight) if !(weight.is_finite() && weight >= 0.0) => {
            Err(PatternError::InvalidWeight { weight })
        }
        Some(weight) if weight > MAX_WEIGHT => Err(PatternError::WeightTooLarge {
            weight,
            max: MAX_WEIGHT,
        }),
        _ => Ok(()),
    }
}

/// Candidate-tile indices of the forced pairs, checked against the mesh.
fn forced_tiles(
    mesh: &PolyMesh,
    topology: &Topology,
    graph: &DualGraph,
    excluded: &[bool],
    pairs: &[[usize; 2]],
) -> Result<Vec<usize>, PatternError> {
    let mut used = vec![false; mesh.face_count()];
    let mut tiles = Vec::with_capacity(pairs.len());
    for &[a, b] in pairs {
        for f in [a, b] {
            if f >= mesh.face_count() {
                return Err(PatternError::FaceOutOfRange {
                    face: f,
                    face_count: mesh.face_count(),
                });
            }
            if excluded[f] {
                return Err(PatternError::ForcedExcluded { face: f });
            }
            if !mesh.is_quad(f) {
                return Err(PatternError::ForcedNonQuad {
                    face: f,
                    corners: mesh.faces()[f].len(),
                });
            }
            if std::mem::replace(&mut used[f], true) {
                return Err(PatternError::ForcedTwice { face: f });
            }
        }
        let adjacent = || {
            topology
                .face_edges(a)
                .iter()
                .any(|&e| topology.edges()[e].other_face(a) == Some(b))
        };
        let tile = graph.tile_between(a, b).ok_or_else(|| {
            if adjacent() {
                PatternError::ForcedAcrossCourses { a, b }
            } else {
                PatternError::ForcedNotAdjacent { a, b }
            }
        })?;
        tiles.push(tile);
    }
    Ok(tiles)
}
