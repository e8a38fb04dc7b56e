//! `scratchwave`: BRDF tables, footprint tables and the conformance run.
//!
//! Exit codes: 0 success, 1 a conformance disagreement, 2 bad input (the message names the
//! file or field; nothing is written to stdout).

use scratchwave_conformance::format::g9;
use scratchwave_conformance::reference_cmd::flag;
use scratchwave_conformance::{backends, reference_cmd, run};
use scratchwave_host::{BackendError, CaseBatch, TableBackend, TableBatch};
use scratchwave_spec::{SpecError, json, spec};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

const USAGE: &str = "usage:
  scratchwave run [--cases DIR] [--scenes DIR] [--out DIR] [--spirv-scenes yes|no]
                                                  conformance run over the committed cases
                                                  and scenes (embree and spirv renders vs cpu; --spirv-scenes no skips spirv)
  scratchwave table SPEC.json [--backend cpu|simd|spirv|all]
  scratchwave footprint SPEC.json [--backend cpu|simd|spirv]
  scratchwave light SPEC.json [--backend cpu|simd|spirv]
  scratchwave render SCENE.json [--backend cpu|embree|spirv] [--out IMAGE.exr] [--png PREVIEW.png] [--exposure EV] [--model-map MAP.png]
  scratchwave render SCENE.json --integrator reference [--backend cpu|embree] [--out REF.exr] [--png PREVIEW.png]
                    [--rel-stderr 0.01] [--min-spp 256] [--max-spp 65536] [--seed 1] [--spectral continuous|scene] [--pixel box|scene]
                                                  Monte Carlo reference: mean, stderr.R/G/B, spp (docs/reference.md)
  scratchwave compare ANALYTIC.exr REFERENCE.exr [--out-dir DIR]
  scratchwave reference-check SCENE.json [--reference-scene OTHER.json] [--out-dir DIR] [reference options]
                                                  analytic render vs reference: z-score report, EXR, PNG heat map";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match dispatch(&args) {
        Ok(code) => code,
        Err(Failure::Usage(msg)) => {
            eprintln!("error: {msg}\n{USAGE}");
            ExitCode::from(2)
        }
        Err(Failure::Spec(e)) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
        Err(Failure::Backend(e)) => {
            eprintln!("error: backend failed: {e}");
            ExitCode::from(1)
        }
        Err(Failure::Output(e)) => {
            eprintln!("error: writing stdout: {e}");
            ExitCode::from(1)
        }
    }
}

enum Failure {
    Usage(String),
    Spec(SpecError),
    Backend(BackendError),
    Output(String),
}

impl From<SpecError> for Failure {
    fn from(e: SpecError) -> Self {
        Failure::Spec(e)
    }
}

/// Positional arguments and `--flag value` pairs.
type Parsed<'a> = (Vec<&'a str>, Vec<(&'a str, &'a str)>);

/// Splits `args` into positionals and `--flag value` pairs, accepting only `allowed` flags.
fn parse_flags<'a>(args: &'a [String], allowed: &[&str]) -> Result<Parsed<'a>, Failure> {
    let (mut pos, mut flags) = (Vec::new(), Vec::new());
    let mut i = 0;
    while i < args.len() {
        let a = args[i].as_str();
        if let Some(f) = a.strip_prefix("--") {
            if !allowed.contains(&f) {
                return Err(Failure::Usage(format!("unknown option --{f}")));
            }
            let v = args
                .get(i + 1)
                .ok_or_else(|| Failure::Usage(format!("--{f} needs a value")))?;
            flags.push((f, v.as_str()));
            i += 2;
        } else {
            pos.push(a);
            i += 1;
        }
    }
    Ok((pos, flags))
}

/// Bytes of memory a JSON spec takes while it is parsed and read, per byte of the file
/// (text, `serde_json::Value` tree and the records read from it): twice the 12.8 measured
/// with `/usr/bin/time -v scratchwave table` on a listed 10⁵-query spec (10.5 MB file,
/// 134 MB peak RSS; README, Reliability). JSON made of many tiny objects can need more.
const JSON_BYTES_PER_FILE_BYTE: u64 = 24;

