//! "Every scratch near `x0`": the one question the shading code asks of the scratch data.
//!
//! Implementations decide how to answer it (brute force over a slice here; the flattened
//! BVH in `crate::bvh` for large sets) and the models stay generic over them, so the CPU and
//! GPU run the same model code whatever the lookup.

use super::segment::Scratch;
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
