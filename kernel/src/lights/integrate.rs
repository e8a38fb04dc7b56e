//! `∫_light f_r cos θi dωi` for the incoherent scratch model (Velinov 2018 Eq. 27), and
//! the `Pod` records every backend uploads.
//!
//! Per scratch k (see [`super::band`]):
//! `I_k = F/(A_C) · D² · P_k · Σ_lit [A(q1) − A(q0)]`, with
//! * `D² = |1 − e^{iκ}|²` the depth term (rectangular groove),
//! * `P_k = ∫ |η_k|² dξ₁` (Parseval): `√π σ e^{−s_b²/σ²}` for the infinite scratch
//!   (Eq. 27's `√π/(σk)` with Eq. 10's `η_s²`), `e^{−s_b²/σ²} ∫_{seg} e^{−u²/σ²} du` for the
//!   finite segment,
//! * the lit intervals `[q0, q1]` of ξ₂ where the band ξ₁ = 0 lies inside the light above
//!   the horizon ([`super::band_circle`], [`super::sphere`], [`super::polygon`]).
//!
//! `F` (and `γ` for the exact depth term) is evaluated once, at the light's centre
//! direction. The V-shaped groove has no closed form across the scratch; its band integral
//! is done by panelled Gauss–Legendre over `|M − P|²`.
//!
//! Validity: the band model takes the whole Gaussian along ξ₁ wherever the band is lit.
//! It is accurate when the light's extent across the band (in direction cosines) is large
//! against `λ/(2πσ)`; lights that only graze the band or are narrower than it are
//! over- or under-estimated (measured in `testkit/tests/light_reference.rs`).

use super::band::{SiMode, band_integral_len};
use super::band_circle::{ArcPoint, ArcPoints, BandCircle, BandFamily, Breakpoints};
use super::limits::MAX_VERTICES;
use super::limits::{MAX_BREAKPOINTS, MAX_CUTS, SPHERE_BREAKPOINTS};
use super::polygon::SphericalPolygon;
use super::sphere::{Cone, SphereCap};
use crate::footprint::{Ellipse, eta_p_accurate};
#[cfg(not(target_arch = "spirv"))]
use crate::lane::Lanes;
use crate::lane::Real;
use crate::material::{Material, Reflectance};
use crate::math;
use crate::math::quadrature::{GL4_W, GL4_X, GL8_W, GL8_X};
use crate::scratch::profile::mask_minus_profile;
use crate::scratch::profile::mask_minus_profile_lanes;
use crate::scratch::response::CUTOFF_SIGMAS;
use crate::scratch::{DepthTerm, EtaMode, NearCursor, Profile, Scratch, ScratchSet, SegmentFrame};
use bytemuck::{Pod, Zeroable};
use glam::{Vec2, Vec3};

gpu_enum! {
    /// The shape of an area light ([`Light::kind`]).
    pub enum LightKind {
        /// A sphere ([`Light::sphere`]).
        Sphere = 0,
        /// A planar convex polygon ([`Light::vertices`]).
        Polygon = 1,
    }
    fallback = Sphere;
}

/// An area light, positions relative to the shading point in any one length unit (the
/// shading point's own µm offset `x` is negligible against light distances and is not
/// applied). GPU-visible: 288 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct Light {
    /// A [`LightKind`] as `u32`.
    pub kind: u32,
    /// A [`Cone`] as `u32` (spheres).
    pub cone: u32,
    /// Number of vertices (polygons, 3..=16).
    pub count: u32,
    /// Explicit padding.
    pub pad: u32,
    /// Sphere centre `xyz` and radius.
    pub sphere: [f32; 4],
    /// Polygon vertices (`xyz`, 4th component unused), in order around the polygon.
    pub vertices: [[f32; 4]; MAX_VERTICES],
}

const _: () = assert!(core::mem::size_of::<Light>() == 288);

impl Default for Light {
    /// All zero, field by field (`Zeroable::zeroed` writes bytes through a pointer cast,
    /// which SPIR-V cannot express).
    fn default() -> Self {
        Light {
            kind: 0,
            cone: 0,
            count: 0,
            pad: 0,
            sphere: [0.0; 4],
            vertices: [[0.0; 4]; MAX_VERTICES],
        }
    }
}

impl Light {
    /// A sphere light.
    pub fn sphere(center: [f32; 3], radius: f32, cone: Cone) -> Light {
        Light {
            kind: LightKind::Sphere as u32,
            cone: cone as u32,
            sphere: [center[0], center[1], center[2], radius],
            ..Light::default()
        }
    }

    /// A polygon light from up to [`MAX_VERTICES`] vertices (extra ones are dropped).
    /// Host side (the std spec reader splits larger polygons into fans).
    #[cfg(not(target_arch = "spirv"))]
    pub fn polygon(vertices: &[[f32; 3]]) -> Light {
        let mut l = Light {
            kind: LightKind::Polygon as u32,
            ..Light::default()
        };
        let mut i = 0;
        while i < vertices.len() && i < MAX_VERTICES {
            let v = vertices[i];
            l.vertices[i] = [v[0], v[1], v[2], 0.0];
            i += 1;
        }
        l.count = i as u32;
        l
    }
}

/// One light query. GPU-visible: 352 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct LightQuery {
    /// Direction towards the viewer (normalised by the kernel).
    pub wo: [f32; 3],
    /// Wavelength (nm).
    pub lambda_nm: f32,
    /// Shading point (µm).
    pub x: [f32; 2],
    /// Explicit padding.
    pub pad: [f32; 2],
    /// Material.
    pub material: Material,
    /// The light.
    pub light: Light,
}

const _: () = assert!(core::mem::size_of::<LightQuery>() == 352);

/// Options shared by every query. GPU-visible: 32 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct LightParams {
    /// Coherence σ (µm).
    pub sigma_um: f32,
    /// An [`EtaMode`] as `u32`.
    pub eta: u32,
    /// A [`DepthTerm`] as `u32`.
    pub depth_term: u32,
    /// A [`SiMode`] as `u32`.
    pub si_mode: u32,
    /// Bands across ξ₁ (see [`BandRule`]): 0 or 1 → Velinov's single band; 3 or 5 →
    /// Gauss–Hermite bands; 20 → the extent rule.
    pub bands: u32,
    /// Explicit padding.
    pub pad: [u32; 3],
}

