//! Indexed triangle meshes as the std-side APIs take them.

use scratchwave_kernel::ray::Triangle;

/// A mesh given as a vertex array and one index triple per triangle was malformed.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum MeshError {
    /// An index points past the vertex array.
    #[error(
        "triangle {triangle} refers to vertex {index}, but the mesh has {vertex_count} vertices"
    )]
    IndexOutOfRange {
        /// The offending triangle.
        triangle: usize,
        /// Its out-of-range vertex index.
        index: u32,
        /// Number of vertices given.
        vertex_count: usize,
    },
    /// More primitives than 32-bit ids can name.
    #[error("{count} primitives exceed the 32-bit primitive id range")]
    TooManyPrimitives {
        /// Number of primitives given.
        count: usize,
    },
}

/// Checks that every index is in range and the ids fit in `u32` (with `u32::MAX` reserved
/// for "invalid").
pub fn validate_mesh(vertex_count: usize, indices: &[[u32; 3]]) -> Result<(), MeshError> {
    check_count(indices.len())?;
    check_count(vertex_count)?;
    for (triangle, tri) in indices.iter().enumerate() {
        for &index in tri {
            if index as usize >= vertex_count {
                return Err(MeshError::IndexOutOfRange {
                    triangle,
                    index,
                    vertex_count,
                });
            }
        }
    }
    Ok(())
}

/// Fails if `count` primitives cannot all get a `u32` id below `u32::MAX`.
pub fn check_count(count: usize) -> Result<(), MeshError> {
    if count >= u32::MAX as usize {
        return Err(MeshError::TooManyPrimitives { count });
    }
    Ok(())
}

/// The triangles of a validated mesh, by value (panics on out-of-range indices: call
/// [`validate_mesh`] first).
pub fn triangles_of(vertices: &[[f32; 3]], indices: &[[u32; 3]]) -> Vec<Triangle> {
    indices
        .iter()
        .map(|t| Triangle {
            v0: vertices[t[0] as usize],
            v1: vertices[t[1] as usize],
            v2: vertices[t[2] as usize],
        })
        .collect()
}
