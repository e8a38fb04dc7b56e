//! OpenEXR files with several named layers in one part (`R`, `G`, `B` for the main layer,
//! `stderr.R`, `stderr.G`, … for the others, the channel naming Nuke, Mitsuba and
//! OpenImageIO read), float32, written atomically like [`crate::output::write_exr`]; and
//! the reader for them.

use crate::render::Image;
use crate::{RenderError, output};
use scratchwave_spec::SpecError;
use std::path::Path;

/// One layer: a name (`""` for the main `R`, `G`, `B`) and its pixels.
pub enum ExrLayer<'a> {
    /// Three channels `name.R`, `name.G`, `name.B`.
    Rgb(&'a str, &'a [[f32; 3]]),
    /// One channel `name`.
    Scalar(&'a str, &'a [f32]),
}

/// Writes the layers (each `width·height` values, row-major from the top) with one text
/// attribute per `(name, value)`; written to a temporary file and renamed.
pub fn write_layers(
    path: &Path,
    width: u32,
    height: u32,
    layers: &[ExrLayer<'_>],
    attributes: &[(&str, String)],
) -> Result<(), RenderError> {
    use exr::prelude::*;
    let (w, h) = (width as usize, height as usize);
    let mut channels: Vec<AnyChannel<FlatSamples>> = Vec::new();
    for layer in layers {
        match layer {
            ExrLayer::Rgb(name, px) => {
                for (c, ch) in ["R", "G", "B"].iter().enumerate() {
                    let full = if name.is_empty() {
                        (*ch).to_string()
                    } else {
                        format!("{name}.{ch}")
                    };
                    let data: Vec<f32> = px.iter().map(|p| p[c]).collect();
                    channels.push(AnyChannel::new(full.as_str(), FlatSamples::F32(data)));
                }
            }
            ExrLayer::Scalar(name, px) => {
                channels.push(AnyChannel::new(*name, FlatSamples::F32(px.to_vec())));
            }
        }
    }
    if channels.iter().any(|c| match &c.sample_data {
        FlatSamples::F32(d) => d.len() != w * h,
        _ => true,
    }) {
        return Err(RenderError::Output {
            path: path.display().to_string(),
            msg: "a layer does not have width·height pixels".into(),
        });
    }
    let mut attrs = LayerAttributes::default();
    for (k, v) in attributes {
        attrs
            .other
            .insert(Text::from(*k), AttributeValue::Text(Text::from(v.as_str())));
    }
    let list = AnyChannels::sort(channels.into());
    let layer = exr::image::Layer::new((w, h), attrs, Encoding::FAST_LOSSLESS, list);
    output::atomically(path, |tmp| {
        exr::image::Image::from_layer(layer)
            .write()
            .to_file(tmp)
            .map_err(|e| e.to_string())
    })
}

/// The channels of an EXR file by name, all of its first part.
pub struct Channels {
    /// Width (pixels).
    pub width: u32,
    /// Height (pixels).
    pub height: u32,
    channels: Vec<(String, Vec<f32>)>,
    path: String,
}

impl Channels {
    /// Reads every channel of the first part of `path` as f32; errors name the file.
    pub fn read(path: &Path) -> Result<Channels, SpecError> {
        use exr::prelude::*;
        let bad = |msg: String| SpecError::Io {
            path: path.display().to_string(),
            msg,
        };
        let img = read_first_flat_layer_from_file(path).map_err(|e| bad(e.to_string()))?;
        let size = img.layer_data.size;
        let channels = img
            .layer_data
            .channel_data
            .list
            .iter()
            .map(|c| {
                let v: Vec<f32> = c.sample_data.values_as_f32().collect();
                (c.name.to_string(), v)
            })
            .collect();
        Ok(Channels {
            width: size.width() as u32,
            height: size.height() as u32,
            channels,
            path: path.display().to_string(),
        })
    }

    /// Channel `name`; a typed error naming the file and the channel when it is missing.
    pub fn channel(&self, name: &str) -> Result<&[f32], SpecError> {
        self.channels
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.as_slice())
            .ok_or_else(|| {
                SpecError::field(
                    format!("{}: channel {name}", self.path),
                    "missing (expected a file written by scratchwave render)",
                )
            })
    }

    /// Layer `name` (`""`: the main `R`, `G`, `B`) as an image.
    pub fn rgb(&self, name: &str) -> Result<Image, SpecError> {
        let full = |c: &str| {
            if name.is_empty() {
                c.to_string()
            } else {
                format!("{name}.{c}")
            }
        };
        let (r, g, b) = (
            self.channel(&full("R"))?,
            self.channel(&full("G"))?,
            self.channel(&full("B"))?,
        );
        Ok(Image {
            width: self.width,
            height: self.height,
            rgb: r
                .iter()
                .zip(g)
                .zip(b)
                .map(|((&r, &g), &b)| [r, g, b])
                .collect(),
            model_choice: Vec::new(),
        })
    }
}
