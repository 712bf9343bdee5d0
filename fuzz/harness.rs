// The bodies of the fuzz targets, shared by `fuzz/fuzz_targets/*.rs` (cargo fuzz) and
// `tests/fuzz_regressions.rs` (which replays every file under `fuzz/regressions/<target>/`
// on every `cargo test`, through `include!`, hence no inner doc comment here). Each takes
// arbitrary bytes and panics only on a bug.

use std::ffi::c_char;
use std::ptr;

use nalgebra::Point3;
use tilepattern::ffi::*;
use tilepattern::mesh::{MAX_COORDINATE, PolyMesh, Topology, io, obj};
use tilepattern::pattern::{Bond, DualGraph, score};

/// Arbitrary bytes as an OBJ file: parsed and validated, or refused with an error; never a
/// panic. A parsed mesh writes back to OBJ and parses again to the same mesh. The same bytes
/// as a file of every format the command line reads (STL, PLY, OFF, by extension and by
/// content), welded: a mesh or an error, never a panic.
pub fn obj_reader(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    if let Ok(mesh) = obj::parse(&text) {
        let again = obj::parse(&obj::to_string(&mesh)).expect("a written mesh parses");
        assert_eq!(again, mesh, "OBJ round trip");
    }
    for extension in [Some("obj"), Some("stl"), Some("ply"), Some("off"), None] {
        let _ = io::parse(data, extension, io::Weld::default());
    }
}

