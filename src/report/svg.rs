//! Pictures of a tiling seen along the shell's mean normal (a top view for a vault).
//!
//! `pattern.svg`: every tile as laid (after the fit stage, off its quads), filled by its kind
//! (full, half, cut to the boundary, cut to fit) with the kept outline of a cut tile dashed;
//! faces without a tile are grey; continuous joints are red, irregular vertices blue dots.
//!
//! `gaps.svg`: every tile coloured by its worst joint against the nominal joint (paper
//! Figure 8), blue where tiles press together or overlap, red where the joint opens.

use std::fmt::Write as _;

use nalgebra::{Point3, Vector3};

use super::gaps::Joint;
use crate::mesh::{PolyMesh, Topology};
use crate::pattern::DualGraph;
use crate::tiles::{Tile, TileKind, outline};

const WIDTH: f64 = 1000.0;
const MARGIN: f64 = 20.0;
const FULL_FILL: &str = "#e8c9a0";
const HALF_FILL: &str = "#f08a5d";
const BOUNDARY_FILL: &str = "#a6cee3";
const FIT_CUT_FILL: &str = "#b589d6";
const CUT_COLOUR: &str = "#1f4e79";
const NO_TILE_FILL: &str = "#c8c8c8";
const JOINT_COLOUR: &str = "#5a4632";
const CONTINUOUS_COLOUR: &str = "#d7191c";
const SINGULAR_COLOUR: &str = "#2c7bb6";

