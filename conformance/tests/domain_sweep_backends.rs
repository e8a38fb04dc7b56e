//! The domain sweeps of issue #20 on every backend this machine has (cpu, simd, and spirv
//! on lavapipe or a GPU when Vulkan is present), through the batch interface a user of the
//! CLI or the conformance run goes through: each sweep query is one batch, evaluated at the
//! very f32 inputs the mpmath reference evaluated, and held to the kernel sweeps' rule
//! `err ≤ max(1e-4, 8κ)` (κ the query's one-ulp conditioning; `kernel/tests/sweep_common`).
//!
//! * Scratch models (`reference/golden/sweep/`): every query that `table::evaluate` answers
//!   (Velinov, Werner rect and triangle, and `werner_blended` without a base; its smooth and
//!   GHS bases go through `bsdf::eval`, which no batch interface exposes).
//! * GHS (`reference/ghs/golden/sweep/brdf.csv`): the full BRDF through a GHS table, for the
//!   queries whose inputs the table carries exactly: both directions within the kernel's
//!   unit tolerance (used as given) and λ (µm) the f32 image of some λ in nm under
//!   `units::um_from_nm`.
//!
//! * Pixel footprints (`reference/golden/sweep/footprint.csv`): Eqs. 15, 16, 18 and the
//!   accurate `η_P` through a footprint table (one query per batch), with the footprint
//!   sweep's constants (`K = 8` for the closed forms, 16 for the accurate average;
//!   `kernel/tests/footprint_domain_sweep.rs`).
//!
//! * Area lights (`reference/golden/sweep/light.csv` and `light_found.csv`, and the same
//!   domain with V grooves, `light_vgroove.csv`, whose chords take the quadrature across the
//!   band): Velinov Eq. 27's single band through a light batch (one query per batch), held
//!   to the light sweep's bound `max(1e-4, 8·max(κ, κs))`, an exact 0 to its 8-ulp reach,
//!   and the committed ones also to the inputs' `max(1e-4, 8κ)`, as the kernel sweep holds
//!   the CPU (`kernel/tests/light_domain_sweep.rs`). On SPIR-V that bound needs the kernel's
//!   two-fold arithmetic kept by the driver (`backend-spirv/src/no_contraction.rs`).
//!
//! Run with `--nocapture` for the per-backend tables.

#[path = "../../kernel/tests/sweep_common/mod.rs"]
mod sweep_common;

use scratchwave_conformance::backends::available;
use scratchwave_host::{FootprintBatch, LightBatch, TableBatch};
use scratchwave_kernel::material::Material;
use scratchwave_kernel::table::{TableParams, TableQuery};
use scratchwave_kernel::units::{UNIT_TOLERANCE, um_from_nm};
use std::collections::BTreeMap;
use sweep_common::{
    FLOOR, K, K_LIGHT, SCRATCH_FAMILIES, Stat, Table, footprint_inputs, ghs_params, light_err,
    light_is_vgroove, light_query, light_reach, light_tables, rel, report, scratch_query,
};

/// One sweep query as a batch, with its exact value, κ and report group.
struct Case {
    batch: TableBatch,
    exact: f64,
    kappa: f64,
    group: &'static str,
    row: String,
}

fn scratch_cases() -> Vec<Case> {
    let mut out = Vec::new();
    for family in SCRATCH_FAMILIES {
        let t = Table::load("SCRATCH_SWEEP_DIR", "reference/golden/sweep", family);
        for r in t.rows() {
            let sq = scratch_query(family, &r);
            if sq.base != 0 {
                continue;
            }
            out.push(Case {
                batch: TableBatch {
                    params: sq.params,
                    scratches: sq.scratches,
                    queries: vec![sq.query],
                    default_material: Material::constant(1.0),
                    ghs: None,
                },
                exact: r.d("ref"),
                kappa: r.d("kappa"),
                group: sq.group,
                row: format!("{family}: {}", r.text()),
            });
        }
    }
    out
}

