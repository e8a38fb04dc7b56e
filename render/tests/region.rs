//! Regions of an image, rendered apart and put together, equal the whole image bit for bit
//! (what a render spread over processes relies on), on scenes with a pixel footprint, area
//! lights and shadows; a region outside the image is an input error naming `region`.

use scratchwave_render::{Backend, Region, RenderError, render_scene, render_scene_region};
use std::path::Path;

fn scene(name: &str) -> scratchwave_render::Scene {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../conformance/scenes")
        .join(name);
    scratchwave_render::scene_file::read_scene(&p).expect("scene")
}

#[test]
fn regions_assemble_into_the_whole_image() {
    for name in ["velinov_footprint.json", "ghs_polygon_shadow.json"] {
        let s = scene(name);
        let (w, h) = (s.camera.width_px, s.camera.height_px);
        let whole = render_scene(&s, Backend::Cpu, &|_, _| {}).unwrap().image;
        // Cuts off the tile grid (8 px) on purpose.
        let (cx, cy) = (13, 7);
        let parts = [
            Region {
                x0: 0,
                y0: 0,
                width: cx,
                height: cy,
            },
            Region {
                x0: cx,
                y0: 0,
                width: w - cx,
                height: cy,
            },
            Region {
                x0: 0,
                y0: cy,
                width: cx,
                height: h - cy,
            },
            Region {
                x0: cx,
                y0: cy,
                width: w - cx,
                height: h - cy,
            },
        ];
        let mut rgb = vec![[f32::NAN; 3]; (w * h) as usize];
        for r in parts {
            let img = render_scene_region(&s, Backend::Cpu, r, &|_, _| {})
                .unwrap()
                .image;
            assert_eq!((img.width, img.height), (r.width, r.height));
            for j in 0..r.height {
                for i in 0..r.width {
                    rgb[((r.y0 + j) * w + r.x0 + i) as usize] = img.rgb[(j * r.width + i) as usize];
                }
            }
        }
        let bits = |v: &[[f32; 3]]| v.iter().flatten().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(
            bits(&rgb),
            bits(&whole.rgb),
            "{name}: regions differ from the whole"
        );
        assert!(
            whole.rgb.iter().flatten().any(|x| *x > 0.0),
            "{name}: black image"
        );
    }
}

#[test]
fn region_outside_the_image_is_an_input_error() {
    let s = scene("velinov_footprint.json");
    let w = s.camera.width_px;
    for r in [
        Region {
            x0: w - 4,
            y0: 0,
            width: 5,
            height: 1,
        },
        Region {
            x0: 0,
            y0: 0,
            width: 0,
            height: 3,
        },
        Region {
            x0: u32::MAX,
            y0: 0,
            width: 2,
            height: 1,
        },
    ] {
        match render_scene_region(&s, Backend::Cpu, r, &|_, _| {}) {
            Err(RenderError::Input(e)) => assert!(e.to_string().starts_with("region")),
            other => panic!(
                "{r:?}: expected an input error, got {:?}",
                other.map(|_| ())
            ),
        }
    }
}
