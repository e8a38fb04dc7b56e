//! The generic dispatch: upload read-only `Pod` buffers, run one entry point once per
//! output element (in chunks the device limits allow), read the output back, and say how
//! long each of the three steps took.

use crate::error::{Result, SpirvError};
use crate::gpu::{ErrorScopes, Gpu, chunk_alignment};
use bytemuck::Pod;
use std::time::{Duration, Instant};

/// One read-only input buffer of a dispatch; its position in the list is its binding.
#[derive(Clone, Copy, Debug)]
pub struct Input<'a> {
    bytes: &'a [u8],
    /// `Some(element size)` when the buffer holds one element per output element.
    per_item: Option<usize>,
}

impl<'a> Input<'a> {
    /// One element per output element (queries, arguments). Large jobs are split into
    /// chunks and each chunk sees only its own sub-range, indexed from 0.
    pub fn per_item<T: Pod>(data: &'a [T]) -> Self {
        Self {
            bytes: bytemuck::cast_slice(data),
            per_item: Some(size_of::<T>()),
        }
    }

    /// A buffer every invocation may read whole (parameters, scratch segments, BVH nodes).
    /// An empty slice is bound as 4 zero bytes, since Vulkan cannot bind nothing: `len()`
    /// is then 0 in the shader for elements larger than 4 bytes (scratches, BVH nodes);
    /// for 4-byte elements an entry point must take the count from its parameters.
    pub fn whole<T: Pod>(data: &'a [T]) -> Self {
        Self {
            bytes: bytemuck::cast_slice(data),
            per_item: None,
        }
    }
}

/// How a dispatch is sliced in time: every dispatch is submitted in slices that are each
/// waited for on their own, the first of `first` elements, each next one sized from the
/// last one's measured time so that it takes about `target` (between ¼× and 4× the last
/// size, never more than the device limits allow). No single submission then runs for
/// long: a display driver's watchdog (about 2 s on Windows) never sees one, a lost device
/// is noticed between slices, and progress can be reported.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pace {
    /// Elements in the first slice.
    pub first: usize,
    /// The wall time each slice aims at.
    pub target: Duration,
}

impl Pace {
    /// The pace of every [`Gpu`] unless [`Gpu::with_pace`] sets another: 1024 elements
    /// first, then slices of about 100 ms.
    pub const DEFAULT: Pace = Pace {
        first: 1024,
        target: Duration::from_millis(100),
    };

    /// The environment variable [`Pace::from_env`] reads: the slice target in whole
    /// milliseconds.
    pub const ENV: &'static str = "SCRATCHWAVE_PACE_MS";

    /// [`Pace::DEFAULT`] with the target from `SCRATCHWAVE_PACE_MS` when it is set (1 to
    /// 60 000 ms): a GPU that drives no display can take longer submissions, which keep
    /// more of it busy while a slice's slowest invocations finish. Any other value is
    /// [`SpirvError::BadEnv`].
    pub fn from_env() -> Result<Pace> {
        Self::from_setting(std::env::var_os(Self::ENV).as_deref())
    }

    /// [`Pace::from_env`] for the variable's value (`None`: not set).
    pub fn from_setting(value: Option<&std::ffi::OsStr>) -> Result<Pace> {
        let Some(value) = value else {
            return Ok(Self::DEFAULT);
        };
        let text = value.to_string_lossy();
        match text.trim().parse::<u64>() {
            Ok(ms) if (1..=60_000).contains(&ms) => Ok(Pace {
                target: Duration::from_millis(ms),
                ..Self::DEFAULT
            }),
            _ => Err(SpirvError::BadEnv {
                name: Self::ENV,
                value: text.into_owned(),
                expected: "whole milliseconds from 1 to 60000",
            }),
        }
    }
}

