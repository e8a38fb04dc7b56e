//! Throughput: lavapipe (or the adapter `SCRATCHWAVE_ADAPTER` picks) against the CPU
//! backend's scalar and simd+rayon paths, for N queries (default 10⁶) of each table model,
//! N of the GHS model, and N/10 area-light queries (the light sweep's configurations laid
//! out by `light_configs::grid_batch`) with Eq. 27 and with the extent rule.
//!
//! `cargo run --release -p scratchwave-benches --features spirv --example throughput [-- N SCRATCHES]`
//!
//! "scan" (tables only) is the CPU visiting the scratches in slot order instead of
//! traversing the BVH, to separate the lookup from the device. GPU times are split as the
//! dispatch API reports them (pipeline compilation excluded by a warm-up run); "incl." adds
//! upload and readback; "slices" and "longest" are the submissions the dispatch was cut
//! into by its time budget (`scratchwave_spirv::Pace`, about 100 ms each) and the longest of
//! them, what a display driver's watchdog would see. The scratch lookup (BVH) is built once on the CPU and shared by both
//! sides, so neither side's time includes it.

use scratchwave_cpu::Backend;
use scratchwave_cpu::parallel::map;
use scratchwave_host::ScratchLookup;
use scratchwave_kernel::ghs::presets;
use scratchwave_kernel::lights::{LightParams, light_integral};
use scratchwave_kernel::material::{FresnelAngle, Material};
use scratchwave_kernel::scratch::ScratchSlice;
use scratchwave_kernel::table::{Model, TableParams, TableQuery, evaluate, evaluate_ghs};
use scratchwave_spirv::{Dispatched, Gpu};
use scratchwave_testkit::fixtures::table_scratches;
use scratchwave_testkit::light_configs::{Rng, SweepRanges, grid_batch};
use std::time::{Duration, Instant};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let n: usize = args.next().map_or(Ok(1_000_000), |s| s.parse())?;
    let count: usize = args.next().map_or(Ok(64), |s| s.parse())?;
    let gpu = Gpu::new()?;
    let scratches = table_scratches(count);
    let queries = queries(n);
    println!(
        "adapter: {}; {n} queries, {count} scratches in a 200 µm square, σ = 10 µm, {} rayon threads\n",
        gpu.adapter(),
        rayon::current_num_threads()
    );
    println!(
        "| model | CPU scalar Mq/s | CPU simd+rayon Mq/s | CPU simd+rayon, scan Mq/s | GPU dispatch Mq/s | GPU incl. upload+readback Mq/s | upload ms | dispatch ms | readback ms | slices | longest slice ms | max rel diff vs CPU |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    for model in [Model::Werner, Model::WernerBlended, Model::Velinov] {
        let params = TableParams {
            model: model as u32,
            sigma_um: 10.0,
            ..Default::default()
        };
        let lookup = ScratchLookup::new(&scratches, params.sigma_um);
        let set = lookup.set();
        // The same BVH-free scan on the CPU, to separate the lookup from the device.
        let scan_set = ScratchSlice {
            scratches: lookup.scratches(),
        };
        let start = Instant::now();
        let _ = map(Backend::Simd, &queries, |q| evaluate(&params, q, &scan_set));
        let scan = start.elapsed();
        row(
            &format!("{model:?}"),
            queries.len(),
            Some(scan),
            |b| map(b, &queries, |q| evaluate(&params, q, &set)),
            |m| gpu.evaluate_table_with(&params, &lookup, &queries[..m]),
        )?;
    }
    let ghs = presets::channel(presets::ROUGH_METAL, &presets::GOLD, 1);
    row(
        "ghs (rough gold)",
        queries.len(),
        None,
        |b| map(b, &queries, |q| evaluate_ghs(&ghs, q)),
        |m| gpu.evaluate_ghs_table(&ghs, &queries[..m]),
    )?;
    let (light_params, light_scratches, light_queries) = grid_batch(
        &mut Rng::new(3),
        &SweepRanges::default(),
        1,
        (n / 10).max(1),
    );
    let light_lookup = ScratchLookup::new(&light_scratches, light_params.sigma_um);
    let light_set = light_lookup.set();
    for (label, bands) in [("light, Eq. 27", 1), ("light, extent rule", 20)] {
        let p = LightParams {
            bands,
            ..light_params
        };
        row(
            label,
            light_queries.len(),
            None,
            |b| map(b, &light_queries, |q| light_integral(&p, q, &light_set)),
            |m| gpu.light_table(&p, &light_lookup, &light_queries[..m]),
        )?;
    }
    Ok(())
}

/// Times `cpu` on both CPU paths and `gpu` (after a warm-up dispatch that compiles the
/// pipeline) and prints one table row.
fn row(
    label: &str,
    n: usize,
    scan: Option<Duration>,
    cpu: impl Fn(Backend) -> Vec<f32>,
    gpu: impl Fn(usize) -> scratchwave_spirv::Result<Dispatched<f32>>,
) -> Result<(), Box<dyn std::error::Error>> {
    let timed = |backend| {
        let start = Instant::now();
        let out = cpu(backend);
        (out, start.elapsed())
    };
    let (_, scalar) = timed(Backend::Scalar);
    let (reference, simd) = timed(Backend::Simd);
    gpu(1024.min(n))?;
    let run = gpu(n)?;
    let t = run.timings;
    let rate = |d: Duration| n as f64 / d.as_secs_f64() / 1e6;
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    println!(
        "| {label} | {:.3} | {:.3} | {} | {:.3} | {:.3} | {:.1} | {:.1} | {:.1} | {} | {:.1} | {:.2e} |",
        rate(scalar),
        rate(simd),
        scan.map_or("—".to_string(), |d| format!("{:.3}", rate(d))),
        rate(t.dispatch),
        rate(t.total()),
        ms(t.upload),
        ms(t.dispatch),
        ms(t.readback),
        t.slices,
        ms(t.longest_slice),
        max_rel_diff(&reference, &run.output),
    );
    Ok(())
}

/// `n` queries: viewing directions on a spiral, fixed light, shading points on a grid.
fn queries(n: usize) -> Vec<TableQuery> {
    (0..n)
        .map(|i| {
            let t = i as f32 / n as f32;
            let theta = 1.3 * t.sqrt();
            let phi = 2_399.963 * t;
            let side = (n as f32).sqrt().max(1.0) as usize;
            TableQuery {
                wi: [0.3, 0.1, 0.95],
                lambda_nm: 400.0 + 300.0 * ((i * 7919) % 1000) as f32 / 1000.0,
                wo: [
                    theta.sin() * phi.cos(),
                    theta.sin() * phi.sin(),
                    theta.cos(),
                ],
                x: [
                    200.0 * (i % side) as f32 / side as f32 - 100.0,
                    200.0 * (i / side % side) as f32 / side as f32 - 100.0,
                ],
                material: Material::ior(0.2, 3.5, FresnelAngle::ThetaD),
                ..Default::default()
            }
        })
        .collect()
}

/// Max relative difference where the CPU value exceeds 1e-6 of the table maximum.
fn max_rel_diff(cpu: &[f32], gpu: &[f32]) -> f32 {
    let max = cpu.iter().fold(0.0_f32, |m, v| m.max(v.abs()));
    cpu.iter()
        .zip(gpu)
        .filter(|(c, _)| c.abs() > 1e-6 * max)
        .map(|(c, g)| (c - g).abs() / c.abs())
        .fold(0.0, f32::max)
}
