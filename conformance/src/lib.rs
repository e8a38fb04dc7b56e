//! # scratchwave-conformance
//!
//! The `scratchwave` command line (`run`, `table`, `footprint`) and the library behind it:
//! strict JSON spec readers that name the offending field, `%.9g` output, and the
//! conformance run that compares every backend with the committed high-precision
//! references.

pub mod backends;
pub mod error;
pub mod format;
pub mod generate;
pub mod json;
pub mod light_case;
pub mod light_spec;
pub mod run;
pub mod spec;

pub use error::SpecError;
