//! Bytes → (scene JSON, `m.obj`, `s.csv`, `s.json`) →
//! `scene_file::scene_from_value_with_limit` with a [`LIMIT`]-byte memory limit; small
//! accepted scenes are also prepared (`prepare::prepare`, the portable triangle BVH). Never
//! renders.
//!
//! The input is split at its first three NUL bytes: the scene, then the contents of `m.obj`,
//! `s.csv` and `s.json`, written to a per-process temporary directory that is the scene's
//! base directory (so `{"shape": "mesh", "file": "m.obj"}` and `{"file": "s.csv"}` scratch
//! sources read them). Checks on an accepted scene: the reader's limits hold (the memory
//! estimate within [`LIMIT`], image edge, spp, spectral samples, sphere segments, polygon
//! vertices), every reference is in range (object → material, mesh index → vertex), every
//! number the renderer reads is finite, sizes and emissions are ≥ 0, scratch segments are
//! well formed; prepared: one surface per object, one lookup per material, the triangle
//! counts of each shape, every light emitting ≥ 0.
#![no_main]

use libfuzzer_sys::fuzz_target;
use scratchwave_fuzz::{check_segment, work_dir};
use scratchwave_kernel::render::shading::SceneModel;
use scratchwave_render::prepare::{estimate_bytes, prepare};
use scratchwave_render::scene::{LightDef, Shape};
use scratchwave_render::scene_file::{
    MAX_IMAGE_EDGE, MAX_SEGMENTS, MAX_SPECTRAL_SAMPLES, MAX_SPP, scene_from_value_with_limit,
};

/// Memory limit passed to the reader (bytes).
const LIMIT: u64 = 64 << 20;
/// Scenes whose estimate is at most this are prepared (bytes).
const PREPARE_LIMIT: u64 = 4 << 20;

fn finite<const N: usize>(v: &[f32; N]) -> bool {
    v.iter().all(|x| x.is_finite())
}

fuzz_target!(|data: &[u8]| {
    let mut parts = data.splitn(4, |&b| b == 0);
    let scene = parts.next().unwrap_or_default();
    let files = [
        ("m.obj", parts.next().unwrap_or_default()),
        ("s.csv", parts.next().unwrap_or_default()),
        ("s.json", parts.next().unwrap_or_default()),
    ];
    let Ok(v) = serde_json::from_slice::<serde_json::Value>(scene) else {
        return;
    };
    let d = work_dir();
    for (name, bytes) in files {
        std::fs::write(d.join(name), bytes).expect("write");
    }
    let Ok(s) = scene_from_value_with_limit(&v, "fuzz", d, LIMIT) else {
        return;
    };
    let need = estimate_bytes(&s);
    assert!(need <= LIMIT, "estimate {need} > limit {LIMIT}");
    let c = &s.camera;
    for n in [c.width_px, c.height_px] {
        assert!((1..=MAX_IMAGE_EDGE).contains(&u64::from(n)), "{c:?}");
    }
    assert!(
        finite(&c.eye) && finite(&c.forward) && finite(&c.right) && finite(&c.up),
        "{c:?}"
    );
    assert!(c.h.is_finite() && c.h > 0.0, "{c:?}");
    assert!(s.unit_um.is_finite() && s.unit_um > 0.0);
    assert!((1..=MAX_SPP).contains(&u64::from(s.settings.spp)));
    assert!((1..=MAX_SPECTRAL_SAMPLES).contains(&u64::from(s.spectrum.samples)));
    assert!(s.spectrum.lambda_nm.is_finite() && s.spectrum.lambda_nm > 0.0);
    for m in &s.materials {
        let t = &m.shade.table;
        let ghs = m.shade.model == SceneModel::Ghs as u32;
        assert!(ghs || (t.sigma_um.is_finite() && t.sigma_um > 0.0), "{m:?}");
        assert!(!ghs || m.scratches.is_empty(), "{m:?}");
        m.scratches.iter().for_each(check_segment);
    }
    let mut tris = 0usize;
    for o in &s.objects {
        assert!(o.material < s.materials.len());
        tris += match &o.shape {
            Shape::Rectangle {
                center,
                tangent,
                normal,
                size,
            } => {
                assert!(finite(center) && finite(tangent) && finite(normal));
                assert!(size.iter().all(|x| x.is_finite() && *x > 0.0), "{size:?}");
                2
            }
            Shape::Sphere {
                center,
                radius,
                pole,
                tangent,
                uv_um,
                segments,
            } => {
                assert!(finite(center) && finite(pole) && finite(tangent));
                assert!(radius.is_finite() && *radius > 0.0 && uv_um.is_finite() && *uv_um > 0.0);
                assert!((2..=MAX_SEGMENTS).contains(&u64::from(*segments)));
                let n = *segments as usize;
                4 * n * n
            }
            Shape::Mesh {
                vertices,
                indices,
                uvs,
                uv_um,
            } => {
                assert!(!indices.is_empty() && uvs.len() == vertices.len());
                assert!(uv_um.is_finite() && *uv_um > 0.0);
                assert!(vertices.iter().all(finite));
                assert!(
                    indices
                        .iter()
                        .flatten()
                        .all(|&i| (i as usize) < vertices.len())
                );
                indices.len()
            }
        };
    }
    for l in &s.lights {
        match l {
            LightDef::Point {
                position,
                intensity,
            } => assert!(finite(position) && intensity.is_finite() && *intensity >= 0.0),
            LightDef::Directional {
                direction,
                irradiance,
            } => assert!(finite(direction) && irradiance.is_finite() && *irradiance >= 0.0),
            LightDef::Sphere {
                center,
                radius,
                radiance,
            } => assert!(
                finite(center)
                    && radius.is_finite()
                    && *radius > 0.0
                    && radiance.is_finite()
                    && *radiance >= 0.0
            ),
            LightDef::Polygon { vertices, radiance } => {
                assert!((3..=64).contains(&vertices.len()));
                assert!(vertices.iter().all(finite) && radiance.is_finite() && *radiance >= 0.0);
            }
        }
    }
    if need > PREPARE_LIMIT {
        return;
    }
    let p = prepare(&s);
    assert_eq!(p.triangles.len(), tris);
    assert_eq!(p.uvs.len(), tris);
    assert_eq!(p.prim_object.len(), tris);
    assert_eq!(p.surfaces.len(), s.objects.len());
    assert_eq!(p.lookups.len(), s.materials.len());
    assert_eq!(p.materials.len(), s.materials.len());
    assert!(p.lights.len() >= s.lights.len());
    for l in &p.lights {
        assert!(l.emission.is_finite() && l.emission >= 0.0, "{l:?}");
    }
    std::hint::black_box(p.cpu_bvh());
});
