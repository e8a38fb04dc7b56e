//! Deterministic random table specs for the conformance run (10^4…10^6 queries are too many
//! to commit; the case file holds the recipe, this module expands it).
//!
//! Queries mix the regions where backends are most likely to part ways: near-specular
//! (cancellation in |B − S|²), across scratches on sinc zeros, grazing (z = 1e-3) and
//! below-horizon directions, far segments (up to 20σ), λ at 380 and 780 nm.

use scratchwave_host::TableBatch;
use scratchwave_host::generate::{HalfLength, ProfileMix, ScratchRecipe, Uniform};
use scratchwave_host::rng::SplitMix64;
use scratchwave_kernel::material::{FresnelAngle, Material};
use scratchwave_kernel::table::TableQuery;
use scratchwave_spec::SpecError;
use scratchwave_spec::json::Obj;
use scratchwave_spec::spec::table_spec;
use serde_json::Value;

/// Expands `{"seed", "queries", "scratches", "base": <spec without scratches/queries>}`.
pub fn random_spec(v: &Value, path: &str) -> Result<TableBatch, SpecError> {
    let o = Obj::new(v, path, &["seed", "queries", "scratches", "base"])?;
    let seed = o.integer("seed", 1e15)?;
    let nq = o.integer("queries", 1e7)? as usize;
    let ns = o.integer("scratches", 1e6)? as usize;
    let mut base = o.req("base")?.clone();
    if let Some(m) = base.as_object_mut() {
        m.insert("scratches".into(), Value::Array(vec![]));
        m.insert("queries".into(), Value::Array(vec![]));
    }
    let mut spec = table_spec(&base).map_err(|e| match e {
        SpecError::Field { field, msg } => {
            SpecError::field(format!("{}.{field}", o.path_of("base")), msg)
        }
        other => other,
    })?;
    let sigma = spec.params.sigma_um;
    let mut r = SplitMix64::new(seed);
    spec.scratches = ScratchRecipe {
        count: ns,
        unit: sigma,
        center: [0.0, 0.0],
        side: 2.0,
        outliers: Some((7, 20.0)),
        half_length: HalfLength::Cycle(&[0.05, 0.5, 3.0, 500.0]),
        width: Uniform::new(0.3, 3.0),
        depth: Uniform::new(0.02, 0.6),
        profile: ProfileMix::Alternate,
    }
    .generate(&mut r);
    let first = spec.scratches.first().copied();
    spec.queries = (0..nq)
        .map(|i| {
            let ti = 1.2 * r.next_f32();
            let pi = std::f32::consts::TAU * r.next_f32();
            let mut wi = [ti.sin() * pi.cos(), ti.sin() * pi.sin(), ti.cos()];
            let lambda_nm = [380.0, 780.0, 380.0 + 400.0 * r.next_f32()][i % 3];
            let spread = [0.01, 0.1, 0.6][i % 3];
            let (a, b) = (
                -wi[0] + spread * (r.next_f32() - 0.5),
                -wi[1] + spread * (r.next_f32() - 0.5),
            );
            let mut wo = [a, b, (1.0 - a * a - b * b).max(0.0).sqrt()];
            match i % 16 {
                0 => wi[2] = 1e-3,
                1 => wo[2] = -0.05,
                2 => {
                    // ξ₂ on the first scratch's second sinc zero.
                    if let Some(f) = first.and_then(|s| s.frame().map(|f| (s, f))) {
                        let (s, f) = f;
                        let target = 2.0 * lambda_nm * 1e-3 / s.width;
                        let cur = (wi[0] + wo[0]) * f.bitangent.x + (wi[1] + wo[1]) * f.bitangent.y;
                        wo[0] += (target - cur) * f.bitangent.x;
                        wo[1] += (target - cur) * f.bitangent.y;
                        wo[2] = (1.0 - wo[0] * wo[0] - wo[1] * wo[1]).max(1e-3).sqrt();
                    }
                }
                _ => {}
            }
            let material = if i % 5 == 0 {
                Material::ior(
                    0.2 + 2.0 * r.next_f32(),
                    4.0 * r.next_f32(),
                    FresnelAngle::ThetaD,
                )
            } else {
                spec_material(&spec)
            };
            let n = |v: [f32; 3]| {
                let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(1e-20);
                [v[0] / l, v[1] / l, v[2] / l]
            };
            TableQuery {
                wi: n(wi),
                lambda_nm,
                wo: n(wo),
                x: [(r.next_f32() - 0.5) * sigma, (r.next_f32() - 0.5) * sigma],
                material,
                ..TableQuery::default()
            }
        })
        .collect();
    Ok(spec)
}

/// The spec-level material the base declared (the generator needs it before any query).
fn spec_material(spec: &TableBatch) -> Material {
    spec.default_material
}
