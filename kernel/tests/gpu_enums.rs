//! Every GPU-visible enum decodes its own codes both ways, rejects unknown codes on the host
//! with an error naming the enum, and falls back to its documented variant on the GPU side.

use scratchwave_kernel::ghs::layers::LayerForm;
use scratchwave_kernel::ghs::{DiffColor, Layer};
use scratchwave_kernel::gpu_enum::UnknownVariant;
use scratchwave_kernel::lights::{BandRule, Cone, LightKind, LightMethod, SiMode};
use scratchwave_kernel::material::{FresnelAngle, MaterialKind};
use scratchwave_kernel::render::area::SceneLightKind;
use scratchwave_kernel::render::camera::Projection;
use scratchwave_kernel::render::model_choice::Choice;
use scratchwave_kernel::render::shading::{BaseKind, SceneModel};
use scratchwave_kernel::render::spectrum::SpectrumMode;
use scratchwave_kernel::render::surface::SurfaceKind;
use scratchwave_kernel::scratch::{DepthTerm, EtaMode, Profile};
use scratchwave_kernel::table::Model;

/// Checks `variants` (all of an enum's variants) and its fallback.
fn check<E>(name: &str, variants: &[E], fallback: E, from_u32: fn(u32) -> E)
where
    E: Copy + PartialEq + core::fmt::Debug + Into<u32> + TryFrom<u32, Error = UnknownVariant>,
{
    let codes: Vec<u32> = variants.iter().map(|&v| v.into()).collect();
    for (&v, &code) in variants.iter().zip(&codes) {
        assert_eq!(E::try_from(code), Ok(v), "{name}: {code}");
        assert_eq!(from_u32(code), v, "{name}: {code}");
    }
    let unknown = (0..=codes.iter().max().copied().unwrap_or(0) + 1)
        .chain([u32::MAX])
        .filter(|c| !codes.contains(c));
    for code in unknown {
        let err = E::try_from(code).unwrap_err();
        assert_eq!((err.enum_name, err.value), (name, code));
        assert!(err.to_string().contains(name), "{err}");
        assert_eq!(from_u32(code), fallback, "{name}: fallback for {code}");
    }
}

#[test]
fn every_gpu_enum_round_trips_and_rejects_unknown_codes() {
    check(
        "Projection",
        &[Projection::Orthographic, Projection::Perspective],
        Projection::Orthographic,
        Projection::from_u32,
    );
    check(
        "SurfaceKind",
        &[
            SurfaceKind::Rectangle,
            SurfaceKind::Sphere,
            SurfaceKind::Mesh,
        ],
        SurfaceKind::Rectangle,
        SurfaceKind::from_u32,
    );
    check(
        "SceneLightKind",
        &[
            SceneLightKind::Point,
            SceneLightKind::Directional,
            SceneLightKind::Sphere,
            SceneLightKind::Triangle,
        ],
        SceneLightKind::Point,
        SceneLightKind::from_u32,
    );
    check(
        "Choice",
        &[Choice::Coherent, Choice::Incoherent],
        Choice::Coherent,
        Choice::from_u32,
    );
    check(
        "SceneModel",
        &[
            SceneModel::Werner,
            SceneModel::WernerBlended,
            SceneModel::Velinov,
            SceneModel::Ghs,
            SceneModel::Auto,
        ],
        SceneModel::Werner,
        SceneModel::from_u32,
    );
    check(
        "BaseKind",
        &[BaseKind::None, BaseKind::Smooth, BaseKind::Ghs],
        BaseKind::None,
        BaseKind::from_u32,
    );
    check(
        "SpectrumMode",
        &[
            SpectrumMode::Single,
            SpectrumMode::Rgb,
            SpectrumMode::Spectral,
        ],
        SpectrumMode::Single,
        SpectrumMode::from_u32,
    );
    check(
        "Model",
        &[Model::Werner, Model::WernerBlended, Model::Velinov],
        Model::Werner,
        Model::from_u32,
    );
    check(
        "MaterialKind",
        &[MaterialKind::Constant, MaterialKind::Ior],
        MaterialKind::Ior,
        MaterialKind::from_u32,
    );
    check(
        "FresnelAngle",
        &[
            FresnelAngle::ThetaD,
            FresnelAngle::ThetaI,
            FresnelAngle::Normal,
        ],
        FresnelAngle::ThetaD,
        FresnelAngle::from_u32,
    );
    check(
        "BandRule",
        &[
            BandRule::Single,
            BandRule::Hermite3,
            BandRule::Hermite5,
            BandRule::Extent,
        ],
        BandRule::Single,
        BandRule::from_u32,
    );
    check(
        "LightMethod",
        &[
            LightMethod::Extent,
            LightMethod::Eq27,
            LightMethod::Eq27Eq29,
            LightMethod::Hermite3,
            LightMethod::Hermite5,
        ],
        LightMethod::Extent,
        LightMethod::from_u32,
    );
    // What each method asks of the light integral.
    let rules: Vec<(BandRule, SiMode)> = [
        LightMethod::Extent,
        LightMethod::Eq27,
        LightMethod::Eq27Eq29,
        LightMethod::Hermite3,
        LightMethod::Hermite5,
    ]
    .iter()
    .map(|m| (m.band_rule(), m.si_mode()))
    .collect();
    assert_eq!(
        rules,
        [
            (BandRule::Extent, SiMode::Exact),
            (BandRule::Single, SiMode::Exact),
            (BandRule::Single, SiMode::Velinov),
            (BandRule::Hermite3, SiMode::Exact),
            (BandRule::Hermite5, SiMode::Exact),
        ]
    );
    check(
        "SiMode",
        &[SiMode::Exact, SiMode::Velinov, SiMode::Fast],
        SiMode::Exact,
        SiMode::from_u32,
    );
    check(
        "Cone",
        &[Cone::Asin, Cone::Atan],
        Cone::Asin,
        Cone::from_u32,
    );
    check(
        "LightKind",
        &[LightKind::Sphere, LightKind::Polygon],
        LightKind::Sphere,
        LightKind::from_u32,
    );
    check(
        "LayerForm",
        &[LayerForm::Published, LayerForm::EnergyConserving],
        LayerForm::Published,
        LayerForm::from_u32,
    );
    check(
        "DiffColor",
        &[
            DiffColor::HalfQ,
            DiffColor::Q,
            DiffColor::Fresnel,
            DiffColor::None,
        ],
        DiffColor::HalfQ,
        DiffColor::from_u32,
    );
    check(
        "Layer",
        &[Layer::None, Layer::Plastic, Layer::Subsurface],
        Layer::None,
        Layer::from_u32,
    );
    check(
        "Profile",
        &[Profile::Rect, Profile::Triangle],
        Profile::Rect,
        Profile::from_u32,
    );
    check(
        "DepthTerm",
        &[DepthTerm::SmallAngle, DepthTerm::Exact],
        DepthTerm::SmallAngle,
        DepthTerm::from_u32,
    );
    check(
        "EtaMode",
        &[EtaMode::Finite, EtaMode::Infinite],
        EtaMode::Finite,
        EtaMode::from_u32,
    );
}

#[test]
fn band_rule_codes_are_the_band_counts_of_light_params() {
    assert_eq!(BandRule::from_u32(0), BandRule::Single);
    assert_eq!(BandRule::from_u32(20), BandRule::Extent);
    assert_eq!(u32::from(BandRule::Hermite5), 5);
}
