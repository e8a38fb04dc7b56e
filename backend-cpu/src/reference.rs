//! Brute-force oracles: every primitive tested, no acceleration structure. They use the same
//! kernel primitive tests and hit order as the portable BVH, so the two must agree exactly.

use scratchwave_kernel::ray::{Hit, Ray, Triangle, intersect_triangle, is_closer};
use scratchwave_kernel::segment::Segment2;

/// The closest hit over all `triangles` (primitive id = index, geometry id 0).
pub fn closest_hit(triangles: &[Triangle], ray: &Ray) -> Option<Hit> {
    let mut best: Option<Hit> = None;
    for (i, tri) in triangles.iter().enumerate() {
        let t_max = best.map_or(ray.t_far, |b| b.t);
        if let Some(h) = intersect_triangle(ray, tri, t_max) {
            let hit = h.to_hit(0, i as u32);
            if best.is_none_or(|b| is_closer(&hit, &b)) {
                best = Some(hit);
            }
        }
    }
    best
}

/// `true` if any triangle is hit within the ray interval.
pub fn occluded(triangles: &[Triangle], ray: &Ray) -> bool {
    triangles
        .iter()
        .any(|tri| intersect_triangle(ray, tri, ray.t_far).is_some())
}

/// Clears `out` and fills it with the indices of all segments within `radius` of `p`,
/// ascending.
pub fn segments_within(segments: &[Segment2], p: [f32; 2], radius: f32, out: &mut Vec<u32>) {
    out.clear();
    out.extend(
        segments
            .iter()
            .enumerate()
            .filter(|(_, s)| s.is_within(p, radius))
            .map(|(i, _)| i as u32),
    );
}
