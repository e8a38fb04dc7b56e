//! Bytes → (sources JSON, CSV file, JSON file) → `spec::scratches::scratch_sources_with_limit`.
//!
//! The input is split at its first two NUL bytes: the sources array, then the contents of
//! `s.csv`, then of `s.json`, both written to a per-process temporary directory that
//! `{"file": "s.csv"}` / `{"file": "s.json"}` sources read. The segment budget is
//! [`LIMIT`] (the documented 2²⁵ would let one 200-byte pattern allocate 1 GiB per run).
//! Accepted segments must be finite with a unit tangent and non-negative sizes.
#![no_main]

use libfuzzer_sys::fuzz_target;
use scratchwave_fuzz::check_segment;
use std::path::PathBuf;
use std::sync::OnceLock;

/// Segment budget per input.
const LIMIT: usize = 1 << 16;

fn dir() -> &'static PathBuf {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let d = std::env::temp_dir().join(format!("scratchwave-fuzz-{}", std::process::id()));
        std::fs::create_dir_all(&d).expect("temp dir");
        d
    })
}

fuzz_target!(|data: &[u8]| {
    let mut parts = data.splitn(3, |&b| b == 0);
    let sources = parts.next().unwrap_or_default();
    let csv = parts.next().unwrap_or_default();
    let json = parts.next().unwrap_or_default();
    let Ok(v) = serde_json::from_slice::<serde_json::Value>(sources) else {
        return;
    };
    let d = dir();
    std::fs::write(d.join("s.csv"), csv).expect("write csv");
    std::fs::write(d.join("s.json"), json).expect("write json");
    let Ok(out) =
        scratchwave_spec::scratches::scratch_sources_with_limit(&v, "scratches", d, LIMIT)
    else {
        return;
    };
    assert!(out.len() <= LIMIT, "{} segments", out.len());
    for s in &out {
        check_segment(s);
    }
});
