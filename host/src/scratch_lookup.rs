//! The scratch lookup the models query: the kernel's flattened BVH over segment boxes,
//! built here once per scratch set and traversed by the same kernel code on CPU and GPU
//! (Werner 2017 §5: "all segments within a radius of x0").

use crate::bvh_build::{BuildOptions, build};
use scratchwave_kernel::bvh::BvhNode;
use scratchwave_kernel::scratch::response::CUTOFF_SIGMAS;
use scratchwave_kernel::scratch::{Scratch, ScratchBvh};

/// Scratches in slot order with their hierarchy.
#[derive(Clone, Debug, Default)]
pub struct ScratchLookup {
    nodes: Vec<BvhNode>,
    scratches: Vec<Scratch>,
    ids: Vec<u32>,
}

impl ScratchLookup {
    /// Builds the hierarchy, shaping it for queries of the models' radius
    /// (`CUTOFF_SIGMAS · σ`). Any radius works afterwards.
    pub fn new(scratches: &[Scratch], sigma: f32) -> ScratchLookup {
        let boxes: Vec<_> = scratches.iter().map(|s| s.segment().bounds()).collect();
        let options = BuildOptions {
            cost_margin: CUTOFF_SIGMAS * sigma.max(0.0),
            ..BuildOptions::default()
        };
        let bvh = build(&boxes, &options);
        ScratchLookup {
            scratches: bvh.permute(scratches),
            nodes: bvh.nodes,
            ids: bvh.prim_order,
        }
    }

    /// The kernel view (what the models and the GPU upload take).
    pub fn set(&self) -> ScratchBvh<'_> {
        ScratchBvh {
            nodes: &self.nodes,
            scratches: &self.scratches,
        }
    }

    /// Nodes in depth-first order.
    pub fn nodes(&self) -> &[BvhNode] {
        &self.nodes
    }

    /// Scratches in slot order.
    pub fn scratches(&self) -> &[Scratch] {
        &self.scratches
    }

    /// Input index of each slot.
    pub fn ids(&self) -> &[u32] {
        &self.ids
    }
}
