//! "Every scratch near `x0`": the one question the shading code asks of the scratch data.
//!
//! Implementations decide how to answer it (brute force over a slice here; the flattened
//! BVH in `crate::bvh` for large sets) and the models stay generic over them, so the CPU and
//! GPU run the same model code whatever the lookup.

use super::record::Scratch;
use crate::bvh::{BvhCursor, BvhNode, next_near_point_before};
use glam::Vec2;

/// Where a "scratches near x0" enumeration stands (see [`ScratchSet::next_near`]).
pub type NearCursor = BvhCursor;

/// A set of scratches that can enumerate the ones within a radius of a point.
///
/// The enumeration is a cursor (`next_near`), not a callback, so the models run it as a plain
/// `while let` loop: rust-gpu cannot store closures that capture the models' accumulators
/// by reference, and a cursor needs no closure at all.
pub trait ScratchSet {
    /// The next scratch whose distance to `x0` is at most `radius`, resuming at `cursor`
    /// (start from `NearCursor::default()`); `None` when there are no more.
    fn next_near(&self, cursor: &mut NearCursor, x0: Vec2, radius: f32) -> Option<Scratch>;

    /// Calls `visit` once for every scratch within `radius` of `x0` (host convenience).
    fn for_each_near<F: FnMut(Scratch)>(&self, x0: Vec2, radius: f32, mut visit: F) {
        let mut cursor = NearCursor::default();
        while let Some(s) = self.next_near(&mut cursor, x0, radius) {
            visit(s);
        }
    }
}

impl<T: ScratchSet> ScratchSet for &T {
    #[inline]
    fn next_near(&self, cursor: &mut NearCursor, x0: Vec2, radius: f32) -> Option<Scratch> {
        (**self).next_near(cursor, x0, radius)
    }
}

/// Brute force over a slice: O(n) per query, the reference for every faster lookup.
#[derive(Clone, Copy, Debug)]
pub struct ScratchSlice<'a> {
    /// The scratches.
    pub scratches: &'a [Scratch],
}

impl ScratchSet for ScratchSlice<'_> {
    fn next_near(&self, cursor: &mut NearCursor, x0: Vec2, radius: f32) -> Option<Scratch> {
        while (cursor.slot as usize) < self.scratches.len() {
            let s = self.scratches[cursor.slot as usize];
            cursor.slot += 1;
            if s.distance_to(x0) <= radius {
                return Some(s);
            }
        }
        None
    }
}

/// The flattened BVH ([`crate::bvh`]) over the scratches' segment boxes: O(log n) per query.
/// `scratches` must be in the builder's slot order (`scratchwave-host`'s `ScratchLookup`
/// builds both); the GPU traverses the same two buffers with this same code.
///
/// The hierarchy is `nodes[first..end]` ([`ScratchBvh::new`]: all of them). A renderer on
/// the GPU binds one node and one scratch buffer for every material of a scene, each
/// material's hierarchy a window of it with its skip indices and slots counted in the
/// shared buffers (rust-gpu cannot take a sub-slice of a storage buffer).
#[derive(Clone, Copy, Debug)]
pub struct ScratchBvh<'a> {
    /// Nodes in depth-first order.
    pub nodes: &'a [BvhNode],
    /// Scratches in slot order.
    pub scratches: &'a [Scratch],
    /// The hierarchy's first node.
    pub first: u32,
    /// One past its last node.
    pub end: u32,
}

impl<'a> ScratchBvh<'a> {
    /// The hierarchy of all of `nodes` over `scratches`.
    #[inline]
    pub fn new(nodes: &'a [BvhNode], scratches: &'a [Scratch]) -> ScratchBvh<'a> {
        ScratchBvh {
            nodes,
            scratches,
            first: 0,
            end: nodes.len() as u32,
        }
    }
}

impl ScratchSet for ScratchBvh<'_> {
    fn next_near(&self, cursor: &mut NearCursor, x0: Vec2, radius: f32) -> Option<Scratch> {
        if cursor.node < self.first {
            cursor.node = self.first;
        }
        let end = self.end as usize;
        // One exit (see `bvh::next_slot_before`).
        let mut found = None;
        let mut done = false;
        while !done {
            match next_near_point_before(self.nodes, end, cursor, [x0.x, x0.y, 0.0], radius) {
                Some(slot) => {
                    let i = slot as usize;
                    if i < self.scratches.len() {
                        let s = self.scratches[i];
                        if s.distance_to(x0) <= radius {
                            found = Some(s);
                            done = true;
                        }
                    }
                }
                None => done = true,
            }
        }
        found
    }
}