const _: () = assert!(core::mem::size_of::<LightParams>() == 32);

/// The solid angle a light fills, as the band code sees it: a cone or a spherical polygon,
/// chosen by `kind` (a plain struct rather than a data-carrying `enum`, so no enum tag
/// reaches SPIR-V).
#[derive(Clone, Copy, Debug)]
pub struct LightRegion {
    /// A [`LightKind`] as `u32`.
    pub kind: u32,
    /// The cone (spheres).
    pub sphere: SphereCap,
    /// The spherical polygon (polygons).
    pub polygon: SphericalPolygon,
}

impl LightRegion {
    /// The region of a light record, `None` if it is degenerate or below the horizon.
    pub fn new(light: &Light) -> Option<LightRegion> {
        let mut r = LightRegion {
            kind: LightKind::Sphere as u32,
            sphere: SphereCap::EMPTY,
            polygon: SphericalPolygon::EMPTY,
        };
        if LightKind::from_u32(light.kind) == LightKind::Polygon {
            r.kind = LightKind::Polygon as u32;
            r.polygon = SphericalPolygon::new(&light.vertices, light.count)?;
        } else {
            let s = light.sphere;
            r.sphere = SphereCap::new(
                Vec3::new(s[0], s[1], s[2]),
                s[3],
                Cone::from_u32(light.cone),
            )?;
        }
        Some(r)
    }

    /// Whether the unit direction `w` is inside.
    #[inline]
    pub fn contains(&self, w: Vec3) -> bool {
        if LightKind::from_u32(self.kind) == LightKind::Polygon {
            self.polygon.contains(w)
        } else {
            self.sphere.contains(w)
        }
    }

    /// Adds the band's boundary crossings.
    #[inline]
    pub fn crossings(&self, band: &BandCircle, out: &mut ArcPoints) {
        if LightKind::from_u32(self.kind) == LightKind::Polygon {
            self.polygon.crossings(band, out)
        } else {
            self.sphere.crossings(band, out)
        }
    }

    /// `[min, max]` of `u · w` over the light's directions (horizon not applied).
    #[inline]
    pub fn dot_range(&self, u: Vec3) -> (f32, f32) {
        if LightKind::from_u32(self.kind) == LightKind::Polygon {
            self.polygon.dot_range(u)
        } else {
            self.sphere.dot_range(u)
        }
    }

    /// The offsets `(wi + wo)_xy · t` of the bands that meet the light: a polygon's
    /// [`SphericalPolygon::offset_range`] along `t₃` shifted by `wo_xy · t`, a sphere's
    /// [`SphereCap::offset_range`]; each agrees with its crossings.
    pub fn offset_range(&self, family: &BandFamily) -> (f32, f32) {
        if LightKind::from_u32(self.kind) == LightKind::Polygon {
            self.polygon.offset_range(family)
        } else {
            self.sphere.offset_range(family)
        }
    }

    /// The bands of a scratch (`frame`) for the view `wo`, carrying this light's own term
    /// for all of them, formed once: a sphere's angle to the centre line
    /// ([`SphereCap::axis_angle`]), a small polygon's height over it
    /// ([`SphericalPolygon::centre_height`]).
    pub fn family(&self, frame: &SegmentFrame, wo: Vec3) -> BandFamily {
        let mut family = BandFamily::new(frame.tangent, frame.bitangent, wo);
        if LightKind::from_u32(self.kind) == LightKind::Polygon {
            if self.polygon.is_local() {
                family.centre_height = self.polygon.centre_height(&family);
            }
        } else {
            family.axis_angle = self.sphere.axis_angle(&family);
        }
        family
    }

    /// A superset of [`LightRegion::dot_range`] that costs no trigonometry: a sphere's
    /// [`SphereCap::dot_bound`]; everything for a polygon.
    #[inline]
    pub fn dot_bound(&self, u: Vec3) -> (f32, f32) {
        if LightKind::from_u32(self.kind) == LightKind::Polygon {
            (-1.0, 1.0)
        } else {
            self.sphere.dot_bound(u)
        }
    }

    /// Adds the values of `u · w` where the chord of a band `u · w = c` has kinks: polygon
    /// vertices above the horizon, the points where the light's boundary meets the horizon,
    /// and where a band is tangent to the boundary inside the light's range (an edge, or a
    /// sphere's cone where it holds `±u`).
    pub fn kinks(&self, u: Vec3, out: &mut Breakpoints) {
        if LightKind::from_u32(self.kind) == LightKind::Polygon {
            self.polygon.kinks(u, 0.0, out)
        } else {
            self.sphere.kinks(u, 0.0, out)
        }
    }

    /// [`LightRegion::kinks`] along `t₃` as the offsets of the bands of `family`
    /// (`t₃ · w + wo·t`): a polygon's [`SphericalPolygon::offset_kinks`], which agree with
    /// its crossings.
    pub fn offset_kinks(&self, family: &BandFamily, out: &mut Breakpoints) {
        if LightKind::from_u32(self.kind) == LightKind::Polygon {
            self.polygon.offset_kinks(family, out)
        } else {
            self.sphere.kinks(family.t3, family.wo_t, out)
        }
    }

    /// A representative direction (for `F` and `γ`), lifted above the horizon.
    #[inline]
    pub fn center(&self) -> Vec3 {
        let c = if LightKind::from_u32(self.kind) == LightKind::Polygon {
            self.polygon.center
        } else {
            self.sphere.axis
        };
        Vec3::new(c.x, c.y, math::max(c.z, 1.0e-3)).normalize_or_zero()
    }
}

