//! A uniform grid over scratch space for the models' fixed radius (`CUTOFF_SIGMAS · σ`):
//! each cell lists the scratches whose segment box, grown by the grid's radius, overlaps
//! it, so "scratches within r of x0" for `r` up to that radius is one cell's short list
//! instead of a BVH descent. Larger radii (pixel footprints) go to the BVH it carries.
//! Built by `scratchwave_host::ScratchLookup::grid`.

use super::record::Scratch;
use super::set::{NearCursor, ScratchBvh, ScratchSet};
use bytemuck::{Pod, Zeroable};
use glam::Vec2;

/// The grid's placement. GPU-visible: 32 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GridHeader {
    /// Lower corner of cell (0, 0) (µm).
    pub origin: [f32; 2],
    /// Cell edge (µm).
    pub cell_um: f32,
    /// `1 / cell_um`.
    pub inv_cell: f32,
    /// Cells along x.
    pub nx: u32,
    /// Cells along y.
    pub ny: u32,
    /// The largest query radius the cell lists answer (µm); queries with a larger radius,
    /// and every query when this is not positive, go to the BVH.
    pub radius: f32,
    /// Where cell 0's list start is in `offsets` (0 unless several grids share one
    /// buffer, as on the GPU; see [`super::ScratchBvh`]).
    pub first_offset: u32,
}

const _: () = assert!(core::mem::size_of::<GridHeader>() == 32);

/// The kernel view of a scratch grid: cell `c = first_offset + iy·nx + ix` lists
/// `items[offsets[c]..offsets[c + 1]]`, indices into `scratches` (the BVH's slot order).
#[derive(Clone, Copy, Debug)]
pub struct ScratchGrid<'a> {
    /// Placement and answered radius.
    pub header: GridHeader,
    /// `nx·ny + 1` list starts.
    pub offsets: &'a [u32],
    /// Scratch indices, cell by cell.
    pub items: &'a [u32],
    /// The same scratches and hierarchy, for larger radii.
    pub bvh: ScratchBvh<'a>,
}

impl ScratchGrid<'_> {
    /// The list range of the cell holding `x0`; an empty range outside the grid (which
    /// covers every segment box grown by the radius, so nothing is near a point outside).
    #[inline]
    fn cell_range(&self, x0: Vec2) -> (u32, u32) {
        let h = &self.header;
        let fx = (x0.x - h.origin[0]) * h.inv_cell;
        let fy = (x0.y - h.origin[1]) * h.inv_cell;
        if !(fx >= 0.0 && fy >= 0.0 && fx < h.nx as f32 && fy < h.ny as f32) {
            return (0, 0);
        }
        let (ix, iy) = (fx as u32, fy as u32);
        if ix >= h.nx || iy >= h.ny {
            return (0, 0);
        }
        let c = h.first_offset as usize + (iy as usize) * (h.nx as usize) + ix as usize;
        // Index checks rather than `get`: an `Option<&u32>` is a pointer rust-gpu cannot
        // compare.
        if c + 1 >= self.offsets.len() {
            return (0, 0);
        }
        let (a, b) = (self.offsets[c], self.offsets[c + 1]);
        if a <= b { (a, b) } else { (0, 0) }
    }
}

impl ScratchGrid<'_> {
    /// The next scratch of `x0`'s cell within `radius` (see [`ScratchSet::next_near`]).
    fn next_in_cell(&self, cursor: &mut NearCursor, x0: Vec2, radius: f32) -> Option<Scratch> {
        // `node` marks a started walk (a fresh cursor is all zeros).
        if cursor.node == 0 {
            cursor.node = 1;
            let (a, b) = self.cell_range(x0);
            cursor.slot = a;
            cursor.end = b;
        }
        let mut found = None;
        while found.is_none() && cursor.slot < cursor.end {
            let k = cursor.slot as usize;
            cursor.slot += 1;
            if k < self.items.len() {
                let i = self.items[k] as usize;
                if i < self.bvh.scratches.len() {
                    let s = self.bvh.scratches[i];
                    if s.distance_to(x0) <= radius {
                        found = Some(s);
                    }
                }
            }
        }
        found
    }
}

impl ScratchSet for ScratchGrid<'_> {
    // One exit per function, no `return` inside a loop: the shape lavapipe runs correctly
    // when neighbouring invocations take different paths (a cell list here, the BVH there).
    fn next_near(&self, cursor: &mut NearCursor, x0: Vec2, radius: f32) -> Option<Scratch> {
        if radius <= self.header.radius {
            self.next_in_cell(cursor, x0, radius)
        } else {
            self.bvh.next_near(cursor, x0, radius)
        }
    }
}
