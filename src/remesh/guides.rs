//! Guide curves: polylines the courses should follow (as Rhino's QuadRemesh offers them), for
//! a ridge, a valley, an opening's axis or a line the designer wants the joints to trace.
//!
//! This file only checks the polylines and turns them into weighted samples per vertex of the
//! working surface: a vertex near a curve gets the tangent of the curve's closest segment,
//! weighted by how near it is. The 4-RoSy encoding and the smoothing are the field solve's
//! ([`super::field`]), the same as for the designer's field ([`super::UserField`]); the
//! closest points are the shared ones of [`crate::geom`].

use nalgebra::Vector3;

use super::RemeshError;
use super::surface::{Locator, Surface};
use super::user_field::Samples;
use crate::geom::{Bvh, closest};
use crate::mesh::PolyMesh;

/// How far a guide curve reaches, in target edges: a surface vertex this close to a curve is
/// pulled towards its tangent, fully on the curve and not at all at this distance (or at the
/// longest edge at the vertex, where the input is coarser than that).
pub(crate) const REACH: f64 = 2.0;

/// Polylines the quad rows should follow, in model units; each curve lies on or near the
/// surface (parts farther than 2 target edges from it are ignored). Only the
/// direction of a curve counts, modulo 90 degrees: quad edges run along it or across it.
#[derive(Debug, Clone, PartialEq)]
pub struct GuideCurves {
    /// The polylines, each at least 2 points.
    pub curves: Vec<Vec<[f64; 3]>>,
    /// Share of the guides, on a curve, against every other source (curvature, direction,
    /// the designer's field), in `[0, 1]`: 1 (default) follows the curve alone there, 0
    /// ignores it. The share falls off to 0 at 2 target edges from the curve;
    /// the smoothing carries the direction on beyond.
    pub weight: f64,
}

impl GuideCurves {
    /// Guide curves followed fully near them (weight 1).
    pub fn new(curves: Vec<Vec<[f64; 3]>>) -> Self {
        Self {
            curves,
            weight: 1.0,
        }
    }

    /// Whether they pull at all: some curve and a positive weight.
    pub fn active(&self) -> bool {
        !self.curves.is_empty() && self.weight > 0.0
    }

    /// Checks the polylines on their own: at least 2 points each, every coordinate finite,
    /// some length; the weight in `[0, 1]`.
    ///
    /// # Errors
    /// [`RemeshError::GuideTooShort`], [`RemeshError::BadGuidePoint`],
    /// [`RemeshError::GuideZeroLength`] (the first curve at fault) or
    /// [`RemeshError::BadGuideWeight`].
    pub fn check(&self) -> Result<(), RemeshError> {
        for (curve, points) in self.curves.iter().enumerate() {
            if points.len() < 2 {
                return Err(RemeshError::GuideTooShort {
                    curve,
                    points: points.len(),
                });
            }
            if let Some((point, &value)) = points
                .iter()
                .enumerate()
                .find(|(_, p)| !p.iter().all(|c| c.is_finite()))
            {
                return Err(RemeshError::BadGuidePoint {
                    curve,
                    point,
                    value,
                });
            }
            let length: f64 = points
                .windows(2)
                .map(|w| (Vector3::from(w[1]) - Vector3::from(w[0])).norm())
                .sum();
            if !(length.is_finite() && length > 0.0) {
                return Err(RemeshError::GuideZeroLength { curve });
            }
        }
        if !(self.weight.is_finite() && (0.0..=1.0).contains(&self.weight)) {
            return Err(RemeshError::BadGuideWeight(self.weight));
        }
        Ok(())
    }

    /// The curves partly off `surface` for quads of edge `target_edge`: each with the share
    /// of its length farther than 2 target edges from the surface (those parts pull nothing),
    /// for a warning when it is large (a curve drawn in plan over a vault, or running past the
    /// shell's edge). Curves wholly off the surface are refused by the remesh
    /// ([`RemeshError::GuideOffSurface`]); they are listed here with share 1.
    pub fn off_surface(&self, surface: &PolyMesh, target_edge: f64) -> Vec<(usize, f64)> {
        let locator = Locator::from_polymesh(surface);
        self.curves
            .iter()
            .enumerate()
            .filter_map(|(curve, polyline)| {
                let points: Vec<Vector3<f64>> =
                    polyline.iter().map(|p| Vector3::from(*p)).collect();
                let share = lie(&points, &locator, target_edge).off_share;
                (share > 0.0).then_some((curve, share))
            })
            .collect()
    }

