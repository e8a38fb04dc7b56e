//! Domain sweep of the scratch models (issue #20) — Velinov's incoherent point model
//! (Velinov et al. 2018 Eq. 7, with the Gaussian base of Eq. 6 and the spatial phase of
//! Werner App. A or Velinov Eq. 8), Werner's coherent model (Werner et al. 2017 Eq. 15,
//! rectangular and triangular grooves, Eqs. 26–31) and Werner's model blended with a base
//! (Werner §5: `|S|² + max(1 − ρc, 0) f_base`, family `werner_blended`) — against the mpmath
//! reference `reference/scratch_sweep.py`, at the very f32 inputs the reference evaluated,
//! through `table::evaluate` (what every backend runs for a table query) and, for
//! `werner_blended` with a smooth or GHS base, `bsdf::eval` (the renderer's BRDF, which adds
//! the `(1 − ρc)` base; a smooth base is a delta and adds nothing to the value).
//!
//! Every query stores its f32 inputs, the exact value at those inputs and its conditioning
//! `κ`: the largest relative change of the exact value when one input moves by one f32 ulp.
//! A kernel result is accepted when
//!
//! `err ≤ max(1e-4, K·κ)`, `K = 8`,
//!
//! the rule of the GHS sweep (`ghs_domain_sweep.rs`). `κ` is what an exact evaluation would
//! already lose to rounding one input; the kernel rounds each quantity the result depends on
//! (`ξ`, the frame components `ξ₁, ξ₂, s_t, s_b`, the phases) a few times, each rounding worth
//! at most about one input ulp of the same quantity, so a sound formula stays within a small
//! multiple of `κ`: measured on the subset where `K·κ` binds (1 615 queries), `err/κ` ≤ 2.07
//! (the Werner cancellation sweep, `conformance/tests/cancellation_sweep.rs`, measured up to
//! 4.5 of its own conditioning measure with the same `K`). The formulas the sweep found
//! unsound were 10 to 6 200 `κ` off (`docs/stability.md`). `1e-4` is the kernel's accuracy
//! target for well-conditioned queries.
//!
//! The committed subset (`reference/golden/sweep/`) runs by default; the full sweep
//! (`python3 reference/scratch_sweep.py --full --out DIR`, 10⁵ queries per family) with
//! `SCRATCH_SWEEP_DIR=DIR`. `SCRATCH_SWEEP_DUMP=FILE` writes every query's first scratch's
//! depth and width, min(cosθi, cosθo), σ, err, bound and κ for the stability map
//! (`docs/scratch_stability_map.py`); `SCRATCH_SWEEP_OVER=FILE` every query over its bound.

mod sweep_common;

use glam::Vec3;
use scratchwave_kernel::bsdf::{self, BsdfMaterial, Lookup, ShadingPoint, Wavelengths};
use scratchwave_kernel::ghs::GhsParams;
use scratchwave_kernel::render::shading::BaseKind;
use scratchwave_kernel::scratch::ScratchSlice;
use scratchwave_kernel::table::{TableParams, TableQuery, evaluate};
use std::collections::BTreeMap;
use std::fmt::Write as _;
use sweep_common::{
    FLOOR, K, Row, SCRATCH_FAMILIES, Stat, Table, bound, ghs_params, rel, report, scratch_query,
};

/// The kernel's value of one query, and its report group.
fn kernel_value(family: &str, r: &Row) -> (f32, &'static str) {
    let sq = scratch_query(family, r);
    let set = ScratchSlice {
        scratches: &sq.scratches,
    };
    let got = if sq.base == BaseKind::None as u32 {
        evaluate(&sq.params, &sq.query, &set)
    } else {
        blended_bsdf(r, sq.base, &sq.params, &sq.query, set)
    };
    (got, sq.group)
}

/// `werner_blended` with a smooth (`base` 1) or GHS (`base` 2) base: `bsdf::eval` at the
/// query's one wavelength, the depth term as the query gives it.
fn blended_bsdf(
    r: &Row,
    base: u32,
    params: &TableParams,
    q: &TableQuery,
    set: ScratchSlice<'_>,
) -> f32 {
    let ghs = if base == BaseKind::Ghs as u32 {
        ghs_params(r, "ghs_")
    } else {
        GhsParams::default()
    };
    let mut m = BsdfMaterial::werner_blended(params.sigma_um, q.material, ghs);
    m.base = base;
    m.depth = if params.depth_term == 1 {
        bsdf::DepthChoice::Exact as u32
    } else {
        bsdf::DepthChoice::SmallAngle as u32
    };
    let v = bsdf::eval(
        &m,
        &ShadingPoint::at(q.x),
        Vec3::from_array(q.wi),
        Vec3::from_array(q.wo),
        &Wavelengths::single(q.lambda_nm),
        &Lookup::new(set),
    );
    v.v[0]
}

#[test]
fn every_query_within_its_conditioning_bound() {
    let mut stats: BTreeMap<(usize, &'static str), Stat> = BTreeMap::new();
    let mut total = 0;
    let mut over_rows = Vec::new();
    let mut dump = String::new();
    for (fi, family) in SCRATCH_FAMILIES.iter().enumerate() {
        let t = Table::load("SCRATCH_SWEEP_DIR", "reference/golden/sweep", family);
        assert!(!t.rows.is_empty(), "{family}: no queries");
        for r in t.rows() {
            let (got, group) = kernel_value(family, &r);
            let (want, kappa) = (r.d("ref"), r.d("kappa"));
            let err = rel(got, want);
            total += 1;
            let ratio = stats.entry((fi, group)).or_default().add(err, kappa, || {
                format!("{family}: {} (kernel {got:e})", r.text())
            });
            writeln!(
                dump,
                "{family},{},{},{},{},{err},{},{kappa}",
                r.d("s0_d"),
                r.d("wi_z").min(r.d("wo_z")),
                r.d("sigma"),
                r.d("s0_w"),
                bound(kappa),
            )
            .unwrap();
            if !(ratio <= 1.0) {
                over_rows.push(format!(
                    "{family},{ratio:.3},{err:.3e},{kappa:.3e},{got:e},{}",
                    r.text()
                ));
            }
        }
    }
    println!("{total} queries; bound = max({FLOOR:e}, {K}·κ)");
    let bad = report(&stats, 40);
    if let Ok(path) = std::env::var("SCRATCH_SWEEP_DUMP") {
        let head = "family,depth,cos,sigma,width,err,bound,kappa";
        std::fs::write(&path, format!("{head}\n{dump}")).unwrap();
    }
    if let Ok(path) = std::env::var("SCRATCH_SWEEP_OVER") {
        std::fs::write(&path, over_rows.join("\n")).unwrap();
    }
    assert!(total >= 4_000, "only {total} queries");
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}
