//! The search behind [`solve`](super::solve()): the paper's route ([`Method::Mip`]: the whole
//! program on CBC) and the default engine ([`Method::Auto`]), one method per phase. Every
//! phase improves the pattern or tightens the bound, and the search ends as soon as the
//! pattern meets its bound (or comes within the caller's gap) or the deadline passes.

use std::time::{Duration, Instant};

use super::score::evaluate;
use super::{Bound, Found};
use super::{
    BoundSource, DualGraph, Method, PatternError, PatternOptions, Terms, anneal, bound, construct,
    decompose, linear, mip, program, search,
};
use crate::control::{Control, Figures, relative_gap};
use crate::mesh::Topology;

/// Faces per patch in the first decomposition bound of [`Method::Auto`]: patches this small
/// take CBC some 50 ms each. Meshes this small get the whole program at once.
const FIRST_PATCH_SIZE: usize = 200;
/// Faces per patch in the first round of linear patch relaxations: a few milliseconds each.
const FIRST_LINEAR_PATCH_SIZE: usize = 200;
/// How much longer a round of linear patch relaxations takes than the round before, with
/// patches twice as large and half as many (the barrier's time grows about as size^2 here,
/// plus room for the patches it skips in the smaller rounds).
const LINEAR_ROUND_GROWTH: f64 = 3.0;
/// Largest patches: a few seconds each for CBC.
const LAST_PATCH_SIZE: usize = 1600;
/// Largest program [`Method::Auto`] gives to CBC whole, in faces of a mesh whose faces may
/// pair either way (two candidate tiles per face): a program over level courses, where each
/// face pairs only along its course, counts half as many (see [`Engine::program_faces`]).
/// The root LP of larger staggered programs can take minutes (6589 faces: 110 s), and a solve
/// stopped before its root gives nothing for the time it took.
const WHOLE_MODEL_FACES: usize = 2000;
/// Share of the time left after the first annealing run that the linear relaxation of the
/// whole program may take; it is solved only if expected to finish in that time.
const LINEAR_SHARE: f64 = 0.9;
/// Share of the time limit the first annealing run may take, and of the time left the
/// later ones.
const FIRST_ANNEAL_SHARE: f64 = 0.5;
const ANNEAL_SHARE: f64 = 0.3;
/// Share of the time left that CBC may take in courses; the rest is for the usual route
/// should it not finish.
const COURSES_CBC_SHARE: f64 = 0.6;
/// See [`expected_courses_seconds`].
const COURSES_SECONDS_AT_3000_FACES: f64 = 1.5;
/// See [`expected_courses_seconds`].
const COURSES_TIME_EXPONENT: f64 = 1.5;
/// Share of the time left that annealing may take once the whole linear relaxation is
/// solved (the run ends sooner on small meshes, whose moves are capped per face).
const SOLVED_ANNEAL_SHARE: f64 = 0.9;
/// Each round's exact windows get the time left divided by this: after annealing they
/// rarely improve the pattern, and the bound needs the time more.
const WINDOW_SHARE: u32 = 6;
/// A start this far below the matching bound (or farther) is annealed from the full first
/// temperature; closer starts from proportionally cooler ones.
const MELT_GAP: f64 = 0.01;

/// One search: the program's inputs, the best pattern so far and the best bound.
pub(super) struct Engine<'a, 'c, P: Fn() -> f64> {
    graph: &'a DualGraph,
    topology: &'a Topology,
    options: &'a PatternOptions,
    /// The objective's bond terms (one bond, or zones).
    terms: &'a Terms<'a>,
    /// The forced tiles, held in every pattern.
    fixed: Vec<bool>,
    /// The tiles a solver may choose: all but the forced ones.
    free: Vec<bool>,
    deadline: Instant,
    control: &'a mut Control<'c>,
    progress: &'a P,
    /// A maximum matching with the forced tiles: no pattern has more tiles.
    matching: Vec<bool>,
    /// Tiles of `matching`.
    most_tiles: usize,
    /// The best pattern so far (forced tiles included).
    best: Vec<bool>,
    bound: Bound,
    /// A solver stopped on the time limit (CBC stops a little before the caller's deadline).
    timed_out: bool,
}

