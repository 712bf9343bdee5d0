//! `tilepattern`: the command line. It parses arguments, calls the library, writes files.
//! Command names, flags and JSON fields are a contract that users' scripts rely on.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{Context, Result, bail};
use clap::{Parser, Subcommand, ValueEnum};
use serde::Serialize;
use tilepattern::mesh::{self, PolyMesh};
use tilepattern::pattern::{self, Bond, Formulation, Method, Pattern, PatternOptions};
use tilepattern::pipeline::{self, Tiling};
use tilepattern::report::{Report, svg};
use tilepattern::tiles::{self, TileSpec};

#[derive(Parser)]
#[command(name = "tilepattern", version, about = "Tile laying patterns for free-form shells that need little cutting")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Match the faces of a quad mesh into tiles (paper eqs. 1-3) and write the pairs as JSON.
    Match {
        /// Quad mesh (OBJ). Face indices in the output are 0-based, in OBJ order.
        quads: PathBuf,
        #[command(flatten)]
        pattern: PatternArgs,
        /// Where to write the result JSON (stdout when omitted).
        #[arg(long)]
        json: Option<PathBuf>,
    },
    /// Build tile boxes for pairs written by `match`.
    Tiles {
        /// The quad mesh the pairs refer to (OBJ).
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
    },
    /// Run the whole pipeline on a built-in example: a shell supported at its four corners
    /// (the paper's Figure 9), tiled with 280 x 140 x 15 mm tiles.
    Demo {
        /// Output folder for quads.obj, tiles.obj, report.json, pattern.svg.
        #[arg(long, default_value = "demo")]
        out: PathBuf,
        /// Plan size of the shell in metres.
        #[arg(long, default_value_t = 3.0)]
        span: f64,
        #[command(flatten)]
        pattern: PatternArgs,
    },
}

#[derive(clap::Args)]
struct PatternArgs {
    /// Laying pattern: stack = maximum matching (eq. 1), staggered (eq. 2), running-bond (eq. 3).
    #[arg(long, value_enum, default_value_t = BondArg::Staggered)]
    pattern: BondArg,
    /// Weight of the bond term: penalty per continuous joint (staggered) or reward per shifted
    /// pair (running-bond).
    #[arg(long, default_value_t = pattern::DEFAULT_WEIGHT)]
    weight: f64,
    /// Solver time limit in seconds (wall clock). 0 returns the greedy start without solving.
    #[arg(long, default_value_t = 60.0)]
    time_limit: f64,
    /// How the integer program is written; both reach the same optimum.
    #[arg(long, value_enum, default_value_t = FormulationArg::Strengthened)]
    formulation: FormulationArg,
    /// Search route: auto = bound, running-bond start, window search, whole model when small;
    /// mip = the paper's whole program on CBC.
    #[arg(long, value_enum, default_value_t = MethodArg::Auto)]
    method: MethodArg,
    /// A pair of faces that must form a tile, as A,B (repeatable).
    #[arg(long = "force", value_parser = parse_pair)]
    forced: Vec<[usize; 2]>,
    /// Faces to leave out (openings, areas laid by hand), comma separated.
    #[arg(long, value_delimiter = ',')]
    exclude: Vec<usize>,
}

#[derive(Clone, Copy, ValueEnum)]
enum BondArg {
    Stack,
    Staggered,
    RunningBond,
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
    #[arg(long, value_parser = parse_tile)]
    tile: [f64; 3],
    /// Mortar joint in millimetres.
    #[arg(long, default_value_t = 10.0)]
    joint: f64,
    /// Units of the mesh coordinates; auto = millimetres if the mesh's bounding-box diagonal
    /// is 1000 or more, metres otherwise.
    #[arg(long, value_enum, default_value_t = Units::Auto)]
    units: Units,
}

#[derive(Clone, Copy, PartialEq, ValueEnum)]
enum Units {
    Auto,
    M,
    Cm,
    Mm,
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
    match cli.command {
        Command::Match { quads, pattern, json } => {
            let mesh = read_mesh(&quads)?;
            let found = pattern::solve(&mesh, &pattern.options()?)?;
            eprintln!("{}", pattern_summary(&found));
            write_json(json.as_deref(), &found)
        }
        Command::Tiles { quads, pairs, tile, output, json, svg } => {
            let mesh = read_mesh(&quads)?;
            let text = std::fs::read_to_string(&pairs).with_context(|| format!("cannot read {}", pairs.display()))?;
            let found: Pattern = serde_json::from_str(&text)
                .with_context(|| format!("{} is not the JSON written by `tilepattern match`", pairs.display()))?;
            let (spec, units) = tile.spec(&mesh);
            let tiling = pipeline::tiles_for_pattern(&mesh, found, &spec)?;
            write_text(&output, &tiles::to_obj(&tiling.tiles))?;
            if let Some(svg_path) = svg {
                write_text(&svg_path, &svg::pattern_svg(&mesh, &tiling.tiles))?;
            }
            eprintln!("{}", tiling_summary(&tiling, units));
            json.map_or(Ok(()), |path| write_json(Some(&path), &ReportFile { units: units.name(), report: &tiling.report }))
        }
        Command::Demo { out, span, pattern } => demo(&out, span, &pattern),
    }
}

