//! # scratchwave-testkit
//!
//! Test and reference code, kept out of the library crates (`publish = false`; a
//! dev-dependency of the backends, a dependency of the conformance and bench tooling):
//!
//! - [`fixtures`]: seeded meshes, rays, segments and points;
//! - [`mod@reference`]: brute-force oracles for the ray and segment queries;
//! - [`light_reference`], [`light_mc`], [`light_configs`]: the area-light quadrature
//!   reference (f64, adaptive), the Monte Carlo estimator and the seeded sweep
//!   configurations;
//! - [`heightfield`]: the exact heightfield golden data (`reference/golden/heightfield.json`)
//!   and the kernel's Werner values at its directions, for the test and the chart of
//!   Werner's frozen window and summed crossings.

pub mod dvec;
pub mod fixtures;
pub mod heightfield;
pub mod light_configs;
pub mod light_mc;
pub mod light_reference;
pub mod reference;
