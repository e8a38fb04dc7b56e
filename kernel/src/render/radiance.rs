//! The light loop of one camera hit, and of one pixel: what a renderer does between the
//! primary ray and the pixel value, written once for the CPU tile loop
//! (`scratchwave-render`, which batches the first shadow rays of a whole tile) and the
//! SPIR-V renderer (one invocation per pixel, [`pixel_radiance`]).
//!
//! Per hit and light: the first shadow rays ([`first_rays`]: a delta light's one ray, an
//! area light's probes; none for an area light that cannot add anything there,
//! [`shading::area_light_is_dark`]), then [`shade_light`] with their answers. An area light
//! whose probes agree is wholly visible or hidden; otherwise every quadrature node gets its
//! own shadow ray ([`Occlusion`]). Wavelengths are shaded in groups of
//! [`MAX_LAMBDAS`], one scratch walk per group.

use super::area::{self, SceneLight};
use super::camera::{Camera, RayDifferential};
use super::footprint::footprint_ellipse;
use super::model_choice::{self, Choice, Reach};
use super::pixel::sample_offset;
use super::shading::{self, SceneModel, ShadeMaterial};
use super::spectrum::{self, SpectrumMode};
use super::surface::{Surface, SurfaceKind, SurfacePoint, TriangleUv, hit_position, mesh_point};
use crate::bsdf::{Lookup, Wavelengths};
use crate::bvh::BvhNode;
use crate::footprint::Ellipse;
use crate::ghs::g1::G1Table;
use crate::lights::MAX_LAMBDAS;
use crate::math;
use crate::ray::{Hit, Ray, Triangle};
use crate::scratch::{GridHeader, Scratch, ScratchBvh, ScratchGrid, ScratchSet};
use bytemuck::{Pod, Zeroable};
use glam::Vec3;

gpu_enum! {
    /// Shadow rays towards area lights.
    pub enum ShadowMode {
        /// The light's probe nodes first ([`area::probe_count`]); the other nodes are
        /// traced only where the probes disagree (penumbrae).
        Adaptive = 0,
        /// A shadow ray to every quadrature node.
        AllNodes = 1,
    }
    fallback = Adaptive;
}

/// What every pixel of a frame shares. GPU-visible: 96 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct FrameParams {
    /// The camera (image size included).
    pub camera: Camera,
    /// Samples per pixel (≥ 1).
    pub spp: u32,
    /// 1: Velinov's footprint ellipse from ray differentials, shrunk by `1/√spp`; 0: the
    /// point model.
    pub footprint: u32,
    /// A [`ShadowMode`] as `u32`.
    pub shadows: u32,
    /// A [`SpectrumMode`] as `u32`.
    pub spectrum_mode: u32,
    /// Samples of the spectral mode.
    pub spectrum_samples: u32,
    /// λ of the single mode (nm).
    pub lambda_nm: f32,
    /// `Σ ȳ(λ_k)` of the spectral mode ([`spectrum::y_normalisation`]), else 1.
    pub y_norm: f32,
    /// Number of light records.
    pub light_count: u32,
}

const _: () = assert!(core::mem::size_of::<FrameParams>() == 96);

impl FrameParams {
    /// The frame of `camera` with these settings (`spp` raised to 1; `y_norm` computed).
    pub fn new(
        camera: Camera,
        spp: u32,
        footprint: bool,
        shadows: ShadowMode,
        mode: SpectrumMode,
        samples: u32,
        lambda_nm: f32,
        light_count: u32,
    ) -> FrameParams {
        FrameParams {
            camera,
            spp: if spp > 1 { spp } else { 1 },
            footprint: footprint as u32,
            shadows: shadows as u32,
            spectrum_mode: mode as u32,
            spectrum_samples: samples,
            lambda_nm,
            y_norm: if mode == SpectrumMode::Spectral {
                spectrum::y_normalisation(samples)
            } else {
                1.0
            },
            light_count,
        }
    }

    /// The spectrum mode.
    #[inline]
    pub fn mode(&self) -> SpectrumMode {
        SpectrumMode::from_u32(self.spectrum_mode)
    }

    /// The shadow mode.
    #[inline]
    pub fn shadow_mode(&self) -> ShadowMode {
        ShadowMode::from_u32(self.shadows)
    }

    /// Wavelengths per sample.
    #[inline]
    pub fn wavelength_count(&self) -> u32 {
        spectrum::wavelength_count(self.mode(), self.spectrum_samples)
    }

