//! "Every scratch near `x0`": the one question the shading code asks of the scratch data.
//!
//! Implementations decide how to answer it (brute force over a slice here; the flattened
//! BVH in `crate::bvh` for large sets) and the models stay generic over them, so the CPU and
//! GPU run the same model code whatever the lookup.

use super::segment::Scratch;
use crate::bvh::{BvhNode, for_each_near_point};
use core::ops::ControlFlow;
use glam::Vec2;

/// A set of scratches that can enumerate the ones within a radius of a point.
pub trait ScratchSet {
    /// Calls `visit` once for every scratch whose distance to `x0` is at most `radius`
    /// (it may also visit a few farther ones; the models weight them by the Gaussian window
    /// anyway, so extra visits change nothing but cost).
    fn for_each_near<F: FnMut(Scratch)>(&self, x0: Vec2, radius: f32, visit: F);
}

/// Brute force over a slice: O(n) per query, the reference for every faster lookup.
#[derive(Clone, Copy, Debug)]
pub struct ScratchSlice<'a> {
    /// The scratches.
    pub scratches: &'a [Scratch],
}

impl ScratchSet for ScratchSlice<'_> {
    fn for_each_near<F: FnMut(Scratch)>(&self, x0: Vec2, radius: f32, mut visit: F) {
        let mut i = 0;
        while i < self.scratches.len() {
            let s = self.scratches[i];
            if s.distance_to(x0) <= radius {
                visit(s);
            }
            i += 1;
        }
    }
}

/// The flattened BVH ([`crate::bvh`]) over the scratches' segment boxes: O(log n) per query.
/// `scratches` must be in the builder's slot order (`scratchwave-cpu`'s `ScratchLookup`
/// builds both); the GPU traverses the same two buffers with this same code.
#[derive(Clone, Copy, Debug)]
pub struct ScratchBvh<'a> {
    /// Nodes in depth-first order.
    pub nodes: &'a [BvhNode],
    /// Scratches in slot order.
    pub scratches: &'a [Scratch],
}

impl ScratchSet for ScratchBvh<'_> {
    fn for_each_near<F: FnMut(Scratch)>(&self, x0: Vec2, radius: f32, mut visit: F) {
        let scratches = self.scratches;
        let _ = for_each_near_point(self.nodes, [x0.x, x0.y, 0.0], radius, |slot| {
            if let Some(s) = scratches.get(slot as usize)
                && s.distance_to(x0) <= radius
            {
                visit(*s);
            }
            ControlFlow::Continue(())
        });
    }
}
