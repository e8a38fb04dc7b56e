//! BRDF and footprint tables: lavapipe against the same kernel functions called in a plain
//! loop on the CPU (what the CPU backend's scalar path does).
//!
//! Tolerance (issue #3): relative difference ≤ 1e-4 wherever the value exceeds 1e-6 of
//! the case's maximum. The two sides differ only in libm vs. GLSL.std.450 transcendentals
//! (a few ULP each) and in `fma` contraction; the Werner sums cancel (B − S), which
//! amplifies those ULPs, hence 1e-4 rather than f32 epsilon, and the 1e-6 floor exempts
//! the deep cancellation minima whose relative error is meaningless.

mod common;

use scratchwave_host::{FootprintRow, ScratchLookup};
use scratchwave_kernel::footprint::Ellipse;
use scratchwave_kernel::ghs::layers::LayerForm;
use scratchwave_kernel::ghs::{DiffColor, GhsParams, Layer, presets};
use scratchwave_kernel::material::{FresnelAngle, Material};
use scratchwave_kernel::scratch::{Profile, Scratch};
use scratchwave_kernel::table::{Model, TableParams, TableQuery, evaluate, evaluate_ghs};

const REL_TOL: f32 = 1e-4;

/// The kernel's table value per query on the CPU, through the same BVH lookup.
fn cpu_table(params: &TableParams, scratches: &[Scratch], queries: &[TableQuery]) -> Vec<f32> {
    let lookup = ScratchLookup::new(scratches, params.sigma_um);
    let set = lookup.set();
    queries.iter().map(|q| evaluate(params, q, &set)).collect()
}
const FLOOR: f32 = 1e-6;

/// A few scratches around the origin: both profiles, crossing, one degenerate (zero length),
/// one far away (outside every query's 6σ radius, so the BVH must prune it).
fn scratches() -> Vec<Scratch> {
    let s = |p0: [f64; 2], p1: [f64; 2], width: f32, depth: f32, profile: Profile| {
        Scratch::from_endpoints(p0, p1, width, depth, profile)
    };
    vec![
        s([-40.0, -3.0], [45.0, 4.0], 1.5, 0.35, Profile::Rect),
        s([-10.0, -30.0], [12.0, 35.0], 0.8, 0.12, Profile::Triangle),
        s([5.0, -2.0], [25.0, -1.0], 2.5, 0.6, Profile::Rect),
        s([-20.0, 8.0], [-20.0, 8.0], 1.0, 0.2, Profile::Rect),
        s([600.0, 600.0], [900.0, 700.0], 1.0, 0.2, Profile::Triangle),
    ]
}

/// Directions over the upper hemisphere (including near-mirror and grazing pairs), four
/// wavelengths, shading points on and between scratches, constant and Fresnel materials.
fn queries() -> Vec<TableQuery> {
    let dir = |theta: f32, phi: f32| {
        [
            theta.sin() * phi.cos(),
            theta.sin() * phi.sin(),
            theta.cos(),
        ]
    };
    let mut out = Vec::new();
    for (i, theta_i) in [0.0_f32, 0.3, 0.9, 1.4].into_iter().enumerate() {
        for theta_o in [0.0_f32, 0.05, 0.3, 0.8, 1.3] {
            for phi_o in [0.0_f32, 1.0, 2.5, 3.1] {
                for (j, lambda_nm) in [400.0_f32, 532.0, 600.0, 700.0].into_iter().enumerate() {
                    for x in [[0.0_f32, 0.0], [3.0, 1.0], [-18.0, 7.0], [30.0, -12.0]] {
                        let material = if (i + j) % 2 == 0 {
                            Material::constant(0.9)
                        } else {
                            Material::ior(0.2, 3.5, FresnelAngle::ThetaD)
                        };
                        out.push(TableQuery {
                            wi: dir(theta_i, 0.4),
                            lambda_nm,
                            wo: dir(theta_o, phi_o),
                            x,
                            material,
                            ..Default::default()
                        });
                    }
                }
            }
        }
    }
    out
}

/// Max relative difference over the values above `FLOOR` × the case maximum.
fn max_rel_diff(reference: &[f32], other: &[f32]) -> (f32, usize) {
    let max = reference.iter().fold(0.0_f32, |m, v| m.max(v.abs()));
    let mut worst = (0.0_f32, 0);
    for (i, (r, o)) in reference.iter().zip(other).enumerate() {
        if r.abs() > FLOOR * max {
            let rel = (r - o).abs() / r.abs();
            if rel > worst.0 || rel.is_nan() {
                worst = (rel, i);
            }
        }
    }
    worst
}