/// Reads and parses a JSON spec; refuses, before reading it, a file whose parse would need
/// more than the memory limit (`scratchwave_render::scene_file::memory_limit_bytes`: 8 GiB
/// or half the machine's memory) at [`JSON_BYTES_PER_FILE_BYTE`].
fn read_json(path: &str) -> Result<serde_json::Value, SpecError> {
    let io = |e: std::io::Error| SpecError::Io {
        path: path.into(),
        msg: e.to_string(),
    };
    let len = std::fs::metadata(path).map_err(io)?.len();
    let limit = scratchwave_render::scene_file::memory_limit_bytes();
    if len.saturating_mul(JSON_BYTES_PER_FILE_BYTE) > limit {
        return Err(SpecError::Io {
            path: path.into(),
            msg: format!(
                "{len} bytes would need about {:.1} GiB to read ({JSON_BYTES_PER_FILE_BYTE} per \
                 byte), more than the memory limit of {:.1} GiB (8 GiB or half the machine's \
                 memory); give the queries as a {{\"grid\"}} (README, Reliability)",
                (len.saturating_mul(JSON_BYTES_PER_FILE_BYTE)) as f64 / (1u64 << 30) as f64,
                limit as f64 / (1u64 << 30) as f64
            ),
        });
    }
    let text = std::fs::read_to_string(path).map_err(io)?;
    json::parse(&text, path)
}

/// Queries evaluated per chunk by `scratchwave table` (80 B each: 20 MiB of queries, 1 MiB
/// of values, ~4 MiB of text per chunk).
const TABLE_CHUNK: usize = 1 << 18;

/// `scratchwave table` on one backend: the queries (listed or a grid) are evaluated and
/// written in chunks of [`TABLE_CHUNK`], so memory does not grow with the query count beyond
/// the spec itself. The input was checked whole before anything is written; if the backend
/// fails after the first chunk, the output so far stays on stdout and the exit code is 1.
fn stream_table(s: spec::TableStream, b: &dyn TableBackend) -> Result<ExitCode, Failure> {
    use std::io::Write as _;
    let spec::TableStream { mut batch, grid } = s;
    let listed = std::mem::take(&mut batch.queries);
    let total = grid.as_ref().map_or(listed.len() as u64, |g| g.len());
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::with_capacity(1 << 20, stdout.lock());
    let mut text = String::with_capacity(TABLE_CHUNK * 16);
    let mut start = 0u64;
    while start < total {
        match &grid {
            Some(g) => g.fill(start, TABLE_CHUNK, &mut batch.queries),
            None => {
                let end = (start as usize + TABLE_CHUNK).min(listed.len());
                batch.queries.clear();
                batch
                    .queries
                    .extend_from_slice(&listed[start as usize..end]);
            }
        }
        let values = b.evaluate(&batch).map_err(Failure::Backend)?;
        text.clear();
        for v in values {
            text += &g9(f64::from(v));
            text.push('\n');
        }
        out.write_all(text.as_bytes())
            .map_err(|e| Failure::Output(e.to_string()))?;
        start += batch.queries.len() as u64;
    }
    out.flush().map_err(|e| Failure::Output(e.to_string()))?;
    Ok(ExitCode::SUCCESS)
}

fn one_file<'a>(pos: &[&'a str], cmd: &str) -> Result<&'a str, Failure> {
    match pos {
        [f] => Ok(f),
        _ => Err(Failure::Usage(format!("{cmd} takes exactly one SPEC.json"))),
    }
}

