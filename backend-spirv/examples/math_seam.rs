//! The math-seam study: does the kernel's own f32 approximation (`math::portable`) give
//! bit-identical results on the CPU and on lavapipe, where the default seam (libm on the
//! CPU, GLSL.std.450 on SPIR-V) does not — and what does it cost?
//!
//! `cargo run --release -p scratchwave-spirv --example math_seam [-- N]` prints a markdown
//! table: per function and seam, how many of N results agree bit for bit, the CPU-vs-GPU
//! ULP distance, each side's error against an f64 reference, and the time per 10⁶
//! evaluations on one CPU core and on lavapipe (dispatch only, transfers excluded).

use scratchwave_spirv::{AdapterChoice, Gpu, MathFunction, math_probe_cpu};
use std::hint::black_box;
use std::time::{Duration, Instant};

/// Timing repetitions; the minimum is reported.
const REPEATS: usize = 5;

struct Case {
    name: &'static str,
    /// (default seam, own approximation)
    functions: [MathFunction; 2],
    reference: fn(f64) -> f64,
    lo: f32,
    hi: f32,
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let n: usize = std::env::args()
        .nth(1)
        .map_or(Ok(1_000_000), |s| s.parse())?;
    let gpu = Gpu::with_adapter(&AdapterChoice::Lavapipe)?;
    println!(
        "adapter: {}; N = {n} evenly spaced arguments per case\n",
        gpu.adapter()
    );
    println!(
        "| function | range | seam | bit-identical | max ULP cpu↔gpu | mean ULP cpu↔gpu | max ULP cpu↔f64 | max ULP gpu↔f64 | CPU ms/10⁶ (1 core) | lavapipe ms/10⁶ |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    let cases = [
        Case {
            name: "exp",
            functions: [MathFunction::Exp, MathFunction::PortableExp],
            reference: f64::exp,
            lo: -87.0,
            hi: 88.5,
        },
        Case {
            name: "sin",
            functions: [MathFunction::Sin, MathFunction::PortableSin],
            reference: f64::sin,
            lo: -3.2,
            hi: 3.2,
        },
        Case {
            name: "sin",
            functions: [MathFunction::Sin, MathFunction::PortableSin],
            reference: f64::sin,
            lo: -8192.0,
            hi: 8192.0,
        },
        Case {
            name: "cos",
            functions: [MathFunction::Cos, MathFunction::PortableCos],
            reference: f64::cos,
            lo: -3.2,
            hi: 3.2,
        },
        Case {
            name: "cos",
            functions: [MathFunction::Cos, MathFunction::PortableCos],
            reference: f64::cos,
            lo: -8192.0,
            hi: 8192.0,
        },
    ];
    for case in &cases {
        let args: Vec<[f32; 2]> = (0..n)
            .map(|i| {
                [
                    case.lo + (case.hi - case.lo) * (i as f64 / (n - 1) as f64) as f32,
                    0.0,
                ]
            })
            .collect();
        let reference: Vec<f32> = args
            .iter()
            .map(|a| (case.reference)(f64::from(a[0])) as f32)
            .collect();
        for (seam, function) in ["libm / GLSL.std.450", "portable"]
            .into_iter()
            .zip(case.functions)
        {
            let cpu = math_probe_cpu(function, &args);
            let gpu_out = gpu.math_probe(function, &args)?.output;
            let cpu_gpu: Vec<u64> = cpu
                .iter()
                .zip(&gpu_out)
                .map(|(c, g)| ulps(c[0], g[0]))
                .collect();
            let identical = cpu
                .iter()
                .zip(&gpu_out)
                .filter(|(c, g)| c[0].to_bits() == g[0].to_bits())
                .count();
            let max_vs = |out: &[[f32; 2]]| {
                out.iter()
                    .zip(&reference)
                    .map(|(o, r)| ulps(o[0], *r))
                    .max()
                    .unwrap_or(0)
            };
            let cpu_time = min_time(|| {
                for &arg in &args {
                    black_box(function.evaluate(black_box(arg)));
                }
            });
            let mut gpu_time = Duration::MAX;
            for _ in 0..REPEATS {
                gpu_time = gpu_time.min(gpu.math_probe(function, &args)?.timings.dispatch);
            }
            let per_million = |t: Duration| t.as_secs_f64() * 1e3 * 1e6 / n as f64;
            println!(
                "| {} | [{}, {}] | {seam} | {identical}/{n} | {} | {:.3} | {} | {} | {:.2} | {:.2} |",
                case.name,
                case.lo,
                case.hi,
                cpu_gpu.iter().max().unwrap_or(&0),
                cpu_gpu.iter().sum::<u64>() as f64 / n as f64,
                max_vs(&cpu),
                max_vs(&gpu_out),
                per_million(cpu_time),
                per_million(gpu_time),
            );
        }
    }
    kernel_math_agreement(&gpu, n)?;
    Ok(())
}

