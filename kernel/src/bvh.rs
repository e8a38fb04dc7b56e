//! The portable lookup structure: a flattened bounding-volume hierarchy traversed without a
//! stack.
//!
//! Nodes are stored in depth-first (pre-order) order. Visiting node `i`:
//!
//! - its bounds are tested against the query;
//! - if they pass and it is an inner node, traversal continues at `i + 1` (its first child);
//! - if they pass and it is a leaf, its primitives are visited, then traversal continues at
//!   `i + 1`;
//! - if they fail, traversal continues at the node's *skip* index (the first node after its
//!   subtree) for an inner node, or at `i + 1` for a leaf (a leaf's subtree is itself).
//!
//! This is the skip-pointer ("threaded") traversal of Smits 1998, also used by Werner et al.
//! 2017 §5 for the scratch lookup. It needs no stack and no recursion, so it runs unchanged
//! on SPIR-V. The price is a fixed child order: closest-hit ray queries cannot visit the
//! nearer child first, so they touch more nodes than an ordered stack traversal would.
//!
//! Leaves refer to *slots*: positions in the primitive order chosen by the builder
//! (`scratchwave-cpu`'s `bvh_build`). Store your primitives permuted into that order, so that
//! a slot indexes them directly, and keep the order array to map a slot back to the caller's
//! primitive id.
//!
//! [`traverse`] is generic over a [`BvhVisitor`], which decides which boxes to enter and what
//! to do with each primitive; ray queries ([`crate::ray`]) and range queries
//! ([`for_each_near_point`], [`for_each_overlapping`]) are thin visitors over it.

use bytemuck::{Pod, Zeroable};
use core::ops::ControlFlow;

/// An axis-aligned box. `min > max` on any axis means empty (see [`Aabb::EMPTY`]).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct Aabb {
    /// Lower corner.
    pub min: [f32; 3],
    /// Upper corner.
    pub max: [f32; 3],
}

const _: () = assert!(core::mem::size_of::<Aabb>() == 24);

impl Aabb {
    /// The empty box: the identity of [`Aabb::union`].
    pub const EMPTY: Aabb = Aabb {
        min: [f32::INFINITY; 3],
        max: [f32::NEG_INFINITY; 3],
    };

    /// The box `[min, max]`.
    #[inline]
    pub const fn new(min: [f32; 3], max: [f32; 3]) -> Aabb {
        Aabb { min, max }
    }

    /// The degenerate box holding one point.
    #[inline]
    pub const fn from_point(p: [f32; 3]) -> Aabb {
        Aabb { min: p, max: p }
    }

    /// `true` if the box contains no point (some `min > max`, or a NaN bound).
    #[inline]
    pub fn is_empty(&self) -> bool {
        !(self.min[0] <= self.max[0] && self.min[1] <= self.max[1] && self.min[2] <= self.max[2])
    }

    /// The smallest box containing both boxes.
    #[inline]
    pub fn union(&self, other: &Aabb) -> Aabb {
        Aabb {
            min: [
                self.min[0].min(other.min[0]),
                self.min[1].min(other.min[1]),
                self.min[2].min(other.min[2]),
            ],
            max: [
                self.max[0].max(other.max[0]),
                self.max[1].max(other.max[1]),
                self.max[2].max(other.max[2]),
            ],
        }
    }

    /// The smallest box containing this box and `p`.
    #[inline]
    pub fn grow(&self, p: [f32; 3]) -> Aabb {
        self.union(&Aabb::from_point(p))
    }

    /// The box grown by `margin` on every side.
    #[inline]
    pub fn expand(&self, margin: f32) -> Aabb {
        Aabb {
            min: [
                self.min[0] - margin,
                self.min[1] - margin,
                self.min[2] - margin,
            ],
            max: [
                self.max[0] + margin,
                self.max[1] + margin,
                self.max[2] + margin,
            ],
        }
    }

    /// The box with every bound moved outward by one ulp.
    ///
    /// Builders store node bounds rounded out: a ray travelling exactly in a face plane of a
    /// node box (a zero direction component, as axis-aligned camera rays have) then sees the
    /// plane strictly inside the slab, so the slab test keeps the node instead of producing
    /// an empty interval from `0 · (1/0)`.
    #[inline]
    pub fn round_out(&self) -> Aabb {
        Aabb {
            min: [
                self.min[0].next_down(),
                self.min[1].next_down(),
                self.min[2].next_down(),
            ],
            max: [
                self.max[0].next_up(),
                self.max[1].next_up(),
                self.max[2].next_up(),
            ],
        }
    }

