//! `tilepattern`: the command line. It parses arguments, calls the library, writes files.
//! Command names, flags and JSON fields are a contract that users' scripts rely on.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{Context, Result, bail};
use clap::{Parser, Subcommand, ValueEnum};
use nalgebra::Point3;
use serde::Serialize;
use tilepattern::control::Control;
use tilepattern::mesh::io::{Loaded, Weld};

#[path = "tilepattern/field_file.rs"]
mod field_file;
#[path = "tilepattern/file_order.rs"]
mod file_order;
#[path = "tilepattern/guide_file.rs"]
mod guide_file;
#[path = "tilepattern/progress_line.rs"]
mod progress_line;
#[path = "tilepattern/zones_file.rs"]
mod zones_file;
use progress_line::ProgressLine;
use tilepattern::mesh::{self, MeshError, PolyMesh};
use tilepattern::pattern::{self, Bond, Courses, Formulation, Method, Pattern, PatternOptions};
use tilepattern::pipeline::{self, Tiling, Tries};
use tilepattern::remesh::{FieldDirection, Metrics, RemeshOptions};
use tilepattern::report::{JointSummary, Report, Warning, WarningCode, svg};
use tilepattern::tiles::{self, CutGroup, FinishOptions, Sequence, Tile, TileKind, TileSpec};

#[derive(Parser)]
#[command(
    name = "tilepattern",
    version,
    about = "Tile laying patterns for free-form shells that need little cutting"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Join mesh vertices closer than this fraction of the bounding-box diagonal when reading
    /// a file (triangle soups, STL), or `off` to keep the file's vertices as they are.
    #[arg(long, global = true, value_parser = parse_weld, default_value = "1e-6")]
    weld: Weld,
    /// Take the surface as one sheet: no split where its faces turn sharply (by default a
    /// groin vault's webs get quads of their own and the tiles are cut to the groins).
    #[arg(long, global = true)]
    no_creases: bool,
    /// Write the progress as a log on standard error, one line per stage, per change of the
    /// pattern's best or bound and every 5 s, terminal or not (as a MIP solver's log),
    /// instead of one line redrawn on a terminal.
    #[arg(long, global = true)]
    log: bool,
}

#[derive(Subcommand)]
enum Command {
    /// Match the faces of a quad mesh into tiles (paper eqs. 1-3) and write the pairs as JSON.
    Match {
        /// Quad mesh (OBJ, STL, PLY or OFF). Face indices given (--force, --exclude, --zones) and written are 0-based in the file's order: a face that reading removes (collapsed by welding, or repeating another; the `vertices_welded` warning counts them) is in no pair and shifts no other, and `--weld off` keeps every face.
        quads: PathBuf,
        #[command(flatten)]
        pattern: PatternArgs,
        /// Up direction x,y,z for level courses (`--courses level`).
        #[arg(long, value_parser = parse_vector, default_value = "0,0,1")]
        up: [f64; 3],
        /// Zones: a bond per face of the quad mesh, from a file of `FACE BOND` or
        /// `FIRST-LAST BOND` lines (or JSON, see the README); faces not listed take --pattern,
        /// every zone --weight.
        #[arg(long, value_name = "FILE")]
        zones: Option<PathBuf>,
        /// Where to write the result JSON (stdout when omitted).
        #[arg(long)]
        json: Option<PathBuf>,
    },
    /// Build tile boxes for pairs written by `match`.
    Tiles {
        /// The quad mesh the pairs refer to (OBJ, STL, PLY or OFF).
        quads: PathBuf,
        /// JSON written by `tilepattern match`.
        #[arg(long)]
        pairs: PathBuf,
        #[command(flatten)]
        tile: TileArgs,
        /// Tile boxes as OBJ, one object per tile.
        #[arg(short, long)]
        output: PathBuf,
        /// Report JSON.
        #[arg(long)]
        json: Option<PathBuf>,
        /// Picture of the pattern (SVG).
        #[arg(long)]
        svg: Option<PathBuf>,
        /// The input surface the quads were made from (OBJ, STL, PLY or OFF): tiles are cut to its boundary
        /// (default: the quad mesh's own boundary).
        #[arg(long)]
        surface: Option<PathBuf>,
        /// Folder for the fabrication output: cutlist.csv, cutlist.json, sequence.json,
        /// gaps.svg.
        #[arg(long)]
        fabrication: Option<PathBuf>,
        /// The bond the pairs were matched for (`match --pattern`): the fit stage keeps it.
        #[arg(long, value_enum, default_value_t = BondArg::Staggered)]
        pattern: BondArg,
    },
    /// Quadrangulate a triangle (or polygon) mesh into near-square quads of edge T (stage 1).
    Remesh {
        /// Input surface (OBJ, STL, PLY or OFF).
        input: PathBuf,
        /// Target quad edge in model units.
        #[arg(long, allow_negative_numbers = true)]
        edge: f64,
        #[command(flatten)]
        field: FieldArgs,
        /// Quad mesh (OBJ).
        #[arg(short, long)]
        output: PathBuf,
        /// Quality metrics (JSON).
        #[arg(long)]
        json: Option<PathBuf>,
        /// Wall-clock limit in seconds: when it passes the quad mesh as it stands is written
        /// (final fitting cut short), or the command fails if none is ready yet.
        #[arg(long, default_value_t = 60.0, allow_negative_numbers = true)]
        time_limit: f64,
    },
    /// All three stages on a surface: remesh with quads of (L + joint) / 2, match, tile.
    Run {
        /// Input surface (OBJ, STL, PLY or OFF).
        input: PathBuf,
        #[command(flatten)]
        tile: TileArgs,
        #[command(flatten)]
        field: FieldArgs,
        #[command(flatten)]
        pattern: PatternArgs,
        /// Zones: a bond per face of the INPUT surface (each quad takes the zone of the input
        /// face closest to its centroid), from a file of `FACE BOND` or `FIRST-LAST BOND`
        /// lines (or JSON, see the README); faces not listed take --pattern, every zone
        /// --weight. The quads' zones are written to zones.txt.
        #[arg(long, value_name = "FILE")]
        zones: Option<PathBuf>,
        /// Wall-clock limit of the remesh stage in seconds (`--time-limit` is the pattern
        /// stage's).
        #[arg(long, default_value_t = 60.0, allow_negative_numbers = true)]
        remesh_time_limit: f64,
        #[command(flatten)]
        tries: TriesArg,
        /// Output folder for quads.obj, tiles.obj, report.json, pattern.svg, cutlist.csv,
        /// cutlist.json, sequence.json, gaps.svg.
        #[arg(long)]
        out: PathBuf,
    },
    /// Run the whole pipeline on a built-in example: a shell supported at its four corners
    /// (the paper's Figure 9), tiled with 280 x 140 x 15 mm tiles.
    Demo {
        /// Output folder for quads.obj, tiles.obj, report.json, pattern.svg, cutlist.csv,
        /// cutlist.json, sequence.json, gaps.svg.
        #[arg(long, default_value = "demo")]
        out: PathBuf,
        /// Plan size of the shell in metres.
        #[arg(long, default_value_t = 3.0, allow_negative_numbers = true)]
        span: f64,
        #[command(flatten)]
        pattern: PatternArgs,
        /// Keep the paper's placement (section 3.5): no fit stage.
        #[arg(long)]
        no_fit: bool,
        /// Wall-clock limit of the remesh stage in seconds (as `run`'s; a span of 50 m or
        /// more needs more than the default).
        #[arg(long, default_value_t = 60.0, allow_negative_numbers = true)]
        remesh_time_limit: f64,
        #[command(flatten)]
        tries: TriesArg,
    },
}

