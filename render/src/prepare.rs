//! Scene preparation: shapes → one triangle list (primitive → object), one scratch lookup
//! per material, lights → kernel records (polygons triangulated), and the ray structures.

use crate::scene::{LightDef, Lookup, Scene, Shape};
use scratchwave_host::{GridData, ScratchLookup, TriangleBvh};
use scratchwave_kernel::math;
use scratchwave_kernel::ray::Triangle;
use scratchwave_kernel::render::area::{SceneLight, SceneLightKind};
use scratchwave_kernel::render::radiance::SceneGeometry;
use scratchwave_kernel::render::shading::ShadeMaterial;
use scratchwave_kernel::render::surface::{Surface, SurfaceKind, TriangleUv};
use scratchwave_kernel::scratch::{GridHeader, ScratchGrid};

/// Everything the tile loop reads, independent of the ray backend.
pub struct Prepared {
    /// Triangles in primitive-id order.
    pub triangles: Vec<Triangle>,
    /// Texture coordinates of each primitive (zero except on meshes).
    pub uvs: Vec<TriangleUv>,
    /// Object index of each primitive.
    pub prim_object: Vec<u32>,
    /// Shading geometry per object.
    pub surfaces: Vec<Surface>,
    /// Kernel material records.
    pub materials: Vec<ShadeMaterial>,
    /// Scratch lookup per material.
    pub lookups: Vec<ScratchLookup>,
    /// Scratch grid per material (`None`: the lookup's BVH answers every query).
    pub grids: Vec<Option<GridData>>,
    /// Light records (a polygon gives several triangles).
    pub lights: Vec<SceneLight>,
}

/// The most scratch-grid entries (cells + list entries) per scratch; a material whose grid
/// would need more (few scratches spread over a wide area) uses its BVH alone.
pub const GRID_ENTRIES_PER_SCRATCH: u64 = 16;

impl Prepared {
    /// The scratch set of material `mi`: its grid over the BVH, or the BVH alone.
    pub fn scratch_set(&self, mi: usize) -> ScratchGrid<'_> {
        match &self.grids[mi] {
            Some(g) => g.set(&self.lookups[mi]),
            None => ScratchGrid {
                header: GridHeader {
                    radius: -1.0,
                    ..GridHeader::default()
                },
                offsets: &[],
                items: &[],
                bvh: self.lookups[mi].set(),
            },
        }
    }
}

/// Bytes per scratch segment in [`estimate_bytes`]: the segment (64 B), its BVH nodes and
/// ids, twice while building, and at most [`GRID_ENTRIES_PER_SCRATCH`] `u32` grid entries.
pub const SCRATCH_BYTES: u64 = 2 * (64 + 64 + 8) + 4 * GRID_ENTRIES_PER_SCRATCH;

/// Bytes the preparation and the image of `scene` will take, estimated before allocating
/// (triangles with BVH nodes and ids, scratch lookups, image buffers).
pub fn estimate_bytes(scene: &Scene) -> u64 {
    let mut tris = 0u64;
    for o in &scene.objects {
        tris += match &o.shape {
            Shape::Rectangle { .. } => 2,
            Shape::Sphere { segments, .. } => 4 * u64::from(*segments) * u64::from(*segments),
            Shape::Mesh { indices, .. } => indices.len() as u64 * 2,
        };
    }
    let scratches: u64 = scene
        .materials
        .iter()
        .map(|m| m.scratches.len() as u64)
        .sum();
    let pixels = u64::from(scene.camera.width_px) * u64::from(scene.camera.height_px);
    // Triangle 36 B + BVH node 32 B ×2 + ids, twice (build copy).
    tris * 2 * (36 + 64 + 8 + 24) + scratches * SCRATCH_BYTES + pixels * (12 + 12 + 4)
}

