//! Speed against accuracy of the scratch models on one scene (`docs/tradeoff.md`).
//!
//! ```text
//! tradeoff SCENE.json [--variants werner,velinov,velinov:eq27,velinov:eq27_eq29,velinov:hermite3,auto:0.1,auto:0.01,auto:0.001]
//!          [--reference-spp 16,64,256,1024] [--truth-spp 4096] [--repeats 3]
//!          [--backend embree|cpu] [--out-dir docs/tradeoff] [--name NAME]
//! ```
//!
//! Every `werner`/`werner_blended`/`velinov`/`auto` material of the scene is rewritten per
//! variant (`scratchwave_benches::tradeoff::rewrite`); each variant is rendered `--repeats`
//! times by the analytic renderer (median tile-loop time = ms/frame). The truth is the Monte
//! Carlo reference of the `werner` variant at the scene's own sub-pixel positions and
//! wavelengths, `--truth-spp` samples per pixel, seed 1; the reference at each
//! `--reference-spp` (seed 2) is the Monte Carlo curve. Errors against the truth: relative
//! RMSE and the 99th percentile of the per-pixel relative error. Writes `OUT/NAME.csv` and
//! `OUT/NAME.svg` (each to a temporary name, then renamed), prints a Markdown table; bad
//! input exits 2 with `error: <flag or file>: <what>` and writes nothing.

use scratchwave_benches::svg::{Extras, HLine, PointLabel, Series, loglog_with};
use scratchwave_benches::tradeoff::{
    Args, BackendChoice, Errors, Variant, errors, floor_of, median, noise, parse_args, rewrite,
};
use scratchwave_render::reference::{
    PixelSampling, ReferenceImage, ReferenceOptions, SpectralSampling, render_reference,
};
use scratchwave_render::render::RenderStats;
use scratchwave_render::{Backend, Image, Scene, render_scene, scene_file};
use serde_json::Value;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

/// Seed of the truth.
const TRUTH_SEED: u64 = 1;
/// Seed of the Monte Carlo curve (independent of the truth).
const CURVE_SEED: u64 = 2;

fn fail(what: &str, msg: impl std::fmt::Display) -> ExitCode {
    eprintln!("error: {what}: {msg}");
    ExitCode::from(2)
}

/// One measured point.
struct Row {
    kind: &'static str,
    label: String,
    /// `None`: the variant failed (message printed).
    result: Option<Measured>,
}

struct Measured {
    ms: f64,
    build_ms: f64,
    err: Errors,
    shading_evaluations: Option<u64>,
    samples: Option<u64>,
    /// `auto` variants: the share of hit–light pairs shaded with the coherent model (%).
    coherent_pct: Option<f64>,
    /// Relative RMSE against the `werner` variant's analytic image (the model choice's
    /// own difference, without the truth's noise).
    vs_werner: Option<f64>,
}

fn main() -> ExitCode {
    let argv: Vec<String> = std::env::args().skip(1).collect();
    let args = match parse_args(&argv) {
        Ok(a) => a,
        Err((what, msg)) => return fail(&what, msg),
    };
    let out_dir = PathBuf::from(&args.out_dir);
    if out_dir.exists() && !out_dir.is_dir() {
        return fail(
            "--out-dir",
            format!("{} is not a directory", out_dir.display()),
        );
    }
    let text = match std::fs::read_to_string(&args.scene) {
        Ok(t) => t,
        Err(e) => return fail(&args.scene, format!("cannot read: {e}")),
    };
    let value: Value = match serde_json::from_str(&text) {
        Ok(v) => v,
        Err(e) => return fail(&args.scene, format!("malformed JSON: {e}")),
    };
    let scene_path = Path::new(&args.scene);
    let base_dir = scene_path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let stem = scene_path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let read = |v: &Variant| -> Result<Scene, String> {
        let (rv, n) = rewrite(&value, v)?;
        if n == 0 {
            return Err("no material of model werner, werner_blended, velinov or auto".into());
        }
        scene_file::scene_from_value(&rv, &stem, base_dir).map_err(|e| e.to_string())
    };
    // The truth's scene must read: without it nothing can be measured.
    let truth_scene = match read(&Variant::Werner) {
        Ok(s) => s,
        Err(e) => return fail(&args.scene, format!("the werner variant (the truth): {e}")),
    };
    let backend = match args.backend {
        BackendChoice::Embree => Backend::Embree,
        BackendChoice::Cpu => Backend::Cpu,
    };
    match run(&args, &truth_scene, backend, &read) {
        Ok(()) => ExitCode::SUCCESS,
        Err((what, msg)) => fail(&what, msg),
    }
}