    /// The longest wavelength of the frame (nm): the first or the last (the spectral
    /// samples ascend, RGB descends).
    #[inline]
    pub fn longest_wavelength_nm(&self) -> f32 {
        let n = self.wavelength_count();
        let last = if n > 0 { n - 1 } else { 0 };
        let f = |k| spectrum::wavelength_nm(self.mode(), k, self.spectrum_samples, self.lambda_nm);
        math::max(f(0), f(last))
    }

    /// The scale of the footprint ellipse (`1/√spp`), or 0 without footprints.
    #[inline]
    pub fn footprint_scale(&self) -> f32 {
        if self.footprint == 1 {
            1.0 / math::sqrt(self.spp as f32)
        } else {
            0.0
        }
    }

    /// Wavelengths `k0..` of the frame's spectrum, at most [`MAX_LAMBDAS`] of them, each of
    /// pdf 1.
    pub fn wavelength_group(&self, k0: u32) -> Wavelengths {
        let n = self.wavelength_count();
        // Plain comparisons: `saturating_sub`/`min` lower to intrinsics rust-gpu may not take.
        #[allow(clippy::implicit_saturating_sub)]
        let left = if n > k0 { n - k0 } else { 0 };
        let count = if left < MAX_LAMBDAS as u32 {
            left
        } else {
            MAX_LAMBDAS as u32
        };
        let mut wl = Wavelengths {
            count,
            ..Wavelengths::default()
        };
        let mut j = 0;
        while j < count as usize && j < MAX_LAMBDAS {
            wl.nm[j] = spectrum::wavelength_nm(
                self.mode(),
                k0 + j as u32,
                self.spectrum_samples,
                self.lambda_nm,
            );
            wl.pdf[j] = 1.0;
            j += 1;
        }
        wl
    }
}

/// The shapes a hit refers to, by primitive id.
#[derive(Clone, Copy, Debug)]
pub struct SceneGeometry<'a> {
    /// Triangles in primitive-id order.
    pub triangles: &'a [Triangle],
    /// Texture coordinates per primitive (meshes).
    pub uvs: &'a [TriangleUv],
    /// Object of each primitive.
    pub prim_object: &'a [u32],
    /// Shading geometry per object.
    pub surfaces: &'a [Surface],
}

/// A hit seen from the camera, ready to shade.
#[derive(Clone, Copy, Debug)]
pub struct HitPoint {
    /// Position and shading frame.
    pub sp: SurfacePoint,
    /// Towards the viewer (shading frame).
    pub wo: Vec3,
    /// Geometric normal (world, unnormalised).
    pub ng: Vec3,
    /// The pixel footprint (`a1 = 0`: none).
    pub fp: Ellipse,
    /// Material index.
    pub material: u32,
}

/// The shading point of a primary hit; `None` for a back-facing or unknown primitive.
/// `footprint_scale` is [`FrameParams::footprint_scale`].
pub fn hit_point(
    geo: &SceneGeometry<'_>,
    rd: &RayDifferential,
    footprint_scale: f32,
    hit: &Hit,
) -> Option<HitPoint> {
    let prim = hit.prim_id as usize;
    if prim >= geo.prim_object.len() {
        return None;
    }
    let object = geo.prim_object[prim] as usize;
    if object >= geo.surfaces.len() {
        return None;
    }
    let surface = geo.surfaces[object];
    let ray = &rd.ray;
    let p = hit_position(ray.origin, ray.dir, hit.t);
    let sp = if SurfaceKind::from_u32(surface.kind) == SurfaceKind::Mesh {
        if prim >= geo.triangles.len() || prim >= geo.uvs.len() {
            return None;
        }
        mesh_point(
            &geo.triangles[prim],
            &geo.uvs[prim],
            hit.u,
            hit.v,
            p,
            surface.scale_um,
        )
    } else {
        super::surface::surface_point(&surface, p)
    };
    let wo = sp.to_local(-Vec3::from_array(ray.dir).normalize_or_zero());
    if !(wo.z > 0.0) {
        return None;
    }
    let fp = if footprint_scale > 0.0 {
        footprint_ellipse(rd, hit.t, &sp, footprint_scale)
    } else {
        Ellipse::default()
    };
    Some(HitPoint {
        sp,
        wo,
        ng: Vec3::from_array(hit.ng),
        fp,
        material: surface.material,
    })
}

