//! The light spec of `scratchwave light SPEC.json` (area-light queries) → kernel records.
//! The evaluation and the CSV `closed_exact_si,closed_approx_si,reference,reference_err`
//! are in `scratchwave-conformance` (`light_spec`); the reader lives here so that it has no
//! backend dependency (the `light_spec` fuzz target links it alone).
//!
//! ```json
//! {"sigma_um": 10, "material": {"F": 1}, "scratches": [{"p0": [-150, 0], "p1": [150, 0],
//!   "width": 1, "depth": 0.1}],
//!  "options": {"eta": "finite", "depth_term": "small_angle", "bands": 1, "reference_rel_tol": 1e-4},
//!  "queries": [{"wo": [0, 0, 1], "lambda_nm": 550, "x": [0, 0],
//!               "light": {"type": "sphere", "center": [0, 0, 10], "radius": 1, "cone": "asin"}},
//!              {"wo": [0.1, 0, 1], "lambda_nm": 550, "x": [0, 0],
//!               "light": {"type": "polygon", "vertices": [[-1, -1, 5], [1, -1, 5], [1, 1, 5]]}}]}
//! ```
//!
//! `sigma_um`, `material` and `scratches` are read exactly as by `scratchwave table` (same
//! field paths in errors); exactly one scratch. `options` is optional: `eta` and
//! `depth_term` as for `table` (model `velinov`), `bands` 1 (Velinov Eq. 27, default), 3 or 5
//! (Gauss–Hermite bands) or 20 (the extent rule; see `lights::integrate::BandRule`), `reference_rel_tol` (default
//! 1e-4). Light positions are in the shading frame, in any one unit. Polygons need ≥ 3
//! vertices; more than the kernel's 16 are split into a fan of triangles about their mean
//! (exact for polygons star-shaped about it). Columns: the closed form with the exact Si,
//! with Eq. 29's Si, the adaptive-quadrature reference and its error estimate.

use crate::SpecError;
use crate::json::{self, Obj};
use crate::range;
use crate::spec::table_spec;
use scratchwave_kernel::lights::{Cone, Light, LightParams, LightQuery, MAX_VERTICES};
use scratchwave_kernel::scratch::Scratch;
use serde_json::{Value, json};

/// A parsed light spec.
#[derive(Clone, Debug, PartialEq)]
pub struct LightSpec {
    /// Options (σ, η mode, depth term, bands; `si_mode` is set per column).
    pub params: LightParams,
    /// The one scratch.
    pub scratch: Scratch,
    /// Per query: the kernel records it sums (one, or a fan of triangles).
    pub queries: Vec<Vec<LightQuery>>,
    /// Relative tolerance of the reference.
    pub reference_rel_tol: f64,
}