gpu_enum! {
    /// How the ξ₁ direction (across the band) is integrated.
    ///
    /// Velinov's Eq. 27 evaluates the light's chord on the single line ξ₁ = 0 and multiplies
    /// by the whole Gaussian `∫ e^{−4π²σ²ξ₁²} dξ₁`. That is exact only when the chord does not
    /// change across the band; where a light edge cuts the band at an angle, or the light is
    /// not much wider than the band (`α ≲ 10 λ/(2πσ)`), the chord's curvature in ξ₁ makes it
    /// over- or under-estimate. The Gauss–Hermite rules evaluate the chord on 3 or 5 parallel
    /// lines `ξ₁ = x_k s` (`s = 1/(2√2 πσ)`, the Gaussian's standard deviation) and weight
    /// them, which is exact for chords polynomial in ξ₁ up to degree 5 or 9. Chords are not
    /// polynomial where the band family leaves the light: the chord opens like a square root
    /// from the tangent band (and jumps where the band circle is small), which no Gauss–Hermite
    /// rule resolves (9 and 15 points were tried: 95.5 % and 97 % of the sweep within 1 %).
    /// [`BandRule::Extent`] instead finds the range of ξ₁ the light covers, cuts it at the
    /// chord's kinks (polygon corners, the horizon meeting the light) and steps (the band's
    /// specular point entering the light, graded to the sinc lobe's width) and integrates the
    /// Gaussian-weighted chord over each panel with an 8-point Gauss–Legendre rule in
    /// `1 − cos t`, which absorbs square roots and kinks at the panel ends; a light covering
    /// the whole window without a kink gets the 5-point Gauss–Hermite rule.
    pub enum BandRule {
        /// One band at ξ₁ = 0 (Velinov Eq. 27).
        Single = 1,
        /// 3-point Gauss–Hermite (nodes 0, ±√3).
        Hermite3 = 3,
        /// 5-point Gauss–Hermite.
        Hermite5 = 5,
        /// Bands placed over the light's own ξ₁ range ([`LightRegion::dot_range`]), panel by
        /// panel between its kinks and steps (`bands = 20` in [`LightParams`]).
        Extent = 20,
    }
    fallback = Single;
}

impl BandRule {
    /// Number of fixed bands (0 for [`BandRule::Extent`], which places its own).
    #[inline]
    pub fn count(self) -> usize {
        match self {
            BandRule::Single => 1,
            BandRule::Hermite3 => 3,
            BandRule::Hermite5 => 5,
            BandRule::Extent => 0,
        }
    }

    /// Node `i` (in standard deviations) and its weight (weights sum to 1); the extent rule
    /// places its bands itself (`count` 0).
    #[inline]
    pub fn node(self, i: usize) -> (f32, f32) {
        match (self, i) {
            (BandRule::Hermite3, 1) => (-1.732_050_807_568_877_2, 1.0 / 6.0),
            (BandRule::Hermite3, 2) => (1.732_050_807_568_877_2, 1.0 / 6.0),
            (BandRule::Hermite3, _) => (0.0, 2.0 / 3.0),
            (BandRule::Hermite5, 1) => (-1.355_626_179_974_265_9, 0.222_075_922_005_612_6),
            (BandRule::Hermite5, 2) => (1.355_626_179_974_265_9, 0.222_075_922_005_612_6),
            (BandRule::Hermite5, 3) => (-2.856_970_013_872_805_6, 0.011_257_411_327_720_69),
            (BandRule::Hermite5, 4) => (2.856_970_013_872_805_6, 0.011_257_411_327_720_69),
            (BandRule::Hermite5, _) => (0.0, 0.533_333_333_333_333_3),
            (BandRule::Extent, _) => (0.0, 0.0),
            (BandRule::Single, _) => (0.0, 1.0),
        }
    }
}

/// The lit intervals of the band, reported as `(p0, p1, p1.s − p0.s)` on the half circle
/// ([`ArcPoints::lit_intervals`]).
#[inline]
pub fn lit_intervals<V: FnMut(ArcPoint, ArcPoint, f32)>(
    region: &LightRegion,
    band: &BandCircle,
    visit: V,
) {
    if LightKind::from_u32(region.kind) == LightKind::Polygon {
        // A small polygon decides its lit arcs in the local form of its crossings
        // ([`SphericalPolygon::lit_between`]).
        let mut bp = ArcPoints::<MAX_BREAKPOINTS>::half_circle();
        let polygon = &region.polygon;
        let at = polygon.local_band(band);
        polygon.crossings_with(band, &at, &mut bp);
        bp.lit_intervals(|a, b| polygon.lit_between(band, &at, a, b), visit);
    } else {
        // A sphere decides its lit arcs by the numbers its crossings came from
        // ([`SphereCap::holds_on`]).
        let mut bp = ArcPoints::<SPHERE_BREAKPOINTS>::half_circle();
        let reach = region.sphere.band_reach(band);
        region.sphere.crossings_with(band, &reach, &mut bp);
        bp.lit_intervals(
            |a, b| region.sphere.holds_on(band, &reach, a.between(b)),
            visit,
        );
    }
}

/// `∫ |η|² dξ₁` over ℝ (Parseval; 1/µm · µm² = µm).
#[inline]
pub fn along_power(mode: EtaMode, frame: &SegmentFrame, x0: Vec2, sigma: f32) -> f32 {
    let (s_t, s_b) = frame.offset_from(x0);
    let across = math::exp(-s_b * s_b / (sigma * sigma));
    let along = match mode {
        EtaMode::Infinite => math::SQRT_PI * sigma,
        EtaMode::Finite => math::gauss_interval_centered(
            s_t,
            frame.half_len,
            sigma * core::f32::consts::FRAC_1_SQRT_2,
        ),
    };
    across * along
}

/// Per-wavelength inputs of the across-scratch integral.
#[derive(Clone, Copy, Debug)]
pub struct Across {
    /// Groove profile.
    pub profile: Profile,
    /// Width W (µm).
    pub width: f32,
    /// Depth D (µm).
    pub depth: f32,
    /// Depth phase in half-turns per µm of depth, `2γ/λ` (1/µm; see
    /// [`crate::units::depth_half_turns_per_um`]).
    pub depth_half_turns_per_um: f32,
    /// λ (µm).
    pub lambda: f32,
    /// Si method (rectangular groove).
    pub si: SiMode,
}

