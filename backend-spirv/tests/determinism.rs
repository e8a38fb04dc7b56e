//! The SPIR-V backend is bitwise-identical run to run on one device: the same table twice on
//! one `Gpu`, once on a second `Gpu` opened on the same adapter, and once cut into many
//! more slices by a tight time budget, give the same bits. (Each invocation computes one
//! output from read-only inputs, with no atomics or reductions across invocations, so
//! nothing but the driver could make two runs differ; this checks the driver and the host's
//! slicing.)

mod common;

use common::lavapipe;
use scratchwave_host::ScratchLookup;
use scratchwave_kernel::ghs::presets;
use scratchwave_kernel::material::{FresnelAngle, Material};
use scratchwave_kernel::table::{Model, TableParams, TableQuery};
use scratchwave_spirv::{AdapterChoice, Gpu, Pace};
use scratchwave_testkit::fixtures::table_scratches;
use std::time::Duration;

/// `n` queries: outgoing directions on a spiral, shading points on a grid, four wavelengths.
fn queries(n: usize) -> Vec<TableQuery> {
    let side = (n as f32).sqrt() as usize;
    (0..n)
        .map(|i| {
            let t = i as f32 / n as f32;
            let (theta, phi) = (1.3 * t.sqrt(), 2_399.963 * t);
            TableQuery {
                wi: [0.3, 0.1, 0.95],
                lambda_nm: [420.0, 510.0, 600.0, 690.0][i % 4],
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

fn bits(values: &[f32]) -> Vec<u32> {
    values.iter().map(|v| v.to_bits()).collect()
}

#[test]
fn tables_are_bitwise_identical_run_to_run_on_one_device() {
    let Some(first) = lavapipe() else { return };
    let second = Gpu::with_adapter(&AdapterChoice::Lavapipe).expect("a second lavapipe device");
    let sliced = Gpu::with_adapter(&AdapterChoice::Lavapipe)
        .expect("a third lavapipe device")
        .with_pace(Pace {
            first: 256,
            target: Duration::from_nanos(1),
        });
    let scratches = table_scratches(64);
    let queries = queries(20_000);
    for model in [Model::Werner, Model::WernerBlended, Model::Velinov] {
        let params = TableParams {
            model: model as u32,
            sigma_um: 10.0,
            ..Default::default()
        };
        let lookup = ScratchLookup::new(&scratches, params.sigma_um);
        let run = |gpu: &Gpu| {
            let out = gpu.evaluate_table_with(&params, &lookup, &queries).unwrap();
            (bits(&out.output), out.timings)
        };
        let (a, t) = run(&first);
        let slices = t.slices;
        eprintln!(
            "{model:?}: {} queries in {:.1} ms, {} slices, longest {:.1} ms (target {} ms)",
            queries.len(),
            t.dispatch.as_secs_f64() * 1e3,
            t.slices,
            t.longest_slice.as_secs_f64() * 1e3,
            Pace::DEFAULT.target.as_millis()
        );
        assert!(a.iter().any(|&b| f32::from_bits(b) > 0.0), "{model:?}");
        assert_eq!(a, run(&first).0, "{model:?}: twice on one Gpu");
        assert_eq!(a, run(&second).0, "{model:?}: a second Gpu");
        let (c, sliced_timings) = run(&sliced);
        let more = sliced_timings.slices;
        assert!(more > slices, "{model:?}: {more} slices vs {slices}");
        assert_eq!(a, c, "{model:?}: sliced into {more} submissions");
    }
    let ghs = presets::channel(presets::ROUGH_METAL, &presets::GOLD, 1);
    let a = bits(&first.evaluate_ghs_table(&ghs, &queries).unwrap().output);
    assert_eq!(
        a,
        bits(&second.evaluate_ghs_table(&ghs, &queries).unwrap().output)
    );
    assert_eq!(
        a,
        bits(&sliced.evaluate_ghs_table(&ghs, &queries).unwrap().output)
    );
}
