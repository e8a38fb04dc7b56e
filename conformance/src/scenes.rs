//! Scene conformance: every scene under `conformance/scenes/` rendered with the portable
//! kernel BVH (`cpu`, the reference), with Embree and with the SPIR-V renderer
//! (`render_pixels` on Vulkan), each compared with `cpu` pixel by pixel.
//!
//! Per pixel and channel the relative difference is `|a − b| / max(|a|, |b|, floor)` with
//! `floor = 1e-6 ×` the image's largest value (dark pixels are compared absolutely at that
//! scale). A comparison passes when at most `max_bad_pixels` pixels exceed the scene's
//! `rel_tol`; both come from the scene's `"conformance"` object with the reason (`"why"`).
//! The pixels beyond it are listed (the first [`LISTED`]) and, with an output directory,
//! each comparison's per-pixel difference is written as an EXR (`<scene>-<backend>-diff.exr`,
//! the relative difference of R, G and B in its channels).

use crate::scene_spirv::render_spirv;
use scratchwave_render::{Backend, Image, Rendered, output, render_scene, scene_file};
use scratchwave_spec::SpecError;
use scratchwave_spec::json::Obj;
use scratchwave_spirv::Gpu;
use std::path::{Path, PathBuf};

/// Pixels beyond tolerance listed per comparison.
pub const LISTED: usize = 20;

/// One backend compared with `cpu` on one scene.
#[derive(Clone, Debug, PartialEq)]
pub struct PairReport {
    /// The backend (`embree` or `spirv`).
    pub backend: String,
    /// Worst relative difference.
    pub worst: f64,
    /// 99.9th percentile of the per-pixel relative difference.
    pub p999: f64,
    /// Pixels beyond `rel_tol`.
    pub bad_pixels: usize,
    /// The first [`LISTED`] of them: `(i, j, relative difference)`.
    pub listed: Vec<(u32, u32, f64)>,
    /// Render seconds.
    pub seconds: f64,
    /// Whether it passed.
    pub pass: bool,
    /// A known defect that makes this comparison fail, declared in the scene file
    /// (`"conformance": {"spirv_known_issue": …}`): the comparison is reported but does not
    /// fail the scene.
    pub known_issue: Option<String>,
    /// A failure to render, if any.
    pub error: Option<String>,
}

impl PairReport {
    /// A comparison not (yet) measured: no differences, not passed, with `error` if any.
    fn unmeasured(backend: &str, error: Option<String>) -> PairReport {
        PairReport {
            backend: backend.to_string(),
            worst: f64::NAN,
            p999: f64::NAN,
            bad_pixels: 0,
            listed: Vec::new(),
            seconds: 0.0,
            pass: false,
            known_issue: None,
            error,
        }
    }
}

/// One scene's comparisons.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneReport {
    /// Scene name (file stem).
    pub name: String,
    /// Image size.
    pub size: (u32, u32),
    /// Declared per-pixel relative tolerance.
    pub rel_tol: f64,
    /// Pixels allowed beyond it (edge ties, grazing hits).
    pub max_bad_pixels: usize,
    /// Why the tolerance is what it is.
    pub why: String,
    /// Render seconds of the `cpu` reference.
    pub cpu_seconds: f64,
    /// `embree` and `spirv` against `cpu`.
    pub pairs: Vec<PairReport>,
    /// Whether every comparison passed.
    pub pass: bool,
    /// A failure to read the scene or render the reference, if any.
    pub error: Option<String>,
}

/// The `*.json` scenes of `dir`, sorted.
pub fn scene_files(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|rd| {
            rd.filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x == "json"))
                .collect()
        })
        .unwrap_or_default();
    v.sort();
    v
}

/// `(rel_tol, max_bad_pixels, why)` from the scene file's `"conformance"` object.
pub fn tolerance(path: &Path) -> Result<(f64, usize, String), SpecError> {
    let file = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| SpecError::Io {
        path: file.clone(),
        msg: e.to_string(),
    })?;
    let v = scratchwave_spec::json::parse(&text, &file)?;
    let c = v
        .get("conformance")
        .ok_or_else(|| SpecError::field("conformance", "missing required field"))?;
    let o = Obj::new(
        c,
        "conformance",
        &["rel_tol", "max_bad_pixels", "why", "spirv_known_issue"],
    )?;
    let rel = o.num("rel_tol")?;
    let bad = if o.get("max_bad_pixels").is_some() {
        o.integer("max_bad_pixels", 1e9)? as usize
    } else {
        0
    };
    let why = o
        .req("why")?
        .as_str()
        .ok_or_else(|| SpecError::field("conformance.why", "expected a string"))?
        .to_string();
    Ok((rel, bad, why))
}

