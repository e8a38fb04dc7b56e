//! CPU vs lavapipe on the kernel's `math` seam, through the `math_probe` entry point.
//!
//! Tolerances are Vulkan's: GLSL.std.450 `Exp` may be off by `3 + 2|x|` ULP, `Sin`/`Cos`
//! by 2⁻¹¹ absolute on [-π, π]; libm is within 1 ULP. The kernel's own approximations
//! (`Portable*`) use only `+ - *`, `floor`-free integer conversion and bit casts, which
//! Vulkan rounds exactly, so those must agree bit for bit (unless a driver contracts
//! `a*b+c` into `fma`; lavapipe does not, measured — see ARCHITECTURE.md).

mod common;

use common::{lavapipe, linspace, ulps};
use scratchwave_spirv::{Input, MathFunction, SpirvError, math_probe_cpu};

/// Arguments covering exp's whole finite, normal range (-87.3..88.7) densely.
fn exp_args() -> Vec<[f32; 2]> {
    linspace(-87.0, 88.5, 100_003)
}

/// sin/cos arguments: many periods, up to the portable reduction's accuracy limit 8192.
fn trig_args() -> Vec<[f32; 2]> {
    linspace(-8192.0, 8192.0, 100_003)
}

#[test]
fn exp_agrees_within_vulkan_precision() {
    let Some(gpu) = lavapipe() else { return };
    let args = exp_args();
    let gpu_out = gpu.math_probe(MathFunction::Exp, &args).unwrap().output;
    let cpu_out = math_probe_cpu(MathFunction::Exp, &args);
    for ((arg, g), c) in args.iter().zip(&gpu_out).zip(&cpu_out) {
        let allowed = 4 + (2.0 * arg[0].abs()) as u64;
        assert!(
            ulps(g[0], c[0]) <= allowed,
            "exp({}) = {} on lavapipe, {} on CPU",
            arg[0],
            g[0],
            c[0]
        );
    }
}

#[test]
fn portable_math_is_bit_identical() {
    let Some(gpu) = lavapipe() else { return };
    let exp = exp_args();
    let trig = trig_args();
    for (function, args) in [
        (MathFunction::PortableExp, &exp),
        (MathFunction::PortableSin, &trig),
        (MathFunction::PortableCos, &trig),
    ] {
        let gpu_out = gpu.math_probe(function, args).unwrap().output;
        let cpu_out = math_probe_cpu(function, args);
        let differing = gpu_out
            .iter()
            .zip(&cpu_out)
            .filter(|(g, c)| g[0].to_bits() != c[0].to_bits())
            .count();
        assert_eq!(
            differing,
            0,
            "{function:?}: {differing} of {} results differ in bits",
            args.len()
        );
    }
}

#[test]
fn chunked_dispatch_matches_single_dispatch() {
    let Some(gpu) = lavapipe() else { return };
    let args = linspace(-20.0, 20.0, 10_007);
    let whole = gpu
        .math_probe(MathFunction::PortableExp, &args)
        .unwrap()
        .output;
    let gpu = gpu.with_max_chunk(1024);
    let chunked = gpu
        .math_probe(MathFunction::PortableExp, &args)
        .unwrap()
        .output;
    assert_eq!(whole.len(), args.len());
    assert!(
        whole
            .iter()
            .zip(&chunked)
            .all(|(a, b)| a[0].to_bits() == b[0].to_bits())
    );
}

#[test]
fn empty_dispatch_returns_nothing() {
    let Some(gpu) = lavapipe() else { return };
    assert!(
        gpu.math_probe(MathFunction::Exp, &[])
            .unwrap()
            .output
            .is_empty()
    );
}

#[test]
fn bad_requests_are_typed_errors() {
    let Some(gpu) = lavapipe() else { return };
    let args = [[1.0_f32, 0.0]; 8];
    let unknown = gpu.dispatch::<[f32; 2]>("no_such_entry", &[Input::per_item(&args)], 8);
    assert!(
        matches!(unknown, Err(SpirvError::UnknownEntryPoint { .. })),
        "{unknown:?}"
    );
    let short = gpu.dispatch::<[f32; 2]>(
        "math_probe",
        &[Input::whole(&[0u32; 4]), Input::per_item(&args)],
        9,
    );
    assert!(
        matches!(short, Err(SpirvError::BadInput { index: 1, .. })),
        "{short:?}"
    );
    let odd = gpu.dispatch::<[u16; 1]>("math_probe", &[], 4);
    assert!(matches!(odd, Err(SpirvError::BadOutput { .. })), "{odd:?}");
}
