//! The conformance run: every committed case on every available backend, compared with the
//! case's high-precision reference values and with each other.

use crate::error::SpecError;
use crate::format::g;
use crate::json;
use crate::spec::table_spec;
use scratchwave_cpu::{Backend, evaluate_table};
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

/// Default relative tolerance of a case against its reference, applied where the reference
/// is above [`FLOOR`] times the case's maximum: the f32 kernel's target (issue #2).
pub const DEFAULT_REL_TOL: f64 = 1e-4;
/// Values below this fraction of a case's maximum are compared in absolute terms only.
pub const FLOOR: f64 = 1e-6;

/// A committed case: a table spec, its reference values and its tolerance.
pub struct Case {
    /// File name.
    pub name: String,
    /// What the case exercises.
    pub description: String,
    /// The spec as JSON.
    pub spec: Value,
    /// Reference values (mpmath), one per query.
    pub expected: Vec<f64>,
    /// Relative tolerance above the floor.
    pub rel_tol: f64,
}

/// Agreement between two value lists.
#[derive(Clone, Copy, Debug, Default)]
pub struct Agreement {
    /// Largest |a − b|.
    pub max_abs: f64,
    /// Largest |a − b| / |b| over values with |b| ≥ FLOOR · max|b|.
    pub max_rel: f64,
    /// Largest |a − b| / max|b| over the rest (relative to the case maximum).
    pub max_floor: f64,
}

/// Compares `a` against `b` (the reference side).
pub fn agreement(a: &[f64], b: &[f64]) -> Agreement {
    let peak = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut r = Agreement::default();
    for (x, y) in a.iter().zip(b) {
        let d = (x - y).abs();
        r.max_abs = r.max_abs.max(d);
        if y.abs() >= FLOOR * peak && y.abs() > 0.0 {
            r.max_rel = r.max_rel.max(d / y.abs());
        } else if peak > 0.0 {
            r.max_floor = r.max_floor.max(d / peak);
        }
    }
    r
}

/// Loads every `*.json` case below `dir`, sorted by name.
pub fn load_cases(dir: &Path) -> Result<Vec<Case>, SpecError> {
    let io = |e: std::io::Error| SpecError::Io {
        path: dir.display().to_string(),
        msg: e.to_string(),
    };
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(io)?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    let mut cases = Vec::new();
    for f in files {
        let name = f
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let text = std::fs::read_to_string(&f).map_err(|e| SpecError::Io {
            path: f.display().to_string(),
            msg: e.to_string(),
        })?;
        let v = json::parse(&text, &f.display().to_string())?;
        let field = |k: &str| format!("{name}: {k}");
        let expected = v
            .get("expected")
            .and_then(Value::as_array)
            .ok_or_else(|| SpecError::field(field("expected"), "missing array"))?
            .iter()
            .enumerate()
            .map(|(i, x)| json::number(x, &field(&format!("expected[{i}]"))))
            .collect::<Result<Vec<_>, _>>()?;
        let rel_tol = v
            .get("tolerance")
            .and_then(|t| t.get("rel"))
            .and_then(Value::as_f64)
            .unwrap_or(DEFAULT_REL_TOL);
        let spec = v
            .get("spec")
            .cloned()
            .ok_or_else(|| SpecError::field(field("spec"), "missing"))?;
        let description = v
            .get("description")
            .and_then(Value::as_str)
            .unwrap_or("")
            .to_string();
        cases.push(Case {
            name,
            description,
            spec,
            expected,
            rel_tol,
        });
    }
    Ok(cases)
}

/// Result of one case.
pub struct CaseReport {
    /// Case file name.
    pub name: String,
    /// Number of queries.
    pub queries: usize,
    /// `(label, agreement, tolerance, pass)` per comparison.
    pub rows: Vec<(String, Agreement, f64, bool)>,
}

/// Runs one case on the CPU backends.
pub fn run_case(case: &Case) -> Result<CaseReport, SpecError> {
    let spec = table_spec(&case.spec).map_err(|e| match e {
        SpecError::Field { field, msg } => {
            SpecError::field(format!("{}: spec.{field}", case.name), msg)
        }
        other => other,
    })?;
    if spec.queries.len() != case.expected.len() {
        return Err(SpecError::field(
            format!("{}: expected", case.name),
            format!(
                "{} values for {} queries",
                case.expected.len(),
                spec.queries.len()
            ),
        ));
    }
    let eval = |b| -> Vec<f64> {
        evaluate_table(b, &spec.params, &spec.scratches, &spec.queries)
            .into_iter()
            .map(f64::from)
            .collect()
    };
    let cpu = eval(Backend::Scalar);
    let simd = eval(Backend::Simd);
    let tol = case.rel_tol;
    // Backends run the same f32 code: they must agree far inside the accuracy tolerance.
    let agree_tol = 1e-5;
    let mut rows = Vec::new();
    for (label, a, b, t) in [
        ("cpu vs reference", &cpu, &case.expected, tol),
        ("simd vs reference", &simd, &case.expected, tol),
        ("cpu vs simd", &cpu, &simd, agree_tol),
    ] {
        let ag = agreement(a, b);
        rows.push((
            label.to_string(),
            ag,
            t,
            ag.max_rel <= t && ag.max_floor <= t,
        ));
    }
    Ok(CaseReport {
        name: case.name.clone(),
        queries: spec.queries.len(),
        rows,
    })
}

/// Renders reports as a Markdown table.
pub fn markdown(reports: &[CaseReport]) -> String {
    let mut s = String::from(
        "| case | queries | comparison | max abs | max rel (≥1e-6·max) | max abs/max (below) | tol | ok |\n|---|---|---|---|---|---|---|---|\n",
    );
    for r in reports {
        for (label, a, t, ok) in &r.rows {
            s += &format!(
                "| {} | {} | {} | {} | {} | {} | {} | {} |\n",
                r.name,
                r.queries,
                label,
                g(a.max_abs, 3),
                g(a.max_rel, 3),
                g(a.max_floor, 3),
                g(*t, 2),
                if *ok { "yes" } else { "**NO**" }
            );
        }
    }
    s
}

/// Renders reports as JSON.
pub fn to_json(reports: &[CaseReport]) -> Value {
    Value::Array(
        reports
            .iter()
            .map(|r| {
                json!({"case": r.name, "queries": r.queries, "comparisons": r.rows.iter().map(|(l, a, t, ok)| json!({
                    "comparison": l, "max_abs": a.max_abs, "max_rel": a.max_rel, "max_floor": a.max_floor, "tol": t, "pass": ok
                })).collect::<Vec<_>>()})
            })
            .collect(),
    )
}
