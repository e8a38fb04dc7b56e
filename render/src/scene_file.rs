//! The scene file (JSON) → [`Scene`]. Every rejection is a [`SpecError`] naming the JSON
//! path (`objects[2].size[0]`); the format is documented in `docs/render.md`.

use crate::prepare::{SCRATCH_BYTES, estimate_bytes, triangulate};
use crate::scene::{
    DEFAULT_UNIT_UM, Footprint, LightDef, Lookup, Object, RenderSettings, Scene, SceneMaterial,
    Shadows, Shape, Spectrum,
};
use scratchwave_kernel::render::camera::{Camera, Projection};
use scratchwave_kernel::render::spectrum::SpectrumMode;
use scratchwave_spec::json::{self, Obj};
use scratchwave_spec::{SpecError, range, spec};
use serde_json::Value;
use std::collections::HashMap;
use std::path::Path;

/// Largest image edge (pixels).
pub const MAX_IMAGE_EDGE: u64 = 1 << 15;
/// Largest spp.
pub const MAX_SPP: u64 = 4096;
/// Largest number of spectral samples.
pub const MAX_SPECTRAL_SAMPLES: u64 = 1024;
/// Largest sphere tessellation parameter.
pub const MAX_SEGMENTS: u64 = 2048;
/// Memory a scene may need: 8 GiB, or half the machine's memory if that is less.
pub fn memory_limit_bytes() -> u64 {
    let cap = 8u64 << 30;
    let total = std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("MemTotal:"))
                .and_then(|l| l.split_whitespace().nth(1))
                .and_then(|kb| kb.parse::<u64>().ok())
        })
        .map(|kb| kb * 1024 / 2);
    total.map_or(cap, |t| t.min(cap))
}

/// Reads a scene file; relative paths inside it are relative to its directory.
pub fn read_scene(path: &Path) -> Result<Scene, SpecError> {
    let file = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| SpecError::Io {
        path: file.clone(),
        msg: e.to_string(),
    })?;
    let v = json::parse(&text, &file)?;
    let name = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let base = path.parent().unwrap_or(Path::new("."));
    scene_from_value(&v, &name, base)
}

fn vec3(o: &Obj, key: &str) -> Result<[f32; 3], SpecError> {
    let v = o.vec::<3>(key)?;
    let p = o.path_of(key);
    Ok([
        json::to_f32(v[0], &format!("{p}[0]"))?,
        json::to_f32(v[1], &format!("{p}[1]"))?,
        json::to_f32(v[2], &format!("{p}[2]"))?,
    ])
}

fn unit3(o: &Obj, key: &str) -> Result<[f32; 3], SpecError> {
    spec::direction(o, key)
}

fn pos(o: &Obj, key: &str, allow_zero: bool) -> Result<f32, SpecError> {
    json::positive(o.num(key)?, &o.path_of(key), allow_zero)
}

fn int(o: &Obj, key: &str, lo: u64, hi: u64, default: u64) -> Result<u64, SpecError> {
    if o.get(key).is_none() {
        return Ok(default);
    }
    let n = o.num(key)?;
    if n >= lo as f64 && n <= hi as f64 && n.fract() == 0.0 {
        Ok(n as u64)
    } else {
        Err(SpecError::field(
            o.path_of(key),
            format!("must be an integer in {lo}..={hi}, got {n}"),
        ))
    }
}

