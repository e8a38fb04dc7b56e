//! Raw bytes reinterpreted (`bytemuck`) as the kernel's GPU records — `TableParams`,
//! `TableQuery`, up to 8 `Scratch`es, `GhsParams`, `LightParams`, `LightQuery`, `Ellipse` and
//! a σ — so every bit pattern reaches the kernel: NaN, ±Inf, huge, denormal, unknown enum
//! words, polygon vertex counts past `MAX_VERTICES`.
//!
//! Two passes over the same records:
//! * **raw**: `table::evaluate`, `table::evaluate_ghs`, `ghs::evaluate`, `light_integral`
//!   and the footprint averages must not panic; the table and light values (documented as
//!   finite and ≥ 0 for every input) must be finite and ≥ 0; `ghs::evaluate` (documented
//!   never NaN/Inf) must be finite and ≥ 0;
//! * **physical**: the same words projected onto the physical domain (finite, σ in
//!   [10⁻², 10³] µm, λ in [300, 2000] nm, unit directions, F ≤ 1, …; see
//!   `scratchwave_fuzz::physical_scratch`): every value is also within the a-priori bounds
//!   documented in `scratchwave_fuzz`.
#![no_main]

use libfuzzer_sys::fuzz_target;
use scratchwave_fuzz::{
    Bytes, SLACK, bits, check, light_bound, lin_range, log_range, physical_material,
    physical_scratch, reflectance_bound, table_bound, unit_direction, unit_of,
};
use scratchwave_kernel::footprint::{
    Ellipse, eta_p_accurate, eta_p_eq15, eta_p_eq16, rho_p_accurate, rho_p_eq18,
};
use scratchwave_kernel::ghs::{self, GhsParams};
use scratchwave_kernel::glam::Vec3;
use scratchwave_kernel::lights::{LightParams, LightQuery, light_integral};
use scratchwave_kernel::scratch::{Scratch, ScratchSlice};
use scratchwave_kernel::table::{TableParams, TableQuery, evaluate, evaluate_ghs};

/// Everything one input decodes to.
struct Records {
    params: TableParams,
    query: TableQuery,
    scratches: Vec<Scratch>,
    ghs: GhsParams,
    light_params: LightParams,
    light: LightQuery,
    ellipse: Ellipse,
    sigma: f32,
}

fn decode(data: &[u8]) -> Records {
    let mut b = Bytes::new(data);
    let n = usize::from(b.byte() % 9);
    Records {
        params: b.record(),
        query: b.record(),
        scratches: (0..n).map(|_| b.record()).collect(),
        ghs: b.record(),
        light_params: b.record(),
        light: b.record(),
        ellipse: b.record(),
        sigma: f32::from_le_bytes(b.take::<4>()),
    }
}

/// Raw pass: no panic, finite and non-negative.
fn raw(r: &Records) {
    let set = ScratchSlice {
        scratches: &r.scratches,
    };
    let v = evaluate(&r.params, &r.query, &set);
    check(v, f64::INFINITY, &|| {
        format!("table {:?} {:?}", r.params, r.query)
    });
    let g = evaluate_ghs(&r.ghs, &r.query);
    check(g, f64::INFINITY, &|| {
        format!("table ghs {:?} {:?}", r.ghs, r.query)
    });
    let wi = Vec3::from_array(r.query.wi);
    let wo = Vec3::from_array(r.query.wo);
    let lambda_um = r.query.lambda_nm * 1.0e-3;
    let g = ghs::evaluate(&r.ghs, wi, wo, lambda_um);
    check(g, f64::INFINITY, &|| {
        format!("ghs {:?} {wi} {wo} {lambda_um}", r.ghs)
    });
    let l = light_integral(&r.light_params, &r.light, &set);
    check(l, f64::INFINITY, &|| {
        format!("light {:?} {:?}", r.light_params, r.light)
    });
    for s in &r.scratches {
        std::hint::black_box((
            eta_p_eq15(s, &r.ellipse, r.sigma),
            eta_p_eq16(s, &r.ellipse, r.sigma),
            eta_p_accurate(s, &r.ellipse, r.sigma),
            rho_p_accurate(s, &r.ellipse, r.sigma),
            rho_p_eq18(s, &r.ellipse),
        ));
    }
}