/// The scene file's `conformance.spirv_known_issue`, if any (read after [`tolerance`] has
/// validated the object).
pub fn known_issue(path: &Path) -> Option<String> {
    let text = std::fs::read_to_string(path).ok()?;
    let v = scratchwave_spec::json::parse(&text, &path.display().to_string()).ok()?;
    v.get("conformance")?
        .get("spirv_known_issue")?
        .as_str()
        .map(str::to_string)
}

/// Per-pixel, per-channel relative differences `|x − y| / max(|x|, |y|, 1e-6·peak)` of two
/// images (`peak` the largest value of either).
pub fn channel_differences(a: &[[f32; 3]], b: &[[f32; 3]]) -> Vec<[f64; 3]> {
    let peak = a
        .iter()
        .chain(b)
        .flat_map(|p| p.iter())
        .fold(0.0f64, |m, &x| m.max(f64::from(x).abs()));
    let floor = (peak * 1e-6).max(f64::MIN_POSITIVE);
    a.iter()
        .zip(b)
        .map(|(p, q)| {
            [0, 1, 2].map(|c| {
                let (x, y) = (f64::from(p[c]), f64::from(q[c]));
                (x - y).abs() / x.abs().max(y.abs()).max(floor)
            })
        })
        .collect()
}

/// Per-pixel relative differences (the largest over R, G, B) of two images.
pub fn pixel_differences(a: &[[f32; 3]], b: &[[f32; 3]]) -> Vec<f64> {
    channel_differences(a, b)
        .into_iter()
        .map(|d| d.into_iter().fold(0.0, f64::max))
        .collect()
}

/// The per-pixel comparison of `b` with the reference `a` (its error left `None`).
pub fn compare_images(
    backend: &str,
    a: &Image,
    b: &Image,
    rel_tol: f64,
    max_bad: usize,
) -> PairReport {
    let mut r = PairReport::unmeasured(backend, None);
    if (a.width, a.height) != (b.width, b.height) || a.rgb.len() != b.rgb.len() {
        r.error = Some(format!(
            "image size {}x{} differs from cpu's {}x{}",
            b.width, b.height, a.width, a.height
        ));
        return r;
    }
    let d = pixel_differences(&a.rgb, &b.rgb);
    for (k, &x) in d.iter().enumerate() {
        if !(x <= rel_tol) {
            r.bad_pixels += 1;
            if r.listed.len() < LISTED {
                let w = a.width.max(1) as usize;
                r.listed.push(((k % w) as u32, (k / w) as u32, x));
            }
        }
    }
    let mut sorted = d;
    sorted.sort_by(f64::total_cmp);
    r.worst = sorted.last().copied().unwrap_or(0.0);
    let k = ((sorted.len() as f64) * 0.999).ceil() as usize;
    r.p999 = sorted.get(k.saturating_sub(1)).copied().unwrap_or(0.0);
    r.pass = r.bad_pixels <= max_bad;
    r
}

/// The per-pixel, per-channel relative difference of two images of one size
/// ([`channel_differences`]), as an image.
pub fn difference_image(a: &Image, b: &Image) -> Image {
    Image {
        width: a.width,
        height: a.height,
        rgb: channel_differences(&a.rgb, &b.rgb)
            .into_iter()
            .map(|d| d.map(|x| x as f32))
            .collect(),
        model_choice: Vec::new(),
    }
}

