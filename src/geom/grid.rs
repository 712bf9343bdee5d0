//! A sparse grid of cubic cells: items are entered in every cell they may meet (a point in
//! its cell, a segment or a flat polygon in the cells of its bounding box that come near it),
//! and a query returns the items of the cells a box meets, each once, in index order.

use std::collections::HashMap;

use foldhash::fast::FixedState;

use nalgebra::{Point3, Vector3};

/// Items (by index) in a sparse grid of cells of one size. Cell keys are hashed with a
/// fixed seed (foldhash's fast hasher): the grid is asked for cells by the million in the
/// tile stage, and no result depends on the order of its cells (queries sort what they find).
#[derive(Debug, Clone)]
pub struct HashGrid {
    cell: f64,
    cells: HashMap<[i64; 3], Vec<u32>, FixedState>,
}

impl HashGrid {
    /// An empty grid of cells of side `cell` (a non-positive or non-finite side becomes 1).
    pub fn new(cell: f64) -> Self {
        Self {
            cell: if cell.is_finite() && cell > 0.0 {
                cell
            } else {
                1.0
            },
            cells: HashMap::default(),
        }
    }

    /// A grid with item `k` entered in the cells the `k`-th set of points may meet: one
    /// point's cell; for two, the cells of their bounding box the segment between them may
    /// pass through; for more (a face, flat or nearly), the cells of their bounding box that
    /// the slab around their mean plane, as thick as the points stray from it, crosses. A
    /// tilted face then takes the cells along it, not every cell of its box (a face of `n`
    /// cells across, `n^2` cells against `n^3`), and every cell holding a point of the
    /// segment or of the points' convex hull is among them.
    pub fn of_points<P: AsRef<[Point3<f64>]>>(
        cell: f64,
        items: impl IntoIterator<Item = P>,
    ) -> Self {
        let mut grid = Self::new(cell);
        for (k, points) in items.into_iter().enumerate() {
            grid.insert_near(k, points.as_ref());
        }
        grid
    }

    /// Enters `item` in the cells of `points`' bounding box that may meet their segment or
    /// slab (see [`HashGrid::of_points`]).
    fn insert_near(&mut self, item: usize, points: &[Point3<f64>]) {
        let Some(first) = points.first() else {
            return;
        };
        let (lo, hi) = points
            .iter()
            .fold((*first, *first), |(lo, hi), p| (lo.inf(p), hi.sup(p)));
        let (a, b) = (self.key(&lo), self.key(&hi));
        if a == b {
            self.insert(item, &lo, &hi);
            return;
        }
        let shape = Shape::of(points, self.cell / 2.0 + 1e-9 * self.cell);
        for x in a[0]..=b[0] {
            for y in a[1]..=b[1] {
                for z in a[2]..=b[2] {
                    let centre =
                        Point3::new(x as f64 + 0.5, y as f64 + 0.5, z as f64 + 0.5) * self.cell;
                    if shape.may_meet(&centre) {
                        self.cells.entry([x, y, z]).or_default().push(item as u32);
                    }
                }
            }
        }
    }

    /// Cells that hold at least one item.
    #[cfg(test)]
    pub fn occupied(&self) -> usize {
        self.cells.len()
    }

    fn key(&self, p: &Point3<f64>) -> [i64; 3] {
        [p.x, p.y, p.z].map(|c| (c / self.cell).floor() as i64)
    }

    /// Enters `item` in every cell the box `lo..hi` meets.
    pub fn insert(&mut self, item: usize, lo: &Point3<f64>, hi: &Point3<f64>) {
        let (a, b) = (self.key(lo), self.key(hi));
        for x in a[0]..=b[0] {
            for y in a[1]..=b[1] {
                for z in a[2]..=b[2] {
                    self.cells.entry([x, y, z]).or_default().push(item as u32);
                }
            }
        }
    }