    /// The curves as weighted samples on the working surface `s` (quads of edge `t`), after
    /// checking that each curve comes within reach of the surface (`locator` on `s`): per
    /// vertex, the unit tangent of the closest segment of any curve, weighted from 1 on the
    /// curve down to 0 at the reach.
    ///
    /// # Errors
    /// [`RemeshError::GuideOffSurface`] for the first curve no part of which is within
    /// 2 target edges of the surface.
    pub(crate) fn samples(
        &self,
        s: &Surface,
        locator: &Locator,
        t: f64,
    ) -> Result<Samples, RemeshError> {
        let reach = REACH * t;
        let mut points: Vec<Vector3<f64>> = Vec::new();
        let mut segments: Vec<[usize; 2]> = Vec::new();
        for (curve, polyline) in self.curves.iter().enumerate() {
            let first = points.len();
            points.extend(polyline.iter().map(|p| Vector3::from(*p)));
            let nearest = lie(&points[first..], locator, t).nearest;
            if nearest > reach {
                return Err(RemeshError::GuideOffSurface {
                    curve,
                    distance: nearest,
                    reach,
                });
            }
            segments.extend(
                (first..points.len() - 1)
                    .filter(|&i| points[i + 1] != points[i])
                    .map(|i| [i, i + 1]),
            );
        }
        let bvh = Bvh::of_simplices(&points, &segments);
        let mut out = vec![Vec::new(); s.len()];
        for (v, samples) in out.iter_mut().enumerate() {
            let p = s.pos[v];
            // On an input coarser than the quads a curve may cross a triangle far from its
            // corners: the corners still hear it.
            let longest = s.adj[v]
                .iter()
                .map(|&(w, _)| s.edge_vec(v, w).norm())
                .fold(0.0, f64::max);
            let r = reach.max(longest);
            let Some((i, d2, _)) = bvh.nearest(&p, |i| {
                let [a, b] = segments[i];
                let q = closest::on_segment(&p, &points[a], &points[b]);
                ((q - p).norm_squared(), q)
            }) else {
                continue;
            };
            let d = d2.sqrt();
            if d < r {
                let [a, b] = segments[i];
                let fall = 1.0 - (d / r) * (d / r);
                samples.push(((points[b] - points[a]).normalize(), fall * fall));
            }
        }
        Ok(out)
    }
}

/// How a polyline lies against a surface: its least distance to it, and the share of its
/// length farther than the reach from it.
struct Lie {
    nearest: f64,
    off_share: f64,
}

