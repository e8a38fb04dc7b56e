//! `scratchwave light SPEC.json`: area-light queries → CSV
//! `closed_exact_si,closed_approx_si,reference,reference_err`.
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
//!
//! The reader ([`light_spec`], [`LightSpec`]) is `scratchwave_spec::light`, re-exported here.

use crate::format::g9;
use scratchwave_cpu::parallel::map;
use scratchwave_cpu::{Backend, Cpu};
use scratchwave_host::{BackendError, LightBatch, TableBackend};
use scratchwave_kernel::lights::{LightQuery, SiMode};
pub use scratchwave_spec::light::{LightSpec, light_spec};
use scratchwave_testkit::light_reference::light_reference;

/// One CSV row: `(closed exact Si, closed Eq. 29 Si, reference, reference error)`.
pub type LightRow = (f32, f32, f64, f64);

/// Evaluates every query: the closed forms on `backend` (any [`TableBackend`], the GPU
/// included), the reference on the CPU, in parallel.
pub fn light_rows(
    spec: &LightSpec,
    backend: &dyn TableBackend,
) -> Result<Vec<LightRow>, BackendError> {
    // Flatten the fans into one batch; `owner[i]` is the spec query of batch query `i`.
    let (owner, queries): (Vec<usize>, Vec<LightQuery>) = spec
        .queries
        .iter()
        .enumerate()
        .flat_map(|(i, parts)| parts.iter().map(move |q| (i, *q)))
        .unzip();
    let mut batch = LightBatch {
        params: spec.params,
        scratches: vec![spec.scratch],
        queries,
    };
    let mut closed = |si: SiMode| -> Result<Vec<f32>, BackendError> {
        batch.params.si_mode = si as u32;
        let mut sums = vec![0.0f32; spec.queries.len()];
        for (i, v) in owner.iter().zip(backend.evaluate_light(&batch)?) {
            sums[*i] += v;
        }
        Ok(sums)
    };
    let exact = closed(SiMode::Exact)?;
    let approx = closed(SiMode::Velinov)?;
    let reference = map(Backend::Simd, &spec.queries, |parts: &Vec<LightQuery>| {
        parts.iter().fold((0.0, 0.0), |(v, e), q| {
            let r = light_reference(&spec.params, q, &spec.scratch, spec.reference_rel_tol);
            (v + r.value, e + r.err)
        })
    });
    Ok((0..spec.queries.len())
        .map(|i| (exact[i], approx[i], reference[i].0, reference[i].1))
        .collect())
}

/// The CSV `closed_exact_si,closed_approx_si,reference,reference_err` (header + one line per
/// query), `%.9g`.
pub fn light_csv(spec: &LightSpec) -> String {
    light_csv_on(spec, &Cpu(Backend::Scalar)).unwrap_or_default()
}

/// [`light_csv`] with the closed forms on `backend`.
pub fn light_csv_on(spec: &LightSpec, backend: &dyn TableBackend) -> Result<String, BackendError> {
    let mut out = String::from("closed_exact_si,closed_approx_si,reference,reference_err\n");
    for (a, b, r, e) in light_rows(spec, backend)? {
        out += &format!(
            "{},{},{},{}\n",
            g9(f64::from(a)),
            g9(f64::from(b)),
            g9(r),
            g9(e)
        );
    }
    Ok(out)
}
