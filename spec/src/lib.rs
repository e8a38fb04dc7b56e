//! # scratchwave-spec
//!
//! Strict readers for scratchwave's JSON inputs: every missing, unknown, mistyped or
//! out-of-range field is a [`SpecError`] naming its JSON path (e.g. `queries[3].wi`).
//!
//! - [`json`]: the field-checking object reader and number conversions;
//! - [`range`]: the accepted ranges of σ, λ, scratch width and depth, footprint axes;
//! - [`spec`]: table and footprint specs → the batches of `scratchwave-host`;
//! - [`light`]: the light spec of `scratchwave light` → kernel light records;
//! - [`material`]: a scene material (model, reflectance, options, base, scratches) → the
//!   kernel's shading record, for the scene reader and the C/Python bindings;
//! - [`scratches`]: a material's scratch sources (inline, files, seeded patterns) → scratch
//!   segments (formats in `docs/scratches.md`).

pub mod error;
pub mod json;
pub mod light;
pub mod material;
pub mod range;
pub mod scratches;
pub mod spec;

pub use error::SpecError;
