//! The Monte Carlo reference integrator (`docs/reference.md`): an unbiased estimate of the
//! pixel values the analytic renderer ([`crate::render_scene`]) approximates, with a
//! standard error per pixel.
//!
//! Per camera sample: a sub-pixel position (stratified, 2×2 jittered strata per pass), the
//! closest hit, the **point** model ([`bsdf::eval`](scratchwave_kernel::bsdf::eval()) through
//! the kernel's shading functions, no footprint average) and, per light:
//! * point and directional lights: evaluated directly (one shadow ray),
//! * sphere and polygon lights: one direction sampled by solid angle
//!   ([`crate::light_sampling`]: uniform cone; Arvo 1995 spherical triangles) with its
//!   shadow ray, weighted by `1/pdf`;
//! * a smooth (delta) base of `werner_blended`/`velinov`: the mirror direction traced to
//!   each area light, `(1 − ρc)·F·L` when it reaches the light unoccluded.
//!
//! Wavelengths: in the spectral mode either stratified over the continuous visible range
//! of the spectral mode (380–780 nm, four per sample from one stratified number,
//! [`Wavelengths::sample_uniform`]) with `XYZ = ∫ L c̄ dλ / ∫ ȳ dλ`
//! ([`SpectralSampling::Continuous`]), or the scene's own `N` midpoint wavelengths
//! ([`SpectralSampling::SceneSamples`]); the RGB and single modes use their fixed
//! wavelengths. Colour: the kernel's [`spectrum::accumulate`] and [`spectrum::finish`].
//!
//! Sub-pixel positions: stratified over the pixel square ([`PixelSampling::Box`]) or the
//! scene's own sample positions ([`PixelSampling::SceneSamples`]).
//!
//! Standard error: samples come in passes of [`PASS_SAMPLES`] stratified samples; the pass
//! means are independent, so the standard error of the pixel mean is the standard
//! deviation of the pass means over `√passes` (Welford's update in `f64`). Stopping: every
//! pixel gets `min_spp` samples; then each pixel continues until its relative standard
//! error ([`ReferenceImage::rel_stderr`]) reaches the target or it has `max_spp` samples.
//! Everything is seeded per (pixel, pass), so the image does not depend on the thread
//! count.

use crate::light_sampling::sample_light;
use crate::prepare::Prepared;
use crate::render::{Image, TILE, frame_params};
use crate::{Backend, RenderError, Scene, prepare};
use glam::{DVec3, Vec3};
use rayon::prelude::*;
use scratchwave_host::RayQueries;
use scratchwave_host::rng::SplitMix64;
use scratchwave_kernel::bsdf::{Lookup, Wavelengths};
use scratchwave_kernel::footprint::Ellipse;
use scratchwave_kernel::lights::MAX_LAMBDAS;
use scratchwave_kernel::ray::{Triangle, intersect_triangle};
use scratchwave_kernel::render::area::{AreaNode, SceneLight, SceneLightKind};
use scratchwave_kernel::render::pixel::sample_offset;
use scratchwave_kernel::render::radiance::{FrameParams, hit_point};
use scratchwave_kernel::render::shading::{
    self, BaseKind, ShadeMaterial, area_node_radiance_spectrum, base_weight, delta_light_spectrum,
    is_delta, mirror_reflectance, shadow_ray,
};
use scratchwave_kernel::render::spectrum::{
    self, SPECTRAL_MIN_NM, SPECTRAL_RANGE_NM, SpectrumMode,
};
use scratchwave_kernel::scratch::ScratchGrid;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

/// Samples per pass (2×2 strata of the pixel, of the wavelength offset and of each area
/// light's sample).
pub const PASS_SAMPLES: u32 = 4;

/// Channels whose mean lies below this fraction of the image's peak (99.9th percentile of
/// the pixels' largest channel after `min_spp`) are judged by their standard error
/// relative to that floor instead of their own mean.
pub const FLOOR_FRACTION: f64 = 1.0e-3;

/// Spectral-mode wavelengths of the reference.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpectralSampling {
    /// Stratified over the continuous range 380–780 nm: the spectral integral itself.
    Continuous,
    /// The scene's `N` midpoint wavelengths: isolates the light and footprint methods
    /// from the spectral quadrature.
    SceneSamples,
}

