//! Bytes → JSON → `spec::table_spec`; an accepted table is evaluated (at most
//! [`MAX_QUERIES`] queries, through the host's BVH scratch lookup) and every value must be
//! finite, non-negative and within the a-priori bound of `scratchwave_fuzz`.
#![no_main]

use libfuzzer_sys::fuzz_target;
use scratchwave_fuzz::{check, reflectance_bound, table_bound};
use scratchwave_host::ScratchLookup;
use scratchwave_kernel::table::{evaluate, evaluate_ghs};

/// Queries evaluated per input (the reader itself sees all of them).
const MAX_QUERIES: usize = 64;

fuzz_target!(|data: &[u8]| {
    let Ok(v) = serde_json::from_slice::<serde_json::Value>(data) else {
        return;
    };
    let Ok(batch) = scratchwave_spec::spec::table_spec(&v) else {
        return;
    };
    if let Some(g) = &batch.ghs {
        for q in batch.queries.iter().take(MAX_QUERIES) {
            let r = evaluate_ghs(g, q);
            check(r, f64::INFINITY, &|| format!("ghs {g:?} {q:?}"));
        }
        return;
    }
    let lookup = ScratchLookup::new(&batch.scratches, batch.params.sigma_um);
    let set = lookup.set();
    for q in batch.queries.iter().take(MAX_QUERIES) {
        let r = evaluate(&batch.params, q, &set);
        let bound = table_bound(
            reflectance_bound(&q.material),
            batch.params.sigma_um,
            q.lambda_nm,
            &batch.scratches,
        );
        check(r, bound, &|| format!("{:?} {q:?}", batch.params));
    }
});