    /// Items in the cells that the box of half-side `radius` around `p` meets (a superset of
    /// those within `radius`), each once, in index order.
    pub fn near(&self, p: &Point3<f64>, radius: f64) -> Vec<usize> {
        let r = nalgebra::Vector3::repeat(radius.max(0.0));
        self.in_box(&(p - r), &(p + r))
    }

    /// Items in the cells that the box `lo..hi` meets, each once, in index order.
    pub fn in_box(&self, lo: &Point3<f64>, hi: &Point3<f64>) -> Vec<usize> {
        let (a, b) = (self.key(lo), self.key(hi));
        let box_cells: f64 = (0..3).map(|k| (b[k] as f64 - a[k] as f64) + 1.0).product();
        let mut found: Vec<usize> = Vec::new();
        if box_cells > self.cells.len() as f64 {
            // A box of more cells than the grid holds: read the grid instead.
            let inside = |c: &[i64; 3]| (0..3).all(|k| (a[k]..=b[k]).contains(&c[k]));
            found.extend(
                self.cells
                    .iter()
                    .filter(|(c, _)| inside(c))
                    .flat_map(|(_, items)| items.iter().map(|&i| i as usize)),
            );
        } else {
            for x in a[0]..=b[0] {
                for y in a[1]..=b[1] {
                    for z in a[2]..=b[2] {
                        found.extend(
                            self.cells
                                .get(&[x, y, z])
                                .into_iter()
                                .flatten()
                                .map(|&i| i as usize),
                        );
                    }
                }
            }
        }
        found.sort_unstable();
        found.dedup();
        found
    }
}

/// The unit normal of a polygon by Newell's method (any vertex order, any shape), `None`
/// when it has no area.
fn newell_normal(points: &[Point3<f64>]) -> Option<Vector3<f64>> {
    let mut n = Vector3::zeros();
    for (i, p) in points.iter().enumerate() {
        let q = points[(i + 1) % points.len()];
        n += Vector3::new(
            (p.y - q.y) * (p.z + q.z),
            (p.z - q.z) * (p.x + q.x),
            (p.x - q.x) * (p.y + q.y),
        );
    }
    n.try_normalize(1e-300)
}

/// Where an item lies, to tell which cells of its bounding box it may meet: a cell of
/// half-side `h` whose centre is farther than `h sqrt 3` from a segment, or farther than
/// `h (|n_x| + |n_y| + |n_z|)` from a slab across the normal `n`, holds none of it (the slack
/// `h` is given with a hair added for rounding).
enum Shape {
    /// The segment from `from` along `along`, reaching `reach` around it.
    Segment {
        from: Point3<f64>,
        along: Vector3<f64>,
        reach: f64,
    },
    /// The slab of points `p` with `below <= n.(p - origin) <= above`, widened by `reach`.
    Slab {
        origin: Point3<f64>,
        normal: Vector3<f64>,
        below: f64,
        above: f64,
        reach: f64,
    },
    /// No shape to go by (collinear points): every cell of the box.
    Box,
}

impl Shape {
    /// The shape of two points (a segment) or more (a flat polygon's slab), for cells of
    /// half-side `half`.
    fn of(points: &[Point3<f64>], half: f64) -> Self {
        match points {
            [from, to] => Shape::Segment {
                from: *from,
                along: to - from,
                reach: half * 3f64.sqrt(),
            },
            [origin, ..] => match newell_normal(points) {
                Some(normal) => {
                    let (below, above) = points
                        .iter()
                        .map(|p| normal.dot(&(p - origin)))
                        .fold((0.0f64, 0.0f64), |(lo, hi), d| (lo.min(d), hi.max(d)));
                    Shape::Slab {
                        origin: *origin,
                        normal,
                        below,
                        above,
                        reach: half * normal.abs().sum(),
                    }
                }
                None => Shape::Box,
            },
            [] => Shape::Box,
        }
    }

