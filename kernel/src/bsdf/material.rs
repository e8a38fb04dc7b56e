//! The material record of the BSDF interface: one `Pod` for the four models (Werner
//! coherent, Werner with a blended GHS base, Velinov incoherent, plain GHS).
//!
//! The depth phase follows each paper unless the record says otherwise
//! ([`DepthChoice::ModelDefault`], the zeroed value): Werner's models use the exact
//! `γ = γi + γo` (Werner Eqs. 7, 20), Velinov's uses the small-angle `γ = 2` (Velinov Eq. 4).
//! The table spec's default (`DepthTerm::SmallAngle` for every model) is a conformance
//! convention and is not inherited here.

use super::scratch_models::Model;
use crate::ghs::GhsParams;
use crate::material::Material;
use crate::render::shading::{BaseKind, SceneModel, ShadeMaterial};
use crate::scratch::{Crossings, DepthTerm, EtaMode, Window};
use crate::table::TableParams;
use bytemuck::{Pod, Zeroable};

gpu_enum! {
    /// Which depth phase a [`BsdfMaterial`] uses.
    pub enum DepthChoice {
        /// The model's paper: exact for Werner and Werner-blended, small-angle for Velinov.
        ModelDefault = 0,
        /// `γ = 2` (Velinov Eq. 4).
        SmallAngle = 1,
        /// `γ = γi + γo` (Werner Eqs. 7, 20).
        Exact = 2,
    }
    fallback = ModelDefault;
}

impl DepthChoice {
    /// The choice that names `term` explicitly.
    #[inline]
    pub fn explicit(term: DepthTerm) -> DepthChoice {
        match term {
            DepthTerm::Exact => DepthChoice::Exact,
            DepthTerm::SmallAngle => DepthChoice::SmallAngle,
        }
    }
}

/// One material of the BSDF interface. GPU-visible: 112 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct BsdfMaterial {
    /// A [`SceneModel`] as `u32` (Werner, WernerBlended, Velinov, Ghs).
    pub model: u32,
    /// A [`BaseKind`] as `u32`: the `(1 − ρc)` base of WernerBlended and Velinov (`Ghs` is
    /// evaluated and sampled; `Smooth`, a delta, is neither: see `docs/bsdf.md`).
    pub base: u32,
    /// An [`EtaMode`] as `u32` (Velinov only; the Werner models use the finite phase).
    pub eta: u32,
    /// A [`DepthChoice`] as `u32`.
    pub depth: u32,
    /// 1: Velinov's Gaussian base `(1 − ρc)|B|²` (Velinov Eq. 7).
    pub base_gaussian: u32,
    /// Coherence σ (µm).
    pub sigma_um: f32,
    /// A [`Window`] as `u32`: the coherence window across a groove (every scratch model).
    pub window: u32,
    /// A [`Crossings`] as `u32`: how overlapping grooves cut (the coherent models).
    pub crossings: u32,
    /// The scratch models' reflectance F.
    pub material: Material,
    /// GHS parameters: the material of model `Ghs`, or the base of [`BaseKind::Ghs`].
    pub ghs: GhsParams,
}

const _: () = assert!(core::mem::size_of::<BsdfMaterial>() == 112);

impl BsdfMaterial {
    /// Werner's coherent model (Werner Eq. 15): scratches and their Gaussian base.
    pub const fn werner(sigma_um: f32, material: Material) -> BsdfMaterial {
        BsdfMaterial::scratch_model(SceneModel::Werner, sigma_um, material)
    }

    /// Werner §5: the coherent scratches plus `(1 − ρc)` times the GHS base `ghs`.
    pub const fn werner_blended(sigma_um: f32, material: Material, ghs: GhsParams) -> BsdfMaterial {
        let mut m = BsdfMaterial::scratch_model(SceneModel::WernerBlended, sigma_um, material);
        m.base = BaseKind::Ghs as u32;
        m.ghs = ghs;
        m
    }

    /// Velinov's incoherent model (Velinov Eq. 7) with its Gaussian base, finite segments.
    pub const fn velinov(sigma_um: f32, material: Material) -> BsdfMaterial {
        let mut m = BsdfMaterial::scratch_model(SceneModel::Velinov, sigma_um, material);
        m.base_gaussian = 1;
        m
    }

    /// Holzschuch & Pacanowski's two-scale BRDF alone.
    pub const fn ghs(ghs: GhsParams) -> BsdfMaterial {
        let mut m = BsdfMaterial::scratch_model(SceneModel::Ghs, 10.0, Material::constant(1.0));
        m.ghs = ghs;
        m
    }

    const fn scratch_model(model: SceneModel, sigma_um: f32, material: Material) -> BsdfMaterial {
        BsdfMaterial {
            model: model as u32,
            base: BaseKind::None as u32,
            eta: EtaMode::Finite as u32,
            depth: DepthChoice::ModelDefault as u32,
            base_gaussian: 0,
            sigma_um,
            window: Window::Frozen as u32,
            crossings: Crossings::Summed as u32,
            material,
            ghs: GhsParams::new(0.0, 0.1, 1.0, 1.0, 2.0, 1.5, 0.0),
        }
    }