#[derive(clap::Args)]
struct FieldArgs {
    /// Align quads with this direction x,y,z (projected onto the surface) instead of the
    /// principal curvature.
    #[arg(long, value_parser = parse_vector, conflicts_with = "angle")]
    direction: Option<[f64; 3]>,
    /// Rotate the curvature-aligned field by this many degrees (e.g. 45).
    #[arg(long, allow_negative_numbers = true)]
    angle: Option<f64>,
    /// Follow neither the curvature nor a direction: the boundary and smoothness alone orient
    /// the quads (run's second try). Where the curvature lines converge (a cone, a funnel, a
    /// bend) its quads end fewer rows and the tiles are cut less.
    #[arg(long, conflicts_with_all = ["direction", "angle"])]
    smooth: bool,
    /// Pull faces towards squares (shape-up) without leaving the surface.
    #[arg(long)]
    shapeup: bool,
    /// The designer's direction field (e.g. principal stress or thrust directions): a CSV
    /// (x,y,z per line) or JSON ([[x,y,z], ...]) file with one vector per input vertex or one
    /// per input face, told apart by the count; signs and lengths do not matter.
    #[arg(long, value_name = "FILE")]
    field: Option<PathBuf>,
    /// Share of --field against the curvature field (or --direction / --angle), from 0 to 1.
    #[arg(
        long,
        default_value_t = 1.0,
        requires = "field",
        allow_negative_numbers = true
    )]
    field_weight: f64,
    /// Guide curves the quad rows follow near them: polylines in the mesh's units, as text
    /// (x y z per line, a blank line between curves) or JSON ([[[x,y,z], ...], ...]); each
    /// pulls within 2 target edges of it.
    #[arg(long, value_name = "FILE")]
    guides: Option<PathBuf>,
    /// Share of --guides on the curves against every other source, from 0 to 1.
    #[arg(
        long,
        default_value_t = 1.0,
        requires = "guides",
        allow_negative_numbers = true
    )]
    guide_weight: f64,
    /// Strength of the field's renormalising steps, which place its cones and with them where
    /// rows end (any number from 0): other strengths give other, equally valid quads, whose
    /// tiles may fit better. `run` tries this, twice and half of it, and a smooth field
    /// (--tries).
    #[arg(long, default_value_t = tilepattern::remesh::RENORMALISATION, allow_negative_numbers = true)]
    renormalisation: f64,
}

impl FieldArgs {
    /// The remesh options for quads of edge `target_edge` on `surface` (the field file's
    /// vectors are counted against its vertices and faces, or its file's as `numbering`
    /// has them), split at its creases or not.
    fn options(
        &self,
        target_edge: f64,
        surface: &PolyMesh,
        numbering: &mesh::FileNumbering,
        creases: bool,
    ) -> Result<RemeshOptions> {
        let direction = match (self.direction, self.angle) {
            (Some(v), _) => FieldDirection::Vector(v),
            (None, Some(a)) => FieldDirection::Angle(a),
            (None, None) if self.smooth => FieldDirection::Smooth,
            (None, None) => FieldDirection::Curvature,
        };
        let user_field = self
            .field
            .as_deref()
            .map(|path| field_file::read(path, surface, numbering, self.field_weight))
            .transpose()?;
        let guides = self
            .guides
            .as_deref()
            .map(|path| guide_file::read(path, self.guide_weight, surface, target_edge))
            .transpose()?;
        Ok({
            let mut o = RemeshOptions::default();
            o.target_edge = target_edge;
            o.direction = direction;
            o.user_field = user_field;
            o.guides = guides;
            o.shapeup = self.shapeup;
            o.creases = creases;
            o.renormalisation = self.renormalisation;
            o
        })
    }
}

#[derive(clap::Args)]
struct TriesArg {
    /// Quad meshes to lay tiles on, keeping the tiles that fit best (fewest cut, joints closest
    /// to the nominal one, most of the surface covered; report.json lists each try): 1 to 6,
    /// the field's cones placed by a renormalisation at --renormalisation's strength (run;
    /// the default for demo), then a smooth field that follows neither the curvature nor
    /// anything else (made only when no --direction, --angle, --field or --guides is given),
    /// then twice and half the strength, then the smooth field's quads laid out for level
    /// courses, half a tile and a joint along them (made only in level courses), then the
    /// smooth field free of the boundary, its rows cut to curved edges instead of following
    /// them (made only where the first try follows an edge with corners). Default: all of
    /// them on surfaces of at most 10,000 quads, 1 on larger ones. Each try has the stages'
    /// time limits.
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=6))]
    tries: Option<u64>,
}

impl TriesArg {
    /// The pipeline's tries (none given: [`Tries::Auto`]).
    fn tries(&self) -> Tries {
        self.tries.map_or(Tries::Auto, |n| Tries::Count(n as usize))
    }
}

#[derive(clap::Args)]
struct PatternArgs {
    /// Laying pattern: stack = maximum matching (eq. 1), staggered (eq. 2), running-bond (eq. 3),
    /// herringbone (90-degree zig-zag), basket-weave (2 x 2 squares of parallel tiles,
    /// alternating); the last two lay tiles either way (courses free by default, level refused).
    #[arg(long, value_enum, default_value_t = BondArg::Staggered)]
    pattern: BondArg,
    /// Weight of the bond term: penalty per continuous joint (staggered), reward per shifted
    /// pair (running-bond), penalty per continuous joint or end-to-end pair (herringbone),
    /// penalty per shifted, end-to-end or one-course-apart pair (basket-weave).
    #[arg(long, default_value_t = pattern::DEFAULT_WEIGHT, allow_negative_numbers = true)]
    weight: f64,
    /// Solver time limit in seconds (wall clock). 0 returns the greedy start without solving.
    #[arg(long, default_value_t = 60.0, allow_negative_numbers = true)]
    time_limit: f64,
    /// Stop once the relative gap (bound - objective) / bound is at most this, like a MIP
    /// solver's gap: 0 proves optimality (or runs to the time limit), 0.01 stops within 1 %.
    #[arg(long, default_value_t = 0.0)]
    gap: f64,
    /// How the integer program is written; both reach the same optimum.
    #[arg(long, value_enum, default_value_t = FormulationArg::Strengthened)]
    formulation: FormulationArg,
    /// Search route: auto = bound, running-bond start, window search, whole model when small;
    /// mip = the paper's whole program on CBC.
    #[arg(long, value_enum, default_value_t = MethodArg::Auto)]
    method: MethodArg,
    /// A pair of faces that must form a tile, as A,B (repeatable; quads of `match`, which
    /// `run` makes itself and so refuses).
    #[arg(long = "force", value_parser = parse_pair)]
    forced: Vec<[usize; 2]>,
    /// Faces to leave out (openings, areas laid by hand), comma separated: quads of `match`,
    /// faces of the input surface in `run` (each quad whose closest input face is one is left
    /// out).
    #[arg(long, value_delimiter = ',')]
    exclude: Vec<usize>,
    /// Which way tiles may lie: level = all along level courses (default of run and demo:
    /// tiles that fit), free = either way across any quad (the paper's eqs. 1-3, default of
    /// match).
    #[arg(long, value_enum)]
    courses: Option<CoursesArg>,
}

