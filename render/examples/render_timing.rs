//! Times a scene on both ray backends: `cargo run --release -p scratchwave-render --example
//! render_timing -- SCENE.json [REPEATS [cpu|embree [PREVIEW.png [EXPOSURE]]]]`. Prints ms per frame (median of the repeats, tile
//! loop only), Mrays/s (primary + shadow) and shading evaluations per backend.

use scratchwave_render::{Backend, render_scene, scene_file};
use std::path::Path;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(file) = args.first() else {
        eprintln!(
            "usage: render_timing SCENE.json [REPEATS [cpu|embree [PREVIEW.png [EXPOSURE]]]]"
        );
        std::process::exit(2);
    };
    let repeats: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(5);
    let scene = match scene_file::read_scene(Path::new(file)) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(2);
        }
    };
    println!("| backend | ms/frame (median of {repeats}) | Mrays/s | shading evaluations |");
    println!("|---|---|---|---|");
    for backend in [Backend::Cpu, Backend::Embree] {
        if args.get(2).is_some_and(|b| b != backend.name()) {
            continue;
        }
        let mut runs = Vec::new();
        for _ in 0..repeats {
            match render_scene(&scene, backend, &|_, _| {}) {
                Ok(r) => {
                    if let Some(png) = args.get(3) {
                        let exposure: f32 = args.get(4).and_then(|s| s.parse().ok()).unwrap_or(0.0);
                        if let Err(e) = scratchwave_render::output::write_png(
                            Path::new(png),
                            &r.image,
                            exposure,
                        ) {
                            eprintln!("{png}: {e}");
                        }
                        let max = r.image.rgb.iter().flatten().fold(0.0f32, |a, &b| a.max(b));
                        let lit = r
                            .image
                            .rgb
                            .iter()
                            .filter(|p| p.iter().any(|&c| c > 0.0))
                            .count();
                        eprintln!("{png}: max {max:.3e}, {lit} pixels above 0");
                    }
                    runs.push(r.stats)
                }
                Err(e) => {
                    eprintln!("{}: {e}", backend.name());
                    break;
                }
            }
        }
        if runs.is_empty() {
            continue;
        }
        runs.sort_by(|a, b| a.seconds.total_cmp(&b.seconds));
        let m = runs[runs.len() / 2];
        println!(
            "| {} | {:.1} | {:.3} | {} |",
            backend.name(),
            m.seconds * 1e3,
            m.mrays_per_s(),
            m.shading_evaluations
        );
    }
}