/// Same length, not all zero, and within [`REL_TOL`] above the floor.
fn assert_agree(label: &str, cpu: &[f32], gpu: &[f32]) {
    assert_eq!(gpu.len(), cpu.len());
    assert!(
        cpu.iter().any(|&v| v > 0.0),
        "{label}: an all-zero case tests nothing"
    );
    let (rel, at) = max_rel_diff(cpu, gpu);
    eprintln!("{label}: max rel diff {rel:.2e}");
    assert!(
        rel <= REL_TOL,
        "{label}: rel diff {rel:e} at query {at}: cpu {} gpu {}",
        cpu[at],
        gpu[at]
    );
}

#[test]
fn tables_agree_with_the_cpu_backend() {
    let Some(gpu) = common::lavapipe() else {
        return;
    };
    let scratches = scratches();
    let queries = queries();
    for model in [Model::Werner, Model::WernerBlended, Model::Velinov] {
        for (eta, depth_term, base_gaussian) in [(0, 0, 0), (1, 1, 1)] {
            let params = TableParams {
                model: model as u32,
                eta,
                depth_term,
                base_gaussian,
                sigma_um: 10.0,
                ..Default::default()
            };
            let cpu = cpu_table(&params, &scratches, &queries);
            let gpu_out = gpu
                .evaluate_table(&params, &scratches, &queries)
                .unwrap()
                .output;
            assert_agree(&format!("{params:?}"), &cpu, &gpu_out);
        }
    }
}

#[test]
fn a_table_without_scratches_is_the_flat_base() {
    let Some(gpu) = common::lavapipe() else {
        return;
    };
    let queries = queries();
    let params = TableParams {
        model: Model::Werner as u32,
        sigma_um: 10.0,
        ..Default::default()
    };
    let cpu = cpu_table(&params, &[], &queries);
    let gpu_out = gpu.evaluate_table(&params, &[], &queries).unwrap().output;
    let (rel, at) = max_rel_diff(&cpu, &gpu_out);
    assert!(rel <= REL_TOL, "rel diff {rel:e} at query {at}");
}

#[test]
fn footprint_tables_agree_with_the_cpu_backend() {
    let Some(gpu) = common::lavapipe() else {
        return;
    };
    let mut pairs = Vec::new();
    for scratch in scratches() {
        for (k, a1) in [0.5_f32, 3.0, 12.0, 40.0, 150.0].into_iter().enumerate() {
            for center in [[0.0_f32, 0.0], [2.0, 1.0], [-15.0, 20.0]] {
                let ellipse = Ellipse {
                    center,
                    angle_rad: 0.3 * k as f32,
                    a1,
                    a2: 0.4 * a1,
                    pad: [0.0; 3],
                };
                pairs.push((scratch, ellipse));
            }
        }
    }
    let sigma = 10.0;
    let cpu: Vec<FootprintRow> = pairs
        .iter()
        .map(|(s, e)| FootprintRow::of(s, e, sigma))
        .collect();
    let gpu_rows = gpu.footprint_table(sigma, &pairs).unwrap().output;
    type Column = fn(&FootprintRow) -> f32;
    let columns: [(&str, Column); 4] = [
        ("eq15", |r| r.eq15),
        ("eq16", |r| r.eq16),
        ("accurate", |r| r.accurate),
        ("rho_p", |r| r.rho_p),
    ];
    for (name, column) in columns {
        let c: Vec<f32> = cpu.iter().map(column).collect();
        let g: Vec<f32> = gpu_rows.iter().map(column).collect();
        let (rel, at) = max_rel_diff(&c, &g);
        eprintln!("footprint {name}: max rel diff {rel:.2e}");
        assert!(
            rel <= REL_TOL,
            "{name}: rel diff {rel:e} at {at}: cpu {} gpu {}",
            c[at],
            g[at]
        );
    }
}

#[test]
fn ghs_tables_agree_with_the_cpu_backend() {
    let Some(gpu) = common::lavapipe() else {
        return;
    };
    let queries = queries();
    let gold = presets::channel(presets::ROUGH_METAL, &presets::GOLD, 1);
    let materials = [
        gold,
        presets::channel(presets::POLISHED_METAL, &presets::GOLD, 0).with_diff_color(DiffColor::Q),
        presets::GLOSSY_PLASTIC.with_diff_color(DiffColor::Fresnel),
        presets::TRANSLUCENT_STONE.with_diff_color(DiffColor::None),
        GhsParams::new(0.1, 0.3, 0.2, 0.05, 1.05, 1.5, 0.0).with_layer(
            Layer::Plastic,
            LayerForm::EnergyConserving,
            0.5,
        ),
    ];
    for params in materials {
        let cpu: Vec<f32> = queries.iter().map(|q| evaluate_ghs(&params, q)).collect();
        let gpu_out = gpu.evaluate_ghs_table(&params, &queries).unwrap().output;
        assert_agree(&format!("ghs {params:?}"), &cpu, &gpu_out);
    }
}
