//! # scratchwave-conformance
//!
//! The `scratchwave` command line (`run`, `table`, `footprint`, `light`, `render`, the
//! reference commands of [`reference_cmd`]) and the library
//! behind it: `%.9g` output, the conformance recipes (seeded table and light cases) and the
//! conformance run that compares every backend with the committed high-precision
//! references. The spec readers are `scratchwave-spec`; the backend interface is
//! `scratchwave-host`'s `TableBackend`.

pub mod backends;
pub mod format;
pub mod generate;
pub mod light_case;
pub mod light_spec;
pub mod reference_cmd;
pub mod run;
pub mod scene_spirv;
pub mod scenes;
