//! Every material's scratch lookup in one set of buffers, as a GPU binds them: the BVH
//! nodes, scratches, grid offsets and grid items of all materials concatenated, with
//! skip indices, leaf slots, list starts and item values rebased to count in the shared
//! arrays, and one [`MaterialScratches`] record per material saying where its part lies
//! (rust-gpu cannot take sub-slices of a storage buffer). The kernel reads them through
//! [`SharedScratches`], with the same traversal as a lookup of its own.

use crate::scratch_lookup::{GridData, ScratchLookup};
use scratchwave_kernel::bvh::BvhNode;
use scratchwave_kernel::ghs::g1::G1Table;
use scratchwave_kernel::render::radiance::{MaterialScratches, SharedScratches};
use scratchwave_kernel::scratch::{GridHeader, Scratch};

/// Why the lookups cannot share buffers.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("the scratch lookups hold more than 2^32 - 1 {what} together")]
pub struct SharedScratchesError {
    /// What overflowed a `u32` index.
    pub what: &'static str,
}

/// The shared buffers ([`SharedScratchData::new`]).
#[derive(Clone, Debug, Default)]
pub struct SharedScratchData {
    /// One record per material.
    pub materials: Vec<MaterialScratches>,
    /// All BVH nodes.
    pub nodes: Vec<BvhNode>,
    /// All scratches in slot order.
    pub scratches: Vec<Scratch>,
    /// All grid list starts.
    pub offsets: Vec<u32>,
    /// All grid lists.
    pub items: Vec<u32>,
}

impl SharedScratchData {
    /// Concatenates `lookups[i]` (with its grid `grids[i]`, if any) for every material `i`.
    pub fn new(
        lookups: &[ScratchLookup],
        grids: &[Option<GridData>],
    ) -> Result<SharedScratchData, SharedScratchesError> {
        let mut out = SharedScratchData::default();
        let index = |n: usize, what: &'static str| {
            u32::try_from(n).map_err(|_| SharedScratchesError { what })
        };
        for (i, lookup) in lookups.iter().enumerate() {
            let node_base = index(out.nodes.len(), "BVH nodes")?;
            let slot_base = index(out.scratches.len(), "scratches")?;
            out.nodes.extend(lookup.nodes().iter().map(|n| {
                let mut n = *n;
                n.link = n
                    .link
                    .saturating_add(if n.is_leaf() { slot_base } else { node_base });
                n
            }));
            out.scratches.extend_from_slice(lookup.scratches());
            let end_node = index(out.nodes.len(), "BVH nodes")?;
            index(out.scratches.len(), "scratches")?;
            let grid = match grids.get(i).and_then(Option::as_ref) {
                Some(g) => {
                    let first_offset = index(out.offsets.len(), "grid cells")?;
                    let item_base = index(out.items.len(), "grid entries")?;
                    out.offsets
                        .extend(g.offsets.iter().map(|&o| o.saturating_add(item_base)));
                    out.items
                        .extend(g.items.iter().map(|&s| s.saturating_add(slot_base)));
                    index(out.items.len(), "grid entries")?;
                    GridHeader {
                        first_offset,
                        ..g.header
                    }
                }
                None => GridHeader {
                    radius: -1.0,
                    ..GridHeader::default()
                },
            };
            out.materials.push(MaterialScratches {
                grid,
                first_node: node_base,
                end_node,
                pad: [0; 2],
            });
        }
        Ok(out)
    }

    /// The kernel view (with the builtin G1 table as a slice, [`G1Table::FLAT`]).
    pub fn view(&self) -> SharedScratches<'_> {
        SharedScratches {
            materials: &self.materials,
            nodes: &self.nodes,
            scratches: &self.scratches,
            offsets: &self.offsets,
            items: &self.items,
            g1: G1Table::FLAT,
        }
    }
}
