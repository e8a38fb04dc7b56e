//! # scratchwave-spirv-shader
//!
//! The rust-gpu compute entry points of scratchwave. Each `#[spirv(compute)]` function is a
//! thin wrapper: it reads its invocation's element from a storage buffer, calls a plain
//! function — a kernel function, or a small dispatcher here that the CPU calls too — and
//! writes the result. No formula lives in this crate.
//!
//! Buffer conventions shared with the host (`scratchwave-spirv`'s `dispatch`):
//! descriptor set 0, read-only inputs at bindings `0..k` in the order the host passes them,
//! the output at binding `k`; one invocation per output element, workgroups of
//! [`WORKGROUP_SIZE`] along x. The host splits large jobs into chunks and binds each
//! chunk's sub-range, so `out.len()` is the chunk length and `id.x` indexes the chunk.
//!
//! The crate also compiles for the host (it is a workspace member), where the entry points
//! are ordinary functions and [`probe`] serves as the CPU reference.
#![no_std]

pub mod probe;

use spirv_std::glam::UVec3;
use spirv_std::spirv;

/// Invocations per workgroup of every entry point (the `threads(64)` below).
pub const WORKGROUP_SIZE: u32 = 64;

/// Element-wise evaluation of one kernel math function (see [`probe::MathFunction`]).
#[spirv(compute(threads(64)))]
pub fn math_probe(
    #[spirv(global_invocation_id)] id: UVec3,
    #[spirv(storage_buffer, descriptor_set = 0, binding = 0)] params: &[probe::ProbeParams],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 1)] args: &[[f32; 2]],
    #[spirv(storage_buffer, descriptor_set = 0, binding = 2)] out: &mut [[f32; 2]],
) {
    let i = id.x as usize;
    if i < out.len() {
        out[i] = probe::evaluate(params[0].function, args[i]);
    }
}