#[derive(Clone, Copy, PartialEq, ValueEnum)]
enum CoursesArg {
    Level,
    Free,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum BondArg {
    Stack,
    Staggered,
    RunningBond,
    Herringbone,
    BasketWeave,
}

#[derive(Clone, Copy, ValueEnum)]
enum MethodArg {
    Auto,
    Mip,
}

#[derive(Clone, Copy, ValueEnum)]
enum FormulationArg {
    Paper,
    Strengthened,
}

#[derive(clap::Args)]
struct TileArgs {
    /// Tile size LxWxT in millimetres, e.g. 280x140x15.
    #[arg(long, value_parser = parse_tile, allow_hyphen_values = true)]
    tile: [f64; 3],
    /// Mortar joint in millimetres.
    #[arg(long, default_value_t = 10.0, value_parser = parse_mm, allow_negative_numbers = true)]
    joint: f64,
    /// Units of the mesh coordinates (in = inches, ft = feet); auto = the one reading (m, cm
    /// or mm) under which the mesh is a plausible shell for this tile (see the README); it
    /// refuses when two readings are plausible. Inches and feet are never guessed: give them.
    #[arg(long, value_enum, default_value_t = Units::Auto)]
    units: Units,
    /// Cutting tolerance in millimetres: tiles the boundary enters by no more than this stay
    /// whole, cut shapes this close share a label (default: 1 % of the tile width).
    #[arg(long, value_parser = parse_mm, allow_negative_numbers = true)]
    cut_tolerance: Option<f64>,
    /// Boundary pieces narrower than this (millimetres) are reported as slivers, not emitted
    /// (default: a fifth of the tile width).
    #[arg(long, value_parser = parse_mm, allow_negative_numbers = true)]
    min_kept_width: Option<f64>,
    /// Up direction x,y,z for the laying order.
    #[arg(long, value_parser = parse_vector, default_value = "0,0,1")]
    up: [f64; 3],
    /// Tiles with a boundary edge within this height (millimetres) of the lowest boundary
    /// point stand on the supports (default: one tile width).
    #[arg(long, value_parser = parse_mm, allow_negative_numbers = true)]
    support_band: Option<f64>,
    /// Keep the paper's placement (section 3.5): no fit stage moving tiles to even joints.
    #[arg(long)]
    no_fit: bool,
    /// Wall-clock limit of the fit stage in seconds; when it passes, the best placement so far
    /// is kept (and again for filling the fit's tears with pieces: those laid so far are kept).
    /// It also sizes, by a count of work and not the clock, the largest first placement that a
    /// second one (with closers) may follow, so the same input gives the same tiles on any
    /// machine.
    #[arg(long, default_value_t = 10.0, allow_negative_numbers = true)]
    fit_time_limit: f64,
    /// Overlaps the fit leaves (millimetres); deeper ones are cut (default: a twentieth of
    /// the joint, at least a three-hundredth of the tile's width).
    #[arg(long, value_parser = parse_mm, allow_negative_numbers = true)]
    overlap_tolerance: Option<f64>,
    /// How far (millimetres) the fit may move a running bond's half offset or an aligned
    /// joint (default: a tenth of the tile length).
    #[arg(long, value_parser = parse_mm, allow_negative_numbers = true)]
    bond_tolerance: Option<f64>,
}

#[derive(Clone, Copy, PartialEq, ValueEnum)]
enum Units {
    Auto,
    M,
    Cm,
    Mm,
    In,
    Ft,
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error:#}");
            ExitCode::FAILURE
        }
    }
}

fn run(cli: Cli) -> Result<()> {
    let weld = cli.weld;
    let creases = !cli.no_creases;
    let log = cli.log;
    let read_mesh = |path: &Path| read_mesh(path, weld);
    match cli.command {
        Command::Match {
            quads,
            pattern,
            up,
            zones,
            json,
        } => {
            let loaded = read_mesh(&quads)?;
            print_warnings(&reading_warnings(&loaded));
            let numbering = loaded.numbering;
            let shrunk = loaded.weld.shrunk_faces;
            let mesh = loaded.mesh;
            // Faces that are not quads are left out of the pattern (its `non_quad`); said, so
            // that a triangle mesh given by mistake does not end in "0 tiles" and nothing else.
            let quad_faces = (0..mesh.face_count()).filter(|&f| mesh.is_quad(f)).count();
            if quad_faces < mesh.face_count() {
                let which = if quad_faces == 0 {
                    format!("none of the {} faces is a quad", mesh.face_count())
                } else {
                    format!(
                        "{} of the {} faces are not quads",
                        mesh.face_count() - quad_faces,
                        mesh.face_count()
                    )
                };
                // Quads with a collapsed edge (QuadriFlow leaves some) are triangles once
                // welded: said, since the file does give them four corners.
                let welded = if shrunk > 0 {
                    format!(
                        " ({shrunk} of the file's faces lost a corner, two neighbouring corners lying at one place or one corner given twice in a row, as a triangle written as a quad is: give --weld off to match quads with a collapsed edge as the file gives them)"
                    )
                } else {
                    String::new()
                };
                eprintln!(
                    "warning: {which}{welded}: `match` pairs quads into tiles and leaves the others out (non_quad in its JSON); make quads of half a tile first (`tilepattern remesh {} --edge T -o quads.obj`, T = (length + joint) / 2), or tile the surface with `tilepattern run`",
                    quads.display()
                );
            }
            // Face numbers given and written are the file's (welding may remove faces).
            let zones = zones
                .map(|path| {
                    zones_file::read(&path, numbering.file_faces(), "quad mesh")
                        .map(|z| numbering.faces_from_file(&z))
                })
                .transpose()?;
            let mut options = pattern.options(false, up, zones.as_deref())?;
            options.excluded_faces =
                file_order::mesh_faces(&numbering, &options.excluded_faces, "--exclude")?;
            options.forced_pairs = options
                .forced_pairs
                .iter()
                .map(|&[a, b]| file_order::mesh_pair(&numbering, [a, b], "--force"))
                .collect::<Result<_>>()?;
            let mut line = ProgressLine::on_stderr(log);
            let found = pattern::solve_with(
                &mesh,
                &options,
                &mut Control::with_figures(&mut |fraction, figures| {
                    line.update("pattern", fraction, figures)
                }),
            );
            line.finish();
            let found = found.map_err(|e| e.in_file_numbers(&numbering))?;
            eprintln!("{}", pattern_summary(&found));
            write_json(
                json.as_deref(),
                &MatchFile {
                    pattern: &file_order::pattern_in_file(&found, &numbering),
                    zones: zones.map(|z| zones_file::counts(&pattern.zone_bonds(&z))),
                },
            )
        }
        Command::Tiles {
            quads,
            pairs,
            tile,
            output,
            json,
            svg,
            surface,
            fabrication,
            pattern,
        } => {
            let loaded = read_mesh(&quads)?;
            let surface = surface.map(|path| read_mesh(&path)).transpose()?;
            let mut welds: Vec<Warning> = std::iter::once(&loaded)
                .chain(surface.as_ref())
                .flat_map(reading_warnings)
                .collect();
            let numbering = loaded.numbering;
            let mesh = loaded.mesh;
            let (surface, surface_numbering) = surface.map(|s| (s.mesh, s.numbering)).unzip();
            let text = std::fs::read_to_string(&pairs)
                .with_context(|| format!("cannot read {}", pairs.display()))?;
            let found: Pattern = serde_json::from_str(&text).with_context(|| {
                format!(
                    "{} is not the JSON written by `tilepattern match`",
                    pairs.display()
                )
            })?;
            let found = file_order::pattern_from_file(found, &numbering)
                .with_context(|| format!("{}", pairs.display()))?;
            let (spec, units) = tile.spec(surface.as_ref().unwrap_or(&mesh))?;
            eprintln!("{}", units.why);
            let finish = pipeline::with_bond(
                &tile.finish(&spec, units.unit, creases),
                pattern.bond(pattern::DEFAULT_WEIGHT),
            );
            let mut tiling =
                pipeline::tiles_for_pattern(&mesh, surface.as_ref(), found, &spec, &finish)
                    .map_err(|e| units.explain(e.in_file_numbers(&numbering)))?;
            // Warnings name faces of the surface the tiles were cut to, in its file's numbers.
            let checked = surface_numbering.as_ref().unwrap_or(&numbering);
            in_file_numbers(&mut tiling.report.warnings, checked);
            tiling.report.warnings.append(&mut welds);
            // The tiles left out, by the quads' numbers in their file.
            let slivers = tiling
                .report
                .cutting
                .iter_mut()
                .flat_map(|c| &mut c.slivers);
            for f in slivers.flat_map(|dropped| &mut dropped.faces) {
                *f = numbering.file_face(*f);
            }
            let units = units.unit;
            write_text(&output, &tiles::to_obj(&tiling.tiles))?;
            if let Some(svg_path) = svg {
                write_text(&svg_path, &svg::pattern_svg(&mesh, &tiling.tiles))?;
            }
            if let Some(dir) = fabrication {
                write_fabrication(&dir, &mesh, &tiling, units, Some(&numbering))?;
            }
            eprintln!("{}", tiling_summary(&tiling, units));
            print_warnings(&tiling.report.warnings);
            json.map_or(Ok(()), |path| {
                write_json(
                    Some(&path),
                    &ReportFile {
                        units: units.name(),
                        remesh: None,
                        report: &tiling.report,
                        zones: None,
                    },
                )
            })
        }
        Command::Remesh {
            input,
            edge,
            field,
            output,
            json,
            time_limit,
        } => {
            let loaded = read_mesh(&input)?;
            print_warnings(&reading_warnings(&loaded));
            let surface = &loaded.mesh;
            let options = {
                let mut o = field.options(edge, surface, &loaded.numbering, creases)?;
                o.time_limit = RemeshOptions::time_limit_from_secs(time_limit)?;
                o
            };
            let remeshed = tilepattern::remesh::remesh(surface, &options)?;
            mesh::obj::write(&remeshed.quads, &output)?;
            eprintln!("{}", remesh_summary(&remeshed.metrics));
            print_warnings(
                &tilepattern::report::warnings::quad_size_of(
                    remeshed.metrics.edges_within_20pct,
                    edge,
                )
                .into_iter()
                .collect::<Vec<_>>(),
            );
            json.map_or(Ok(()), |path| write_json(Some(&path), &remeshed.metrics))
        }
        Command::Run {
            input,
            tile,
            field,
            pattern,
            zones,
            remesh_time_limit,
            tries,
            out,
        } => {
            output_folder(&out)?;
            let loaded = read_mesh(&input)?;
            let surface = &loaded.mesh;
            // Zones per face of the file (welding may remove or zipping split faces).
            let zones = zones
                .map(|path| {
                    zones_file::read(&path, loaded.numbering.file_faces(), "input surface")
                        .map(|z| loaded.numbering.faces_from_file(&z))
                })
                .transpose()?;
            let (spec, units) = tile.spec(surface)?;
            eprintln!("{}", units.why);
            let finish = tile.finish(&spec, units.unit, creases);
            // Zones and excluded faces per input face: the pipeline carries them over to the
            // quads. Forced pairs would name quads, which do not exist yet.
            let mut options = pattern.options(true, tile.up, zones.as_deref())?;
            if let Some([a, b]) = options.forced_pairs.first() {
                bail!(
                    "--force {a},{b}: a forced pair names two quads, and run makes its quads itself; make them with `tilepattern remesh`, then give the pair to `tilepattern match` on them and lay the tiles with `tilepattern tiles`"
                );
            }
            options.excluded_faces =
                file_order::mesh_faces(&loaded.numbering, &options.excluded_faces, "--exclude")?;
            let edge = spec.quad_edge(options.courses != Courses::Free);
            let remesh = {
                let mut o = field.options(edge, surface, &loaded.numbering, creases)?;
                o.time_limit = RemeshOptions::time_limit_from_secs(remesh_time_limit)?;
                o
            };
            let tries = tries.tries();
            let mut line = ProgressLine::on_stderr(log).with_tries(tries.count_for(
                surface.area(),
                &remesh,
                &options,
                &spec,
            ));
            let found = pipeline::tile_surface_tries(
                surface,
                &remesh,
                &options,
                &spec,
                &finish,
                tries,
                &mut Control::with_figures(&mut |fraction, figures| {
                    line.update_run(fraction, figures)
                }),
            );
            line.finish();
            let (remeshed, mut tiling) = found.map_err(|e| units.explain(e))?;
            in_file_numbers(&mut tiling.report.warnings, &loaded.numbering);
            tiling.report.warnings.extend(reading_warnings(&loaded));
            let units = units.unit;
            // The quads' zones, as the pipeline gave them to the pattern stage.
            let quad_zones = zones
                .map(|z| {
                    pipeline::zones_on_quads(surface, &pattern.zone_bonds(&z), &remeshed.quads)
                })
                .transpose()?;
            write_outputs(
                &out,
                &remeshed.quads,
                &tiling,
                units,
                Some(&remeshed.metrics),
                quad_zones.as_deref(),
            )?;
            println!("{}", remesh_summary(&remeshed.metrics));
            println!("{}", tiling_summary(&tiling, units));
            print_warnings(&tiling.report.warnings);
            Ok(())
        }
        Command::Demo {
            out,
            span,
            pattern,
            no_fit,
            remesh_time_limit,
            tries,
        } => demo(
            &out,
            span,
            &pattern,
            no_fit,
            remesh_time_limit,
            tries.tries(),
            log,
        ),
    }
}