/// Builds the preparation of `scene`.
pub fn prepare(scene: &Scene) -> Prepared {
    let mut triangles = Vec::new();
    let mut prim_object = Vec::new();
    let mut uvs = Vec::new();
    let mut surfaces = Vec::new();
    for (oi, o) in scene.objects.iter().enumerate() {
        let before = triangles.len();
        let surface = match &o.shape {
            Shape::Rectangle {
                center,
                tangent,
                normal,
                size,
            } => {
                let c = v3(*center);
                let t = v3(*tangent);
                let n = v3(*normal);
                let b = cross(n, t);
                let corner = |sa: f32, sb: f32| {
                    add(
                        c,
                        add(scale(t, sa * size[0] * 0.5), scale(b, sb * size[1] * 0.5)),
                    )
                };
                let (p00, p10, p11, p01) = (
                    corner(-1.0, -1.0),
                    corner(1.0, -1.0),
                    corner(1.0, 1.0),
                    corner(-1.0, 1.0),
                );
                triangles.push(Triangle {
                    v0: p00,
                    v1: p10,
                    v2: p11,
                });
                triangles.push(Triangle {
                    v0: p00,
                    v1: p11,
                    v2: p01,
                });
                Surface {
                    kind: SurfaceKind::Rectangle as u32,
                    material: o.material as u32,
                    center: *center,
                    scale_um: scene.unit_um,
                    tangent: *tangent,
                    normal: *normal,
                    ..Surface::default()
                }
            }
            Shape::Sphere {
                center,
                radius,
                pole,
                tangent,
                uv_um,
                segments,
            } => {
                sphere_triangles(*center, *radius, *pole, *tangent, *segments, &mut triangles);
                Surface {
                    kind: SurfaceKind::Sphere as u32,
                    material: o.material as u32,
                    center: *center,
                    scale_um: *uv_um,
                    tangent: *tangent,
                    radius: *radius,
                    normal: *pole,
                    ..Surface::default()
                }
            }
            Shape::Mesh {
                vertices,
                indices,
                uvs: tex,
                uv_um,
            } => {
                uvs.resize(triangles.len(), TriangleUv::default());
                for t in indices {
                    let [a, b, c] = t.map(|i| i as usize);
                    triangles.push(Triangle {
                        v0: vertices[a],
                        v1: vertices[b],
                        v2: vertices[c],
                    });
                    uvs.push(TriangleUv {
                        uv: [tex[a], tex[b], tex[c]],
                        pad: [0.0; 2],
                    });
                }
                Surface {
                    kind: SurfaceKind::Mesh as u32,
                    material: o.material as u32,
                    scale_um: *uv_um,
                    ..Surface::default()
                }
            }
        };
        uvs.resize(triangles.len(), TriangleUv::default());
        surfaces.push(surface);
        prim_object.resize(triangles.len(), oi as u32);
        debug_assert!(triangles.len() > before);
    }
    let lookups: Vec<ScratchLookup> = scene
        .materials
        .iter()
        .map(|m| ScratchLookup::new(&m.scratches, m.shade.table.sigma_um))
        .collect();
    let grids = scene
        .materials
        .iter()
        .zip(&lookups)
        .map(|(m, l)| {
            if scene.settings.lookup != Lookup::Grid {
                return None;
            }
            let budget = (m.scratches.len() as u64 * GRID_ENTRIES_PER_SCRATCH).max(1 << 20);
            l.grid(m.shade.table.sigma_um, budget as usize)
        })
        .collect();
    let mut lights = Vec::new();
    for (li, l) in scene.lights.iter().enumerate() {
        let source = li as u32;
        match l {
            LightDef::Point {
                position,
                intensity,
            } => lights.push(SceneLight {
                kind: SceneLightKind::Point as u32,
                source,
                p0: [position[0], position[1], position[2], 0.0],
                emission: *intensity,
                ..SceneLight::default()
            }),
            LightDef::Directional {
                direction,
                irradiance,
            } => lights.push(SceneLight {
                kind: SceneLightKind::Directional as u32,
                source,
                p0: [direction[0], direction[1], direction[2], 0.0],
                emission: *irradiance,
                ..SceneLight::default()
            }),
            LightDef::Sphere {
                center,
                radius,
                radiance,
            } => lights.push(SceneLight {
                kind: SceneLightKind::Sphere as u32,
                source,
                p0: [center[0], center[1], center[2], *radius],
                emission: *radiance,
                ..SceneLight::default()
            }),
            LightDef::Polygon { vertices, radiance } => {
                for [a, b, c] in triangulate(vertices).unwrap_or_default() {
                    let p = |i: usize| [vertices[i][0], vertices[i][1], vertices[i][2], 0.0];
                    lights.push(SceneLight {
                        kind: SceneLightKind::Triangle as u32,
                        source,
                        p0: p(a),
                        p1: p(b),
                        p2: p(c),
                        emission: *radiance,
                        ..SceneLight::default()
                    });
                }
            }
        }
    }
    Prepared {
        triangles,
        prim_object,
        uvs,
        surfaces,
        materials: scene.materials.iter().map(|m| m.shade).collect(),
        lookups,
        grids,
        lights,
    }
}

impl Prepared {
    /// The shapes a hit refers to, as the kernel's light loop reads them.
    pub fn geometry(&self) -> SceneGeometry<'_> {
        SceneGeometry {
            triangles: &self.triangles,
            uvs: &self.uvs,
            prim_object: &self.prim_object,
            surfaces: &self.surfaces,
        }
    }

    /// The portable kernel BVH over the triangles.
    pub fn cpu_bvh(&self) -> TriangleBvh {
        TriangleBvh::from_triangles(&self.triangles)
            .expect("prepared scenes are limited far below 2^32 triangles")
    }

    /// The triangles as an indexed mesh (three vertices per triangle).
    pub fn indexed(&self) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
        let mut v = Vec::with_capacity(self.triangles.len() * 3);
        let mut i = Vec::with_capacity(self.triangles.len());
        for (k, t) in self.triangles.iter().enumerate() {
            v.extend_from_slice(&[t.v0, t.v1, t.v2]);
            let b = 3 * k as u32;
            i.push([b, b + 1, b + 2]);
        }
        (v, i)
    }
}