fn run(
    args: &Args,
    truth_scene: &Scene,
    backend: Backend,
    read: &dyn Fn(&Variant) -> Result<Scene, String>,
) -> Result<(), (String, String)> {
    let t_all = Instant::now();
    let (w, h) = (truth_scene.camera.width_px, truth_scene.camera.height_px);
    let threads = rayon::current_num_threads();
    eprintln!(
        "{}: {w}×{h}, backend {}, {threads} threads",
        args.name,
        backend.name()
    );

    // The truth first: every error needs it.
    let truth = reference(truth_scene, backend, args.truth_spp, TRUTH_SEED, "truth")
        .map_err(|e| (args.scene.clone(), format!("the truth: {e}")))?;
    let floor = floor_of(&truth.mean.rgb);
    let truth_noise = noise(&truth.mean.rgb, &truth.stderr.rgb, floor);
    eprintln!(
        "truth noise: rel RMS {:.3e}, p99 {:.3e} (floor {floor:.3e})",
        truth_noise.rel_rmse, truth_noise.p99
    );
    let err_of = |img: &Image| errors(&img.rgb, &truth.mean.rgb, floor);

    let mut rows: Vec<Row> = Vec::new();
    let mut images: Vec<(String, Image)> = Vec::new();
    for v in &args.variants {
        let label = v.label();
        let kind = if v.is_auto() { "auto" } else { "model" };
        let result = match measure_variant(v, read, backend, args.repeats) {
            Ok((ms, build_ms, image, stats)) => {
                let err = err_of(&image);
                eprintln!(
                    "{label}: {ms:.2} ms/frame, rel RMSE {:.3e}, p99 {:.3e}",
                    err.rel_rmse, err.p99
                );
                let pairs = stats.auto_coherent + stats.auto_incoherent;
                images.push((label.clone(), image));
                Some(Measured {
                    ms,
                    build_ms,
                    err,
                    shading_evaluations: Some(stats.shading_evaluations),
                    samples: None,
                    coherent_pct: (pairs > 0)
                        .then(|| 100.0 * stats.auto_coherent as f64 / pairs as f64),
                    vs_werner: None,
                })
            }
            Err(e) => {
                eprintln!("{label}: failed: {e}");
                None
            }
        };
        rows.push(Row {
            kind,
            label,
            result,
        });
    }
    // Each variant against Werner's analytic image: what the model choice alone changes.
    if let Some((_, werner)) = images.iter().find(|(l, _)| l == "werner") {
        let werner_floor = floor_of(&werner.rgb);
        for (label, image) in &images {
            let row = rows.iter_mut().find(|r| &r.label == label);
            if let Some(m) = row.and_then(|r| r.result.as_mut()) {
                m.vs_werner = Some(errors(&image.rgb, &werner.rgb, werner_floor).rel_rmse);
            }
        }
    }
    for &spp in &args.reference_spp {
        let r = reference(truth_scene, backend, spp, CURVE_SEED, &format!("{spp} spp")).map_err(
            |e| {
                (
                    args.scene.clone(),
                    format!("the reference at {spp} spp: {e}"),
                )
            },
        )?;
        let err = err_of(&r.mean);
        eprintln!(
            "reference {spp} spp: rel RMSE {:.3e}, p99 {:.3e}",
            err.rel_rmse, err.p99
        );
        rows.push(Row {
            kind: "reference",
            label: format!("reference {spp} spp"),
            result: Some(Measured {
                ms: 1e3 * r.stats.seconds,
                build_ms: 1e3 * r.stats.build_seconds,
                err,
                shading_evaluations: None,
                samples: Some(r.stats.samples),
                coherent_pct: None,
                vs_werner: None,
            }),
        });
    }
    rows.push(Row {
        kind: "truth",
        label: format!("truth {} spp (noise)", args.truth_spp),
        result: Some(Measured {
            ms: 1e3 * truth.stats.seconds,
            build_ms: 1e3 * truth.stats.build_seconds,
            err: truth_noise,
            shading_evaluations: None,
            samples: Some(truth.stats.samples),
            coherent_pct: None,
            vs_werner: None,
        }),
    });

    let csv = csv(&rows);
    let svg = chart(args, &rows, truth_noise);
    write_outputs(args, &csv, &svg)?;
    // The model-choice map of each `auto` variant (blue incoherent, orange coherent).
    for (label, image) in images.iter().filter(|(_, i)| !i.model_choice.is_empty()) {
        let path = Path::new(&args.out_dir).join(format!(
            "{}-{}-map.png",
            args.name,
            label.replace(':', "_")
        ));
        scratchwave_render::output::write_model_map(&path, image)
            .map_err(|e| ("--out-dir".to_string(), e.to_string()))?;
    }
    print_table(args, w, h, threads, backend, &rows);
    eprintln!(
        "wrote {}/{}.csv and .svg; {:.1} s in all",
        args.out_dir,
        args.name,
        t_all.elapsed().as_secs_f64()
    );
    Ok(())
}