/// Half-width (standard deviations) of the band range the extent rule integrates over: the
/// Gaussian beyond holds 6.8e-6 of its mass.
const EXTENT_SDS: f32 = 4.5;
/// Widest panel of the extent rule (standard deviations): the 8-point rule in `1 − cos t`
/// integrates the bare Gaussian over any such panel to 5e-5 of the panel's mass (3 sd:
/// 1.2e-4), and each panel is rescaled by its exact Gaussian mass, which removes even that;
/// what is left is the rule's error on the Gaussian times the chord, 1.4e-4 on a 2.9-sd
/// panel of a 0.04-rad sphere at the horizon (`docs/stability.md` *Panels*).
const EXTENT_PANEL_SDS: f32 = 2.5;
/// Widest panel of the extent rule in units of `δ = λ/(W·sd)`, the offset over which the
/// band moves by one lobe spacing `1/W` of `|M − P|²`: the lit chord's ends cross the lobes
/// as the band moves, so its integral ripples on that scale (and faster where a chord end
/// runs along the light's boundary, which [`end_sweep`] measures). Only grooves wider than
/// `2√2πσ/5 ≈ 1.8σ` have `δ/2` below [`EXTENT_PANEL_SDS`].
const EXTENT_PANEL_LOBES: f32 = 0.5;
/// Most e-folds of the Gaussian one panel of the extent rule spans (`x²/2` from one end to
/// the other, or from the centre to the farther end of a panel across it), as a 3-sd panel
/// from the centre does: a panel from 2.1 to 4.4 (7.3 e-folds, the integrand falling
/// 1 400-fold) was 2.9e-4 off.
const EXTENT_PANEL_EFOLDS: f32 = 4.5;
/// Most panels between two cuts of the extent rule (8 chords each).
const EXTENT_MAX_PIECES: f32 = 32.0;
/// Most lit-chord ends [`end_sweep`] follows (four chords); a band with more is left to
/// the lobe-step panels alone.
const MAX_CHORD_ENDS: usize = 8;
/// Where between two cuts [`end_sweep`] places the bands it compares, as a fraction of the
/// interval from each end: inside, so that a chord that opens or closes at a cut (a band
/// tangent to the light) is met with the same count of ends at both.
const SWEEP_INSET: f32 = 1.0e-3;
/// `1/√(2π)`.
const FRAC_1_SQRT_TAU: f32 = 0.398_942_28;

/// Most panels the V-groove quadrature uses per interval: a quarter of the integrand's lobe
/// spacing `1/W` each up to 512 lobes (`W·|len|`), which covers every chord (`|len| ≤ 2/λ`)
/// of grooves up to 2048·λ/8 wide: 92 µm at λ = 360 nm, beyond the certified 50 µm. The cap
/// was 64, which left chords over 16 lobes with wider panels: up to 22 % off at 300 lobes
/// (`kernel/tests/vgroove_band_sweep.rs`, `docs/stability.md` *The V-groove across the band*).
pub const MAX_PANELS: u32 = 2048;
/// Panels summed into one partial sum before it joins the total, so that the rounding of the
/// sum grows like `PANEL_BLOCK + panels/PANEL_BLOCK` rather than like the panel count.
pub const PANEL_BLOCK: u32 = 64;

/// The panels of the V-groove quadrature over a chord of length `len` (1/µm) of a groove
/// `width` µm wide: no wider than a quarter of the sinc lobe spacing `1/W`, 1 to
/// [`MAX_PANELS`].
#[inline]
pub fn triangle_panels(width: f32, len: f32) -> u32 {
    let want = math::abs(len) * width * 4.0 + 1.0;
    let panels = if want < MAX_PANELS as f32 {
        want as u32
    } else {
        MAX_PANELS
    };
    if panels == 0 { 1 } else { panels }
}

/// `∫_{q0}^{q0 + len} |M − P|²(ξ₂) dξ₂` (µm² · 1/µm), the length passed apart from the start
/// (see [`band_integral_len`]).
pub fn across_integral(a: &Across, q0: f32, len: f32) -> f32 {
    match a.profile {
        Profile::Rect => {
            let depth2 =
                mask_minus_profile(Profile::Rect, 1.0, a.depth, a.depth_half_turns_per_um, 0.0)
                    .norm_sqr();
            depth2 * band_integral_len(a.width, q0, len, a.si)
        }
        Profile::Triangle => {
            let panels = triangle_panels(a.width, len);
            let h = len / panels as f32;
            let mut total = 0.0;
            let mut p = 0;
            while p < panels {
                let end = if panels - p < PANEL_BLOCK {
                    panels
                } else {
                    p + PANEL_BLOCK
                };
                let mut acc = 0.0;
                while p < end {
                    let mid = q0 + (p as f32 + 0.5) * h;
                    acc = triangle_panel(a, mid, 0.5 * h, acc);
                    p += 1;
                }
                total += acc;
            }
            0.5 * h * total
        }
    }
}

/// Node `i` (0..4) of the 4-point Gauss–Legendre rule on [−1, 1] and its weight, in the
/// order `−x₀, x₀, −x₁, x₁`.
#[inline(always)]
fn gl4_node(i: usize) -> (f32, f32) {
    let j = (i / 2) % 2;
    let x = if i & 1 == 0 { -GL4_X[j] } else { GL4_X[j] };
    (x, GL4_W[j])
}

/// `|M − P|²` of the V-groove at `ξ₂ = q` (1/µm): the one formula of a node of
/// [`across_integral`]'s V-groove rule, for any [`Real`].
#[inline(always)]
fn triangle_node<R: Real>(a: &Across, q: R) -> R {
    mask_minus_profile_lanes(
        Profile::Triangle,
        R::splat(a.width),
        R::splat(a.depth),
        R::splat(a.depth_half_turns_per_um),
        q,
    )
    .norm_sqr()
}

/// `acc` plus the weighted node values of one V-groove panel centred on `mid` with
/// half-width `half`, added in node order ([`gl4_node`]): the 4 nodes in one `Lanes<4>` on
/// the CPU, one after the other on SPIR-V. The two give the same bits (the node formula
/// uses the kernel's own polynomials, not the `exp`/`ln` seam where lanes and scalar
/// differ; `kernel/tests/band_triangle_lanes.rs`).
#[inline]
fn triangle_panel(a: &Across, mid: f32, half: f32, mut acc: f32) -> f32 {
    #[cfg(not(target_arch = "spirv"))]
    let v: Lanes<4> = triangle_node(
        a,
        Lanes(core::array::from_fn(|i| mid + half * gl4_node(i).0)),
    );
    let mut i = 0;
    while i < 4 {
        let (x, w) = gl4_node(i);
        #[cfg(not(target_arch = "spirv"))]
        let value = {
            let _ = x;
            v.0[i]
        };
        #[cfg(target_arch = "spirv")]
        let value = triangle_node(a, mid + half * x);
        acc += w * value;
        i += 1;
    }
    acc
}

