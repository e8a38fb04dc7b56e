//! The reference commands of the `scratchwave` CLI (`docs/reference.md`):
//! * `render SCENE.json --integrator reference`: the Monte Carlo reference
//!   ([`scratchwave_render::reference`]) written as an EXR with the mean in `R, G, B`, the
//!   standard error in `stderr.R/G/B` and the samples in `spp`;
//! * `compare ANALYTIC.exr REFERENCE.exr`: the per-pixel statistical comparison
//!   ([`scratchwave_render::stat_compare`]);
//! * `reference-check SCENE.json`: both renders and the comparison in one command.
//!
//! Errors are typed [`SpecError`]s naming the flag, file or channel (the CLI exits 2).

use scratchwave_render::layered_exr::{Channels, ExrLayer, write_layers};
use scratchwave_render::reference::{
    PixelSampling, ReferenceImage, ReferenceOptions, SpectralSampling, quantile_sorted,
    relative_error_floor, render_reference,
};
use scratchwave_render::stat_compare::{Comparison, Z_QUANTILES, compare, write_heat_map};
use scratchwave_render::{Backend, Image, RenderError, render_scene, scene_file};
use scratchwave_spec::SpecError;
use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Flags of `render --integrator reference` (besides `render`'s own).
pub const REFERENCE_FLAGS: [&str; 7] = [
    "integrator",
    "pixel",
    "rel-stderr",
    "max-spp",
    "min-spp",
    "seed",
    "spectral",
];

/// The last value given for flag `name` (a later flag overrides an earlier one).
pub fn flag<'a>(flags: &[(&str, &'a str)], name: &str) -> Option<&'a str> {
    flags
        .iter()
        .rev()
        .find(|(f, _)| *f == name)
        .map(|(_, v)| *v)
}

fn bad_flag(name: &str, msg: impl Into<String>) -> SpecError {
    SpecError::field(format!("--{name}"), msg)
}

/// `--exposure EV` (default 0): a finite number, else an error naming the flag.
pub fn exposure_flag(flags: &[(&str, &str)]) -> Result<f32, SpecError> {
    match flag(flags, "exposure") {
        Some(v) => v
            .parse::<f32>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| bad_flag("exposure", format!("expected a finite number, got {v:?}"))),
        None => Ok(0.0),
    }
}

fn int_flag(
    flags: &[(&str, &str)],
    name: &str,
    lo: u64,
    hi: u64,
) -> Result<Option<u64>, SpecError> {
    flag(flags, name)
        .map(|v| {
            v.parse::<u64>()
                .ok()
                .filter(|x| (lo..=hi).contains(x))
                .ok_or_else(|| {
                    bad_flag(
                        name,
                        format!("expected an integer in {lo}..={hi}, got {v:?}"),
                    )
                })
        })
        .transpose()
}

/// The reference options from the flags (defaults: [`ReferenceOptions::default`]).
pub fn reference_options(flags: &[(&str, &str)]) -> Result<ReferenceOptions, SpecError> {
    let mut o = ReferenceOptions::default();
    if let Some(v) = flag(flags, "rel-stderr") {
        o.rel_stderr = v
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite() && *x > 0.0 && *x < 1.0)
            .ok_or_else(|| {
                bad_flag(
                    "rel-stderr",
                    format!("expected a number in (0, 1), got {v:?}"),
                )
            })?;
    }
    if let Some(n) = int_flag(flags, "max-spp", 8, 1 << 24)? {
        o.max_spp = n as u32;
    }
    if let Some(n) = int_flag(flags, "min-spp", 8, 1 << 24)? {
        o.min_spp = n as u32;
    }
    o.max_spp = o.max_spp.max(o.min_spp);
    if let Some(n) = int_flag(flags, "seed", 0, u64::MAX)? {
        o.seed = n;
    }
    o.spectral = match flag(flags, "spectral") {
        None | Some("continuous") => SpectralSampling::Continuous,
        Some("scene") => SpectralSampling::SceneSamples,
        Some(v) => {
            return Err(bad_flag(
                "spectral",
                format!("expected continuous or scene, got {v:?}"),
            ));
        }
    };
    o.pixel = match flag(flags, "pixel") {
        None | Some("box") => PixelSampling::Box,
        Some("scene") => PixelSampling::SceneSamples,
        Some(v) => {
            return Err(bad_flag(
                "pixel",
                format!("expected box or scene, got {v:?}"),
            ));
        }
    };
    Ok(o)
}