/// Renders one scene on `cpu`, `embree` and (when `gpu` is given) `spirv`, and compares the
/// others with `cpu`. A `gpu` of `Some(Err(reason))` (no device) fails the `spirv`
/// comparison with that reason. With `diff_dir`, each comparison's difference image is
/// written there.
pub fn compare_scene(
    path: &Path,
    gpu: Option<Result<&Gpu, &str>>,
    diff_dir: Option<&Path>,
) -> SceneReport {
    let name = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mut r = SceneReport {
        name,
        size: (0, 0),
        rel_tol: 0.0,
        max_bad_pixels: 0,
        why: String::new(),
        cpu_seconds: 0.0,
        pairs: Vec::new(),
        pass: false,
        error: None,
    };
    let result = (|| -> Result<(), String> {
        let (rel, bad, why) = tolerance(path).map_err(|e| e.to_string())?;
        (r.rel_tol, r.max_bad_pixels, r.why) = (rel, bad, why);
        let scene = scene_file::read_scene(path).map_err(|e| e.to_string())?;
        let a = render_scene(&scene, Backend::Cpu, &|_, _| {}).map_err(|e| e.to_string())?;
        r.size = (a.image.width, a.image.height);
        r.cpu_seconds = a.stats.seconds;
        let mut others: Vec<(&str, Result<Rendered, String>)> = vec![(
            "embree",
            render_scene(&scene, Backend::Embree, &|_, _| {}).map_err(|e| e.to_string()),
        )];
        if let Some(gpu) = gpu {
            others.push((
                "spirv",
                gpu.map_err(str::to_string)
                    .and_then(|g| render_spirv(g, &scene, &|_, _| {})),
            ));
        }
        for (backend, out) in others {
            let pair = match out {
                Ok(b) => {
                    let mut p = compare_images(backend, &a.image, &b.image, rel, bad);
                    p.seconds = b.stats.seconds;
                    if let Some(dir) = diff_dir
                        && p.error.is_none()
                    {
                        let file = dir.join(format!("{}-{backend}-diff.exr", r.name));
                        if let Err(e) =
                            output::write_exr(&file, &difference_image(&a.image, &b.image), &[])
                        {
                            p.error = Some(e.to_string());
                            p.pass = false;
                        }
                    }
                    p
                }
                Err(e) => PairReport::unmeasured(backend, Some(e)),
            };
            r.pairs.push(pair);
        }
        if let Some(p) = r.pairs.iter_mut().find(|p| p.backend == "spirv") {
            p.known_issue = known_issue(path);
        }
        r.pass = r
            .pairs
            .iter()
            .all(|p| (p.pass && p.error.is_none()) || p.known_issue.is_some());
        Ok(())
    })();
    if let Err(e) = result {
        r.error = Some(e);
        r.pass = false;
    }
    r
}

/// A Markdown table of scene reports.
pub fn markdown(reports: &[SceneReport]) -> String {
    let mut s = String::from(
        "## Scenes: embree and spirv against cpu (kernel BVH), per pixel\n\n| scene | size | vs cpu | worst rel | 99.9 % rel | beyond tol | allowed | rel_tol | cpu s | its s | pass |\n|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in reports {
        for p in &r.pairs {
            s += &format!(
                "| {} | {}x{} | {} | {:.3e} | {:.3e} | {} | {} | {:.0e} | {:.3} | {:.3} | {} |\n",
                r.name,
                r.size.0,
                r.size.1,
                p.backend,
                p.worst,
                p.p999,
                p.bad_pixels,
                r.max_bad_pixels,
                r.rel_tol,
                r.cpu_seconds,
                p.seconds,
                if p.pass && p.error.is_none() {
                    "yes"
                } else if p.known_issue.is_some() {
                    "known issue"
                } else {
                    "**no**"
                }
            );
        }
    }
    for r in reports {
        if let Some(e) = &r.error {
            s += &format!("\n{}: error: {e}\n", r.name);
        }
        for p in &r.pairs {
            if let Some(e) = &p.error {
                s += &format!("\n{} ({}): error: {e}\n", r.name, p.backend);
            }
            if !p.listed.is_empty() {
                let list: Vec<String> = p
                    .listed
                    .iter()
                    .map(|(i, j, x)| format!("({i}, {j}) {x:.2e}"))
                    .collect();
                s += &format!(
                    "\n{} ({}): pixels beyond {:.0e}: {}{}\n",
                    r.name,
                    p.backend,
                    r.rel_tol,
                    list.join(", "),
                    if p.bad_pixels > p.listed.len() {
                        ", …"
                    } else {
                        ""
                    }
                );
            }
        }
    }
    for r in reports {
        s += &format!("\n- {}: {}", r.name, r.why);
        for p in &r.pairs {
            if let Some(k) = &p.known_issue {
                s += &format!(" Known issue ({}): {k}", p.backend);
            }
        }
    }
    s.push('\n');
    s
}
