//! 2-D line segments in the tangent plane and the radius query over them: "every segment
//! within distance `r` of the shading point `x0`" (Werner et al. 2017 §5's scratch lookup).
//!
//! Build the hierarchy over [`Segment2::bounds`] (tight boxes at z = 0); the query then costs
//! one point–box distance per visited node and one point–segment distance per candidate,
//! and the radius may change from query to query.

use crate::bvh::{Aabb, BvhNode, for_each_near_point};
use bytemuck::{Pod, Zeroable};
use core::ops::ControlFlow;

/// A segment from `a` to `b` in tangent-plane coordinates (µm).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct Segment2 {
    /// First endpoint.
    pub a: [f32; 2],
    /// Second endpoint.
    pub b: [f32; 2],
}

const _: () = assert!(core::mem::size_of::<Segment2>() == 16);

impl Segment2 {
    /// The segment from `a` to `b`.
    #[inline]
    pub const fn new(a: [f32; 2], b: [f32; 2]) -> Segment2 {
        Segment2 { a, b }
    }

    /// Tight bounding box at z = 0.
    #[inline]
    pub fn bounds(&self) -> Aabb {
        Aabb::new(
            [self.a[0].min(self.b[0]), self.a[1].min(self.b[1]), 0.0],
            [self.a[0].max(self.b[0]), self.a[1].max(self.b[1]), 0.0],
        )
    }

    /// Squared distance from `p` to the closest point of the segment (a degenerate segment
    /// is a point).
    #[inline]
    #[allow(
        clippy::manual_clamp,
        reason = "f32::clamp has a panic path; the kernel keeps panics unreachable"
    )]
    pub fn distance2(&self, p: [f32; 2]) -> f32 {
        let ab = [self.b[0] - self.a[0], self.b[1] - self.a[1]];
        let ap = [p[0] - self.a[0], p[1] - self.a[1]];
        let len2 = ab[0] * ab[0] + ab[1] * ab[1];
        let s = if len2 > 0.0 {
            ((ap[0] * ab[0] + ap[1] * ab[1]) / len2).max(0.0).min(1.0)
        } else {
            0.0
        };
        let d = [ap[0] - s * ab[0], ap[1] - s * ab[1]];
        d[0] * d[0] + d[1] * d[1]
    }

    /// `true` if the segment comes within `radius` of `p` (closed disc).
    #[inline]
    pub fn is_within(&self, p: [f32; 2], radius: f32) -> bool {
        self.distance2(p) <= radius * radius
    }
}

/// Calls `f(slot)` for every segment within `radius` of `p`, where `segments[slot]` is in the
/// builder's primitive order. `f` returning `Break` stops the query.
#[inline]
pub fn for_each_segment_within<F: FnMut(u32) -> ControlFlow<()>>(
    nodes: &[BvhNode],
    segments: &[Segment2],
    p: [f32; 2],
    radius: f32,
    mut f: F,
) -> ControlFlow<()> {
    for_each_near_point(nodes, [p[0], p[1], 0.0], radius, |slot| {
        match segments.get(slot as usize) {
            Some(s) if s.is_within(p, radius) => f(slot),
            _ => ControlFlow::Continue(()),
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distance_to_interior_endpoints_and_degenerate() {
        let s = Segment2::new([0.0, 0.0], [2.0, 0.0]);
        assert_eq!(s.distance2([1.0, 3.0]), 9.0);
        assert_eq!(s.distance2([-3.0, 4.0]), 25.0);
        assert_eq!(s.distance2([5.0, 4.0]), 25.0);
        let point = Segment2::new([1.0, 1.0], [1.0, 1.0]);
        assert_eq!(point.distance2([4.0, 5.0]), 25.0);
        assert!(s.is_within([1.0, 3.0], 3.0));
        assert!(!s.is_within([1.0, 3.0], 2.999));
        assert!(!s.is_within([f32::NAN, 0.0], 1.0));
    }

    #[test]
    fn bounds_are_flat_and_tight() {
        let s = Segment2::new([2.0, -1.0], [0.5, 3.0]);
        assert_eq!(s.bounds(), Aabb::new([0.5, -1.0, 0.0], [2.0, 3.0, 0.0]));
    }
}