    /// Whether the cell centred on `centre` may meet the shape.
    fn may_meet(&self, centre: &Point3<f64>) -> bool {
        match self {
            Shape::Segment { from, along, reach } => {
                let length2 = along.norm_squared();
                let t = if length2 > 0.0 {
                    ((centre - from).dot(along) / length2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                (centre - (from + along * t)).norm() <= *reach
            }
            Shape::Slab {
                origin,
                normal,
                below,
                above,
                reach,
            } => {
                let s = normal.dot(&(centre - origin));
                s + reach >= *below && s - reach <= *above
            }
            Shape::Box => true,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_what_a_scan_finds() {
        let points: Vec<Point3<f64>> = (0..400)
            .map(|i| {
                Point3::new(
                    (i % 20) as f64 * 0.37,
                    (i / 20) as f64 * 0.41,
                    (i % 7) as f64 * 0.1,
                )
            })
            .collect();
        let grid = HashGrid::of_points(0.5, points.iter().map(|p| [*p]));
        for (q, r) in [
            (Point3::new(1.0, 1.0, 0.0), 0.6),
            (Point3::new(-3.0, 2.0, 0.3), 4.0),
            (Point3::new(5.0, 5.0, 0.2), 0.01),
        ] {
            let found = grid.near(&q, r);
            assert!(
                found.windows(2).all(|w| w[0] < w[1]),
                "sorted and each once"
            );
            for (i, p) in points.iter().enumerate() {
                if (p - q).amax() <= r {
                    assert!(found.contains(&i), "point {i} within the box is found");
                }
            }
        }
    }

    #[test]
    fn a_box_larger_than_the_grid_reads_the_grid() {
        let grid = HashGrid::of_points(
            1.0,
            [[Point3::new(0.5, 0.5, 0.5)], [Point3::new(1e6, 0.0, 0.0)]],
        );
        assert_eq!(grid.near(&Point3::origin(), 1e9), vec![0, 1]);
        assert_eq!(grid.near(&Point3::origin(), 2.0), vec![0]);
    }

    #[test]
    fn items_spanning_cells_are_entered_in_each() {
        let grid = HashGrid::of_points(
            1.0,
            [[Point3::new(0.1, 0.1, 0.0), Point3::new(3.9, 0.2, 0.0)]],
        );
        assert_eq!(grid.occupied(), 4);
        assert_eq!(grid.near(&Point3::new(3.5, 0.0, 0.0), 0.1), vec![0]);
    }

    /// Every cell holding a point sampled on the item is entered, and no more than a band
    /// along it: for a segment and a triangle, both tilted across every axis.
    #[test]
    fn segments_and_faces_take_the_cells_along_them() {
        let cell = 0.25;
        let segment = [Point3::new(0.1, 0.2, 0.3), Point3::new(7.9, 6.1, 5.3)];
        let triangle = [
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(8.0, 1.0, 6.0),
            Point3::new(1.0, 7.0, 5.0),
        ];
        let grid = HashGrid::of_points(cell, [&segment[..], &triangle[..]]);
        let key = |p: &Point3<f64>| grid.key(p);
        let entered =
            |k: [i64; 3], item: u32| grid.cells.get(&k).is_some_and(|v| v.contains(&item));
        for i in 0..=200 {
            let t = i as f64 / 200.0;
            let p = segment[0] + (segment[1] - segment[0]) * t;
            assert!(entered(key(&p), 0), "segment point {p} missed");
            for j in 0..=(200 - i) {
                let u = j as f64 / 200.0;
                let q =
                    triangle[0] + (triangle[1] - triangle[0]) * t + (triangle[2] - triangle[0]) * u;
                assert!(entered(key(&q), 1), "face point {q} missed");
            }
        }
        let count = |item: u32| grid.cells.values().filter(|v| v.contains(&item)).count();
        // The boxes hold 32 x 24 x 21 and 32 x 28 x 24 cells.
        assert!(count(0) < 32 * 6, "{} cells for the segment", count(0));
        assert!(count(1) < 32 * 28 * 6, "{} cells for the face", count(1));
    }
}