fn demo(out: &Path, span: f64, args: &PatternArgs) -> Result<()> {
    if !(span.is_finite() && (0.5..=100.0).contains(&span)) {
        bail!("--span {span} m: give a shell size between 0.5 and 100 metres");
    }
    let spec = TileSpec { length: 0.280, width: 0.140, thickness: 0.015, joint: 0.010 };
    let quads = mesh::generate::corner_supported_shell(span, spec.target_edge());
    let tiling = pipeline::tile_quad_mesh(&quads, &args.options()?, &spec)?;
    std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    mesh::obj::write(&quads, &out.join("quads.obj"))?;
    write_text(&out.join("tiles.obj"), &tiles::to_obj(&tiling.tiles))?;
    write_text(&out.join("pattern.svg"), &svg::pattern_svg(&quads, &tiling.tiles))?;
    write_json(Some(&out.join("report.json")), &ReportFile { units: Units::M.name(), report: &tiling.report })?;
    println!("demo: {span} m corner-supported shell, {} quads", quads.face_count());
    println!("{}", tiling_summary(&tiling, Units::M));
    println!("wrote {}/{{quads.obj, tiles.obj, report.json, pattern.svg}}", out.display());
    Ok(())
}

/// `report.json`: the library's report plus the units the CLI assumed.
#[derive(Serialize)]
struct ReportFile<'a> {
    units: &'static str,
    #[serde(flatten)]
    report: &'a Report,
}

impl PatternArgs {
    fn options(&self) -> Result<PatternOptions> {
        let bond = match self.pattern {
            BondArg::Stack => Bond::Stack,
            BondArg::Staggered => Bond::Staggered { weight: self.weight },
            BondArg::RunningBond => Bond::RunningBond { weight: self.weight },
        };
        let formulation = match self.formulation {
            FormulationArg::Paper => Formulation::Paper,
            FormulationArg::Strengthened => Formulation::Strengthened,
        };
        Ok(PatternOptions {
            bond,
            time_limit: PatternOptions::time_limit_from_secs(self.time_limit)?,
            forced_pairs: self.forced.clone(),
            excluded_faces: self.exclude.clone(),
            formulation,
            method: match self.method {
                MethodArg::Auto => Method::Auto,
                MethodArg::Mip => Method::Mip,
            },
        })
    }
}

impl TileArgs {
    /// The tile in model units, and the units chosen.
    fn spec(&self, mesh: &PolyMesh) -> (TileSpec, Units) {
        let units = match self.units {
            Units::Auto => {
                let (min, max) = mesh.bounding_box();
                if (max - min).norm() >= 1000.0 { Units::Mm } else { Units::M }
            }
            chosen => chosen,
        };
        let mm = match units {
            Units::M => 0.001,
            Units::Cm => 0.1,
            Units::Mm | Units::Auto => 1.0,
        };
        let [length, width, thickness] = self.tile.map(|d| d * mm);
        (TileSpec { length, width, thickness, joint: self.joint * mm }, units)
    }
}

impl Units {
    fn name(self) -> &'static str {
        match self {
            Units::Auto => "auto",
            Units::M => "m",
            Units::Cm => "cm",
            Units::Mm => "mm",
        }
    }
}

fn parse_tile(text: &str) -> Result<[f64; 3], String> {
    let parts: Vec<&str> = text.split(['x', 'X']).collect();
    let numbers: Option<Vec<f64>> = parts.iter().map(|p| p.trim().parse().ok()).collect();
    match numbers.as_deref() {
        Some(&[l, w, t]) => Ok([l, w, t]),
        _ => Err(format!("'{text}' is not a tile size; write length x width x thickness in mm, e.g. 280x140x15")),
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

fn read_mesh(path: &Path) -> Result<PolyMesh> {
    mesh::obj::read(path).with_context(|| format!("cannot use {} as a mesh", path.display()))
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

fn tiling_summary(t: &Tiling, units: Units) -> String {
    let j = &t.report.joints;
    format!(
        "{}\n{} full tiles, {} half tiles; joints ({}): nominal {}, gap {:.4}..{:.4}, p95 deviation {:.4}, {} overlaps",
        pattern_summary(&t.pattern),
        t.report.full_tiles,
        t.report.half_tiles,
        units.name(),
        j.joint,
        j.min_gap,
        j.max_gap,
        j.p95_deviation,
        j.overlaps
    )
}