impl<'a, 'c, P: Fn() -> f64> Engine<'a, 'c, P> {
    /// A search for `options` on `graph` with the `forced` tiles, until `deadline`; the
    /// first bound is the maximum matching's.
    #[expect(
        clippy::too_many_arguments,
        reason = "the program's inputs, its limits and its control"
    )]
    pub fn new(
        graph: &'a DualGraph,
        topology: &'a Topology,
        options: &'a PatternOptions,
        terms: &'a Terms<'a>,
        forced: &[usize],
        deadline: Instant,
        control: &'a mut Control<'c>,
        progress: &'a P,
    ) -> Self {
        let mut fixed = vec![false; graph.tiles().len()];
        forced.iter().for_each(|&t| fixed[t] = true);
        let free: Vec<bool> = fixed.iter().map(|f| !f).collect();
        let matching = union(&bound::maximum_matching(graph, &free, &fixed), &fixed);
        let most_tiles = matching.iter().filter(|&&c| c).count();
        let bound = Bound {
            value: bound::from_tile_count(terms, most_tiles),
            source: BoundSource::Matching,
        };
        Self {
            graph,
            topology,
            options,
            terms,
            best: fixed.clone(),
            fixed,
            free,
            deadline,
            control,
            progress,
            matching,
            most_tiles,
            bound,
            timed_out: false,
        }
    }

    /// Runs the chosen [`Method`].
    pub fn run(mut self) -> Result<Found, PatternError> {
        match self.options.method {
            Method::Mip => self.paper_route()?,
            Method::Auto => self.default_route()?,
        }
        Ok(Found {
            chosen: self.best,
            bound: self.bound,
            timed_out: self.timed_out,
        })
    }

    /// The paper's route: the whole program on CBC, from a greedy start kept as a fallback.
    fn paper_route(&mut self) -> Result<(), PatternError> {
        construct::complete_greedily(self.graph, self.terms, &self.fixed, &mut self.best);
        let (cbc_bound, timed_out) = self.whole_program(self.left())?;
        self.tighten(cbc_bound, BoundSource::WholeProgram);
        self.timed_out = timed_out;
        Ok(())
    }

    /// The default engine: starts, annealing, the whole linear relaxation or linear patch
    /// relaxations, then rounds of exact patches, windows and annealing.
    fn default_route(&mut self) -> Result<(), PatternError> {
        self.best_start();
        if self.courses_route()? {
            return Ok(());
        }
        self.first_anneal()?;
        let relaxation_solved = self.linear_relaxation()?;
        // With the whole relaxation solved, the rounds below rarely tighten the bound soon,
        // and what is left is mostly the pattern's: anneal again, cooler, with most of the
        // time.
        if relaxation_solved && !self.done() {
            self.anneal(SOLVED_ANNEAL_SHARE, anneal::FIRST_TEMPERATURE / 2.0, 0)?;
        }
        if !self.terms.is_empty() && !relaxation_solved {
            self.linear_patch_rounds()?;
        }
        self.exact_rounds()
    }

    /// In courses (no face with more than two candidate tiles, as in level courses: each
    /// strip of quads along a course is a path of the dual graph), CBC proves the whole
    /// program in seconds where the engine's rounds stall: its root relaxation sees that a
    /// course of odd length leaves a half tile, which the linear relaxations of the rounds
    /// spread as halves over the whole course (on the shared dome's 6342 quads in level
    /// courses the engine ended at 3125 against a bound of 3166 after 60 s; CBC proved 3127
    /// in 3.5 s, and 17013 on a 34,324-quad dome in 48 s where the engine ended 0.7 % off).
    /// CBC gets [`COURSES_CBC_SHARE`] of the time left, and only when it is expected to
    /// finish in it ([`expected_courses_seconds`]); if it does not, the usual route takes
    /// over from the better of the start and CBC's pattern, with CBC's bound. (Until
    /// 2026-12-04 a short annealing ran first, to have a pattern should CBC not finish; the
    /// usual route anneals anyway, and with Clp's presolve off in courses (`mip`) CBC proves
    /// the 20 m cap in 5 s, so the 5 s of annealing before it were most of the stage.)
    /// Whether the search is over.
    fn courses_route(&mut self) -> Result<bool, PatternError> {
        let expected = expected_courses_seconds(self.program_faces());
        let budget = self.left().mul_f64(COURSES_CBC_SHARE);
        if !self.graph.in_courses()
            || self.terms.is_empty()
            || self.done()
            || expected > budget.as_secs_f64()
        {
            return Ok(false);
        }
        let (cbc_bound, cbc_timed_out) = self.whole_program(budget)?;
        self.tighten(cbc_bound, BoundSource::WholeProgram);
        if cbc_timed_out && !self.done() {
            // Slower than expected: the usual rounds get the time left, from the better of
            // the two patterns, with CBC's bound.
            return Ok(false);
        }
        Ok(true)
    }

    /// Objective of `chosen`.
    fn value(&self, chosen: &[bool]) -> f64 {
        evaluate(self.graph, chosen, self.terms).objective
    }

    /// The pattern meets its bound, or comes within the gap the caller accepts.
    fn done(&self) -> bool {
        let objective = self.value(&self.best);
        self.bound.value - objective <= 1e-9
            || relative_gap(objective, self.bound.value) <= self.options.gap
    }

    /// Time to the deadline.
    fn left(&self) -> Duration {
        self.deadline.saturating_duration_since(Instant::now())
    }

    /// Keeps `value` as the bound if tighter, rounded down to the next objective value a
    /// pattern can take.
    fn tighten(&mut self, value: f64, source: BoundSource) {
        let rounded = bound::round_down(value, self.terms, 1.0, self.most_tiles as f64);
        self.bound.tighten(rounded, source);
        self.note();
    }

    /// Tells a watching caller (the command line's progress line) the best objective and the
    /// bound so far; they reach it with the next progress report.
    fn note(&mut self) {
        let best = self.value(&self.best);
        self.control.note(Figures {
            best,
            bound: self.bound.value,
        });
    }

    /// The whole program on CBC for `limit`: keeps CBC's pattern if it beats the best, and
    /// returns CBC's bound and whether it stopped on time.
    fn whole_program(&mut self, limit: Duration) -> Result<(f64, bool), PatternError> {
        let outcome = mip::solve(
            self.graph,
            self.terms,
            self.options.formulation,
            &program::Restriction {
                free: &self.free,
                fixed: &self.fixed,
                patch: None,
            },
            limit,
            self.options.gap,
            self.control,
            self.progress,
        )?;
        if let Some(found) = outcome.chosen.map(|c| union(&c, &self.fixed)) {
            if search::is_matching(self.graph, &found)
                && self.value(&found) > self.value(&self.best)
            {
                self.best = found;
            }
        }
        Ok((outcome.bound, outcome.timed_out))
    }

    /// The best of three cheap starts, each strong where the others are weak: courses
    /// parallel to the boundary (the optimal stagger of regular patches), the running bond
    /// along quad strips (no joints in the interior), the maximum matching (fewest half
    /// tiles).
    fn best_start(&mut self) {
        let (graph, terms, fixed) = (self.graph, self.terms, &self.fixed);
        let mut starts = if terms.is_empty() {
            vec![self.matching.clone()]
        } else {
            let courses = construct::boundary_courses(graph, self.topology, terms, fixed);
            let laid = union(
                &construct::running_bond(graph, self.topology, terms, fixed),
                fixed,
            );
            vec![courses, laid, self.matching.clone()]
        };
        starts.sort_by(|a, b| self.value(b).total_cmp(&self.value(a)));
        self.best = starts.swap_remove(0);
        self.note();
    }

    /// Anneals the best pattern for `share` of the time left from `temperature`.
    fn anneal(&mut self, share: f64, temperature: f64, seed: u64) -> Result<(), PatternError> {
        let budget = self.left().mul_f64(share);
        let schedule =
            anneal::Schedule::for_budget(self.graph.face_count(), budget, temperature, seed);
        let progress = self.progress;
        let control = &mut *self.control;
        let on = anneal::anneal(
            self.graph,
            self.terms,
            &self.fixed,
            &mut self.best,
            &schedule,
            Instant::now() + budget,
            &mut || control.keep_going(progress()),
        );
        if on {
            Ok(())
        } else {
            Err(PatternError::Cancelled)
        }
    }

    /// Annealing moves the defects of the best start until most of them cancel. A start
    /// already close to the bound (a regular mesh) is polished cool rather than melted: a
    /// full melt needs more moves than a large mesh gets to beat it again.
    fn first_anneal(&mut self) -> Result<(), PatternError> {
        if self.done() {
            return Ok(());
        }
        let gap = relative_gap(self.value(&self.best), self.bound.value);
        let temperature = (anneal::FIRST_TEMPERATURE * gap / MELT_GAP)
            .clamp(anneal::LAST_TEMPERATURE, anneal::FIRST_TEMPERATURE);
        self.anneal(FIRST_ANNEAL_SHARE, temperature, 1)
    }

    /// The linear relaxation of the whole program, if the barrier is expected to finish in
    /// the time left: it sees across the seams between forced defects that patches cut.
    /// Whether it converged.
    fn linear_relaxation(&mut self) -> Result<bool, PatternError> {
        if self.terms.is_empty()
            || self.done()
            || linear::expected_seconds(self.graph.face_count())
                > self.left().as_secs_f64() * LINEAR_SHARE
        {
            return Ok(false);
        }
        let Some(found) = linear::bound(
            self.graph,
            self.terms,
            None,
            self.left().mul_f64(LINEAR_SHARE),
            self.control,
            self.progress,
        )?
        else {
            return Ok(false);
        };
        self.tighten(found.value, BoundSource::LinearRelaxation);
        Ok(found.converged)
    }

    /// Linear relaxations of patches: with the star rows they come within about half a
    /// tile per patch of the integer patches' bound in a small part of the time, so patches
    /// can be larger. Patches double, each round made of the last one's, while the last
    /// round's time, grown as a linear program's does with its size, fits the time left.
    fn linear_patch_rounds(&mut self) -> Result<(), PatternError> {
        let mut size = FIRST_LINEAR_PATCH_SIZE;
        let mut finer: Option<(decompose::Partition, decompose::Proven)> = None;
        // These rounds only tighten the bound (and `tighten` notes it): the best stays.
        self.note();
        while !self.done() && Instant::now() < self.deadline {
            let partition = decompose::next_partition(self.graph, size, 0, &[], finer.take());
            let started = Instant::now();
            let proven_here = decompose::bound(
                self.graph,
                self.terms,
                true,
                &partition,
                &self.best,
                started + self.left() / 2,
                self.control,
                self.progress,
            )?;
            if let Some(patches) = proven_here.value {
                self.tighten(patches, BoundSource::Patches);
            }
            if partition.count <= 1
                || started.elapsed().mul_f64(LINEAR_ROUND_GROWTH) > self.left() / 3
            {
                break;
            }
            finer = Some((partition, proven_here));
            size *= 2;
        }
        Ok(())
    }

    /// The program's size in faces of a mesh whose faces pair either way: half its candidate
    /// tiles (a free quad has two, one along each of its directions; in level courses it has
    /// one), which is what CBC's root LP grows with.
    fn program_faces(&self) -> usize {
        self.graph.tiles().len().div_ceil(2)
    }

    /// Rounds of: a decomposition bound with patches twice as large as the round before,
    /// made of its patches (so nothing proven is lost when the deadline cuts a round short)
    /// and centred on the forced defects it found (the last round, one patch, is the whole
    /// program); exact windows around the defects; annealing again from the best pattern,
    /// cooler.
    fn exact_rounds(&mut self) -> Result<(), PatternError> {
        let faces = self.graph.face_count();
        let whole = self.program_faces() <= WHOLE_MODEL_FACES;
        let mut size = FIRST_PATCH_SIZE;
        let mut variant = 0;
        let mut round = 0;
        // Faces where patch relaxations found forced defects: the next patches are centred
        // there.
        let mut sources: Vec<usize> = Vec::new();
        // The last round's partition and what it proved.
        let mut finer: Option<(decompose::Partition, decompose::Proven)> = None;
        while !self.done() && Instant::now() < self.deadline {
            self.note();
            if size >= faces
                && whole
                && mip::expected_linear_seconds(self.program_faces()) <= self.left().as_secs_f64()
            {
                let (cbc_bound, cbc_timed_out) = self.whole_program(self.left())?;
                self.tighten(cbc_bound, BoundSource::WholeProgram);
                self.timed_out = cbc_timed_out;
                break;
            }
            // Larger patches are unions of the last round's, which keeps what that round
            // proved; varied partitions of the largest size start afresh.
            let partition = decompose::next_partition(
                self.graph,
                size,
                variant,
                &sources,
                finer.take().filter(|_| variant == 0),
            );
            let step_deadline = Instant::now() + self.left() / 2;
            let proven_here = decompose::bound(
                self.graph,
                self.terms,
                false,
                &partition,
                &self.best,
                step_deadline,
                self.control,
                self.progress,
            )?;
            if let Some(patches) = proven_here.value {
                self.tighten(patches, BoundSource::Patches);
            }
            // This round's sources (from larger patches, so more telling) first, then earlier
            // ones.
            sources = proven_here
                .sources
                .iter()
                .map(|s| s.face)
                .chain(sources)
                .collect();
            finer = Some((partition, proven_here));
            if self.done() {
                break;
            }
            let windows_until = Instant::now() + self.left() / WINDOW_SHARE;
            search::improve(
                self.graph,
                self.terms,
                &self.fixed,
                &mut self.best,
                windows_until,
                self.control,
                self.progress,
            )?;
            round += 1;
            self.anneal(ANNEAL_SHARE, anneal::FIRST_TEMPERATURE / 2.0, 1 + round)?;
            // Patches grow to the largest size; from there on their partitions vary instead.
            if size < LAST_PATCH_SIZE || (size < faces && whole) {
                size *= 2;
            } else {
                variant += 1;
            }
        }
        Ok(())
    }
}