/// Where in the pixel the camera samples go.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PixelSampling {
    /// Stratified over the whole pixel square: the box-filtered pixel, what a footprint
    /// (`render.footprint: "ellipse"`) approximates.
    Box,
    /// Uniformly among the scene's own `render.spp` sub-pixel positions
    /// ([`sample_offset`]; the pixel centre for `spp` 1): what the analytic renderer
    /// averages, so only its light, footprint and spectral methods are measured.
    SceneSamples,
}

/// Settings of a reference render.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReferenceOptions {
    /// Seed of every random number.
    pub seed: u64,
    /// Target relative standard error per pixel (largest channel).
    pub rel_stderr: f64,
    /// Samples every pixel takes before the stopping rule applies (rounded up to passes).
    pub min_spp: u32,
    /// Sample budget per pixel (rounded up to passes).
    pub max_spp: u32,
    /// Spectral-mode wavelengths.
    pub spectral: SpectralSampling,
    /// Sub-pixel positions.
    pub pixel: PixelSampling,
}

impl Default for ReferenceOptions {
    fn default() -> Self {
        ReferenceOptions {
            seed: 1,
            rel_stderr: 0.01,
            min_spp: 256,
            max_spp: 65536,
            spectral: SpectralSampling::Continuous,
            pixel: PixelSampling::Box,
        }
    }
}

/// Counts and times of a reference render.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReferenceStats {
    /// Camera samples (all pixels).
    pub samples: u64,
    /// Shadow rays traced.
    pub shadow_rays: u64,
    /// Triangle-light samples drawn by the area fallback.
    pub area_fallback_samples: u64,
    /// Wall time of the sampling (s).
    pub seconds: f64,
    /// Preparation and ray-structure build (s).
    pub build_seconds: f64,
    /// Pixels that reached the target relative standard error.
    pub converged_pixels: u64,
    /// The floor of the relative standard error (radiance; see [`FLOOR_FRACTION`]).
    pub floor: f64,
}

/// A reference image: per-pixel mean, standard error and sample count.
#[derive(Clone, Debug, PartialEq)]
pub struct ReferenceImage {
    /// Mean (linear RGB).
    pub mean: Image,
    /// Standard error of the mean per channel.
    pub stderr: Image,
    /// Samples per pixel, row-major.
    pub spp: Vec<u32>,
    /// Counts and times.
    pub stats: ReferenceStats,
}

impl ReferenceImage {
    /// Relative standard error of pixel `k`: the largest over channels of `se/|mean|`,
    /// with `|mean|` raised to `floor` ([`ReferenceStats::floor`]).
    pub fn rel_stderr(&self, k: usize) -> f64 {
        rel_of(
            self.mean.rgb[k].map(f64::from),
            self.stderr.rgb[k].map(f64::from),
            self.stats.floor,
        )
    }
}

fn rel_of(mean: [f64; 3], se: [f64; 3], floor: f64) -> f64 {
    let mut r: f64 = 0.0;
    for c in 0..3 {
        let den = mean[c].abs().max(floor);
        let v = if den > 0.0 {
            se[c] / den
        } else if se[c] > 0.0 {
            f64::INFINITY
        } else {
            0.0
        };
        r = r.max(v);
    }
    r
}

/// Renders the Monte Carlo reference of `scene` with `backend`'s ray queries.
/// `progress(done_pixels, total_pixels, phase)` is called as tiles finish (phase 1: the
/// first `min_spp` samples of every pixel; phase 2: the stopping rule).
pub fn render_reference(
    scene: &Scene,
    backend: Backend,
    opts: &ReferenceOptions,
    progress: &(dyn Fn(usize, usize, u32) + Sync),
) -> Result<ReferenceImage, RenderError> {
    let t0 = Instant::now();
    let prep = prepare::prepare(scene);
    let (image, build) = crate::with_ray_queries(&prep, backend, t0, |q| {
        reference_with(scene, &prep, q, opts, progress)
    })?;
    Ok(ReferenceImage {
        stats: ReferenceStats {
            build_seconds: build,
            ..image.stats
        },
        ..image
    })
}

/// Running mean and sum of squared deviations of the pass means (Welford).
#[derive(Clone, Copy, Debug, Default)]
struct PixelAcc {
    passes: u32,
    mean: [f64; 3],
    m2: [f64; 3],
    done: bool,
}