/// Ear-clipping triangulation of a planar simple polygon (either winding): index triples,
/// or `None` if the polygon is degenerate (zero area) or not simple enough to clip.
pub fn triangulate(vertices: &[[f32; 3]]) -> Option<Vec<[usize; 3]>> {
    let n = vertices.len();
    if n < 3 {
        return None;
    }
    // Newell normal, then 2-D coordinates in the polygon's plane.
    let mut nrm = [0.0f64; 3];
    for i in 0..n {
        let a = vertices[i].map(f64::from);
        let b = vertices[(i + 1) % n].map(f64::from);
        nrm[0] += (a[1] - b[1]) * (a[2] + b[2]);
        nrm[1] += (a[2] - b[2]) * (a[0] + b[0]);
        nrm[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    let len = (nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]).sqrt();
    if !(len > 0.0) {
        return None;
    }
    let nz = nrm.map(|x| x / len);
    let helper = if nz[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let e1 = normalize64(cross64(helper, nz));
    let e2 = cross64(nz, e1);
    let pts: Vec<[f64; 2]> = vertices
        .iter()
        .map(|v| {
            let v = v.map(f64::from);
            [dot64(v, e1), dot64(v, e2)]
        })
        .collect();
    // Counter-clockwise in (e1, e2) since nz = e1 × e2 points along the Newell normal.
    let area2 = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
        (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    };
    let mut idx: Vec<usize> = (0..n).collect();
    let mut out = Vec::with_capacity(n - 2);
    let mut guard = 0;
    while idx.len() > 3 {
        let m = idx.len();
        let mut clipped = false;
        for k in 0..m {
            let (ia, ib, ic) = (idx[(k + m - 1) % m], idx[k], idx[(k + 1) % m]);
            let (a, b, c) = (pts[ia], pts[ib], pts[ic]);
            if area2(a, b, c) <= 0.0 {
                continue;
            }
            let inside = idx.iter().any(|&j| {
                if j == ia || j == ib || j == ic {
                    return false;
                }
                let p = pts[j];
                area2(a, b, p) >= 0.0 && area2(b, c, p) >= 0.0 && area2(c, a, p) >= 0.0
            });
            if !inside {
                out.push([ia, ib, ic]);
                idx.remove(k);
                clipped = true;
                break;
            }
        }
        guard += 1;
        if !clipped || guard > 4 * n {
            return None;
        }
    }
    if area2(pts[idx[0]], pts[idx[1]], pts[idx[2]]) <= 0.0 {
        return None;
    }
    out.push([idx[0], idx[1], idx[2]]);
    Some(out)
}

fn sphere_triangles(
    center: [f32; 3],
    radius: f32,
    pole: [f32; 3],
    tangent: [f32; 3],
    segments: u32,
    out: &mut Vec<Triangle>,
) {
    let n = v3(pole);
    let t = v3(tangent);
    let b = cross(n, t);
    let c = v3(center);
    let (rings, sectors) = (segments.max(2), 2 * segments.max(2));
    let point = |i: u32, j: u32| {
        let theta = math::PI * i as f32 / rings as f32;
        let phi = math::TAU * j as f32 / sectors as f32;
        let (st, ct) = (theta.sin(), theta.cos());
        let (sp, cp) = (phi.sin(), phi.cos());
        add(
            c,
            scale(
                add(scale(n, ct), add(scale(t, st * cp), scale(b, st * sp))),
                radius,
            ),
        )
    };
    for i in 0..rings {
        for j in 0..sectors {
            let (p00, p01, p10, p11) = (
                point(i, j),
                point(i, j + 1),
                point(i + 1, j),
                point(i + 1, j + 1),
            );
            // Outward winding; pole quads degenerate to one triangle each, but both are kept
            // so primitive counts stay 2·rings·sectors (a zero-area triangle is never hit).
            out.push(Triangle {
                v0: p00,
                v1: p10,
                v2: p11,
            });
            out.push(Triangle {
                v0: p00,
                v1: p11,
                v2: p01,
            });
        }
    }
}

fn v3(a: [f32; 3]) -> [f32; 3] {
    a
}
fn add(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn scale(a: [f32; 3], s: f32) -> [f32; 3] {
    [a[0] * s, a[1] * s, a[2] * s]
}
fn cross(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn cross64(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn dot64(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn normalize64(a: [f64; 3]) -> [f64; 3] {
    let l = dot64(a, a).sqrt();
    a.map(|x| x / l)
}
