//! The Vulkan device, the embedded shader module and its compute pipelines.

use crate::adapter::{AdapterChoice, AdapterSummary};
use crate::dispatch::Pace;
use crate::error::{Result, SpirvError};
use crate::module::{CheckedModule, check};
use crate::no_contraction;
use std::borrow::Cow;
use std::collections::HashMap;
use std::sync::{Arc, Mutex, PoisonError};
use std::time::{Duration, Instant};

/// The SPIR-V module `build.rs` compiled from `shader/` on the pinned nightly.
pub const SHADER_SPV: &[u8] = include_bytes!(env!("SCRATCHWAVE_SHADER_SPV"));

/// The module's entry points, comma-separated (from rust-gpu's build metadata).
const ENTRY_POINTS: &str = env!("SCRATCHWAVE_SHADER_ENTRY_POINTS");

/// The entry points of [`SHADER_SPV`] (from the build; a [`Gpu`] reads its own module's).
pub fn entry_points() -> impl Iterator<Item = &'static str> {
    ENTRY_POINTS.split(',').filter(|name| !name.is_empty())
}

/// A compute pipeline for one entry point and number of input buffers.
pub(crate) struct Pipeline {
    pub(crate) layout: wgpu::BindGroupLayout,
    pub(crate) pipeline: wgpu::ComputePipeline,
}

/// A Vulkan device with the scratchwave shader module loaded.
///
/// Create one and keep it: device creation and each entry point's first pipeline
/// compilation are slow (lavapipe JIT-compiles through LLVM). `Gpu` is `Send + Sync`;
/// dispatches from several threads serialise on the queue.
pub struct Gpu {
    pub(crate) device: wgpu::Device,
    pub(crate) queue: wgpu::Queue,
    pub(crate) limits: wgpu::Limits,
    adapter: AdapterSummary,
    module: wgpu::ShaderModule,
    /// The module's compute entry points.
    entry_points: Vec<String>,
    pipelines: Mutex<HashMap<(String, usize), Arc<Pipeline>>>,
    /// Why the device was lost, once wgpu's device-lost callback has run.
    lost: Arc<Mutex<Option<String>>>,
    /// Largest chunk (elements) one dispatch covers; see [`Gpu::with_max_chunk`].
    pub(crate) max_chunk: usize,
    /// How dispatches are sliced in time; see [`Gpu::with_pace`].
    pub(crate) pace: Pace,
    /// Device bytes one dispatch may allocate; see [`Gpu::with_memory_budget`].
    pub(crate) memory_budget: Option<u64>,
}

impl Gpu {
    /// Opens the adapter [`AdapterChoice::from_env`] selects (`SCRATCHWAVE_ADAPTER`), with
    /// the pace [`Pace::from_env`] reads (`SCRATCHWAVE_PACE_MS`).
    pub fn new() -> Result<Self> {
        let pace = Pace::from_env()?;
        Ok(Self::with_adapter(&AdapterChoice::from_env())?.with_pace(pace))
    }

    /// Opens the adapter `choice` selects among the machine's Vulkan adapters.
    pub fn with_adapter(choice: &AdapterChoice) -> Result<Self> {
        // The embedded module is rust-gpu's validated output for `shader/`.
        Self::open_with(choice, SHADER_SPV)
    }

    /// Opens the adapter `choice` selects with a SPIR-V module other than the embedded
    /// one: a build of `shader/` made elsewhere, or a damaged module in a fault-injection
    /// test. The module is first checked structurally (`module.rs`): a truncated or
    /// otherwise malformed module is [`SpirvError::BadShader`] and never reaches the driver.
    /// Its `GLCompute` entry points are the ones dispatches may name.
    ///
    /// # Safety
    ///
    /// A module that passes the structural check goes to the driver with its float
    /// arithmetic marked `NoContraction` (`no_contraction.rs`, as the embedded module) and
    /// otherwise as it is (`wgpu`'s SPIR-V passthrough): it must be valid SPIR-V (`spirv-val` passes) with the
    /// shader crate's conventions (workgroup size `WORKGROUP_SIZE`, descriptor set 0 with
    /// the inputs then the output). An invalid one is undefined behaviour in the driver.
    pub unsafe fn with_module(choice: &AdapterChoice, spirv: &[u8]) -> Result<Self> {
        Self::open_with(choice, spirv)
    }

