//! Hostile scene inputs (issue #18, found while writing the `scene_file` and `obj_mesh` fuzz
//! targets): the mesh file or an OBJ's `mtllib` naming a device that never ends, a mesh file
//! over the size limit, and materials whose scratch sources together ask for more segments
//! than the memory limit allows. Each is a typed error naming the field, or (for `mtllib`,
//! which is ignored) a normal read, and none allocates beyond the limit.

use scratchwave_render::prepare::SCRATCH_BYTES;
use scratchwave_render::scene::Shape;
use scratchwave_render::scene_file::{MAX_MESH_FILE_BYTES, scene_from_value_with_limit};
use scratchwave_spec::SpecError;
use serde_json::{Value, json};
use std::path::PathBuf;

fn dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("scratchwave-hostile-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

const QUAD: &str =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n";

fn mesh_scene(file: &str) -> Value {
    json!({
        "camera": {"type": "orthographic", "eye": [0, 0, 5], "target": [0, 0, 0],
                   "up": [0, 1, 0], "view_height": 2, "width_px": 4, "height_px": 4},
        "materials": {"m": {"model": "werner", "scratches": []}},
        "objects": [{"shape": "mesh", "file": file, "uv_um": 1000, "material": "m"}],
        "lights": []
    })
}

fn field_error(r: Result<scratchwave_render::Scene, SpecError>) -> (String, String) {
    match r {
        Err(SpecError::Field { field, msg }) => (field, msg),
        Err(e) => panic!("expected a field error, got {e}"),
        Ok(_) => panic!("expected a field error, the scene was accepted"),
    }
}

#[test]
fn mesh_file_that_is_a_device_is_rejected() {
    let d = dir("device");
    let (path, msg) = field_error(scene_from_value_with_limit(
        &mesh_scene("/dev/zero"),
        "t",
        &d,
        1 << 30,
    ));
    assert_eq!(path, "objects[0].file");
    assert!(msg.contains("not a regular file"), "{msg}");
}

#[test]
fn mtllib_naming_a_device_is_ignored() {
    let d = dir("mtllib");
    std::fs::write(
        d.join("q.obj"),
        format!("mtllib /dev/zero\nusemtl x\n{QUAD}"),
    )
    .unwrap();
    let s = scene_from_value_with_limit(&mesh_scene("q.obj"), "t", &d, 1 << 30).unwrap();
    match &s.objects[0].shape {
        Shape::Mesh { indices, .. } => assert_eq!(indices.len(), 2),
        other => panic!("{other:?}"),
    }
}

#[test]
fn mesh_file_over_the_size_limit_is_rejected_before_reading() {
    let d = dir("big");
    let f = std::fs::File::create(d.join("big.obj")).unwrap();
    // Sparse: no disk space is used, and the reader must not read it.
    f.set_len(MAX_MESH_FILE_BYTES + 1).unwrap();
    let (path, msg) = field_error(scene_from_value_with_limit(
        &mesh_scene("big.obj"),
        "t",
        &d,
        1 << 30,
    ));
    std::fs::remove_file(d.join("big.obj")).unwrap();
    assert_eq!(path, "objects[0].file");
    assert!(msg.contains("MAX_MESH_FILE_BYTES"), "{msg}");
}

#[test]
fn scratch_segments_of_all_materials_share_one_budget() {
    // 3 materials × 400 segments against a limit worth 1000 segments (`SCRATCH_BYTES` each): the
    // third material's pattern is refused before it is generated.
    let generate = |seed: u64| {
        json!([{"generate": {"seed": seed, "count": 400, "region": {"min": [0, 0], "max": [1000, 1000]},
            "shape": {"type": "straight", "length": {"uniform": [10, 20]}},
            "width": {"uniform": [1, 2]}, "depth": {"uniform": [0.1, 0.2]}}}])
    };
    let mut v = mesh_scene("unused.obj");
    v["objects"] = json!([{"shape": "rectangle", "center": [0, 0, 0], "tangent": [1, 0, 0],
        "normal": [0, 0, 1], "size": [1, 1], "material": "m0"}]);
    v["materials"] = json!({
        "m0": {"model": "werner", "scratches": generate(1)},
        "m1": {"model": "werner", "scratches": generate(2)},
        "m2": {"model": "werner", "scratches": generate(3)},
    });
    let d = dir("budget");
    let (path, msg) = field_error(scene_from_value_with_limit(
        &v,
        "t",
        &d,
        SCRATCH_BYTES * 1000,
    ));
    assert_eq!(path, "materials.m2.scratches[0].generate");
    assert!(msg.contains("200"), "{msg}");
    // With room for all three the same scene is read.
    let s = scene_from_value_with_limit(&v, "t", &d, SCRATCH_BYTES * 1300).unwrap();
    assert_eq!(
        s.materials.iter().map(|m| m.scratches.len()).sum::<usize>(),
        1200
    );
}

#[test]
fn face_indices_naming_no_element_are_rejected() {
    // The `obj_mesh` fuzz finding (a relative texture index before the first one made tobj
    // multiply a wrapped usize), and its variants: positive past the end, relative before
    // the start, for positions, texture coordinates and normals.
    let d = dir("faces");
    let cases = [
        ("f 1/-4 2/2 3/3", "vt index -4"),
        ("f 1/1 2/2 3/99", "vt index 99"),
        ("f 1/1 2/2 -5/3", "v index -5"),
        (
            "f 1/1 2/2 9223372036854775807/3",
            "v index 9223372036854775807",
        ),
        ("f 1/1/-2 2/2/1 3/3/1", "vn index -2"),
        ("l 1/1 5/2", "v index 5"),
    ];
    for (i, (face, want)) in cases.iter().enumerate() {
        let name = format!("f{i}.obj");
        std::fs::write(
            d.join(&name),
            format!(
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n{face}\n"
            ),
        )
        .unwrap();
        let (path, msg) = field_error(scene_from_value_with_limit(
            &mesh_scene(&name),
            "t",
            &d,
            1 << 30,
        ));
        assert_eq!(path, "objects[0].file");
        assert!(
            msg.contains(want) && msg.contains("line 9"),
            "{face}: {msg}"
        );
    }
    // In range (relative and absolute, zero meaning "none") is read as before.
    std::fs::write(
        d.join("ok.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf -3/1 -2/-2 3/3\n",
    )
    .unwrap();
    let s = scene_from_value_with_limit(&mesh_scene("ok.obj"), "t", &d, 1 << 30).unwrap();
    assert!(matches!(&s.objects[0].shape, Shape::Mesh { indices, .. } if indices.len() == 1));
}

#[test]
fn texture_coordinates_that_overflow_are_rejected() {
    // The `obj_mesh` fuzz finding: `vt 1e39 0` parses to an infinite f32 texture coordinate,
    // which the scene reader took; it is refused like a non-finite position.
    let d = dir("uv-overflow");
    std::fs::write(
        d.join("uv.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1e39 0\nvt 0 1\nf 1/1 2/2 3/3\n",
    )
    .unwrap();
    let (path, msg) = field_error(scene_from_value_with_limit(
        &mesh_scene("uv.obj"),
        "t",
        &d,
        1 << 30,
    ));
    assert_eq!(path, "objects[0].file");
    assert!(
        msg.contains("texture coordinate") && msg.contains("not finite"),
        "{msg}"
    );
}
