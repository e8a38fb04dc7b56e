//! # scratchwave-kernel
//!
//! The single definition of every formula in scratchwave: `#![no_std]`, no allocation, no
//! reachable panic, `f32` throughout. The same source compiles for the CPU (scalar, SIMD
//! and rayon backends) and for SPIR-V through rust-gpu.
//!
//! Conventions (see `ARCHITECTURE.md`): the local shading frame has `z` as the surface
//! normal; tangent-plane positions are in micrometres; `wi` (towards the light) and `wo`
//! (towards the viewer) point away from the surface; `xi = (wi + wo)_xy / λ` in 1/µm.
#![no_std]
#![cfg_attr(target_arch = "spirv", allow(internal_features))]

pub mod footprint;
pub mod fresnel;
pub mod lights;
pub mod math;
pub mod scratch;
pub mod table;

pub use glam;
pub use num_complex;
