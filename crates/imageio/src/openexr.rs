//! OpenEXR through the `exr` crate: every buffer of an image as named channels, colour and
//! scalar channels as half or float, depth, normals and motion as float, tags as 32-bit
//! unsigned integers.

use std::path::Path;

use exr::prelude::{
    f16, AnyChannel, AnyChannels, Encoding, FlatSamples, Image, Layer, LayerAttributes, LineOrder, WritableImage,
};

use crate::{Error, Format, ImageData, Pixels, Sample};

/// The channels of one buffer: their names and values. The main buffer (`name` empty) is
/// `R G B A` (colour), `Y` (scalar), `Z` (depth), `N.X N.Y N.Z` (normals), `M.X M.Y`
/// (motion) or `tag`; a named buffer prefixes colour channels with `name.` (`fb0.R`), names a
/// scalar, depth or tag channel `name`, and normal and motion channels `name.X`….
pub fn exr_channels(name: &str, pixels: &Pixels, half: bool) -> Vec<(String, ChannelValues)> {
    let dotted = |c: &str| if name.is_empty() { c.to_string() } else { format!("{name}.{c}") };
    let plain = |default: &str| if name.is_empty() { default.to_string() } else { name.to_string() };
    let colour = |v: Vec<f32>| if half { ChannelValues::Half(v) } else { ChannelValues::Float(v) };
    match pixels {
        Pixels::Color { linear, .. } => ["R", "G", "B", "A"]
            .iter()
            .enumerate()
            .map(|(k, c)| (dotted(c), colour(linear.iter().map(|p| p[k]).collect())))
            .collect(),
        Pixels::Scalar(v) => vec![(plain("Y"), colour(v.clone()))],
        Pixels::Depth(v) => vec![(plain("Z"), ChannelValues::Float(v.clone()))],
        Pixels::Normal(v) => ["X", "Y", "Z"]
            .iter()
            .enumerate()
            .map(|(k, c)| (format!("{}.{c}", plain("N")), ChannelValues::Float(v.iter().map(|n| n[k]).collect())))
            .collect(),
        Pixels::Motion(v) => ["X", "Y"]
            .iter()
            .enumerate()
            .map(|(k, c)| (format!("{}.{c}", plain("M")), ChannelValues::Float(v.iter().map(|m| m[k]).collect())))
            .collect(),
        Pixels::Tag(v) => vec![(plain("tag"), ChannelValues::Uint(v.clone()))],
    }
}

/// The values of one EXR channel.
#[derive(Clone, Debug, PartialEq)]
pub enum ChannelValues {
    /// Stored as 16-bit half floats.
    Half(Vec<f32>),
    /// Stored as 32-bit floats.
    Float(Vec<f32>),
    /// Stored as 32-bit unsigned integers.
    Uint(Vec<u32>),
}

/// The EXR channels of every buffer of `image`, in the order the buffers list them:
/// colour and scalar channels half when `format.sample` is [`Sample::Half`], else float;
/// colour without alpha (`format.alpha` false) leaves out `A`. Two buffers writing one
/// channel name is an error.
pub(crate) fn channel_list(format: Format, image: &ImageData) -> Result<Vec<(String, ChannelValues)>, Error> {
    let half = format.sample == Sample::Half;
    let mut list: Vec<(String, ChannelValues)> = Vec::new();
    for (name, pixels) in std::iter::once(("", &image.pixels)).chain(image.layers.iter().map(|(n, p)| (n.as_str(), p)))
    {
        for (channel, values) in exr_channels(name, pixels, half) {
            if name.is_empty() && channel == "A" && !format.alpha {
                continue;
            }
            if list.iter().any(|(c, _)| *c == channel) {
                return Err(Error::Unsupported(format!("two buffers write the EXR channel '{channel}'")));
            }
            list.push((channel, values));
        }
    }
    Ok(list)
}

/// How mira's EXR files are encoded: RLE in 64 × 64 tiles written in increasing order
/// (the same image gives the same file, byte for byte; the default order is whichever
/// parallel compression finishes first).
pub(crate) const ENCODING: Encoding = Encoding { line_order: LineOrder::Increasing, ..Encoding::FAST_LOSSLESS };

/// Writes every buffer of `image` to one single-part EXR (see [`channel_list`] and
/// [`ENCODING`]).
pub(crate) fn write(path: &Path, format: Format, image: &ImageData) -> Result<(), Error> {
    let list = channel_list(format, image)?;
    let channels: Vec<AnyChannel<FlatSamples>> = list
        .into_iter()
        .map(|(name, values)| {
            let samples = match values {
                ChannelValues::Half(v) => FlatSamples::F16(v.into_iter().map(f16::from_f32).collect()),
                ChannelValues::Float(v) => FlatSamples::F32(v),
                ChannelValues::Uint(v) => FlatSamples::U32(v),
            };
            AnyChannel::new(name.as_str(), samples)
        })
        .collect();
    let size = (image.width as usize, image.height as usize);
    let layer = Layer::new(size, LayerAttributes::default(), ENCODING, AnyChannels::sort(channels.into()));
    Image::from_layer(layer).write().to_file(path).map_err(|e| Error::Encode(e.to_string()))
}
