//! # scratchwave-cpu
//!
//! The std side of the portable lookup structures and the CPU query interfaces:
//!
//! - [`bvh_build`]: binned-SAH builder for the kernel's flattened, stackless BVH
//!   ([`scratchwave_kernel::bvh`]);
//! - [`queries`]: the [`RayQueries`] and [`SegmentRadiusQuery`] traits, implemented here by
//!   the portable [`TriangleBvh`] / [`SegmentBvh`] and in `scratchwave-embree` by Embree;
//! - [`mod@reference`]: brute-force oracles; [`fixtures`]: seeded test scenes.

pub mod bvh_build;
pub mod fixtures;
pub mod mesh;
pub mod queries;
pub mod reference;
mod segment_bvh;
mod triangle_bvh;

pub use mesh::MeshError;
pub use queries::{Coherence, RayQueries, SegmentRadiusQuery};
pub use segment_bvh::SegmentBvh;
pub use triangle_bvh::TriangleBvh;
