//! The query interfaces shared by every CPU-side acceleration structure: the portable
//! kernel hierarchy ([`crate::TriangleBvh`], [`crate::SegmentBvh`]) and Embree
//! (`scratchwave-embree`). A renderer or the conformance suite holds a `&dyn RayQueries` or a
//! generic `Q: RayQueries` and does not care which one it got.

use scratchwave_kernel::ray::{Hit, Ray};

/// Whether a batch of rays is coherent (similar origins and directions, such as primary rays
/// of neighbouring pixels) or not (secondary bounces). A hint; results do not depend on it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Coherence {
    /// Neighbouring rays have similar origins and directions.
    Coherent,
    /// No relation between neighbouring rays.
    Incoherent,
}

/// Closest-hit and occlusion ray queries against one static scene. Implementations are
/// `Sync`: queries take `&self` and may run from many threads at once (rayon).
///
/// Hits are raw geometry ([`Hit`]: `t`, ids, barycentrics, unnormalized geometric normal);
/// shading stays in the kernel. When two primitives are hit at exactly the same `t` (a ray
/// through a shared edge), implementations may report either.
pub trait RayQueries: Sync {
    /// The closest hit with `t ∈ (ray.t_near, ray.t_far]`.
    fn closest_hit(&self, ray: &Ray) -> Option<Hit>;

    /// `true` if anything is hit with `t ∈ (ray.t_near, ray.t_far]` (shadow rays).
    fn occluded(&self, ray: &Ray) -> bool;

    /// Closest hits of many rays; `hits[i]` answers `rays[i]`. With [`Coherence::Coherent`]
    /// implementations may trace groups of consecutive rays together (Embree packets), so
    /// pass coherent rays in compact screen-space tiles.
    ///
    /// # Panics
    /// If `rays` and `hits` differ in length.
    fn closest_hits(&self, rays: &[Ray], hits: &mut [Option<Hit>], coherence: Coherence) {
        let _ = coherence;
        assert_eq!(rays.len(), hits.len(), "one hit slot per ray");
        for (ray, hit) in rays.iter().zip(hits.iter_mut()) {
            *hit = self.closest_hit(ray);
        }
    }

    /// Occlusion of many rays; `out[i]` answers `rays[i]`. With [`Coherence::Coherent`]
    /// implementations may trace groups of consecutive rays together (Embree packets), so
    /// pass rays with similar origins and directions next to each other (shadow rays of
    /// neighbouring pixels towards one light).
    ///
    /// # Panics
    /// If `rays` and `out` differ in length.
    fn occluded_many(&self, rays: &[Ray], out: &mut [bool], coherence: Coherence) {
        let _ = coherence;
        assert_eq!(rays.len(), out.len(), "one answer slot per ray");
        for (ray, o) in rays.iter().zip(out.iter_mut()) {
            *o = self.occluded(ray);
        }
    }
}

/// "Every scratch segment within `radius` of the point `p`" in the tangent plane.
pub trait SegmentRadiusQuery: Sync {
    /// Clears `out`, then fills it with the ids (input order) of all segments whose distance
    /// to `p` is at most `radius`, in no particular order.
    fn segments_within(&self, p: [f32; 2], radius: f32, out: &mut Vec<u32>);
}