fn demo(
    out: &Path,
    span: f64,
    args: &PatternArgs,
    no_fit: bool,
    remesh_time_limit: f64,
    tries: Tries,
    log: bool,
) -> Result<()> {
    if !(span.is_finite() && (0.5..=100.0).contains(&span)) {
        bail!("--span {span} m: give a shell size between 0.5 and 100 metres");
    }
    output_folder(out)?;
    let spec = TileSpec {
        length: 0.280,
        width: 0.140,
        thickness: 0.015,
        joint: 0.010,
    };
    // The surface a designer would export: the shell as a fine triangle mesh.
    let surface = mesh::generate::triangulate_quads(&mesh::generate::corner_supported_shell(
        span,
        spec.target_edge() / 3.0,
    ));
    let options = args.options(true, [0.0, 0.0, 1.0], None)?;
    let remesh = {
        let mut o = RemeshOptions::default();
        o.target_edge = spec.quad_edge(options.courses != Courses::Free);
        o.time_limit = RemeshOptions::time_limit_from_secs(remesh_time_limit)?;
        o
    };
    let finish = {
        let mut o = FinishOptions::for_spec(&spec);
        o.fit = FinishOptions::for_spec(&spec).fit.filter(|_| !no_fit);
        o
    };
    let mut line = ProgressLine::on_stderr(log).with_tries(tries.count_for(
        surface.area(),
        &remesh,
        &options,
        &spec,
    ));
    let found = pipeline::tile_surface_tries(
        &surface,
        &remesh,
        &options,
        &spec,
        &finish,
        tries,
        &mut Control::with_figures(&mut |fraction, figures| line.update_run(fraction, figures)),
    );
    line.finish();
    let (remeshed, tiling) = found?;
    write_outputs(
        out,
        &remeshed.quads,
        &tiling,
        Units::M,
        Some(&remeshed.metrics),
        None,
    )?;
    println!(
        "demo: {span} m corner-supported shell, {} triangles",
        surface.face_count()
    );
    println!("{}", remesh_summary(&remeshed.metrics));
    println!("{}", tiling_summary(&tiling, Units::M));
    print_warnings(&tiling.report.warnings);
    println!(
        "wrote {}/{{quads.obj, tiles.obj, report.json, pattern.svg, cutlist.csv, cutlist.json, sequence.json, gaps.svg}}",
        out.display()
    );
    Ok(())
}

/// Makes the output folder `out` (and its parents), or says why it cannot be one: called
/// before the work as well as before writing, so that a path that cannot be written fails at
/// once and not after minutes of remeshing.
fn output_folder(out: &Path) -> Result<()> {
    if out.exists() && !out.is_dir() {
        bail!(
            "--out {} is a file, not a folder: give a folder for the output files",
            out.display()
        );
    }
    std::fs::create_dir_all(out)
        .with_context(|| format!("cannot create the folder {}", out.display()))
}

