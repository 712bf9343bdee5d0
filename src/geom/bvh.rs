//! A bounding volume hierarchy over axis-aligned boxes, for nearest-primitive queries that
//! stay fast on slivers (whose boxes would fill many cells of a grid).

use nalgebra::Vector3;

/// A bounding volume hierarchy over the boxes of primitives (triangles, segments, ...).
#[derive(Debug, Clone)]
pub struct Bvh {
    nodes: Vec<Node>,
    order: Vec<u32>,
}

#[derive(Debug, Clone)]
struct Node {
    lo: Vector3<f64>,
    hi: Vector3<f64>,
    /// Leaf: range in `order`; inner: `start` is the second child (the first follows).
    start: u32,
    count: u32,
}

/// Most primitives in a leaf.
const LEAF: usize = 4;

impl Bvh {
    /// Builds the hierarchy over `boxes` (lower, upper corner), splitting at the median of the
    /// widest spread of the boxes' centres; ties go by index, so the tree is deterministic.
    pub fn new(boxes: &[(Vector3<f64>, Vector3<f64>)]) -> Self {
        let mut order: Vec<u32> = (0..boxes.len() as u32).collect();
        let centres: Vec<Vector3<f64>> = boxes.iter().map(|(lo, hi)| (lo + hi) * 0.5).collect();
        let mut bvh = Self {
            nodes: Vec::with_capacity(2 * boxes.len() / LEAF + 1),
            order: Vec::new(),
        };
        if !boxes.is_empty() {
            bvh.build(boxes, &centres, &mut order, 0);
        }
        bvh.order = order;
        bvh
    }

    /// A hierarchy over simplices or polygons of the points `pos` (segments `[a, b]`,
    /// triangles `[a, b, c]`, a mesh's faces; each with at least one corner), each in the box
    /// of its corners.
    pub fn of_simplices<S: AsRef<[usize]>>(pos: &[Vector3<f64>], simplices: &[S]) -> Self {
        let boxes: Vec<_> = simplices
            .iter()
            .map(|s| {
                let s = s.as_ref();
                s[1..].iter().fold((pos[s[0]], pos[s[0]]), |(lo, hi), &v| {
                    (lo.inf(&pos[v]), hi.sup(&pos[v]))
                })
            })
            .collect();
        Self::new(&boxes)
    }

    /// Number of primitives.
    #[cfg(test)]
    pub fn len(&self) -> usize {
        self.order.len()
    }

    /// Whether it holds no primitive.
    #[cfg(test)]
    pub fn is_empty(&self) -> bool {
        self.order.is_empty()
    }

    fn build(
        &mut self,
        boxes: &[(Vector3<f64>, Vector3<f64>)],
        centres: &[Vector3<f64>],
        order: &mut [u32],
        offset: usize,
    ) -> usize {
        let mut lo = Vector3::repeat(f64::INFINITY);
        let mut hi = Vector3::repeat(f64::NEG_INFINITY);
        let mut clo = Vector3::repeat(f64::INFINITY);
        let mut chi = Vector3::repeat(f64::NEG_INFINITY);
        for &i in order.iter() {
            let (a, b) = &boxes[i as usize];
            lo = lo.inf(a);
            hi = hi.sup(b);
            clo = clo.inf(&centres[i as usize]);
            chi = chi.sup(&centres[i as usize]);
        }
        let id = self.nodes.len();
        self.nodes.push(Node {
            lo,
            hi,
            start: offset as u32,
            count: order.len() as u32,
        });
        if order.len() <= LEAF {
            return id;
        }
        let extent = chi - clo;
        let axis = if extent.x >= extent.y && extent.x >= extent.z {
            0
        } else if extent.y >= extent.z {
            1
        } else {
            2
        };
        let mid = order.len() / 2;
        order.select_nth_unstable_by(mid, |&a, &b| {
            centres[a as usize][axis]
                .total_cmp(&centres[b as usize][axis])
                .then(a.cmp(&b))
        });
        let (left, right) = order.split_at_mut(mid);
        self.build(boxes, centres, left, offset);
        let second = self.build(boxes, centres, right, offset + mid);
        self.nodes[id].start = second as u32;
        self.nodes[id].count = 0;
        id
    }

    /// Primitives whose boxes come within `radius` of `p` (a superset of those within
    /// `radius`), each once, in index order.
    pub fn within(&self, p: &Vector3<f64>, radius: f64) -> Vec<usize> {
        let mut found = Vec::new();
        if self.nodes.is_empty() {
            return found;
        }
        let r2 = radius * radius;
        let mut stack = vec![0usize];
        while let Some(id) = stack.pop() {
            let node = &self.nodes[id];
            if box_distance2(node, p) > r2 {
                continue;
            }
            if node.count > 0 {
                let start = node.start as usize;
                found.extend(
                    self.order[start..start + node.count as usize]
                        .iter()
                        .map(|&i| i as usize),
                );
            } else {
                stack.push(node.start as usize);
                stack.push(id + 1);
            }
        }
        found.sort_unstable();
        found
    }