    fn open_with(choice: &AdapterChoice, spirv: &[u8]) -> Result<Self> {
        let mut module = check(spirv)?;
        module.words = no_contraction::decorate(&module.words);
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
            backends: wgpu::Backends::VULKAN,
            ..wgpu::InstanceDescriptor::new_without_display_handle_from_env()
        });
        let adapters = pollster::block_on(instance.enumerate_adapters(wgpu::Backends::VULKAN));
        if adapters.is_empty() {
            return Err(SpirvError::NoVulkan);
        }
        let summaries: Vec<AdapterSummary> = adapters
            .iter()
            .map(|a| AdapterSummary::from_wgpu(&a.get_info()))
            .collect();
        let Some(index) = choice.select(&summaries) else {
            let available = summaries
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>();
            return Err(SpirvError::NoMatchingAdapter {
                wanted: choice.to_string(),
                available: available.join(", "),
            });
        };
        Self::open(&adapters[index], summaries[index].clone(), module)
    }

    fn open(
        adapter: &wgpu::Adapter,
        summary: AdapterSummary,
        module: CheckedModule,
    ) -> Result<Self> {
        if !adapter
            .features()
            .contains(wgpu::Features::PASSTHROUGH_SHADERS)
        {
            return Err(SpirvError::MissingFeature {
                adapter: summary.name,
                feature: "PASSTHROUGH_SHADERS",
            });
        }
        // Everything the adapter offers: large storage bindings matter for 10⁶-query jobs.
        let limits = adapter.limits();
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("scratchwave"),
            required_features: wgpu::Features::PASSTHROUGH_SHADERS,
            required_limits: limits.clone(),
            ..Default::default()
        }))
        .map_err(|source| SpirvError::RequestDevice {
            adapter: summary.name.clone(),
            source,
        })?;
        // Errors are caught by error scopes around each operation; anything that escapes
        // them must not panic (wgpu's default handler does).
        device.on_uncaptured_error(Arc::new(|error| {
            eprintln!("scratchwave-spirv: uncaptured wgpu error: {error}");
        }));
        let lost = Arc::new(Mutex::new(None));
        let lost_flag = Arc::clone(&lost);
        device.set_device_lost_callback(move |reason, message| {
            *lost_flag.lock().unwrap_or_else(PoisonError::into_inner) =
                Some(format!("{reason:?}: {message}"));
        });

        let CheckedModule {
            words,
            entry_points: names,
        } = module;
        let entry_points: Vec<wgpu::PassthroughShaderEntryPoint<'_>> = names
            .iter()
            .map(|name| wgpu::PassthroughShaderEntryPoint {
                name: Cow::Borrowed(name.as_str()),
                workgroup_size: (scratchwave_spirv_shader::WORKGROUP_SIZE, 1, 1),
            })
            .collect();
        let scope = ErrorScopes::push(&device);
        // SAFETY: the module passed the structural check, and it is either rust-gpu's output
        // for `shader/` (validated by spirv-val at build time) or one whose caller promised
        // the same (`with_module`); its buffer interface (set 0, inputs then output, runtime
        // arrays of the Pod types in `scratchwave-spirv-shader`) is what `dispatch` binds.
        let module = unsafe {
            device.create_shader_module_passthrough(wgpu::ShaderModuleDescriptorPassthrough {
                label: Some("scratchwave-spirv-shader"),
                entry_points: Cow::Owned(entry_points),
                spirv: Some(Cow::Owned(words)),
                ..Default::default()
            })
        };
        scope.pop("loading the SPIR-V module")?;

        Ok(Self {
            device,
            queue,
            max_chunk: max_chunk_for(&limits),
            limits,
            adapter: summary,
            module,
            entry_points: names,
            pipelines: Mutex::new(HashMap::new()),
            lost,
            pace: Pace::DEFAULT,
            memory_budget: None,
        })
    }

    /// Destroys the device, as a driver reset or the GPU's removal would: every later call
    /// on this `Gpu` returns [`SpirvError::Gpu`] (`device lost`), never a panic or a hang.
    /// For fault-injection tests (`tests/faults.rs`); a `Gpu` cannot be revived.
    pub fn lose_device(&self) {
        self.device.destroy();
    }

    /// [`SpirvError::Gpu`] once the device is lost (wgpu's lost callback has run).
    pub(crate) fn check_alive(&self, during: &str) -> Result<()> {
        match self
            .lost
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .as_ref()
        {
            None => Ok(()),
            Some(why) => Err(SpirvError::Gpu {
                during: during.to_owned(),
                message: format!("device lost: {why}"),
            }),
        }
    }

    /// The adapter in use.
    pub fn adapter(&self) -> &AdapterSummary {
        &self.adapter
    }

    /// Caps the elements per dispatch (normally set by the device limits). Tests use a
    /// small cap to exercise the chunking that 10⁶-element jobs need on real limits.
    /// The cap is rounded down to a multiple of the storage offset alignment.
    pub fn with_max_chunk(mut self, elements: usize) -> Self {
        let align = chunk_alignment(&self.limits);
        self.max_chunk = (elements / align * align).clamp(align, max_chunk_for(&self.limits));
        self
    }

    /// Caps the bytes of one storage binding below the device's
    /// `max_storage_buffer_binding_size` (never above it). Per-item inputs are then split
    /// into more dispatches so that no binding exceeds the cap; a whole input above it is
    /// [`SpirvError::TooLarge`] naming the limit. A service can use it as a size budget per
    /// dispatch; tests use it to reach both paths without allocating the device's limit.
    pub fn with_max_binding_bytes(mut self, bytes: u64) -> Self {
        let l = &mut self.limits;
        l.max_storage_buffer_binding_size = l.max_storage_buffer_binding_size.min(bytes);
        self
    }

    /// Slices every later dispatch in time by `pace` instead of [`Pace::DEFAULT`]: a
    /// display driver with a shorter watchdog, or a service that must answer between
    /// slices, lowers `pace.target`. [`Timings::slices`](crate::Timings::slices) and
    /// [`Timings::longest_slice`](crate::Timings::longest_slice) report what a dispatch did.
    pub fn with_pace(mut self, pace: Pace) -> Self {
        self.pace = pace;
        self
    }

    /// Caps the device memory one dispatch may allocate (its inputs, its output and the
    /// output's readback copy) at `bytes`. A dispatch that needs more is refused before
    /// anything is allocated, as [`SpirvError::OutOfMemory`] naming both sizes; without a
    /// budget the driver decides, and its out-of-memory error is the same variant. A
    /// service sharing the device sets one; tests use it to inject the fault.
    pub fn with_memory_budget(mut self, bytes: u64) -> Self {
        self.memory_budget = Some(bytes);
        self
    }

    /// The compute entry points of this `Gpu`'s module.
    pub fn module_entry_points(&self) -> impl Iterator<Item = &str> {
        self.entry_points.iter().map(String::as_str)
    }

    /// The pipeline for `entry` with `inputs` read-only buffers, compiled on first use;
    /// also returns the compile time (zero when cached).
    pub(crate) fn pipeline(&self, entry: &str, inputs: usize) -> Result<(Arc<Pipeline>, Duration)> {
        let key = (entry.to_owned(), inputs);
        if let Some(p) = self
            .pipelines
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .get(&key)
        {
            return Ok((Arc::clone(p), Duration::ZERO));
        }
        if !self.module_entry_points().any(|name| name == entry) {
            return Err(SpirvError::UnknownEntryPoint {
                name: entry.to_owned(),
                available: self.entry_points.join(", "),
            });
        }
        let start = Instant::now();
        let storage = |binding: u32, read_only: bool| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let entries: Vec<_> = (0..inputs)
            .map(|i| storage(i as u32, true))
            .chain([storage(inputs as u32, false)])
            .collect();
        let scope = ErrorScopes::push(&self.device);
        let layout = self
            .device
            .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(entry),
                entries: &entries,
            });
        let pipeline_layout = self
            .device
            .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(entry),
                bind_group_layouts: &[Some(&layout)],
                immediate_size: 0,
            });
        let pipeline = self
            .device
            .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry),
                layout: Some(&pipeline_layout),
                module: &self.module,
                entry_point: Some(entry),
                compilation_options: Default::default(),
                cache: None,
            });
        if let Some(error) = scope.pop_error() {
            return Err(match error {
                error @ wgpu::Error::OutOfMemory { .. } => {
                    classify(error, &format!("creating the pipeline for `{entry}`"))
                }
                other => SpirvError::ShaderCompile {
                    entry: entry.to_owned(),
                    message: other.to_string(),
                },
            });
        }
        let compiled = Arc::new(Pipeline { layout, pipeline });
        self.pipelines
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .insert(key, Arc::clone(&compiled));
        Ok((compiled, start.elapsed()))
    }

    /// Blocks until the queue is idle.
    pub(crate) fn wait(&self, during: &str) -> Result<()> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map(drop)
            .map_err(|e| SpirvError::Gpu {
                during: during.to_owned(),
                message: e.to_string(),
            })
    }
}

