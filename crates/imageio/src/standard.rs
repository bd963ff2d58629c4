//! PNG, JPEG, TIFF, Targa (uncompressed), BMP, PPM and Radiance HDR through the `image`
//! crate.

use std::fs::File;
use std::io::BufWriter;
use std::path::Path;

use image::codecs::{bmp, hdr, jpeg, png, pnm, tga, tiff};
use image::{ExtendedColorType, ImageEncoder};

use crate::pixels::{f32s, sample, u16s, u8s};
use crate::{Error, Format, ImageData, Kind, Sample};

/// JPEG quality, 1–100: the `image` crate's default, as mira wrote JPEG before this crate.
const JPEG_QUALITY: u8 = 75;

fn colour_type(channels: usize, sample: Sample) -> ExtendedColorType {
    match (channels, sample) {
        (1, Sample::U8) => ExtendedColorType::L8,
        (3, Sample::U8) => ExtendedColorType::Rgb8,
        (4, Sample::U8) => ExtendedColorType::Rgba8,
        (1, Sample::U16) => ExtendedColorType::L16,
        (3, Sample::U16) => ExtendedColorType::Rgb16,
        (4, Sample::U16) => ExtendedColorType::Rgba16,
        (4, _) => ExtendedColorType::Rgba32F,
        _ => ExtendedColorType::Rgb32F,
    }
}

fn encode_err(e: image::ImageError) -> Error {
    Error::Encode(e.to_string())
}

/// Writes a format the `image` crate encodes.
pub(crate) fn write(path: &Path, format: Format, image: &ImageData) -> Result<(), Error> {
    let sample = sample(format)?;
    let (w, h) = (image.width, image.height);
    let mut out = BufWriter::new(File::create(path)?);
    let grey = matches!(format.kind, Kind::Png | Kind::Tiff | Kind::Jpeg | Kind::Targa | Kind::Bmp);
    // Formats without alpha drop it.
    let format = Format { alpha: format.alpha && !matches!(format.kind, Kind::Jpeg | Kind::Ppm | Kind::Hdr), ..format };
    match sample {
        Sample::U8 => {
            let px = u8s(format, image, grey)?;
            let ct = colour_type(px.channels, Sample::U8);
            let buf = &px.samples;
            match format.kind {
                Kind::Png => png::PngEncoder::new(&mut out).write_image(buf, w, h, ct),
                Kind::Jpeg => jpeg::JpegEncoder::new_with_quality(&mut out, JPEG_QUALITY).write_image(buf, w, h, ct),
                Kind::Tiff => tiff::TiffEncoder::new(&mut out).write_image(buf, w, h, ct),
                // Uncompressed: the image crate's run-length packets run across scanlines, which
                // Targa 2.0 forbids and readers such as Pillow reject.
                Kind::Targa => tga::TgaEncoder::new(&mut out).disable_rle().write_image(buf, w, h, ct),
                Kind::Bmp => bmp::BmpEncoder::new(&mut out).write_image(buf, w, h, ct),
                Kind::Ppm => pnm::PnmEncoder::new(&mut out)
                    .with_subtype(pnm::PnmSubtype::Pixmap(pnm::SampleEncoding::Binary))
                    .write_image(buf, w, h, ct),
                _ => unreachable!("8-bit formats of the image crate"),
            }
            .map_err(encode_err)?;
        }
        Sample::U16 => {
            let px = u16s(format, image, grey)?;
            let ct = colour_type(px.channels, Sample::U16);
            let bytes: Vec<u8> = px.samples.iter().flat_map(|v| v.to_ne_bytes()).collect();
            match format.kind {
                Kind::Png => png::PngEncoder::new(&mut out).write_image(&bytes, w, h, ct),
                Kind::Tiff => tiff::TiffEncoder::new(&mut out).write_image(&bytes, w, h, ct),
                _ => unreachable!("16-bit formats of the image crate"),
            }
            .map_err(encode_err)?;
        }
        Sample::F32 | Sample::Half => {
            let px = f32s(format, image, false)?;
            let ct = colour_type(px.channels, Sample::F32);
            let bytes: Vec<u8> = px.samples.iter().flat_map(|v| v.to_ne_bytes()).collect();
            match format.kind {
                Kind::Tiff => tiff::TiffEncoder::new(&mut out).write_image(&bytes, w, h, ct),
                Kind::Hdr => {
                    let rgb: Vec<image::Rgb<f32>> =
                        px.samples.chunks_exact(3).map(|c| image::Rgb([c[0], c[1], c[2]])).collect();
                    hdr::HdrEncoder::new(&mut out).encode(&rgb, w as usize, h as usize)
                }
                _ => unreachable!("float formats of the image crate"),
            }
            .map_err(encode_err)?;
        }
    }
    use std::io::Write;
    out.flush()?;
    Ok(())
}
