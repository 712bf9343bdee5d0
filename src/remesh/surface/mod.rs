//! The working triangle surface of the remesher: the triangulated input with vertex normals,
//! edge adjacency and the boundary read off it.
//!
//! - [`boundary`]: boundary loops with their corners and narrow parts, measured at the scale
//!   of the quads;
//! - [`locator`]: closest points on the input surface and along its boundary loops.
//!
//! The refinement the position field needs is [`super::refine`].

mod boundary;
mod locator;

use std::collections::HashMap;

use nalgebra::Vector3;

use super::RemeshError;
use crate::mesh::PolyMesh;

pub(crate) use locator::Locator;

/// A triangle surface with the adjacency the solvers walk over, always in index order.
#[derive(Debug, Clone)]
pub(crate) struct Surface {
    /// Vertex positions.
    pub pos: Vec<Vector3<f64>>,
    /// Triangles, consistently oriented as in the input.
    pub tris: Vec<[usize; 3]>,
    /// Unit vertex normals.
    pub normals: Vec<Vector3<f64>>,
    /// Undirected edges, smaller vertex first, numbered in order of first appearance.
    pub edges: Vec<[usize; 2]>,
    /// Per vertex: (neighbour, edge) sorted by neighbour.
    pub adj: Vec<Vec<(usize, usize)>>,
    /// Per boundary vertex: the previous and next vertex along its boundary loop.
    pub boundary: Vec<Option<(usize, usize)>>,
    /// Mean edge length.
    pub mean_edge: f64,
    /// Per boundary vertex: incoming and outgoing boundary directions measured over an arc
    /// of the boundary scale (so a zig-zag boundary reads as its overall course).
    pub bdirs: Vec<Option<(Vector3<f64>, Vector3<f64>)>>,
    /// Boundary vertices where the boundary, seen at its scale, turns by more than 50
    /// degrees (the sharpest vertex of each such bend).
    pub corner: Vec<bool>,
    /// Boundary vertices where the surface is narrower than the boundary scale: another part
    /// of the boundary, far away along the loop, passes close by (teeth, slivers, acute
    /// tongues). Quads cannot follow such a boundary, so it neither pins nor aligns them.
    pub narrow: Vec<bool>,
}

/// The centroid of a flat polygon of [`STAR_CORNERS`] corners or more (`ids` into `pos`) when every
/// triangle from it to a side turns the polygon's way (it sees every side from inside), else
/// `None`: triangles, quads, polygons not star-shaped about their centroid and polygons that
/// are not flat are fanned. Only on a flat polygon do the centroid's triangles and the fan
/// ([`crate::geom::fan`], which the tile stage cuts and measures the tiles against) make the
/// same surface; a curved one (a vault meshed in hexagons) keeps the fan everywhere.
fn star_centre(pos: &[Vector3<f64>], ids: &[usize]) -> Option<Vector3<f64>> {
    if ids.len() < STAR_CORNERS {
        return None;
    }
    let centre = ids.iter().map(|&v| pos[v]).sum::<Vector3<f64>>() / ids.len() as f64;
    let side = |k: usize| (pos[ids[k]], pos[ids[(k + 1) % ids.len()]]);
    // The polygon's area vector (Newell), the way its triangles must turn.
    let area: Vector3<f64> = (0..ids.len())
        .map(|k| {
            let (a, b) = side(k);
            a.cross(&b)
        })
        .sum();
    let normal = area.try_normalize(0.0)?;
    let across = ids
        .iter()
        .map(|&v| (pos[v] - centre).norm())
        .fold(0.0, f64::max);
    let flat = ids
        .iter()
        .all(|&v| (pos[v] - centre).dot(&normal).abs() <= FLAT * across);
    let sees_every_side = (0..ids.len()).all(|k| {
        let (a, b) = side(k);
        (a - centre).cross(&(b - centre)).dot(&area) > 0.0
    });
    (flat && sees_every_side).then_some(centre)
}

