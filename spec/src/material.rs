//! A scene material (JSON) → the kernel's [`ShadeMaterial`] and its scratches: the
//! `materials.NAME` objects of a scene file (`docs/render.md`), also what the C and Python
//! bindings take. Every rejection names the field.

use crate::error::SpecError;
use crate::json::Obj;
use crate::spec;
use scratchwave_kernel::lights::LightMethod;
use scratchwave_kernel::material::Material;
use scratchwave_kernel::render::shading::{BaseKind, SceneModel, ShadeMaterial};
use scratchwave_kernel::scratch::Scratch;
use scratchwave_kernel::scratch::{Crossings, DepthTerm, Window};
use scratchwave_kernel::table::{Model, TableParams};
use serde_json::Value;
use std::path::Path;

/// The `tolerance` of an `auto` material that gives none.
pub const DEFAULT_TOLERANCE: f32 = 0.01;

/// The `"light_integral"` names of [`LightMethod`] (default `extent`).
pub const LIGHT_METHODS: [(&str, LightMethod); 5] = [
    ("extent", LightMethod::Extent),
    ("eq27", LightMethod::Eq27),
    ("eq27_eq29", LightMethod::Eq27Eq29),
    ("hermite3", LightMethod::Hermite3),
    ("hermite5", LightMethod::Hermite5),
];

/// A material as read: the kernel record and its scratches (µm of scratch space).
#[derive(Clone, Debug, PartialEq)]
pub struct MaterialSpec {
    /// Model, options, reflectance, GHS parameters, base.
    pub shade: ShadeMaterial,
    /// Scratches in scratch space (µm), from the `"scratches"` sources.
    pub scratches: Vec<Scratch>,
}