fn dispatch(args: &[String]) -> Result<ExitCode, Failure> {
    let Some(cmd) = args.first() else {
        return Err(Failure::Usage("no command".into()));
    };
    let rest = &args[1..];
    match cmd.as_str() {
        "table" => {
            let (pos, flags) = parse_flags(rest, &["backend"])?;
            let file = one_file(&pos, "table")?;
            let which = flag(&flags, "backend").unwrap_or("cpu");
            let v = read_json(file)?;
            if which == "all" {
                return table_all(&spec::table_spec(&v)?);
            }
            let s = spec::table_stream(&v)?;
            drop(v);
            let b = backends::by_name(which).map_err(|e| Failure::Usage(e.to_string()))?;
            stream_table(s, b.as_ref())
        }
        "light" => {
            let (pos, flags) = parse_flags(rest, &["backend"])?;
            let file = one_file(&pos, "light")?;
            let which = flag(&flags, "backend").unwrap_or("cpu");
            let s = scratchwave_conformance::light_spec::light_spec(&read_json(file)?)?;
            let b = backends::by_name(which).map_err(|e| Failure::Usage(e.to_string()))?;
            let csv = scratchwave_conformance::light_spec::light_csv_on(&s, b.as_ref())
                .map_err(Failure::Backend)?;
            print!("{csv}");
            Ok(ExitCode::SUCCESS)
        }
        "footprint" => {
            let (pos, flags) = parse_flags(rest, &["backend"])?;
            let file = one_file(&pos, "footprint")?;
            let which = flag(&flags, "backend").unwrap_or("cpu");
            let s = spec::footprint_spec(&read_json(file)?)?;
            let b = backends::by_name(which).map_err(|e| Failure::Usage(e.to_string()))?;
            let rows = b.evaluate_footprint(&s).map_err(Failure::Backend)?;
            let mut out = String::from("eq15,eq16,accurate,rho_p\n");
            for r in rows {
                let f = |v: f32| g9(f64::from(v));
                out += &format!(
                    "{},{},{},{}\n",
                    f(r.eq15),
                    f(r.eq16),
                    f(r.accurate),
                    f(r.rho_p)
                );
            }
            print!("{out}");
            Ok(ExitCode::SUCCESS)
        }
        "render" => {
            let mut allowed = vec!["backend", "out", "png", "exposure", "model-map"];
            allowed.extend(reference_cmd::REFERENCE_FLAGS);
            let (pos, flags) = parse_flags(rest, &allowed)?;
            let file = match pos.as_slice() {
                [f] => *f,
                _ => return Err(Failure::Usage("render takes exactly one SCENE.json".into())),
            };
            match flag(&flags, "integrator") {
                Some("reference") => {
                    reference_cmd::render_reference_command(file, &flags)?;
                    Ok(ExitCode::SUCCESS)
                }
                None | Some("analytic") => {
                    if let Some((f, _)) = flags.iter().find(|(f, _)| {
                        reference_cmd::REFERENCE_FLAGS.contains(f) && *f != "integrator"
                    }) {
                        return Err(Failure::Usage(format!(
                            "--{f} needs --integrator reference"
                        )));
                    }
                    render_command(file, &flags)
                }
                Some(other) => Err(Failure::Usage(format!(
                    "unknown --integrator {other:?} (expected analytic or reference)"
                ))),
            }
        }
        "compare" => {
            let (pos, flags) = parse_flags(rest, &["out-dir"])?;
            let [a, r] = pos.as_slice() else {
                return Err(Failure::Usage(
                    "compare takes ANALYTIC.exr REFERENCE.exr".into(),
                ));
            };
            reference_cmd::compare_command(a, r, &flags)?;
            Ok(ExitCode::SUCCESS)
        }
        "reference-check" => {
            let mut allowed = vec!["backend", "out-dir", "reference-scene"];
            allowed.extend(
                reference_cmd::REFERENCE_FLAGS
                    .iter()
                    .filter(|f| **f != "integrator"),
            );
            let (pos, flags) = parse_flags(rest, &allowed)?;
            let file = one_file(&pos, "reference-check")?;
            reference_cmd::reference_check_command(file, &flags)?;
            Ok(ExitCode::SUCCESS)
        }
        "run" => {
            let (pos, flags) = parse_flags(rest, &["cases", "scenes", "out", "spirv-scenes"])?;
            if !pos.is_empty() {
                return Err(Failure::Usage("run takes no positional arguments".into()));
            }
            let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
            let mut scene_dirs: Vec<PathBuf> = flags
                .iter()
                .filter(|(f, _)| *f == "scenes")
                .map(|(_, v)| PathBuf::from(v))
                .collect();
            if scene_dirs.is_empty() && flag(&flags, "cases").is_none() {
                scene_dirs = vec![root.join("conformance/scenes")];
            }
            let mut dirs: Vec<PathBuf> = flags
                .iter()
                .filter(|(f, _)| *f == "cases")
                .map(|(_, v)| PathBuf::from(v))
                .collect();
            if dirs.is_empty() && flag(&flags, "scenes").is_none() {
                dirs = vec![
                    root.join("conformance/cases"),
                    root.join("reference/golden/tables"),
                ];
            }
            let out_dir = flag(&flags, "out")
                .map(PathBuf::from)
                .unwrap_or_else(|| root.join("target/conformance"));
            let spirv_scenes = match flag(&flags, "spirv-scenes") {
                None | Some("yes") => true,
                Some("no") => false,
                Some(other) => {
                    return Err(Failure::Usage(format!(
                        "--spirv-scenes takes yes or no, got {other:?}"
                    )));
                }
            };
            conformance_run(&dirs, &scene_dirs, &out_dir, spirv_scenes)
        }
        "-h" | "--help" | "help" => {
            println!("{USAGE}");
            Ok(ExitCode::SUCCESS)
        }
        other => Err(Failure::Usage(format!("unknown command {other:?}"))),
    }
}