/// How far (a share of its radius) a polygon's corners may stand off its mean plane for
/// [`star_centre`] to call it flat.
const FLAT: f64 = 1e-6;

/// The fewest corners [`star_centre`] triangulates from the centroid: a fan of a regular
/// octagon already has angles of 22.5 degrees at its corner, and they narrow as `180 / n`.
/// Hexagons (a vault meshed in planar hexagons) keep their fans: the centroid, a vertex more
/// in each flat facet, changes the curvature read there and the quads with it (measured on
/// one such vault: 43 -> 107 pieces cut).
const STAR_CORNERS: usize = 8;

impl Surface {
    /// [`Self::from_polymesh_mapped`] without the vertex map.
    #[cfg(test)]
    pub fn from_polymesh(mesh: &PolyMesh) -> Result<Self, RemeshError> {
        Self::from_polymesh_mapped(mesh).map(|(surface, _)| surface)
    }

    /// Triangulates the input polygons (triangles and quads as they are or fanned, larger
    /// polygons from their centroid where it sees every side, [`star_centre`]), dropping
    /// vertices no face uses; also returns, per input vertex, its vertex on the surface
    /// (`usize::MAX` for vertices no face uses; the centroids come after the input's).
    pub fn from_polymesh_mapped(mesh: &PolyMesh) -> Result<(Self, Vec<usize>), RemeshError> {
        let mut remap = vec![usize::MAX; mesh.positions().len()];
        let mut pos = Vec::new();
        let mut tris = Vec::new();
        for face in mesh.faces() {
            let mut ids = Vec::with_capacity(face.len());
            for &v in face {
                if remap[v] == usize::MAX {
                    remap[v] = pos.len();
                    pos.push(mesh.positions()[v].coords);
                }
                ids.push(remap[v]);
            }
            match star_centre(&pos, &ids) {
                // A flat polygon of many corners: triangles from its centroid, which a fan
                // from one corner makes needles of (a flat 40-gon's quads had 47 % of their
                // edges within 20 % of the target and 91 irregular vertices; now 91 % and 0).
                Some(centre) => {
                    let c = pos.len();
                    pos.push(centre);
                    for k in 0..ids.len() {
                        tris.push([c, ids[k], ids[(k + 1) % ids.len()]]);
                    }
                }
                None => {
                    for k in 1..ids.len() - 1 {
                        tris.push([ids[0], ids[k], ids[k + 1]]);
                    }
                }
            }
        }
        let surface = Self::build(pos, tris, None);
        if let Some(v) = surface.pinched_vertex() {
            // `v` numbers the vertices as the faces first use them: the message names the
            // mesh's own number and where it is.
            let own = remap.iter().position(|&r| r == v).unwrap_or(v);
            let p = mesh.positions()[own];
            return Err(RemeshError::UnsupportedInput(format!(
                "vertex {own} (counted from 0) at ({:.4}, {:.4}, {:.4}) is where two boundary loops or two surface sheets touch at a single point; split it into separate vertices, one per sheet, or delete the faces of one sheet around it",
                p.x, p.y, p.z
            )));
        }
        Ok((surface, remap))
    }