/// Writes quads.obj, tiles.obj, pattern.svg, report.json and the fabrication output into
/// `out`, and zones.txt when the quads have zones.
fn write_outputs(
    out: &Path,
    quads: &PolyMesh,
    tiling: &Tiling,
    units: Units,
    remesh: Option<&Metrics>,
    zones: Option<&[BondArg]>,
) -> Result<()> {
    output_folder(out)?;
    mesh::obj::write(quads, &out.join("quads.obj"))?;
    if let Some(zones) = zones {
        write_text(&out.join("zones.txt"), &zones_file::to_text(zones))?;
    }
    write_text(&out.join("tiles.obj"), &tiles::to_obj(&tiling.tiles))?;
    write_text(
        &out.join("pattern.svg"),
        &svg::pattern_svg(quads, &tiling.tiles),
    )?;
    write_json(
        Some(&out.join("report.json")),
        &ReportFile {
            units: units.name(),
            remesh,
            report: &tiling.report,
            zones: zones.map(zones_file::counts),
        },
    )?;
    write_fabrication(out, quads, tiling, units, None)
}

/// Writes cutlist.csv, cutlist.json, sequence.json and gaps.svg into `dir`; the quads' face
/// numbers as `numbering` has them in their file, if they were read from one.
fn write_fabrication(
    dir: &Path,
    quads: &PolyMesh,
    tiling: &Tiling,
    units: Units,
    numbering: Option<&mesh::FileNumbering>,
) -> Result<()> {
    let millimetre = units.per_mm();
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    write_text(
        &dir.join("cutlist.csv"),
        &cutlist_csv(&tiling.cut_list, units.name()),
    )?;
    write_json(Some(&dir.join("cutlist.json")), &tiling.cut_list)?;
    let mut order: Vec<&Tile> = tiling.tiles.iter().collect();
    order.sort_by_key(|t| t.step);
    let steps: Vec<SequenceStep> = order
        .iter()
        .map(|t| SequenceStep {
            step: t.step,
            label: &t.label,
            faces: t
                .faces
                .iter()
                .map(|&f| numbering.map_or(f, |n| n.file_face(f)))
                .collect(),
            origin: t.frame.origin.into(),
        })
        .collect();
    let summary = tiling.report.sequence.as_ref();
    write_json(
        Some(&dir.join("sequence.json")),
        &SequenceFile {
            units: units.name(),
            summary,
            steps,
        },
    )?;
    write_text(
        &dir.join("gaps.svg"),
        &svg::gaps_svg(
            quads,
            &tiling.tiles,
            &tiling.joints,
            tiling.report.tile.joint,
            millimetre,
        ),
    )
}

/// `cutlist.csv`: one row per cut shape; outlines (boundary shapes) as loops separated by
/// `|`, points `x y` separated by `;`, in the blank's frame and model units, which the last
/// column names.
fn cutlist_csv(groups: &[CutGroup], units: &str) -> String {
    let mut csv = String::from("label,kind,count,blank_length,blank_width,area,outline,units\n");
    for g in groups {
        let outline: Vec<String> = g
            .outline
            .iter()
            .map(|l| {
                l.iter()
                    .map(|p| format!("{:.6} {:.6}", p[0], p[1]))
                    .collect::<Vec<_>>()
                    .join(";")
            })
            .collect();
        let kind = serde_json::to_value(g.kind)
            .ok()
            .and_then(|v| v.as_str().map(str::to_owned))
            .unwrap_or_default();
        csv.push_str(&format!(
            "{},{},{},{},{},{:.6},{},{units}\n",
            g.label,
            kind,
            g.count,
            g.blank[0],
            g.blank[1],
            g.area,
            outline.join("|")
        ));
    }
    csv
}

/// `sequence.json`: the laying order's summary and the tiles step by step.
#[derive(Serialize)]
struct SequenceFile<'a> {
    /// The model unit of `origin` (as `report.json`'s `units`).
    units: &'static str,
    summary: Option<&'a Sequence>,
    steps: Vec<SequenceStep<'a>>,
}

/// One step of the laying order.
#[derive(Serialize)]
struct SequenceStep<'a> {
    step: usize,
    label: &'a str,
    faces: Vec<usize>,
    origin: [f64; 3],
}

/// `report.json`: the library's report plus the units the CLI assumed and, after `run`, the
/// remesh metrics.
#[derive(Serialize)]
struct ReportFile<'a> {
    units: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    remesh: Option<&'a Metrics>,
    #[serde(flatten)]
    report: &'a Report,
    /// After `run --zones`: quads per bond name.
    #[serde(skip_serializing_if = "Option::is_none")]
    zones: Option<BTreeMap<&'static str, usize>>,
}

/// `match`'s JSON: the pattern, and after `--zones` the faces per bond name.
#[derive(Serialize)]
struct MatchFile<'a> {
    #[serde(flatten)]
    pattern: &'a Pattern,
    #[serde(skip_serializing_if = "Option::is_none")]
    zones: Option<BTreeMap<&'static str, usize>>,
}

impl BondArg {
    /// Its `--pattern` name.
    fn name(self) -> &'static str {
        self.bond(pattern::DEFAULT_WEIGHT).name()
    }

    fn bond(self, weight: f64) -> Bond {
        match self {
            BondArg::Stack => Bond::Stack,
            BondArg::Staggered => Bond::Staggered { weight },
            BondArg::RunningBond => Bond::RunningBond { weight },
            BondArg::Herringbone => Bond::Herringbone { weight },
            BondArg::BasketWeave => Bond::BasketWeave { weight },
        }
    }
}

impl PatternArgs {
    /// Each face's bond from a zones file: its own, or `--pattern` where it lists none.
    fn zone_bonds(&self, zones: &[Option<BondArg>]) -> Vec<BondArg> {
        zones.iter().map(|z| z.unwrap_or(self.pattern)).collect()
    }

    /// The options, with tiles in level courses (with respect to `up`) unless `--courses`
    /// says otherwise, `level_by_default` is false or a bond (`--pattern` or a zone's) lays
    /// tiles both ways; with `zones` (per face, from [`zones_file`]) every zone at `--weight`.
    fn options(
        &self,
        level_by_default: bool,
        up: [f64; 3],
        zones: Option<&[Option<BondArg>]>,
    ) -> Result<PatternOptions> {
        let bond = self.pattern.bond(self.weight);
        let zones: Option<Vec<Bond>> = zones.map(|z| {
            self.zone_bonds(z)
                .into_iter()
                .map(|b| b.bond(self.weight))
                .collect()
        });
        // Bonds laid both ways need tiles free to lie either way.
        let both_ways = std::iter::once(bond)
            .chain(zones.iter().flatten().copied())
            .find(|b| b.lays_both_ways());
        let level = self
            .courses
            .map_or(level_by_default && both_ways.is_none(), |c| {
                c == CoursesArg::Level
            });
        if let Some(b) = both_ways
            && level_by_default
            && self.courses.is_none()
        {
            eprintln!(
                "note: {} lays tiles both ways: courses free (not the level courses of the default)",
                b.name()
            );
        }
        let formulation = match self.formulation {
            FormulationArg::Paper => Formulation::Paper,
            FormulationArg::Strengthened => Formulation::Strengthened,
        };
        let mut options = PatternOptions::default();
        options.bond = bond;
        options.time_limit = PatternOptions::time_limit_from_secs(self.time_limit)?;
        options.forced_pairs = self.forced.clone();
        options.excluded_faces = self.exclude.clone();
        options.formulation = formulation;
        options.method = match self.method {
            MethodArg::Auto => Method::Auto,
            MethodArg::Mip => Method::Mip,
        };
        options.courses = if level {
            Courses::Level { up }
        } else {
            Courses::Free
        };
        options.gap = self.gap;
        options.zones = zones;
        Ok(options)
    }
}