fn dot(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Reads a scene from a JSON value; `base_dir` resolves relative file names. The memory
/// limit is [`memory_limit_bytes`].
pub fn scene_from_value(v: &Value, name: &str, base_dir: &Path) -> Result<Scene, SpecError> {
    scene_from_value_with_limit(v, name, base_dir, memory_limit_bytes())
}

/// [`scene_from_value`] with a caller's memory limit (bytes; the fuzz targets pass a small
/// one). The scratch sources of all materials together get a segment budget of
/// `limit_bytes / SCRATCH_BYTES` (at most `MAX_SEGMENTS` of `scratchwave_host::pattern`), checked
/// before the segments are allocated; the whole scene's estimate
/// ([`estimate_bytes`]) is checked against `limit_bytes` after reading.
pub fn scene_from_value_with_limit(
    v: &Value,
    name: &str,
    base_dir: &Path,
    limit_bytes: u64,
) -> Result<Scene, SpecError> {
    let top = Obj::new(
        v,
        "",
        &[
            "name",
            "description",
            "unit_um",
            "camera",
            "objects",
            "materials",
            "lights",
            "spectrum",
            "render",
            "conformance",
        ],
    )?;
    let name = match top.get("name") {
        Some(n) => n
            .as_str()
            .ok_or_else(|| SpecError::field("name", "expected a string"))?
            .to_string(),
        None => name.to_string(),
    };
    let unit_um = match top.opt_num("unit_um")? {
        Some(u) => json::positive(u, "unit_um", false)?,
        None => DEFAULT_UNIT_UM,
    };
    let camera = camera(top.req("camera")?)?;
    let segment_budget = usize::try_from(limit_bytes / SCRATCH_BYTES).unwrap_or(usize::MAX);
    let (materials, by_name) = materials(top.req("materials")?, base_dir, segment_budget)?;
    let objects = objects(&top, &by_name, base_dir)?;
    let lights = lights(&top)?;
    let spectrum = spectrum(top.get("spectrum"))?;
    let settings = settings(top.get("render"))?;
    let scene = Scene {
        name,
        unit_um,
        camera,
        objects,
        materials,
        lights,
        spectrum,
        settings,
    };
    let need = estimate_bytes(&scene);
    let limit = limit_bytes;
    if need > limit {
        return Err(SpecError::field(
            largest_consumer(&scene),
            format!(
                "the scene needs about {:.1} GiB, more than the {:.1} GiB limit",
                need as f64 / (1u64 << 30) as f64,
                limit as f64 / (1u64 << 30) as f64
            ),
        ));
    }
    Ok(scene)
}

/// The JSON path of whatever dominates the memory estimate.
fn largest_consumer(scene: &Scene) -> String {
    let pixels = u64::from(scene.camera.width_px) * u64::from(scene.camera.height_px) * 28;
    let mut best = (pixels, "camera.width_px".to_string());
    for (i, o) in scene.objects.iter().enumerate() {
        let (tris, key) = match &o.shape {
            Shape::Sphere { segments, .. } => {
                (4 * u64::from(*segments) * u64::from(*segments), "segments")
            }
            Shape::Mesh { indices, .. } => (indices.len() as u64, "file"),
            Shape::Rectangle { .. } => (2, "size"),
        };
        if tris * 264 > best.0 {
            best = (tris * 264, format!("objects[{i}].{key}"));
        }
    }
    for m in &scene.materials {
        let b = m.scratches.len() as u64 * SCRATCH_BYTES;
        if b > best.0 {
            best = (b, format!("materials.{}.scratches", m.name));
        }
    }
    best.1
}

fn camera(v: &Value) -> Result<Camera, SpecError> {
    let c = Obj::new(
        v,
        "camera",
        &[
            "type",
            "eye",
            "target",
            "up",
            "view_height",
            "fov_y_deg",
            "width_px",
            "height_px",
        ],
    )?;
    let kind = c.choice("type", &["orthographic", "perspective"])?;
    let eye = vec3(&c, "eye")?;
    let target = vec3(&c, "target")?;
    let up = vec3(&c, "up")?;
    let w = int(&c, "width_px", 1, MAX_IMAGE_EDGE, 0)?;
    let h = int(&c, "height_px", 1, MAX_IMAGE_EDGE, 0)?;
    for (k, n) in [("width_px", w), ("height_px", h)] {
        if n == 0 {
            return Err(SpecError::field(c.path_of(k), "missing required field"));
        }
    }
    let (projection, hv) = if kind == "perspective" {
        if c.get("view_height").is_some() {
            return Err(SpecError::field(
                c.path_of("view_height"),
                "only for orthographic cameras",
            ));
        }
        let fov = c.num("fov_y_deg")?;
        if !(fov > 0.0 && fov < 180.0) {
            return Err(SpecError::field(
                c.path_of("fov_y_deg"),
                format!("must be in (0, 180), got {fov}"),
            ));
        }
        (
            Projection::Perspective,
            (2.0 * (fov.to_radians() / 2.0).tan()) as f32,
        )
    } else {
        if c.get("fov_y_deg").is_some() {
            return Err(SpecError::field(
                c.path_of("fov_y_deg"),
                "only for perspective cameras",
            ));
        }
        (Projection::Orthographic, pos(&c, "view_height", false)?)
    };
    let cam = Camera::look_at(projection, eye, target, up, hv, w as u32, h as u32);
    let f = cam.forward;
    if dot(f, f) == 0.0 {
        return Err(SpecError::field(
            c.path_of("target"),
            "must differ from eye",
        ));
    }
    if dot(cam.right, cam.right) == 0.0 || !cam.right.iter().all(|x| x.is_finite()) {
        return Err(SpecError::field(
            c.path_of("up"),
            "must not be parallel to the view direction",
        ));
    }
    Ok(cam)
}

/// The materials (`scratchwave_spec::material::scene_material` each); `budget` scratch
/// segments for all of them together.
fn materials(
    v: &Value,
    base_dir: &Path,
    mut budget: usize,
) -> Result<(Vec<SceneMaterial>, HashMap<String, usize>), SpecError> {
    let map = v
        .as_object()
        .ok_or_else(|| SpecError::field("materials", "expected an object of named materials"))?;
    let mut out = Vec::new();
    let mut by_name = HashMap::new();
    for (name, mv) in map {
        let path = format!("materials.{name}");
        let m = scratchwave_spec::material::scene_material(mv, &path, base_dir, budget)?;
        budget -= m.scratches.len().min(budget);
        by_name.insert(name.clone(), out.len());
        out.push(SceneMaterial {
            name: name.clone(),
            shade: m.shade,
            scratches: m.scratches,
        });
    }
    Ok((out, by_name))
}

/// Largest mesh (triangles).
pub const MAX_MESH_TRIANGLES: usize = 1 << 26;

/// Largest OBJ file (bytes).
pub const MAX_MESH_FILE_BYTES: u64 = 1 << 30;

/// `{"shape": "mesh", "file", "uv_um", "material"}`: an OBJ file (relative to the scene's
/// directory) read with `tobj`, triangulated, one index per vertex (positions and texture
/// coordinates); every vertex needs texture coordinates.
///
/// The file must be a regular file of at most [`MAX_MESH_FILE_BYTES`] (a device such as
/// `/dev/zero` or a FIFO would never end); it is read whole, then parsed from memory.
/// `mtllib` lines are ignored: materials come from the scene, and a material library path
/// is another file a hostile OBJ could point at a device.
fn read_mesh(o: &Obj, base_dir: &Path) -> Result<Shape, SpecError> {
    use std::io::Read as _;
    let fp = o.path_of("file");
    let name = o
        .req("file")?
        .as_str()
        .ok_or_else(|| SpecError::field(&fp, "expected a file name"))?;
    let file = base_dir.join(name);
    let uv_um = pos(o, "uv_um", false)?;
    let cannot = |e: &dyn std::fmt::Display| {
        SpecError::field(&fp, format!("cannot read mesh {}: {e}", file.display()))
    };
    let meta = std::fs::metadata(&file).map_err(|e| cannot(&e))?;
    if !meta.is_file() {
        return Err(cannot(&"not a regular file"));
    }
    if meta.len() > MAX_MESH_FILE_BYTES {
        return Err(cannot(&format_args!(
            "{} bytes, more than the limit of {MAX_MESH_FILE_BYTES} (MAX_MESH_FILE_BYTES)",
            meta.len()
        )));
    }
    let mut bytes = Vec::new();
    std::fs::File::open(&file)
        .and_then(|f| f.take(MAX_MESH_FILE_BYTES + 1).read_to_end(&mut bytes))
        .map_err(|e| cannot(&e))?;
    if bytes.len() as u64 > MAX_MESH_FILE_BYTES {
        return Err(cannot(&format_args!(
            "more than the limit of {MAX_MESH_FILE_BYTES} bytes (MAX_MESH_FILE_BYTES)"
        )));
    }
    if let Some(msg) = bad_face_index(&bytes) {
        return Err(cannot(&msg));
    }
    let (models, _) = tobj::load_obj_buf(
        &mut std::io::Cursor::new(bytes),
        &tobj::LoadOptions {
            triangulate: true,
            single_index: true,
            ..tobj::LoadOptions::default()
        },
        |_| Err(tobj::LoadError::OpenFileFailed),
    )
    .map_err(|e| cannot(&e))?;
    let (mut vertices, mut indices, mut uvs) = (Vec::new(), Vec::new(), Vec::new());
    for m in &models {
        let mesh = &m.mesh;
        let n = mesh.positions.len() / 3;
        if mesh.texcoords.len() != 2 * n {
            return Err(SpecError::field(
                &fp,
                format!(
                    "mesh {:?} in {} has no texture coordinates on every vertex (scratch space is UV·uv_um)",
                    m.name,
                    file.display()
                ),
            ));
        }
        let base = vertices.len() as u64;
        for k in 0..n {
            let p = [
                mesh.positions[3 * k],
                mesh.positions[3 * k + 1],
                mesh.positions[3 * k + 2],
            ];
            if !p.iter().all(|x| x.is_finite()) {
                return Err(SpecError::field(
                    &fp,
                    format!("vertex {k} of mesh {:?} is not finite", m.name),
                ));
            }
            let uv = [mesh.texcoords[2 * k], mesh.texcoords[2 * k + 1]];
            if !uv.iter().all(|x| x.is_finite()) {
                return Err(SpecError::field(
                    &fp,
                    format!(
                        "texture coordinate of vertex {k} of mesh {:?} is not finite",
                        m.name
                    ),
                ));
            }
            vertices.push(p);
            uvs.push(uv);
        }
        for t in mesh.indices.chunks(3) {
            if t.len() == 3 {
                let idx = [t[0], t[1], t[2]].map(|i| u64::from(i) + base);
                if idx.iter().any(|&i| i >= vertices.len() as u64) {
                    return Err(SpecError::field(&fp, "a face refers to a missing vertex"));
                }
                indices.push(idx.map(|i| i as u32));
            }
        }
        if indices.len() > MAX_MESH_TRIANGLES {
            return Err(SpecError::field(
                &fp,
                format!("more than {MAX_MESH_TRIANGLES} triangles"),
            ));
        }
    }
    if indices.is_empty() {
        return Err(SpecError::field(
            &fp,
            format!("{} contains no triangles", file.display()),
        ));
    }
    Ok(Shape::Mesh {
        vertices,
        indices,
        uvs,
        uv_um,
    })
}

/// The first face (`f`) or line (`l`) index of an OBJ text that names no element: a
/// positive index past the file's count of positions / texture coordinates / normals, or a
/// negative (relative) one reaching before the first. `tobj` 4.0.5 resolves such an index
/// to a huge `usize` and multiplies it unchecked (`vt * 2 + 1`): an overflow panic with
/// overflow checks, a silently wrapped (wrong) texture coordinate without (found by the
/// `obj_mesh` fuzz target).
fn bad_face_index(obj: &[u8]) -> Option<String> {
    const KINDS: [&str; 3] = ["v", "vt", "vn"];
    let lines = || {
        obj.split(|&b| b == b'\n')
            .map(|l| std::str::from_utf8(l).unwrap_or(""))
    };
    let mut total = [0usize; 3];
    for l in lines() {
        if let Some(k) = l
            .split_whitespace()
            .next()
            .and_then(|w| KINDS.iter().position(|&x| x == w))
        {
            total[k] += 1;
        }
    }
    let mut seen = [0usize; 3];
    for (n, l) in lines().enumerate() {
        let mut words = l.split_whitespace();
        let first = words.next();
        if let Some(k) = first.and_then(|w| KINDS.iter().position(|&x| x == w)) {
            seen[k] += 1;
            continue;
        }
        if !matches!(first, Some("f" | "l")) {
            continue;
        }
        for w in words {
            for (k, part) in w.split('/').take(3).enumerate() {
                let Ok(x) = part.parse::<isize>() else {
                    continue;
                };
                let ok = if x < 0 {
                    x.unsigned_abs() <= seen[k]
                } else {
                    x.unsigned_abs() <= total[k]
                };
                if !ok {
                    return Some(format!(
                        "line {}: {} index {x} names no element ({} so far, {} in the file)",
                        n + 1,
                        KINDS[k],
                        seen[k],
                        total[k]
                    ));
                }
            }
        }
    }
    None
}

fn objects(
    top: &Obj,
    by_name: &HashMap<String, usize>,
    base_dir: &Path,
) -> Result<Vec<Object>, SpecError> {
    let mut out = Vec::new();
    for (i, v) in top.arr("objects")?.iter().enumerate() {
        let path = format!("objects[{i}]");
        let kind = Obj::new(
            v,
            &path,
            &[
                "shape", "center", "tangent", "normal", "size", "material", "radius", "pole",
                "uv_um", "segments", "file",
            ],
        )?
        .choice("shape", &["rectangle", "sphere", "mesh"])?;
        let o = if kind == "mesh" {
            Obj::new(v, &path, &["shape", "file", "uv_um", "material"])?
        } else if kind == "rectangle" {
            Obj::new(
                v,
                &path,
                &["shape", "center", "tangent", "normal", "size", "material"],
            )?
        } else {
            Obj::new(
                v,
                &path,
                &[
                    "shape", "center", "radius", "pole", "tangent", "uv_um", "segments", "material",
                ],
            )?
        };
        let material = {
            let mp = o.path_of("material");
            let name = o
                .req("material")?
                .as_str()
                .ok_or_else(|| SpecError::field(&mp, "expected a material name"))?;
            *by_name
                .get(name)
                .ok_or_else(|| SpecError::field(&mp, format!("unknown material {name:?}")))?
        };
        if kind == "mesh" {
            let shape = read_mesh(&o, base_dir)?;
            out.push(Object { shape, material });
            continue;
        }
        let center = vec3(&o, "center")?;
        let perpendicular = |t: [f32; 3], n: [f32; 3], key: &str| {
            if dot(t, n).abs() > 1.0e-4 {
                Err(SpecError::field(
                    o.path_of(key),
                    format!(
                        "must be perpendicular to the normal/pole (dot = {})",
                        dot(t, n)
                    ),
                ))
            } else {
                Ok(())
            }
        };
        let shape = if kind == "rectangle" {
            let tangent = unit3(&o, "tangent")?;
            let normal = unit3(&o, "normal")?;
            perpendicular(tangent, normal, "tangent")?;
            let s = o.vec::<2>("size")?;
            let sp = o.path_of("size");
            Shape::Rectangle {
                center,
                tangent,
                normal,
                size: [
                    json::positive(s[0], &format!("{sp}[0]"), false)?,
                    json::positive(s[1], &format!("{sp}[1]"), false)?,
                ],
            }
        } else {
            let pole = if o.get("pole").is_some() {
                unit3(&o, "pole")?
            } else {
                [0.0, 0.0, 1.0]
            };
            let tangent = if o.get("tangent").is_some() {
                unit3(&o, "tangent")?
            } else {
                [1.0, 0.0, 0.0]
            };
            perpendicular(tangent, pole, "tangent")?;
            Shape::Sphere {
                center,
                radius: pos(&o, "radius", false)?,
                pole,
                tangent,
                uv_um: pos(&o, "uv_um", false)?,
                segments: int(&o, "segments", 2, MAX_SEGMENTS, 32)? as u32,
            }
        };
        out.push(Object { shape, material });
    }
    Ok(out)
}

fn lights(top: &Obj) -> Result<Vec<LightDef>, SpecError> {
    let mut out = Vec::new();
    for (i, v) in top.arr("lights")?.iter().enumerate() {
        let path = format!("lights[{i}]");
        let kind = Obj::new(
            v,
            &path,
            &[
                "type",
                "position",
                "intensity",
                "direction",
                "irradiance",
                "center",
                "radius",
                "radiance",
                "vertices",
            ],
        )?
        .choice("type", &["point", "directional", "sphere", "polygon"])?;
        let allowed: &[&str] = match kind {
            "point" => &["type", "position", "intensity"],
            "directional" => &["type", "direction", "irradiance"],
            "sphere" => &["type", "center", "radius", "radiance"],
            _ => &["type", "vertices", "radiance"],
        };
        let o = Obj::new(v, &path, allowed)?;
        out.push(match kind {
            "point" => LightDef::Point {
                position: vec3(&o, "position")?,
                intensity: pos(&o, "intensity", true)?,
            },
            "directional" => LightDef::Directional {
                direction: unit3(&o, "direction")?,
                irradiance: pos(&o, "irradiance", true)?,
            },
            "sphere" => LightDef::Sphere {
                center: vec3(&o, "center")?,
                radius: pos(&o, "radius", false)?,
                radiance: pos(&o, "radiance", true)?,
            },
            _ => {
                let vp = o.path_of("vertices");
                let list = o.arr("vertices")?;
                if !(3..=64).contains(&list.len()) {
                    return Err(SpecError::field(
                        &vp,
                        format!("needs 3 to 64 vertices, got {}", list.len()),
                    ));
                }
                let mut vertices = Vec::new();
                for (k, p) in list.iter().enumerate() {
                    let a = json::numbers::<3>(p, &format!("{vp}[{k}]"))?;
                    vertices.push([a[0] as f32, a[1] as f32, a[2] as f32]);
                    if !vertices[k].iter().all(|x| x.is_finite()) {
                        return Err(SpecError::field(
                            format!("{vp}[{k}]"),
                            "does not fit in f32",
                        ));
                    }
                }
                if triangulate(&vertices).is_none() {
                    return Err(SpecError::field(
                        vp,
                        "not a simple polygon with non-zero area",
                    ));
                }
                if let Some(k) = off_plane(&vertices) {
                    return Err(SpecError::field(
                        format!("{vp}[{k}]"),
                        "the polygon's vertices must lie in one plane",
                    ));
                }
                LightDef::Polygon {
                    vertices,
                    radiance: pos(&o, "radiance", true)?,
                }
            }
        });
    }
    Ok(out)
}

/// The first vertex farther than 1e-4 × the polygon's size from the plane of its first
/// three non-collinear vertices.
fn off_plane(v: &[[f32; 3]]) -> Option<usize> {
    let sub = |a: [f32; 3], b: [f32; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let cross = |a: [f32; 3], b: [f32; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let size = v
        .iter()
        .map(|p| dot(sub(*p, v[0]), sub(*p, v[0])).sqrt())
        .fold(0.0f32, f32::max);
    for k in 2..v.len() {
        let n = cross(sub(v[1], v[0]), sub(v[k], v[0]));
        let l = dot(n, n).sqrt();
        if l > 1.0e-6 * size * size {
            let n = n.map(|x| x / l);
            return v
                .iter()
                .position(|p| dot(sub(*p, v[0]), n).abs() > 1.0e-4 * size);
        }
    }
    None
}

fn spectrum(v: Option<&Value>) -> Result<Spectrum, SpecError> {
    let Some(v) = v else {
        return Ok(Spectrum {
            mode: SpectrumMode::Rgb,
            lambda_nm: 550.0,
            samples: 16,
        });
    };
    let o = Obj::new(v, "spectrum", &["mode", "lambda_nm", "samples"])?;
    let mode = match o.choice("mode", &["single", "rgb", "spectral"])? {
        "single" => SpectrumMode::Single,
        "spectral" => SpectrumMode::Spectral,
        _ => SpectrumMode::Rgb,
    };
    let only = |key: &str, m: SpectrumMode, what: &str| {
        if o.get(key).is_some() && mode != m {
            Err(SpecError::field(
                o.path_of(key),
                format!("only for mode \"{what}\""),
            ))
        } else {
            Ok(())
        }
    };
    only("lambda_nm", SpectrumMode::Single, "single")?;
    only("samples", SpectrumMode::Spectral, "spectral")?;
    let lambda_nm = if mode == SpectrumMode::Single {
        range::LAMBDA_NM.check(o.num("lambda_nm")?, &o.path_of("lambda_nm"))?
    } else {
        550.0
    };
    let samples = int(&o, "samples", 1, MAX_SPECTRAL_SAMPLES, 16)? as u32;
    Ok(Spectrum {
        mode,
        lambda_nm,
        samples,
    })
}

fn settings(v: Option<&Value>) -> Result<RenderSettings, SpecError> {
    let Some(v) = v else {
        return Ok(RenderSettings {
            spp: 1,
            footprint: Footprint::None,
            shadows: Shadows::Adaptive,
            lookup: Lookup::Grid,
        });
    };
    let o = Obj::new(
        v,
        "render",
        &["spp", "footprint", "shadows", "scratch_lookup"],
    )?;
    let spp = int(&o, "spp", 1, MAX_SPP, 1)? as u32;
    let footprint = match o.opt_choice("footprint", &["none", "ellipse"])? {
        Some("ellipse") => Footprint::Ellipse,
        _ => Footprint::None,
    };
    let shadows = match o.opt_choice("shadows", &["adaptive", "all_nodes"])? {
        Some("all_nodes") => Shadows::AllNodes,
        _ => Shadows::Adaptive,
    };
    let lookup = match o.opt_choice("scratch_lookup", &["grid", "bvh"])? {
        Some("bvh") => Lookup::Bvh,
        _ => Lookup::Grid,
    };
    Ok(RenderSettings {
        spp,
        footprint,
        shadows,
        lookup,
    })
}
