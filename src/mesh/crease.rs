//! Creases: lines where a surface turns sharply from one face to the next (a groin vault's
//! groins, a cloister vault's valleys, the folds of a folded plate), and the sheets between
//! them.
//!
//! Courses cannot run smoothly over a crease: on a groin vault the tiles of each web lie in
//! level courses along its own barrel, and the courses of two webs meet at the groin at an
//! angle, where the mason cuts the tiles to the groin line. A single cross field over both
//! webs (paper section 3.2) turns instead, and half the webs' tiles climb. So the remesh stage
//! quadrangulates each sheet with a field of its own, and the tile stage cuts the tiles to
//! the creases as to a boundary; [`split_at_creases`] is the one rule both follow.
//!
//! An edge is a crease when its faces turn by at least [`CREASE_DEGREES`] and by at least
//! twice as much as across any other edge of the faces around its ends (but the edges that
//! run on from it): a sharp line on a smooth surface, not the even facets of a coarse mesh
//! of a smooth one (a barrel of eight facets turns by 22.5 degrees at every edge and is no
//! crease), nor the growing turn of a mesh sampled evenly in plan towards a barrel's
//! springing. A crease that fades out (a groin flattens towards the crown) is carried on in
//! the direction it ran to where it meets another crease or the boundary, when that is near
//! ([`EXTEND_SHARE`] of its length): the four groins of a groin vault meet at its crown.
//! Creases that do not part the surface (a fold dying out in the middle) and sheets smaller
//! than [`MIN_SHEET_SHARE`] of the area are left joined.

use super::{PolyMesh, Topology};
use nalgebra::Vector3;

/// Least turn between two faces, in degrees, for their edge to be a crease.
pub const CREASE_DEGREES: f64 = 12.0;

/// A crease turns by at least this many times the turn across the other edges of the faces
/// around its ends.
const CREASE_RATIO: f64 = 2.0;

/// A fading crease is carried on over at most this share of its own length.
const EXTEND_SHARE: f64 = 0.6;

/// Cosine of the largest angle (35 degrees) between a carried-on crease's edges and the
/// direction it ran in.
const EXTEND_COS: f64 = 0.819_152_044_288_991_8;

/// Sheets smaller than this share of the surface's area stay joined to their neighbours.
pub const MIN_SHEET_SHARE: f64 = 0.02;

/// A surface cut open along its creases.
#[derive(Debug, Clone, PartialEq)]
pub struct Sheets {
    /// The surface with every crease vertex repeated once per sheet around it: the same faces
    /// in the same order, the input's vertices first, the copies after them.
    pub mesh: PolyMesh,
    /// For every vertex of `mesh`, the input vertex it stands for.
    pub source: Vec<usize>,
    /// Each face's sheet, numbered in order of their first face.
    pub sheet: Vec<usize>,
    /// Number of sheets.
    pub count: usize,
    /// The creases as edges of `mesh`, once per side: each pair of vertices is a boundary
    /// edge of `mesh` that was an interior edge of the input.
    pub seams: Vec<[usize; 2]>,
}

/// Cuts `mesh` open along the creases that part it into sheets; `None` when none does.
pub fn split_at_creases(mesh: &PolyMesh) -> Option<Sheets> {
    // Most surfaces turn gently everywhere: they are told apart without building the edges.
    let normal = normals(mesh);
    if !turns_sharply(mesh, &normal) {
        return None;
    }
    let topology = Topology::new(mesh).expect("a PolyMesh is manifold by construction");
    let mut crease = sharp_edges(mesh, &topology, &normal);
    if !crease.iter().any(|&c| c) {
        return None;
    }
    carry_on(mesh, &topology, &normal, &mut crease);
    let (_, pieces) = topology.face_pieces();
    let total_area = mesh.area();
    // Creases that part nothing, and sheets too small to lay on their own, are joined again
    // until every crease left parts two sheets of some size.
    let (sheet, count) = loop {
        let (sheet, count) = sheets(&topology, mesh.face_count(), &crease);
        let mut area = vec![0.0; count];
        for (f, &s) in sheet.iter().enumerate() {
            area[s] += mesh.face_area_vector(f).norm();
        }
        let mut changed = false;
        for (e, edge) in topology.edges().iter().enumerate() {
            if !crease[e] {
                continue;
            }
            let [a, b] = [edge.faces[0], edge.faces[1]].map(|f| sheet[f]);
            if a == b || area[a].min(area[b]) < MIN_SHEET_SHARE * total_area {
                crease[e] = false;
                changed = true;
            }
        }
        if !changed {
            break (sheet, count);
        }
    };
    if count <= pieces {
        return None;
    }
    Some(cut_open(mesh, &topology, &crease, sheet, count))
}