impl TileArgs {
    /// The finishing options in model units, cutting to the surface's creases or not.
    fn finish(&self, spec: &TileSpec, units: Units, creases: bool) -> FinishOptions {
        let scale = units.per_mm();
        let auto = FinishOptions::for_spec(spec);
        let mut finish = auto;
        finish.tolerance = self.cut_tolerance.map_or(auto.tolerance, |v| v * scale);
        finish.min_kept_width = self
            .min_kept_width
            .map_or(auto.min_kept_width, |v| v * scale);
        finish.sequence.up = nalgebra::Vector3::from(self.up);
        finish.sequence.support_band = self
            .support_band
            .map_or(auto.sequence.support_band, |v| v * scale);
        finish.fit = auto.fit.filter(|_| !self.no_fit).map(|mut fit| {
            fit.overlap_tolerance = self
                .overlap_tolerance
                .map_or(fit.overlap_tolerance, |v| v * scale);
            fit.bond_tolerance = self
                .bond_tolerance
                .map_or(fit.bond_tolerance, |v| v * scale);
            fit.time_limit = self.fit_time_limit;
            fit
        });
        finish.units_per_mm = scale;
        finish.creases = creases;
        finish
    }

    /// The tile in model units, and the units chosen with the reason.
    ///
    /// # Errors
    /// `--units auto` when no reading, or more than one, makes the mesh a plausible shell.
    fn spec(&self, mesh: &PolyMesh) -> Result<(TileSpec, ChosenUnits)> {
        // The tile on its own first, in the millimetres it was given in: a joint of 1000 was
        // refused as a mesh of no plausible size in any unit.
        let [length, width, thickness] = self.tile;
        if length < 10.0 {
            bail!(
                "--tile {length}x{width}x{thickness}: a tile {length} mm long is tiny; --tile is in millimetres whatever the mesh's units (e.g. 280x140x15): are the tile and the mesh in the same units?"
            );
        }
        TileSpec {
            length,
            width,
            thickness,
            joint: self.joint,
        }
        .validate()
        .map_err(|e| anyhow::anyhow!("{e} (--tile and --joint in millimetres)"))?;
        let units = match self.units {
            Units::Auto => auto_units(mesh, self.tile, self.joint)?,
            chosen => ChosenUnits {
                unit: chosen,
                why: format!("units: {} (--units {})", chosen.name(), chosen.name()),
            },
        };
        let mm = units.unit.per_mm();
        let [length, width, thickness] = self.tile.map(|d| d * mm);
        Ok((
            TileSpec {
                length,
                width,
                thickness,
                joint: self.joint * mm,
            },
            units,
        ))
    }
}

/// The units the mesh is read in, and why.
struct ChosenUnits {
    unit: Units,
    why: String,
}

impl ChosenUnits {
    /// Adds the units to errors a wrong unit typically causes, naming `--units`.
    fn explain(&self, error: pipeline::Error) -> anyhow::Error {
        use tilepattern::remesh::RemeshError as R;
        let scale = matches!(
            error,
            pipeline::Error::TileTooSmall { .. }
                | pipeline::Error::Tiles(tiles::TileError::TileLargerThanMesh { .. })
                | pipeline::Error::Remesh(
                    R::NothingExtracted(_)
                        | R::TargetEdgeTooLarge { .. }
                        | R::TargetEdgeTooSmall { .. }
                )
        );
        let error = anyhow::Error::new(error);
        if scale {
            error.context(format!(
                "{}; if the mesh is not in these units, give --units m, cm, mm, in or ft",
                self.why
            ))
        } else {
            error
        }
    }
}

/// Area, as a share of the squared diagonal, below which a mesh has no area to speak of (a
/// shell's is a tenth or more; 1e-12 is rounding).
const NO_AREA: f64 = 1e-12;

/// Plausible shells: bounding-box diagonal in metres, and tiles on them.
const PLAUSIBLE_DIAGONAL_M: [f64; 2] = [0.5, 100.0];
const PLAUSIBLE_TILES: [f64; 2] = [20.0, 2e6];
/// Usual shells: a reading in this range wins over one that is merely plausible.
const USUAL_DIAGONAL_M: [f64; 2] = [2.0, 25.0];

/// `--units auto`: reads the mesh in metres, centimetres and millimetres and keeps the one
/// reading under which it is a usual shell (diagonal 2 to 25 m), else the one under which it is
/// at least plausible (0.5 to 100 m, 20 to 2 million tiles of this size). The size is that of
/// the vertices the faces use (a stray vertex far off, as some exporters leave, does not count).
/// Inches and feet are not guessed (a shell in inches is as plausible in centimetres), but
/// where one of them reads as a usual shell the message says so, so that a model in inches
/// read as centimetres shows it.
fn auto_units(mesh: &PolyMesh, tile_mm: [f64; 3], joint_mm: f64) -> Result<ChosenUnits> {
    let diagonal = used_diagonal(mesh);
    let area = mesh.area();
    // No unit gives a surface of no area one: say what is wrong instead of naming units.
    if area.is_nan() || area <= NO_AREA * diagonal * diagonal {
        bail!(
            "the surface has no area ({area:e} square units, {diagonal:.4} units across): the corners of every face lie on a line or coincide, so there is no shell to tile in any unit; export the surface again (in Rhino: a mesh of the surface or polysurface, not of its edges)"
        );
    }
    // Area of one tile with its joint, in square metres.
    let tile_m2 = (tile_mm[0] + joint_mm) * (tile_mm[1] + joint_mm) * 1e-6;
    let readings: Vec<(Units, f64, f64)> = [Units::M, Units::Cm, Units::Mm]
        .into_iter()
        .map(|u| {
            let metre = u.per_mm() * 1000.0; // model units per metre
            (u, diagonal / metre, area / (metre * metre) / tile_m2)
        })
        .collect();
    let within = |v: f64, [lo, hi]: [f64; 2]| (lo..=hi).contains(&v);
    let plausible: Vec<&(Units, f64, f64)> = readings
        .iter()
        .filter(|(_, d, n)| within(*d, PLAUSIBLE_DIAGONAL_M) && within(*n, PLAUSIBLE_TILES))
        .collect();
    let usual: Vec<_> = plausible
        .iter()
        .copied()
        .filter(|(_, d, _)| within(*d, USUAL_DIAGONAL_M))
        .collect();
    let describe = |(u, d, n): &(Units, f64, f64)| {
        format!(
            "in {} it is {} across with about {n:.0} tiles",
            u.name(),
            metres(*d)
        )
    };
    let all: Vec<String> = readings.iter().map(describe).collect();
    let candidates = if usual.is_empty() { plausible } else { usual };
    let chosen = match candidates.as_slice() {
        [one] => *one,
        [] => bail!(
            "--units auto: the mesh ({diagonal:.4} units across) is no plausible shell for a {}x{} mm tile in any unit ({}); give --units m, cm, mm, in or ft",
            tile_mm[0],
            tile_mm[1],
            all.join("; ")
        ),
        several => {
            let names: Vec<&str> = several.iter().map(|r| r.0.name()).collect();
            bail!(
                "--units auto: the mesh ({diagonal:.4} units across) reads as a plausible shell in {} ({}); give --units {} to say which",
                names.join(" and "),
                several
                    .iter()
                    .map(|r| describe(r))
                    .collect::<Vec<_>>()
                    .join("; "),
                names.join(" or ")
            )
        }
    };
    let others: Vec<String> = readings
        .iter()
        .filter(|r| r.0 != chosen.0)
        .map(describe)
        .chain(
            [(Units::In, "inches"), (Units::Ft, "feet")]
                .into_iter()
                .map(|(u, name)| (name, diagonal / (u.per_mm() * 1000.0)))
                .filter(|&(_, d)| within(d, USUAL_DIAGONAL_M))
                .map(|(name, d)| format!("in {name} it would be {} across", metres(d))),
        )
        .collect();
    Ok(ChosenUnits {
        unit: chosen.0,
        why: format!(
            "units: {} (--units auto: {}; {}); give --units to override",
            chosen.0.name(),
            describe(chosen),
            others.join(", ")
        ),
    })
}

/// Bounding-box diagonal of the vertices `mesh`'s faces use.
fn used_diagonal(mesh: &PolyMesh) -> f64 {
    let p = mesh.positions();
    let mut corners: Option<(Point3<f64>, Point3<f64>)> = None;
    for &v in mesh.faces().iter().flatten() {
        corners = Some(corners.map_or((p[v], p[v]), |(lo, hi)| (lo.inf(&p[v]), hi.sup(&p[v]))));
    }
    corners.map_or(0.0, |(lo, hi)| (hi - lo).norm())
}