fn backend(flags: &[(&str, &str)]) -> Result<Backend, SpecError> {
    match flag(flags, "backend").unwrap_or("embree") {
        "cpu" => Ok(Backend::Cpu),
        "embree" => Ok(Backend::Embree),
        other => Err(bad_flag(
            "backend",
            format!("the reference runs on cpu or embree, got {other:?}"),
        )),
    }
}

fn render_error(file: &str, e: RenderError) -> SpecError {
    match e {
        RenderError::Input(e) => e,
        RenderError::Output { path, msg } => SpecError::field(path, format!("cannot write: {msg}")),
        other => SpecError::field(file, other.to_string()),
    }
}

/// Progress of a reference render on stderr (a terminal: one updating line; otherwise a line
/// per phase).
fn progress_printer() -> impl Fn(usize, usize, u32) + Sync {
    let tty = std::io::stderr().is_terminal();
    move |done: usize, total: usize, phase: u32| {
        let mut e = std::io::stderr().lock();
        if tty {
            let _ = write!(
                e,
                "\rreference phase {phase}/2: {:3}% ({done}/{total} pixels)",
                done * 100 / total.max(1)
            );
            let _ = e.flush();
        } else if done == total {
            let _ = writeln!(e, "reference phase {phase}/2 done ({total} pixels)");
        }
    }
}

/// The summary line of a reference render.
pub fn summary(r: &ReferenceImage) -> String {
    let n = r.spp.len();
    let mut rel: Vec<f64> = (0..n).map(|k| r.rel_stderr(k)).collect();
    rel.sort_by(f64::total_cmp);
    let mut spp: Vec<f64> = r.spp.iter().map(|&s| f64::from(s)).collect();
    spp.sort_by(f64::total_cmp);
    let st = &r.stats;
    format!(
        "reference {}x{}: {} samples (spp median {}, max {}), {:.2} s (+{:.2} s build), relative stderr median {:.2e}, max {:.2e}, {}/{} pixels at target, {} shadow rays{}",
        r.mean.width,
        r.mean.height,
        st.samples,
        quantile_sorted(&spp, 0.5),
        spp.last().copied().unwrap_or(0.0),
        st.seconds,
        st.build_seconds,
        quantile_sorted(&rel, 0.5),
        rel.last().copied().unwrap_or(0.0),
        st.converged_pixels,
        n,
        st.shadow_rays,
        if st.area_fallback_samples > 0 {
            format!(
                ", {} triangle samples by area (fallback)",
                st.area_fallback_samples
            )
        } else {
            String::new()
        }
    )
}

/// Writes a reference image: mean in `R, G, B`, `stderr.R/G/B`, `spp`.
pub fn write_reference(
    path: &Path,
    scene_name: &str,
    r: &ReferenceImage,
    opts: &ReferenceOptions,
) -> Result<(), RenderError> {
    let spp: Vec<f32> = r.spp.iter().map(|&s| s as f32).collect();
    let st = &r.stats;
    write_layers(
        path,
        r.mean.width,
        r.mean.height,
        &[
            ExrLayer::Rgb("", &r.mean.rgb),
            ExrLayer::Rgb("stderr", &r.stderr.rgb),
            ExrLayer::Scalar("spp", &spp),
        ],
        &[
            ("scene", scene_name.to_string()),
            ("integrator", "reference".into()),
            ("seed", opts.seed.to_string()),
            ("pixel", format!("{:?}", opts.pixel)),
            ("spectral", format!("{:?}", opts.spectral)),
            ("rel_stderr_target", opts.rel_stderr.to_string()),
            ("render_seconds", format!("{:.6}", st.seconds)),
            ("samples", st.samples.to_string()),
            ("floor", format!("{:e}", st.floor)),
        ],
    )
}