/// Elements per dispatch under `limits`: at most the workgroup-count limit along x, and a
/// multiple of the storage offset alignment so every chunk's binding offset is aligned
/// whatever the element size.
fn max_chunk_for(limits: &wgpu::Limits) -> usize {
    let align = chunk_alignment(limits);
    let groups = limits.max_compute_workgroups_per_dimension as usize;
    (groups * scratchwave_spirv_shader::WORKGROUP_SIZE as usize / align * align).max(align)
}

/// Chunk lengths are multiples of this (a power of two ≥ the workgroup size), so every
/// chunk's binding offset is aligned whatever the element size.
pub(crate) fn chunk_alignment(limits: &wgpu::Limits) -> usize {
    (limits.min_storage_buffer_offset_alignment as usize)
        .max(scratchwave_spirv_shader::WORKGROUP_SIZE as usize)
}

/// Validation, out-of-memory and internal error scopes around one operation.
pub(crate) struct ErrorScopes {
    scopes: [wgpu::ErrorScopeGuard; 3],
}

impl ErrorScopes {
    pub(crate) fn push(device: &wgpu::Device) -> Self {
        Self {
            scopes: [
                device.push_error_scope(wgpu::ErrorFilter::Internal),
                device.push_error_scope(wgpu::ErrorFilter::OutOfMemory),
                device.push_error_scope(wgpu::ErrorFilter::Validation),
            ],
        }
    }

