//! # scratchwave-embree
//!
//! Embree 4 behind a small safe API, for the CPU renderer and the conformance suite:
//!
//! - [`Device`]: loads Embree (from the path the build script found: `.deps/embree` or
//!   `$EMBREE_DIR`), checks the version (≥ 4.3) and the hit-record layout once per process;
//! - [`SceneBuilder`] → [`Scene`]: triangle meshes; closest hit for single rays and packets
//!   of 4/8/16, occlusion for shadow rays. Implements [`scratchwave_host::RayQueries`];
//! - [`SegmentIndex`]: "all scratch segments within `r` of a point" (USER geometry +
//!   `rtcPointQuery`). Implements [`scratchwave_host::SegmentRadiusQuery`].
//!
//! [`c_reference`] builds and drives a small C program calling the same Embree on the same
//! rays, to measure the wrapper's overhead and check that both find the same hits.
//!
//! All results are raw hits; shading stays in the kernel. Committed scenes and segment
//! indices are `Send + Sync` for rayon.
//!
//! The FFI is hand-written ([`ffi`]) against the Embree 4.4 ABI; see `ARCHITECTURE.md` for
//! why neither `embree4-rs` nor `embree4-sys` is used.

pub mod c_reference;
mod device;
pub mod ffi;
mod open;
mod scene;
mod segments;

pub use device::{Device, Error};
pub use scene::{BuildQuality, Scene, SceneBuilder};
pub use segments::SegmentIndex;