/// The f32 λ in nm whose `um_from_nm` is `um` exactly, if there is one near `1000·um`.
fn nm_of(um: f32) -> Option<f32> {
    let guess = um * 1000.0;
    let mut c = f32::from_bits(guess.to_bits().saturating_sub(4));
    for _ in 0..9 {
        if um_from_nm(c) == um {
            return Some(c);
        }
        c = f32::from_bits(c.to_bits() + 1);
    }
    None
}

fn unit(v: [f32; 3]) -> bool {
    let l2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    (l2 - 1.0).abs() <= UNIT_TOLERANCE
}

fn ghs_cases() -> (Vec<Case>, usize) {
    let t = Table::load("GHS_SWEEP_DIR", "reference/ghs/golden/sweep", "brdf");
    let mut out = Vec::new();
    let mut skipped = 0;
    for r in t.rows() {
        let (wi, wo) = (r.a3("wi"), r.a3("wo"));
        let Some(lambda_nm) = nm_of(r.f("lambda")).filter(|_| unit(wi) && unit(wo)) else {
            skipped += 1;
            continue;
        };
        out.push(Case {
            batch: TableBatch {
                params: TableParams::default(),
                scratches: Vec::new(),
                queries: vec![TableQuery {
                    wi,
                    lambda_nm,
                    wo,
                    ..Default::default()
                }],
                default_material: Material::constant(1.0),
                ghs: Some(ghs_params(&r, "")),
            },
            exact: r.d("ref"),
            kappa: r.d("kappa"),
            group: "GHS ρ (table)",
            row: format!("brdf: {}", r.text()),
        });
    }
    (out, skipped)
}

/// The footprint functions a footprint table returns: CSV prefix, report group, `K`, and
/// the column of `FootprintRow`.
const FOOTPRINT: [(&str, &str, f64); 4] = [
    ("eq15", "footprint Eq. 15", K),
    ("eq16", "footprint Eq. 16", K),
    ("eq18", "footprint Eq. 18 (ρ_P)", K),
    ("eta", "footprint accurate η_P", 16.0),
];

/// One footprint query as a batch, with `(exact, κ)` per entry of [`FOOTPRINT`].
struct FootprintCase {
    batch: FootprintBatch,
    exact: [(f64, f64); 4],
    row: String,
}

fn footprint_cases() -> Vec<FootprintCase> {
    let t = Table::load("FOOTPRINT_SWEEP_DIR", "reference/golden/sweep", "footprint");
    t.rows()
        .map(|r| {
            let (s, e, sigma) = footprint_inputs(&r);
            FootprintCase {
                batch: FootprintBatch {
                    sigma_um: sigma,
                    queries: vec![(s, e)],
                },
                exact: FOOTPRINT
                    .map(|(key, _, _)| (r.d(&format!("{key}_ref")), r.d(&format!("{key}_kappa")))),
                row: format!("footprint: {}", r.text()),
            }
        })
        .collect()
}

/// One light-sweep query as a batch, with its exact value, `max(κ, κs)` and reach.
struct LightCase {
    batch: LightBatch,
    exact: f64,
    kappa: f64,
    /// `κ` of the inputs alone, for the kernel sweep's `max(1e-4, 8κ)`.
    kappa_inputs: f64,
    reach: f64,
    group: &'static str,
    /// The report group under `max(1e-4, 8κ)`.
    strict_group: &'static str,
    row: String,
}

/// The light sweep's queries (`sweep_common::light_tables`).
fn light_cases() -> Vec<LightCase> {
    light_tables()
        .iter()
        .flat_map(Table::rows)
        .map(|r| {
            let (params, query, scratches) = light_query(&r);
            LightCase {
                batch: LightBatch {
                    params,
                    scratches,
                    queries: vec![query],
                },
                exact: r.d("ref"),
                kappa: r.d("kappa").max(r.d("kappa_s")),
                kappa_inputs: r.d("kappa"),
                reach: light_reach(&r),
                group: if light_is_vgroove(&r) {
                    "area light, Eq. 27, V grooves"
                } else {
                    "area light, Eq. 27"
                },
                strict_group: if light_is_vgroove(&r) {
                    "area light, V grooves, 8κ"
                } else {
                    "area light, Eq. 27, 8κ"
                },
                row: format!("light: {}", r.text()),
            }
        })
        .collect()
}