/// The shadow rays a light needs first at a hit ([`first_rays`]).
#[derive(Clone, Copy, Debug)]
pub struct FirstRays {
    /// The rays; the first `count` are used.
    pub rays: [Ray; area::MAX_PROBES],
    /// How many.
    pub count: u32,
    /// Nothing to shade for this area light: it lies wholly below the hit's horizon
    /// (adaptive shadows), or sends nothing towards the viewer through this material here
    /// whatever its visibility ([`shading::area_light_is_dark`]).
    pub skip: bool,
}

/// The shadow rays `light` needs first at `hp` on material `m` (lookup `lk`): a delta
/// light's one ray (if above the horizon); an area light's probes above the horizon
/// (adaptive shadows only); none, and [`FirstRays::skip`], for an area light that cannot
/// add anything there (below the horizon, or [`shading::area_light_is_dark`] at the frame's
/// longest wavelength).
pub fn first_rays<S: ScratchSet>(
    frame: &FrameParams,
    m: &ShadeMaterial,
    lk: &Lookup<'_, S>,
    hp: &HitPoint,
    light: &SceneLight,
) -> FirstRays {
    let mode = frame.shadow_mode();
    let mut out = FirstRays {
        rays: [Ray::new([0.0; 3], [0.0; 3]); area::MAX_PROBES],
        count: 0,
        skip: false,
    };
    let sp = &hp.sp;
    if !shading::is_delta(light)
        && shading::area_light_is_dark(
            m,
            sp,
            hp.wo,
            light,
            lk,
            &hp.fp,
            frame.longest_wavelength_nm(),
        )
    {
        out.skip = true;
        return out;
    }
    if shading::is_delta(light) {
        if let Some((dir, dist, _)) = shading::delta_direction(light, sp.position)
            && sp.to_local(dir).z > 0.0
        {
            out.rays[0] = shading::shadow_ray(sp.position, hp.ng, dir, dist);
            out.count = 1;
        }
    } else if mode == ShadowMode::Adaptive {
        if area::below_horizon(light, sp.position, sp.z) {
            out.skip = true;
            return out;
        }
        let probes = area::probe_nodes(light, sp.position);
        let mut k = 0;
        while k < area::MAX_PROBES {
            if let Some(node) = probes[k]
                && sp.to_local(node.dir).z > 0.0
            {
                out.rays[out.count as usize] =
                    shading::shadow_ray(sp.position, hp.ng, node.dir, node.dist);
                out.count += 1;
            }
            k += 1;
        }
    }
    out
}

/// Answers shadow rays.
pub trait Occlusion {
    /// `true` if something blocks `ray` within its interval.
    fn occluded(&self, ray: &Ray) -> bool;
}

/// Work done while shading (per pixel; a renderer sums them).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ShadeCounts {
    /// Kernel shading evaluations (BRDF × light, per node and wavelength; one per
    /// closed-form area-light integral and wavelength).
    pub shading: u32,
    /// Shadow rays traced (the first rays included).
    pub shadow_rays: u32,
    /// Hit–light pairs of `auto` materials shaded with the coherent model.
    pub auto_coherent: u32,
    /// Hit–light pairs of `auto` materials shaded with the incoherent model.
    pub auto_incoherent: u32,
}

