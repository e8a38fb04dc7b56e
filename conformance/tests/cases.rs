//! Every committed case file parses, and the reference tables (mpmath) are reproduced by the
//! CPU backends within each case's tolerance. The full run over every backend, including the
//! 10^5–10^6-query cases and SPIR-V, is `scratchwave run` (scripts/test.sh runs it too).

use scratchwave_conformance::run::{load_case, markdown, run_case};
use scratchwave_cpu::{Backend, Cpu};
use scratchwave_host::TableBackend;
use std::path::PathBuf;

fn files(dir: &str) -> Vec<PathBuf> {
    let d = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join(dir);
    let mut v: Vec<PathBuf> = std::fs::read_dir(&d)
        .unwrap_or_else(|e| panic!("{}: {e}", d.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    v.sort();
    v
}

#[test]
fn reference_tables_are_reproduced_on_cpu() {
    let backends: Vec<Box<dyn TableBackend>> =
        vec![Box::new(Cpu(Backend::Scalar)), Box::new(Cpu(Backend::Simd))];
    let mut tables = files("reference/golden/tables");
    tables.extend(files("reference/ghs/golden/tables"));
    assert!(!tables.is_empty(), "no reference tables");
    let mut reports = Vec::new();
    for f in tables {
        let case = load_case(&f).unwrap_or_else(|e| panic!("{e}"));
        assert!(
            case.expected.is_some(),
            "{}: reference tables carry expected values",
            case.name
        );
        reports.push(run_case(&case, &backends));
    }
    let md = markdown(&reports);
    eprintln!("{md}");
    for r in &reports {
        assert!(r.errors.is_empty());
        for row in &r.rows {
            assert!(
                row.pass,
                "{} {}: max rel {} (tol {})",
                r.name, row.label, row.agreement.max_rel, row.tol
            );
        }
    }
}

#[test]
fn committed_conformance_cases_parse() {
    for f in files("conformance/cases") {
        let case = load_case(&f).unwrap_or_else(|e| panic!("{e}"));
        assert!(
            !case.spec.is_empty() && !case.why.is_empty(),
            "{}",
            case.name
        );
    }
}