/// `{"model": "werner" | "werner_blended" | "velinov" | "auto" | "ghs", "sigma_um",
/// "material", "options", "scratches", "base", "tolerance", "light_integral"}` at JSON path
/// `path`. The depth
/// term defaults to each paper's (exact for `werner`, `werner_blended` and `auto`,
/// small-angle for `velinov`); `options.depth_term` overrides it. `tolerance` (model
/// `auto` only, in (0, 1), default [`DEFAULT_TOLERANCE`]) bounds the relative error the
/// model choice may add (`kernel::render::model_choice`). `light_integral` (`velinov` and
/// `auto` only, one of [`LIGHT_METHODS`]) picks how the incoherent model integrates area
/// lights. Scratch files are read relative to
/// `base_dir`; at most `budget` scratch segments are accepted.
pub fn scene_material(
    v: &Value,
    path: &str,
    base_dir: &Path,
    budget: usize,
) -> Result<MaterialSpec, SpecError> {
    let m = Obj::new(
        v,
        path,
        &[
            "model",
            "sigma_um",
            "material",
            "options",
            "scratches",
            "base",
            "tolerance",
            "light_integral",
        ],
    )?;
    let model = m.choice(
        "model",
        &["werner", "werner_blended", "velinov", "auto", "ghs"],
    )?;
    if model != "auto" && m.get("tolerance").is_some() {
        return Err(SpecError::field(
            m.path_of("tolerance"),
            "only meaningful for model \"auto\"",
        ));
    }
    let mut shade = ShadeMaterial::default();
    let mut scratches = Vec::new();
    if model == "ghs" {
        for key in [
            "sigma_um",
            "options",
            "scratches",
            "base",
            "tolerance",
            "light_integral",
        ] {
            if m.get(key).is_some() {
                return Err(SpecError::field(
                    m.path_of(key),
                    "not used by model \"ghs\"",
                ));
            }
        }
        shade.model = SceneModel::Ghs as u32;
        shade.ghs = spec::ghs_material(m.req("material")?, &m.path_of("material"))?;
        return Ok(MaterialSpec { shade, scratches });
    }
    let (tm, sm) = match model {
        "werner_blended" => (Model::WernerBlended, SceneModel::WernerBlended),
        "velinov" => (Model::Velinov, SceneModel::Velinov),
        "auto" => (Model::Werner, SceneModel::Auto),
        _ => (Model::Werner, SceneModel::Werner),
    };
    shade.model = sm as u32;
    if sm == SceneModel::Auto {
        shade.tolerance = match m.opt_num("tolerance")? {
            Some(t) if t > 0.0 && t < 1.0 => t as f32,
            Some(_) => {
                return Err(SpecError::field(
                    m.path_of("tolerance"),
                    "must be in (0, 1): the relative error the model choice may add",
                ));
            }
            None => DEFAULT_TOLERANCE,
        };
    }
    if let Some(name) = m.opt_choice("light_integral", &LIGHT_METHODS.map(|(n, _)| n))? {
        if !matches!(sm, SceneModel::Velinov | SceneModel::Auto) {
            return Err(SpecError::field(
                m.path_of("light_integral"),
                "only meaningful for the incoherent model (\"velinov\", or \"auto\" where it \
                 chooses it): the coherent models integrate area lights by quadrature",
            ));
        }
        let method = LIGHT_METHODS.iter().find(|(n, _)| *n == name);
        shade.light_method = method.map_or(LightMethod::Extent, |(_, m)| *m) as u32;
    }
    shade.material = match m.get("material") {
        Some(x) => spec::material(x, &m.path_of("material"))?,
        None => Material::constant(1.0),
    };
    // Each paper's depth phase (`docs/bsdf.md`): Werner's models the exact `γi + γo`
    // (Werner Eqs. 7, 20), Velinov the small-angle `γ = 2` (Velinov Eq. 4). The table spec's
    // small-angle default for every model is a conformance convention, not inherited here.
    let depth = if tm == Model::Velinov {
        DepthTerm::SmallAngle
    } else {
        DepthTerm::Exact
    };
    shade.table = TableParams {
        model: tm as u32,
        sigma_um: spec::sigma(&m)?,
        depth_term: depth as u32,
        ..TableParams::default()
    };
    if let Some(o) = m.get("options") {
        let path = m.path_of("options");
        spec::options(o, &path, tm, &mut shade.table)?;
        // The incoherent model's closed forms (pixel footprint, area lights) integrate the
        // frozen window; a scene would use them silently.
        if shade.table.window == Window::Exact as u32
            && matches!(sm, SceneModel::Velinov | SceneModel::Auto)
        {
            return Err(SpecError::field(
                format!("{path}.window"),
                "\"exact\" is for the coherent models in scenes (\"werner\", \
                 \"werner_blended\"): the incoherent model's footprint and area-light \
                 closed forms take the frozen window (a table spec may use it with \
                 \"velinov\")",
            ));
        }
        // Likewise for the crossings: the closed forms integrate each groove on its own.
        if shade.table.crossings == Crossings::Deepest as u32
            && matches!(sm, SceneModel::Velinov | SceneModel::Auto)
        {
            return Err(SpecError::field(
                format!("{path}.crossings"),
                "\"deepest\" is for the coherent models in scenes (\"werner\", \
                 \"werner_blended\"): the incoherent model's footprint and area-light closed \
                 forms integrate each groove on its own (a table spec may use it with \
                 \"velinov\")",
            ));
        }
    }
    if let Some(s) = m.get("scratches") {
        scratches = crate::scratches::scratch_sources_with_limit(
            s,
            &m.path_of("scratches"),
            base_dir,
            budget,
        )?;
    }
    if let Some(b) = m.get("base") {
        let bp = m.path_of("base");
        if sm == SceneModel::Werner {
            return Err(SpecError::field(
                bp,
                "model \"werner\" has its own base; use \"werner_blended\"",
            ));
        }
        match b.as_str() {
            Some("smooth") => shade.base = BaseKind::Smooth as u32,
            Some("none") => shade.base = BaseKind::None as u32,
            Some(other) => {
                return Err(SpecError::field(
                    bp,
                    format!(
                        "unknown value {other:?} (expected \"smooth\", \"none\" or a GHS material object)"
                    ),
                ));
            }
            None => {
                shade.base = BaseKind::Ghs as u32;
                shade.ghs = spec::ghs_material(b, &bp)?;
            }
        }
    }
    Ok(MaterialSpec { shade, scratches })
}
