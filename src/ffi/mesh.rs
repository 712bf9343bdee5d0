//! Meshes in and out: vertices as xyz triples, faces as a flat index list plus face sizes.

use nalgebra::Point3;

use super::status::{Failure, TpStatus, TpStatus::*, guard};
use super::{borrow, hand_over, input, output, release, write_out};
use crate::mesh::PolyMesh;

/// A validated polygon mesh (opaque).
pub struct TpMesh {
    pub(super) mesh: PolyMesh,
}

/// Builds and validates a mesh from `vertex_count` xyz triples at `vertices` and
/// `face_count` faces: face `i` has `face_sizes[i]` vertex indices, taken in order from
/// `face_indices` (`index_count` in all). Triangles, quads and n-gons may be mixed. On
/// success `*out` holds a new mesh to release with [`tp_mesh_free`].
///
/// Limits per mesh: 4,000,000 vertices, 4,000,000 faces, 16,000,000 face indices; larger
/// counts are refused with `TP_INVALID_ARGUMENT` before any array is read or anything is
/// allocated (a mesh needs about a kilobyte per face at the peak of all stages, so a mesh at
/// the limits needs some 4 GB).
///
/// Refused with `TP_INVALID_MESH`, the message naming the face or vertex: no faces or no
/// vertices; a NaN or infinite coordinate, or one larger than 1e12 in magnitude; a face
/// with fewer than 3 vertices; an index out of range (a negative index converted to
/// `uint32_t` is one); a vertex twice in one face; two faces with the same vertices; an edge
/// shared by 3 or more faces; two faces running along their shared edge in the same
/// direction (inconsistent orientation). Accepted: zero-area faces, vertices where pieces
/// touch, disconnected pieces, unused vertices, triangles and n-gons (never paired).
///
/// # Safety
/// The arrays must hold the stated numbers of items; `out` must be writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_mesh_new(
    vertices: *const f64,
    vertex_count: usize,
    face_indices: *const u32,
    index_count: usize,
    face_sizes: *const u32,
    face_count: usize,
    out: *mut *mut TpMesh,
) -> TpStatus {
    guard(|| {
        if out.is_null() {
            return Err(Failure::null("out"));
        }
        // Refuse absurd counts before reading or allocating anything for them.
        crate::mesh::check_size(vertex_count, face_count, index_count)?;
        let coordinates_len = vertex_count.checked_mul(3).ok_or_else(|| {
            Failure::new(
                TP_INVALID_ARGUMENT,
                format!("vertex_count {vertex_count} is too large"),
            )
        })?;
        // SAFETY: sizes as promised by the caller.
        let (coordinates, indices, sizes) = unsafe {
            (
                input(vertices, coordinates_len, "vertices")?,
                input(face_indices, index_count, "face_indices")?,
                input(face_sizes, face_count, "face_sizes")?,
            )
        };
        let total: u64 = sizes.iter().map(|&s| u64::from(s)).sum();
        if total != index_count as u64 {
            return Err(Failure::new(
                TP_INVALID_ARGUMENT,
                format!("face_sizes add up to {total}, but index_count is {index_count}"),
            ));
        }
        let positions = coordinates
            .chunks_exact(3)
            .map(|c| Point3::new(c[0], c[1], c[2]))
            .collect();
        let mut faces = Vec::with_capacity(face_count);
        let mut next = 0;
        for &size in sizes {
            let size = size as usize;
            faces.push(
                indices[next..next + size]
                    .iter()
                    .map(|&i| i as usize)
                    .collect(),
            );
            next += size;
        }
        let mesh = PolyMesh::new(positions, faces)?;
        // SAFETY: checked non-null above.
        unsafe { hand_over(out, TpMesh { mesh }, "out") }
    })
}

/// Releases a mesh. NULL is accepted.
///
/// # Safety
/// `mesh` must be NULL or a live mesh, not used afterwards.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_mesh_free(mesh: *mut TpMesh) {
    // SAFETY: forwarded.
    unsafe { release(mesh) }
}

/// Writes the numbers of vertices, faces and face indices (any out pointer may be NULL).
///
/// # Safety
/// `mesh` must be a live mesh; non-NULL out pointers must be writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_mesh_counts(
    mesh: *const TpMesh,
    vertex_count: *mut usize,
    face_count: *mut usize,
    index_count: *mut usize,
) -> TpStatus {
    guard(|| {
        // SAFETY: live handle by the caller's promise.
        let mesh = &unsafe { borrow(mesh, "mesh") }?.mesh;
        let indices = mesh.faces().iter().map(Vec::len).sum();
        for (out, value) in [
            (vertex_count, mesh.positions().len()),
            (face_count, mesh.face_count()),
            (index_count, indices),
        ] {
            if !out.is_null() {
                // SAFETY: non-null and writable by the caller's promise.
                unsafe { write_out(out, value, "count") }?;
            }
        }
        Ok(())
    })
}

/// Copies the vertices as xyz triples into `out` (capacity in doubles: 3 x vertex count).
///
/// # Safety
/// `mesh` must be a live mesh; `out` must hold `capacity` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_mesh_copy_vertices(
    mesh: *const TpMesh,
    out: *mut f64,
    capacity: usize,
) -> TpStatus {
    guard(|| {
        // SAFETY: live handle by the caller's promise.
        let mesh = &unsafe { borrow(mesh, "mesh") }?.mesh;
        let xyz: Vec<f64> = mesh
            .positions()
            .iter()
            .flat_map(|p| [p.x, p.y, p.z])
            .collect();
        // SAFETY: capacity as promised.
        unsafe { output(&xyz, out, capacity, "out") }
    })
}

/// Copies the faces: all vertex indices in face order into `indices` (capacity: index
/// count) and each face's size into `sizes` (capacity: face count).
///
/// # Safety
/// `mesh` must be a live mesh; the buffers must hold their stated capacities.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_mesh_copy_faces(
    mesh: *const TpMesh,
    indices: *mut u32,
    index_capacity: usize,
    sizes: *mut u32,
    size_capacity: usize,
) -> TpStatus {
    guard(|| {
        // SAFETY: live handle by the caller's promise.
        let mesh = &unsafe { borrow(mesh, "mesh") }?.mesh;
        let flat: Vec<u32> = mesh.faces().iter().flatten().map(|&v| v as u32).collect();
        let counts: Vec<u32> = mesh.faces().iter().map(|f| f.len() as u32).collect();
        // SAFETY: capacities as promised.
        unsafe {
            output(&flat, indices, index_capacity, "indices")?;
            output(&counts, sizes, size_capacity, "sizes")
        }
    })
}
