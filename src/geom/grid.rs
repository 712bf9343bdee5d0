//! A sparse grid of cubic cells: items are entered in every cell their bounding box meets,
//! and a query returns the items of the cells a box meets, each once, in index order.

use std::collections::HashMap;

use nalgebra::Point3;

/// Items (by index) in a sparse grid of cells of one size.
#[derive(Debug, Clone)]
pub struct HashGrid {
    cell: f64,
    cells: HashMap<[i64; 3], Vec<u32>>,
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
            cells: HashMap::new(),
        }
    }

    /// A grid with item `k` entered over the bounding box of the `k`-th set of points.
    pub fn of_points<P: AsRef<[Point3<f64>]>>(
        cell: f64,
        items: impl IntoIterator<Item = P>,
    ) -> Self {
        let mut grid = Self::new(cell);
        for (k, points) in items.into_iter().enumerate() {
            let points = points.as_ref();
            let Some(first) = points.first() else {
                continue;
            };
            let (lo, hi) = points
                .iter()
                .fold((*first, *first), |(lo, hi), p| (lo.inf(p), hi.sup(p)));
            grid.insert(k, &lo, &hi);
        }
        grid
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
}