/// Physical pass: the raw words projected onto the physical domain; values within bounds.
fn physical(r: &Records) {
    let (Some(wi), Some(wo)) = (unit_direction(r.query.wi), unit_direction(r.query.wo)) else {
        return;
    };
    let scratches: Vec<Scratch> = r.scratches.iter().map(physical_scratch).collect();
    let set = ScratchSlice {
        scratches: &scratches,
    };
    let sigma = log_range(bits(r.params.sigma_um), 1.0e-2, 1.0e3, false);
    let params = TableParams {
        sigma_um: sigma,
        ..r.params
    };
    let lambda_nm = log_range(bits(r.query.lambda_nm), 300.0, 2000.0, false);
    let query = TableQuery {
        wi,
        wo,
        lambda_nm,
        x: [
            lin_range(bits(r.query.x[0]), -1.0e5, 1.0e5),
            lin_range(bits(r.query.x[1]), -1.0e5, 1.0e5),
        ],
        material: physical_material(&r.query.material),
        ..r.query
    };
    let v = evaluate(&params, &query, &set);
    let bound = table_bound(
        reflectance_bound(&query.material),
        sigma,
        lambda_nm,
        &scratches,
    );
    check(v, bound, &|| {
        format!("table {params:?} {query:?} {scratches:?}")
    });

    let g = &r.ghs;
    let ghs = GhsParams {
        sigma_s_um: log_range(bits(g.sigma_s_um), 1.0e-3, 1.0e3, true),
        beta: log_range(bits(g.beta), 1.0e-4, 1.0e3, false),
        p: lin_range(bits(g.p), 0.1, 4.0),
        b_um: log_range(bits(g.b_um), 1.0e-3, 1.0e6, false),
        c: 1.0 + log_range(bits(g.c), 1.0e-4, 1.0e4 - 1.0, false),
        n: log_range(bits(g.n), 0.05, 10.0, false),
        k: lin_range(bits(g.k), 0.0, 20.0),
        layer_albedo: unit_of(bits(g.layer_albedo)) as f32,
        ..*g
    };
    let v = ghs::evaluate(&ghs, wi.into(), wo.into(), lambda_nm * 1.0e-3);
    check(v, f64::INFINITY, &|| {
        format!("ghs {ghs:?} {wi:?} {wo:?} {lambda_nm}")
    });

    let lp = LightParams {
        sigma_um: sigma,
        ..r.light_params
    };
    let mut light = r.light;
    light.wo = wo;
    light.lambda_nm = lambda_nm;
    light.x = query.x;
    light.material = query.material;
    // Light geometry: finite positions within ±10³ (any unit), radius in [10⁻³, 10³].
    let l = &mut light.light;
    for c in &mut l.sphere[..3] {
        *c = lin_range(bits(*c), -1.0e3, 1.0e3);
    }
    l.sphere[3] = log_range(bits(l.sphere[3]), 1.0e-3, 1.0e3, false);
    for v in &mut l.vertices {
        for c in v.iter_mut() {
            *c = lin_range(bits(*c), -1.0e3, 1.0e3);
        }
    }
    let v = light_integral(&lp, &light, &set);
    let bound = light_bound(
        reflectance_bound(&light.material),
        lambda_nm,
        sigma,
        lp.bands,
        &scratches,
    );
    check(v, bound, &|| {
        format!("light {lp:?} {light:?} {scratches:?}")
    });

    let e = Ellipse {
        center: [
            lin_range(bits(r.ellipse.center[0]), -1.0e5, 1.0e5),
            lin_range(bits(r.ellipse.center[1]), -1.0e5, 1.0e5),
        ],
        angle_rad: lin_range(bits(r.ellipse.angle_rad), -10.0, 10.0),
        a1: log_range(bits(r.ellipse.a1), 1.0e-3, 1.0e6, false),
        a2: log_range(bits(r.ellipse.a2), 1.0e-3, 1.0e6, false),
        ..r.ellipse
    };
    let s64 = f64::from(sigma);
    let max_eta = 2.0 * std::f64::consts::PI * s64 * s64 * (1.0 + SLACK);
    for s in &scratches {
        let what = || format!("footprint σ {sigma} {s:?} {e:?}");
        let acc = eta_p_accurate(s, &e, sigma);
        check(acc, max_eta, &what);
        let v15 = eta_p_eq15(s, &e, sigma);
        check(v15, f64::INFINITY, &what);
        let v16 = eta_p_eq16(s, &e, sigma);
        check(v16, max_eta.max(f64::from(v15) * (1.0 + SLACK)), &what);
        let max_rho = f64::from(s.width) / (2.0 * std::f64::consts::PI).sqrt() / s64;
        let rho = rho_p_accurate(s, &e, sigma);
        check(rho, max_rho * (1.0 + SLACK) + 1.0e-6, &what);
        check(rho_p_eq18(s, &e), f64::INFINITY, &what);
    }
}

fuzz_target!(|data: &[u8]| {
    let r = decode(data);
    raw(&r);
    physical(&r);
});