    /// The centre point.
    #[inline]
    pub fn centroid(&self) -> [f32; 3] {
        [
            0.5 * (self.min[0] + self.max[0]),
            0.5 * (self.min[1] + self.max[1]),
            0.5 * (self.min[2] + self.max[2]),
        ]
    }

    /// Half the surface area (`dx·dy + dy·dz + dz·dx`); 0 for an empty box.
    #[inline]
    pub fn half_area(&self) -> f32 {
        if self.is_empty() {
            return 0.0;
        }
        let d = [
            self.max[0] - self.min[0],
            self.max[1] - self.min[1],
            self.max[2] - self.min[2],
        ];
        d[0] * d[1] + d[1] * d[2] + d[2] * d[0]
    }

    /// Squared Euclidean distance from `p` to the box (0 inside).
    #[inline]
    pub fn distance2_to_point(&self, p: [f32; 3]) -> f32 {
        let dx = (self.min[0] - p[0]).max(p[0] - self.max[0]).max(0.0);
        let dy = (self.min[1] - p[1]).max(p[1] - self.max[1]).max(0.0);
        let dz = (self.min[2] - p[2]).max(p[2] - self.max[2]).max(0.0);
        dx * dx + dy * dy + dz * dz
    }

    /// `true` if the (closed) boxes share a point.
    #[inline]
    pub fn overlaps(&self, other: &Aabb) -> bool {
        self.min[0] <= other.max[0]
            && other.min[0] <= self.max[0]
            && self.min[1] <= other.max[1]
            && other.min[1] <= self.max[1]
            && self.min[2] <= other.max[2]
            && other.min[2] <= self.max[2]
    }
}

/// One node of the flattened hierarchy, 32 bytes, GPU-visible.
///
/// `bounds` are conservative: the builder rounds them out by one ulp ([`Aabb::round_out`]).
///
/// - inner node: `count == 0`, `link` = skip index (the first node after this subtree; equal to
///   the node count for the last subtree). Its first child is the next node.
/// - leaf: `count ≥ 1` primitives in slots `link .. link + count`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct BvhNode {
    /// Bounds of everything below this node.
    pub bounds: Aabb,
    /// Skip index (inner node) or first primitive slot (leaf).
    pub link: u32,
    /// Number of primitives (leaf) or 0 (inner node).
    pub count: u32,
}

const _: () = assert!(core::mem::size_of::<BvhNode>() == 32);

impl BvhNode {
    /// An inner node whose subtree ends just before node `skip`.
    #[inline]
    pub const fn inner(bounds: Aabb, skip: u32) -> BvhNode {
        BvhNode {
            bounds,
            link: skip,
            count: 0,
        }
    }

    /// A leaf holding the `count ≥ 1` primitive slots starting at `first`.
    #[inline]
    pub const fn leaf(bounds: Aabb, first: u32, count: u32) -> BvhNode {
        BvhNode {
            bounds,
            link: first,
            count,
        }
    }

    /// `true` for a leaf.
    #[inline]
    pub const fn is_leaf(&self) -> bool {
        self.count != 0
    }
}

/// What a traversal does at each node and primitive. Implemented by the ray and range
/// queries in this crate; implement it for any other query over the same hierarchy.
pub trait BvhVisitor {
    /// Whether to descend into a node with these bounds (for a leaf: whether to visit its
    /// primitives). Must be conservative: returning `false` prunes everything below.
    fn enter(&mut self, bounds: &Aabb) -> bool;

    /// Visits the primitive in `slot`; `Break` ends the traversal at once.
    fn primitive(&mut self, slot: u32) -> ControlFlow<()>;
}

/// Stackless traversal of `nodes` (as laid out by the builder), calling `visitor` for every
/// entered node and every primitive of every entered leaf. Returns `Break` if the visitor
/// stopped it.
///
/// Terminates on any input: the node index strictly increases, even for a corrupt skip index.
pub fn traverse<V: BvhVisitor>(nodes: &[BvhNode], visitor: &mut V) -> ControlFlow<()> {
    let mut cursor = BvhCursor::default();
    while let Some(slot) = next_slot(nodes, &mut cursor, |b: &Aabb| visitor.enter(b)) {
        if visitor.primitive(slot).is_break() {
            return ControlFlow::Break(());
        }
    }
    ControlFlow::Continue(())
}

/// Where a resumable traversal stands: the next node to test, and the slots `slot..end` of
/// the leaf being drained. Plain integers, so a shader keeps it in registers.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BvhCursor {
    /// Next node to test.
    pub node: u32,
    /// Next slot of the current leaf.
    pub slot: u32,
    /// One past the current leaf's last slot.
    pub end: u32,
}

