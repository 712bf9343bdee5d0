//! Meshes in and out: vertices as xyz triples, faces as a flat index list plus face sizes.

use nalgebra::Point3;

use super::status::{Failure, TpStatus, TpStatus::*, guard};
use super::{borrow, hand_over, input, output, release, write_out};
use crate::mesh::io::{Raw, Weld, prepare};
use crate::mesh::{FileNumbering, PolyMesh};

/// A validated polygon mesh (opaque).
pub struct TpMesh {
    pub(super) mesh: PolyMesh,
    /// Where each face and vertex came from in the caller's arrays, for a mesh made by
    /// [`tp_mesh_new_welded`] (`None`: they are the caller's own).
    pub(super) given: Option<FileNumbering>,
}

impl TpMesh {
    /// A mesh handed out as it is, numbered as made.
    pub(super) fn made(mesh: PolyMesh) -> Self {
        Self { mesh, given: None }
    }
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
    let arrays = Arrays {
        vertices,
        vertex_count,
        face_indices,
        index_count,
        face_sizes,
        face_count,
    };
    // SAFETY: forwarded, the caller's promise.
    unsafe {
        new_mesh(arrays, out, |(positions, faces)| {
            Ok(TpMesh::made(PolyMesh::new(positions, faces)?))
        })
    }
}

/// [`tp_mesh_new`] for meshes as hosts and files give them, as the command line reads a
/// file: vertices closer than `relative_tolerance` times the diagonal of the used vertices'
/// bounding box are joined and the faces this collapses or repeats removed (a triangle soup,
/// an STL, a polysurface meshed face by face, whose faces keep their own vertices along the
/// seams), the cracks of a triangle mesh zipped where patches meshed apart meet (their
/// triangles split), and faces turned to agree with their neighbours; then the mesh is
/// validated as [`tp_mesh_new`] does, errors naming faces and vertices as given.
/// `relative_tolerance` 0 joins nothing but still turns faces; the command line's default
/// is 1e-6. [`tp_mesh_copy_sources`] gives where each face and vertex of the result came
/// from, to carry data given per face or vertex (zones, excluded faces, a field) over.
///
/// # Safety
/// As [`tp_mesh_new`].
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn tp_mesh_new_welded(
    vertices: *const f64,
    vertex_count: usize,
    face_indices: *const u32,
    index_count: usize,
    face_sizes: *const u32,
    face_count: usize,
    relative_tolerance: f64,
    out: *mut *mut TpMesh,
) -> TpStatus {
    if !(relative_tolerance.is_finite() && (0.0..1.0).contains(&relative_tolerance)) {
        return guard(|| {
            Err(Failure::new(
                TP_INVALID_ARGUMENT,
                format!(
                    "relative_tolerance is {relative_tolerance}: give a share of the mesh's size from 0 (join nothing) up to below 1 (1e-6 as the command line)"
                ),
            ))
        });
    }
    let arrays = Arrays {
        vertices,
        vertex_count,
        face_indices,
        index_count,
        face_sizes,
        face_count,
    };
    let weld = if relative_tolerance > 0.0 {
        Weld::Relative(relative_tolerance)
    } else {
        Weld::Off
    };
    // SAFETY: forwarded, the caller's promise.
    unsafe {
        new_mesh(arrays, out, |(positions, faces)| {
            let given = FileNumbering::identity(faces.len(), positions.len());
            let prepared = prepare(positions, faces, weld, given)?;
            Ok(TpMesh {
                mesh: prepared.mesh,
                given: Some(prepared.numbering),
            })
        })
    }
}

/// Where each vertex and face of `mesh` came from: `vertex_source` (capacity: the vertex
/// count) gets each vertex's first given vertex, `face_source` (capacity: the face count)
/// each face's given face (a triangle zipping split keeps its face's number); either may be
/// NULL when not wanted. A mesh from [`tp_mesh_new_welded`] counts the arrays it was made
/// from; any other mesh its own vertices and faces (0, 1, 2, ...).
///
/// # Safety
/// `mesh` must be a live mesh; non-NULL buffers must hold their stated capacities.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_mesh_copy_sources(
    mesh: *const TpMesh,
    vertex_source: *mut u32,
    vertex_capacity: usize,
    face_source: *mut u32,
    face_capacity: usize,
) -> TpStatus {
    guard(|| {
        // SAFETY: live handle by the caller's promise.
        let handle = unsafe { borrow(mesh, "mesh") }?;
        let (vertices, faces) = (handle.mesh.positions().len(), handle.mesh.face_count());
        let given = handle.given.as_ref();
        let as_u32 = |v: usize| u32::try_from(v).unwrap_or(u32::MAX);
        if !vertex_source.is_null() {
            let list: Vec<u32> = (0..vertices)
                .map(|v| as_u32(given.map_or(v, |n| n.file_vertex(v))))
                .collect();
            // SAFETY: capacity as promised.
            unsafe { output(&list, vertex_source, vertex_capacity, "vertex_source") }?;
        }
        if !face_source.is_null() {
            let list: Vec<u32> = (0..faces)
                .map(|f| as_u32(given.map_or(f, |n| n.file_face(f))))
                .collect();
            // SAFETY: capacity as promised.
            unsafe { output(&list, face_source, face_capacity, "face_source") }?;
        }
        Ok(())
    })
}

/// A caller's mesh arrays, as [`tp_mesh_new`] takes them.
#[derive(Clone, Copy)]
struct Arrays {
    vertices: *const f64,
    vertex_count: usize,
    face_indices: *const u32,
    index_count: usize,
    face_sizes: *const u32,
    face_count: usize,
}

/// Reads `arrays`, makes a mesh of them with `make` and hands it over in `*out`, behind the
/// panic boundary.
///
/// # Safety
/// The arrays must hold their stated numbers of items; `out` must be writable.
unsafe fn new_mesh(
    arrays: Arrays,
    out: *mut *mut TpMesh,
    make: impl FnOnce(Raw) -> Result<TpMesh, Failure>,
) -> TpStatus {
    guard(|| {
        if out.is_null() {
            return Err(Failure::null("out"));
        }
        // SAFETY: forwarded, the caller's promise.
        let mesh = make(unsafe { arrays.read() }?)?;
        // SAFETY: checked non-null above.
        unsafe { hand_over(out, mesh, "out") }
    })
}

impl Arrays {
    /// Positions and faces, counts over the limits refused before anything is read.
    ///
    /// # Safety
    /// The arrays must hold their stated numbers of items.
    unsafe fn read(self) -> Result<Raw, Failure> {
        let Arrays {
            vertices,
            vertex_count,
            face_indices,
            index_count,
            face_sizes,
            face_count,
        } = self;
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
        Ok((positions, faces))
    }
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