/// `scratchwave render`: renders on the chosen backend, writes the EXR and/or PNG (each
/// through a temporary file, so a failure leaves nothing at the target), and reports time,
/// Mrays/s and shading evaluations on stderr.
fn render_command(file: &str, flags: &[(&str, &str)]) -> Result<ExitCode, Failure> {
    use scratchwave_render::{Backend, RenderError, output};
    use std::io::{IsTerminal, Write};
    let name = flag(flags, "backend").unwrap_or("cpu");
    let backend = match name {
        "cpu" => Some(Backend::Cpu),
        "embree" => Some(Backend::Embree),
        "spirv" => None,
        other => {
            return Err(Failure::Usage(format!(
                "unknown render backend {other:?} (expected cpu, embree or spirv)"
            )));
        }
    };
    let exposure = reference_cmd::exposure_flag(flags)?;
    let scene = scratchwave_render::scene_file::read_scene(Path::new(file))?;
    let tty = std::io::stderr().is_terminal();
    let progress = |done: usize, total: usize| {
        if tty {
            let mut e = std::io::stderr().lock();
            let _ = write!(
                e,
                "\rrendering {:3}% ({done}/{total} {})",
                done * 100 / total.max(1),
                if backend.is_some() { "tiles" } else { "pixels" }
            );
            let _ = e.flush();
        }
    };
    let out = match backend {
        Some(b) => match scratchwave_render::render_scene(&scene, b, &progress) {
            Ok(o) => o,
            Err(RenderError::Input(e)) => return Err(Failure::Spec(e)),
            Err(e) => {
                eprintln!("error: {e}");
                return Ok(ExitCode::from(1));
            }
        },
        None => {
            let rendered = scratchwave_spirv::Gpu::new()
                .map_err(|e| format!("spirv: {e}"))
                .and_then(|gpu| {
                    scratchwave_conformance::scene_spirv::render_spirv(&gpu, &scene, &progress)
                });
            match rendered {
                Ok(o) => o,
                Err(e) => {
                    eprintln!("error: {e}");
                    return Ok(ExitCode::from(1));
                }
            }
        }
    };
    if tty {
        eprintln!();
    }
    let st = &out.stats;
    let attrs = [
        ("scene", scene.name.clone()),
        ("backend", name.to_string()),
        ("render_seconds", format!("{:.6}", st.seconds)),
        ("build_seconds", format!("{:.6}", out.build_seconds)),
        ("primary_rays", st.primary_rays.to_string()),
        ("shadow_rays", st.shadow_rays.to_string()),
        ("shading_evaluations", st.shading_evaluations.to_string()),
    ];
    let write_err = |e: RenderError| {
        Failure::Spec(match e {
            RenderError::Output { path, msg } => {
                SpecError::field(path, format!("cannot write: {msg}"))
            }
            other => SpecError::field(file, other.to_string()),
        })
    };
    if flag(flags, "model-map").is_some() && out.image.model_choice.is_empty() {
        return Err(Failure::Spec(SpecError::field(
            "--model-map",
            "no hit of a material with \"model\": \"auto\" was shaded, so there is no map",
        )));
    }
    if let Some(p) = flag(flags, "out") {
        output::write_exr(Path::new(p), &out.image, &attrs).map_err(write_err)?;
    }
    if let Some(p) = flag(flags, "png") {
        output::write_png(Path::new(p), &out.image, exposure).map_err(write_err)?;
    }
    if let Some(p) = flag(flags, "model-map") {
        output::write_model_map(Path::new(p), &out.image).map_err(write_err)?;
    }
    eprintln!(
        "rendered {}x{} in {:.3} s (+{:.3} s build), {:.4} Mrays/s, {} shading evaluations ({})",
        out.image.width,
        out.image.height,
        st.seconds,
        out.build_seconds,
        st.mrays_per_s(),
        st.shading_evaluations,
        name
    );
    let pairs = st.auto_coherent + st.auto_incoherent;
    if pairs > 0 {
        eprintln!(
            "auto: {} of {pairs} hit-light pairs coherent ({:.1} %), {} incoherent",
            st.auto_coherent,
            100.0 * st.auto_coherent as f64 / pairs as f64,
            st.auto_incoherent
        );
    }
    Ok(ExitCode::SUCCESS)
}