    /// The renderer's material record as a BSDF material. The record's depth term is kept
    /// as written (it is explicit there), so the BSDF equals the renderer's `brdf`. An
    /// `auto` record (whose choice needs a light) becomes its coherent model
    /// ([`crate::render::model_choice::coherent`]).
    pub fn from_shade(m: &ShadeMaterial) -> BsdfMaterial {
        // A copy, not a choice between references (rust-gpu cannot merge pointers).
        let m = if SceneModel::from_u32(m.model) == SceneModel::Auto {
            crate::render::model_choice::coherent(m)
        } else {
            *m
        };
        let m = &m;
        let depth = DepthChoice::explicit(DepthTerm::from_u32(m.table.depth_term));
        BsdfMaterial {
            model: m.model,
            base: m.base,
            eta: m.table.eta,
            depth: depth as u32,
            base_gaussian: m.table.base_gaussian,
            sigma_um: m.table.sigma_um,
            window: m.table.window,
            crossings: m.table.crossings,
            material: m.material,
            ghs: m.ghs,
        }
    }

    /// A table's scratch model (`params`, with the query's `material`) as a BSDF material:
    /// the table's depth term kept as written, no GHS base (the table's `werner_blended`
    /// leaves the base to the caller, Werner §5). [`crate::table::evaluate`] is
    /// [`crate::bsdf::eval::scratch_point_values`] of this material.
    pub fn from_table(params: &TableParams, material: Material) -> BsdfMaterial {
        let model = match Model::from_u32(params.model) {
            Model::Werner => SceneModel::Werner,
            Model::WernerBlended => SceneModel::WernerBlended,
            Model::Velinov => SceneModel::Velinov,
        };
        let depth = DepthChoice::explicit(DepthTerm::from_u32(params.depth_term));
        let mut m = BsdfMaterial::scratch_model(model, params.sigma_um, material);
        m.eta = params.eta;
        m.depth = depth as u32;
        m.base_gaussian = params.base_gaussian;
        m.window = params.window;
        m.crossings = params.crossings;
        m
    }

    /// The model.
    #[inline]
    pub fn scene_model(&self) -> SceneModel {
        SceneModel::from_u32(self.model)
    }

    /// The table model of the scratch models (Werner for `Ghs`, unused there).
    #[inline]
    pub fn table_model(&self) -> Model {
        match self.scene_model() {
            SceneModel::WernerBlended => Model::WernerBlended,
            SceneModel::Velinov => Model::Velinov,
            _ => Model::Werner,
        }
    }

    /// The depth term after resolving [`DepthChoice::ModelDefault`].
    #[inline]
    pub fn depth_term(&self) -> DepthTerm {
        match DepthChoice::from_u32(self.depth) {
            DepthChoice::SmallAngle => DepthTerm::SmallAngle,
            DepthChoice::Exact => DepthTerm::Exact,
            DepthChoice::ModelDefault => {
                if self.scene_model() == SceneModel::Velinov {
                    DepthTerm::SmallAngle
                } else {
                    DepthTerm::Exact
                }
            }
        }
    }

    /// The spatial phase: the material's for Velinov, finite for the Werner models.
    #[inline]
    pub fn eta_mode(&self) -> EtaMode {
        if self.scene_model() == SceneModel::Velinov {
            EtaMode::from_u32(self.eta)
        } else {
            EtaMode::Finite
        }
    }

    /// The coherence window across a groove.
    #[inline]
    pub fn window(&self) -> Window {
        Window::from_u32(self.window)
    }

    /// How overlapping grooves cut.
    #[inline]
    pub fn crossings(&self) -> Crossings {
        Crossings::from_u32(self.crossings)
    }

    /// Whether the `(1 − ρc)` GHS base applies (WernerBlended and Velinov with
    /// [`BaseKind::Ghs`], as in the renderer).
    #[inline]
    pub fn has_ghs_base(&self) -> bool {
        let m = self.scene_model();
        BaseKind::from_u32(self.base) == BaseKind::Ghs
            && (m == SceneModel::WernerBlended || m == SceneModel::Velinov)
    }

    /// Whether the scratch walk gathers ρc: for a GHS base, or Velinov's Gaussian base.
    #[inline]
    pub fn needs_area_density(&self) -> bool {
        self.has_ghs_base() || (self.table_model() == Model::Velinov && self.base_gaussian == 1)
    }

    /// Whether the Gaussian base response is part of the BRDF (Werner; Velinov with
    /// `base_gaussian`).
    #[inline]
    pub fn has_gaussian_base(&self) -> bool {
        match self.scene_model() {
            SceneModel::Werner => true,
            SceneModel::Velinov => self.base_gaussian == 1,
            _ => false,
        }
    }

    /// The table parameters of the scratch models, with the resolved depth term.
    #[inline]
    pub fn table_params(&self) -> TableParams {
        TableParams {
            model: self.table_model() as u32,
            eta: self.eta_mode() as u32,
            depth_term: self.depth_term() as u32,
            base_gaussian: self.base_gaussian,
            sigma_um: self.sigma_um,
            window: self.window,
            crossings: self.crossings,
            pad: [0; 1],
        }
    }
}
