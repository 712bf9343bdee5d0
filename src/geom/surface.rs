//! Closest points on a triangulated surface, with the surface's smooth normal there.

use nalgebra::Vector3;

use super::{Bvh, closest};
use crate::mesh::PolyMesh;

/// A triangle surface indexed for closest-point queries, with area-weighted vertex normals
/// for a normal that varies smoothly over it (a tile laid tangent to the surface follows the
/// shell the mesh approximates, not the kinks between its triangles).
#[derive(Debug, Clone)]
pub struct SurfaceIndex {
    pos: Vec<Vector3<f64>>,
    tris: Vec<[usize; 3]>,
    normals: Vec<Vector3<f64>>,
    /// Boundary edges (one triangle), smaller vertex first, sorted.
    boundary: Vec<[usize; 2]>,
    /// Per vertex: whether a boundary edge ends there.
    boundary_vertex: Vec<bool>,
    bvh: Bvh,
}

/// A point on a [`SurfaceIndex`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    /// The point.
    pub point: Vector3<f64>,
    /// The triangle it lies on.
    pub triangle: usize,
    /// Unit normal interpolated from the triangle's vertex normals.
    pub normal: Vector3<f64>,
    /// Unit normal of the triangle itself.
    pub face_normal: Vector3<f64>,
    /// Whether it lies on the surface's boundary (a boundary edge or vertex): the query
    /// point was beyond the surface's edge, not over it.
    pub on_boundary: bool,
}

impl SurfaceIndex {
    /// Indexes triangles over `pos` (counter-clockwise seen from the normals' side).
    pub fn new(pos: Vec<Vector3<f64>>, tris: Vec<[usize; 3]>) -> Self {
        let mut acc = vec![Vector3::zeros(); pos.len()];
        for t in &tris {
            let w = (pos[t[1]] - pos[t[0]]).cross(&(pos[t[2]] - pos[t[0]]));
            for &v in t {
                acc[v] += w;
            }
        }
        let normals = acc
            .into_iter()
            .map(|a| a.try_normalize(1e-300).unwrap_or_else(Vector3::z))
            .collect();
        let bvh = Bvh::of_simplices(&pos, &tris);
        let mut edges: Vec<[usize; 2]> = tris
            .iter()
            .flat_map(|t| (0..3).map(move |k| [t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3])]))
            .collect();
        edges.sort_unstable();
        let mut boundary = Vec::new();
        let mut i = 0;
        while i < edges.len() {
            let mut j = i + 1;
            while j < edges.len() && edges[j] == edges[i] {
                j += 1;
            }
            if j - i == 1 {
                boundary.push(edges[i]);
            }
            i = j;
        }
        let mut boundary_vertex = vec![false; pos.len()];
        for e in &boundary {
            boundary_vertex[e[0]] = true;
            boundary_vertex[e[1]] = true;
        }
        Self {
            pos,
            tris,
            normals,
            boundary,
            boundary_vertex,
            bvh,
        }
    }

    /// Indexes a polygon mesh, its faces fan-triangulated in face order
    /// ([`SurfaceIndex::polymesh_faces`] maps the triangles back to the faces).
    pub fn from_polymesh(mesh: &PolyMesh) -> Self {
        let pos = mesh.positions().iter().map(|p| p.coords).collect();
        let tris = fan(mesh).map(|(_, t)| t).collect();
        Self::new(pos, tris)
    }

    /// The face of `mesh` each triangle of [`SurfaceIndex::from_polymesh`]`(mesh)` lies on:
    /// [`SurfacePoint::triangle`] of a closest point on it is an index into this.
    pub fn polymesh_faces(mesh: &PolyMesh) -> Vec<usize> {
        fan(mesh).map(|(f, _)| f).collect()
    }

    /// The point of the surface closest to `p` (ties go to the lower triangle), `None` for a
    /// surface with no triangles.
    pub fn closest(&self, p: &Vector3<f64>) -> Option<SurfacePoint> {
        let (i, _, point) = self.bvh.nearest(p, |i| {
            let [a, b, c] = self.tris[i];
            let q = closest::on_triangle(p, &self.pos[a], &self.pos[b], &self.pos[c]);
            ((q - p).norm_squared(), q)
        })?;
        let [a, b, c] = self.tris[i];
        let w = closest::triangle_weights(&point, &self.pos[a], &self.pos[b], &self.pos[c]);
        let face_normal = (self.pos[b] - self.pos[a])
            .cross(&(self.pos[c] - self.pos[a]))
            .try_normalize(1e-300)
            .unwrap_or_else(Vector3::z);
        let smooth = self.normals[a] * w[0] + self.normals[b] * w[1] + self.normals[c] * w[2];
        let normal = smooth.try_normalize(1e-12).unwrap_or(face_normal);
        // On an edge (one weight zero) or at a corner (two zero) of the triangle: is that
        // edge, or an edge at that corner, on the boundary?
        let corners = [a, b, c];
        let used: Vec<usize> = (0..3)
            .filter(|&k| w[k] > 1e-12)
            .map(|k| corners[k])
            .collect();
        let is_boundary =
            |x: usize, y: usize| self.boundary.binary_search(&[x.min(y), x.max(y)]).is_ok();
        let on_boundary = match used[..] {
            [x, y] => is_boundary(x, y),
            [x] => self.boundary_vertex[x],
            _ => false,
        };
        Some(SurfacePoint {
            point,
            triangle: i,
            normal,
            face_normal,
            on_boundary,
        })
    }
}

