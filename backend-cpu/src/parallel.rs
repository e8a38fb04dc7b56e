//! Mapping a kernel function over a slice: scalar, or rayon + SIMD code generation.

use rayon::prelude::*;

/// How a CPU evaluation runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Backend {
    /// One thread, baseline instruction set.
    Scalar,
    /// All rayon threads, each chunk compiled for AVX2 + FMA when the CPU has them.
    Simd,
    /// One thread, AVX2 + FMA code generation (isolates the SIMD gain from threading).
    SimdSingleThread,
}

/// Inputs per rayon task: large enough to amortise scheduling, small enough to balance.
pub(crate) const CHUNK: usize = 256;

/// `out[i] = f(&inputs[i])` on the chosen backend.
pub fn map<I: Sync, O: Send + Default + Clone, F: Fn(&I) -> O + Sync>(
    backend: Backend,
    inputs: &[I],
    f: F,
) -> Vec<O> {
    let mut out = vec![O::default(); inputs.len()];
    match backend {
        Backend::Scalar => run_chunk_baseline(inputs, &mut out, &f),
        Backend::SimdSingleThread => run_chunk(inputs, &mut out, &f),
        Backend::Simd => {
            out.par_chunks_mut(CHUNK)
                .zip(inputs.par_chunks(CHUNK))
                .for_each(|(o, i)| run_chunk(i, o, &f));
        }
    }
    out
}

fn run_chunk_baseline<I, O, F: Fn(&I) -> O>(inputs: &[I], out: &mut [O], f: &F) {
    for (o, i) in out.iter_mut().zip(inputs) {
        *o = f(i);
    }
}

/// Runs a chunk through the AVX2 + FMA instantiation when available.
fn run_chunk<I, O, F: Fn(&I) -> O>(inputs: &[I], out: &mut [O], f: &F) {
    #[cfg(target_arch = "x86_64")]
    {
        if std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma") {
            // SAFETY: the features were just detected on this CPU.
            unsafe { run_chunk_avx2(inputs, out, f) };
            return;
        }
    }
    run_chunk_baseline(inputs, out, f);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn run_chunk_avx2<I, O, F: Fn(&I) -> O>(inputs: &[I], out: &mut [O], f: &F) {
    for (o, i) in out.iter_mut().zip(inputs) {
        *o = f(i);
    }
}