/// The next primitive slot of an entered leaf, resuming at `cursor` (start from
/// `BvhCursor::default()`); `None` once the traversal is done. `enter` decides per node box
/// as in [`BvhVisitor::enter`]. This is the one implementation of the skip-pointer walk:
/// [`traverse`] is a loop over it, and GPU code calls it directly with a `move` closure (no
/// captured pointers, which rust-gpu cannot store).
///
/// Terminates on any input: the node index strictly increases, even for a corrupt skip index.
#[inline]
pub fn next_slot<E: FnMut(&Aabb) -> bool>(
    nodes: &[BvhNode],
    cursor: &mut BvhCursor,
    enter: E,
) -> Option<u32> {
    next_slot_before(nodes, nodes.len(), cursor, enter)
}

/// [`next_slot`] over the hierarchy that ends before node `end` (`min(end, nodes.len())`).
/// Several hierarchies can share one node array this way (a GPU binds one buffer for all
/// of a scene's materials): each starts its cursor at its own first node and ends at the
/// next one's, with skip indices counted in the shared array.
#[inline]
pub fn next_slot_before<E: FnMut(&Aabb) -> bool>(
    nodes: &[BvhNode],
    end: usize,
    cursor: &mut BvhCursor,
    mut enter: E,
) -> Option<u32> {
    let n = if end < nodes.len() { end } else { nodes.len() };
    // One exit, no `return` inside the loop: neighbouring GPU invocations leave it after
    // different numbers of iterations, and lavapipe runs that correctly only for a loop
    // whose every exit goes through its condition (see ARCHITECTURE.md, *Divergence*).
    let mut out = None;
    let mut done = false;
    while !done {
        if cursor.slot < cursor.end {
            out = Some(cursor.slot);
            cursor.slot += 1;
            done = true;
        } else if cursor.node as usize >= n {
            done = true;
        } else {
            let node = nodes[cursor.node as usize];
            let entered = enter(&node.bounds);
            cursor.node += 1;
            if node.is_leaf() {
                if entered {
                    cursor.slot = node.link;
                    cursor.end = node.link.wrapping_add(node.count).max(node.link);
                }
            } else if !entered && node.link > cursor.node {
                cursor.node = node.link;
            }
        }
    }
    out
}

/// The next slot of a leaf whose box lies within `radius` of `p` (conservatively, as in
/// [`for_each_near_point`]), resuming at `cursor`.
#[inline]
pub fn next_near_point(
    nodes: &[BvhNode],
    cursor: &mut BvhCursor,
    p: [f32; 3],
    radius: f32,
) -> Option<u32> {
    next_near_point_before(nodes, nodes.len(), cursor, p, radius)
}

/// [`next_near_point`] over the hierarchy that ends before node `end` (see
/// [`next_slot_before`]).
#[inline]
pub fn next_near_point_before(
    nodes: &[BvhNode],
    end: usize,
    cursor: &mut BvhCursor,
    p: [f32; 3],
    radius: f32,
) -> Option<u32> {
    let r = radius * (1.0 + RADIUS_SLACK);
    let r2 = r * r;
    next_slot_before(nodes, end, cursor, move |b: &Aabb| {
        b.distance2_to_point(p) <= r2
    })
}

/// Relative slack applied to query radii so that rounding in the box test can only add
/// candidates, never drop one.
pub const RADIUS_SLACK: f32 = 8.0 * f32::EPSILON;

struct NearPoint<F> {
    p: [f32; 3],
    r2: f32,
    f: F,
}

impl<F: FnMut(u32) -> ControlFlow<()>> BvhVisitor for NearPoint<F> {
    #[inline]
    fn enter(&mut self, bounds: &Aabb) -> bool {
        bounds.distance2_to_point(self.p) <= self.r2
    }

    #[inline]
    fn primitive(&mut self, slot: u32) -> ControlFlow<()> {
        (self.f)(slot)
    }
}

/// Calls `f(slot)` for every primitive in a leaf whose box lies within distance `radius` of
/// `p` (conservatively: radius × (1 + [`RADIUS_SLACK`])). The candidates are a superset of
/// the primitives within `radius`; `f` does the exact test. `f` returning `Break` stops.
///
/// This is the scratch lookup's query: build over tight segment boxes (z = 0) and pass the
/// shading point with z = 0.
#[inline]
pub fn for_each_near_point<F: FnMut(u32) -> ControlFlow<()>>(
    nodes: &[BvhNode],
    p: [f32; 3],
    radius: f32,
    f: F,
) -> ControlFlow<()> {
    let r = radius * (1.0 + RADIUS_SLACK);
    let mut visitor = NearPoint { p, r2: r * r, f };
    traverse(nodes, &mut visitor)
}

