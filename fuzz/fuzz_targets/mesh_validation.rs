//! Arbitrary arrays as a polygon mesh: validated or refused, never a panic; an accepted mesh
//! keeps its invariants (its topology builds, every face has 3+ in-range vertices).
#![no_main]

use libfuzzer_sys::fuzz_target;
use nalgebra::Point3;
use tilepattern::mesh::{PolyMesh, Topology};

fuzz_target!(|data: &[u8]| {
    if data.len() < 2 {
        return;
    }
    // First byte: vertex count; then coordinates from bytes (with a few special values),
    // then faces as runs: a size byte followed by that many index bytes.
    let vertex_count = (data[0] % 24) as usize;
    let mut bytes = data[1..].iter().copied();
    let mut coordinate = || match bytes.next() {
        Some(255) => f64::NAN,
        Some(254) => f64::INFINITY,
        Some(b) => f64::from(b) / 16.0,
        None => 0.0,
    };
    let positions: Vec<Point3<f64>> = (0..vertex_count).map(|_| Point3::new(coordinate(), coordinate(), coordinate())).collect();
    let rest = &data[1 + (3 * vertex_count).min(data.len() - 1)..];
    let mut faces = Vec::new();
    let mut i = 0;
    while i < rest.len() && faces.len() < 64 {
        let size = (rest[i] % 7) as usize;
        let end = (i + 1 + size).min(rest.len());
        faces.push(rest[i + 1..end].iter().map(|&b| (b % 32) as usize).collect::<Vec<_>>());
        i = end;
    }
    if let Ok(mesh) = PolyMesh::new(positions, faces) {
        let topology = Topology::new(&mesh).expect("an accepted mesh has a topology");
        assert!(mesh.faces().iter().all(|f| f.len() >= 3 && f.iter().all(|&v| v < mesh.positions().len())));
        assert!(topology.edges().iter().all(|e| e.faces.len() <= 2));
    }
});