/// `scratchwave render SCENE.json --integrator reference`.
pub fn render_reference_command(file: &str, flags: &[(&str, &str)]) -> Result<(), SpecError> {
    let opts = reference_options(flags)?;
    let b = backend(flags)?;
    let scene = scene_file::read_scene(Path::new(file))?;
    let progress = progress_printer();
    let r = render_reference(&scene, b, &opts, &progress).map_err(|e| render_error(file, e))?;
    if let Some(p) = flag(flags, "out") {
        write_reference(Path::new(p), &scene.name, &r, &opts).map_err(|e| render_error(file, e))?;
    }
    if let Some(p) = flag(flags, "png") {
        scratchwave_render::output::write_png(Path::new(p), &r.mean, exposure_flag(flags)?)
            .map_err(|e| render_error(file, e))?;
    }
    eprintln!();
    eprintln!("{}", summary(&r));
    Ok(())
}

/// The report of a comparison (markdown), `timing` a line of render times.
pub fn report(name: &str, c: &Comparison, timing: &str) -> String {
    let mut s = format!("## {name}\n\n{timing}\n\n");
    s += &format!(
        "pixels: {}; within 3 SE (every channel): {:.2} %; beyond: {}\n\n",
        c.pixels,
        100.0 * c.within_3se,
        c.beyond
    );
    s += "| channel |";
    for q in Z_QUANTILES {
        s += &format!(" z q{} |", q);
    }
    s += "\n|---|";
    for _ in Z_QUANTILES {
        s += "---|";
    }
    s += "\n";
    for (c_name, qs) in ["R", "G", "B"].iter().zip(&c.z_quantiles) {
        s += &format!("| {c_name} |");
        for q in qs {
            s += &format!(" {q:.3} |");
        }
        s += "\n";
    }
    if c.beyond > 0 {
        let [med, p99, worst] = c.beyond_rel_err;
        let at = c
            .worst_pixel
            .map(|(i, j)| format!(" at pixel ({i}, {j})"))
            .unwrap_or_default();
        s += &format!(
            "\nrelative error of the {} pixels beyond 3 SE (floor {:.3e}): median {:.3e}, 99th percentile {:.3e}, worst {:.3e}{at}\n",
            c.beyond, c.floor, med, p99, worst
        );
    } else {
        s += "\nno pixel beyond 3 SE\n";
    }
    s
}

/// Writes the comparison's EXR (`z.R/G/B`, `rel_err.R/G/B`) and PNG heat map into `dir`.
fn write_comparison(dir: &Path, stem: &str, c: &Comparison) -> Result<Vec<PathBuf>, RenderError> {
    let exr = dir.join(format!("{stem}-zscore.exr"));
    write_layers(
        &exr,
        c.z.width,
        c.z.height,
        &[
            ExrLayer::Rgb("z", &c.z.rgb),
            ExrLayer::Rgb("rel_err", &c.rel_err.rgb),
        ],
        &[("floor", format!("{:e}", c.floor))],
    )?;
    let png = dir.join(format!("{stem}-zscore.png"));
    write_heat_map(&png, c)?;
    Ok(vec![exr, png])
}

fn make_dir(dir: &Path) -> Result<(), SpecError> {
    std::fs::create_dir_all(dir).map_err(|e| SpecError::Io {
        path: dir.display().to_string(),
        msg: e.to_string(),
    })
}

fn same_size(a: &Image, b: &Image, what: &str) -> Result<(), SpecError> {
    if (a.width, a.height) != (b.width, b.height) {
        return Err(SpecError::field(
            what,
            format!(
                "image is {}x{}, the reference {}x{}",
                a.width, a.height, b.width, b.height
            ),
        ));
    }
    Ok(())
}

/// The floor of relative errors of a reference read from a file
/// ([`relative_error_floor`]).
fn floor_of(mean: &Image) -> f64 {
    relative_error_floor(mean.rgb.iter().map(|p| p.map(f64::from)))
}

