//! The scratch record shared by CPU and GPU, and its local frame (Werner §3.1, Eq. 13).

use crate::segment::Segment2;
use bytemuck::{Pod, Zeroable};
use glam::Vec2;

/// One straight scratch segment on the tangent plane (µm). GPU-visible: 32 bytes, no `Vec`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct Scratch {
    /// First end point (µm).
    pub p0: [f32; 2],
    /// Second end point (µm).
    pub p1: [f32; 2],
    /// Groove width W (µm).
    pub width: f32,
    /// Groove depth D (µm), measured downwards.
    pub depth: f32,
    /// Cross-section profile, a [`super::Profile`] as `u32`.
    pub profile: u32,
    /// Explicit padding (keep 0).
    pub pad: u32,
}

const _: () = assert!(core::mem::size_of::<Scratch>() == 32);

/// A segment's geometry in its own frame: centre `c`, unit tangent `t`, bitangent
/// `b = n × t = (−t.y, t.x)`, half length.
#[derive(Clone, Copy, Debug)]
pub struct SegmentFrame {
    /// Midpoint (µm).
    pub center: Vec2,
    /// Unit tangent.
    pub tangent: Vec2,
    /// Unit bitangent `n × t`.
    pub bitangent: Vec2,
    /// Half of the segment length (µm).
    pub half_len: f32,
}

impl Scratch {
    /// The segment's frame, or `None` for a zero-length (or non-finite) segment, which
    /// reflects nothing of its own.
    #[inline]
    pub fn frame(&self) -> Option<SegmentFrame> {
        let p0 = Vec2::from_array(self.p0);
        let p1 = Vec2::from_array(self.p1);
        let d = p1 - p0;
        let len = d.length();
        if !(len > 0.0) || !len.is_finite() {
            return None;
        }
        let t = d / len;
        Some(SegmentFrame {
            center: 0.5 * (p0 + p1),
            tangent: t,
            bitangent: Vec2::new(-t.y, t.x),
            half_len: 0.5 * len,
        })
    }

    /// The bare segment (what the lookup structures index).
    #[inline]
    pub fn segment(&self) -> Segment2 {
        Segment2::new(self.p0, self.p1)
    }

    /// Distance from `x` to the closed segment (µm).
    #[inline]
    pub fn distance_to(&self, x: Vec2) -> f32 {
        crate::math::sqrt(self.segment().distance2([x.x, x.y]))
    }
}

impl SegmentFrame {
    /// `(s_t, s_b)`: the centre relative to `x0` in tangent/bitangent components.
    #[inline]
    pub fn offset_from(&self, x0: Vec2) -> (f32, f32) {
        let r0 = self.center - x0;
        (r0.dot(self.tangent), r0.dot(self.bitangent))
    }
}