impl PixelAcc {
    fn add(&mut self, x: [f64; 3]) {
        self.passes += 1;
        let n = f64::from(self.passes);
        for ((m, m2), x) in self.mean.iter_mut().zip(&mut self.m2).zip(x) {
            let d = x - *m;
            *m += d / n;
            *m2 += d * (x - *m);
        }
    }

    fn stderr(&self) -> [f64; 3] {
        let n = f64::from(self.passes);
        if self.passes < 2 {
            return [0.0; 3];
        }
        self.m2.map(|m2| (m2.max(0.0) / (n - 1.0) / n).sqrt())
    }
}

/// The pixels of one tile: `(i, j)` and their accumulators.
type Tile = Vec<(u32, u32, PixelAcc)>;

struct Ctx<'a, Q: ?Sized> {
    scene: &'a Scene,
    prep: &'a Prepared,
    queries: &'a Q,
    frame: FrameParams,
    opts: ReferenceOptions,
    /// Mean ȳ over the spectral range (`∫ ȳ dλ / range`), continuous spectral sampling.
    y_mean: f32,
    shadow_rays: AtomicU64,
    fallback: AtomicU64,
}

fn reference_with<Q: RayQueries + ?Sized>(
    scene: &Scene,
    prep: &Prepared,
    queries: &Q,
    opts: &ReferenceOptions,
    progress: &(dyn Fn(usize, usize, u32) + Sync),
) -> ReferenceImage {
    let start = Instant::now();
    let cam = scene.camera;
    let (w, h) = (cam.width_px, cam.height_px);
    let y_samples = 4096;
    let ctx = Ctx {
        scene,
        prep,
        queries,
        frame: frame_params(scene, prep),
        opts: *opts,
        y_mean: spectrum::y_normalisation(y_samples) / y_samples as f32,
        shadow_rays: AtomicU64::new(0),
        fallback: AtomicU64::new(0),
    };
    let tiles_x = w.div_ceil(TILE);
    let tiles_y = h.div_ceil(TILE);
    let mut tiles: Vec<Tile> = (0..tiles_x * tiles_y)
        .map(|t| {
            let (tx, ty) = (t % tiles_x, t / tiles_x);
            let mut px = Vec::new();
            for j in ty * TILE..((ty + 1) * TILE).min(h) {
                for i in tx * TILE..((tx + 1) * TILE).min(w) {
                    px.push((i, j, PixelAcc::default()));
                }
            }
            px
        })
        .collect();
    let total = (w as usize) * (h as usize);
    let min_passes = opts.min_spp.max(2 * PASS_SAMPLES).div_ceil(PASS_SAMPLES);
    let max_passes = opts.max_spp.div_ceil(PASS_SAMPLES).max(min_passes);
    // Phase 1: min_spp everywhere.
    let done = AtomicU64::new(0);
    tiles.par_iter_mut().for_each(|px| {
        for (i, j, acc) in px.iter_mut() {
            while acc.passes < min_passes {
                let v = ctx.pass(*i, *j, acc.passes);
                acc.add(v);
            }
        }
        let d = done.fetch_add(px.len() as u64, Ordering::Relaxed) as usize + px.len();
        progress(d, total, 1);
    });
    // The floor of the relative error: a fraction of the image's peak.
    let floor = relative_error_floor(tiles.iter().flat_map(|px| px.iter().map(|p| p.2.mean)));
    // Phase 2: each pixel until its relative standard error reaches the target.
    let done = AtomicU64::new(0);
    tiles.par_iter_mut().for_each(|px| {
        for (i, j, acc) in px.iter_mut() {
            loop {
                if rel_of(acc.mean, acc.stderr(), floor) <= opts.rel_stderr {
                    acc.done = true;
                    break;
                }
                if acc.passes >= max_passes {
                    break;
                }
                let v = ctx.pass(*i, *j, acc.passes);
                acc.add(v);
            }
        }
        let d = done.fetch_add(px.len() as u64, Ordering::Relaxed) as usize + px.len();
        progress(d, total, 2);
    });
    let seconds = start.elapsed().as_secs_f64();
    let n = total;
    let mut mean = vec![[0.0f32; 3]; n];
    let mut stderr = vec![[0.0f32; 3]; n];
    let mut spp = vec![0u32; n];
    let mut samples = 0u64;
    let mut converged = 0u64;
    for px in &tiles {
        for (i, j, acc) in px {
            let k = (j * w + i) as usize;
            mean[k] = acc.mean.map(|v| v as f32);
            stderr[k] = acc.stderr().map(|v| v as f32);
            spp[k] = acc.passes * PASS_SAMPLES;
            samples += u64::from(spp[k]);
            converged += u64::from(acc.done);
        }
    }
    ReferenceImage {
        mean: Image {
            width: w,
            height: h,
            rgb: mean,
            model_choice: Vec::new(),
        },
        stderr: Image {
            width: w,
            height: h,
            rgb: stderr,
            model_choice: Vec::new(),
        },
        spp,
        stats: ReferenceStats {
            samples,
            shadow_rays: ctx.shadow_rays.into_inner(),
            area_fallback_samples: ctx.fallback.into_inner(),
            seconds,
            // Set by the caller, which built the ray structure.
            build_seconds: 0.0,
            converged_pixels: converged,
            floor,
        },
    }
}