/// Reads a light spec.
pub fn light_spec(v: &Value) -> Result<LightSpec, SpecError> {
    let top = Obj::new(
        v,
        "",
        &["sigma_um", "material", "scratches", "options", "queries"],
    )?;
    // Material, σ and scratches exactly as `table` reads them.
    let mut shared = serde_json::Map::new();
    shared.insert("model".into(), json!("velinov"));
    for key in ["sigma_um", "material", "scratches"] {
        if let Some(x) = top.get(key) {
            shared.insert(key.into(), x.clone());
        }
    }
    // One dummy query carries the parsed top-level material back.
    shared.insert(
        "queries".into(),
        json!([{"wi": [0, 0, 1], "wo": [0, 0, 1], "lambda_nm": 500, "x": [0, 0]}]),
    );
    let t = table_spec(&Value::Object(shared))?;
    if t.scratches.len() != 1 {
        return Err(SpecError::field(
            "scratches",
            format!(
                "light specs take exactly one scratch, got {}",
                t.scratches.len()
            ),
        ));
    }
    let material = t.queries[0].material;
    let mut params = LightParams {
        sigma_um: t.params.sigma_um,
        bands: 1,
        ..LightParams::default()
    };
    let mut reference_rel_tol = 1e-4;
    if let Some(o) = top.get("options") {
        let o = Obj::new(
            o,
            "options",
            &["eta", "depth_term", "bands", "reference_rel_tol"],
        )?;
        params.eta = u32::from(o.opt_choice("eta", &["finite", "infinite"])? == Some("infinite"));
        params.depth_term =
            u32::from(o.opt_choice("depth_term", &["small_angle", "exact"])? == Some("exact"));
        if let Some(b) = o.opt_num("bands")? {
            if ![1.0, 3.0, 5.0, 20.0].contains(&b) {
                return Err(SpecError::field(
                    o.path_of("bands"),
                    format!("must be 1, 3, 5 or 20, got {b}"),
                ));
            }
            params.bands = b as u32;
        }
        if let Some(r) = o.opt_num("reference_rel_tol")? {
            if !(1e-9..=0.1).contains(&r) {
                return Err(SpecError::field(
                    o.path_of("reference_rel_tol"),
                    format!("must be in [1e-9, 0.1], got {r}"),
                ));
            }
            reference_rel_tol = r;
        }
    }
    let mut queries = Vec::new();
    for (i, q) in top.arr("queries")?.iter().enumerate() {
        let path = format!("queries[{i}]");
        let q = Obj::new(q, &path, &["wo", "lambda_nm", "x", "light"])?;
        let wo = unit(q.vec::<3>("wo")?, &q.path_of("wo"))?;
        let lambda_nm = range::LAMBDA_NM.check(q.num("lambda_nm")?, &q.path_of("lambda_nm"))?;
        let x = q.vec::<2>("x")?;
        let x = [
            json::to_f32(x[0], &q.path_of("x"))?,
            json::to_f32(x[1], &q.path_of("x"))?,
        ];
        let base = LightQuery {
            wo,
            lambda_nm,
            x,
            material,
            ..LightQuery::default()
        };
        let lights = light(q.req("light")?, &q.path_of("light"))?;
        queries.push(
            lights
                .into_iter()
                .map(|light| LightQuery { light, ..base })
                .collect(),
        );
    }
    Ok(LightSpec {
        params,
        scratch: t.scratches[0],
        queries,
        reference_rel_tol,
    })
}

fn unit(d: [f64; 3], path: &str) -> Result<[f32; 3], SpecError> {
    let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    if !(len > 0.0 && len.is_finite()) {
        return Err(SpecError::field(
            path,
            "direction must have non-zero, finite length",
        ));
    }
    Ok(d.map(|v| (v / len) as f32))
}

fn vec3(v: [f64; 3], path: &str) -> Result<[f32; 3], SpecError> {
    Ok([
        json::to_f32(v[0], path)?,
        json::to_f32(v[1], path)?,
        json::to_f32(v[2], path)?,
    ])
}

/// One light object → the kernel records whose integrals add up to it.
fn light(v: &Value, path: &str) -> Result<Vec<Light>, SpecError> {
    let kind = Obj::new(v, path, &["type", "center", "radius", "cone", "vertices"])?
        .choice("type", &["sphere", "polygon"])?;
    if kind == "sphere" {
        let o = Obj::new(v, path, &["type", "center", "radius", "cone"])?;
        let center = vec3(o.vec::<3>("center")?, &o.path_of("center"))?;
        let radius = json::positive(o.num("radius")?, &o.path_of("radius"), false)?;
        let cone = match o.opt_choice("cone", &["asin", "atan"])? {
            Some("atan") => Cone::Atan,
            _ => Cone::Asin,
        };
        return Ok(vec![Light::sphere(center, radius, cone)]);
    }
    let o = Obj::new(v, path, &["type", "vertices"])?;
    let arr = o.arr("vertices")?;
    if arr.len() < 3 {
        return Err(SpecError::field(
            o.path_of("vertices"),
            format!("needs ≥ 3 vertices, got {}", arr.len()),
        ));
    }
    let mut vs = Vec::with_capacity(arr.len());
    for (k, p) in arr.iter().enumerate() {
        let p_path = format!("{}[{k}]", o.path_of("vertices"));
        vs.push(vec3(json::numbers::<3>(p, &p_path)?, &p_path)?);
    }
    if vs.len() <= MAX_VERTICES {
        return Ok(vec![Light::polygon(&vs)]);
    }
    let n = vs.len() as f32;
    let c = vs.iter().fold([0.0f32; 3], |a, p| {
        [a[0] + p[0] / n, a[1] + p[1] / n, a[2] + p[2] / n]
    });
    Ok((0..vs.len())
        .map(|m| Light::polygon(&[c, vs[m], vs[(m + 1) % vs.len()]]))
        .collect())
}