struct Overlapping<F> {
    query: Aabb,
    f: F,
}

impl<F: FnMut(u32) -> ControlFlow<()>> BvhVisitor for Overlapping<F> {
    #[inline]
    fn enter(&mut self, bounds: &Aabb) -> bool {
        bounds.overlaps(&self.query)
    }

    #[inline]
    fn primitive(&mut self, slot: u32) -> ControlFlow<()> {
        (self.f)(slot)
    }
}

/// Calls `f(slot)` for every primitive in a leaf whose box overlaps `query` (a superset of the
/// primitives whose own boxes overlap it). `f` returning `Break` stops.
#[inline]
pub fn for_each_overlapping<F: FnMut(u32) -> ControlFlow<()>>(
    nodes: &[BvhNode],
    query: &Aabb,
    f: F,
) -> ControlFlow<()> {
    let mut visitor = Overlapping { query: *query, f };
    traverse(nodes, &mut visitor)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// root(0..3) → [inner(1) → [leaf 2, leaf 3], leaf 4]: skip of node 1 is 4, of node 0 is 5.
    fn tiny() -> [BvhNode; 5] {
        let b = |x0: f32, x1: f32| Aabb::new([x0, 0.0, 0.0], [x1, 1.0, 1.0]);
        [
            BvhNode::inner(b(0.0, 3.0), 5),
            BvhNode::inner(b(0.0, 2.0), 4),
            BvhNode::leaf(b(0.0, 1.0), 0, 1),
            BvhNode::leaf(b(1.0, 2.0), 1, 1),
            BvhNode::leaf(b(2.0, 3.0), 2, 1),
        ]
    }

    fn collect(nodes: &[BvhNode], p: [f32; 3], r: f32) -> ([u32; 8], usize) {
        let mut out = [u32::MAX; 8];
        let mut n = 0;
        let _ = for_each_near_point(nodes, p, r, |s| {
            out[n] = s;
            n += 1;
            ControlFlow::Continue(())
        });
        (out, n)
    }

    #[test]
    fn skip_pointers_prune_subtrees() {
        let nodes = tiny();
        assert_eq!(
            collect(&nodes, [2.5, 0.5, 0.5], 0.1),
            (
                [
                    2,
                    u32::MAX,
                    u32::MAX,
                    u32::MAX,
                    u32::MAX,
                    u32::MAX,
                    u32::MAX,
                    u32::MAX
                ],
                1
            )
        );
        assert_eq!(collect(&nodes, [0.5, 0.5, 0.5], 0.1).1, 1);
        assert_eq!(collect(&nodes, [1.5, 0.5, 0.5], 10.0).1, 3);
        assert_eq!(collect(&nodes, [9.0, 0.5, 0.5], 1.0).1, 0);
    }

    #[test]
    fn break_stops_traversal() {
        let nodes = tiny();
        let mut seen = 0;
        let flow = for_each_near_point(&nodes, [1.5, 0.5, 0.5], 10.0, |_| {
            seen += 1;
            ControlFlow::Break(())
        });
        assert!(flow.is_break());
        assert_eq!(seen, 1);
    }

    #[test]
    fn empty_and_corrupt_hierarchies_terminate() {
        assert_eq!(collect(&[], [0.0; 3], 1.0).1, 0);
        // A skip index pointing backwards must not loop forever.
        let mut nodes = tiny();
        nodes[1].link = 0;
        let _ = collect(&nodes, [9.0, 0.5, 0.5], 0.1);
    }

    #[test]
    fn box_distance_and_overlap() {
        let b = Aabb::new([0.0; 3], [1.0; 3]);
        assert_eq!(b.distance2_to_point([0.5; 3]), 0.0);
        assert_eq!(b.distance2_to_point([2.0, 0.5, 0.5]), 1.0);
        assert_eq!(b.distance2_to_point([2.0, 2.0, 0.5]), 2.0);
        assert!(b.overlaps(&Aabb::new([1.0; 3], [2.0; 3])));
        assert!(!b.overlaps(&Aabb::new([1.5; 3], [2.0; 3])));
        assert!(Aabb::EMPTY.is_empty());
        assert!(!Aabb::from_point([f32::NAN; 3]).overlaps(&b));
        assert_eq!(Aabb::EMPTY.union(&b), b);
        assert_eq!(Aabb::EMPTY.half_area(), 0.0);
        assert_eq!(b.half_area(), 3.0);
    }
}