/// The fan triangles of `mesh`'s faces, in face order, each with its face: the one
/// triangulation of polygon faces that every index over a [`PolyMesh`] uses, so that a
/// triangle index means the same everywhere.
pub fn fan(mesh: &PolyMesh) -> impl Iterator<Item = (usize, [usize; 3])> + '_ {
    mesh.faces()
        .iter()
        .enumerate()
        .flat_map(|(i, f)| (1..f.len() - 1).map(move |k| (i, [f[0], f[k], f[k + 1]])))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A hemisphere of radius 1 as a latitude-longitude triangle mesh, normals outward.
    fn hemisphere(rings: usize, sectors: usize) -> SurfaceIndex {
        let mut pos = vec![Vector3::z()];
        for i in 1..=rings {
            let polar = std::f64::consts::FRAC_PI_2 * i as f64 / rings as f64;
            for j in 0..sectors {
                let az = std::f64::consts::TAU * j as f64 / sectors as f64;
                pos.push(Vector3::new(
                    polar.sin() * az.cos(),
                    polar.sin() * az.sin(),
                    polar.cos(),
                ));
            }
        }
        let at = |i: usize, j: usize| 1 + (i - 1) * sectors + j % sectors;
        let mut tris = Vec::new();
        for j in 0..sectors {
            tris.push([0, at(1, j), at(1, j + 1)]);
        }
        for i in 1..rings {
            for j in 0..sectors {
                tris.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                tris.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        SurfaceIndex::new(pos, tris)
    }

    #[test]
    fn closest_point_agrees_with_a_scan_and_normals_follow_the_sphere() {
        let surface = hemisphere(24, 48);
        for k in 0..50 {
            let a = k as f64 * 0.37;
            let p = Vector3::new(a.cos() * 0.6, a.sin() * 0.5, 0.3 + 0.01 * k as f64) * 1.3;
            let found = surface.closest(&p).unwrap();
            let scan = surface
                .tris
                .iter()
                .map(|t| {
                    closest::on_triangle(
                        &p,
                        &surface.pos[t[0]],
                        &surface.pos[t[1]],
                        &surface.pos[t[2]],
                    )
                })
                .map(|q| (q - p).norm())
                .fold(f64::INFINITY, f64::min);
            assert!(((found.point - p).norm() - scan).abs() < 1e-12);
            // The smooth normal is close to the sphere's radial direction.
            assert!(found.normal.dot(&found.point.normalize()) > 0.999);
            assert!(found.face_normal.dot(&found.point.normalize()) > 0.99);
            assert!(!found.on_boundary);
        }
        // Beyond the rim (z < 0 below the equator, outside): the closest point is on it.
        let rim = surface.closest(&Vector3::new(1.5, 0.1, -0.3)).unwrap();
        assert!(rim.on_boundary && rim.point.z.abs() < 1e-12);
    }

    #[test]
    fn empty_surface_has_no_closest_point() {
        assert!(
            SurfaceIndex::new(Vec::new(), Vec::new())
                .closest(&Vector3::zeros())
                .is_none()
        );
    }

    #[test]
    fn polymesh_faces_name_the_face_of_each_fan_triangle() {
        // A triangle, a quad and a pentagon: 1 + 2 + 3 triangles.
        let p = |x: f64, y: f64| nalgebra::Point3::new(x, y, 0.0);
        let mesh = PolyMesh::new(
            vec![
                p(0.0, 0.0),
                p(1.0, 0.0),
                p(1.0, 1.0),
                p(0.0, 1.0),
                p(2.0, 0.0),
                p(2.0, 1.0),
                p(3.0, 0.5),
                p(0.5, -1.0),
            ],
            vec![vec![0, 7, 1], vec![0, 1, 2, 3], vec![1, 4, 6, 5, 2]],
        )
        .unwrap();
        assert_eq!(SurfaceIndex::polymesh_faces(&mesh), vec![0, 1, 1, 2, 2, 2]);
        let index = SurfaceIndex::from_polymesh(&mesh);
        let faces = SurfaceIndex::polymesh_faces(&mesh);
        for (q, face) in [
            ((0.5, -0.4), 0),
            ((0.3, 0.8), 1),
            ((2.6, 0.5), 2),
            ((1.9, 0.9), 2),
        ] {
            let found = index.closest(&Vector3::new(q.0, q.1, 0.2)).unwrap();
            assert_eq!(faces[found.triangle], face, "{q:?}");
        }
    }
}
