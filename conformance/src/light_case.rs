//! Light-integral conformance cases: a batch of area-light queries over a scratch set,
//! evaluated by every backend's `light` path and compared like a table.
//!
//! A case file holds the recipe `{"random_lights": {"seed", "queries", "eta", "bands",
//! "si"}}` and this module expands it: each query is one configuration of the accuracy
//! sweep (`scratchwave_testkit::light_configs`: spheres with either cone, 3–8-gons tilted up to
//! 50°, partly below the horizon, every scratch orientation), laid out by
//! `light_configs::grid_batch` so one BVH holds all scratches and each query sees exactly
//! its own; odd queries use the V-groove (triangle) profile, which the kernel integrates
//! numerically across the band.

use scratchwave_host::LightBatch;
use scratchwave_kernel::lights::{LightParams, SiMode};
use scratchwave_kernel::scratch::EtaMode;
use scratchwave_spec::SpecError;
use scratchwave_spec::json::Obj;
use scratchwave_testkit::light_configs::{Rng, SweepRanges, grid_batch};
use serde_json::Value;

/// Expands `{"seed", "queries", "eta": "finite"|"infinite", "bands": 1|3|5|20,
/// "si": "exact"|"velinov"|"fast"}` (`eta`, `bands`, `si` optional: finite, 1, exact).
pub fn random_light_batch(v: &Value, path: &str) -> Result<LightBatch, SpecError> {
    let o = Obj::new(v, path, &["seed", "queries", "eta", "bands", "si"])?;
    let seed = o.integer("seed", 1e15)?;
    let count = o.integer("queries", 1e6)? as usize;
    let eta = match o.opt_choice("eta", &["finite", "infinite"])? {
        Some("infinite") => EtaMode::Infinite,
        _ => EtaMode::Finite,
    };
    let bands = match o.get("bands") {
        None => 1,
        Some(_) => match o.integer("bands", 20.0)? {
            b @ (1 | 3 | 5 | 20) => b as u32,
            _ => {
                return Err(SpecError::field(
                    o.path_of("bands"),
                    "must be 1, 3, 5 or 20",
                ));
            }
        },
    };
    let si = match o.opt_choice("si", &["exact", "velinov", "fast"])? {
        Some("velinov") => SiMode::Velinov,
        Some("fast") => SiMode::Fast,
        _ => SiMode::Exact,
    };
    let (params, scratches, queries) = grid_batch(
        &mut Rng::new(seed),
        &SweepRanges::default(),
        eta as u32,
        count,
    );
    let params = LightParams {
        bands,
        si_mode: si as u32,
        ..params
    };
    Ok(LightBatch {
        params,
        scratches,
        queries,
    })
}
