//! White-furnace (directional albedo) tests of the GHS model, through the SIMD backend.
//! They pin down where the model as published conserves, loses or gains energy (chart:
//! `docs/ghs-albedo.svg`, generator `backend-cpu/examples/ghs_albedo.rs`). Albedo is
//! estimated with the model's χ²-tested sampler on a 96×96 stratified grid (≈ 0.5 % noise).

use scratchwave_cpu::Backend;
use scratchwave_cpu::ghs::directional_albedo;
use scratchwave_kernel::ghs::{DiffColor, GhsParams, Layer, layers::LayerForm, presets};

const N: u32 = 96;

fn albedo(p: &GhsParams, thetas_deg: &[f32]) -> Vec<f32> {
    let t: Vec<f32> = thetas_deg.iter().map(|d| d.to_radians()).collect();
    let a = directional_albedo(Backend::Simd, p, 0.526, &t, N);
    println!("{:?} → {a:?}", thetas_deg);
    a
}

/// F ≈ 1 at every angle: isolates geometry and the energy split from colour.
fn mirror(p: GhsParams) -> GhsParams {
    GhsParams {
        n: 0.001,
        k: 1000.0,
        ..p
    }
}

const ANGLES: [f32; 5] = [0.0, 30.0, 60.0, 80.0, 88.0];

#[test]
fn cook_torrance_limit_never_gains() {
    let a = albedo(
        &mirror(GhsParams::new(0.0, 0.2, 0.6, 2.0, 2.0, 0.0, 0.0)),
        &ANGLES,
    );
    assert!(a.iter().all(|&v| v <= 1.01), "{a:?}");
    assert!(
        a[0] > 0.97,
        "single scattering loses little at normal incidence: {a:?}"
    );
}

#[test]
fn uncoloured_split_conserves_or_loses() {
    // colour "none": reflection + diffraction share energy through A; G loses at grazing.
    let p = mirror(presets::ROUGH_METAL).with_diff_color(DiffColor::None);
    let a = albedo(&p, &ANGLES);
    assert!(a.iter().all(|&v| v <= 1.01), "{a:?}");
    assert!((a[0] - 1.0).abs() < 0.02, "{a:?}");
}

#[test]
fn q_colour_gains_at_grazing_for_good_conductors() {
    // Eq. 27's cross-polarised terms grow like 1/cos²θ when |η| ≫ 1 (Rayleigh–Rice multiplies
    // Q by cosθi cosθo; Eq. 36 does not): the published diffraction colour creates energy.
    let a = albedo(&mirror(presets::ROUGH_METAL), &ANGLES);
    assert!(a[4] > 2.0 && a[0] > 1.2, "{a:?}");
}

#[test]
fn published_plastic_gains_energy_corrected_form_does_not() {
    let base = GhsParams::new(0.05, 0.1, 1.0, 3.0, 3.0, 1.5, 0.0);
    let pub_ = albedo(
        &base.with_layer(Layer::Plastic, LayerForm::Published, 1.0),
        &ANGLES,
    );
    let ec = albedo(
        &base.with_layer(Layer::Plastic, LayerForm::EnergyConserving, 1.0),
        &ANGLES,
    );
    assert!(pub_[0] > 1.08, "Eq. 49 with a white base: {pub_:?}");
    assert!(ec.iter().all(|&v| v <= 1.015), "{ec:?}");
    assert!(ec[0] > 0.98, "{ec:?}");
}

#[test]
fn published_subsurface_double_counts_single_scattering() {
    // Jensen's R_d already contains every scattering order; Eq. 48 adds the single-scattering
    // term on top, so α = 1 reflects more than it receives near normal incidence.
    let p = GhsParams::new(0.1, 0.15, 1.0, 2.0, 2.5, 1.5, 0.0).with_layer(
        Layer::Subsurface,
        LayerForm::Published,
        1.0,
    );
    let a = albedo(&p, &ANGLES);
    assert!(a[0] > 1.01, "{a:?}");
}