/// Wall-clock time of each step of a dispatch, each ended by waiting for the device.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Timings {
    /// Compiling the pipeline; zero once the entry point has been used on this [`Gpu`].
    pub pipeline: Duration,
    /// Creating the buffers and copying the inputs to the device.
    pub upload: Duration,
    /// Recording, submitting and finishing the compute work.
    pub dispatch: Duration,
    /// Copying the output to a mappable buffer and into host memory.
    pub readback: Duration,
    /// Submissions the compute work was sliced into ([`Pace`]).
    pub slices: usize,
    /// The longest of them, submission to completion: what a watchdog would see.
    pub longest_slice: Duration,
}

impl Timings {
    /// `upload + dispatch + readback` (pipeline compilation excluded).
    pub fn total(&self) -> Duration {
        self.upload + self.dispatch + self.readback
    }

    /// Adds the cost of another dispatch of the same job: times and slices summed, the
    /// longest slice the longer one.
    pub fn absorb(&mut self, other: &Timings) {
        self.pipeline += other.pipeline;
        self.upload += other.upload;
        self.dispatch += other.dispatch;
        self.readback += other.readback;
        self.slices += other.slices;
        self.longest_slice = self.longest_slice.max(other.longest_slice);
    }
}

/// The output of a dispatch and what it cost.
#[derive(Clone, Debug)]
pub struct Dispatched<O> {
    /// One element per invocation.
    pub output: Vec<O>,
    /// Time per step.
    pub timings: Timings,
}

