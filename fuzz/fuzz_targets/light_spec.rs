//! Bytes → JSON → `spec::light::light_spec` (the reader of `scratchwave light`); every
//! accepted query (at most [`MAX_QUERIES`], each possibly a fan of triangles) is integrated
//! by `lights::light_integral` with the exact and with Eq. 29's Si. Every part must be
//! finite and ≥ 0; within the physical domain of `kernel_raw` (σ in [10⁻², 10³] µm, λ in
//! [300, 2000] nm, light positions within ±10³, sphere radii in [10⁻³, 10³], scratch
//! width ≤ 100 µm) also at most the a-priori bound of `scratchwave_fuzz::light_bound` (the physical
//! `8π F W² / λ²`, or the fixed band rules' own bound).
//! The adaptive-quadrature reference column (testkit) is not run: it is slow by design.
#![no_main]

use libfuzzer_sys::fuzz_target;
use scratchwave_fuzz::{check, light_bound, reflectance_bound};
use scratchwave_kernel::lights::{LightQuery, SiMode, light_integral};
use scratchwave_kernel::scratch::ScratchSlice;

/// Spec queries integrated per input (the reader itself sees all of them).
const MAX_QUERIES: usize = 16;

/// Whether a query lies in the domain the bound is checked on.
fn physical(sigma: f32, width: f32, q: &LightQuery) -> bool {
    let l = &q.light;
    let in_box = |c: f32| c.abs() <= 1.0e3;
    (1.0e-2..=1.0e3).contains(&sigma)
        && width <= 100.0
        && (300.0..=2000.0).contains(&q.lambda_nm)
        && l.sphere[..3].iter().all(|&c| in_box(c))
        && (l.sphere[3] == 0.0 || (1.0e-3..=1.0e3).contains(&l.sphere[3]))
        && l.vertices.iter().flatten().all(|&c| in_box(c))
}

fuzz_target!(|data: &[u8]| {
    let Ok(v) = serde_json::from_slice::<serde_json::Value>(data) else {
        return;
    };
    let Ok(spec) = scratchwave_spec::light::light_spec(&v) else {
        return;
    };
    let scratches = [spec.scratch];
    let set = ScratchSlice {
        scratches: &scratches,
    };
    for parts in spec.queries.iter().take(MAX_QUERIES) {
        for si in [SiMode::Exact, SiMode::Velinov] {
            let params = scratchwave_kernel::lights::LightParams {
                si_mode: si as u32,
                ..spec.params
            };
            for q in parts {
                let v = light_integral(&params, q, &set);
                let bound = if physical(params.sigma_um, spec.scratch.width, q) {
                    light_bound(
                        reflectance_bound(&q.material),
                        q.lambda_nm,
                        params.sigma_um,
                        params.bands,
                        &scratches,
                    )
                } else {
                    f64::INFINITY
                };
                check(v, bound, &|| {
                    format!("light {params:?} {q:?} {scratches:?}")
                });
            }
        }
    }
});