    /// Pops the scopes (innermost first) and returns the first error caught.
    pub(crate) fn pop_error(self) -> Option<wgpu::Error> {
        let mut first = None;
        for scope in self.scopes.into_iter().rev() {
            if let Some(error) = pollster::block_on(scope.pop()) {
                first.get_or_insert(error);
            }
        }
        first
    }

    /// Pops the scopes and reports the first error caught as [`classify`] does.
    pub(crate) fn pop(self, during: &str) -> Result<()> {
        self.pop_error()
            .map_or(Ok(()), |e| Err(classify(e, during)))
    }
}

/// A wgpu error as the backend's error: out of memory as [`SpirvError::OutOfMemory`],
/// anything else as [`SpirvError::Gpu`].
pub(crate) fn classify(error: wgpu::Error, during: &str) -> SpirvError {
    match error {
        wgpu::Error::OutOfMemory { .. } => SpirvError::OutOfMemory {
            during: during.to_owned(),
            detail: format!("the driver: {error}"),
        },
        other => SpirvError::Gpu {
            during: during.to_owned(),
            message: other.to_string(),
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chunks_respect_workgroup_limit_and_alignment() {
        let limits = wgpu::Limits {
            max_compute_workgroups_per_dimension: 65_535,
            min_storage_buffer_offset_alignment: 256,
            ..wgpu::Limits::default()
        };
        let chunk = max_chunk_for(&limits);
        assert_eq!(chunk % 256, 0);
        assert!(chunk / 64 <= 65_535);
        assert!(chunk > 4_000_000);
    }

    #[test]
    fn driver_out_of_memory_is_its_own_variant() {
        let oom = wgpu::Error::OutOfMemory {
            source: Box::new(std::io::Error::other("heap exhausted")),
        };
        match classify(oom, "uploading") {
            SpirvError::OutOfMemory { during, detail } => {
                assert_eq!(during, "uploading");
                assert!(detail.contains("the driver"), "{detail}");
            }
            other => panic!("expected OutOfMemory, got {other:?}"),
        }
    }

    #[test]
    fn module_is_spirv_with_entry_points() {
        assert_eq!(SHADER_SPV.len() % 4, 0);
        assert_eq!(SHADER_SPV[..4], 0x0723_0203_u32.to_le_bytes());
        assert!(entry_points().any(|name| name == "math_probe"));
        // The structural check reads the same entry points as the build reported.
        let mut read = check(SHADER_SPV).unwrap().entry_points;
        let mut built: Vec<&str> = entry_points().collect();
        read.sort();
        built.sort_unstable();
        assert_eq!(read, built);
    }
}
