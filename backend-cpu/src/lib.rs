//! # scratchwave-cpu
//!
//! The CPU side of scratchwave.
//!
//! Running kernel functions over many inputs — two paths, one source:
//! * **scalar** ([`Backend::Scalar`]): a plain loop calling the kernel function per input;
//! * **simd** ([`Backend::Simd`]): rayon over chunks of inputs, each chunk run through a copy
//!   of the same kernel function compiled for AVX2 + FMA (`#[target_feature]`
//!   multiversioning with run-time detection, baseline x86-64 otherwise). No formula is
//!   written twice: the chunk function is generic over the kernel closure, so the compiler
//!   instantiates the kernel code inside the AVX2 context.
//!
//! The std side of the portable lookup structures and the CPU query interfaces:
//!
//! - [`bvh_build`]: binned-SAH builder for the kernel's flattened, stackless BVH
//!   ([`scratchwave_kernel::bvh`]); [`scratch_lookup`]: the scratch set the models query;
//! - [`queries`]: the [`RayQueries`] and [`SegmentRadiusQuery`] traits, implemented here by
//!   the portable [`TriangleBvh`] / [`SegmentBvh`] and in `scratchwave-embree` by Embree;
//! - [`mod@reference`]: brute-force oracles; [`fixtures`]: seeded test scenes;
//! - [`light_reference`], [`light_mc`], [`light_configs`]: the area-light quadrature
//!   reference, Monte Carlo estimator and seeded sweep configurations.

pub mod bvh_build;
pub mod fixtures;
pub mod ghs;
pub mod light_configs;
pub mod light_mc;
pub mod light_reference;
pub mod mesh;
pub mod parallel;
pub mod queries;
pub mod reference;
pub mod scratch_lookup;
mod segment_bvh;
pub mod table;
mod triangle_bvh;
pub mod vec64;

pub use mesh::MeshError;
pub use parallel::Backend;
pub use queries::{Coherence, RayQueries, SegmentRadiusQuery};
pub use scratch_lookup::ScratchLookup;
pub use segment_bvh::SegmentBvh;
pub use table::{FootprintRow, evaluate_table, footprint_table};
pub use triangle_bvh::TriangleBvh;