/// About how long CBC takes to prove the whole program in courses over `faces` program
/// faces ([`Engine::program_faces`], about half the quads in courses). Measured here (2
/// cores, 2026-12-02, level courses, 150 mm quads): 1252 quads 0.13 s, 2419: 0.28 s, 3127
/// (a sphere's): 2.5 s, 3798: 0.34 s, 6342: 3.5 s, 6885: 2.0 s, 34,324: 48 s; again on
/// 2026-12-04 (`match --courses level --method mip`): 1264 quads 0.10 s, 2412-2573 (domes)
/// 1.1-2.0 s, 3128 (a sphere's) 0.47 s, 3791 0.39 s, 6342: 2.9 s, the 20 m cap's 34,330:
/// 20.8 s. This rough fit (0.14 s expected for 1264 quads, 1.6 s for 6342, 20.5 s for
/// 34,330) is within about a factor of two of most, and under the domes of 2400-3100 quads
/// (0.5-0.6 s expected); CBC gets more than it expects ([`COURSES_CBC_SHARE`] of the time
/// left once it fits) and hands over to the rounds should it not finish. At 3 s for 3000
/// program faces (the fit of 2026-12-02) the 20 m cap was expected to take 41 s, more than
/// the 32 s CBC gets of the default 60, and the rounds ended 1.1 % from the bound (16877.5)
/// where CBC proves 17014 in 21 s. With Clp's presolve off in courses (`mip`, later on
/// 2026-12-04) CBC is faster still (1155-6342 quads 0.07-0.52 s, one 2060-quad mesh 2.4 s,
/// the 20 m cap 5.4 s), so this fit now expects too much for most; it only decides whether
/// CBC is tried, and trying it on the programs it underestimates costs little.
fn expected_courses_seconds(faces: usize) -> f64 {
    COURSES_SECONDS_AT_3000_FACES * (faces as f64 / 3000.0).powf(COURSES_TIME_EXPONENT)
}

/// Tiles chosen in `a` or in `b`.
fn union(a: &[bool], b: &[bool]) -> Vec<bool> {
    a.iter().zip(b).map(|(x, y)| *x || *y).collect()
}
