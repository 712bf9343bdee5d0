//! Arbitrary arrays through the C ABI: tp_mesh_new, then pattern (short time limit), tiles
//! cut to the mesh and every accessor. Statuses may be errors; nothing may panic
//! (TP_PANIC), crash or leak.
#![no_main]

use std::ptr;

use libfuzzer_sys::fuzz_target;
use tilepattern::ffi::*;

fuzz_target!(|data: &[u8]| {
    if data.len() < 4 {
        return;
    }
    let vertex_count = (data[0] % 20) as usize;
    let bond = i32::from(data[1] % 4);
    let weight = f64::from(data[2]) / 64.0;
    let mut body = data[3..].iter().copied();
    let vertices: Vec<f64> = (0..3 * vertex_count).map(|_| f64::from(body.next().unwrap_or(0)) / 32.0).collect();
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
    // SAFETY: every pointer below points to live arrays of the stated lengths or to locals.
    unsafe {
        let mut mesh = ptr::null_mut();
        let status = tp_mesh_new(vertices.as_ptr(), vertex_count, indices.as_ptr(), indices.len(), sizes.as_ptr(), sizes.len(), &mut mesh);
        assert_ne!(status, TpStatus::TP_PANIC);
        if status != TpStatus::TP_OK {
            return;
        }
        let mut options = tp_pattern_options_default();
        options.bond = bond;
        options.weight = weight;
        options.time_limit_seconds = 0.02;
        let mut pattern = ptr::null_mut();
        let status = tp_pattern_solve(mesh, &options, None, ptr::null_mut(), &mut pattern);
        assert_ne!(status, TpStatus::TP_PANIC);
        if status == TpStatus::TP_OK {
            let mut tile = tp_tile_options_default();
            tile.length = 0.5;
            tile.width = 0.25;
            let mut tiles = ptr::null_mut();
            let status = tp_tiles_build(mesh, pattern, &tile, &mut tiles);
            assert_ne!(status, TpStatus::TP_PANIC);
            if status == TpStatus::TP_OK {
                let (mut count, mut loops, mut points, mut needed) = (0usize, 0usize, 0usize, 0usize);
                assert_eq!(tp_tiles_count(tiles, &mut count), TpStatus::TP_OK);
                let mut doubles = vec![0.0f64; 24 * count + 1];
                let mut words = vec![0u32; 2 * count + 1];
                assert_eq!(tp_tiles_copy_corners(tiles, doubles.as_mut_ptr(), doubles.len()), TpStatus::TP_OK);
                assert!(doubles.iter().all(|d| d.is_finite()), "tile corners are finite");
                assert_eq!(tp_tiles_copy_faces(tiles, words.as_mut_ptr(), words.len()), TpStatus::TP_OK);
                assert_eq!(tp_tiles_outline_counts(tiles, &mut loops, &mut points), TpStatus::TP_OK);
                let mut xy = vec![0.0f64; 2 * points + 1];
                assert_eq!(tp_tiles_copy_loop_points(tiles, xy.as_mut_ptr(), xy.len()), TpStatus::TP_OK);
                tp_tiles_report_json(tiles, ptr::null_mut(), 0, &mut needed);
                let mut text = vec![0 as std::ffi::c_char; needed + 1];
                assert_eq!(tp_tiles_report_json(tiles, text.as_mut_ptr(), text.len(), ptr::null_mut()), TpStatus::TP_OK);
                tp_tiles_free(tiles);
            }
            tp_pattern_free(pattern);
        }
        tp_mesh_free(mesh);
    }
});