/// `scratchwave compare ANALYTIC.exr REFERENCE.exr [--out-dir DIR]`: prints the report,
/// writes the z-score EXR and heat map when `--out-dir` is given.
pub fn compare_command(
    analytic: &str,
    reference: &str,
    flags: &[(&str, &str)],
) -> Result<(), SpecError> {
    let a = Channels::read(Path::new(analytic))?.rgb("")?;
    let rc = Channels::read(Path::new(reference))?;
    let (mean, se) = (rc.rgb("")?, rc.rgb("stderr")?);
    same_size(&a, &mean, analytic)?;
    let c = compare(&a, &mean, &se, floor_of(&mean));
    let stem = Path::new(analytic)
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "analytic".into());
    print!(
        "{}",
        report(&stem, &c, &format!("{analytic} against {reference}"))
    );
    if let Some(dir) = flag(flags, "out-dir") {
        let dir = Path::new(dir);
        make_dir(dir)?;
        for p in write_comparison(dir, &stem, &c).map_err(|e| render_error(analytic, e))? {
            eprintln!("wrote {}", p.display());
        }
    }
    Ok(())
}

/// `scratchwave reference-check SCENE.json [--reference-scene OTHER.json] [--out-dir DIR]`:
/// the analytic render of SCENE, the reference of SCENE (or of OTHER, a scene of the same
/// size whose materials are the model to measure against, e.g. Werner's coherent sum for
/// a Velinov scene), the comparison report on stdout, the images in DIR (default
/// `target/reference-check`).
pub fn reference_check_command(file: &str, flags: &[(&str, &str)]) -> Result<(), SpecError> {
    let opts = reference_options(flags)?;
    let b = backend(flags)?;
    let scene = scene_file::read_scene(Path::new(file))?;
    let ref_file = flag(flags, "reference-scene").unwrap_or(file);
    let ref_scene = scene_file::read_scene(Path::new(ref_file))?;
    if (scene.camera.width_px, scene.camera.height_px)
        != (ref_scene.camera.width_px, ref_scene.camera.height_px)
    {
        return Err(bad_flag(
            "reference-scene",
            format!("{ref_file} has another image size than {file}"),
        ));
    }
    let dir = flag(flags, "out-dir")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("target/reference-check"));
    make_dir(&dir)?;
    let t = Instant::now();
    let analytic = render_scene(&scene, b, &|_, _| {}).map_err(|e| render_error(file, e))?;
    let analytic_s = t.elapsed().as_secs_f64();
    eprintln!("analytic: {analytic_s:.3} s");
    let progress = progress_printer();
    let r =
        render_reference(&ref_scene, b, &opts, &progress).map_err(|e| render_error(ref_file, e))?;
    eprintln!();
    eprintln!("{}", summary(&r));
    let c = compare(&analytic.image, &r.mean, &r.stderr, r.stats.floor);
    let timing = format!(
        "analytic {:.3} s, reference {:.2} s ({} samples, target relative stderr {}, max spp {}, seed {}, pixel {:?}, spectral {:?}){}",
        analytic_s,
        r.stats.seconds + r.stats.build_seconds,
        r.stats.samples,
        opts.rel_stderr,
        opts.max_spp,
        opts.seed,
        opts.pixel,
        opts.spectral,
        if ref_file != file {
            format!("; reference scene {ref_file}")
        } else {
            String::new()
        }
    );
    print!("{}", report(&scene.name, &c, &timing));
    let out_err = |e: RenderError| render_error(file, e);
    let a_path = dir.join(format!("{}-analytic.exr", scene.name));
    scratchwave_render::output::write_exr(
        &a_path,
        &analytic.image,
        &[("scene", scene.name.clone())],
    )
    .map_err(out_err)?;
    let r_path = dir.join(format!("{}-reference.exr", scene.name));
    write_reference(&r_path, &ref_scene.name, &r, &opts).map_err(out_err)?;
    let mut written = vec![a_path, r_path];
    written.extend(write_comparison(&dir, &scene.name, &c).map_err(out_err)?);
    for p in written {
        eprintln!("wrote {}", p.display());
    }
    Ok(())
}