/// `∫ |M − P|² dξ₂` over the lit part of the band at `offset` (direction cosines) from the
/// central band ξ₁ = 0; 0 where that band misses the light.
#[inline]
fn chord_power(region: &LightRegion, family: &BandFamily, across: &Across, offset: f32) -> f32 {
    let mut part = 0.0;
    if let Some(band) = BandCircle::of_family(*family, offset) {
        let lambda = across.lambda;
        lit_intervals(region, &band, |p0, _, ds| {
            part += across_integral(across, band.xi2(p0.s, lambda), band.xi2_len(ds, lambda));
        });
    }
    part
}

/// `Σ w_k chord_power(x_k·sd)` over the fixed nodes of `rule` (single band or Gauss–Hermite).
#[inline]
fn fixed_rule_power(
    rule: BandRule,
    region: &LightRegion,
    family: &BandFamily,
    across: &Across,
    sd: f32,
) -> f32 {
    let mut sum = 0.0;
    let mut i = 0;
    while i < rule.count() {
        let (x, w) = rule.node(i);
        sum += w * chord_power(region, family, across, x * sd);
        i += 1;
    }
    sum
}

/// The extent rule's `∫ chord_power(x·sd) φ(x) dx` (φ the standard normal density) over the
/// light's own range of `x`: the range is cut where the chord has kinks (polygon corners, the
/// horizon meeting the light's boundary, a band tangent to an edge), where it steps (the
/// band's specular point entering the light, [`specular_cuts`]) and into panels at most
/// [`EXTENT_PANEL_SDS`] and [`EXTENT_PANEL_LOBES`] lobe steps wide,
/// and each panel gets the 8-point Gauss–Legendre rule in `1 − cos t`, whose nodes crowd
/// at both ends where the chord opens like a square root or kinks.
fn extent_power(
    region: &LightRegion,
    frame: &SegmentFrame,
    wo: Vec3,
    family: &BandFamily,
    across: &Across,
    sd: f32,
) -> f32 {
    let wo_t = family.wo_t;
    let (lo, hi) = region.offset_range(family);
    let x_lo = math::max(lo / sd, -EXTENT_SDS);
    let x_hi = math::min(hi / sd, EXTENT_SDS);
    if !(x_hi > x_lo) {
        return 0.0;
    }
    let mut kinks = Breakpoints::empty();
    region.offset_kinks(family, &mut kinks);
    let mut cuts = Breakpoints::empty();
    cuts.push(x_lo);
    cuts.push(x_hi);
    let mut i = 0;
    while i < kinks.len && i < MAX_CUTS {
        let x = kinks.s[i] / sd;
        if x > x_lo && x < x_hi {
            cuts.push(x);
        }
        i += 1;
    }
    specular_cuts(region, frame, wo, wo_t, across, sd, (x_lo, x_hi), &mut cuts);
    let lobe = EXTENT_PANEL_LOBES * across.lambda / (across.width * sd);
    let widest = if lobe > 0.0 && lobe < EXTENT_PANEL_SDS {
        lobe
    } else {
        EXTENT_PANEL_SDS
    };
    // The most lobes a chord end can sweep anywhere: an end's `ξ₂` is `(w·b₃ + wo·b₃)/λ`,
    // `w` in the light.
    let b3 = Vec3::new(frame.bitangent.x, frame.bitangent.y, 0.0);
    let (b_lo, b_hi) = region.dot_range(b3);
    let sweep_bound = (b_hi - b_lo) * across.width / across.lambda;
    // The panels of one cut interval: at most `widest`, at most `EXTENT_PANEL_EFOLDS` e-folds
    // of the Gaussian, and at most `EXTENT_PANEL_LOBES` of the lobes a chord end sweeps
    // across the interval (measured only where the bound allows more).
    let pieces_of = |a: f32, b: f32| {
        let efolds = if a >= 0.0 {
            0.5 * (b * b - a * a)
        } else if b <= 0.0 {
            0.5 * (a * a - b * b)
        } else {
            0.5 * math::max(a * a, b * b)
        };
        let base = math::ceil(math::max((b - a) / widest, efolds / EXTENT_PANEL_EFOLDS));
        let lobes = if sweep_bound > EXTENT_PANEL_LOBES * base {
            end_sweep(region, family, across, sd, a, b)
        } else {
            0.0
        };
        let want = math::max(base, math::ceil(lobes / EXTENT_PANEL_LOBES));
        math::clamp(want, 1.0, EXTENT_MAX_PIECES)
    };
    // The light covers the whole window with no kink in it, and neither the lobe step nor
    // the chord ends' sweep asks for more panels than panels of the widest width would be:
    // the chord is smooth across the band, and 5-point Gauss–Hermite is exact to degree 9 at
    // a fifth of the cost. With no cut inside, the one interval's panel count is formed
    // once, for this test and for the panels.
    let whole = if cuts.len == 2 {
        pieces_of(x_lo, x_hi)
    } else {
        0.0
    };
    if cuts.len == 2
        && x_lo <= -EXTENT_SDS
        && x_hi >= EXTENT_SDS
        && widest == EXTENT_PANEL_SDS
        && whole <= math::ceil((x_hi - x_lo) / EXTENT_PANEL_SDS)
    {
        return fixed_rule_power(BandRule::Hermite5, region, family, across, sd);
    }
    cuts.sort();
    let mut sum = 0.0;
    let mut c = 0;
    while c + 1 < cuts.len && c + 1 < MAX_CUTS {
        let (a, b) = (cuts.s[c], cuts.s[c + 1]);
        let pieces = if cuts.len == 2 {
            whole
        } else {
            pieces_of(a, b)
        } as u32;
        let h = (b - a) / pieces as f32;
        let mut p = 0;
        while p < pieces {
            let start = a + p as f32 * h;
            // Σ w φ(x) g(x), and Σ w φ(x) to rescale by the exact ∫ φ over the panel, which
            // removes the rule's error on the Gaussian itself.
            let (mut acc, mut norm) = (0.0, 0.0);
            let mut k = 0;
            while k < 8 {
                // GL node v ∈ (0, 1) mapped by ξ = (1 − cos πv)/2.
                let j = if k < 4 { 3 - k } else { k - 4 };
                let v = if k < 4 {
                    0.5 * (1.0 - GL8_X[j])
                } else {
                    0.5 * (1.0 + GL8_X[j])
                };
                let (sin_pv, cos_pv) = math::sin_cos(math::PI * v);
                let x = start + h * 0.5 * (1.0 - cos_pv);
                let w = 0.5 * GL8_W[j] * (0.5 * math::PI * sin_pv) * h;
                let weight = w * math::exp(-0.5 * x * x) * FRAC_1_SQRT_TAU;
                if weight > 0.0 {
                    norm += weight;
                    acc += weight * chord_power(region, family, across, x * sd);
                }
                k += 1;
            }
            if norm > 0.0 {
                // The panel's Gaussian mass, not as a difference of `erf` values: beyond
                // ~3 standard deviations both are within a few ulps of 1, and a narrow
                // panel's mass kept only the difference's rounding (20 % off at 4.3).
                let exact =
                    math::gauss_interval_centered(start + 0.5 * h, 0.5 * h, 1.0) * FRAC_1_SQRT_TAU;
                sum += acc * (exact / norm);
            }
            p += 1;
        }
        c += 1;
    }
    sum
}

