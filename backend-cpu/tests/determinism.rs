//! Determinism: the CPU backends give bit-identical results whatever the thread count.
//!
//! A seeded table (20 000 queries over 300 scratches, every scratch model), a light batch
//! and a GHS table are evaluated with the scalar backend, with the single-thread SIMD
//! backend, and with `Backend::Simd` inside rayon pools of 1, 2 and 8 threads; every output
//! must have the same bits as the scalar one. The scratch and GHS tables run in lanes on
//! the SIMD backends (`scratchwave_cpu::lanes`), whose `exp` and `ln` are not libm's: there
//! the SIMD runs must match the single-thread SIMD run bit for bit (whatever the threads'
//! split of the sorted queries into batches), and `tests/lanes.rs` and
//! `tests/scratch_lanes.rs` bound their distance to the scalar backend in ULP. (Each query is evaluated by one thread from
//! start to end, and the kernel's coherent sum does not depend on the order in which the
//! BVH hands out scratches, so no result may depend on scheduling.)

use scratchwave_cpu::{Backend, Cpu, evaluate_ghs_table, evaluate_table};
use scratchwave_host::TableBackend;
use scratchwave_host::generate::{HalfLength, ProfileMix, ScratchRecipe, Uniform};
use scratchwave_host::rng::SplitMix64;
use scratchwave_host::{LightBatch, TableBatch};
use scratchwave_kernel::ghs::GhsParams;
use scratchwave_kernel::lights::{Cone, Light, LightParams, LightQuery};
use scratchwave_kernel::material::{FresnelAngle, Material};
use scratchwave_kernel::scratch::Scratch;
use scratchwave_kernel::table::{Model, TableParams, TableQuery};

const SIGMA: f32 = 10.0;

/// 300 scratches in a 40σ square (so a query sees a few dozen), every tenth one far out.
fn scratches(seed: u64) -> Vec<Scratch> {
    ScratchRecipe {
        count: 300,
        unit: SIGMA,
        center: [0.0, 0.0],
        side: 40.0,
        outliers: Some((10, 400.0)),
        half_length: HalfLength::Uniform(Uniform::new(0.5, 10.0)),
        width: Uniform::new(0.5, 5.0),
        depth: Uniform::new(0.05, 1.0),
        profile: ProfileMix::Alternate,
    }
    .generate(&mut SplitMix64::new(seed))
}

/// An upper-hemisphere direction.
fn upper(r: &mut SplitMix64) -> [f32; 3] {
    let d = r.direction();
    [d[0], d[1], d[2].abs().max(1.0e-3)]
}

/// `n` table queries: random directions and wavelengths, shading points over the scratched
/// square, constant and Fresnel materials.
fn table_queries(n: usize, seed: u64) -> Vec<TableQuery> {
    let mut r = SplitMix64::new(seed);
    (0..n)
        .map(|i| TableQuery {
            wi: upper(&mut r),
            wo: upper(&mut r),
            lambda_nm: r.range(380.0, 780.0),
            x: [r.range(-200.0, 200.0), r.range(-200.0, 200.0)],
            material: if i % 2 == 0 {
                Material::constant(0.9)
            } else {
                Material::ior(0.2, 3.5, FresnelAngle::ThetaD)
            },
            ..TableQuery::default()
        })
        .collect()
}

/// `f` on the scalar backend, the single-thread SIMD backend and `Backend::Simd` in pools of
/// 1, 2 and 8 threads; asserts every output is bit-identical to the one of `reference`
/// (the scalar backend, or for lane code the single-thread SIMD one).
fn assert_same_bits(what: &str, f: impl Fn(Backend) -> Vec<f32> + Sync) {
    assert_same_bits_as(what, Backend::Scalar, f);
}

