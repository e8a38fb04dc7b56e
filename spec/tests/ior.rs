//! `"ior"`: a constant `[n, k]` or a metal's name (its spectral IOR), for the scratch models'
//! reflectance and for GHS materials alike, with the field path of every rejection.

use scratchwave_kernel::conductor::Conductor;
use scratchwave_kernel::material::{FresnelAngle, Material, MaterialKind};
use scratchwave_spec::SpecError;
use scratchwave_spec::spec::{ghs_material, material};
use serde_json::{Value, json};

fn ghs(ior: Value) -> Value {
    json!({"sigma_s_um": 0.1, "beta": 0.2, "p": 1.0, "b_um": 2.0, "c": 2.0, "ior": ior})
}

/// Asserts a field error at `field` whose message contains `msg`.
fn rejects(r: Result<impl std::fmt::Debug, SpecError>, field: &str, msg: &str) {
    match r {
        Err(SpecError::Field { field: f, msg: m }) => {
            assert_eq!(f, field, "message: {m}");
            assert!(m.contains(msg), "{f}: {m:?} lacks {msg:?}");
        }
        other => panic!("expected a field error at {field}, got {other:?}"),
    }
}

#[test]
fn metal_names_select_the_spectral_curve() {
    for (code, name) in Conductor::NAMES.iter().enumerate() {
        let metal = Conductor::from_u32(code as u32 + 1);
        let m = material(&json!({"ior": name, "fresnel_angle": "normal"}), "m").unwrap();
        assert_eq!(
            m,
            Material::conductor(metal, FresnelAngle::Normal),
            "{name}"
        );
        assert!(m.is_spectral());
        let g = ghs_material(&ghs(json!(name)), "g").unwrap();
        assert_eq!(g.conductor, metal as u32, "{name}");
    }
}

#[test]
fn constant_ior_is_unchanged() {
    let m = material(&json!({"ior": [0.2, 3.5]}), "m").unwrap();
    assert_eq!(m, Material::ior(0.2, 3.5, FresnelAngle::ThetaD));
    assert_eq!(MaterialKind::from_u32(m.kind), MaterialKind::Ior);
    assert!(!m.is_spectral());
    let g = ghs_material(&ghs(json!([1.5, 0.0])), "g").unwrap();
    assert_eq!((g.n, g.k, g.conductor), (1.5, 0.0, Conductor::None as u32));
}

#[test]
fn unknown_metals_and_wrong_types_name_the_field() {
    rejects(
        material(&json!({"ior": "brass"}), "materials.a"),
        "materials.a.ior",
        "gold",
    );
    rejects(material(&json!({"ior": "Gold"}), "m"), "m.ior", "aluminium");
    rejects(
        ghs_material(&ghs(json!("tin")), "g.material"),
        "g.material.ior",
        "nickel",
    );
    rejects(material(&json!({"ior": 1.5}), "m"), "m.ior", "");
    rejects(material(&json!({"ior": [1.5]}), "m"), "m.ior", "");
    rejects(material(&json!({"ior": [-1.0, 0.0]}), "m"), "m.ior[0]", "");
}