/// Renders variant `v` `repeats` times: median tile-loop ms, median build ms, the image of
/// the last render (renders are deterministic) and its shading evaluations.
fn measure_variant(
    v: &Variant,
    read: &dyn Fn(&Variant) -> Result<Scene, String>,
    backend: Backend,
    repeats: u32,
) -> Result<(f64, f64, Image, RenderStats), String> {
    let scene = read(v)?;
    let (mut times, mut builds) = (Vec::new(), Vec::new());
    let mut last = None;
    for k in 0..repeats {
        let r = render_scene(&scene, backend, &|_, _| {}).map_err(|e| e.to_string())?;
        eprintln!(
            "{} {}/{repeats}: {:.4} s (+{:.3} s build)",
            v.label(),
            k + 1,
            r.stats.seconds,
            r.build_seconds
        );
        times.push(1e3 * r.stats.seconds);
        builds.push(1e3 * r.build_seconds);
        last = Some(r);
    }
    let r = last.ok_or("no render")?;
    Ok((median(&times), median(&builds), r.image, r.stats))
}

/// The reference of `scene` at the scene's sub-pixel positions and wavelengths, exactly
/// `spp` samples per pixel (no stopping rule).
fn reference(
    scene: &Scene,
    backend: Backend,
    spp: u32,
    seed: u64,
    what: &str,
) -> Result<ReferenceImage, String> {
    eprintln!("{what}: reference, {spp} spp, seed {seed} ...");
    let opts = ReferenceOptions {
        seed,
        rel_stderr: 0.01,
        min_spp: spp,
        max_spp: spp,
        spectral: SpectralSampling::SceneSamples,
        pixel: PixelSampling::SceneSamples,
    };
    let r = render_reference(scene, backend, &opts, &|_, _, _| {}).map_err(|e| e.to_string())?;
    eprintln!(
        "{what}: {:.2} s (+{:.3} s build), {} samples",
        r.stats.seconds, r.stats.build_seconds, r.stats.samples
    );
    Ok(r)
}

/// A measured row's cells after the label: ms, build ms, relative RMSE, p99, shading
/// evaluations, samples, coherent %, relative RMSE against `werner`; `precise` for the CSV
/// (more digits), `missing` for an absent value.
fn cells(m: &Measured, precise: bool, missing: &str) -> [String; 8] {
    let opt = |x: Option<String>| x.unwrap_or_else(|| missing.to_string());
    let (t, e) = if precise { (4, 6) } else { (2, 2) };
    [
        format!("{:.t$}", m.ms),
        format!("{:.1$}", m.build_ms, if precise { 4 } else { 1 }),
        format!("{:.e$e}", m.err.rel_rmse),
        format!("{:.e$e}", m.err.p99),
        opt(m.shading_evaluations.map(|v| v.to_string())),
        opt(m.samples.map(|v| v.to_string())),
        opt(m.coherent_pct.map(|p| format!("{p:.2}"))),
        opt(m.vs_werner.map(|p| format!("{p:.e$e}"))),
    ]
}

fn csv(rows: &[Row]) -> String {
    let mut s = String::from(
        "kind,variant,status,ms_per_frame,build_ms,rel_rmse,p99,shading_evaluations,samples,coherent_pct,rel_rmse_vs_werner\n",
    );
    for r in rows {
        match &r.result {
            Some(m) => {
                let _ = writeln!(
                    s,
                    "{},{},ok,{}",
                    r.kind,
                    r.label,
                    cells(m, true, "").join(",")
                );
            }
            None => {
                let _ = writeln!(s, "{},{},failed,,,,,,,,", r.kind, r.label);
            }
        }
    }
    s
}

