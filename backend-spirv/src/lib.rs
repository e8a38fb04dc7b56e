//! # scratchwave-spirv
//!
//! Runs scratchwave's kernel functions as rust-gpu compute shaders on Vulkan through wgpu.
//!
//! - `shader/` (`scratchwave-spirv-shader`): the `#[spirv(compute)]` entry points, thin
//!   wrappers over the kernel. `build.rs` compiles it to SPIR-V on the pinned nightly
//!   (`nightly-2026-08-15`, installed by `scripts/setup.sh`) and embeds the module as
//!   [`SHADER_SPV`]; the workspace itself builds on stable.
//! - [`Gpu`]: the Vulkan device. A discrete or integrated GPU when present, else lavapipe
//!   (Mesa's CPU driver, `mesa-vulkan-drivers`); `SCRATCHWAVE_ADAPTER=lavapipe|gpu|<name
//!   substring>` chooses explicitly ([`AdapterChoice`]). No Vulkan at all is a
//!   [`SpirvError::NoVulkan`] naming the packages to install, never a panic.
//! - [`Gpu::dispatch`]: the generic path — `Pod` input buffers in, one output element per
//!   invocation out, chunked to the device limits, with [`Timings`] split into upload,
//!   dispatch and readback, and the slices the dispatch was cut into.
//! - Typed entry points on top of it, each with the CPU function it must agree with:
//!   [`Gpu::evaluate_table`] and [`Gpu::footprint_table`] (the CPU backend's
//!   `evaluate_table` / `footprint_table`), [`Gpu::math_probe`] / [`math_probe_cpu`],
//!   [`Gpu::lobe_probe`] (the shader crate's `lobe_probe::evaluate` on the CPU);
//!   [`Gpu`] implements `scratchwave_host::TableBackend` for the conformance run.
//! - [`Gpu::render_scene`]: a whole frame, the kernel's per-pixel light loop
//!   (`kernel::render::radiance::pixel_radiance`) over a [`SceneInput`].
//! - Every dispatch is submitted in slices of about 100 ms ([`Pace`]), within a memory
//!   budget when one is set ([`Gpu::with_memory_budget`]); a damaged shader module is
//!   refused before the driver sees it ([`SpirvError::BadShader`]).

mod adapter;
mod dispatch;
mod error;
mod gpu;
mod module;
mod no_contraction;
mod probe;
mod scene;
mod table;
mod table_backend;

pub use adapter::{ADAPTER_ENV, AdapterChoice, AdapterKind, AdapterSummary};
pub use dispatch::{Dispatched, Input, Pace, Timings};
pub use error::{Result, SpirvError};
pub use gpu::{Gpu, SHADER_SPV, entry_points};
pub use probe::math_probe_cpu;
pub use scene::SceneInput;
pub use scratchwave_spirv_shader::FootprintParams;
pub use scratchwave_spirv_shader::probe::{MathFunction, ProbeParams};