/// The ends `ξ₂` (1/µm) of the lit chords of the band at `offset` (direction cosines), in
/// the order [`lit_intervals`] gives them, and their count (`None` beyond
/// [`MAX_CHORD_ENDS`]).
#[inline]
fn chord_ends(
    region: &LightRegion,
    family: &BandFamily,
    lambda: f32,
    offset: f32,
    ends: &mut [f32; MAX_CHORD_ENDS],
) -> Option<usize> {
    let mut n = 0;
    if let Some(band) = BandCircle::of_family(*family, offset) {
        lit_intervals(region, &band, |p0, p1, _| {
            if n + 1 < MAX_CHORD_ENDS {
                ends[n] = band.xi2(p0.s, lambda);
                ends[n + 1] = band.xi2(p1.s, lambda);
            }
            n += 2;
        });
    }
    if n <= MAX_CHORD_ENDS { Some(n) } else { None }
}

/// How many lobes `1/W` of `|M − P|²` a lit chord's end sweeps between the bands at
/// offsets `a` and `b` (standard deviations) with no cut between them: the most any end
/// moves in `ξ₂`, times `W`. Between cuts the chords neither appear nor vanish and each end
/// runs along one boundary (an edge, the cone, the horizon) one way, so the ends at the two
/// bands pair up in order. Where an end runs along an edge that meets the band at a shallow
/// angle it moves many times faster than the band ([`EXTENT_PANEL_LOBES`]' a-priori step
/// `δ` assumes the band's own pace), and the chord ripples that much faster; 0 where the ends
/// do not pair up.
fn end_sweep(
    region: &LightRegion,
    family: &BandFamily,
    across: &Across,
    sd: f32,
    a: f32,
    b: f32,
) -> f32 {
    let inset = SWEEP_INSET * (b - a);
    let (mut at_a, mut at_b) = ([0.0; MAX_CHORD_ENDS], [0.0; MAX_CHORD_ENDS]);
    let na = chord_ends(region, family, across.lambda, (a + inset) * sd, &mut at_a);
    let nb = chord_ends(region, family, across.lambda, (b - inset) * sd, &mut at_b);
    let (Some(na), Some(nb)) = (na, nb) else {
        return 0.0;
    };
    if na != nb {
        return 0.0;
    }
    let mut most: f32 = 0.0;
    let mut i = 0;
    while i < na && i < MAX_CHORD_ENDS {
        most = math::max(most, math::abs(at_b[i] - at_a[i]));
        i += 1;
    }
    most * across.width
}

/// Adds to `cuts` the offsets `x ∈ (x_lo, x_hi)` (standard deviations) where the band's
/// specular point `ξ₂ = 0` (`w · b₃ = −wo · b₃`, where `|M − P|²` peaks in a lobe `1/W`
/// wide) enters or leaves the light: there the chord steps by the lobe's whole weight within
/// `δ = λ/(W·sd)`, so the range is also cut at `x ± δ` and `x ± 4δ` when `δ` is below a
/// panel. The points trace the circle `w · b₃ = −wo · b₃` (a [`BandCircle`] with the roles
/// of `t` and `b` swapped, on which `w · t₃ = ρ s`), and its lit intervals' ends are the
/// crossings.
#[allow(clippy::too_many_arguments)]
fn specular_cuts(
    region: &LightRegion,
    frame: &SegmentFrame,
    wo: Vec3,
    wo_t: f32,
    across: &Across,
    sd: f32,
    (x_lo, x_hi): (f32, f32),
    cuts: &mut Breakpoints,
) {
    let Some(peak) = BandCircle::new_offset(frame.bitangent, frame.tangent, wo, 0.0) else {
        return;
    };
    let delta = across.lambda / (across.width * sd);
    // x, x ± δ, x ± 4δ; the grading only where the step is narrower than a panel.
    let mut cut_at = |p: ArcPoint| {
        let x = (peak.rho * p.s + wo_t) / sd;
        let mut k = 0;
        while k < 5 {
            let d = match k {
                0 => 0.0,
                1 => delta,
                2 => -delta,
                3 => 4.0 * delta,
                _ => -4.0 * delta,
            };
            let y = x + d;
            if (k == 0 || delta < EXTENT_PANEL_SDS) && y > x_lo && y < x_hi {
                cuts.push(y);
            }
            k += 1;
        }
    };
    lit_intervals(region, &peak, |p0, p1, _| {
        cut_at(p0);
        cut_at(p1);
    });
}

