//! Edge adjacency of a polygon mesh: which faces meet at each edge and which edges meet at
//! each vertex. Built in face order, so edge numbering is deterministic.

use std::collections::HashMap;

use foldhash::fast::FixedState;

use super::{MeshError, PolyMesh};

/// The pieces of a mesh ([`Topology::face_pieces`]) and their areas.
#[derive(Debug, Clone)]
pub struct PieceAreas {
    /// Each face's piece.
    pub piece: Vec<usize>,
    /// Each piece's area.
    pub areas: Vec<f64>,
}

impl PieceAreas {
    /// The piece of the most area (the first of equals).
    pub fn main(&self) -> usize {
        (0..self.areas.len())
            .max_by(|&a, &b| self.areas[a].total_cmp(&self.areas[b]).then(b.cmp(&a)))
            .unwrap_or(0)
    }

    /// The share of the whole area [`Self::main`] holds (NaN for a mesh of no area).
    pub fn main_share(&self) -> f64 {
        self.areas.get(self.main()).copied().unwrap_or(0.0) / self.areas.iter().sum::<f64>()
    }
}

/// An undirected mesh edge with its (at most two) faces.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Edge {
    /// End points, smaller index first.
    pub vertices: [usize; 2],
    /// The faces on either side, in order of first appearance; one for a boundary edge.
    pub faces: Vec<usize>,
}

impl Edge {
    /// True when only one face borders the edge.
    pub fn is_boundary(&self) -> bool {
        self.faces.len() == 1
    }

    /// The face across this edge from `f`, if there is one.
    pub fn other_face(&self, f: usize) -> Option<usize> {
        match self.faces.as_slice() {
            [a, b] if *a == f => Some(*b),
            [a, b] if *b == f => Some(*a),
            _ => None,
        }
    }
}

/// Edges of a mesh and their incidences.
#[derive(Debug, Clone)]
pub struct Topology {
    edges: Vec<Edge>,
    /// `face_edges[f][i]` is the edge from corner `i` to corner `i + 1` of face `f`.
    face_edges: Vec<Vec<usize>>,
    vertex_edges: Vec<Vec<usize>>,
    /// `edge_corners[e][k]`: the corner of `edges[e].faces[k]` where edge `e` starts, so that
    /// finding an edge in a face takes constant time however large the face.
    edge_corners: Vec<[usize; 2]>,
}

impl Topology {
    /// Builds the adjacency of `mesh`.
    ///
    /// # Errors
    /// [`MeshError::NonManifoldEdge`] when an edge borders more than two faces.
    pub fn new(mesh: &PolyMesh) -> Result<Self, MeshError> {
        // Looked up once per face corner: a fast fixed-seed hasher (only lookups, never the
        // map's order, shape the result).
        let corners: usize = mesh.faces().iter().map(Vec::len).sum();
        let mut index: HashMap<[usize; 2], usize, FixedState> =
            HashMap::with_capacity_and_hasher(corners / 2 + 1, FixedState::default());
        let mut edges: Vec<Edge> = Vec::new();
        let mut vertex_edges = vec![Vec::new(); mesh.positions().len()];
        let mut face_edges = Vec::with_capacity(mesh.face_count());
        let mut edge_corners: Vec<[usize; 2]> = Vec::new();
        for (f, face) in mesh.faces().iter().enumerate() {
            let mut own = Vec::with_capacity(face.len());
            for (i, &a) in face.iter().enumerate() {
                let b = face[(i + 1) % face.len()];
                let key = [a.min(b), a.max(b)];
                let e = *index.entry(key).or_insert_with(|| {
                    edges.push(Edge {
                        vertices: key,
                        faces: Vec::with_capacity(2),
                    });
                    edge_corners.push([usize::MAX; 2]);
                    vertex_edges[key[0]].push(edges.len() - 1);
                    vertex_edges[key[1]].push(edges.len() - 1);
                    edges.len() - 1
                });
                edges[e].faces.push(f);
                if edges[e].faces.len() > 2 {
                    let faces = edges[e].faces.clone();
                    // A face without area along the edge is the fault, not a fin.
                    let length2 =
                        (mesh.positions()[key[0]] - mesh.positions()[key[1]]).norm_squared();
                    if let Some(&flat) = faces
                        .iter()
                        .find(|&&g| mesh.face_area_vector(g).norm() <= 1e-5 * length2)
                    {
                        return Err(MeshError::DegenerateFace {
                            face: flat,
                            a: key[0],
                            b: key[1],
                        });
                    }
                    return Err(MeshError::NonManifoldEdge {
                        a: key[0],
                        b: key[1],
                        face_count: faces.len(),
                        faces,
                    });
                }
                edge_corners[e][edges[e].faces.len() - 1] = i;
                own.push(e);
            }
            face_edges.push(own);
        }
        Ok(Self {
            edges,
            face_edges,
            vertex_edges,
            edge_corners,
        })
    }