/// Draws the tiling of `mesh` as an SVG document.
pub fn pattern_svg(mesh: &PolyMesh, tiles: &[Tile]) -> String {
    let topology = Topology::new(mesh).expect("a PolyMesh is manifold by construction");
    let view = View::fit(mesh);
    let tile_of = tile_of_face(mesh, tiles);
    // Faces without a tile (excluded, not quads) stay grey underneath.
    let mut body = String::new();
    for (f, face) in mesh
        .faces()
        .iter()
        .enumerate()
        .filter(|(f, _)| tile_of[*f].is_none())
    {
        let _ = f;
        let points: Vec<String> = face
            .iter()
            .map(|&v| view.xy(&mesh.positions()[v]))
            .collect();
        let _ = writeln!(
            body,
            r#"<polygon points="{}" fill="{NO_TILE_FILL}" stroke="{NO_TILE_FILL}" stroke-width="0.5"/>"#,
            points.join(" ")
        );
    }
    // Every tile as laid: its kept outline (all loops of a cut tile) filled by its kind.
    for tile in tiles {
        let fill = kind_fill(tile.kind);
        let (hx, hy) = (tile.size[0] / 2.0, tile.size[1] / 2.0);
        let whole = vec![vec![[-hx, -hy], [hx, -hy], [hx, hy], [-hx, hy]]];
        let loops = tile.cut.as_ref().map_or(&whole, |c| &c.loops);
        let path: String = loops
            .iter()
            .map(|l| {
                let points: Vec<String> = l
                    .iter()
                    .map(|p| view.xy(&tile.to_world(Vector3::new(p[0], p[1], 0.0))))
                    .collect();
                format!("M{}Z", points.join("L"))
            })
            .collect();
        let dash = if tile.cut.is_some() {
            format!(r#" stroke-dasharray="3,2" stroke="{CUT_COLOUR}""#)
        } else {
            format!(r#" stroke="{JOINT_COLOUR}""#)
        };
        let _ = writeln!(
            body,
            r#"<path d="{path}" fill="{fill}" fill-rule="evenodd"{dash} stroke-width="0.5"/>"#
        );
    }
    for [a, b] in continuous_joints(mesh, &topology, tiles) {
        for t in [a, b] {
            for end in end_edges(mesh, &topology, &tiles[t]) {
                body.push_str(&view.line(mesh, end, CONTINUOUS_COLOUR, 3.0));
            }
        }
    }
    for v in 0..mesh.positions().len() {
        if !topology.is_boundary_vertex(v) && topology.vertex_edges(v).len() != 4 {
            let (x, y) = view.project(&mesh.positions()[v]);
            let _ = writeln!(
                body,
                r#"<circle cx="{x:.2}" cy="{y:.2}" r="4" fill="{SINGULAR_COLOUR}"/>"#
            );
        }
    }
    let legend = [
        Legend::Swatch(FULL_FILL.into(), "full tile".into()),
        Legend::Swatch(HALF_FILL.into(), "half tile (cut)".into()),
        Legend::Swatch(BOUNDARY_FILL.into(), "boundary tile (cut)".into()),
        Legend::Swatch(FIT_CUT_FILL.into(), "cut to fit".into()),
        Legend::Line(CONTINUOUS_COLOUR.into(), "continuous joint".into()),
        Legend::Dot(SINGULAR_COLOUR.into(), "irregular vertex".into()),
    ];
    document(&view, &body, &legend)
}

/// Draws every tile's kept outline coloured by its worst joint against the nominal `joint`
/// (the joint of `joints` that strays furthest from it: blue where it is tighter or the
/// tiles overlap, red where it is wider), with `mm` model units per millimetre for the
/// legend. The colour saturates at half the joint (5 mm on a 10 mm joint, the band a mason
/// fills or cuts beyond), whatever the tiling: a picture of joints within a millimetre
/// of the joint stays grey, and two pictures compare by colour.
pub fn gaps_svg(mesh: &PolyMesh, tiles: &[Tile], joints: &[Joint], joint: f64, mm: f64) -> String {
    let view = View::fit(mesh);
    let mut worst: Vec<Option<f64>> = vec![None; tiles.len()];
    for j in joints {
        for t in j.tiles {
            if worst[t].is_none_or(|w| (j.gap - joint).abs() > (w - joint).abs()) {
                worst[t] = Some(j.gap);
            }
        }
    }
    // Without a joint, a tenth of the tiles' mean width.
    let scale = if joint > 0.0 {
        joint / 2.0
    } else {
        tiles.iter().map(|t| t.size[1]).sum::<f64>() / (10.0 * tiles.len().max(1) as f64)
    }
    .max(1e-12);
    let mut body = String::new();
    for (tile, worst) in tiles.iter().zip(&worst) {
        let fill = worst.map_or_else(|| gap_colour(0.0), |g| gap_colour((g - joint) / scale));
        let points: Vec<String> = outline::world_outline(tile)
            .iter()
            .map(|p| view.xy(p))
            .collect();
        let _ = writeln!(
            body,
            r#"<polygon points="{}" fill="{fill}" stroke="{JOINT_COLOUR}" stroke-width="0.3"/>"#,
            points.join(" ")
        );
    }
    let legend = [
        Legend::Swatch(
            gap_colour(-1.0),
            format!("joint {:.1} mm or less", (joint - scale) / mm),
        ),
        Legend::Swatch(
            gap_colour(0.0),
            format!("nominal joint {:.1} mm", joint / mm),
        ),
        Legend::Swatch(
            gap_colour(1.0),
            format!("joint {:.1} mm or more", (joint + scale) / mm),
        ),
    ];
    document(&view, &body, &legend)
}

/// Blue (tighter than the joint) through grey (nominal) to red (wider), for `s` in `[-1, 1]`.
fn gap_colour(s: f64) -> String {
    let s = s.clamp(-1.0, 1.0);
    let (grey, blue, red) = (
        [160.0, 160.0, 160.0],
        [33.0, 102.0, 172.0],
        [202.0, 0.0, 32.0],
    );
    let target = if s < 0.0 { blue } else { red };
    let c: Vec<u8> = (0..3)
        .map(|k| (grey[k] + (target[k] - grey[k]) * s.abs()).round() as u8)
        .collect();
    format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}

/// Which tile covers each face.
fn tile_of_face(mesh: &PolyMesh, tiles: &[Tile]) -> Vec<Option<usize>> {
    let mut tile_of = vec![None; mesh.face_count()];
    for (t, tile) in tiles.iter().enumerate() {
        tile.faces.iter().for_each(|&f| tile_of[f] = Some(t));
    }
    tile_of
}

/// The fill of a tile of `kind`.
fn kind_fill(kind: TileKind) -> &'static str {
    match kind {
        TileKind::Full => FULL_FILL,
        TileKind::Half => HALF_FILL,
        TileKind::Boundary => BOUNDARY_FILL,
        TileKind::FitCut => FIT_CUT_FILL,
    }
}

/// One entry of a picture's legend.
enum Legend {
    Swatch(String, String),
    Line(String, String),
    Dot(String, String),
}

/// The page around a drawing, with a one-line legend below it.
fn document(view: &View, body: &str, legend: &[Legend]) -> String {
    let legend_y = view.height + 2.0 * MARGIN + 15.0;
    let mut x = 20.0;
    let mut items = String::new();
    for entry in legend {
        let (colour, text) = match entry {
            Legend::Swatch(c, t) | Legend::Line(c, t) | Legend::Dot(c, t) => (c, t),
        };
        let _ = match entry {
            Legend::Swatch(..) => write!(
                items,
                r#"<rect x="{x:.0}" y="{:.0}" width="14" height="14" fill="{colour}"/>"#,
                legend_y - 12.0
            ),
            Legend::Line(..) => write!(
                items,
                r#"<line x1="{x:.0}" y1="{y:.0}" x2="{:.0}" y2="{y:.0}" stroke="{colour}" stroke-width="3"/>"#,
                x + 14.0,
                y = legend_y - 5.0
            ),
            Legend::Dot(..) => write!(
                items,
                r#"<circle cx="{:.0}" cy="{:.0}" r="4" fill="{colour}"/>"#,
                x + 7.0,
                legend_y - 5.0
            ),
        };
        let _ = write!(
            items,
            r#"<text x="{:.0}" y="{legend_y:.0}">{text}</text>"#,
            x + 20.0
        );
        x += 30.0 + 7.5 * text.len() as f64;
    }
    let height = view.height + 2.0 * MARGIN + 30.0;
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{WIDTH}\" height=\"{height:.0}\" viewBox=\"0 0 {WIDTH} {height:.0}\">\n\
         <rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n{body}<g font-family=\"sans-serif\" font-size=\"14\">{items}</g>\n</svg>\n"
    )
}

