//! Bytes → JSON → `spec::footprint_spec`; every accepted query's footprint averages must be
//! finite, non-negative and within the bounds of `kernel/tests/stability.rs`.
#![no_main]

use libfuzzer_sys::fuzz_target;
use scratchwave_fuzz::SLACK;
use scratchwave_host::FootprintRow;
use scratchwave_kernel::footprint::rho_p_accurate;

fuzz_target!(|data: &[u8]| {
    let Ok(v) = serde_json::from_slice::<serde_json::Value>(data) else {
        return;
    };
    let Ok(batch) = scratchwave_spec::spec::footprint_spec(&v) else {
        return;
    };
    let sigma = batch.sigma_um;
    for (s, e) in batch.queries.iter().take(64) {
        let row = FootprintRow::of(s, e, sigma);
        let rho = rho_p_accurate(s, e, sigma);
        let what = || format!("σ {sigma} {s:?} {e:?} → {row:?}, ρ {rho}");
        for v in [row.eq15, row.eq16, row.accurate, row.rho_p, rho] {
            assert!(v.is_finite() && v >= 0.0, "{}", what());
        }
        let s64 = f64::from(sigma);
        let max_eta = 2.0 * std::f64::consts::PI * s64 * s64 * (1.0 + SLACK);
        assert!(f64::from(row.accurate) <= max_eta, "{}", what());
        assert!(
            f64::from(row.eq16) <= max_eta.max(f64::from(row.eq15) * (1.0 + SLACK)),
            "{}",
            what()
        );
        let max_rho = f64::from(s.width) / (2.0 * std::f64::consts::PI).sqrt() / s64;
        assert!(
            f64::from(rho) <= max_rho * (1.0 + SLACK) + 1.0e-6,
            "{}",
            what()
        );
    }
});