    /// Nearest primitive to `p` by `dist2` (squared distance to primitive `i` and its closest
    /// point), as (primitive, squared distance, point); ties go to the smaller index.
    pub fn nearest(
        &self,
        p: &Vector3<f64>,
        dist2: impl Fn(usize) -> (f64, Vector3<f64>),
    ) -> Option<(usize, f64, Vector3<f64>)> {
        if self.nodes.is_empty() {
            return None;
        }
        let box_d2 = |n: &Node| box_distance2(n, p);
        let mut best: Option<(usize, f64, Vector3<f64>)> = None;
        let mut stack: Vec<(f64, usize)> = Vec::with_capacity(64);
        stack.push((box_d2(&self.nodes[0]), 0));
        while let Some((d2, id)) = stack.pop() {
            if best.is_some_and(|(_, bd, _)| d2 > bd) {
                continue;
            }
            let node = &self.nodes[id];
            if node.count > 0 {
                let start = node.start as usize;
                for &i in &self.order[start..start + node.count as usize] {
                    let i = i as usize;
                    let (d2, q) = dist2(i);
                    if best.is_none_or(|(bi, bd, _)| d2 < bd || (d2 == bd && i < bi)) {
                        best = Some((i, d2, q));
                    }
                }
            } else {
                let (a, b) = (id + 1, node.start as usize);
                let (da, db) = (box_d2(&self.nodes[a]), box_d2(&self.nodes[b]));
                // Nearer child on top of the stack.
                if da <= db {
                    stack.push((db, b));
                    stack.push((da, a));
                } else {
                    stack.push((da, a));
                    stack.push((db, b));
                }
            }
        }
        best
    }
}

/// Squared distance from `p` to the box of `node` (zero inside it).
fn box_distance2(node: &Node, p: &Vector3<f64>) -> f64 {
    (0..3)
        .map(|k| {
            let d = (node.lo[k] - p[k]).max(p[k] - node.hi[k]).max(0.0);
            d * d
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::numbers;

    #[test]
    fn nearest_point_agrees_with_a_scan() {
        let mut rnd = numbers(7);
        let points: Vec<Vector3<f64>> = (0..500)
            .map(|_| Vector3::new(rnd(), rnd(), rnd() * 0.1))
            .collect();
        let bvh = Bvh::new(&points.iter().map(|p| (*p, *p)).collect::<Vec<_>>());
        assert_eq!(bvh.len(), 500);
        for _ in 0..200 {
            let q = Vector3::new(rnd() * 1.4 - 0.2, rnd() * 1.4 - 0.2, rnd() - 0.5);
            let (i, d2, _) = bvh
                .nearest(&q, |i| ((points[i] - q).norm_squared(), points[i]))
                .unwrap();
            let scan = (0..points.len())
                .min_by(|&a, &b| {
                    (points[a] - q)
                        .norm_squared()
                        .total_cmp(&(points[b] - q).norm_squared())
                })
                .unwrap();
            assert_eq!(i, scan);
            assert!((d2 - (points[scan] - q).norm_squared()).abs() < 1e-15);
        }
    }

    #[test]
    fn boxes_within_a_radius_include_those_a_scan_finds() {
        let mut rnd = numbers(11);
        let boxes: Vec<(Vector3<f64>, Vector3<f64>)> = (0..400)
            .map(|_| {
                let lo = Vector3::new(rnd(), rnd(), rnd() * 0.1);
                (lo, lo + Vector3::new(rnd(), rnd(), rnd()) * 0.05)
            })
            .collect();
        let bvh = Bvh::new(&boxes);
        for _ in 0..100 {
            let q = Vector3::new(rnd() * 1.4 - 0.2, rnd() * 1.4 - 0.2, rnd() - 0.5);
            let r = rnd() * 0.3;
            let scan: Vec<usize> = (0..boxes.len())
                .filter(|&i| {
                    let (lo, hi) = &boxes[i];
                    let d = (lo - q).sup(&(q - hi)).sup(&Vector3::zeros());
                    d.norm_squared() <= r * r
                })
                .collect();
            let found = bvh.within(&q, r);
            assert!(found.windows(2).all(|w| w[0] < w[1]), "each once, in order");
            assert!(
                scan.iter().all(|i| found.binary_search(i).is_ok()),
                "none missed"
            );
            // A leaf's box decides: its other primitives may come along, far ones do not.
            let far = Vector3::new(10.0, 10.0, 10.0);
            assert!(bvh.within(&far, r).is_empty());
        }
    }

    #[test]
    fn empty_hierarchy_finds_nothing() {
        let bvh = Bvh::new(&[]);
        assert!(bvh.is_empty());
        assert!(bvh.nearest(&Vector3::zeros(), |_| unreachable!()).is_none());
        assert!(bvh.within(&Vector3::zeros(), 1.0).is_empty());
    }
}