/// The floor of relative errors in an image: [`FLOOR_FRACTION`] of the 99.9th percentile
/// of the pixels' largest channel (`|value|`), so black and near-black pixels are measured
/// by an absolute error.
pub fn relative_error_floor(pixels: impl IntoIterator<Item = [f64; 3]>) -> f64 {
    let mut peaks: Vec<f64> = pixels
        .into_iter()
        .map(|p| p.iter().fold(0.0f64, |a, &b| a.max(b.abs())))
        .collect();
    peaks.sort_by(f64::total_cmp);
    FLOOR_FRACTION * quantile_sorted(&peaks, 0.999)
}

/// The `q`-quantile of sorted values (nearest rank; 0 when empty).
pub fn quantile_sorted(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return 0.0;
    }
    let k = ((q * (sorted.len() - 1) as f64).round() as usize).min(sorted.len() - 1);
    sorted[k]
}

/// SplitMix64's finaliser, to derive independent seeds.
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// A random permutation of `0..PASS_SAMPLES` (Fisher–Yates).
fn permutation(rng: &mut SplitMix64) -> [u32; PASS_SAMPLES as usize] {
    let mut p = [0, 1, 2, 3];
    for k in (1..p.len()).rev() {
        let j = (rng.next_u64() % (k as u64 + 1)) as usize;
        p.swap(k, j);
    }
    p
}

/// The 2×2 stratum `s` of `[0, 1)²`, jittered.
fn stratum(s: u32, rng: &mut SplitMix64) -> [f64; 2] {
    [
        (f64::from(s % 2) + rng.next_f64()) * 0.5,
        (f64::from(s / 2) + rng.next_f64()) * 0.5,
    ]
}

/// What one light contributes at one camera sample, before the wavelengths.
#[derive(Clone, Copy)]
enum LightTerm {
    /// Nothing arrives.
    None,
    /// A visible point or directional light.
    Delta,
    /// A visible sampled direction of an area light.
    Area(AreaNode),
}