#[test]
fn every_backend_within_the_conditioning_bound() {
    let mut cases = scratch_cases();
    let (ghs, skipped) = ghs_cases();
    let n_ghs = ghs.len();
    cases.extend(ghs);
    println!(
        "{} queries ({n_ghs} GHS; {skipped} GHS queries skipped: inputs a table cannot carry \
         exactly); bound = max({FLOOR:e}, {K}·κ)",
        cases.len()
    );
    assert!(cases.len() >= 4_000, "only {} queries", cases.len());
    assert!(n_ghs >= 200, "only {n_ghs} GHS queries");
    let footprints = footprint_cases();
    assert!(
        footprints.len() >= 800,
        "only {} footprints",
        footprints.len()
    );
    println!("{} footprint queries", footprints.len());
    let lights = light_cases();
    assert!(lights.len() >= 1_500, "only {} lights", lights.len());
    println!("{} light queries", lights.len());
    // The kernel sweep's `max(1e-4, 8κ)` on the lights (groups ordered 4, after the
    // `8·max(κ, κs)` ones): asserted for the committed tables only, as there; a further
    // sample's are reported.
    let strict_asserted = std::env::var_os("LIGHT_SWEEP_DIR").is_none()
        && std::env::var_os("LIGHT_VGROOVE_SWEEP_DIR").is_none();
    let (backends, notes) = available();
    for n in notes {
        println!("{n}");
    }
    let mut bad = Vec::new();
    for b in &backends {
        let start = std::time::Instant::now();
        let mut stats: BTreeMap<(u8, &'static str), Stat> = BTreeMap::new();
        for c in &cases {
            let got = b
                .evaluate(&c.batch)
                .unwrap_or_else(|e| panic!("{}: {e}", c.row))[0];
            let err = rel(got, c.exact);
            let order = u8::from(c.batch.ghs.is_some());
            stats
                .entry((order, c.group))
                .or_default()
                .add(err, c.kappa, || format!("{} ({} {got:e})", c.row, b.name()));
        }
        for c in &footprints {
            let got = b
                .evaluate_footprint(&c.batch)
                .unwrap_or_else(|e| panic!("{}: {e}", c.row))[0];
            let values = [got.eq15, got.eq16, got.rho_p, got.accurate];
            for (i, &(_, group, k)) in FOOTPRINT.iter().enumerate() {
                let (exact, kappa) = c.exact[i];
                stats.entry((2, group)).or_default().add_with(
                    k,
                    rel(values[i], exact),
                    kappa,
                    || format!("{} ({} {:e})", c.row, b.name(), values[i]),
                );
            }
        }
        for c in &lights {
            let got = b
                .evaluate_light(&c.batch)
                .unwrap_or_else(|e| panic!("{}: {e}", c.row))[0];
            let row = || format!("{} ({} {got:e})", c.row, b.name());
            stats.entry((3, c.group)).or_default().add_with(
                K_LIGHT,
                light_err(got, c.exact, c.reach),
                c.kappa,
                row,
            );
            let plain = rel(got, c.exact);
            stats.entry((4, c.strict_group)).or_default().add_with(
                K,
                if plain.is_nan() { f64::INFINITY } else { plain },
                c.kappa_inputs,
                row,
            );
        }
        println!(
            "\n{} ({:.1} s, one batch per query):",
            b.name(),
            start.elapsed().as_secs_f64()
        );
        bad.extend(
            report(&stats, 40)
                .into_iter()
                .filter(|l| strict_asserted || !l.contains(", 8κ:"))
                .map(|l| format!("{}: {l}", b.name())),
        );
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}