    /// Checks that every edge shared by two faces is run in opposite directions by them.
    ///
    /// # Errors
    /// [`MeshError::InconsistentOrientation`] naming the first such edge.
    pub fn check_orientation(&self, mesh: &PolyMesh) -> Result<(), MeshError> {
        for (f, edges) in self.face_edges.iter().enumerate() {
            let face = &mesh.faces()[f];
            for (i, &e) in edges.iter().enumerate() {
                let Some(g) = self.edges[e].other_face(f) else {
                    continue;
                };
                if g < f {
                    continue;
                }
                let (a, b) = (face[i], face[(i + 1) % face.len()]);
                let k = self.corner(g, e).expect("the other face has the edge");
                let other = &mesh.faces()[g];
                if other[k] == a {
                    return Err(MeshError::InconsistentOrientation {
                        a,
                        b,
                        faces: [f, g],
                    });
                }
            }
        }
        Ok(())
    }

    /// The corner of face `f` where edge `e` starts (`face_edges(f)[corner] == e`), if `e`
    /// borders `f`.
    fn corner(&self, f: usize, e: usize) -> Option<usize> {
        let k = self.edges.get(e)?.faces.iter().position(|&x| x == f)?;
        Some(self.edge_corners[e][k])
    }

    /// The pieces of the mesh: faces joined across shared edges. Returns each face's piece
    /// (numbered in order of their first face) and the number of pieces.
    pub fn face_pieces(&self) -> (Vec<usize>, usize) {
        let mut piece = vec![usize::MAX; self.face_edges.len()];
        let mut count = 0;
        let mut stack = Vec::new();
        for start in 0..piece.len() {
            if piece[start] != usize::MAX {
                continue;
            }
            piece[start] = count;
            stack.push(start);
            while let Some(f) = stack.pop() {
                for &e in &self.face_edges[f] {
                    if let Some(g) = self.edges[e].other_face(f)
                        && piece[g] == usize::MAX
                    {
                        piece[g] = count;
                        stack.push(g);
                    }
                }
            }
            count += 1;
        }
        (piece, count)
    }

    /// [`Self::face_pieces`] with each piece's area: `mesh` is the mesh this topology was
    /// built from.
    pub fn piece_areas(&self, mesh: &PolyMesh) -> PieceAreas {
        let (piece, pieces) = self.face_pieces();
        let mut areas = vec![0.0; pieces];
        for (f, &p) in piece.iter().enumerate() {
            areas[p] += mesh.face_area_vector(f).norm();
        }
        PieceAreas { piece, areas }
    }

    /// All edges.
    pub fn edges(&self) -> &[Edge] {
        &self.edges
    }

    /// Edges of face `f` in face order: entry `i` joins corners `i` and `i + 1`.
    pub fn face_edges(&self, f: usize) -> &[usize] {
        &self.face_edges[f]
    }

    /// Edges incident to vertex `v`.
    pub fn vertex_edges(&self, v: usize) -> &[usize] {
        &self.vertex_edges[v]
    }

    /// True when `v` touches a boundary edge or no edge at all.
    pub fn is_boundary_vertex(&self, v: usize) -> bool {
        self.vertex_edges[v].is_empty()
            || self.vertex_edges[v]
                .iter()
                .any(|&e| self.edges[e].is_boundary())
    }

    /// The edge of face `f` that meets edge `e` at vertex `v` (the neighbour of `e` around `f`
    /// on `v`'s side), or `None` if `e` is not an edge of `f` touching `v`.
    pub fn face_edge_at(&self, f: usize, e: usize, v: usize) -> Option<usize> {
        let own = &self.face_edges[f];
        let i = self.corner(f, e)?;
        let n = own.len();
        [own[(i + n - 1) % n], own[(i + 1) % n]]
            .into_iter()
            .find(|&other| other != e && self.edges[other].vertices.contains(&v))
    }

    /// For an interior vertex with exactly four edges and four faces (a regular vertex of a
    /// quad mesh), the edge opposite `e` at `v`: the one sharing no face with `e`.
    pub fn opposite_edge(&self, v: usize, e: usize) -> Option<usize> {
        let around = &self.vertex_edges[v];
        if around.len() != 4 || self.is_boundary_vertex(v) {
            return None;
        }
        let neighbours: Vec<usize> = self.edges[e]
            .faces
            .iter()
            .filter_map(|&f| self.face_edge_at(f, e, v))
            .collect();
        let mut rest = around
            .iter()
            .copied()
            .filter(|&x| x != e && !neighbours.contains(&x));
        match (rest.next(), rest.next()) {
            (Some(o), None) if neighbours.len() == 2 => Some(o),
            _ => None,
        }
    }
}
