//! # scratchwave-cpu
//!
//! The CPU backend: kernel functions over many inputs, two paths, one source:
//! * **scalar** ([`Backend::Scalar`]): a plain loop calling the kernel function per input;
//! * **simd** ([`Backend::Simd`]): rayon over chunks of inputs, each chunk run through a copy
//!   of the same kernel function compiled for AVX2 + FMA (`#[target_feature]`
//!   multiversioning with run-time detection, baseline x86-64 otherwise). No formula is
//!   written twice: the chunk function is generic over the kernel closure, so the compiler
//!   instantiates the kernel code inside the AVX2 context.
//!
//! [`table`] evaluates BRDF, GHS and footprint tables, [`ghs`] GHS batches and directional
//! albedo; [`Cpu`] implements [`scratchwave_host::TableBackend`]. The shared lookup
//! structures (BVH builder, scratch lookup) live in `scratchwave-host`.

mod cpu_backend;
pub mod ghs;
pub mod lanes;
pub mod parallel;
pub mod table;

pub use cpu_backend::Cpu;
pub use parallel::Backend;
pub use table::{evaluate_ghs_table, evaluate_table, evaluate_table_counted, footprint_table};