impl<Q: RayQueries + ?Sized> Ctx<'_, Q> {
    /// One pass of [`PASS_SAMPLES`] stratified samples of pixel `(i, j)`: their mean RGB.
    fn pass(&self, i: u32, j: u32, pass: u32) -> [f64; 3] {
        let cam = &self.scene.camera;
        let pixel = u64::from(j) * u64::from(cam.width_px) + u64::from(i);
        let mut rng = SplitMix64::new(mix(
            mix(self.opts.seed ^ mix(pixel.wrapping_add(0x5151))) ^ u64::from(pass)
        ));
        let perm_lambda = permutation(&mut rng);
        let perm_light: Vec<[u32; PASS_SAMPLES as usize]> = (0..self.prep.lights.len())
            .map(|_| permutation(&mut rng))
            .collect();
        let mut sum = [0.0f64; 3];
        for k in 0..PASS_SAMPLES {
            let [mut sx, mut sy] = stratum(k, &mut rng);
            if self.opts.pixel == PixelSampling::SceneSamples {
                let n = self.frame.spp.max(1);
                let pick = (rng.next_u64() % u64::from(n)) as u32;
                let (ox, oy) = sample_offset(j * cam.width_px + i, pick, n);
                (sx, sy) = (f64::from(ox), f64::from(oy));
            }
            let u_lambda = (f64::from(perm_lambda[k as usize]) + rng.next_f64()) * 0.25;
            let light_u: Vec<[f64; 2]> = perm_light
                .iter()
                .map(|p| stratum(p[k as usize], &mut rng))
                .collect();
            let rgb = self.sample(i, j, [sx as f32, sy as f32], u_lambda as f32, &light_u);
            for c in 0..3 {
                sum[c] += f64::from(rgb[c]);
            }
        }
        sum.map(|s| s / f64::from(PASS_SAMPLES))
    }

    /// One camera sample at sub-pixel offset `o`: linear RGB.
    fn sample(&self, i: u32, j: u32, o: [f32; 2], u_lambda: f32, light_u: &[[f64; 2]]) -> [f32; 3] {
        let cam = &self.scene.camera;
        let ox = o[0].min(1.0 - f32::EPSILON);
        let oy = o[1].min(1.0 - f32::EPSILON);
        let rd = cam.ray(i as f32 + ox, j as f32 + oy);
        let Some(hit) = self.queries.closest_hit(&rd.ray) else {
            return [0.0; 3];
        };
        let geo = self.prep.geometry();
        let Some(hp) = hit_point(&geo, &rd, 0.0, &hit) else {
            return [0.0; 3];
        };
        let mi = hp.material as usize;
        let Some(m) = self.prep.materials.get(mi) else {
            return [0.0; 3];
        };
        let lk = Lookup::new(self.prep.scratch_set(mi));
        let sp = &hp.sp;
        // Visibility and directions first: one light sample and shadow ray per light,
        // shared by every wavelength group.
        let mut terms = Vec::with_capacity(self.prep.lights.len());
        let mut mirror = 0.0f32;
        let mut shadow_rays = 0u64;
        for (li, light) in self.prep.lights.iter().enumerate() {
            if is_delta(light) {
                let mut t = LightTerm::None;
                if let Some((dir, dist, _)) = shading::delta_direction(light, sp.position)
                    && sp.to_local(dir).z > 0.0
                {
                    shadow_rays += 1;
                    if !self
                        .queries
                        .occluded(&shadow_ray(sp.position, hp.ng, dir, dist))
                    {
                        t = LightTerm::Delta;
                    }
                }
                terms.push(t);
                continue;
            }
            let mut t = LightTerm::None;
            if let Some(s) = sample_light(light, sp.position, light_u[li]) {
                if s.area_fallback {
                    self.fallback.fetch_add(1, Ordering::Relaxed);
                }
                if sp.to_local(s.node.dir).z > 0.0 {
                    shadow_rays += 1;
                    let ray = shadow_ray(sp.position, hp.ng, s.node.dir, s.node.dist);
                    if !self.queries.occluded(&ray) {
                        t = LightTerm::Area(s.node);
                    }
                }
            }
            terms.push(t);
            if BaseKind::from_u32(m.base) == BaseKind::Smooth {
                let (l, rays) = self.mirror_base(m, &lk, &hp, light);
                mirror += l;
                shadow_rays += rays;
            }
        }
        self.shadow_rays.fetch_add(shadow_rays, Ordering::Relaxed);
        let mode = self.frame.mode();
        let mut acc = [0.0f32; 3];
        let continuous =
            mode == SpectrumMode::Spectral && self.opts.spectral == SpectralSampling::Continuous;
        if continuous {
            let wl = Wavelengths::sample_uniform(
                u_lambda,
                SPECTRAL_MIN_NM,
                SPECTRAL_MIN_NM + SPECTRAL_RANGE_NM,
                MAX_LAMBDAS as u32,
            );
            let l = self.radiance(m, &lk, &hp, &terms, &wl, mirror);
            for (j, &v) in l.iter().enumerate().take(wl.len()) {
                spectrum::accumulate(mode, j as u32, wl.nm[j], v, &mut acc);
            }
            // Σ_j L c̄ / (count · mean ȳ) = (1/count) Σ_j (L c̄ / pdf) / ∫ȳ dλ.
            return spectrum::finish(mode, acc, wl.len() as f32 * self.y_mean);
        }
        let n = self.frame.wavelength_count();
        let mut k0 = 0;
        while k0 < n {
            let wl = self.frame.wavelength_group(k0);
            if wl.count == 0 {
                break;
            }
            let l = self.radiance(m, &lk, &hp, &terms, &wl, mirror);
            for (j, &v) in l.iter().enumerate().take(wl.count as usize) {
                spectrum::accumulate(mode, k0 + j as u32, wl.nm[j], v, &mut acc);
            }
            k0 += wl.count;
        }
        spectrum::finish(mode, acc, self.frame.y_norm)
    }

    /// The radiance of every light term at the wavelengths of `wl` (one scratch walk per
    /// light), plus the smooth base's `mirror` radiance (per unit reflectance).
    fn radiance(
        &self,
        m: &ShadeMaterial,
        lk: &Lookup<'_, ScratchGrid<'_>>,
        hp: &scratchwave_kernel::render::radiance::HitPoint,
        terms: &[LightTerm],
        wl: &Wavelengths,
        mirror: f32,
    ) -> [f32; MAX_LAMBDAS] {
        let mut out = [0.0; MAX_LAMBDAS];
        if mirror > 0.0 {
            for (o, &nm) in out.iter_mut().zip(&wl.nm).take(wl.len()) {
                *o = mirror * mirror_reflectance(m, hp.wo, nm);
            }
        }
        for (light, t) in self.prep.lights.iter().zip(terms) {
            let s = match t {
                LightTerm::None => continue,
                LightTerm::Delta => {
                    delta_light_spectrum(m, &hp.sp, hp.wo, light, wl, lk, &Ellipse::default())
                }
                LightTerm::Area(node) => {
                    area_node_radiance_spectrum(m, &hp.sp, hp.wo, node, light.emission, wl, lk)
                }
            };
            for (o, v) in out.iter_mut().zip(s.v) {
                *o += v;
            }
        }
        out
    }

    /// A smooth base's mirror reflection of an area light, per unit reflectance: `(1 − ρc)·L`
    /// when the mirror direction of `wo` reaches the light unoccluded (a delta: no
    /// sampling; [`Self::radiance`] multiplies by `F` per wavelength). Returns it and the
    /// shadow rays traced.
    fn mirror_base(
        &self,
        m: &ShadeMaterial,
        lk: &Lookup<'_, ScratchGrid<'_>>,
        hp: &scratchwave_kernel::render::radiance::HitPoint,
        light: &SceneLight,
    ) -> (f32, u64) {
        let sp = &hp.sp;
        let wm = Vec3::new(-hp.wo.x, -hp.wo.y, hp.wo.z);
        if !(wm.z > 0.0) {
            return (0.0, 0);
        }
        let dir = sp.to_world(wm).normalize_or_zero();
        let Some(dist) = light_distance(light, sp.position, dir) else {
            return (0.0, 0);
        };
        if self
            .queries
            .occluded(&shadow_ray(sp.position, hp.ng, dir, dist))
        {
            return (0.0, 1);
        }
        let w = base_weight(m, sp.x_um, &lk.scratches);
        (w * light.emission, 1)
    }
}

/// Distance from `p` along the unit `dir` to an area light's surface, `None` if the ray
/// misses it.
fn light_distance(light: &SceneLight, p: Vec3, dir: Vec3) -> Option<f32> {
    let v = |a: [f32; 4]| [a[0], a[1], a[2]];
    match SceneLightKind::from_u32(light.kind) {
        SceneLightKind::Sphere => {
            let c = DVec3::from_array(v(light.p0).map(f64::from));
            let r = f64::from(light.p0[3]);
            let to_c = c - p.as_dvec3();
            let d = dir.as_dvec3();
            let proj = d.dot(to_c);
            let disc = r * r - (to_c.length_squared() - proj * proj);
            let t = proj - disc.max(0.0).sqrt();
            (disc >= 0.0 && proj > 0.0 && t > 0.0).then_some(t as f32)
        }
        SceneLightKind::Triangle => {
            let tri = Triangle {
                v0: v(light.p0),
                v1: v(light.p1),
                v2: v(light.p2),
            };
            let ray = scratchwave_kernel::ray::Ray::new(p.to_array(), dir.to_array());
            intersect_triangle(&ray, &tri, f32::INFINITY).map(|h| h.t)
        }
        _ => None,
    }
}