/// Pairs of placed full tiles that form a continuous joint.
fn continuous_joints(mesh: &PolyMesh, topology: &Topology, tiles: &[Tile]) -> Vec<[usize; 2]> {
    let graph = DualGraph::new(mesh, topology, &[]);
    let mut placed = vec![None; graph.tiles().len()];
    for (t, tile) in tiles.iter().enumerate() {
        if let [a, b] = tile.faces[..] {
            if let Some(candidate) = graph.tile_between(a, b) {
                placed[candidate] = Some(t);
            }
        }
    }
    graph
        .continuous_joints()
        .iter()
        .filter_map(|&[a, b]| Some([placed[a]?, placed[b]?]))
        .collect()
}

/// The two end edges of a full tile: in each of its quads, the edge opposite the middle edge.
fn end_edges(mesh: &PolyMesh, topology: &Topology, tile: &Tile) -> Vec<[usize; 2]> {
    let [a, b] = tile.faces[..] else {
        return Vec::new();
    };
    [(a, b), (b, a)]
        .into_iter()
        .filter_map(|(f, other)| {
            let edges = topology.face_edges(f);
            let middle = edges
                .iter()
                .position(|&e| topology.edges()[e].other_face(f) == Some(other))?;
            (mesh.faces()[f].len() == 4).then(|| topology.edges()[edges[(middle + 2) % 4]].vertices)
        })
        .collect()
}

/// Orthographic projection along the mesh's area-weighted mean normal, scaled to the page.
struct View {
    u: Vector3<f64>,
    v: Vector3<f64>,
    min: (f64, f64),
    scale: f64,
    height: f64,
}

impl View {
    fn fit(mesh: &PolyMesh) -> Self {
        let normal =
            (0..mesh.face_count()).fold(Vector3::zeros(), |acc, f| acc + mesh.face_area_vector(f));
        let n = normal.try_normalize(1e-12).unwrap_or_else(Vector3::z);
        let reference = if n.x.abs() < 0.9 {
            Vector3::x()
        } else {
            Vector3::y()
        };
        let u = (reference - n * reference.dot(&n)).normalize();
        let v = n.cross(&u);
        let coords: Vec<(f64, f64)> = mesh
            .positions()
            .iter()
            .map(|p| (p.coords.dot(&u), p.coords.dot(&v)))
            .collect();
        let fold = |pick: fn(&(f64, f64)) -> f64, f: fn(f64, f64) -> f64, start: f64| {
            coords.iter().map(pick).fold(start, f)
        };
        let min = (
            fold(|c| c.0, f64::min, f64::INFINITY),
            fold(|c| c.1, f64::min, f64::INFINITY),
        );
        let max = (
            fold(|c| c.0, f64::max, f64::NEG_INFINITY),
            fold(|c| c.1, f64::max, f64::NEG_INFINITY),
        );
        let extent = (max.0 - min.0).max(1e-12);
        let scale = (WIDTH - 2.0 * MARGIN) / extent;
        Self {
            u,
            v,
            min,
            scale,
            height: (max.1 - min.1) * scale,
        }
    }

    /// Page coordinates (y down) of a point.
    fn project(&self, p: &Point3<f64>) -> (f64, f64) {
        let x = MARGIN + (p.coords.dot(&self.u) - self.min.0) * self.scale;
        let y = MARGIN + self.height - (p.coords.dot(&self.v) - self.min.1) * self.scale;
        (x, y)
    }

    fn xy(&self, p: &Point3<f64>) -> String {
        let (x, y) = self.project(p);
        format!("{x:.2},{y:.2}")
    }

    fn line(&self, mesh: &PolyMesh, [a, b]: [usize; 2], colour: &str, width: f64) -> String {
        let (x1, y1) = self.project(&mesh.positions()[a]);
        let (x2, y2) = self.project(&mesh.positions()[b]);
        format!(
            "<line x1=\"{x1:.2}\" y1=\"{y1:.2}\" x2=\"{x2:.2}\" y2=\"{y2:.2}\" stroke=\"{colour}\" stroke-width=\"{width}\" stroke-linecap=\"round\"/>\n"
        )
    }
}
