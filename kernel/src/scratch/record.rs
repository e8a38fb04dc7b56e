//! The scratch record shared by CPU and GPU, and its local frame (Werner §3.1, Eq. 13).

use super::spatial_phase::dot;
use crate::lane::Real;
use crate::segment2d::Segment2;
use bytemuck::{Pod, Zeroable};
use glam::Vec2;

/// One straight scratch segment on the tangent plane (µm). GPU-visible: 32 bytes, no `Vec`.
///
/// Stored as centre, unit tangent and half length rather than end points: a long segment's
/// end points are large numbers whose f32 rounding (0.03 µm at 400 mm) would move the line,
/// and the spatial phase `2π s_b ξ₂` amplifies that. Build it with
/// [`Scratch::from_endpoints`], which does the conversion in f64.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct Scratch {
    /// Midpoint (µm).
    pub center: [f32; 2],
    /// Unit tangent (from the first end point to the second).
    pub tangent: [f32; 2],
    /// Half of the length (µm); 0 for a zero-length segment, which reflects nothing.
    pub half_len: f32,
    /// Groove width W (µm).
    pub width: f32,
    /// Groove depth D (µm), measured downwards.
    pub depth: f32,
    /// Cross-section profile, a [`super::Profile`] as `u32`.
    pub profile: u32,
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
    /// The scratch from `p0` to `p1` (µm, f64 so long segments keep their position), with
    /// the given width, depth (µm) and profile. Host side only (f64).
    #[cfg(not(target_arch = "spirv"))]
    pub fn from_endpoints(
        p0: [f64; 2],
        p1: [f64; 2],
        width: f32,
        depth: f32,
        profile: super::Profile,
    ) -> Scratch {
        let d = [p1[0] - p0[0], p1[1] - p0[1]];
        let len = libm::sqrt(d[0] * d[0] + d[1] * d[1]);
        let tangent = if len > 0.0 {
            [(d[0] / len) as f32, (d[1] / len) as f32]
        } else {
            [1.0, 0.0]
        };
        Scratch {
            center: [
                (0.5 * (p0[0] + p1[0])) as f32,
                (0.5 * (p0[1] + p1[1])) as f32,
            ],
            tangent,
            half_len: (0.5 * len) as f32,
            width,
            depth,
            profile: profile as u32,
        }
    }

    /// The segment's frame, or `None` for a zero-length (or non-finite) segment, which
    /// reflects nothing of its own.
    #[inline]
    pub fn frame(&self) -> Option<SegmentFrame> {
        let t = Vec2::from_array(self.tangent);
        let c = Vec2::from_array(self.center);
        if !(self.half_len > 0.0) || !self.half_len.is_finite() || !c.is_finite() || !t.is_finite()
        {
            return None;
        }
        Some(SegmentFrame {
            center: c,
            tangent: t,
            bitangent: Vec2::new(-t.y, t.x),
            half_len: self.half_len,
        })
    }

    /// The two end points (f32; for bounds and display).
    #[inline]
    pub fn endpoints(&self) -> ([f32; 2], [f32; 2]) {
        let (c, t, h) = (self.center, self.tangent, self.half_len);
        (
            [c[0] - h * t[0], c[1] - h * t[1]],
            [c[0] + h * t[0], c[1] + h * t[1]],
        )
    }

    /// The bare segment (what the lookup structures index).
    #[inline]
    pub fn segment(&self) -> Segment2 {
        let (a, b) = self.endpoints();
        Segment2::new(a, b)
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
        self.offset_from_lanes([x0.x, x0.y])
    }

    /// [`SegmentFrame::offset_from`] for one `x0` per lane.
    #[inline(always)]
    pub fn offset_from_lanes<R: Real>(&self, x0: [R; 2]) -> (R, R) {
        let r0 = [
            R::splat(self.center.x) - x0[0],
            R::splat(self.center.y) - x0[1],
        ];
        (dot(r0, self.tangent), dot(r0, self.bitangent))
    }
}
