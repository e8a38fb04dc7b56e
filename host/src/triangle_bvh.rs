//! The portable triangle BVH: the kernel's stackless traversal over a hierarchy built here.
//! The same three buffers (`nodes`, `triangles`, `prim_ids`) are what a GPU backend uploads.

use crate::bvh_build::{BuildOptions, build};
use crate::mesh::{MeshError, check_count, triangles_of, validate_mesh};
use crate::queries::RayQueries;
use scratchwave_kernel::bvh::BvhNode;
use scratchwave_kernel::ray::{self, Hit, Ray, Triangle};

/// A triangle mesh with its flattened hierarchy; implements [`RayQueries`] with the kernel's
/// traversal, so CPU results equal what the GPU computes from the same buffers.
#[derive(Clone, Debug)]
pub struct TriangleBvh {
    nodes: Vec<BvhNode>,
    triangles: Vec<Triangle>,
    prim_ids: Vec<u32>,
}

impl TriangleBvh {
    /// Builds over an indexed mesh. Primitive ids are positions in `indices`.
    pub fn new(vertices: &[[f32; 3]], indices: &[[u32; 3]]) -> Result<TriangleBvh, MeshError> {
        validate_mesh(vertices.len(), indices)?;
        Self::from_triangles(&triangles_of(vertices, indices))
    }

    /// Builds over a triangle soup. Primitive ids are positions in `triangles`.
    pub fn from_triangles(triangles: &[Triangle]) -> Result<TriangleBvh, MeshError> {
        check_count(triangles.len())?;
        let boxes: Vec<_> = triangles.iter().map(Triangle::bounds).collect();
        let bvh = build(&boxes, &BuildOptions::default());
        Ok(TriangleBvh {
            triangles: bvh.permute(triangles),
            nodes: bvh.nodes,
            prim_ids: bvh.prim_order,
        })
    }

    /// Nodes in depth-first order.
    pub fn nodes(&self) -> &[BvhNode] {
        &self.nodes
    }

    /// Triangles in slot order.
    pub fn triangles(&self) -> &[Triangle] {
        &self.triangles
    }

    /// Input id of each slot.
    pub fn prim_ids(&self) -> &[u32] {
        &self.prim_ids
    }
}

impl RayQueries for TriangleBvh {
    fn closest_hit(&self, r: &Ray) -> Option<Hit> {
        ray::closest_hit(&self.nodes, &self.triangles, &self.prim_ids, r)
    }

    fn occluded(&self, r: &Ray) -> bool {
        ray::occluded(&self.nodes, &self.triangles, r)
    }
}
