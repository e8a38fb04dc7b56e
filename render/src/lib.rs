//! # scratchwave-render
//!
//! Renders scenes of scratched and GHS surfaces to images on the CPU, with the portable
//! kernel BVH ([`scratchwave_host::TriangleBvh`]) or Embree (`scratchwave-embree`) for the
//! primary and shadow rays. Every formula (camera rays, frames, BRDFs, light integrals,
//! colour matching) is a kernel function from [`scratchwave_kernel::render`]; this crate
//! holds the scene model, the JSON reader, the preparation, the tile loop and the writers.
//!
//! ```no_run
//! let scene = scratchwave_render::scene_file::read_scene(std::path::Path::new("scene.json"))?;
//! let out = scratchwave_render::render_scene(&scene, scratchwave_render::Backend::Cpu, &|_, _| {})?;
//! scratchwave_render::output::write_exr(std::path::Path::new("out.exr"), &out.image, &[])?;
//! # Ok::<(), scratchwave_render::RenderError>(())
//! ```

pub mod layered_exr;
pub mod light_sampling;
pub mod output;
pub mod per_pixel;
pub mod prepare;
pub mod reference;
pub mod render;
pub mod scene;
pub mod scene_file;
pub mod stat_compare;

pub use render::{Image, Region, RenderStats};
pub use scene::Scene;

use scratchwave_spec::SpecError;
use std::time::Instant;

/// Which structure answers the ray queries.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Backend {
    /// The portable kernel BVH (`scratchwave_host::TriangleBvh`).
    Cpu,
    /// Embree 4.
    Embree,
}

impl Backend {
    /// `"cpu"` or `"embree"`.
    pub fn name(self) -> &'static str {
        match self {
            Backend::Cpu => "cpu",
            Backend::Embree => "embree",
        }
    }
}

/// Why a render failed.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// Bad input: the message names the file or JSON path.
    #[error(transparent)]
    Input(#[from] SpecError),
    /// Embree could not be loaded or failed.
    #[error("embree: {0}")]
    Embree(#[from] scratchwave_embree::Error),
    /// Writing an output file failed.
    #[error("{path}: cannot write: {msg}")]
    Output {
        /// File path.
        path: String,
        /// What went wrong.
        msg: String,
    },
}

/// A finished render.
#[derive(Clone, Debug)]
pub struct Rendered {
    /// The image.
    pub image: Image,
    /// Counts and tile-loop time.
    pub stats: RenderStats,
    /// Preparation and acceleration-structure build time (s).
    pub build_seconds: f64,
}

/// Prepares `scene`, builds the chosen ray structure and renders.
pub fn render_scene(
    scene: &Scene,
    backend: Backend,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Rendered, RenderError> {
    let full = Region::full(scene.camera.width_px, scene.camera.height_px);
    render_scene_region(scene, backend, full, progress)
}

/// [`render_scene`] for the pixels of `region` only (an image of the region's size, equal
/// bit for bit to that part of the whole image): tiles of a render spread over processes or
/// machines (the Python binding's Dask renderer). A region outside the image is an input
/// error naming `region`.
pub fn render_scene_region(
    scene: &Scene,
    backend: Backend,
    region: Region,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Rendered, RenderError> {
    let (w, h) = (scene.camera.width_px, scene.camera.height_px);
    if !region.fits(w, h) {
        return Err(RenderError::Input(SpecError::field(
            "region",
            format!(
                "{}×{} pixels at ({}, {}) is empty or leaves the {w}×{h} image",
                region.width, region.height, region.x0, region.y0
            ),
        )));
    }
    let t0 = Instant::now();
    let prep = prepare::prepare(scene);
    let ((image, stats), build_seconds) = with_ray_queries(&prep, backend, t0, |q| {
        render::render_region(scene, &prep, q, region, progress)
    })?;
    Ok(Rendered {
        image,
        stats,
        build_seconds,
    })
}

/// Builds `backend`'s ray structure over `prep` and runs `f` with it; returns `f`'s result
/// and the seconds from `t0` (the start of preparation) to the end of the build.
pub(crate) fn with_ray_queries<R>(
    prep: &prepare::Prepared,
    backend: Backend,
    t0: Instant,
    f: impl FnOnce(&dyn scratchwave_host::RayQueries) -> R,
) -> Result<(R, f64), RenderError> {
    Ok(match backend {
        Backend::Cpu => {
            let bvh = prep.cpu_bvh();
            let build = t0.elapsed().as_secs_f64();
            (f(&bvh), build)
        }
        Backend::Embree => {
            let device = scratchwave_embree::Device::new()?;
            let mut b = scratchwave_embree::SceneBuilder::new(&device)?;
            let (v, i) = prep.indexed();
            b.add_triangle_mesh(&v, &i)?;
            let es = b.commit()?;
            let build = t0.elapsed().as_secs_f64();
            (f(&es), build)
        }
    })
}