    /// Builds adjacency, boundary loops and (unless given) area-weighted vertex normals.
    pub fn build(
        pos: Vec<Vector3<f64>>,
        tris: Vec<[usize; 3]>,
        normals: Option<Vec<Vector3<f64>>>,
    ) -> Self {
        let n = pos.len();
        let mut edges = Vec::new();
        let mut edge_faces: Vec<u32> = Vec::new();
        let mut directed: Vec<[usize; 2]> = Vec::new();
        let mut adj: Vec<Vec<(usize, usize)>> = vec![Vec::new(); n];
        for tri in &tris {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                let key = [a.min(b), a.max(b)];
                // Vertex neighbourhoods are short: a scan beats hashing.
                let e = match adj[key[0]].iter().find(|&&(w, _)| w == key[1]) {
                    Some(&(_, e)) => e,
                    None => {
                        edges.push(key);
                        edge_faces.push(0);
                        directed.push([a, b]);
                        adj[key[0]].push((key[1], edges.len() - 1));
                        adj[key[1]].push((key[0], edges.len() - 1));
                        edges.len() - 1
                    }
                };
                edge_faces[e] += 1;
            }
        }
        for list in &mut adj {
            list.sort_unstable();
        }
        let mut boundary: Vec<Option<(usize, usize)>> = vec![None; n];
        let mut next = vec![usize::MAX; n];
        let mut prev = vec![usize::MAX; n];
        for (e, &[a, b]) in directed.iter().enumerate() {
            if edge_faces[e] == 1 {
                if next[a] == usize::MAX {
                    next[a] = b;
                }
                if prev[b] == usize::MAX {
                    prev[b] = a;
                }
            }
        }
        for v in 0..n {
            if next[v] != usize::MAX && prev[v] != usize::MAX {
                boundary[v] = Some((prev[v], next[v]));
            }
        }
        let normals = normals.unwrap_or_else(|| {
            let mut acc = vec![Vector3::zeros(); n];
            for tri in &tris {
                let w = (pos[tri[1]] - pos[tri[0]]).cross(&(pos[tri[2]] - pos[tri[0]]));
                for &v in tri {
                    acc[v] += w;
                }
            }
            acc.into_iter()
                .map(|a| a.try_normalize(1e-300).unwrap_or_else(Vector3::z))
                .collect()
        });
        let mean_edge = if edges.is_empty() {
            0.0
        } else {
            edges
                .iter()
                .map(|&[a, b]| (pos[a] - pos[b]).norm())
                .sum::<f64>()
                / edges.len() as f64
        };
        let mut surface = Self {
            pos,
            tris,
            normals,
            edges,
            adj,
            boundary,
            mean_edge,
            bdirs: Vec::new(),
            corner: Vec::new(),
            narrow: Vec::new(),
        };
        surface.set_boundary_scale(0.0);
        surface
    }

    /// A vertex with more than one boundary edge pair (two loops touching), if any.
    fn pinched_vertex(&self) -> Option<usize> {
        let mut count = vec![0usize; self.pos.len()];
        let mut uses: HashMap<[usize; 2], u8> = HashMap::new();
        for tri in &self.tris {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                *uses.entry([a.min(b), a.max(b)]).or_insert(0) += 1;
            }
        }
        for &[a, b] in &self.edges {
            if uses.get(&[a, b]) == Some(&1) {
                count[a] += 1;
                count[b] += 1;
            }
        }
        count.iter().position(|&c| c > 2)
    }

    /// Number of vertices.
    pub fn len(&self) -> usize {
        self.pos.len()
    }

    /// The index of the edge joining `a` and `b` (which must be adjacent), in either order.
    pub fn edge(&self, a: usize, b: usize) -> usize {
        let list = &self.adj[a];
        list[list.partition_point(|&(v, _)| v < b)].1
    }

    /// The 3D edge vector from `a` to `b`.
    pub fn edge_vec(&self, a: usize, b: usize) -> Vector3<f64> {
        self.pos[b] - self.pos[a]
    }

    /// Per vertex, the area it stands for: a third of the area of each of its triangles (the
    /// barycentric dual cell), so that a sum of per-vertex terms times these areas is the
    /// integral of the term over the surface, whatever the triangulation.
    pub fn vertex_areas(&self) -> Vec<f64> {
        let mut area = vec![0.0; self.len()];
        for &[a, b, c] in &self.tris {
            let twice = (self.pos[b] - self.pos[a])
                .cross(&(self.pos[c] - self.pos[a]))
                .norm();
            for v in [a, b, c] {
                area[v] += twice / 6.0;
            }
        }
        area
    }
}

/// `d` laid into the tangent plane of the unit normal `n` and made a unit vector; some
/// tangent ([`any_tangent`]) where `d` has no part in that plane.
pub(crate) fn in_tangent_plane(d: &Vector3<f64>, n: &Vector3<f64>) -> Vector3<f64> {
    (d - n * n.dot(d))
        .try_normalize(1e-300)
        .unwrap_or_else(|| any_tangent(n))
}