/// Shades one light at one hit into the accumulator `acc` ([`spectrum::accumulate`]),
/// given its first rays and which of them are blocked (bit `k` of `first_blocked` for
/// `first.rays[k]`). Further shadow rays (an area light in penumbra, or with
/// [`ShadowMode::AllNodes`]) go to `occ` and are counted in `counts`; the first rays are
/// the caller's to count. `reach` is the hit's [`model_choice::hit_reach`] (the same for
/// every light).
#[allow(clippy::too_many_arguments)]
pub fn shade_light<S: ScratchSet, O: Occlusion>(
    frame: &FrameParams,
    m: &ShadeMaterial,
    lk: &Lookup<'_, S>,
    hp: &HitPoint,
    reach: &Reach,
    light: &SceneLight,
    first: &FirstRays,
    first_blocked: u32,
    occ: &O,
    acc: &mut [f32; 3],
    counts: &mut ShadeCounts,
) {
    // `auto`: the model for this hit and light (`model_choice`), counted; below, `m` is
    // a fixed model. A copy, not a choice between references: rust-gpu cannot merge
    // pointers (an `OpPhi` of pointers needs the VariablePointers capability).
    let m = if SceneModel::from_u32(m.model) == SceneModel::Auto {
        let choice = model_choice::choose(
            m,
            &hp.sp,
            hp.wo,
            light,
            reach,
            frame.longest_wavelength_nm(),
        );
        if choice == Choice::Incoherent {
            counts.auto_incoherent += 1;
        } else {
            counts.auto_coherent += 1;
        }
        model_choice::resolve(m, choice)
    } else {
        *m
    };
    let m = &m;
    let n_lambda = frame.wavelength_count();
    let mode = frame.mode();
    if shading::is_delta(light) {
        // No ray (below the horizon) or a blocked one: nothing arrives.
        if first.count != 1 || first_blocked & 1 != 0 {
            return;
        }
        let mut k0 = 0;
        while k0 < n_lambda {
            let wl = frame.wavelength_group(k0);
            let l = shading::delta_light_spectrum(m, &hp.sp, hp.wo, light, &wl, lk, &hp.fp);
            let mut j = 0;
            while j < wl.count {
                counts.shading += 1;
                spectrum::accumulate(mode, k0 + j, wl.nm[j as usize], l.v[j as usize], acc);
                j += 1;
            }
            if wl.count == 0 {
                break;
            }
            k0 += wl.count;
        }
        return;
    }
    if first.skip {
        return;
    }
    // Consensus of the probes: all lit, all blocked, or none (they disagree, or there are
    // no probes: trace every node).
    let consensus = if frame.shadow_mode() == ShadowMode::Adaptive && first.count > 0 {
        let mask = (1u32 << first.count) - 1;
        let blocked = first_blocked & mask;
        if blocked == 0 {
            Consensus::Lit
        } else if blocked == mask {
            Consensus::Hidden
        } else {
            Consensus::None
        }
    } else {
        Consensus::None
    };
    area_light(frame, m, lk, hp, light, consensus, occ, acc, counts);
}

/// What an area light's probes say (an `Option<bool>` would be a pointer comparison on
/// SPIR-V; `u32` discriminants need no Int8 capability).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u32)]
enum Consensus {
    /// Every probe lit: the light is taken as wholly visible.
    Lit,
    /// Every probe blocked: wholly hidden.
    Hidden,
    /// They disagree, or there are none: a shadow ray per node.
    None,
}

/// A sphere or triangle light: the visible fraction from `consensus` (its probes agreed:
/// wholly visible or hidden) or, without one, from a shadow ray to every quadrature node;
/// then the closed form (velinov) scaled by the visible fraction, or the quadrature over the
/// visible nodes.
#[allow(clippy::too_many_arguments)]
fn area_light<S: ScratchSet, O: Occlusion>(
    frame: &FrameParams,
    m: &ShadeMaterial,
    lk: &Lookup<'_, S>,
    hp: &HitPoint,
    light: &SceneLight,
    consensus: Consensus,
    occ: &O,
    acc: &mut [f32; 3],
    counts: &mut ShadeCounts,
) {
    let (sp, wo, fp) = (&hp.sp, hp.wo, &hp.fp);
    let nodes = shading::needs_area_nodes(m);
    if consensus == Consensus::Hidden {
        return;
    }
    let mut visible = [None; area::MAX_NODES as usize];
    let (mut w_vis, mut w_all) = (1.0f32, 1.0f32);
    if consensus == Consensus::None || nodes {
        (w_vis, w_all) = (0.0, 0.0);
        let mut i = 0;
        while i < area::node_count(light) && i < area::MAX_NODES {
            if let Some(node) = area::area_node(light, sp.position, i)
                && sp.to_local(node.dir).z > 0.0
            {
                w_all += node.weight;
                let lit = match consensus {
                    Consensus::Lit => true,
                    Consensus::Hidden => false,
                    Consensus::None => {
                        counts.shadow_rays += 1;
                        !occ.occluded(&shading::shadow_ray(
                            sp.position,
                            hp.ng,
                            node.dir,
                            node.dist,
                        ))
                    }
                };
                if lit {
                    w_vis += node.weight;
                    visible[i as usize] = Some(node);
                }
            }
            i += 1;
        }
    }
    if !(w_vis > 0.0) {
        return;
    }
    let closed = shading::closed_form_area(m);
    let scale = w_vis / w_all;
    // A smooth base of a quadrature model: its mirror image of the light, scaled by the
    // visible fraction like the closed form (its reflectance per wavelength below).
    let mirror = if closed {
        0.0
    } else {
        shading::area_mirror_weight(m, sp, wo, light, lk, fp)
    };
    let n_lambda = frame.wavelength_count();
    let mode = frame.mode();
    // Wavelengths in groups of MAX_LAMBDAS: one scratch walk per group (and per node).
    let mut k0 = 0;
    while k0 < n_lambda {
        let wl = frame.wavelength_group(k0);
        let count = wl.count as usize;
        if count == 0 {
            break;
        }
        let closed_l = if closed {
            counts.shading += count as u32;
            shading::velinov_area_light(m, sp, wo, light, &wl.nm, count, lk, fp)
        } else {
            [0.0; MAX_LAMBDAS]
        };
        // Per node, every wavelength of the group (quadrature models: one walk per node).
        let mut node_l = [[0.0f32; MAX_LAMBDAS]; area::MAX_NODES as usize];
        if nodes && !closed {
            let mut slot = 0;
            while slot < area::MAX_NODES as usize {
                if let Some(node) = visible[slot] {
                    node_l[slot] = shading::area_node_radiance_spectrum(
                        m,
                        sp,
                        wo,
                        &node,
                        light.emission,
                        &wl,
                        lk,
                    )
                    .v;
                }
                slot += 1;
            }
        }
        let mut j = 0;
        while j < count && j < MAX_LAMBDAS {
            let lam = wl.nm[j];
            let mut l = closed_l[j] * scale;
            if mirror > 0.0 {
                l += mirror * shading::mirror_reflectance(m, wo, lam) * light.emission * scale;
            }
            if nodes {
                let mut slot = 0;
                while slot < area::MAX_NODES as usize {
                    if let Some(node) = visible[slot] {
                        l += if closed {
                            shading::base_node_radiance(m, sp, wo, &node, light.emission, lam, lk)
                        } else {
                            node_l[slot][j]
                        };
                        counts.shading += 1;
                    }
                    slot += 1;
                }
            }
            spectrum::accumulate(mode, k0 + j as u32, lam, l, acc);
            j += 1;
        }
        k0 += wl.count;
    }
}

