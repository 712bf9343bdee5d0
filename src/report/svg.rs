//! `pattern.svg`: the tiling seen along the shell's mean normal (a top view for a vault).
//! Full tiles, half tiles and faces without a tile get different fills; joints between tiles
//! are drawn, joints inside a tile are not; continuous joints are red, irregular vertices are
//! blue dots.

use std::fmt::Write as _;

use nalgebra::{Point3, Vector3};

use crate::mesh::{PolyMesh, Topology};
use crate::pattern::DualGraph;
use crate::tiles::{Tile, TileKind};

const WIDTH: f64 = 1000.0;
const MARGIN: f64 = 20.0;
const FULL_FILL: &str = "#e8c9a0";
const HALF_FILL: &str = "#f08a5d";
const NO_TILE_FILL: &str = "#c8c8c8";
const JOINT_COLOUR: &str = "#5a4632";
const CONTINUOUS_COLOUR: &str = "#d7191c";
const SINGULAR_COLOUR: &str = "#2c7bb6";

/// Draws the tiling of `mesh` as an SVG document.
pub fn pattern_svg(mesh: &PolyMesh, tiles: &[Tile]) -> String {
    let topology = Topology::new(mesh).expect("a PolyMesh is manifold by construction");
    let view = View::fit(mesh);
    let mut tile_of = vec![None; mesh.face_count()];
    for (t, tile) in tiles.iter().enumerate() {
        tile.faces.iter().for_each(|&f| tile_of[f] = Some(t));
    }

    let mut body = String::new();
    for (f, face) in mesh.faces().iter().enumerate() {
        let fill = match tile_of[f].map(|t| tiles[t].kind) {
            Some(TileKind::Full) => FULL_FILL,
            Some(TileKind::Half) => HALF_FILL,
            None => NO_TILE_FILL,
        };
        let points: Vec<String> = face.iter().map(|&v| view.xy(&mesh.positions()[v])).collect();
        let _ = writeln!(body, r#"<polygon points="{}" fill="{fill}" stroke="{fill}" stroke-width="0.5"/>"#, points.join(" "));
    }
    for edge in topology.edges() {
        let inside_one_tile = match edge.faces[..] {
            [f, g] => tile_of[f].is_some() && tile_of[f] == tile_of[g],
            _ => false,
        };
        if !inside_one_tile {
            body.push_str(&view.line(mesh, edge.vertices, JOINT_COLOUR, 1.0));
        }
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
            let _ = writeln!(body, r#"<circle cx="{x:.2}" cy="{y:.2}" r="4" fill="{SINGULAR_COLOUR}"/>"#);
        }
    }
    let height = view.height + 2.0 * MARGIN + 30.0;
    let legend_y = view.height + 2.0 * MARGIN + 15.0;
    format!(
        concat!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h:.0}" viewBox="0 0 {w} {h:.0}">"#,
            "\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n{body}",
            r#"<g font-family="sans-serif" font-size="14">"#,
            r#"<rect x="20" y="{ly0:.0}" width="14" height="14" fill="{full}"/><text x="40" y="{ly:.0}">full tile</text>"#,
            r#"<rect x="130" y="{ly0:.0}" width="14" height="14" fill="{half}"/><text x="150" y="{ly:.0}">half tile (cut)</text>"#,
            r#"<line x1="280" y1="{lym:.0}" x2="300" y2="{lym:.0}" stroke="{cont}" stroke-width="3"/><text x="306" y="{ly:.0}">continuous joint</text>"#,
            r#"<circle cx="447" cy="{lym:.0}" r="4" fill="{sing}"/><text x="456" y="{ly:.0}">irregular vertex</text>"#,
            "</g>\n</svg>\n"
        ),
        w = WIDTH,
        h = height,
        body = body,
        ly0 = legend_y - 12.0,
        ly = legend_y,
        lym = legend_y - 5.0,
        full = FULL_FILL,
        half = HALF_FILL,
        cont = CONTINUOUS_COLOUR,
        sing = SINGULAR_COLOUR,
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
    graph.continuous_joints().iter().filter_map(|&[a, b]| Some([placed[a]?, placed[b]?])).collect()
}

/// The two end edges of a full tile: in each of its quads, the edge opposite the middle edge.
fn end_edges(mesh: &PolyMesh, topology: &Topology, tile: &Tile) -> Vec<[usize; 2]> {
    let [a, b] = tile.faces[..] else { return Vec::new() };
    [(a, b), (b, a)]
        .into_iter()
        .filter_map(|(f, other)| {
            let edges = topology.face_edges(f);
            let middle = edges.iter().position(|&e| topology.edges()[e].other_face(f) == Some(other))?;
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
        let normal = (0..mesh.face_count()).fold(Vector3::zeros(), |acc, f| acc + mesh.face_area_vector(f));
        let n = normal.try_normalize(1e-12).unwrap_or_else(Vector3::z);
        let reference = if n.x.abs() < 0.9 { Vector3::x() } else { Vector3::y() };
        let u = (reference - n * reference.dot(&n)).normalize();
        let v = n.cross(&u);
        let coords: Vec<(f64, f64)> = mesh.positions().iter().map(|p| (p.coords.dot(&u), p.coords.dot(&v))).collect();
        let fold = |pick: fn(&(f64, f64)) -> f64, f: fn(f64, f64) -> f64, start: f64| coords.iter().map(pick).fold(start, f);
        let min = (fold(|c| c.0, f64::min, f64::INFINITY), fold(|c| c.1, f64::min, f64::INFINITY));
        let max = (fold(|c| c.0, f64::max, f64::NEG_INFINITY), fold(|c| c.1, f64::max, f64::NEG_INFINITY));
        let extent = (max.0 - min.0).max(1e-12);
        let scale = (WIDTH - 2.0 * MARGIN) / extent;
        Self { u, v, min, scale, height: (max.1 - min.1) * scale }
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
        format!("<line x1=\"{x1:.2}\" y1=\"{y1:.2}\" x2=\"{x2:.2}\" y2=\"{y2:.2}\" stroke=\"{colour}\" stroke-width=\"{width}\" stroke-linecap=\"round\"/>\n")
    }
}