/// Some unit vector orthogonal to `n`.
pub(crate) fn any_tangent(n: &Vector3<f64>) -> Vector3<f64> {
    let axis = if n.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    (axis - n * n.dot(&axis)).normalize()
}

/// Generated surfaces for the remesher's unit tests.
#[cfg(test)]
pub(crate) mod samples {
    use std::ops::Range;

    use nalgebra::Point3;

    use super::Surface;
    use crate::mesh::PolyMesh;

    /// A sheet of `n` x `n` square cells of side `cell` over the xy-plane, lifted to
    /// `height(x, y)`, without the cells `(i, j)` with `i` in `hole.0` and `j` in `hole.1`;
    /// quads counter-clockwise seen from above, fan-triangulated as any input is.
    pub fn sheet(
        n: usize,
        cell: f64,
        hole: (Range<usize>, Range<usize>),
        height: impl Fn(f64, f64) -> f64,
    ) -> Surface {
        let at = |i: usize, j: usize| j * (n + 1) + i;
        let positions = (0..=n)
            .flat_map(|j| (0..=n).map(move |i| (i as f64 * cell, j as f64 * cell)))
            .map(|(x, y)| Point3::new(x, y, height(x, y)))
            .collect();
        let faces = (0..n)
            .flat_map(|j| (0..n).map(move |i| (i, j)))
            .filter(|(i, j)| !(hole.0.contains(i) && hole.1.contains(j)))
            .map(|(i, j)| vec![at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)])
            .collect();
        Surface::from_polymesh(&PolyMesh::new(positions, faces).expect("a valid sheet"))
            .expect("a manifold sheet")
    }

    /// A gently curved sheet: a low saddle with a ripple, so no two triangles are coplanar.
    pub fn wavy(x: f64, y: f64) -> f64 {
        0.15 * (x - 1.0) * (y - 1.0) + 0.05 * (3.0 * x).sin() * (2.0 * y).cos()
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::Point3;

    use super::samples::{sheet, wavy};
    use super::*;

    #[test]
    fn a_flat_polygon_of_many_corners_is_triangulated_from_its_centroid() {
        // A regular n-gon of radius 3 in the plane z = 0, its corners lifted by `lift(k)`.
        let polygon = |n: usize, lift: &dyn Fn(usize) -> f64| {
            let positions = (0..n)
                .map(|k| {
                    let a = std::f64::consts::TAU * k as f64 / n as f64;
                    Point3::new(3.0 * a.cos(), 3.0 * a.sin(), lift(k))
                })
                .collect();
            PolyMesh::new(positions, vec![(0..n).collect()]).expect("a polygon")
        };
        // Flat, 40 corners: 40 triangles about a 41st vertex (a fan: 38 needles).
        let flat = Surface::from_polymesh(&polygon(40, &|_| 0.0)).unwrap();
        assert_eq!((flat.len(), flat.tris.len()), (41, 40));
        // Not flat, or a hexagon: the fan, as the tile stage triangulates them.
        let bent = Surface::from_polymesh(&polygon(40, &|k| 0.1 * (k % 2) as f64)).unwrap();
        assert_eq!((bent.len(), bent.tris.len()), (40, 38));
        let hexagon = Surface::from_polymesh(&polygon(6, &|_| 0.0)).unwrap();
        assert_eq!((hexagon.len(), hexagon.tris.len()), (6, 4));
        // A flat comb whose centroid does not see every side: fanned.
        let comb = [
            [0.0, 0.0],
            [4.0, 0.0],
            [4.0, 3.0],
            [3.0, 3.0],
            [3.0, 0.5],
            [2.5, 0.5],
            [2.5, 3.0],
            [1.5, 3.0],
            [1.5, 0.5],
            [1.0, 0.5],
            [1.0, 3.0],
            [0.0, 3.0],
        ];
        let pos: Vec<Vector3<f64>> = comb.iter().map(|p| Vector3::new(p[0], p[1], 0.0)).collect();
        let ids: Vec<usize> = (0..comb.len()).collect();
        assert!(star_centre(&pos, &ids).is_none());
    }

    #[test]
    fn vertex_areas_share_out_the_surface() {
        // A 2 x 2 m sheet of 0.1 m cells, gently curved: the areas sum to the triangles'
        // area, and a vertex inside a flat one stands for one cell.
        let s = sheet(20, 0.1, (0..0, 0..0), wavy);
        let area = s.vertex_areas();
        let total: f64 = s
            .tris
            .iter()
            .map(|&[a, b, c]| (s.pos[b] - s.pos[a]).cross(&(s.pos[c] - s.pos[a])).norm() / 2.0)
            .sum();
        assert!((area.iter().sum::<f64>() - total).abs() < 1e-12 * total);
        let flat = sheet(20, 0.1, (0..0, 0..0), |_, _| 0.0);
        let area = flat.vertex_areas();
        assert!(
            (area[10 * 21 + 10] - 0.01).abs() < 1e-12,
            "{}",
            area[10 * 21 + 10]
        );
    }

    #[test]
    fn adjacency_lists_every_edge_at_both_ends_in_order() {
        // A sheet with a hole is an annulus: V - E + F = 0.
        let s = sheet(8, 0.25, (3..5, 2..6), wavy);
        assert_eq!(
            s.len() as i64 - s.edges.len() as i64 + s.tris.len() as i64,
            0
        );
        for (e, &[a, b]) in s.edges.iter().enumerate() {
            assert!(a < b);
            assert!(s.adj[a].contains(&(b, e)) && s.adj[b].contains(&(a, e)));
        }
        for list in &s.adj {
            assert!(
                list.windows(2).all(|w| w[0].0 < w[1].0),
                "sorted by neighbour, each once"
            );
        }
        assert_eq!(s.adj.iter().map(Vec::len).sum::<usize>(), 2 * s.edges.len());
        let mean = s
            .edges
            .iter()
            .map(|&[a, b]| s.edge_vec(a, b).norm())
            .sum::<f64>()
            / s.edges.len() as f64;
        assert!((s.mean_edge - mean).abs() < 1e-12);
        // Normals are unit and face up, as the faces do.
        assert!(
            s.normals
                .iter()
                .all(|n| (n.norm() - 1.0).abs() < 1e-12 && n.z > 0.8)
        );
    }

    #[test]
    fn unused_vertices_are_dropped_and_pinched_vertices_refused() {
        // Two triangles sharing only vertex 2 (a bow tie), and vertex 5 used by no face.
        let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
        let positions = vec![
            p(0.0, 0.0),
            p(1.0, 0.0),
            p(1.0, 1.0),
            p(2.0, 1.0),
            p(2.0, 2.0),
            p(9.0, 9.0),
        ];
        let bow_tie = PolyMesh::new(positions.clone(), vec![vec![0, 1, 2], vec![2, 3, 4]]).unwrap();
        assert!(matches!(
            Surface::from_polymesh(&bow_tie),
            Err(RemeshError::UnsupportedInput(_))
        ));
        let apart = PolyMesh::new(positions, vec![vec![0, 1, 2], vec![1, 3, 2]]).unwrap();
        let s = Surface::from_polymesh(&apart).unwrap();
        assert_eq!((s.len(), s.tris.len(), s.edges.len()), (4, 2, 5));
    }

    #[test]
    fn any_tangent_is_a_unit_vector_orthogonal_to_the_normal() {
        for n in [
            Vector3::x(),
            Vector3::y(),
            Vector3::z(),
            Vector3::new(0.95, 0.1, -0.3).normalize(),
        ] {
            let t = any_tangent(&n);
            assert!((t.norm() - 1.0).abs() < 1e-12 && t.dot(&n).abs() < 1e-12);
        }
    }
}
