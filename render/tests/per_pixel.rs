//! The per-pixel renderer (what the SPIR-V backend runs: `kernel::render::radiance::
//! pixel_radiance` over the scene's shared scratch buffers and the kernel triangle
//! hierarchy) equals the tile loop bit for bit on every conformance scene, with its
//! counts. The two differ in everything around the kernel's light loop: shadow rays
//! batched per tile vs traced one by one, per-material lookups vs one set of shared
//! buffers with rebased links (the part a GPU cannot do otherwise), tiles vs rows.

use scratchwave_render::per_pixel::{FlatScene, render_per_pixel};
use scratchwave_render::{prepare, render, scene_file};
use std::path::Path;

#[test]
fn per_pixel_equals_tile_loop_on_every_conformance_scene() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../conformance/scenes");
    let mut scenes = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "json") {
            continue;
        }
        let scene = scene_file::read_scene(&path).unwrap();
        let prep = prepare::prepare(&scene);
        let bvh = prep.cpu_bvh();
        let (tiles, ts) = render::render(&scene, &prep, &bvh, &|_, _| {});
        let flat = FlatScene::new(&scene, &prep).unwrap();
        let (pixels, ps) = render_per_pixel(&flat);
        let name = path.display();
        assert_eq!((tiles.width, tiles.height), (pixels.width, pixels.height));
        for (k, (a, b)) in tiles.rgb.iter().zip(&pixels.rgb).enumerate() {
            let bits = |p: &[f32; 3]| p.map(f32::to_bits);
            assert_eq!(bits(a), bits(b), "{name}: pixel {k}: {a:?} vs {b:?}");
        }
        assert_eq!(tiles.model_choice, pixels.model_choice, "{name}");
        assert_eq!(ts.shading_evaluations, ps.shading_evaluations, "{name}");
        assert_eq!(ts.shadow_rays, ps.shadow_rays, "{name}");
        assert_eq!(ts.primary_rays, ps.primary_rays, "{name}");
        scenes += 1;
    }
    assert!(scenes >= 6, "only {scenes} scenes in {}", dir.display());
}

/// A scene whose two materials have scratches of their own (two lookups in the shared
/// buffers: rebased BVH links and slots, grid list starts and items) renders the same both
/// ways, with the grids and with the BVHs alone (`scratch_lookup: bvh`).
#[test]
fn two_scratched_materials_share_buffers() {
    let text = r#"{
      "camera": {"type": "orthographic", "eye": [0, -3, 4], "target": [0, 0, 0], "up": [0, 0, 1],
                 "view_height": 3, "width_px": 40, "height_px": 30},
      "materials": {
        "a": {"model": "velinov", "sigma_um": 10, "material": {"ior": [1.2, 7.0]}, "options": {"base": "gaussian"},
              "scratches": [{"generate": {"seed": 1, "count": 300, "region": {"min": [0, 0], "max": [1500, 1500]},
                             "shape": {"type": "straight", "length": {"uniform": [100, 600]}},
                             "orientation": {"type": "random"}, "width": {"uniform": [0.8, 3]},
                             "depth": {"uniform": [0.1, 0.4]}, "profile": "alternate"}}]},
        "b": {"model": "werner_blended", "sigma_um": 8, "material": {"ior": [0.2, 3.0]}, "base": "smooth",
              "scratches": [{"generate": {"seed": 2, "count": 200, "region": {"min": [0, 0], "max": [1500, 1500]},
                             "shape": {"type": "straight", "length": {"uniform": [100, 600]}},
                             "orientation": {"type": "brushed", "angle_deg": 30, "spread_deg": 5},
                             "width": {"uniform": [0.5, 2]}, "depth": {"uniform": [0.05, 0.2]}, "profile": "rect"}}]}
      },
      "objects": [
        {"shape": "rectangle", "center": [-0.8, 0, 0], "tangent": [1, 0, 0], "normal": [0, 0, 1], "size": [1.5, 1.5], "material": "a"},
        {"shape": "rectangle", "center": [0.8, 0, 0], "tangent": [1, 0, 0], "normal": [0, 0, 1], "size": [1.5, 1.5], "material": "b"}
      ],
      "lights": [{"type": "sphere", "center": [1, 2, 4], "radius": 0.3, "radiance": 20},
                 {"type": "point", "position": [-1, -2, 3], "intensity": 5}],
      "spectrum": {"mode": "rgb"},
      "render": {"spp": 1, "footprint": "ellipse"}
    }"#;
    let dir = std::env::temp_dir().join(format!("sw-per-pixel-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (k, lookup) in ["grid", "bvh"].iter().enumerate() {
        let path = dir.join(format!("two-{lookup}.json"));
        let text = text.replace(
            r#""footprint": "ellipse""#,
            &format!(r#""footprint": "ellipse", "scratch_lookup": "{lookup}""#),
        );
        std::fs::write(&path, text).unwrap();
        compare_two(&path, k == 0);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

fn compare_two(path: &Path, grids: bool) {
    let scene = scene_file::read_scene(path).unwrap();
    let prep = prepare::prepare(&scene);
    assert!(prep.lookups.iter().all(|l| !l.scratches().is_empty()));
    assert!(prep.grids.iter().all(|g| g.is_some() == grids));
    let bvh = prep.cpu_bvh();
    let (tiles, _) = render::render(&scene, &prep, &bvh, &|_, _| {});
    let flat = FlatScene::new(&scene, &prep).unwrap();
    assert_eq!(flat.scratches.materials.len(), 2);
    assert!(flat.scratches.materials[1].first_node > 0);
    let (pixels, _) = render_per_pixel(&flat);
    let lit = tiles.rgb.iter().filter(|p| p[0] > 0.0).count();
    assert!(lit > 100, "only {lit} lit pixels");
    for (k, (a, b)) in tiles.rgb.iter().zip(&pixels.rgb).enumerate() {
        assert_eq!(a.map(f32::to_bits), b.map(f32::to_bits), "pixel {k}");
    }
}
