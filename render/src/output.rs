//! Image writers: OpenEXR (linear float32 R, G, B, with string attributes) and a PNG
//! preview (exposure, sRGB transfer). Each file is written to a temporary name in the same
//! directory and renamed into place, so a failed write leaves nothing at the target path.

use crate::RenderError;
use crate::render::Image;
use scratchwave_kernel::render::spectrum::srgb_encode;
use std::path::{Path, PathBuf};

fn temp_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "image".into());
    path.with_file_name(format!(".{name}.{}.partial", std::process::id()))
}

fn fail(path: &Path, msg: impl std::fmt::Display) -> RenderError {
    RenderError::Output {
        path: path.display().to_string(),
        msg: msg.to_string(),
    }
}

/// Writes `tmp` with `write`, then renames it to `path` (removing `tmp` on failure).
pub(crate) fn atomically(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), String>,
) -> Result<(), RenderError> {
    let tmp = temp_path(path);
    if let Err(e) = write(&tmp) {
        let _ = std::fs::remove_file(&tmp);
        return Err(fail(path, e));
    }
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        fail(path, e)
    })
}

/// Writes `image` as OpenEXR: float32 R, G, B (linear), one text attribute per
/// `(name, value)` in `attributes` (scene name, backend, timings). An image with a
/// model-choice map (`"model": "auto"`) also gets the channels `auto.coherent` and
/// `auto.incoherent`: per pixel, the hit–light pairs shaded with each model.
pub fn write_exr(
    path: &Path,
    image: &Image,
    attributes: &[(&str, String)],
) -> Result<(), RenderError> {
    use crate::layered_exr::{ExrLayer, write_layers};
    use exr::prelude::*;
    if !image.model_choice.is_empty() {
        let count =
            |k: usize| -> Vec<f32> { image.model_choice.iter().map(|c| c[k] as f32).collect() };
        let (coherent, incoherent) = (count(0), count(1));
        return write_layers(
            path,
            image.width,
            image.height,
            &[
                ExrLayer::Rgb("", &image.rgb),
                ExrLayer::Scalar("auto.coherent", &coherent),
                ExrLayer::Scalar("auto.incoherent", &incoherent),
            ],
            attributes,
        );
    }
    let w = image.width as usize;
    let h = image.height as usize;
    atomically(path, |tmp| {
        let channels = SpecificChannels::rgb(|pos: Vec2<usize>| {
            let p = image.rgb[pos.y() * w + pos.x()];
            (p[0], p[1], p[2])
        });
        let mut attrs = LayerAttributes::default();
        for (k, v) in attributes {
            attrs
                .other
                .insert(Text::from(*k), AttributeValue::Text(Text::from(v.as_str())));
        }
        let layer = Layer::new((w, h), attrs, Encoding::FAST_LOSSLESS, channels);
        exr::image::Image::from_layer(layer)
            .write()
            .to_file(tmp)
            .map_err(|e| e.to_string())
    })
}

/// 8-bit sRGB of a linear value times `2^exposure`.
#[inline]
pub fn preview_byte(linear: f32, exposure: f32) -> u8 {
    let v = srgb_encode(linear * exposure.exp2());
    (v * 255.0 + 0.5) as u8
}

/// Writes a PNG preview: linear values scaled by `2^exposure`, clamped, sRGB-encoded.
pub fn write_png(path: &Path, image: &Image, exposure: f32) -> Result<(), RenderError> {
    write_rgb8_png(path, image.width, image.height, 1, |k| {
        image.rgb[k].map(|c| preview_byte(c, exposure))
    })
}

/// Writes an 8-bit RGB PNG of a `width × height` image, each pixel `scale × scale` wide,
/// pixel `k` (row-major from the top) coloured `colour(k)`.
pub fn write_rgb8_png(
    path: &Path,
    width: u32,
    height: u32,
    scale: u32,
    colour: impl Fn(usize) -> [u8; 3],
) -> Result<(), RenderError> {
    let s = scale.max(1);
    let mut data = Vec::with_capacity((width * s * height * s * 3) as usize);
    for y in 0..height * s {
        for x in 0..width * s {
            data.extend_from_slice(&colour(((y / s) * width + x / s) as usize));
        }
    }
    atomically(path, |tmp| {
        let file = std::fs::File::create(tmp).map_err(|e| e.to_string())?;
        let mut enc = png::Encoder::new(std::io::BufWriter::new(file), width * s, height * s);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut writer = enc.write_header().map_err(|e| e.to_string())?;
        writer.write_image_data(&data).map_err(|e| e.to_string())?;
        writer.finish().map_err(|e| e.to_string())
    })
}

/// The model-choice map's colour of a pixel with `c` coherent and `i` incoherent
/// hit–light pairs: dark grey without any, blue for all incoherent through to orange for
/// all coherent.
pub fn model_choice_colour(c: u32, i: u32) -> [u8; 3] {
    if c + i == 0 {
        return [24, 24, 24];
    }
    let f = c as f32 / (c + i) as f32;
    let mix = |a: f32, b: f32| (a + (b - a) * f).round() as u8;
    [mix(40.0, 255.0), mix(110.0, 140.0), mix(255.0, 20.0)]
}

/// Writes the model-choice map of an `auto` render as a PNG, 4× enlarged
/// ([`model_choice_colour`]); an image without a map is an error.
pub fn write_model_map(path: &Path, image: &Image) -> Result<(), RenderError> {
    if image.model_choice.is_empty() {
        return Err(fail(
            path,
            "no model-choice map: no hit of a material with \"model\": \"auto\" was shaded",
        ));
    }
    write_rgb8_png(path, image.width, image.height, 4, |k| {
        let c = image.model_choice[k];
        model_choice_colour(c[0], c[1])
    })
}

/// Reads back the R, G, B channels of an EXR written by [`write_exr`] (tests, comparisons).
pub fn read_exr(path: &Path) -> Result<crate::render::Image, RenderError> {
    use exr::prelude::*;
    let img = read_first_rgba_layer_from_file(
        path,
        |res: Vec2<usize>, _| (res, vec![[0.0f32; 3]; res.width() * res.height()]),
        |(res, px): &mut (Vec2<usize>, Vec<[f32; 3]>),
         pos: Vec2<usize>,
         (r, g, b, _a): (f32, f32, f32, f32)| {
            px[pos.y() * res.width() + pos.x()] = [r, g, b];
        },
    )
    .map_err(|e| fail(path, e))?;
    let (res, rgb) = img.layer_data.channel_data.pixels;
    Ok(crate::render::Image {
        width: res.width() as u32,
        height: res.height() as u32,
        rgb,
        model_choice: Vec::new(),
    })
}
