//! The quad mesh in progress as a list of faces (vertex indices, counter-clockwise): its
//! edges and their faces, its boundary loops, compaction, and the shape of a quad.

use std::collections::BTreeMap;

use nalgebra::Vector3;

/// Undirected edge key.
pub(super) fn key(a: usize, b: usize) -> (usize, usize) {
    (a.min(b), a.max(b))
}

/// Undirected edge -> faces containing it, in face order.
pub(super) fn edge_faces(faces: &[Vec<usize>]) -> BTreeMap<(usize, usize), Vec<usize>> {
    let mut map: BTreeMap<(usize, usize), Vec<usize>> = BTreeMap::new();
    for (fi, f) in faces.iter().enumerate() {
        for i in 0..f.len() {
            map.entry(key(f[i], f[(i + 1) % f.len()])).or_default().push(fi);
        }
    }
    map
}

/// Boundary loops of the face set, each as the sequence of vertices along boundary
/// half-edges (faces on the left).
pub(super) fn boundary_loops(faces: &[Vec<usize>]) -> Vec<Vec<usize>> {
    let mut directed: BTreeMap<(usize, usize), usize> = BTreeMap::new();
    for f in faces {
        for i in 0..f.len() {
            *directed.entry((f[i], f[(i + 1) % f.len()])).or_default() += 1;
        }
    }
    let mut out: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for &(a, b) in directed.keys() {
        if !directed.contains_key(&(b, a)) {
            out.entry(a).or_default().push(b);
        }
    }
    let mut loops = Vec::new();
    let starts: Vec<usize> = out.keys().copied().collect();
    for s in starts {
        while out.get(&s).is_some_and(|l| !l.is_empty()) {
            let mut walk = vec![s];
            let mut cur = s;
            while let Some(next) = out.get_mut(&cur).and_then(|list| list.pop()) {
                if next == s {
                    break;
                }
                walk.push(next);
                cur = next;
                if walk.len() > faces.len() * 4 + 8 {
                    break;
                }
            }
            // Split figure-eights at repeated vertices into simple loops.
            let mut stack: Vec<usize> = Vec::new();
            for v in walk {
                if let Some(p) = stack.iter().position(|&w| w == v) {
                    let sub: Vec<usize> = stack.drain(p..).collect();
                    if sub.len() >= 3 {
                        loops.push(sub);
                    }
                }
                stack.push(v);
            }
            if stack.len() >= 3 {
                loops.push(stack);
            }
        }
    }
    loops
}

/// Drops unused vertices, keeping order.
pub(super) fn compact(pos: Vec<Vector3<f64>>, faces: Vec<Vec<usize>>) -> (Vec<Vector3<f64>>, Vec<Vec<usize>>) {
    let mut remap = vec![usize::MAX; pos.len()];
    let mut out = Vec::new();
    let faces = faces
        .into_iter()
        .map(|f| {
            f.into_iter()
                .map(|v| {
                    if remap[v] == usize::MAX {
                        remap[v] = out.len();
                        out.push(pos[v]);
                    }
                    remap[v]
                })
                .collect()
        })
        .collect();
    (out, faces)
}

/// Quality of a quad: summed corner deviation from 90 degrees (radians), plus a penalty for
/// reflex corners with respect to the quad's own normal.
pub(super) fn quad_cost(pos: &[Vector3<f64>], q: [usize; 4]) -> f64 {
    let p: Vec<Vector3<f64>> = q.iter().map(|&v| pos[v]).collect();
    let normal = (p[2] - p[0]).cross(&(p[3] - p[1]));
    let mut cost = 0.0;
    for i in 0..4 {
        let a = p[(i + 3) % 4] - p[i];
        let b = p[(i + 1) % 4] - p[i];
        let angle = a.angle(&b);
        cost += (angle - std::f64::consts::FRAC_PI_2).abs();
        if b.cross(&a).dot(&normal) < 0.0 {
            cost += std::f64::consts::PI;
        }
    }
    cost
}