/// Whether two faces sharing an edge turn by [`CREASE_DEGREES`] or more: the faces around
/// each vertex in one array (no hashing), each face's neighbour across an edge found among
/// the faces of the edge's first vertex.
fn turns_sharply(mesh: &PolyMesh, n: &[Vector3<f64>]) -> bool {
    let faces = mesh.faces();
    let mut start = vec![0usize; mesh.positions().len() + 1];
    for face in faces {
        for &v in face {
            start[v + 1] += 1;
        }
    }
    for v in 0..mesh.positions().len() {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    let mut around = vec![0usize; start[mesh.positions().len()]];
    for (f, face) in faces.iter().enumerate() {
        for &v in face {
            around[fill[v]] = f;
            fill[v] += 1;
        }
    }
    let cos = CREASE_DEGREES.to_radians().cos();
    faces.iter().enumerate().any(|(f, face)| {
        (0..face.len()).any(|i| {
            let (a, b) = (face[i], face[(i + 1) % face.len()]);
            around[start[a]..start[a + 1]].iter().any(|&g| {
                // Across the edge a -> b: the face holding b -> a (orientation is consistent).
                let other = &faces[g];
                g > f
                    && (0..other.len()).any(|j| other[j] == b && other[(j + 1) % other.len()] == a)
                    && n[f] != Vector3::zeros()
                    && n[g] != Vector3::zeros()
                    && n[f].dot(&n[g]) <= cos
            })
        })
    })
}

/// Unit normal of every face (zero for a face without area).
fn normals(mesh: &PolyMesh) -> Vec<Vector3<f64>> {
    (0..mesh.face_count())
        .map(|f| {
            mesh.face_area_vector(f)
                .try_normalize(0.0)
                .unwrap_or_else(Vector3::zeros)
        })
        .collect()
}

/// The turn in degrees between the faces (unit normals `n`) of every interior edge (0 on the
/// boundary and next to a face without area).
fn turns(topology: &Topology, n: &[Vector3<f64>]) -> Vec<f64> {
    topology
        .edges()
        .iter()
        .map(|edge| match edge.faces.as_slice() {
            [f, g] if n[*f] != Vector3::zeros() && n[*g] != Vector3::zeros() => {
                n[*f].dot(&n[*g]).clamp(-1.0, 1.0).acos().to_degrees()
            }
            _ => 0.0,
        })
        .collect()
}

/// Edges that turn by at least [`CREASE_DEGREES`] and [`CREASE_RATIO`] times any other edge
/// of the faces around their ends, but those that run on from them (within 35 degrees): on a
/// smooth surface the turn grows from edge to edge, at a crease it jumps.
fn sharp_edges(mesh: &PolyMesh, topology: &Topology, normal: &[Vector3<f64>]) -> Vec<bool> {
    let turn = turns(topology, normal);
    let p = mesh.positions();
    let edges = topology.edges();
    let direction = |e: usize| {
        let [a, b] = edges[e].vertices;
        (p[b] - p[a])
            .try_normalize(0.0)
            .unwrap_or_else(Vector3::zeros)
    };
    edges
        .iter()
        .enumerate()
        .map(|(e, edge)| {
            if turn[e] < CREASE_DEGREES {
                return false;
            }
            let along = direction(e);
            let around = edge
                .vertices
                .iter()
                .flat_map(|&v| topology.vertex_edges(v))
                .flat_map(|&o| edges[o].faces.iter())
                .flat_map(|&f| topology.face_edges(f))
                .filter(|&&o| {
                    let runs_on = edges[o].vertices.iter().any(|v| edge.vertices.contains(v))
                        && direction(o).dot(&along).abs() >= EXTEND_COS;
                    o != e && !runs_on
                })
                .map(|&o| turn[o])
                .fold(0.0, f64::max);
            turn[e] >= CREASE_RATIO * around
        })
        .collect()
}

/// Carries every crease that ends inside the surface on in the direction it ran in, over
/// edges within 35 degrees of it in the tangent plane, to the first vertex on another crease
/// or on the boundary; when that is farther than [`EXTEND_SHARE`] of the crease's length,
/// the crease is left as it was. Ends are taken in vertex order, so a carried-on crease is a
/// crease for the next (its length stays the one found before any was carried on).
fn carry_on(
    mesh: &PolyMesh,
    topology: &Topology,
    face_normal: &[Vector3<f64>],
    crease: &mut [bool],
) {
    let p = mesh.positions();
    let edges = topology.edges();
    let creased = |crease: &[bool], v: usize| -> Vec<usize> {
        topology
            .vertex_edges(v)
            .iter()
            .copied()
            .filter(|&e| crease[e])
            .collect()
    };
    let other = |e: usize, v: usize| {
        let [a, b] = edges[e].vertices;
        if a == v { b } else { a }
    };
    let length_at = crease_lengths(mesh, topology, crease);
    // The area-weighted mean of the normals of the faces around `v`.
    let vertex_normal = |v: usize| {
        faces_around(topology, v)
            .iter()
            .map(|&f| face_normal[f] * mesh.face_area_vector(f).norm())
            .sum::<Vector3<f64>>()
            .try_normalize(0.0)
            .unwrap_or_else(Vector3::zeros)
    };
    for end in 0..p.len() {
        let ending = topology
            .vertex_edges(end)
            .iter()
            .filter(|&&e| crease[e])
            .count()
            == 1;
        if !ending || topology.is_boundary_vertex(end) {
            continue;
        }
        // The crease's length, and its direction over its last three edges.
        let length = length_at[end];
        let arriving = creased(crease, end);
        let (mut back, mut from) = (end, arriving[0]);
        for _ in 0..3 {
            back = other(from, back);
            match creased(crease, back).as_slice() {
                [a, b] => from = if *a == from { *b } else { *a },
                _ => break,
            }
        }
        let Some(dir) = (p[end] - p[back]).try_normalize(0.0) else {
            continue;
        };
        let (mut at, mut walked, mut path) = (end, 0.0, Vec::new());
        let reached = loop {
            // Angles in the surface's tangent plane at `at`: over a ridge or an apex (a hip
            // roof's creases meet at its top) the crease runs on straight in plan while it
            // turns from rising to falling.
            let normal = vertex_normal(at);
            let flat = |d: Vector3<f64>| (d - normal * d.dot(&normal)).try_normalize(0.0);
            let Some(ahead) = flat(dir) else {
                break false;
            };
            let step = topology
                .vertex_edges(at)
                .iter()
                .copied()
                .filter(|e| !path.contains(e) && !crease[*e])
                .filter_map(|e| {
                    let to = other(e, at);
                    let along = p[to] - p[at];
                    let cos = flat(along)?.dot(&ahead);
                    (cos >= EXTEND_COS).then_some((cos, e, to, along.norm()))
                })
                .max_by(|a, b| a.0.total_cmp(&b.0).then(b.1.cmp(&a.1)));
            let Some((_, e, to, len)) = step else {
                break false;
            };
            walked += len;
            if walked > EXTEND_SHARE * length {
                break false;
            }
            path.push(e);
            if topology.is_boundary_vertex(to) || !creased(crease, to).is_empty() {
                break true;
            }
            at = to;
        };
        if reached {
            for e in path {
                crease[e] = true;
            }
        }
    }
}

/// The faces around vertex `v`, in index order.
fn faces_around(topology: &Topology, v: usize) -> Vec<usize> {
    let mut faces: Vec<usize> = topology
        .vertex_edges(v)
        .iter()
        .flat_map(|&e| topology.edges()[e].faces.iter().copied())
        .collect();
    faces.sort_unstable();
    faces.dedup();
    faces
}

/// For every vertex, the length of the creases joined to it (0 off the creases): the crease
/// edges' lengths summed over their connected pieces, once for all.
fn crease_lengths(mesh: &PolyMesh, topology: &Topology, crease: &[bool]) -> Vec<f64> {
    let p = mesh.positions();
    let mut root: Vec<usize> = (0..p.len()).collect();
    fn find(root: &mut [usize], mut v: usize) -> usize {
        while root[v] != v {
            root[v] = root[root[v]];
            v = root[v];
        }
        v
    }
    let creases = topology
        .edges()
        .iter()
        .enumerate()
        .filter(|&(e, _)| crease[e]);
    for (_, edge) in creases.clone() {
        let [a, b] = edge.vertices.map(|v| find(&mut root, v));
        root[a.max(b)] = a.min(b);
    }
    let mut length = vec![0.0; p.len()];
    for (_, edge) in creases {
        let [a, b] = edge.vertices;
        let r = find(&mut root, a);
        length[r] += (p[a] - p[b]).norm();
    }
    (0..p.len())
        .map(|v| {
            let on = topology.vertex_edges(v).iter().any(|&e| crease[e]);
            if on { length[find(&mut root, v)] } else { 0.0 }
        })
        .collect()
}

/// Faces joined across edges that are not creases: each face's sheet and their number.
fn sheets(topology: &Topology, faces: usize, crease: &[bool]) -> (Vec<usize>, usize) {
    let mut sheet = vec![usize::MAX; faces];
    let mut count = 0;
    for start in 0..faces {
        if sheet[start] != usize::MAX {
            continue;
        }
        sheet[start] = count;
        let mut stack = vec![start];
        while let Some(f) = stack.pop() {
            for &e in topology.face_edges(f) {
                if crease[e] {
                    continue;
                }
                if let Some(g) = topology.edges()[e].other_face(f)
                    && sheet[g] == usize::MAX
                {
                    sheet[g] = count;
                    stack.push(g);
                }
            }
        }
        count += 1;
    }
    (sheet, count)
}

/// Repeats every vertex once per wedge of faces around it that creases part, and renumbers
/// the faces' corners.
fn cut_open(
    mesh: &PolyMesh,
    topology: &Topology,
    crease: &[bool],
    sheet: Vec<usize>,
    count: usize,
) -> Sheets {
    let mut positions = mesh.positions().to_vec();
    let mut source: Vec<usize> = (0..positions.len()).collect();
    let mut faces = mesh.faces().to_vec();
    let edges = topology.edges();
    for v in 0..mesh.positions().len() {
        if !topology.vertex_edges(v).iter().any(|&e| crease[e]) {
            continue;
        }
        // The faces around v, joined across its edges that are not creases.
        let around = faces_around(topology, v);
        let mut wedge: Vec<usize> = (0..around.len()).collect();
        let find = |wedge: &mut Vec<usize>, mut i: usize| {
            while wedge[i] != i {
                wedge[i] = wedge[wedge[i]];
                i = wedge[i];
            }
            i
        };
        for &e in topology.vertex_edges(v) {
            if let ([f, g], false) = (edges[e].faces.as_slice(), crease[e]) {
                let i = around.binary_search(f).expect("a face around v");
                let j = around.binary_search(g).expect("a face around v");
                let (ri, rj) = (find(&mut wedge, i), find(&mut wedge, j));
                wedge[ri.max(rj)] = ri.min(rj);
            }
        }
        // The wedge of the lowest face keeps v; each other wedge gets a copy.
        let mut copy_of_root = std::collections::BTreeMap::new();
        for i in 0..around.len() {
            let root = find(&mut wedge, i);
            let copy = *copy_of_root.entry(root).or_insert_with(|| {
                if root == 0 {
                    v
                } else {
                    positions.push(positions[v]);
                    source.push(v);
                    positions.len() - 1
                }
            });
            for corner in faces[around[i]].iter_mut().filter(|c| **c == v) {
                *corner = copy;
            }
        }
    }
    let mut seams = Vec::new();
    for (e, edge) in edges.iter().enumerate() {
        if !crease[e] {
            continue;
        }
        for &f in &edge.faces {
            // The edge as face f now names it, in f's order.
            let face = &mesh.faces()[f];
            let n = face.len();
            let i = (0..n)
                .find(|&i| {
                    let (a, b) = (face[i], face[(i + 1) % n]);
                    edge.vertices == [a.min(b), a.max(b)]
                })
                .expect("an edge of its face");
            seams.push([faces[f][i], faces[f][(i + 1) % n]]);
        }
    }
    let mesh = PolyMesh::new(positions, faces).expect("cutting open keeps a mesh valid");
    Sheets {
        mesh,
        source,
        sheet,
        count,
        seams,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `f` on an `n` x `n` grid of the square [-1, 1]^2, cells split along its diagonals.
    fn surface(n: usize, f: impl Fn(f64, f64) -> f64) -> PolyMesh {
        super::super::generate::diagonal_grid(n, 1.0, f)
    }

    /// Two semicircular barrels of radius 1.2 crossing over the square.
    fn groin(x: f64, y: f64) -> f64 {
        let across = if x.abs() >= y.abs() { x } else { y };
        (1.44 - across * across).sqrt()
    }

    #[test]
    fn a_groin_vault_parts_into_its_four_webs_at_the_groins() {
        let mesh = surface(24, groin);
        let sheets = split_at_creases(&mesh).expect("the groins part the webs");
        assert_eq!(sheets.count, 4);
        assert_eq!(sheets.mesh.faces().len(), mesh.faces().len());
        // Each web is the quarter of the plan between two groins.
        let web_of = |x: f64, y: f64| {
            let f = (0..mesh.face_count())
                .min_by(|&a, &b| {
                    let d = |g: usize| {
                        let c = mesh.face_centroid(g);
                        (c.x - x).powi(2) + (c.y - y).powi(2)
                    };
                    d(a).total_cmp(&d(b))
                })
                .unwrap();
            sheets.sheet[f]
        };
        let webs = [
            web_of(0.6, 0.1),
            web_of(-0.6, 0.1),
            web_of(0.1, 0.6),
            web_of(0.1, -0.6),
        ];
        let mut distinct = webs.to_vec();
        distinct.sort_unstable();
        distinct.dedup();
        assert_eq!(distinct.len(), 4, "{webs:?}");
        assert_eq!(web_of(0.6, 0.1), web_of(0.9, -0.5));
        // Both groins, from corner to corner (the crown's flat stretch carried on): 2 x 24
        // edges, once per side.
        assert_eq!(sheets.seams.len(), 2 * 2 * 24);
        // Copies stand for the vertex they repeat, at its place.
        for (v, &s) in sheets.source.iter().enumerate() {
            assert_eq!(sheets.mesh.positions()[v], mesh.positions()[s]);
        }
        // The crown is repeated once per web; the groins' other vertices once per side.
        assert_eq!(
            sheets.mesh.positions().len() - mesh.positions().len(),
            3 + 2 * 22 + 4
        );
    }

    #[test]
    fn a_hip_roof_parts_into_its_four_planes_over_its_apex() {
        // The four hips meet at the apex, where each turns from rising to falling; the edges
        // at the apex turn no more than the other hips' there and are carried on over it.
        let mesh = surface(16, |x, y| 0.8 * (1.0 - x.abs().max(y.abs())));
        let sheets = split_at_creases(&mesh).expect("the hips");
        assert_eq!(sheets.count, 4);
        assert_eq!(sheets.seams.len(), 2 * 2 * 16);
    }

    #[test]
    fn smooth_and_evenly_faceted_surfaces_have_no_creases() {
        // A barrel, fine and in eight facets (22.5 degrees at every edge).
        let barrel = |x: f64, _: f64| (1.0 - x * x).max(0.0).sqrt();
        assert!(split_at_creases(&surface(24, barrel)).is_none());
        assert!(split_at_creases(&surface(8, |x, _| 0.8 * (x * 1.2).cos())).is_none());
        assert!(split_at_creases(&surface(4, barrel)).is_none());
        assert!(split_at_creases(&surface(16, |x, y| 0.3 * x * y)).is_none());
    }

    #[test]
    fn a_fold_that_dies_out_inside_the_surface_parts_nothing() {
        // A ridge along x = 0 for y > 0, fading to nothing at y = 0 and flat beyond: the crease
        // cannot be carried to the boundary or to another crease within 0.6 of its length.
        let mesh = surface(24, |x, y| -0.6 * x.abs() * y.max(0.0));
        assert!(split_at_creases(&mesh).is_none());
    }

    #[test]
    fn a_folded_plate_parts_into_its_two_planes() {
        let mesh = surface(12, |x, _| 0.4 * x.abs());
        let sheets = split_at_creases(&mesh).expect("the fold");
        assert_eq!(sheets.count, 2);
        assert_eq!(sheets.seams.len(), 2 * 12);
        // Every seam is a boundary edge of the cut-open mesh, on x = 0.
        let topology = Topology::new(&sheets.mesh).unwrap();
        for &[a, b] in &sheets.seams {
            let e = topology
                .edges()
                .iter()
                .find(|e| e.vertices == [a.min(b), a.max(b)])
                .unwrap();
            assert!(e.is_boundary());
            assert_eq!(sheets.mesh.positions()[a].x, 0.0);
        }
    }
}
