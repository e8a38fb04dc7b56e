//! `scratchwave light`: spec reading (errors name the field) and the CSV on the committed
//! example `docs/examples/light.json`, whose closed-form columns must agree with the
//! reference column within the per-query tolerances below, and within 1 % everywhere with
//! the 3-band Gauss–Hermite rule.

use scratchwave_conformance::light_spec::{light_csv, light_rows, light_spec};
use scratchwave_cpu::{Backend, Cpu};
use scratchwave_spec::SpecError;
use serde_json::json;

/// Per query: in query 2 the band crosses near the edge of the light (Eq. 27's single band
/// is then a few % off; the Hermite bands fix it). Queries 2 and 4 see their lights far off
/// the specular peak, where the band integral is a small difference of Si values and
/// Eq. 29's absolute error (~0.01) swamps it (factors of 5 and 4).
const EXACT_TOL: [f64; 5] = [0.01, 0.01, 0.03, 0.01, 0.01];
/// See [`EXACT_TOL`].
const APPROX_TOL: [f64; 5] = [0.05, 0.05, 1.0, 0.05, 1.0];

fn example() -> serde_json::Value {
    serde_json::from_str(include_str!("../../docs/examples/light.json")).expect("valid JSON")
}

#[test]
fn example_closed_forms_agree_with_the_reference() {
    let spec = light_spec(&example()).expect("valid spec");
    let rows = light_rows(&spec, &Cpu(Backend::Scalar)).unwrap();
    assert_eq!(rows.len(), 5);
    for (i, (exact, approx, reference, err)) in rows.iter().enumerate() {
        println!("{i}: exact {exact:.6e} eq29 {approx:.6e} ref {reference:.6e} ± {err:.1e}");
    }
    for (i, (exact, approx, reference, err)) in rows.iter().enumerate() {
        assert!(*reference > 0.0 && *err < 1e-3 * reference);
        let rel = |v: f32| (f64::from(v) / reference - 1.0).abs();
        assert!(
            rel(*exact) < EXACT_TOL[i],
            "query {i}: {exact} vs {reference}"
        );
        assert!(
            rel(*approx) < APPROX_TOL[i],
            "query {i}: {approx} vs {reference}"
        );
    }
    let mut spec3 = spec.clone();
    spec3.params.bands = 3;
    for (i, (exact, _, reference, _)) in light_rows(&spec3, &Cpu(Backend::Scalar))
        .unwrap()
        .iter()
        .enumerate()
    {
        assert!(
            (f64::from(*exact) / reference - 1.0).abs() < 0.01,
            "3 bands, query {i}"
        );
    }
    let csv = light_csv(&spec);
    assert!(csv.starts_with("closed_exact_si,closed_approx_si,reference,reference_err\n"));
    assert_eq!(csv.lines().count(), 6);
}

#[test]
fn large_polygons_are_split_into_fans() {
    let n = 40;
    let ring: Vec<_> = (0..n)
        .map(|k| {
            let p = std::f64::consts::TAU * k as f64 / n as f64;
            json!([1.5 * p.cos(), 1.5 * p.sin(), 4.0])
        })
        .collect();
    let mut v = example();
    v["queries"] = json!([
        {"wo": [0.05, 0.1, 1], "lambda_nm": 550, "x": [0, 0],
         "light": {"type": "polygon", "vertices": ring}}
    ]);
    let spec = light_spec(&v).expect("valid");
    assert_eq!(spec.queries[0].len(), n);
    let (exact, _, reference, _) = light_rows(&spec, &Cpu(Backend::Scalar)).unwrap()[0];
    assert!(
        (f64::from(exact) / reference - 1.0).abs() < 0.01,
        "{exact} vs {reference}"
    );
}

fn error_of(v: serde_json::Value) -> String {
    match light_spec(&v) {
        Err(SpecError::Field { field, .. }) => field,
        other => panic!("expected a field error, got {other:?}"),
    }
}

#[test]
fn errors_name_the_field() {
    let mut v = example();
    v["queries"][2]["light"]["radius"] = json!(-1);
    assert_eq!(error_of(v), "queries[2].light.radius");
    let mut v = example();
    v["queries"][3]["light"]["vertices"] = json!([[0, 0, 1], [1, 0, 1]]);
    assert_eq!(error_of(v), "queries[3].light.vertices");
    let mut v = example();
    v["queries"][0]["light"]["cone"] = json!("acos");
    assert_eq!(error_of(v), "queries[0].light.cone");
    let mut v = example();
    v["queries"][0]["light"]["type"] = json!("disk");
    assert_eq!(error_of(v), "queries[0].light.type");
    let mut v = example();
    v["scratches"][0]["width"] = json!(-2);
    assert_eq!(error_of(v), "scratches[0].width");
    let mut v = example();
    v["scratches"] = json!([]);
    assert_eq!(error_of(v), "scratches");
    let mut v = example();
    v["options"] = json!({"bands": 2});
    assert_eq!(error_of(v), "options.bands");
    let mut v = example();
    v["queries"][1]["wo"] = json!([0, 0, 0]);
    assert_eq!(error_of(v), "queries[1].wo");
    let mut v = example();
    v["queries"][1]["extra"] = json!(1);
    assert_eq!(error_of(v), "queries[1].extra");
}