fn assert_same_bits_as(what: &str, reference: Backend, f: impl Fn(Backend) -> Vec<f32> + Sync) {
    let reference: Vec<u32> = f(reference).iter().map(|v| v.to_bits()).collect();
    assert!(
        reference.iter().any(|&b| f32::from_bits(b) > 0.0),
        "{what}: every value is 0, the test would compare nothing"
    );
    let mut runs = vec![("simd1".to_string(), f(Backend::SimdSingleThread))];
    for threads in [1, 2, 8] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("thread pool");
        runs.push((
            format!("simd, {threads} threads"),
            pool.install(|| f(Backend::Simd)),
        ));
    }
    for (name, out) in runs {
        assert_eq!(out.len(), reference.len(), "{what} ({name})");
        let diff = out
            .iter()
            .zip(&reference)
            .position(|(v, &r)| v.to_bits() != r);
        assert!(
            diff.is_none(),
            "{what} ({name}): query {} differs: {} vs scalar {}",
            diff.unwrap(),
            out[diff.unwrap()],
            f32::from_bits(reference[diff.unwrap()])
        );
    }
}

#[test]
fn tables_are_bit_identical_across_thread_counts() {
    let scratches = scratches(18);
    let queries = table_queries(20_000, 19);
    for (model, depth_term, base_gaussian) in [
        (Model::Werner, 1, 0),
        (Model::WernerBlended, 0, 0),
        (Model::Velinov, 0, 1),
    ] {
        let params = TableParams {
            model: model as u32,
            depth_term,
            base_gaussian,
            sigma_um: SIGMA,
            ..TableParams::default()
        };
        assert_same_bits_as(
            &format!("{model:?} table"),
            Backend::SimdSingleThread,
            |b| evaluate_table(b, &params, &scratches, &queries),
        );
    }
}

#[test]
fn table_backend_batch_is_bit_identical_across_thread_counts() {
    let batch = TableBatch {
        params: TableParams {
            model: Model::Werner as u32,
            sigma_um: SIGMA,
            ..TableParams::default()
        },
        scratches: scratches(20),
        queries: table_queries(5_000, 21),
        default_material: Material::constant(0.9),
        ghs: None,
    };
    assert_same_bits_as("Cpu::evaluate", Backend::SimdSingleThread, |b| {
        Cpu(b).evaluate(&batch).expect("cpu evaluate")
    });
}

#[test]
fn light_batches_are_bit_identical_across_thread_counts() {
    let mut r = SplitMix64::new(22);
    let queries: Vec<LightQuery> = (0..2_000)
        .map(|i| {
            let c = upper(&mut r);
            let light = if i % 2 == 0 {
                Light::sphere([c[0] * 5.0, c[1] * 5.0, c[2] * 5.0], 0.5, Cone::Asin)
            } else {
                let z = 3.0 + c[2];
                Light::polygon(&[
                    [c[0] - 0.4, c[1] - 0.3, z],
                    [c[0] + 0.4, c[1] - 0.3, z],
                    [c[0] + 0.4, c[1] + 0.3, z],
                    [c[0] - 0.4, c[1] + 0.3, z],
                ])
            };
            LightQuery {
                wo: upper(&mut r),
                lambda_nm: r.range(380.0, 780.0),
                x: [r.range(-200.0, 200.0), r.range(-200.0, 200.0)],
                material: Material::constant(0.9),
                light,
                ..LightQuery::default()
            }
        })
        .collect();
    for bands in [1, 3, 20] {
        let batch = LightBatch {
            params: LightParams {
                sigma_um: SIGMA,
                bands,
                ..LightParams::default()
            },
            scratches: scratches(23),
            queries: queries.clone(),
        };
        assert_same_bits(&format!("light batch, bands {bands}"), |b| {
            Cpu(b).evaluate_light(&batch).expect("cpu light")
        });
    }
}

#[test]
fn ghs_tables_in_lanes_are_bit_identical_across_thread_counts() {
    let params = GhsParams::new(0.05, 0.1, 1.5, 2.0, 1.5, 0.2, 3.5);
    let queries = table_queries(20_000, 24);
    assert_same_bits_as("ghs table", Backend::SimdSingleThread, |b| {
        evaluate_ghs_table(b, &params, &queries)
    });
}