/// `--backend all`: every available backend, pairwise max abs/rel differences; exit 1 beyond
/// the default tolerance.
fn table_all(s: &TableBatch) -> Result<ExitCode, Failure> {
    let (list, notes) = backends::available();
    for n in &notes {
        eprintln!("note: {n}");
    }
    let case = run::Case {
        name: "spec".into(),
        description: String::new(),
        spec: CaseBatch::Table(s.clone()),
        expected: None,
        rel_tol: run::DEFAULT_REL_TOL,
        why: String::new(),
    };
    let report = run::run_case(&case, &list);
    print!("{}", run::markdown(std::slice::from_ref(&report)));
    let ok = report.errors.is_empty() && report.rows.iter().all(|r| r.pass);
    Ok(if ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

fn conformance_run(
    dirs: &[PathBuf],
    scene_dirs: &[PathBuf],
    out_dir: &Path,
    spirv_scenes: bool,
) -> Result<ExitCode, Failure> {
    let cases = run::load_cases(dirs)?;
    if cases.is_empty() && scene_dirs.is_empty() {
        return Err(Failure::Spec(SpecError::Io {
            path: format!("{dirs:?}"),
            msg: "no *.json cases".into(),
        }));
    }
    let (list, notes) = backends::available();
    let names: Vec<String> = list.iter().map(|b| b.name()).collect();
    eprintln!("backends: {}", names.join(", "));
    for n in &notes {
        eprintln!("note: {n}");
    }
    let mut reports = Vec::new();
    for (i, c) in cases.iter().enumerate() {
        eprintln!(
            "[{}/{}] {} ({} queries) — {}",
            i + 1,
            cases.len(),
            c.name,
            c.spec.len(),
            c.description
        );
        reports.push(run::run_case(c, &list));
    }
    let scene_files: Vec<PathBuf> = scene_dirs
        .iter()
        .flat_map(|d| scratchwave_conformance::scenes::scene_files(d))
        .collect();
    let mut scene_reports = Vec::new();
    let diff_dir = out_dir.join("scenes");
    let gpu = if scene_files.is_empty() || !spirv_scenes {
        None
    } else {
        Some(scratchwave_spirv::Gpu::new().map_err(|e| format!("spirv unavailable: {e}")))
    };
    if !scene_files.is_empty() {
        std::fs::create_dir_all(&diff_dir).map_err(|e| {
            Failure::Spec(SpecError::Io {
                path: diff_dir.display().to_string(),
                msg: e.to_string(),
            })
        })?;
    }
    for (i, f) in scene_files.iter().enumerate() {
        eprintln!(
            "[scene {}/{}] {} (embree{} vs cpu)",
            i + 1,
            scene_files.len(),
            f.display(),
            if gpu.is_some() { " and spirv" } else { "" }
        );
        scene_reports.push(scratchwave_conformance::scenes::compare_scene(
            f,
            gpu.as_ref().map(|g| g.as_ref().map_err(String::as_str)),
            Some(&diff_dir),
        ));
    }
    let mut md = if reports.is_empty() {
        String::new()
    } else {
        run::markdown(&reports)
    };
    if !scene_reports.is_empty() {
        md += "\n";
        md += &scratchwave_conformance::scenes::markdown(&scene_reports);
    }
    println!("{md}");
    let failed = reports
        .iter()
        .flat_map(|r| &r.rows)
        .filter(|r| !r.pass)
        .count()
        + reports.iter().map(|r| r.errors.len()).sum::<usize>()
        + scene_reports.iter().filter(|r| !r.pass).count();
    let total = reports
        .iter()
        .map(|r| r.rows.len() + r.errors.len())
        .sum::<usize>()
        + scene_reports.len();
    println!("conformance: {} passed, {} failed", total - failed, failed);
    let io = |e: std::io::Error| {
        Failure::Spec(SpecError::Io {
            path: out_dir.display().to_string(),
            msg: e.to_string(),
        })
    };
    std::fs::create_dir_all(out_dir).map_err(io)?;
    let header = format!("backends: {}\n{}\n\n", names.join(", "), notes.join("\n"));
    std::fs::write(out_dir.join("report.md"), header + &md).map_err(io)?;
    let js = serde_json::json!({"backends": names, "notes": notes, "cases": run::to_json(&reports),
            "scenes": scene_reports.iter().map(|r| serde_json::json!({
                "name": r.name, "width": r.size.0, "height": r.size.1,
                "max_bad_pixels": r.max_bad_pixels, "rel_tol": r.rel_tol, "why": r.why,
                "cpu_seconds": r.cpu_seconds, "pass": r.pass, "error": r.error,
                "against_cpu": r.pairs.iter().map(|p| serde_json::json!({
                    "backend": p.backend, "worst_rel": p.worst, "p999_rel": p.p999,
                    "bad_pixels": p.bad_pixels, "listed": p.listed, "seconds": p.seconds,
                    "pass": p.pass, "known_issue": p.known_issue, "error": p.error,
                })).collect::<Vec<_>>(),
            })).collect::<Vec<_>>()});
    std::fs::write(
        out_dir.join("report.json"),
        serde_json::to_string_pretty(&js).unwrap_or_default(),
    )
    .map_err(io)?;
    eprintln!("wrote {}/report.{{md,json}}", out_dir.display());
    Ok(if failed == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}