/// How the polyline `points` lies against the surface of `locator` for quads of edge `t`,
/// probed at its points and along its segments at most half a target edge apart (at most
/// about 100 000 probes a curve, so a stray long curve cannot stall the remesh).
fn lie(points: &[Vector3<f64>], locator: &Locator, t: f64) -> Lie {
    let reach = REACH * t;
    let length: f64 = points.windows(2).map(|w| (w[1] - w[0]).norm()).sum();
    let step = (0.5 * t).max(length / 100_000.0);
    // Each point is probed once: a segment starts where the last one's probes ended.
    let mut last = points
        .first()
        .map_or(f64::INFINITY, |p| locator.distance(p));
    let mut nearest = last;
    let mut off = 0.0;
    for w in points.windows(2) {
        let d = w[1] - w[0];
        let pieces = (d.norm() / step).ceil().max(1.0) as usize;
        for k in 1..=pieces {
            let here = locator.distance(&(w[0] + d * (k as f64 / pieces as f64)));
            nearest = nearest.min(here);
            // A piece counts as off when both its ends are.
            if last > reach && here > reach {
                off += d.norm() / pieces as f64;
            }
            last = here;
        }
    }
    Lie {
        nearest,
        off_share: if length > 0.0 { off / length } else { 0.0 },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::remesh::surface::samples::sheet;

    #[test]
    fn bad_polylines_name_the_curve_and_point() {
        let good = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]];
        let err = GuideCurves::new(vec![good.clone(), vec![[0.0, 0.0, 0.0]]])
            .check()
            .unwrap_err();
        assert_eq!(
            err,
            RemeshError::GuideTooShort {
                curve: 1,
                points: 1
            }
        );
        assert!(err.to_string().contains("guide curve 1"), "{err}");
        let err = GuideCurves::new(vec![vec![[0.0, 0.0, 0.0], [1.0, f64::NAN, 0.0]]])
            .check()
            .unwrap_err();
        assert!(
            matches!(
                err,
                RemeshError::BadGuidePoint {
                    curve: 0,
                    point: 1,
                    ..
                }
            ),
            "{err}"
        );
        assert!(err.to_string().contains("point 1"), "{err}");
        let err = GuideCurves::new(vec![good.clone(), vec![[1.0, 2.0, 3.0]; 3]])
            .check()
            .unwrap_err();
        assert_eq!(err, RemeshError::GuideZeroLength { curve: 1 });
        // Coordinates whose differences overflow give no finite length either.
        let err = GuideCurves::new(vec![vec![[-1e308, 0.0, 0.0], [1e308, 0.0, 0.0]]])
            .check()
            .unwrap_err();
        assert_eq!(err, RemeshError::GuideZeroLength { curve: 0 });
        for w in [-0.5, 2.0, f64::INFINITY] {
            let guides = GuideCurves {
                weight: w,
                ..GuideCurves::new(vec![good.clone()])
            };
            assert!(matches!(
                guides.check(),
                Err(RemeshError::BadGuideWeight(_))
            ));
        }
        assert!(GuideCurves::new(vec![good]).check().is_ok());
        assert!(!GuideCurves::new(Vec::new()).active());
    }

    #[test]
    fn vertices_near_a_curve_get_its_tangent_falling_off_with_distance() {
        // A flat 2 x 2 sheet at spacing 0.1; a guide along the diagonal, with a repeated
        // point (a zero-length segment, skipped).
        let s = sheet(20, 0.1, (0..0, 0..0), |_, _| 0.0);
        let locator = Locator::new(&s);
        let guides = GuideCurves::new(vec![vec![
            [0.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
            [2.0, 2.0, 0.0],
        ]]);
        let t = 0.1;
        let samples = guides.samples(&s, &locator, t).unwrap();
        let diagonal = Vector3::new(1.0, 1.0, 0.0).normalize();
        let mut near = 0;
        for (v, list) in samples.iter().enumerate() {
            let p = s.pos[v];
            let d = (p.x - p.y).abs() / 2f64.sqrt();
            if d >= REACH * t - 1e-9 {
                assert!(list.is_empty(), "vertex {v} at {d:.3} has {list:?}");
                continue;
            }
            near += 1;
            let [(dir, w)] = list[..] else {
                panic!("vertex {v} at {d:.3}: {list:?}")
            };
            assert!((dir - diagonal).norm() < 1e-12);
            let r = d / (REACH * t);
            assert!((w - (1.0 - r * r).powi(2)).abs() < 1e-12);
        }
        assert_eq!(
            near,
            21 + 2 * (20 + 19),
            "the diagonal and two rows beside it"
        );
        // A curve 1 m above the sheet is nowhere near it.
        let off = GuideCurves::new(vec![
            vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]],
            vec![[0.0, 0.0, 1.0], [2.0, 2.0, 1.0]],
        ]);
        let err = off.samples(&s, &locator, t).unwrap_err();
        // Half of a curve running past the sheet's edge is off it.
        let mesh = PolyMesh::new(
            s.pos.iter().map(|p| nalgebra::Point3::from(*p)).collect(),
            s.tris.iter().map(|t| t.to_vec()).collect(),
        )
        .unwrap();
        let past = GuideCurves::new(vec![
            vec![[1.0, 1.0, 0.0], [1.0, 1.5, 0.0]],
            vec![[1.0, 1.2, 0.0], [1.0, 2.2, 0.0], [1.0, 3.2, 0.0]],
        ]);
        let off_share = past.off_surface(&mesh, t);
        assert_eq!(off_share.len(), 1, "{off_share:?}");
        assert_eq!(off_share[0].0, 1);
        assert!((off_share[0].1 - 0.5).abs() < 0.03, "{off_share:?}");
        assert!(
            matches!(err, RemeshError::GuideOffSurface { curve: 1, distance, .. } if (distance - 1.0).abs() < 1e-9),
            "{err}"
        );
    }
}