/// Closest hits and shadow rays of a scene.
pub trait Tracer: Occlusion {
    /// The closest hit of `ray` within its interval.
    fn closest_hit(&self, ray: &Ray) -> Option<Hit>;
}

/// The kernel's own triangle hierarchy ([`crate::ray::closest_hit`],
/// [`crate::ray::occluded`]): what the portable CPU backend and the GPU trace.
#[derive(Clone, Copy, Debug)]
pub struct TriangleHierarchy<'a> {
    /// Nodes in depth-first order.
    pub nodes: &'a [BvhNode],
    /// Triangles in slot order.
    pub triangles: &'a [Triangle],
    /// Primitive id of each slot.
    pub prim_ids: &'a [u32],
}

impl Occlusion for TriangleHierarchy<'_> {
    #[inline]
    fn occluded(&self, ray: &Ray) -> bool {
        crate::ray::occluded(self.nodes, self.triangles, ray)
    }
}

impl Tracer for TriangleHierarchy<'_> {
    #[inline]
    fn closest_hit(&self, ray: &Ray) -> Option<Hit> {
        crate::ray::closest_hit(self.nodes, self.triangles, self.prim_ids, ray)
    }
}

/// Where one material's scratch lookup lies in buffers shared by all materials of a scene
/// (the GPU binds one buffer of each kind; see [`ScratchBvh`]). GPU-visible: 48 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct MaterialScratches {
    /// The grid (`radius ≤ 0`: none; `first_offset` is its place in the shared offsets).
    pub grid: GridHeader,
    /// The material's first BVH node in the shared node buffer.
    pub first_node: u32,
    /// One past its last node.
    pub end_node: u32,
    /// Explicit padding.
    pub pad: [u32; 2],
}

const _: () = assert!(core::mem::size_of::<MaterialScratches>() == 48);

/// The scratch lookups of a scene's materials.
pub trait SceneScratches<'a> {
    /// The lookup of one material.
    type Set: ScratchSet;
    /// Material `i`'s scratches and the G1 table.
    fn lookup(&self, material: u32) -> Lookup<'a, Self::Set>;
}

/// Every material's lookup in shared buffers: BVH windows, grids sharing one offset and one
/// item buffer (item values and BVH links are counted in the shared buffers).
#[derive(Clone, Copy, Debug)]
pub struct SharedScratches<'a> {
    /// One record per material.
    pub materials: &'a [MaterialScratches],
    /// All BVH nodes.
    pub nodes: &'a [BvhNode],
    /// All scratches, in slot order.
    pub scratches: &'a [Scratch],
    /// All grid list starts.
    pub offsets: &'a [u32],
    /// All grid lists.
    pub items: &'a [u32],
    /// The GHS G1 table ([`G1Table::FLAT`]).
    pub g1: &'a [f32],
}

