//! Frame time of one scene on every backend, in one run: `cpu` (the portable kernel BVH),
//! `embree` and `spirv` (the `render_pixels` compute shader on the Vulkan adapter that
//! `SCRATCHWAVE_ADAPTER` selects), each the median of `REPEATS` renders after one warm-up
//! (which also compiles the GPU pipeline), with shading evaluations per second.
//!
//! ```text
//! cargo run --release -p scratchwave-conformance --example scene_timing -- SCENE.json [REPEATS]
//! ```

use scratchwave_conformance::scene_spirv::render_spirv;
use scratchwave_render::{Backend, Rendered, render_scene, scene_file};
use scratchwave_spirv::Gpu;
use std::path::Path;
use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(path) = args.first() else {
        eprintln!("usage: scene_timing SCENE.json [REPEATS]");
        return ExitCode::from(2);
    };
    let repeats: usize = match args.get(1).map(|r| r.parse()) {
        None => 3,
        Some(Ok(n)) if n > 0 => n,
        Some(_) => {
            eprintln!("REPEATS must be a positive integer");
            return ExitCode::from(2);
        }
    };
    let scene = match scene_file::read_scene(Path::new(path)) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let gpu = Gpu::new().map_err(|e| format!("spirv unavailable: {e}"));
    let adapter = match &gpu {
        Ok(g) => format!("{} ({:?})", g.adapter().name, g.adapter().kind),
        Err(e) => e.clone(),
    };
    let cam = scene.camera;
    println!(
        "## {} ({}x{}, spp {}), median of {repeats}; spirv on {adapter}\n",
        scene.name, cam.width_px, cam.height_px, scene.settings.spp
    );
    println!("| backend | ms/frame | shading evaluations | evaluations/s |");
    println!("|---|---|---|---|");
    let mut failed = false;
    for name in ["cpu", "embree", "spirv"] {
        let once = || -> Result<Rendered, String> {
            match name {
                "cpu" => render_scene(&scene, Backend::Cpu, &|_, _| {}).map_err(|e| e.to_string()),
                "embree" => {
                    render_scene(&scene, Backend::Embree, &|_, _| {}).map_err(|e| e.to_string())
                }
                _ => gpu
                    .as_ref()
                    .map_err(Clone::clone)
                    .and_then(|g| render_spirv(g, &scene, &|_, _| {})),
            }
        };
        let runs: Result<Vec<Rendered>, String> = (0..=repeats).map(|_| once()).collect();
        match runs {
            Ok(runs) => {
                let mut ms: Vec<f64> = runs[1..].iter().map(|r| r.stats.seconds * 1e3).collect();
                ms.sort_by(f64::total_cmp);
                let med = ms[ms.len() / 2];
                let evals = runs[0].stats.shading_evaluations;
                println!(
                    "| {name} | {med:.1} | {evals} | {:.3e} |",
                    evals as f64 / (med / 1e3)
                );
            }
            Err(e) => {
                println!("| {name} | failed: {e} | | |");
                failed = true;
            }
        }
    }
    if failed {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
}
