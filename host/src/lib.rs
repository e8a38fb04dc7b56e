//! # scratchwave-host
//!
//! The std-side structures that every scratchwave backend shares, so that no backend
//! depends on another:
//!
//! - [`bvh_build`]: binned-SAH builder for the kernel's flattened, stackless BVH
//!   ([`scratchwave_kernel::bvh`]); [`scratch_lookup`]: the scratch set the models query;
//!   [`TriangleBvh`] and [`SegmentBvh`]: the portable ray and segment-radius structures;
//! - [`queries`]: the [`RayQueries`] and [`SegmentRadiusQuery`] traits, implemented here by
//!   the portable structures and in `scratchwave-embree` by Embree; [`mesh`]: mesh
//!   validation;
//! - [`batch`]: the table, light and footprint batches a backend evaluates, and
//!   [`backend`]: the [`TableBackend`] interface with its typed [`BackendError`];
//! - [`rng`]: the seeded random stream; [`generate`]: the random-scratch generator of the
//!   conformance recipes; [`pattern`]: seeded scene scratch patterns (straight, arcs,
//!   random walks; brushed and circular orientations) split into segments.

pub mod backend;
pub mod batch;
pub mod bvh_build;
pub mod generate;
pub mod mesh;
pub mod pattern;
pub mod queries;
pub mod rng;
pub mod scratch_lookup;
mod segment_bvh;
pub mod shared_scratches;
mod triangle_bvh;

pub use backend::{BackendError, TableBackend};
pub use batch::{CaseBatch, FootprintBatch, FootprintRow, LightBatch, TableBatch};
pub use mesh::MeshError;
pub use queries::{Coherence, RayQueries, SegmentRadiusQuery};
pub use scratch_lookup::{GridData, ScratchLookup};
pub use segment_bvh::SegmentBvh;
pub use shared_scratches::{SharedScratchData, SharedScratchesError};
pub use triangle_bvh::TriangleBvh;