/// Two log–log charts side by side: relative RMSE and p99 against ms/frame.
fn chart(args: &Args, rows: &[Row], truth_noise: Errors) -> String {
    let kinds: [(&str, &str, &str, bool); 3] = [
        ("model", "fixed models", "#1f77b4", false),
        ("auto", "auto:T", "#2ca02c", true),
        (
            "reference",
            "Monte Carlo reference (seed 2)",
            "#d62728",
            true,
        ),
    ];
    let one = |pick: fn(&Errors) -> f64, title: &str, ylabel: &str| -> String {
        let mut series = Vec::new();
        let mut labels = Vec::new();
        for (kind, name, color, line) in kinds {
            let pts: Vec<(f64, f64, String)> = rows
                .iter()
                .filter(|r| r.kind == kind)
                .filter_map(|r| {
                    r.result.as_ref().map(|m| {
                        let text = match kind {
                            "reference" => r.label.trim_start_matches("reference ").to_string(),
                            _ => r.label.clone(),
                        };
                        (m.ms, pick(&m.err).max(1e-9), text)
                    })
                })
                .collect();
            if pts.is_empty() {
                continue;
            }
            for (x, y, t) in &pts {
                labels.push(PointLabel {
                    x: *x,
                    y: *y,
                    text: t.clone(),
                    color: color.into(),
                });
            }
            series.push(Series {
                label: name.into(),
                color: color.into(),
                points: pts.iter().map(|p| (p.0, p.1, p.1, p.1)).collect(),
                line,
            });
        }
        let extras = Extras {
            labels,
            hlines: vec![HLine {
                y: pick(&truth_noise).max(1e-9),
                label: format!("truth's own noise ({} spp)", args.truth_spp),
                color: "#555".into(),
            }],
            notes: vec![
                format!("{}, backend {}", args.name, backend_name(args.backend)),
                "truth: werner reference,".into(),
                format!("{} spp, seed 1", args.truth_spp),
                "x: median render time".into(),
                "(tile loop, no build)".into(),
            ],
            whiskers: false,
            y_headroom: 1.5,
        };
        loglog_with(title, "ms per frame", ylabel, &series, &extras)
    };
    let left = one(
        |e| e.rel_rmse,
        &format!("{}: relative RMSE against the truth", args.name),
        "relative RMSE",
    );
    let right = one(
        |e| e.p99,
        &format!("{}: 99th percentile of the pixel error", args.name),
        "p99 relative error",
    );
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"1800\" height=\"600\">\n<g>{left}</g>\n<g transform=\"translate(900,0)\">{right}</g>\n</svg>\n"
    )
}

fn backend_name(b: BackendChoice) -> &'static str {
    match b {
        BackendChoice::Embree => "embree",
        BackendChoice::Cpu => "cpu",
    }
}

/// Writes both files to temporary names, then renames them; nothing is left on failure.
fn write_outputs(args: &Args, csv: &str, svg: &str) -> Result<(), (String, String)> {
    let dir = Path::new(&args.out_dir);
    let e = |m: String| ("--out-dir".to_string(), m);
    std::fs::create_dir_all(dir).map_err(|x| e(format!("{}: {x}", dir.display())))?;
    let files = [("csv", csv), ("svg", svg)];
    let mut tmps = Vec::new();
    for (ext, body) in files {
        let target = dir.join(format!("{}.{ext}", args.name));
        let tmp = dir.join(format!(
            ".{}.{ext}.{}.partial",
            args.name,
            std::process::id()
        ));
        if let Err(x) = std::fs::write(&tmp, body) {
            let _ = std::fs::remove_file(&tmp);
            for (t, _) in &tmps {
                let _ = std::fs::remove_file(t);
            }
            return Err(e(format!("{}: {x}", target.display())));
        }
        tmps.push((tmp, target));
    }
    for (tmp, target) in &tmps {
        if let Err(x) = std::fs::rename(tmp, target) {
            for (t, _) in &tmps {
                let _ = std::fs::remove_file(t);
            }
            return Err(e(format!("{}: {x}", target.display())));
        }
    }
    Ok(())
}

fn print_table(args: &Args, w: u32, h: u32, threads: usize, backend: Backend, rows: &[Row]) {
    println!(
        "{} ({w}×{h}, {} backend, {threads} threads; truth: werner reference, {} spp, seed 1)\n",
        args.name,
        backend.name(),
        args.truth_spp
    );
    println!(
        "| variant | ms/frame | build ms | rel. RMSE | p99 | shading evaluations | samples | coherent % | rel. RMSE vs werner |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for r in rows {
        match &r.result {
            Some(m) => println!("| {} | {} |", r.label, cells(m, false, "—").join(" | ")),
            None => println!("| {} | failed | | | | | | | |", r.label),
        }
    }
}
