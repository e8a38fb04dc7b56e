//! Batch `eval` throughput of the Rust core on queries read from a file, for
//! `python/bench/eval_throughput.py` (which times the Python binding on the same queries in
//! the same run and compares the outputs bit for bit).
//!
//! `cargo run --release -p scratchwave-capi --example eval_throughput -- MATERIAL.json
//! QUERIES.f32 OUT.f32 REPEATS`: QUERIES holds `n` rows of 8 little-endian f32 (`wo`, `wi`,
//! `x_um`); prints the best time of REPEATS runs in ns per query and writes the values.

use scratchwave_capi::{Bsdf, Queries};
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [material, queries, out, repeats] = args.as_slice() else {
        return Err("usage: eval_throughput MATERIAL.json QUERIES.f32 OUT.f32 REPEATS".into());
    };
    let m = Bsdf::from_json(&std::fs::read_to_string(material)?, None, None)?;
    let raw = std::fs::read(queries)?;
    let vals: Vec<f32> = raw
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect();
    let n = vals.len() / 8;
    let (mut wo, mut wi, mut x) = (Vec::new(), Vec::new(), Vec::new());
    for r in vals.chunks_exact(8) {
        wo.extend_from_slice(&r[0..3]);
        wi.extend_from_slice(&r[3..6]);
        x.extend_from_slice(&r[6..8]);
    }
    let q = Queries {
        wo: &wo,
        wi: Some(&wi),
        x_um: Some(&x),
        ..Queries::default()
    };
    let mut f = vec![0.0f32; 3 * n];
    let mut best = f64::INFINITY;
    for _ in 0..repeats.parse::<u32>()?.max(1) {
        let t = Instant::now();
        m.eval(&q, &mut f)?;
        best = best.min(t.elapsed().as_secs_f64());
    }
    println!("{:.3}", best * 1e9 / n as f64);
    let bytes: Vec<u8> = f.iter().flat_map(|v| v.to_le_bytes()).collect();
    std::fs::write(out, bytes)?;
    Ok(())
}
