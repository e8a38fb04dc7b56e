//! The scratch lookup the models query: the kernel's flattened BVH over segment boxes,
//! built here once per scratch set and traversed by the same kernel code on CPU and GPU
//! (Werner 2017 §5: "all segments within a radius of x0").

use crate::bvh_build::{BuildOptions, build};
use scratchwave_kernel::bvh::{BvhNode, RADIUS_SLACK};
use scratchwave_kernel::scratch::response::CUTOFF_SIGMAS;
use scratchwave_kernel::scratch::{GridHeader, Scratch, ScratchBvh, ScratchGrid};

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
        ScratchBvh::new(&self.nodes, &self.scratches)
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

    /// A uniform grid over these scratches for queries of radius up to
    /// `CUTOFF_SIGMAS · sigma` ([`ScratchGrid`]), or `None` when there is nothing to grid or
    /// it would need more than `max_entries` list entries plus cells (then the BVH serves
    /// every query). Cells are `4 ×` the radius wide: a query scans the segments whose box,
    /// grown by the radius, overlaps its cell.
    pub fn grid(&self, sigma: f32, max_entries: usize) -> Option<GridData> {
        let radius = CUTOFF_SIGMAS * sigma;
        let max_entries = max_entries.min(u32::MAX as usize);
        if !(radius > 0.0 && radius.is_finite()) || self.scratches.is_empty() {
            return None;
        }
        // Grown so that rounding in the cell test can only add candidates.
        let grow = radius * (1.0 + 4.0 * RADIUS_SLACK);
        let boxes: Vec<[f32; 4]> = self
            .scratches
            .iter()
            .map(|s| {
                let b = s.segment().bounds();
                [
                    b.min[0] - grow,
                    b.min[1] - grow,
                    b.max[0] + grow,
                    b.max[1] + grow,
                ]
            })
            .collect();
        let (mut lo, mut hi) = ([f32::INFINITY; 2], [f32::NEG_INFINITY; 2]);
        for b in &boxes {
            lo = [lo[0].min(b[0]), lo[1].min(b[1])];
            hi = [hi[0].max(b[2]), hi[1].max(b[3])];
        }
        if !(lo[0].is_finite() && lo[1].is_finite() && hi[0].is_finite() && hi[1].is_finite()) {
            return None;
        }
        let cell = 4.0 * radius;
        let inv = 1.0 / cell;
        let nx = (((hi[0] - lo[0]) * inv).floor() as usize).saturating_add(1);
        let ny = (((hi[1] - lo[1]) * inv).floor() as usize).saturating_add(1);
        let cells = nx.checked_mul(ny)?;
        if cells > max_entries || nx > u32::MAX as usize || ny > u32::MAX as usize {
            return None;
        }
        let span = |b: &[f32; 4]| {
            let c =
                |v: f32, o: f32, n: usize| (((v - o) * inv).floor().max(0.0) as usize).min(n - 1);
            (
                c(b[0], lo[0], nx),
                c(b[2], lo[0], nx),
                c(b[1], lo[1], ny),
                c(b[3], lo[1], ny),
            )
        };
        // Counting sort: sizes, prefix sums, then the lists in slot order.
        let mut offsets = vec![0u32; cells + 1];
        let mut total = 0usize;
        for b in &boxes {
            let (x0, x1, y0, y1) = span(b);
            total += (x1 - x0 + 1) * (y1 - y0 + 1);
            if total + cells > max_entries {
                return None;
            }
            for y in y0..=y1 {
                for x in x0..=x1 {
                    offsets[y * nx + x + 1] += 1;
                }
            }
        }
        for c in 0..cells {
            offsets[c + 1] += offsets[c];
        }
        let mut fill: Vec<u32> = offsets[..cells].to_vec();
        let mut items = vec![0u32; total];
        for (i, b) in boxes.iter().enumerate() {
            let (x0, x1, y0, y1) = span(b);
            for y in y0..=y1 {
                for x in x0..=x1 {
                    let c = y * nx + x;
                    items[fill[c] as usize] = i as u32;
                    fill[c] += 1;
                }
            }
        }
        Some(GridData {
            header: GridHeader {
                origin: lo,
                cell_um: cell,
                inv_cell: inv,
                nx: nx as u32,
                ny: ny as u32,
                radius,
                first_offset: 0,
            },
            offsets,
            items,
        })
    }
}

/// The host storage of a scratch grid ([`ScratchLookup::grid`]).
#[derive(Clone, Debug, Default)]
pub struct GridData {
    /// Placement and answered radius.
    pub header: GridHeader,
    /// List starts, one per cell plus the end.
    pub offsets: Vec<u32>,
    /// Scratch slots, cell by cell.
    pub items: Vec<u32>,
}

impl GridData {
    /// The kernel view over `lookup` (the lookup this grid was built from).
    pub fn set<'a>(&'a self, lookup: &'a ScratchLookup) -> ScratchGrid<'a> {
        ScratchGrid {
            header: self.header,
            offsets: &self.offsets,
            items: &self.items,
            bvh: lookup.set(),
        }
    }

    /// Bytes held.
    pub fn bytes(&self) -> usize {
        4 * (self.offsets.len() + self.items.len())
    }
}