impl Gpu {
    /// Runs `entry` once for each of `len` output elements of type `O`.
    ///
    /// `inputs` are bound read-only at bindings `0..inputs.len()` of descriptor set 0 and
    /// the output at binding `inputs.len()`, matching the entry point's signature (see
    /// `scratchwave-spirv-shader`). Every [`Input::per_item`] buffer must hold `len`
    /// elements. Element sizes must be multiples of 4 bytes (Vulkan storage buffers).
    /// The work is submitted in slices of about [`Pace::target`] each (see [`Pace`]).
    pub fn dispatch<O: Pod>(
        &self,
        entry: &str,
        inputs: &[Input<'_>],
        len: usize,
    ) -> Result<Dispatched<O>> {
        self.dispatch_with_progress(entry, inputs, len, &|_, _| {})
    }

    /// [`Gpu::dispatch`], calling `progress(done, len)` after each slice.
    pub fn dispatch_with_progress<O: Pod>(
        &self,
        entry: &str,
        inputs: &[Input<'_>],
        len: usize,
        progress: &dyn Fn(usize, usize),
    ) -> Result<Dispatched<O>> {
        let plan = self.plan::<O>(entry, inputs, len)?;
        self.check_alive(&format!("dispatching `{entry}`"))?;
        if len == 0 {
            return Ok(Dispatched {
                output: Vec::new(),
                timings: Timings::default(),
            });
        }
        let (pipeline, pipeline_time) = self.pipeline(entry, inputs.len())?;
        let mut timings = Timings {
            pipeline: pipeline_time,
            ..Timings::default()
        };

        let start = Instant::now();
        let scope = ErrorScopes::push(&self.device);
        let input_buffers: Vec<wgpu::Buffer> = inputs
            .iter()
            .enumerate()
            .map(|(i, input)| {
                let contents: &[u8] = if input.bytes.is_empty() {
                    &[0; 4]
                } else {
                    input.bytes
                };
                // Created unmapped and filled through the queue: a buffer mapped at creation
                // panics inside wgpu when the device is lost (`tests/faults.rs`); this way
                // the loss reaches the error scope instead.
                let buffer = self.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some(&format!("{entry} input {i}")),
                    size: contents.len() as u64,
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
                self.queue.write_buffer(&buffer, 0, contents);
                buffer
            })
            .collect();
        let output_bytes = plan.output_bytes;
        let output = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(&format!("{entry} output")),
            size: output_bytes,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let staging = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(&format!("{entry} readback")),
            size: output_bytes,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        scope.pop(&format!("uploading the inputs of `{entry}`"))?;
        self.queue.submit([]);
        self.wait("uploading")?;
        timings.upload = start.elapsed();

        let start = Instant::now();
        let align = chunk_alignment(&self.limits);
        let group = scratchwave_spirv_shader::WORKGROUP_SIZE as usize;
        let round = |n: usize| (n / align * align).clamp(align, plan.chunk);
        let pace = self.pace;
        let mut size = round(pace.first);
        let mut first = 0;
        while first < len {
            let count = size.min(len - first);
            let slice_start = Instant::now();
            let scope = ErrorScopes::push(&self.device);
            let mut encoder = self.device.create_command_encoder(&Default::default());
            {
                let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some(entry),
                    timestamp_writes: None,
                });
                pass.set_pipeline(&pipeline.pipeline);
                let range = |stride: usize| wgpu::BufferBinding {
                    buffer: &output,
                    offset: (first * stride) as u64,
                    size: wgpu::BufferSize::new((count * stride) as u64),
                };
                let mut entries: Vec<wgpu::BindGroupEntry<'_>> = input_buffers
                    .iter()
                    .zip(inputs)
                    .enumerate()
                    .map(|(i, (buffer, input))| wgpu::BindGroupEntry {
                        binding: i as u32,
                        resource: match input.per_item {
                            Some(stride) => wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                                buffer,
                                ..range(stride)
                            }),
                            None => buffer.as_entire_binding(),
                        },
                    })
                    .collect();
                entries.push(wgpu::BindGroupEntry {
                    binding: inputs.len() as u32,
                    resource: wgpu::BindingResource::Buffer(range(size_of::<O>())),
                });
                let bind_group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some(entry),
                    layout: &pipeline.layout,
                    entries: &entries,
                });
                pass.set_bind_group(0, &bind_group, &[]);
                pass.dispatch_workgroups(count.div_ceil(group) as u32, 1, 1);
            }
            self.queue.submit([encoder.finish()]);
            scope.pop(&format!("dispatching `{entry}`"))?;
            first += count;
            self.wait("dispatching")?;
            self.check_alive(&format!("dispatching `{entry}`"))?;
            progress(first, len);
            let took = slice_start.elapsed();
            timings.slices += 1;
            timings.longest_slice = timings.longest_slice.max(took);
            let scale = (pace.target.as_secs_f64() / took.as_secs_f64().max(1e-6)).clamp(0.25, 4.0);
            size = round((count as f64 * scale) as usize);
        }
        timings.dispatch = start.elapsed();

        let start = Instant::now();
        let mut encoder = self.device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(&output, 0, &staging, 0, output_bytes);
        self.queue.submit([encoder.finish()]);
        let (sender, receiver) = std::sync::mpsc::channel();
        staging.map_async(wgpu::MapMode::Read, .., move |result| {
            let _ = sender.send(result);
        });
        self.wait("reading back")?;
        let mapping_failed = |message: String| SpirvError::Gpu {
            during: format!("mapping the output of `{entry}`"),
            message,
        };
        match receiver.recv() {
            Ok(Ok(())) => {}
            Ok(Err(error)) => return Err(mapping_failed(error.to_string())),
            Err(_) => return Err(mapping_failed("the map callback never ran".into())),
        }
        let view = staging
            .get_mapped_range(..)
            .map_err(|error| mapping_failed(error.to_string()))?;
        let output: Vec<O> = bytemuck::pod_collect_to_vec(&view);
        drop(view);
        staging.unmap();
        timings.readback = start.elapsed();
        Ok(Dispatched { output, timings })
    }

    /// Checks the request against the shader conventions and the device limits.
    fn plan<O: Pod>(&self, entry: &str, inputs: &[Input<'_>], len: usize) -> Result<Plan> {
        let limits = &self.limits;
        let too_large = |what: String, bytes: u64, limit: &'static str, max: u64| {
            Err(SpirvError::TooLarge {
                entry: entry.to_owned(),
                what,
                bytes,
                limit,
                max,
            })
        };
        let bad_input = |index: usize, problem: String| {
            Err(SpirvError::BadInput {
                entry: entry.to_owned(),
                index,
                problem,
            })
        };
        if size_of::<O>() == 0 || !size_of::<O>().is_multiple_of(4) {
            return Err(SpirvError::BadOutput {
                entry: entry.to_owned(),
                size: size_of::<O>(),
            });
        }
        let buffers = inputs.len() as u32 + 1;
        if buffers > limits.max_storage_buffers_per_shader_stage {
            return bad_input(
                inputs.len(),
                format!(
                    "{buffers} storage buffers exceed the device's limit of {}",
                    limits.max_storage_buffers_per_shader_stage
                ),
            );
        }
        let max_binding = limits.max_storage_buffer_binding_size;
        let mut chunk = self.max_chunk;
        let mut strides = vec![size_of::<O>()];
        for (index, input) in inputs.iter().enumerate() {
            let bytes = input.bytes.len() as u64;
            if bytes > limits.max_buffer_size {
                return too_large(
                    format!("input {index}"),
                    bytes,
                    "max_buffer_size",
                    limits.max_buffer_size,
                );
            }
            match input.per_item {
                Some(stride) => {
                    if stride == 0 || !stride.is_multiple_of(4) {
                        return bad_input(
                            index,
                            format!("element size {stride} bytes is not a non-zero multiple of 4"),
                        );
                    }
                    if input.bytes.len() != len * stride {
                        let elements = input.bytes.len() / stride;
                        return bad_input(index, format!("{elements} elements for {len} outputs"));
                    }
                    strides.push(stride);
                }
                None => {
                    if !bytes.is_multiple_of(4) {
                        return bad_input(index, format!("{bytes} bytes is not a multiple of 4"));
                    }
                    if bytes > max_binding {
                        return too_large(
                            format!("input {index}"),
                            bytes,
                            "max_storage_buffer_binding_size",
                            max_binding,
                        );
                    }
                }
            }
        }
        let output_bytes = (len * size_of::<O>()) as u64;
        if let Some(budget) = self.memory_budget {
            // What the dispatch allocates: each input (an empty one as 4 bytes), the output
            // and its readback copy.
            let inputs_bytes: u64 = inputs.iter().map(|i| i.bytes.len().max(4) as u64).sum();
            let needed = inputs_bytes + 2 * output_bytes;
            if needed > budget {
                return Err(SpirvError::OutOfMemory {
                    during: format!("planning `{entry}`"),
                    detail: format!(
                        "{len} elements need {needed} bytes on the device (inputs \
                         {inputs_bytes}, output and its readback copy 2 × {output_bytes}), \
                         more than the memory budget of {budget} bytes"
                    ),
                });
            }
        }
        if output_bytes > limits.max_buffer_size {
            return too_large(
                "the output".into(),
                output_bytes,
                "max_buffer_size",
                limits.max_buffer_size,
            );
        }
        // Per-item bindings of one chunk must fit the binding limit; keep the alignment.
        let align = chunk_alignment(limits);
        for stride in strides {
            let fit = (max_binding / stride as u64) as usize / align * align;
            if fit == 0 {
                return too_large(
                    format!("one chunk of {align} elements of {stride} bytes"),
                    (align * stride) as u64,
                    "max_storage_buffer_binding_size",
                    max_binding,
                );
            }
            chunk = chunk.min(fit);
        }
        Ok(Plan {
            chunk,
            output_bytes,
        })
    }
}

struct Plan {
    /// Elements per dispatch.
    chunk: usize,
    output_bytes: u64,
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::ffi::OsStr;

    #[test]
    fn pace_setting_sets_the_target_or_names_the_variable() {
        assert_eq!(Pace::from_setting(None).unwrap(), Pace::DEFAULT);
        let long = Pace::from_setting(Some(OsStr::new(" 2000 "))).unwrap();
        assert_eq!(long.target, Duration::from_millis(2000));
        assert_eq!(long.first, Pace::DEFAULT.first);
        for bad in ["0", "60001", "-5", "1.5", "fast", ""] {
            let error = Pace::from_setting(Some(OsStr::new(bad))).unwrap_err();
            let text = error.to_string();
            assert!(text.starts_with("SCRATCHWAVE_PACE_MS: must be"), "{text}");
            assert!(text.contains(&format!("{bad:?}")), "{text}");
        }
    }
}