/// The standard deviation of the band in direction cosines, `λ/(2√2 πσ)` (λ, σ in µm).
#[inline]
fn band_sd(lambda: f32, sigma: f32) -> f32 {
    lambda / (2.0 * math::SQRT_2 * math::PI * sigma)
}

/// The distance (µm) from the shading point within which a scratch can contribute to the
/// light integral: `max(a1, a2) + 6σ` with the footprint `fp`, `6σ` without (`fp.a1 = 0`).
#[inline]
fn reach_radius(fp: &Ellipse, sigma: f32) -> f32 {
    if fp.a1 > 0.0 && fp.a2 > 0.0 {
        math::max(fp.a1, fp.a2) + CUTOFF_SIGMAS * sigma
    } else {
        CUTOFF_SIGMAS * sigma
    }
}

/// Whether [`light_integrals_in`] (same `params`, `region`, `wo`, `x`, `fp`, `set`) can be
/// non-zero at some wavelength up to `lambda_max_nm`: some scratch within its reach has a
/// band that may meet the light ([`band_may_reach`] at the band of `lambda_max_nm`, the
/// widest). `false` means the integral is exactly 0 at every wavelength up to that one; a
/// renderer then needs no shadow ray for the light. The walk and the test are
/// `light_integrals_in`'s own, without the band integrals.
pub fn light_may_reach<S: ScratchSet>(
    params: &LightParams,
    region: &LightRegion,
    wo: [f32; 3],
    x: [f32; 2],
    lambda_max_nm: f32,
    fp: &Ellipse,
    set: &S,
) -> bool {
    let wo = Vec3::from_array(wo).normalize_or_zero();
    let sigma = params.sigma_um;
    if !(wo.z > 0.0 && sigma > 0.0 && sigma.is_finite()) {
        return false;
    }
    let lambda_max = crate::units::um_from_nm(lambda_max_nm);
    if !(lambda_max > 0.0 && lambda_max.is_finite()) {
        return true;
    }
    let sd_max = band_sd(lambda_max, sigma);
    let radius = reach_radius(fp, sigma);
    let mut cursor = NearCursor::default();
    while let Some(s) = set.next_near(&mut cursor, Vec2::from_array(x), radius) {
        if let Some(frame) = s.frame()
            && band_may_reach(region, &frame, wo, sd_max)
        {
            return true;
        }
    }
    false
}

/// Band offsets (in the band's standard deviations) beyond which a light cannot contribute:
/// [`EXTENT_SDS`] with a margin for rounding (every band rule stays within 4.5).
const REJECT_SDS: f32 = 4.6;

/// Whether the light can meet a band of the scratch within 4.6 standard deviations `sd`
/// of the central band ξ₁ = 0 (the test the extent rule starts with,
/// done once for all wavelengths at the widest `sd`). `false` means every band rule gives
/// 0 for this scratch at every `sd` up to this one.
#[inline]
pub fn band_may_reach(region: &LightRegion, frame: &SegmentFrame, wo: Vec3, sd: f32) -> bool {
    let wo_t = Vec2::new(wo.x, wo.y).dot(frame.tangent);
    let t3 = Vec3::new(frame.tangent.x, frame.tangent.y, 0.0);
    let reach = REJECT_SDS * sd;
    let meets = |(lo, hi): (f32, f32)| lo + wo_t <= reach && hi + wo_t >= -reach;
    // The cheap bound first: it settles most scratches of a small light.
    meets(region.dot_bound(t3)) && meets(region.dot_range(t3))
}

/// One scratch's `∫ |S_k|² dξ₁ dξ₂` over the lit band (µm²) at the point `x0`:
/// [`band_power`] times [`along_power`].
#[allow(clippy::too_many_arguments)]
pub fn scratch_band_power(
    region: &LightRegion,
    scratch: &Scratch,
    wo: Vec3,
    x0: Vec2,
    eta: EtaMode,
    sigma: f32,
    depth_half_turns_per_um: f32,
    lambda: f32,
    si: SiMode,
    rule: BandRule,
) -> f32 {
    let Some(frame) = scratch.frame() else {
        return 0.0;
    };
    band_power(
        region,
        scratch,
        &frame,
        wo,
        sigma,
        depth_half_turns_per_um,
        lambda,
        si,
        rule,
    ) * along_power(eta, &frame, x0, sigma)
}

/// One scratch's band integral without its spatial factor: `∫ |M − P|² dξ₂` over the lit
/// band, weighted across ξ₁ by the normalised Gaussian `e^{−4π²σ²ξ₁²}` of the infinite
/// scratch (by `rule`), in 1/µm · µm² (multiply by `∫|η|² dξ₁`, µm, for µm²).
#[allow(clippy::too_many_arguments)]
pub fn band_power(
    region: &LightRegion,
    scratch: &Scratch,
    frame: &SegmentFrame,
    wo: Vec3,
    sigma: f32,
    depth_half_turns_per_um: f32,
    lambda: f32,
    si: SiMode,
    rule: BandRule,
) -> f32 {
    let across = Across {
        profile: Profile::from_u32(scratch.profile),
        width: scratch.width,
        depth: scratch.depth,
        depth_half_turns_per_um,
        lambda,
        si,
    };
    let sd = band_sd(lambda, sigma);
    let family = region.family(frame, wo);
    if rule == BandRule::Extent {
        extent_power(region, frame, wo, &family, &across, sd)
    } else {
        fixed_rule_power(rule, region, &family, &across, sd)
    }
}

/// `∫_light f_r cos θi dωi` (unit radiance) for the incoherent model summed over the
/// scratches near `x`: finite, ≥ 0 for every input (0 for degenerate lights, views or
/// lights below the horizon).
pub fn light_integral<S: ScratchSet>(params: &LightParams, q: &LightQuery, set: &S) -> f32 {
    light_integral_footprint(params, q, &Ellipse::default(), set)
}

/// [`light_integral`] averaged over the pixel footprint `fp` (Velinov §4 combined with
/// Eq. 27; `fp.a1 = 0` is the point model at `q.x`): [`light_integrals`] at `q.lambda_nm`.
pub fn light_integral_footprint<S: ScratchSet>(
    params: &LightParams,
    q: &LightQuery,
    fp: &Ellipse,
    set: &S,
) -> f32 {
    let lambdas = [q.lambda_nm, 0.0, 0.0, 0.0];
    light_integrals(params, q, &lambdas, 1, fp, set)[0]
}