/// Arbitrary arrays as a polygon mesh: validated or refused, never a panic; an accepted mesh
/// keeps its invariants and its dual graph builds.
///
/// Layout: byte 0 = vertex count (mod 24); then 3 bytes per coordinate triple (255 = NaN,
/// 254 = infinity, 253 = 1e13, otherwise byte / 16); then faces as runs of a size byte
/// (mod 7) followed by that many index bytes (mod 32, so some are out of range).
pub fn mesh_validation(data: &[u8]) {
    if data.len() < 2 {
        return;
    }
    let vertex_count = (data[0] % 24) as usize;
    let mut bytes = data[1..].iter().copied();
    let mut coordinate = || match bytes.next() {
        Some(255) => f64::NAN,
        Some(254) => f64::INFINITY,
        Some(253) => 1e13,
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
    let Ok(mesh) = PolyMesh::new(positions, faces) else { return };
    assert!(mesh.positions().iter().all(|p| p.coords.iter().all(|c| c.is_finite() && c.abs() <= MAX_COORDINATE)));
    assert!(mesh.faces().iter().all(|f| f.len() >= 3 && f.iter().all(|&v| v < mesh.positions().len())));
    let mut keys: Vec<Vec<usize>> = mesh.faces().iter().map(|f| {
        let mut k = f.clone();
        k.sort_unstable();
        k
    }).collect();
    keys.sort();
    assert!(keys.windows(2).all(|w| w[0] != w[1]), "no duplicate faces");
    let topology = Topology::new(&mesh).expect("an accepted mesh has a topology");
    topology.check_orientation(&mesh).expect("an accepted mesh is consistently oriented");
    assert!(topology.edges().iter().all(|e| e.faces.len() <= 2));
    let graph = DualGraph::new(&mesh, &topology, &vec![false; mesh.face_count()]);
    let none = vec![false; graph.tiles().len()];
    for bond in [Bond::Stack, Bond::Staggered { weight: 0.5 }, Bond::RunningBond { weight: 0.5 }] {
        assert_eq!(score(&graph, &none, bond).objective, 0.0);
    }
    let _ = (mesh.area(), mesh.bounding_box());
}

/// Arbitrary arrays through the C ABI: `tp_mesh_new`, `tp_pattern_solve` (50 ms),
/// `tp_tiles_build` and every accessor of the result. Statuses may be errors; none may be
/// `TP_PANIC`, and accepted tiles have finite corners.
///
/// Layout: byte 0 = vertex count (mod 20); byte 1 = bond (mod 4; 3 is invalid); byte 2 =
/// weight (/ 64); byte 3 = tile size and options (see below); then 3 bytes per vertex
/// (255 = NaN, otherwise byte / 32); then faces as runs of a size byte (3 + mod 3) and that
/// many index bytes (mod 24).
pub fn ffi_pipeline(data: &[u8]) {
    if data.len() < 5 {
        return;
    }
    let vertex_count = (data[0] % 20) as usize;
    let bond = i32::from(data[1] % 4);
    let weight = f64::from(data[2]) / 64.0;
    let tile_length = [0.5, 1.0, 2.0, 0.25, 4.0, 1e-7, 0.0, f64::NAN][usize::from(data[3] & 7)];
    let method = i32::from((data[3] >> 3) & 1);
    let force_first_pair = (data[3] >> 4) & 1 == 1;
    let exclude_first = (data[3] >> 5) & 1 == 1;
    let mut body = data[4..].iter().copied();
    let vertices: Vec<f64> = (0..3 * vertex_count)
        .map(|_| match body.next() {
            Some(255) => f64::NAN,
            Some(b) => f64::from(b) / 32.0,
            None => 0.0,
        })
        .collect();
    let rest: Vec<u8> = body.collect();
    let (mut indices, mut sizes) = (Vec::new(), Vec::new());
    let mut i = 0;
    while i < rest.len() && sizes.len() < 24 {
        let size = 3 + (rest[i] % 3) as usize;
        let end = (i + 1 + size).min(rest.len());
        indices.extend(rest[i + 1..end].iter().map(|&b| u32::from(b % 24)));
        sizes.push((end - i - 1) as u32);
        i = end;
    }
    let ok = TpStatus::TP_OK;
    // SAFETY: every pointer below points to live arrays of the stated lengths or to locals.
    unsafe {
        let mut mesh = ptr::null_mut();
        let status = tp_mesh_new(vertices.as_ptr(), vertex_count, indices.as_ptr(), indices.len(), sizes.as_ptr(), sizes.len(), &mut mesh);
        assert_ne!(status, TpStatus::TP_PANIC, "tp_mesh_new");
        if status != ok {
            assert!(mesh.is_null());
            return;
        }
        let mut options = tp_pattern_options_default();
        options.bond = bond;
        options.weight = weight;
        options.method = method;
        options.time_limit_seconds = 0.05;
        let pair = [0u32, 1];
        if force_first_pair {
            options.forced_pairs = pair.as_ptr();
            options.forced_pair_count = 1;
        }
        let first = [0u32];
        if exclude_first {
            options.excluded_faces = first.as_ptr();
            options.excluded_face_count = 1;
        }
        let mut pattern = ptr::null_mut();
        let status = tp_pattern_solve(mesh, &options, None, ptr::null_mut(), &mut pattern);
        assert_ne!(status, TpStatus::TP_PANIC, "tp_pattern_solve");
        if status == ok {
            let mut summary = TpPatternSummary::default();
            assert_eq!(tp_pattern_summary(pattern, &mut summary), ok);
            assert!(summary.bound + 1e-9 >= summary.objective, "the bound bounds the objective");
            let mut pairs = vec![0u32; 2 * summary.pairs + 1];
            assert_eq!(tp_pattern_copy_pairs(pattern, pairs.as_mut_ptr(), pairs.len()), ok);
            let mut tile = tp_tile_options_default();
            tile.length = tile_length;
            tile.width = tile_length / 2.0;
            tile.thickness = 0.05;
            tile.joint = 0.02;
            // Short, as the pattern's: a tile far smaller than the faces asks the fit's tear
            // fill for a piece per tile of the faces' area.
            tile.fit_time_limit_seconds = 1.0;
            let mut tiles = ptr::null_mut();
            let status = tp_tiles_build(mesh, pattern, &tile, &mut tiles);
            assert_ne!(status, TpStatus::TP_PANIC, "tp_tiles_build");
            if status == ok {
                read_tiles(tiles);
                tp_tiles_free(tiles);
            }
            tp_pattern_free(pattern);
        }
        tp_mesh_free(mesh);
    }
}

/// Calls every accessor of `tiles` with buffers of the sizes the counts ask for.
///
/// # Safety
/// `tiles` must be a live handle.
unsafe fn read_tiles(tiles: *const TpTiles) {
    let ok = TpStatus::TP_OK;
    let (mut count, mut loops, mut points, mut needed) = (0usize, 0usize, 0usize, 0usize);
    // SAFETY: live handle, buffers of the stated sizes.
    unsafe {
        assert_eq!(tp_tiles_count(tiles, &mut count), ok);
        let mut doubles = vec![0.0f64; 24 * count + 1];
        assert_eq!(tp_tiles_copy_corners(tiles, doubles.as_mut_ptr(), doubles.len()), ok);
        assert!(doubles.iter().all(|d| d.is_finite()), "tile corners are finite");
        assert_eq!(tp_tiles_copy_frames(tiles, doubles.as_mut_ptr(), doubles.len()), ok);
        assert_eq!(tp_tiles_copy_sizes(tiles, doubles.as_mut_ptr(), doubles.len()), ok);
        assert_eq!(tp_tiles_copy_kept_fractions(tiles, doubles.as_mut_ptr(), doubles.len()), ok);
        let mut words = vec![0u32; 2 * count + 1];
        assert_eq!(tp_tiles_copy_faces(tiles, words.as_mut_ptr(), words.len()), ok);
        assert_eq!(tp_tiles_copy_steps(tiles, words.as_mut_ptr(), words.len()), ok);
        assert_eq!(tp_tiles_copy_loop_counts(tiles, words.as_mut_ptr(), words.len()), ok);
        let mut kinds = vec![0i32; count + 1];
        assert_eq!(tp_tiles_copy_kinds(tiles, kinds.as_mut_ptr(), kinds.len()), ok);
        assert_eq!(tp_tiles_outline_counts(tiles, &mut loops, &mut points), ok);
        let mut sizes = vec![0u32; loops + 1];
        assert_eq!(tp_tiles_copy_loop_sizes(tiles, sizes.as_mut_ptr(), sizes.len()), ok);
        let mut xy = vec![0.0f64; 2 * points + 1];
        assert_eq!(tp_tiles_copy_loop_points(tiles, xy.as_mut_ptr(), xy.len()), ok);
        assert!(xy.iter().all(|d| d.is_finite()), "outline points are finite");
        type Text = unsafe extern "C" fn(*const TpTiles, *mut c_char, usize, *mut usize) -> TpStatus;
        for text in [tp_tiles_report_json as Text, tp_tiles_labels, tp_tiles_cutlist_json] {
            assert_eq!(text(tiles, ptr::null_mut(), 0, &mut needed), TpStatus::TP_BUFFER_TOO_SMALL, "asking for the size");
            let mut buf = vec![0 as c_char; needed + 1];
            assert_eq!(text(tiles, buf.as_mut_ptr(), buf.len(), ptr::null_mut()), ok);
        }
    }
}