/// The rest of the seam (libm / GLSL.std.450 based): CPU vs lavapipe, max absolute and
/// relative difference (relative only where |value| > 1e-6 of the range's maximum).
fn kernel_math_agreement(gpu: &Gpu, n: usize) -> Result<(), Box<dyn std::error::Error>> {
    println!("\n| function | arguments | max abs diff | max rel diff | max ULP | bit-identical |");
    println!("|---|---|---|---|---|---|");
    let line = |lo: f32, hi: f32| -> Vec<[f32; 2]> {
        (0..n)
            .map(|i| [lo + (hi - lo) * (i as f64 / (n - 1) as f64) as f32, 0.0])
            .collect()
    };
    let side = (n as f64).sqrt() as usize;
    let grid: Vec<[f32; 2]> = (0..side * side)
        .map(|i| {
            [
                -10.0 + 20.0 * (i % side) as f32 / (side - 1) as f32,
                10.0 * (i / side) as f32 / (side - 1) as f32,
            ]
        })
        .collect();
    let cases: [(MathFunction, &str, Vec<[f32; 2]>); 8] = [
        (MathFunction::Exp, "[-87, 88.5]", line(-87.0, 88.5)),
        (MathFunction::Sin, "[-100, 100]", line(-100.0, 100.0)),
        (MathFunction::Cos, "[-100, 100]", line(-100.0, 100.0)),
        (MathFunction::Sqrt, "[0, 1e6]", line(0.0, 1.0e6)),
        (MathFunction::Sinc, "[-100, 100]", line(-100.0, 100.0)),
        (MathFunction::Si, "[-100, 100]", line(-100.0, 100.0)),
        (MathFunction::Erf, "[-6, 6]", line(-6.0, 6.0)),
        (MathFunction::Faddeeva, "re [-10, 10] × im [0, 10]", grid),
    ];
    for (function, label, args) in cases {
        let cpu = math_probe_cpu(function, &args);
        let gpu_out = gpu.math_probe(function, &args)?.output;
        let magnitude = |v: &[f32; 2]| v[0].hypot(v[1]);
        let max = cpu.iter().map(magnitude).fold(0.0_f32, f32::max);
        let (mut abs, mut rel, mut ulp, mut identical) = (0.0_f32, 0.0_f32, 0_u64, 0);
        for (c, g) in cpu.iter().zip(&gpu_out) {
            let d = (c[0] - g[0]).hypot(c[1] - g[1]);
            abs = abs.max(d);
            if magnitude(c) > 1e-6 * max {
                rel = rel.max(d / magnitude(c));
            }
            ulp = ulp.max(ulps(c[0], g[0]).max(ulps(c[1], g[1])));
            identical +=
                usize::from(c[0].to_bits() == g[0].to_bits() && c[1].to_bits() == g[1].to_bits());
        }
        println!(
            "| {function:?} | {label} | {abs:.2e} | {rel:.2e} | {ulp} | {identical}/{} |",
            args.len()
        );
    }
    Ok(())
}

fn min_time(mut f: impl FnMut()) -> Duration {
    (0..REPEATS)
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed()
        })
        .min()
        .unwrap_or_default()
}

/// Units in the last place between two `f32` (sign-magnitude order; NaN = NaN counts 0).
fn ulps(a: f32, b: f32) -> u64 {
    if a.is_nan() && b.is_nan() {
        return 0;
    }
    let key = |x: f32| {
        let bits = i64::from(x.to_bits());
        if bits < 0x8000_0000 {
            bits
        } else {
            0x8000_0000 - bits
        }
    };
    (key(a) - key(b)).unsigned_abs()
}