impl<'a> SceneScratches<'a> for SharedScratches<'a> {
    type Set = ScratchGrid<'a>;

    fn lookup(&self, material: u32) -> Lookup<'a, ScratchGrid<'a>> {
        let i = material as usize;
        let rec = if i < self.materials.len() {
            self.materials[i]
        } else {
            MaterialScratches::default()
        };
        let set = ScratchGrid {
            header: rec.grid,
            offsets: self.offsets,
            items: self.items,
            bvh: ScratchBvh {
                nodes: self.nodes,
                scratches: self.scratches,
                first: rec.first_node,
                end: rec.end_node,
            },
        };
        Lookup::with_g1_table(set, G1Table::from_flat(self.g1))
    }
}

/// A pixel's linear RGB from its accumulator summed over its samples
/// ([`spectrum::finish`], then the mean over `frame.spp` samples).
#[inline]
pub fn pixel_rgb(frame: &FrameParams, acc: [f32; 3]) -> [f32; 3] {
    let rgb = spectrum::finish(frame.mode(), acc, frame.y_norm);
    let spp = if frame.spp > 1 { frame.spp } else { 1 };
    let inv = 1.0 / spp as f32;
    [rgb[0] * inv, rgb[1] * inv, rgb[2] * inv]
}

/// The value of one pixel and the work it took.
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
#[repr(C)]
pub struct PixelValue {
    /// Linear RGB.
    pub rgb: [f32; 3],
    /// Kernel shading evaluations.
    pub shading: u32,
    /// Shadow rays.
    pub shadow_rays: u32,
    /// [`ShadeCounts::auto_coherent`].
    pub auto_coherent: u32,
    /// [`ShadeCounts::auto_incoherent`].
    pub auto_incoherent: u32,
    /// Explicit padding.
    pub pad: u32,
}

const _: () = assert!(core::mem::size_of::<PixelValue>() == 32);

/// Pixel `(i, j)` of the frame (`i` from the left, `j` from the top): every sample's camera
/// ray ([`sample_offset`]), its closest hit, every light through [`first_rays`] and
/// [`shade_light`], and the spectrum turned into linear RGB, averaged over the samples.
/// The CPU tile loop computes the same value with its shadow rays batched per tile.
#[allow(clippy::too_many_arguments)]
pub fn pixel_radiance<'a, T: Tracer, L: SceneScratches<'a>>(
    frame: &FrameParams,
    geo: &SceneGeometry<'_>,
    materials: &[ShadeMaterial],
    lights: &[SceneLight],
    scratches: &L,
    tracer: &T,
    i: u32,
    j: u32,
) -> PixelValue {
    let cam = &frame.camera;
    let spp = if frame.spp > 1 { frame.spp } else { 1 };
    let footprint_scale = frame.footprint_scale();
    let mut acc = [0.0f32; 3];
    let mut counts = ShadeCounts::default();
    let mut k = 0;
    while k < spp {
        let (ox, oy) = sample_offset(j * cam.width_px + i, k, spp);
        let rd = cam.ray(i as f32 + ox, j as f32 + oy);
        k += 1;
        let Some(hit) = tracer.closest_hit(&rd.ray) else {
            continue;
        };
        let Some(hp) = hit_point(geo, &rd, footprint_scale, &hit) else {
            continue;
        };
        let mi = hp.material as usize;
        if mi >= materials.len() {
            continue;
        }
        let m = materials[mi];
        let lk = scratches.lookup(hp.material);
        let reach = model_choice::hit_reach(&m, &lk, hp.sp.x_um, &hp.fp);
        let mut li = 0;
        while li < lights.len() {
            let light = lights[li];
            li += 1;
            let first = first_rays(frame, &m, &lk, &hp, &light);
            let mut blocked = 0u32;
            let mut r = 0;
            while r < first.count as usize && r < area::MAX_PROBES {
                if tracer.occluded(&first.rays[r]) {
                    blocked |= 1 << r;
                }
                r += 1;
            }
            counts.shadow_rays += first.count;
            shade_light(
                frame,
                &m,
                &lk,
                &hp,
                &reach,
                &light,
                &first,
                blocked,
                tracer,
                &mut acc,
                &mut counts,
            );
        }
    }
    PixelValue {
        rgb: pixel_rgb(frame, acc),
        shading: counts.shading,
        shadow_rays: counts.shadow_rays,
        auto_coherent: counts.auto_coherent,
        auto_incoherent: counts.auto_incoherent,
        pad: 0,
    }
}
