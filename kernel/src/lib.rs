//! # scratchwave-kernel
//!
//! The single definition of every formula in scratchwave: `#![no_std]`, no allocation, no
//! reachable panic, `f32` throughout. The same source compiles for the CPU (scalar, SIMD
//! and rayon backends) and for SPIR-V through rust-gpu.
//!
//! Conventions (see `ARCHITECTURE.md`): the local shading frame has `z` as the surface
//! normal; tangent-plane positions are in micrometres; `wi` (towards the light) and `wo`
//! (towards the viewer) point away from the surface; `xi = (wi + wo)_xy / λ` in 1/µm.
//!
//! ```
//! use scratchwave_kernel::scratch::{Profile, Scratch, ScratchSlice};
//! use scratchwave_kernel::material::Material;
//! use scratchwave_kernel::table::{evaluate, Model, TableParams, TableQuery};
//!
//! // One 2 µm wide, 0.3 µm deep V-groove through the shading point, along x.
//! let scratches = [Scratch::from_endpoints([-200.0, 0.0], [200.0, 0.0], 2.0, 0.3, Profile::Triangle)];
//! let params = TableParams { model: Model::Werner as u32, sigma_um: 10.0, ..Default::default() };
//! // Light from the normal, viewer tilted across the scratch: first-order diffraction.
//! let q = TableQuery {
//!     wi: [0.0, 0.0, 1.0], wo: [0.0, 0.2, 0.98], lambda_nm: 550.0, x: [0.0, 0.0],
//!     material: Material::constant(0.9), ..Default::default()
//! };
//! let f = evaluate(&params, &q, &ScratchSlice { scratches: &scratches });
//! assert!(f > 0.0 && f.is_finite()); // BRDF in 1/sr, without the cosine
//! ```
#![no_std]
#![cfg_attr(target_arch = "spirv", allow(internal_features))]

#[macro_use]
pub mod gpu_enum;

pub mod bsdf;
pub mod bvh;
pub mod conductor;
pub mod conductor_data;
pub mod footprint;
pub mod fresnel;
pub mod ghs;
pub mod lane;
pub mod lights;
pub mod material;
pub mod math;
pub mod ray;
pub mod render;
pub mod sampling;
pub mod scratch;
pub mod segment2d;
pub mod table;
pub mod units;

pub use glam;
pub use num_complex;
