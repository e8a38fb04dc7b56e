//! Bytes → `m.obj`, read through the scene reader (`tobj`, triangulated, one index per
//! vertex) as the one mesh of a fixed small scene; an accepted mesh is prepared and its
//! portable triangle BVH built. Never renders.
//!
//! Checks: at least one triangle, at most `MAX_MESH_TRIANGLES`, every index names a vertex,
//! every vertex and texture coordinate is finite (the reader promises finite positions;
//! texture coordinates are checked here too), one texture coordinate per vertex; the
//! preparation has one triangle per index triple, each with the mesh's vertices.
#![no_main]

use libfuzzer_sys::fuzz_target;
use scratchwave_fuzz::work_dir;
use scratchwave_render::prepare::prepare;
use scratchwave_render::scene::Shape;
use scratchwave_render::scene_file::{MAX_MESH_TRIANGLES, scene_from_value_with_limit};
use std::sync::OnceLock;

/// Memory limit passed to the reader (bytes).
const LIMIT: u64 = 64 << 20;

fn scene() -> &'static serde_json::Value {
    static SCENE: OnceLock<serde_json::Value> = OnceLock::new();
    SCENE.get_or_init(|| {
        serde_json::json!({
            "camera": {"type": "orthographic", "eye": [0, 0, 5], "target": [0, 0, 0],
                       "up": [0, 1, 0], "view_height": 2, "width_px": 4, "height_px": 4},
            "materials": {"m": {"model": "werner", "sigma_um": 10, "scratches": []}},
            "objects": [{"shape": "mesh", "file": "m.obj", "uv_um": 1000, "material": "m"}],
            "lights": [{"type": "point", "position": [0, 0, 5], "intensity": 1}]
        })
    })
}

fuzz_target!(|data: &[u8]| {
    let d = work_dir();
    std::fs::write(d.join("m.obj"), data).expect("write");
    let Ok(s) = scene_from_value_with_limit(scene(), "fuzz", d, LIMIT) else {
        return;
    };
    let Some(Shape::Mesh {
        vertices,
        indices,
        uvs,
        ..
    }) = s.objects.first().map(|o| &o.shape)
    else {
        panic!("the scene has one mesh object");
    };
    assert!(!indices.is_empty() && indices.len() <= MAX_MESH_TRIANGLES);
    assert_eq!(uvs.len(), vertices.len());
    assert!(vertices.iter().flatten().all(|x| x.is_finite()));
    assert!(uvs.iter().flatten().all(|x| x.is_finite()), "{uvs:?}");
    assert!(
        indices
            .iter()
            .flatten()
            .all(|&i| (i as usize) < vertices.len())
    );
    let p = prepare(&s);
    assert_eq!(p.triangles.len(), indices.len());
    for (t, idx) in p.triangles.iter().zip(indices) {
        assert_eq!([t.v0, t.v1, t.v2], idx.map(|i| vertices[i as usize]));
    }
    std::hint::black_box(p.cpu_bvh());
});