/// A length in metres, written with a sensible unit.
fn metres(m: f64) -> String {
    if m >= 1000.0 {
        format!("{:.1} km", m / 1000.0)
    } else if m >= 1.0 {
        format!("{m:.1} m")
    } else {
        format!("{:.0} mm", m * 1000.0)
    }
}

impl Units {
    /// Model units per millimetre.
    fn per_mm(self) -> f64 {
        match self {
            Units::M => 0.001,
            Units::Cm => 0.1,
            Units::Mm | Units::Auto => 1.0,
            Units::In => 1.0 / 25.4,
            Units::Ft => 1.0 / 304.8,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Units::Auto => "auto",
            Units::M => "m",
            Units::Cm => "cm",
            Units::Mm => "mm",
            Units::In => "in",
            Units::Ft => "ft",
        }
    }
}

fn parse_tile(text: &str) -> Result<[f64; 3], String> {
    let parts: Vec<&str> = text.split(['x', 'X']).collect();
    let numbers: Option<Vec<f64>> = parts.iter().map(|p| p.trim().parse().ok()).collect();
    match numbers.as_deref() {
        Some(&[l, w, t]) => {
            for (name, value) in [("length", l), ("width", w), ("thickness", t)] {
                if !(value.is_finite() && value > 0.0) {
                    return Err(format!("tile {name} {value} mm must be a number > 0"));
                }
            }
            if l < w {
                return Err(format!(
                    "tile {l}x{w}x{t}: the length {l} is shorter than the width {w}; write length x width x thickness, e.g. {w}x{l}x{t}"
                ));
            }
            Ok([l, w, t])
        }
        _ => Err(format!(
            "'{text}' is not a tile size; write length x width x thickness in mm, e.g. 280x140x15"
        )),
    }
}

/// A length in millimetres that may be zero (joint, tolerances).
fn parse_mm(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(value) if value.is_finite() && value >= 0.0 => Ok(value),
        Ok(value) => Err(format!("{value} mm must be a number >= 0")),
        Err(_) => Err(format!("'{text}' is not a length in mm")),
    }
}

fn parse_vector(text: &str) -> Result<[f64; 3], String> {
    let numbers: Option<Vec<f64>> = text.split(',').map(|p| p.trim().parse().ok()).collect();
    match numbers.as_deref() {
        Some(&[x, y, z]) => Ok([x, y, z]),
        _ => Err(format!(
            "'{text}' is not a direction; write x,y,z, e.g. 1,0,0"
        )),
    }
}

fn parse_pair(text: &str) -> Result<[usize; 2], String> {
    let parts: Vec<&str> = text.split(',').collect();
    match parts[..] {
        [a, b] => match (a.trim().parse(), b.trim().parse()) {
            (Ok(a), Ok(b)) => Ok([a, b]),
            _ => Err(format!("'{text}' is not a pair of face indices like 12,13")),
        },
        _ => Err(format!("'{text}' is not a pair of face indices like 12,13")),
    }
}

fn read_mesh(path: &Path, weld: Weld) -> Result<Loaded> {
    mesh::io::read(path, weld).map_err(|error| {
        // Errors naming a face or vertex: say how they are counted, as OBJ counts from 1.
        let numbering = match error {
            MeshError::ObjSyntax { .. } | MeshError::Format { .. } | MeshError::Io { .. } | MeshError::TooLarge { .. } | MeshError::Empty { .. } => "",
            _ => " (faces and vertices counted from 0 in file order: face 0 is the first face of the file, vertex 0 the first vertex)",
        };
        anyhow::Error::new(error).context(format!("cannot use {} as a mesh{numbering}", path.display()))
    })
}

/// `--weld`: a fraction of the bounding-box diagonal, or `off`.
fn parse_weld(text: &str) -> Result<Weld, String> {
    if text.trim().eq_ignore_ascii_case("off") {
        return Ok(Weld::Off);
    }
    match text.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 && v < 0.01 => Ok(Weld::Relative(v)),
        _ => Err(format!(
            "'{text}' is no weld tolerance; give a fraction of the mesh's diagonal between 0 and 0.01 (default 1e-6), or off"
        )),
    }
}

/// What reading `loaded` changed: welded vertices, faces turned over.
fn reading_warnings(loaded: &Loaded) -> Vec<Warning> {
    let turned = (loaded.turned_faces > 0).then(|| {
        // Which way the side kept faces: on a near tie the count alone does not tell.
        let mesh = &loaded.mesh;
        let facing = (0..mesh.face_count())
            .map(|f| mesh.face_area_vector(f))
            .sum::<nalgebra::Vector3<f64>>()
            .try_normalize(0.0)
            .unwrap_or_else(nalgebra::Vector3::zeros)
            // Rounded as printed, and no "-0.00".
            .map(|c| (c * 100.0).round() / 100.0 + 0.0);
        Warning::new(
            WarningCode::NormalsUnified,
            format!(
                "the {} file's faces did not all face the same side: {} of {} faces were turned over to agree with their neighbours (each piece keeps the side most of its faces face; the side kept faces ({:.2}, {:.2}, {:.2}) on average); tiles are laid on that side, so unify the normals in the model (Rhino: UnifyMeshNormals, then Flip if needed) to choose it yourself",
                loaded.format.name(),
                loaded.turned_faces,
                mesh.faces().len(),
                facing.x,
                facing.y,
                facing.z
            ),
        )
    });
    weld_warning(loaded).into_iter().chain(turned).collect()
}

/// The warning that reading `loaded` welded its vertices, if it did.
fn weld_warning(loaded: &Loaded) -> Option<Warning> {
    let w = loaded.weld;
    w.changed().then(|| {
        let renumbered = if w.dropped_faces > 0 {
            " (face numbers given and written stay the file's; a removed face is in no tile)"
        } else {
            ""
        };
        let mut message = if w.merged_vertices > 0 {
            format!(
                "the {} file's faces did not share all their vertices: {} coincident vertices were joined (within {:.3e} model units) and {} collapsed or repeated faces removed{renumbered}",
                loaded.format.name(),
                w.merged_vertices,
                w.tolerance,
                w.dropped_faces,
            )
        } else if w.dropped_faces > 0 {
            format!(
                "the {} file has {} faces with a corner given twice or repeating an earlier face: removed{renumbered}",
                loaded.format.name(),
                w.dropped_faces,
            )
        } else {
            format!("the {} file was read", loaded.format.name())
        };
        if w.shrunk_faces > 0 {
            message.push_str(&format!(
                "; {} faces lost a corner (two neighbouring corners at one place were joined, or a corner was given twice in a row: a quad with a collapsed edge, or written `1 2 3 3`, is a triangle)",
                w.shrunk_faces
            ));
        }
        if w.zipped_vertices > 0 {
            message.push_str(&format!(
                "; {} vertices lying on the edge of another patch (a crack where patches meshed apart meet with their vertices at different places) were inserted into it, splitting its triangles, or joined to its end where they nearly met it, so that the patches share the seam",
                w.zipped_vertices
            ));
        }
        message.push_str(if w.dropped_faces > 0 && w.merged_vertices == 0 {
            "; give --weld off to keep the file as it is (it is then refused)"
        } else {
            "; give --weld off to keep the file as it is"
        });
        Warning::new(WarningCode::VerticesWelded, message)
    })
}

/// `warnings` naming faces of a mesh read from a file, with those faces as `numbering` says
/// the file numbers them.
fn in_file_numbers(warnings: &mut [Warning], numbering: &mesh::FileNumbering) {
    for w in warnings {
        *w = w.clone().renumbered(|f| numbering.file_face_or_same(f));
    }
}

