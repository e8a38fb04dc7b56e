//! Batches of [`LANES`] queries through a kernel function generic over
//! [`scratchwave_kernel::lane::Real`]: the SIMD backend's path for the formulas written in
//! lanes (GHS and the scratch-model table).
//!
//! One binary, run-time dispatch: each chunk of queries runs through the same
//! `Lanes<8>` instantiation, inside an `#[target_feature(enable = "avx2,fma")]` function
//! when the CPU has AVX2 and FMA (8 f32 per instruction), else in the baseline build (SSE2
//! on x86-64, NEON on aarch64: the same eight lanes as two 4-wide halves). The lane
//! functions are `#[inline(always)]` in the kernel, so their code is generated inside
//! whichever context calls them; a lane function too large to inline into the chunk loop
//! brings its own out-of-line AVX2 instance ([`LaneFn::lanes_avx2`]: the scratch table).
//! A short last chunk is padded with copies of its first
//! query, so every query gets the same lane arithmetic wherever it sits in the input.

use crate::parallel::{Backend, CHUNK};
use rayon::prelude::*;

/// Lanes per batch: 8 f32 fill one AVX2 register.
pub const LANES: usize = 8;

/// A kernel function over one query per lane.
pub trait LaneFn: Sync {
    /// One query.
    type In: Sync + Copy;
    /// One result.
    type Out: Send + Copy + Default;
    /// The results of [`LANES`] queries at once.
    fn lanes(&self, q: &[Self::In; LANES]) -> [Self::Out; LANES];
    /// The result of one query (the same formula at one lane: the scalar backend).
    fn one(&self, q: &Self::In) -> Self::Out;
    /// [`LaneFn::lanes`] as the AVX2 + FMA path calls it. The default inlines `lanes` into
    /// that path's chunk loop. A lane function too large for that instead gives `lanes` and
    /// this an out-of-line instance each, this one compiled for AVX2 + FMA (the scratch
    /// table: with its walk inlined into the chunk loop, LLVM's loop passes ran 39 CPU
    /// minutes before they were stopped).
    ///
    /// # Safety
    /// Call only where AVX2 and FMA were detected on the running CPU.
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    unsafe fn lanes_avx2(&self, q: &[Self::In; LANES]) -> [Self::Out; LANES] {
        self.lanes(q)
    }
}

/// `out[i] = f(inputs[i])`: one query at a time on [`Backend::Scalar`], in batches of
/// [`LANES`] on the SIMD backends (all rayon threads for [`Backend::Simd`]).
pub fn map_lanes<F: LaneFn>(backend: Backend, inputs: &[F::In], f: &F) -> Vec<F::Out> {
    let mut out = vec![F::Out::default(); inputs.len()];
    match backend {
        Backend::Scalar => {
            for (o, q) in out.iter_mut().zip(inputs) {
                *o = f.one(q);
            }
        }
        Backend::SimdSingleThread => run_chunk(inputs, &mut out, f),
        Backend::Simd => {
            out.par_chunks_mut(CHUNK)
                .zip(inputs.par_chunks(CHUNK))
                .for_each(|(o, i)| run_chunk(i, o, f));
        }
    }
    out
}

/// [`map_lanes`] on one thread with the baseline instruction set whatever the CPU has: the
/// fallback path of the run-time dispatch, callable on an AVX2 machine so that tests can
/// compare the two (every lane's arithmetic is the same, so are the bits).
pub fn map_lanes_baseline<F: LaneFn>(inputs: &[F::In], f: &F) -> Vec<F::Out> {
    let mut out = vec![F::Out::default(); inputs.len()];
    run_batches(inputs, &mut out, f);
    out
}

/// Whether [`map_lanes`] runs its batches with AVX2 + FMA on this CPU.
pub fn avx2_fma() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

fn run_chunk<F: LaneFn>(inputs: &[F::In], out: &mut [F::Out], f: &F) {
    #[cfg(target_arch = "x86_64")]
    {
        if avx2_fma() {
            // SAFETY: the features were just detected on this CPU.
            unsafe { run_chunk_avx2(inputs, out, f) };
            return;
        }
    }
    run_batches(inputs, out, f);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn run_chunk_avx2<F: LaneFn>(inputs: &[F::In], out: &mut [F::Out], f: &F) {
    // SAFETY: this function runs only where AVX2 and FMA were detected (`run_chunk`).
    run_batches_with(inputs, out, |q| unsafe { f.lanes_avx2(q) });
}

#[inline(always)]
fn run_batches<F: LaneFn>(inputs: &[F::In], out: &mut [F::Out], f: &F) {
    run_batches_with(inputs, out, |q| f.lanes(q));
}

/// Batches of [`LANES`] through `lanes`, the short last one padded with copies of its first
/// query.
#[inline(always)]
fn run_batches_with<I: Copy, O: Copy>(
    inputs: &[I],
    out: &mut [O],
    lanes: impl Fn(&[I; LANES]) -> [O; LANES],
) {
    let mut qs = inputs.chunks_exact(LANES);
    let mut os = out.chunks_exact_mut(LANES);
    for (o, q) in (&mut os).zip(&mut qs) {
        if let Ok(q) = <&[I; LANES]>::try_from(q) {
            o.copy_from_slice(&lanes(q));
        }
    }
    let rest = qs.remainder();
    if let Some(first) = rest.first() {
        let mut q = [*first; LANES];
        q[..rest.len()].copy_from_slice(rest);
        let r = lanes(&q);
        os.into_remainder().copy_from_slice(&r[..rest.len()]);
    }
}
