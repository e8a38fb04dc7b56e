//! Brute-force oracles: every primitive tested, no acceleration structure. They use the same
//! kernel primitive tests and hit order as the portable BVH, so the two must agree exactly.

use scratchwave_kernel::ray::{Hit, Ray, Triangle, intersect_triangle, is_closer};
use scratchwave_kernel::segment2d::Segment2;

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

/// An exact radius-query oracle that scales to 10⁶ segments without a tree: segments sorted
/// by the low x of their box; a query scans only those whose low x lies in
/// `[p.x − r − W, p.x + r]` (W = widest box) and applies the exact test to each. The tests
/// check it against [`segments_within`].
#[derive(Clone, Debug)]
pub struct SegmentSweep {
    by_min_x: Vec<(f32, u32, Segment2)>,
    max_width: f32,
}

impl SegmentSweep {
    /// Sorts `segments` (ids = positions).
    pub fn new(segments: &[Segment2]) -> SegmentSweep {
        let mut by_min_x: Vec<_> = segments
            .iter()
            .enumerate()
            .map(|(i, s)| (s.bounds().min[0], i as u32, *s))
            .collect();
        by_min_x.sort_by(|a, b| a.0.total_cmp(&b.0));
        let max_width = segments
            .iter()
            .map(|s| s.bounds().max[0] - s.bounds().min[0])
            .fold(0.0, f32::max);
        SegmentSweep {
            by_min_x,
            max_width,
        }
    }

    /// Clears `out` and fills it with the ids of all segments within `radius` of `p`,
    /// ascending.
    pub fn query(&self, p: [f32; 2], radius: f32, out: &mut Vec<u32>) {
        out.clear();
        // The ±1 margins absorb rounding in the bounds of the scanned window.
        let lo = self
            .by_min_x
            .partition_point(|e| e.0 < p[0] - radius - self.max_width - 1.0);
        for (min_x, i, s) in &self.by_min_x[lo..] {
            if *min_x > p[0] + radius + 1.0 {
                break;
            }
            if s.is_within(p, radius) {
                out.push(*i);
            }
        }
        out.sort_unstable();
    }
}
