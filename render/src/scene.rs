//! The scene model: plain data a program can build directly or read from JSON
//! ([`crate::scene_file`]). Lengths in scene units; scratch space in µm.

use scratchwave_kernel::render::camera::Camera;
use scratchwave_kernel::render::shading::ShadeMaterial;
use scratchwave_kernel::render::spectrum::SpectrumMode;
use scratchwave_kernel::scratch::Scratch;

/// Default micrometres per scene unit (scene units are mm).
pub const DEFAULT_UNIT_UM: f32 = 1000.0;

/// A scene.
#[derive(Clone, Debug)]
pub struct Scene {
    /// Name (the file stem when read from a file); written to the EXR header.
    pub name: String,
    /// Micrometres per scene unit.
    pub unit_um: f32,
    /// The camera.
    pub camera: Camera,
    /// Objects.
    pub objects: Vec<Object>,
    /// Materials, indexed by [`Object::material`].
    pub materials: Vec<SceneMaterial>,
    /// Lights.
    pub lights: Vec<LightDef>,
    /// How wavelengths become R, G, B.
    pub spectrum: Spectrum,
    /// Sampling.
    pub settings: RenderSettings,
}

/// A shape with its material.
#[derive(Clone, Debug, PartialEq)]
pub struct Object {
    /// The shape.
    pub shape: Shape,
    /// Index into [`Scene::materials`].
    pub material: usize,
}

/// A shape.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// `center + a·tangent + b·(normal × tangent)`, `|a| ≤ size[0]/2`, `|b| ≤ size[1]/2`;
    /// scratch space `(a, b)·unit_um` µm.
    Rectangle {
        /// Centre.
        center: [f32; 3],
        /// Unit tangent (the `a` axis, frame x).
        tangent: [f32; 3],
        /// Unit normal (frame z), perpendicular to `tangent`.
        normal: [f32; 3],
        /// `[su, sv]`.
        size: [f32; 2],
    },
    /// A sphere; scratch space `(u, 1 − v)·uv_um` with `u = φ/2π` about `pole` from
    /// `tangent`, `v = θ/π` from the pole.
    Sphere {
        /// Centre.
        center: [f32; 3],
        /// Radius.
        radius: f32,
        /// Unit pole axis.
        pole: [f32; 3],
        /// Unit direction of φ = 0, perpendicular to `pole`.
        tangent: [f32; 3],
        /// µm of scratch space per unit of u and v.
        uv_um: f32,
        /// Triangles in the ray structures: `4·segments²` (θ in `segments`, φ in
        /// `2·segments` steps).
        segments: u32,
    },
    /// A triangle mesh (read from OBJ); scratch space `UV·uv_um` µm, frame x along
    /// `∂P/∂u`, flat (geometric) normals.
    Mesh {
        /// Vertex positions.
        vertices: Vec<[f32; 3]>,
        /// One index triple per triangle.
        indices: Vec<[u32; 3]>,
        /// Texture coordinates per vertex (same indexing as `vertices`).
        uvs: Vec<[f32; 2]>,
        /// µm of scratch space per unit of u and v.
        uv_um: f32,
    },
}

/// A material: the kernel record and its scratches (µm).
#[derive(Clone, Debug, PartialEq)]
pub struct SceneMaterial {
    /// Name in the scene file.
    pub name: String,
    /// Model, options, reflectance, GHS parameters, base.
    pub shade: ShadeMaterial,
    /// Scratches in scratch space (µm).
    pub scratches: Vec<Scratch>,
}

/// A light. Emission is the same at every wavelength.
#[derive(Clone, Debug, PartialEq)]
pub enum LightDef {
    /// Point light of intensity `intensity` (W/sr).
    Point {
        /// Position.
        position: [f32; 3],
        /// Intensity.
        intensity: f32,
    },
    /// Directional light from `direction` (pointing towards the light) with irradiance
    /// `irradiance` on a surface facing it.
    Directional {
        /// Unit direction towards the light.
        direction: [f32; 3],
        /// Irradiance.
        irradiance: f32,
    },
    /// Sphere light of uniform radiance.
    Sphere {
        /// Centre.
        center: [f32; 3],
        /// Radius.
        radius: f32,
        /// Radiance.
        radiance: f32,
    },
    /// Planar simple polygon of uniform radiance (triangulated by ear clipping).
    Polygon {
        /// Vertices in order.
        vertices: Vec<[f32; 3]>,
        /// Radiance.
        radiance: f32,
    },
}

/// The spectrum mode and its parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spectrum {
    /// Mode.
    pub mode: SpectrumMode,
    /// λ of the single mode (nm).
    pub lambda_nm: f32,
    /// Samples of the spectral mode.
    pub samples: u32,
}

/// Pixel footprint handling.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Footprint {
    /// The point model at each sample's ray.
    None,
    /// Velinov §4: the footprint ellipse from ray differentials (shrunk by `1/√spp`), the
    /// incoherent model averaged over it (other models stay point-sampled).
    Ellipse,
}

/// Shadow rays towards area lights: the kernel's
/// [`ShadowMode`](scratchwave_kernel::render::radiance::ShadowMode).
pub use scratchwave_kernel::render::radiance::ShadowMode as Shadows;

/// How shading finds the scratches near a hit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lookup {
    /// A uniform grid for the models' radius (`kernel::scratch::grid`), the BVH for larger
    /// ones (pixel footprints).
    Grid,
    /// The BVH alone (`kernel::scratch::set::ScratchBvh`).
    Bvh,
}

/// Sampling settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    /// Samples per pixel.
    pub spp: u32,
    /// Footprint mode.
    pub footprint: Footprint,
    /// Shadow rays towards area lights.
    pub shadows: Shadows,
    /// Scratch lookup.
    pub lookup: Lookup,
}
