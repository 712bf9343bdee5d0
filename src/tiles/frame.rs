//! Tile frames: origin, length axis, and thickness axis from a least-squares plane.

use nalgebra::{Matrix3, Point3, SymmetricEigen, Vector3};
use serde::{Serialize, Serializer};

use crate::mesh::PolyMesh;

/// An orthonormal right-handed frame: `x` length, `y` height (width), `z` thickness.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// Origin of the tile.
    pub origin: Point3<f64>,
    /// Length axis.
    pub x: Vector3<f64>,
    /// Height (width) axis, `z × x`.
    pub y: Vector3<f64>,
    /// Thickness axis: the best-fit plane's normal, on the side the face normals point to.
    pub z: Vector3<f64>,
}

impl Serialize for Frame {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let v = |a: &Vector3<f64>| [a.x, a.y, a.z];
        let o = [self.origin.x, self.origin.y, self.origin.z];
        serde::Serialize::serialize(
            &serde_json::json!({ "origin": o, "x": v(&self.x), "y": v(&self.y), "z": v(&self.z) }),
            serializer,
        )
    }
}

impl Frame {
    /// The paper's frame for the tile over faces `a` and `b` (section 3.5).
    pub fn for_pair(mesh: &PolyMesh, a: usize, b: usize) -> Self {
        let (ca, cb) = (mesh.face_centroid(a), mesh.face_centroid(b));
        let mut points: Vec<Point3<f64>> = mesh.face_points(a).collect();
        let shared: Vec<usize> = mesh.faces()[a].clone();
        points.extend(
            mesh.faces()[b]
                .iter()
                .filter(|v| !shared.contains(v))
                .map(|&v| mesh.positions()[v]),
        );
        let up = mesh.face_area_vector(a) + mesh.face_area_vector(b);
        Self::from_axes(nalgebra::center(&ca, &cb), cb - ca, &points, up)
    }

    /// The frame of a half tile on face `f`: origin at its centroid, length along the mean of
    /// its edges 0-1 and 3-2.
    pub fn for_face(mesh: &PolyMesh, f: usize) -> Self {
        let p: Vec<Point3<f64>> = mesh.face_points(f).collect();
        Self::for_corners(&[p[0], p[1], p[2], p[3]], mesh.face_area_vector(f))
    }

    /// The frame of a half tile on the quad `p` (counter-clockwise seen from `up`): origin at
    /// its centroid, length along the mean of its edges 0-1 and 3-2.
    pub fn for_corners(p: &[Point3<f64>; 4], up: Vector3<f64>) -> Self {
        let centroid = Point3::from(p.iter().map(|c| c.coords).sum::<Vector3<f64>>() / 4.0);
        Self::from_axes(centroid, (p[1] - p[0]) + (p[2] - p[3]), p, up)
    }

    /// Frame with `z` the least-squares normal of `points` turned towards `up`, and `x` the
    /// direction `along` projected into that plane.
    fn from_axes(
        origin: Point3<f64>,
        along: Vector3<f64>,
        points: &[Point3<f64>],
        up: Vector3<f64>,
    ) -> Self {
        let mut z = best_fit_normal(points);
        if z.dot(&up) < 0.0 {
            z = -z;
        }
        Self::from_normal(origin, z, &along)
    }

    /// Frame at `origin` with unit normal `z` and `x` the direction `along` laid into the
    /// plane normal to `z`. Where `along` gives no direction in that plane (zero, or along
    /// `z`: a degenerate face), any axis in the plane will do.
    pub(crate) fn from_normal(origin: Point3<f64>, z: Vector3<f64>, along: &Vector3<f64>) -> Self {
        let x = (along - z * along.dot(&z))
            .try_normalize(along.norm() * 1e-12)
            .unwrap_or_else(|| {
                let other = if z.x.abs() < 0.9 {
                    Vector3::x()
                } else {
                    Vector3::y()
                };
                (other - z * other.dot(&z)).normalize()
            });
        let y = z.cross(&x);
        Self { origin, x, y, z }
    }

    /// Position of a world point in this frame's coordinates.
    pub fn to_local(&self, p: &Point3<f64>) -> Vector3<f64> {
        let d = p - self.origin;
        Vector3::new(d.dot(&self.x), d.dot(&self.y), d.dot(&self.z))
    }
}

/// Unit normal of the least-squares plane through `points`: the eigenvector of their
/// covariance with the smallest eigenvalue.
fn best_fit_normal(points: &[Point3<f64>]) -> Vector3<f64> {
    let mean = points
        .iter()
        .fold(Vector3::zeros(), |acc, p| acc + p.coords)
        / points.len() as f64;
    let covariance = points.iter().fold(Matrix3::zeros(), |acc, p| {
        let d = p.coords - mean;
        acc + d * d.transpose()
    });
    let eigen = SymmetricEigen::new(covariance);
    let smallest = eigen.eigenvalues.imin();
    eigen.eigenvectors.column(smallest).normalize()
}
