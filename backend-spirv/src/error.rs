//! The one error type of the SPIR-V backend.

use thiserror::Error;

/// What can go wrong between asking for a Vulkan device and reading results back.
/// The kernel itself cannot fail; every variant is about the machine or the request.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum SpirvError {
    /// An environment variable the backend reads holds a value it cannot use.
    #[error("{name}: must be {expected}, got {value:?}")]
    BadEnv {
        /// The variable.
        name: &'static str,
        /// Its value as set.
        value: String,
        /// What it accepts.
        expected: &'static str,
    },
    /// No Vulkan driver answered: the loader (`libvulkan1`) or every ICD is missing.
    #[error(
        "no Vulkan device found: install the Vulkan loader and the lavapipe CPU driver \
         (Debian/Ubuntu: `apt install mesa-vulkan-drivers libvulkan1`, or run scripts/setup.sh; \
         `vulkaninfo --summary` from `vulkan-tools` shows what the loader finds); \
         the CPU backends work without Vulkan"
    )]
    NoVulkan,
    /// `SCRATCHWAVE_ADAPTER` (or an explicit choice) matched none of the adapters.
    #[error(
        "no Vulkan adapter matches {wanted}; available: {available} \
         (`vulkaninfo --summary` lists them)"
    )]
    NoMatchingAdapter {
        /// The choice as the user spelled it.
        wanted: String,
        /// The adapters that were found, `name (kind)`, comma-separated.
        available: String,
    },
    /// The adapter refused to create a device.
    #[error("creating a device on {adapter}: {source} (diagnose: `vulkaninfo --summary`)")]
    RequestDevice {
        /// Adapter name.
        adapter: String,
        /// wgpu's reason.
        source: wgpu::RequestDeviceError,
    },
    /// The adapter lacks a feature the backend needs.
    #[error("{adapter} lacks the wgpu feature {feature}")]
    MissingFeature {
        /// Adapter name.
        adapter: String,
        /// The feature's name.
        feature: &'static str,
    },
    /// The entry point is not in the embedded shader module.
    #[error("no entry point `{name}` in the shader module; it has: {available}")]
    UnknownEntryPoint {
        /// The name asked for.
        name: String,
        /// The module's entry points, comma-separated.
        available: String,
    },
    /// An input buffer does not fit the dispatch.
    #[error("input {index} of `{entry}`: {problem}")]
    BadInput {
        /// Entry point.
        entry: String,
        /// Position of the input in the list passed to the dispatch (= its binding).
        index: usize,
        /// What is wrong with it.
        problem: String,
    },
    /// The output element type cannot be bound as a storage buffer.
    #[error("output of `{entry}`: element size {size} bytes is not a non-zero multiple of 4")]
    BadOutput {
        /// Entry point.
        entry: String,
        /// `size_of` the output element.
        size: usize,
    },
    /// A buffer exceeds what the device can allocate or bind.
    #[error("`{entry}`: {what} needs {bytes} bytes, more than the device's {limit} limit of {max}")]
    TooLarge {
        /// Entry point.
        entry: String,
        /// Which buffer.
        what: String,
        /// Its size.
        bytes: u64,
        /// The wgpu limit's name.
        limit: &'static str,
        /// The limit's value.
        max: u64,
    },
    /// The SPIR-V module failed the structural check that runs before the driver sees it
    /// (a truncated file, a foreign or stale build); it was not passed to the driver.
    #[error(
        "the SPIR-V shader module is damaged: {problem} (rebuild it: `cargo build -p \
         scratchwave-spirv`; check a module file: `spirv-val FILE`)"
    )]
    BadShader {
        /// What the check found.
        problem: String,
    },
    /// The driver could not compile an entry point of a module that passed the structural
    /// check into a pipeline.
    #[error(
        "the driver failed to compile `{entry}`: {message} (check the module: `spirv-val \
         FILE`; compare with lavapipe: `SCRATCHWAVE_ADAPTER=lavapipe`; the driver's log)"
    )]
    ShaderCompile {
        /// Entry point.
        entry: String,
        /// wgpu's description.
        message: String,
    },
    /// The device, or the budget set with `Gpu::with_memory_budget`, cannot hold the
    /// buffers of a dispatch.
    #[error(
        "out of device memory while {during}: {detail} (diagnose: `vulkaninfo` lists the \
         memory heaps; split the job into smaller tables or render a smaller image)"
    )]
    OutOfMemory {
        /// What the backend was doing.
        during: String,
        /// How much was asked for against what limit, or the driver's words.
        detail: String,
    },
    /// wgpu reported a validation or internal error, or the device was lost.
    #[error(
        "GPU error while {during}: {message} (device lost or a driver fault; \
         diagnose: `vulkaninfo --summary`, the driver's log)"
    )]
    Gpu {
        /// What the backend was doing.
        during: String,
        /// wgpu's description.
        message: String,
    },
}

/// Result with [`SpirvError`].
pub type Result<T, E = SpirvError> = std::result::Result<T, E>;
