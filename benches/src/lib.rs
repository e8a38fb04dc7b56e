//! scratchwave-benches: benches and speed-vs-accuracy charts (see ARCHITECTURE.md).
//!
//! * `light_chart` (binary): error against cost of the area-light integrals — closed form
//!   with exact Si, Eq. 29's Si and the fast Si, one band or Gauss–Hermite bands, and Monte
//!   Carlo with N samples — over a seeded sweep, against the adaptive reference.
//! * `benches/lights.rs`: timing of the closed forms per light kind and method.

pub mod svg;