/// Most wavelengths one [`light_integrals`] call evaluates (as many as one walk of the
/// scratch response, [`crate::scratch::MAX_SPECTRAL`]).
pub const MAX_LAMBDAS: usize = crate::scratch::MAX_SPECTRAL;

/// [`light_integral`] at the first `count` (≤ [`MAX_LAMBDAS`]) of `lambdas_nm`
/// (`q.lambda_nm` is not read) in one walk of the scratch set, optionally averaged over
/// the pixel footprint `fp`; each wavelength's value is bitwise the one a call for it alone
/// returns. Entries past `count`, and those of non-positive or non-finite wavelengths, are 0.
///
/// Footprint (Velinov §4 combined with Eq. 27): with `fp.a1, fp.a2 > 0` each scratch's
/// spatial factor `∫|η|² dξ₁` becomes its footprint average, which under the
/// infinite-scratch separation `|η(ξ₁)|² = e^{−4π²σ²ξ₁²} |η(0)|²` is `η_P / (2√π σ)` with
/// `η_P = (1/A_P) ∫_P |η_s(x)|² dx` ([`eta_p_accurate`]); scratches within
/// `max(a1, a2) + 6σ` of the footprint centre contribute. `fp.center` is not read: the
/// footprint is centred on `q.x`. `fp.a1 = 0` is the point model at `q.x`.
pub fn light_integrals<S: ScratchSet>(
    params: &LightParams,
    q: &LightQuery,
    lambdas_nm: &[f32; MAX_LAMBDAS],
    count: usize,
    fp: &Ellipse,
    set: &S,
) -> [f32; MAX_LAMBDAS] {
    match LightRegion::new(&q.light) {
        Some(region) => light_integrals_in(
            params,
            &region,
            q.wo,
            q.x,
            &q.material,
            lambdas_nm,
            count,
            fp,
            set,
        ),
        None => [0.0; MAX_LAMBDAS],
    }
}

/// [`light_integrals`] for a light already turned into its [`LightRegion`] (a caller that
/// also needs the region builds it once), with the query's fields passed apart.
#[allow(clippy::too_many_arguments)]
pub fn light_integrals_in<S: ScratchSet>(
    params: &LightParams,
    region: &LightRegion,
    wo: [f32; 3],
    x: [f32; 2],
    material: &Material,
    lambdas_nm: &[f32; MAX_LAMBDAS],
    count: usize,
    fp: &Ellipse,
    set: &S,
) -> [f32; MAX_LAMBDAS] {
    let mut out = [0.0f32; MAX_LAMBDAS];
    let n = if count < MAX_LAMBDAS {
        count
    } else {
        MAX_LAMBDAS
    };
    let wo = Vec3::from_array(wo).normalize_or_zero();
    let sigma = params.sigma_um;
    if !(wo.z > 0.0 && sigma > 0.0 && sigma.is_finite()) {
        return out;
    }
    let wc = region.center();
    let gamma = DepthTerm::from_u32(params.depth_term).gamma(wc.z + wo.z);
    // Per wavelength: λ in µm (0 marks one skipped) and the depth phase.
    let mut lambda = [0.0f32; MAX_LAMBDAS];
    let mut half_turns = [0.0f32; MAX_LAMBDAS];
    let mut any = false;
    let mut k = 0;
    while k < n && k < MAX_LAMBDAS {
        let l = crate::units::um_from_nm(lambdas_nm[k]);
        if l > 0.0 && l.is_finite() {
            lambda[k] = l;
            half_turns[k] = crate::units::depth_half_turns_per_um(gamma, lambdas_nm[k]);
            any = true;
        }
        k += 1;
    }
    if !any {
        return out;
    }
    // The widest band window (the longest wavelength's): a scratch whose window misses the
    // light there misses it at every wavelength.
    let mut lambda_max = 0.0f32;
    let mut k = 0;
    while k < n && k < MAX_LAMBDAS {
        lambda_max = math::max(lambda_max, lambda[k]);
        k += 1;
    }
    let sd_max = band_sd(lambda_max, sigma);
    let eta = EtaMode::from_u32(params.eta);
    let si = SiMode::from_u32(params.si_mode);
    let rule = BandRule::from_u32(params.bands);
    let x0 = Vec2::from_array(x);
    let footprint = fp.a1 > 0.0 && fp.a2 > 0.0;
    let mut e = *fp;
    e.center = x;
    let radius = reach_radius(fp, sigma);
    let mut power = [0.0f32; MAX_LAMBDAS];
    let mut cursor = NearCursor::default();
    while let Some(s) = set.next_near(&mut cursor, x0, radius) {
        let Some(frame) = s.frame() else {
            continue;
        };
        // The cheap angular test first: most scratches' bands miss a small light.
        if !band_may_reach(region, &frame, wo, sd_max) {
            continue;
        }
        let spatial = if footprint {
            eta_p_accurate(&s, &e, sigma) / (2.0 * math::SQRT_PI * sigma)
        } else {
            along_power(eta, &frame, x0, sigma)
        };
        if !(spatial > 0.0) {
            continue;
        }
        let mut k = 0;
        while k < n && k < MAX_LAMBDAS {
            if lambda[k] > 0.0 {
                power[k] += spatial
                    * band_power(
                        region,
                        &s,
                        &frame,
                        wo,
                        sigma,
                        half_turns[k],
                        lambda[k],
                        si,
                        rule,
                    );
            }
            k += 1;
        }
    }
    // F only where some power arrives (most shading points see no band reach the light),
    // and once for all wavelengths when it does not depend on them.
    let mut reflectance = Reflectance::new(material, wc, wo);
    let mut k = 0;
    while k < n && k < MAX_LAMBDAS {
        if lambda[k] > 0.0 && power[k] > 0.0 {
            let r = reflectance.at(lambdas_nm[k]) * power[k] / (math::PI * sigma * sigma);
            out[k] = if r.is_finite() && r > 0.0 { r } else { 0.0 };
        }
        k += 1;
    }
    out
}