/// Prints warnings to stderr, one a line with its code.
fn print_warnings(warnings: &[Warning]) {
    for w in warnings {
        let code = serde_json::to_value(w.code)
            .ok()
            .and_then(|v| v.as_str().map(str::to_owned))
            .unwrap_or_default();
        eprintln!("warning [{code}]: {}", w.message);
    }
}

fn write_text(path: &Path, text: &str) -> Result<()> {
    std::fs::write(path, text).with_context(|| format!("cannot write {}", path.display()))
}

fn write_json(path: Option<&Path>, value: &impl Serialize) -> Result<()> {
    let text = serde_json::to_string_pretty(value)? + "\n";
    match path {
        Some(path) => write_text(path, &text),
        None => {
            print!("{text}");
            Ok(())
        }
    }
}

fn pattern_summary(p: &Pattern) -> String {
    format!(
        "{} faces: {} tiles, {} unpaired, {} continuous joints, {} shifted pairs; objective {} bound {} ({:?}, {:.2} s)",
        p.faces,
        p.pairs.len(),
        p.unpaired.len(),
        p.continuous_joints,
        p.shifted_pairs,
        p.objective,
        p.bound,
        p.status,
        p.seconds
    )
}

fn remesh_summary(m: &Metrics) -> String {
    let simplified = if m.input_vertices_removed > 0 {
        format!(
            "; the input, much finer than the quads, simplified first ({} of its vertices removed, the boundary kept)",
            m.input_vertices_removed
        )
    } else {
        String::new()
    };
    let sheets = if m.crease_sheets > 0 {
        format!(
            "; split at its creases into {} sheets, each with quads of its own, tiles cut to the creases",
            m.crease_sheets
        )
    } else {
        String::new()
    };
    format!(
        "{} quads (pure quad: {}), {} interior irregular vertices, mean edge {:.3} t, {:.1} % of edges within 20 %, area covered {:.3}, max distance {:.3} t ({:.2} s){}{}",
        m.faces,
        m.pure_quad,
        m.interior_irregular_vertices,
        m.mean_edge_ratio,
        100.0 * m.edges_within_20pct,
        m.area_covered_ratio,
        m.max_distance_to_input_ratio,
        m.seconds,
        sheets,
        simplified
    )
}

fn tiling_summary(t: &Tiling, units: Units) -> String {
    let cutting = t.report.cutting.as_ref().map_or(String::new(), |c| {
        format!(
            "; {} filler pieces ({} of them in the fit's tears: {} cut to the room there, {} whole halves); {} cut shapes, {} slivers and {} tiles off the surface left out, coverage {:.3}",
            c.filler_tiles,
            c.tear_pieces,
            c.tear_cuts,
            c.tear_halves,
            c.boundary_shapes,
            c.slivers.len(),
            c.outside_tiles,
            c.coverage
        )
    });
    let laying = t.report.sequence.as_ref().map_or(String::new(), |s| {
        let climbing = if s.sloped_tiles > 0 {
            format!(
                "; {} of the {} whole tiles on slopes over {:.0} degrees run up them",
                s.climbing_tiles,
                s.sloped_tiles,
                tilepattern::tiles::SLOPE_DEGREES
            )
        } else {
            String::new()
        };
        format!(
            "\nlaying order: {} tiles on the supports, {} need a prop{climbing}",
            s.support_tiles, s.unsupported
        )
    });
    let mm = units.per_mm();
    let figures = |j: &JointSummary| {
        format!(
            "p95 |gap - joint| {:.1} mm, {:.0} % within 2 mm, {} of {} pairs overlapping (deepest {:.1} mm), widest {:.1} mm",
            j.p95_deviation / mm,
            100.0 * j.within_2mm,
            j.overlaps,
            j.contacts,
            j.max_overlap / mm,
            j.max_gap / mm
        )
    };
    let j = &t.report.joints;
    let joints = match (&j.before_fit, &t.report.fit) {
        (Some(before), Some(fit)) => format!(
            "joints (nominal {:.1} mm) before the fit: {}\nafter the fit ({:?}, {} steps, {:.2} s): {}; {} tiles cut to fit, {} whole pieces laid in rooms of the courses, {} tears too narrow for a piece closed along them",
            j.joint / mm,
            figures(before),
            fit.status,
            fit.iterations,
            t.report.seconds.fit,
            figures(j),
            j.fit_cuts,
            fit.room_pieces,
            fit.closed_tears
        ),
        _ => format!(
            "joints (nominal {:.1} mm, placement of section 3.5): {}",
            j.joint / mm,
            figures(j)
        ),
    };
    // Every try on a line: a designer sees what the others would have given.
    let tries = t.report.chosen_try.map_or(String::new(), |chosen| {
        let lines: Vec<String> = t
            .report
            .tries
            .iter()
            .enumerate()
            .map(|(k, x)| {
                let kept = if k == chosen { " <- kept" } else { "" };
                // The field is named when it is not the curvature's (the smooth try).
                let mut field = match x.field {
                    "curvature" => String::new(),
                    other => format!("{other} field, "),
                };
                if x.quads_along_courses {
                    field.push_str("quads along the courses, ");
                }
                if x.boundary_free {
                    field.push_str("boundary free, ");
                }
                match x.score {
                    None => format!(
                        "\n  try {} ({field}renormalisation {}): failed: {}",
                        k + 1,
                        x.renormalisation,
                        x.failed.as_deref().unwrap_or("no tiles")
                    ),
                    Some(score) => format!(
                        "\n  try {} ({field}renormalisation {}): {} quads, {} irregular, p95 {:.1} mm{}, {:.1} % cut{}, coverage {:.3}, score {:.2}, {:.1} s{}{kept}",
                        k + 1,
                        x.renormalisation,
                        x.quads,
                        x.interior_irregular_vertices,
                        x.p95_deviation / mm,
                        if x.wide_joints { " (wide_joints)" } else { "" },
                        100.0 * x.cut_share,
                        if x.fit_cuts { " (fit_cuts)" } else { "" },
                        x.coverage,
                        score,
                        x.seconds,
                        x.limit_reached.map_or(String::new(), |stage| format!(
                            "; the {stage} stage reached its time limit, so its tiles depend on the machine's speed{}",
                            if x.ended_tries { " and no further try is made" } else { "" }
                        ))
                    ),
                }
            })
            .collect();
        format!(
            "\n{} {}, the tiles of try {} kept (joints not flagged wide first, then cuts not flagged, then the lowest score: % cut + p95 per half joint + % uncovered + % cut at the edge / 4):{}",
            lines.len(),
            if lines.len() == 1 { "try" } else { "tries" },
            chosen + 1,
            lines.concat()
        )
    });
    format!(
        "{}\n{} full tiles, {} half tiles ({} of them cut to the boundary){cutting}{laying}\n{joints}{tries}",
        pattern_summary(&t.pattern),
        t.report.full_tiles,
        t.report.half_tiles,
        // The pattern's own tiles: report.boundary_tiles counts filler pieces too.
        t.tiles
            .iter()
            .filter(|tile| !tile.faces.is_empty() && tile.kind == TileKind::Boundary)
            .count(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn match_json_without_zones_is_the_pattern_json() {
        let found =
            pattern::solve(&mesh::generate::grid(3, 2), &PatternOptions::default()).unwrap();
        let plain = serde_json::to_string_pretty(&found).unwrap();
        let wrapped = MatchFile {
            pattern: &found,
            zones: None,
        };
        assert_eq!(serde_json::to_string_pretty(&wrapped).unwrap(), plain);
        let zoned = MatchFile {
            pattern: &found,
            zones: Some(zones_file::counts(&[BondArg::Stack; 6])),
        };
        let text = serde_json::to_string_pretty(&zoned).unwrap();
        assert!(
            text.starts_with(plain.trim_end_matches(['}', '\n'])),
            "{text}"
        );
        assert!(
            text.ends_with(",\n  \"zones\": {\n    \"stack\": 6\n  }\n}"),
            "{text}"
        );
    }
}
