//! The portable scratch-segment lookup: the kernel's radius query over a hierarchy of tight
//! z = 0 segment boxes.

use crate::bvh_build::{BuildOptions, build};
use crate::mesh::{MeshError, check_count};
use crate::queries::SegmentRadiusQuery;
use core::ops::ControlFlow;
use scratchwave_kernel::bvh::BvhNode;
use scratchwave_kernel::segment2d::{Segment2, for_each_segment_within};

/// Segments with their flattened hierarchy; implements [`SegmentRadiusQuery`] with the
/// kernel's traversal.
#[derive(Clone, Debug)]
pub struct SegmentBvh {
    nodes: Vec<BvhNode>,
    segments: Vec<Segment2>,
    segment_ids: Vec<u32>,
}

impl SegmentBvh {
    /// Builds over `segments` with an SAH tuned for queries of about `typical_radius`
    /// (any radius works; this only shapes the tree). Ids are positions in `segments`.
    pub fn new(segments: &[Segment2], typical_radius: f32) -> Result<SegmentBvh, MeshError> {
        check_count(segments.len())?;
        let boxes: Vec<_> = segments.iter().map(Segment2::bounds).collect();
        let options = BuildOptions {
            cost_margin: typical_radius.max(0.0),
            ..BuildOptions::default()
        };
        let bvh = build(&boxes, &options);
        Ok(SegmentBvh {
            segments: bvh.permute(segments),
            nodes: bvh.nodes,
            segment_ids: bvh.prim_order,
        })
    }

    /// Nodes in depth-first order.
    pub fn nodes(&self) -> &[BvhNode] {
        &self.nodes
    }

    /// Segments in slot order.
    pub fn segments(&self) -> &[Segment2] {
        &self.segments
    }

    /// Input id of each slot.
    pub fn segment_ids(&self) -> &[u32] {
        &self.segment_ids
    }
}

impl SegmentRadiusQuery for SegmentBvh {
    fn segments_within(&self, p: [f32; 2], radius: f32, out: &mut Vec<u32>) {
        out.clear();
        let _ = for_each_segment_within(&self.nodes, &self.segments, p, radius, |slot| {
            out.push(self.segment_ids[slot as usize]);
            ControlFlow::Continue(())
        });
    }
}
