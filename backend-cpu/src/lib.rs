//! # scratchwave-cpu
//!
//! Runs kernel functions over many inputs on the CPU. Two paths, one source:
//! * **scalar** ([`Backend::Scalar`]): a plain loop calling the kernel function per input;
//! * **simd** ([`Backend::Simd`]): rayon over chunks of inputs, each chunk run through a copy
//!   of the same kernel function compiled for AVX2 + FMA (`#[target_feature]`
//!   multiversioning with run-time detection, baseline x86-64 otherwise). No formula is
//!   written twice: the chunk function is generic over the kernel closure, so the compiler
//!   instantiates the kernel code inside the AVX2 context.

pub mod light_configs;
pub mod light_mc;
pub mod light_reference;
pub mod parallel;
pub mod table;

pub use parallel::Backend;
pub use table::{FootprintRow, evaluate_table, footprint_table};
