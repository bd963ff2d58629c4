//! Writing an EXR strip by strip: an image too large to hold in memory is handed over as
//! strips of whole rows, top to bottom, and each 64 × 64 tile is compressed and written as
//! soon as its rows have arrived, so that only one strip is held at a time.
//!
//! The file is the one [`crate::write`] makes of the whole image, byte for byte: the same
//! header (channels sorted by name, RLE in 64 × 64 tiles, increasing order) and the same
//! tiles in the same order.

use std::io::BufWriter;
use std::path::Path;

use exr::block::writer::{ChunksWriter, SequentialBlocksCompressor};
use exr::block::{BlockIndex, UncompressedBlock};
use exr::math::RoundingMode;
use exr::meta::attribute::{ChannelDescription, ChannelList, LevelMode, SampleType, TileDescription};
use exr::meta::header::{Header, ImageAttributes, LayerAttributes};
use exr::meta::{BlockDescription, MetaData};
use exr::prelude::{f16, IntegerBounds, Text, Vec2};

use crate::openexr::{channel_list, ChannelValues, ENCODING};
use crate::{Error, Format, ImageData};

/// Rows of one tile: strips other than the last must hold a multiple of this many rows.
pub const STRIP_ALIGNMENT: u32 = 64;

/// The receiving end of a strip-by-strip EXR: [`ExrStrips::put`] each strip in order.
pub struct ExrStrips<'m, W: ChunksWriter> {
    meta: &'m MetaData,
    compressor: SequentialBlocksCompressor<'m, W>,
    /// The tiles in file order, with their index in increasing-y order.
    blocks: std::iter::Peekable<std::vec::IntoIter<(usize, BlockIndex)>>,
    format: Format,
    width: u32,
    height: u32,
    /// The first row the next strip must start at.
    next_row: u32,
}

impl<W: ChunksWriter> ExrStrips<'_, W> {
    /// Writes the tiles of `strip`, the image's rows `y0 .. y0 + strip.height` (every
    /// buffer the layout had, in the same order). Strips come top to bottom without gaps,
    /// and every strip but the last holds a multiple of [`STRIP_ALIGNMENT`] rows.
    pub fn put(&mut self, y0: u32, strip: &ImageData) -> Result<(), Error> {
        let end = u64::from(y0) + u64::from(strip.height);
        if y0 != self.next_row || strip.width != self.width || end > u64::from(self.height) {
            return Err(Error::Size(format!(
                "strip of {} × {} at row {y0} does not continue the {} × {} image at row {}",
                strip.width, strip.height, self.width, self.height, self.next_row
            )));
        }
        let end = end as u32;
        if strip.height == 0 {
            return Ok(());
        }
        // Every buffer must hold the strip's pixels: the tiles index them by row and column.
        crate::check(strip)?;
        if end < self.height && strip.height % STRIP_ALIGNMENT != 0 {
            return Err(Error::Size(format!(
                "a strip that is not the last must hold a multiple of {STRIP_ALIGNMENT} rows, not {}",
                strip.height
            )));
        }
        let values = channel_list(self.format, strip)?;
        let header = &self.meta.headers[0];
        // Header channel k (sorted by name) → the strip's values.
        let order: Vec<&ChannelValues> = header
            .channels
            .list
            .iter()
            .map(|c| {
                let name = c.name.to_string();
                values.iter().find(|(n, _)| *n == name).map(|(_, v)| v).ok_or_else(|| {
                    Error::Unsupported(format!("the strip has no channel '{name}' that the file's header lists"))
                })
            })
            .collect::<Result<_, _>>()?;
        let width = self.width as usize;
        while let Some(&(index, block)) = self.blocks.peek() {
            let (top, rows) = (block.pixel_position.y(), block.pixel_size.height());
            if top + rows > end as usize {
                break;
            }
            self.blocks.next();
            let mut failed = None;
            let data = UncompressedBlock::collect_block_data_from_lines(&header.channels, block, |line| {
                let row = line.location.position.y() - y0 as usize;
                let start = row * width + line.location.position.x();
                let n = line.location.sample_count;
                let written = match order[line.location.channel] {
                    ChannelValues::Half(v) => line.write_samples(|i| f16::from_f32(v[start + i])),
                    ChannelValues::Float(v) => line.write_samples_from_slice(&v[start..start + n]),
                    ChannelValues::Uint(v) => line.write_samples_from_slice(&v[start..start + n]),
                };
                if let Err(e) = written {
                    failed = Some(e);
                }
            });
            if let Some(e) = failed {
                return Err(Error::Encode(e.to_string()));
            }
            self.compressor
                .compress_block(index, UncompressedBlock { index: block, data })
                .map_err(|e| Error::Encode(e.to_string()))?;
        }
        self.next_row = end;
        Ok(())
    }
}

/// What an [`ExrStrips`] writes to: an EXR file's chunks.
pub type FileChunks = exr::block::writer::ChunkWriter<BufWriter<std::fs::File>>;

/// The header [`crate::write`] gives a `width` × `height` image with `layout`'s buffers.
fn header(format: Format, layout: &ImageData, width: u32, height: u32) -> Result<Header, Error> {
    let mut channels: Vec<ChannelDescription> = channel_list(format, layout)?
        .into_iter()
        .map(|(name, values)| {
            let name = Text::new_or_none(&name)
                .ok_or_else(|| Error::Unsupported(format!("EXR channel name '{name}' is not Latin-1")))?;
            let sample_type = match values {
                ChannelValues::Half(_) => SampleType::F16,
                ChannelValues::Float(_) => SampleType::F32,
                ChannelValues::Uint(_) => SampleType::U32,
            };
            let linear = ChannelDescription::guess_quantization_linearity(&name);
            Ok(ChannelDescription::new(name, sample_type, linear))
        })
        .collect::<Result<_, Error>>()?;
    channels.sort_by(|a, b| a.name.cmp(&b.name));
    let size = Vec2(width as usize, height as usize);
    let exr::image::Blocks::Tiles(tile_size) = ENCODING.blocks else {
        return Err(Error::Unsupported("strips are written as tiles".into()));
    };
    let blocks = BlockDescription::Tiles(TileDescription {
        tile_size,
        level_mode: LevelMode::Singular,
        rounding_mode: RoundingMode::Down,
    });
    let mut h = Header::new(Text::from(""), size, channels.into_iter().collect())
        .with_encoding(ENCODING.compression, blocks, ENCODING.line_order)
        .with_attributes(LayerAttributes::default());
    h.channels = ChannelList::new(h.channels.list);
    h.shared_attributes = ImageAttributes::new(IntegerBounds::new(Vec2(0, 0), size));
    Ok(h)
}

/// Writes a `width` × `height` EXR at `path` whose strips `produce` hands to the
/// [`ExrStrips`] it is given; `layout` is an image of the same buffers (any size: only its
/// buffers' kinds and names are read). Fails, leaving no file, when `produce` fails or does
/// not deliver every row.
pub fn write_exr_strips(
    path: &Path,
    format: Format,
    width: u32,
    height: u32,
    layout: &ImageData,
    produce: impl FnOnce(&mut ExrStrips<'_, FileChunks>) -> Result<(), Error>,
) -> Result<(), Error> {
    if width == 0 || height == 0 {
        return Err(Error::Size("an image of no pixels".into()));
    }
    let headers = smallvec_of(header(format, layout, width, height)?);
    let file = std::fs::File::create(path)?;
    let mut failure: Option<Error> = None;
    let result = exr::block::write(BufWriter::new(file), headers, true, |meta, chunk_writer| {
        let blocks: Vec<(usize, BlockIndex)> =
            exr::block::enumerate_ordered_header_block_indices(&meta.headers).collect();
        let mut sink = ExrStrips {
            meta: &meta,
            compressor: SequentialBlocksCompressor::new(&meta, chunk_writer),
            blocks: blocks.into_iter().peekable(),
            format,
            width,
            height,
            next_row: 0,
        };
        let produced = produce(&mut sink);
        let complete = sink.next_row == height;
        match produced {
            Err(e) => failure = Some(e),
            Ok(()) if !complete => {
                failure = Some(Error::Size(format!("only {} of {height} rows were written", sink.next_row)))
            }
            Ok(()) => return Ok(()),
        }
        Err(exr::error::Error::Aborted)
    });
    if let Some(e) = failure.or_else(|| result.err().map(|e| Error::Encode(e.to_string()))) {
        let _ = std::fs::remove_file(path);
        return Err(e);
    }
    Ok(())
}

fn smallvec_of(h: Header) -> exr::meta::Headers {
    std::iter::once(h).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Kind, Pixels};

    /// A 70 × 150 image with colour, depth, tags and a user buffer; pixel values differ.
    fn image(rows: std::ops::Range<u32>) -> ImageData {
        let w = 70u32;
        let px: Vec<(u32, u32)> = rows.flat_map(|y| (0..w).map(move |x| (x, y))).collect();
        let h = (px.len() / w as usize) as u32;
        let colour: Vec<[f32; 4]> = px.iter().map(|&(x, y)| [x as f32 * 0.01, y as f32 * 0.1, 0.5, 1.0]).collect();
        ImageData::new(w, h, Pixels::Color { linear: colour.clone(), display: colour.clone() })
            .with_layer("", Pixels::Depth(px.iter().map(|&(x, y)| (x * y) as f32).collect()))
            .with_layer("", Pixels::Tag(px.iter().map(|&(x, y)| x + 1000 * y).collect()))
            .with_layer("fb0", Pixels::Color { linear: colour.clone(), display: colour })
    }

    #[test]
    fn strips_make_the_same_file_as_the_whole_image() {
        let dir = std::env::temp_dir().join(format!("mira-exr-strips-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        for format in [Format::of(Kind::Exr), Format::of(Kind::Exr).with_data_type("rgba_h")] {
            let (whole, strips) = (dir.join("whole.exr"), dir.join("strips.exr"));
            crate::write(&whole, format, &image(0..150)).unwrap();
            write_exr_strips(&strips, format, 70, 150, &image(0..0), |sink| {
                for rows in [0..64, 64..128, 128..150] {
                    sink.put(rows.start, &image(rows))?;
                }
                Ok(())
            })
            .unwrap();
            assert!(std::fs::read(&whole).unwrap() == std::fs::read(&strips).unwrap(), "{format:?}");
        }
        // Misuse is an error, and leaves no file.
        let bad = dir.join("bad.exr");
        let gap = write_exr_strips(&bad, Format::of(Kind::Exr), 70, 150, &image(0..0), |sink| {
            sink.put(0, &image(0..64))?;
            sink.put(100, &image(100..150))
        });
        assert!(matches!(gap, Err(Error::Size(_))), "{gap:?}");
        assert!(!bad.exists());
        let unaligned =
            write_exr_strips(&bad, Format::of(Kind::Exr), 70, 150, &image(0..0), |sink| sink.put(0, &image(0..50)));
        assert!(matches!(unaligned, Err(Error::Size(_))), "{unaligned:?}");
        let short =
            write_exr_strips(&bad, Format::of(Kind::Exr), 70, 150, &image(0..0), |sink| sink.put(0, &image(0..64)));
        assert!(matches!(short, Err(Error::Size(m)) if m.contains("only 64 of 150 rows")));
        assert!(!bad.exists());
        // A strip whose buffers do not hold its pixels (a short depth buffer), or whose
        // height runs past the image (and past u32), is an error, not an index out of range
        // or an overflow.
        let mut short_depth = image(0..64);
        short_depth.layers[0].1 = Pixels::Depth(vec![0.0; 10]);
        let e = write_exr_strips(&bad, Format::of(Kind::Exr), 70, 150, &image(0..0), |sink| sink.put(0, &short_depth));
        assert!(matches!(&e, Err(Error::Size(m)) if m.contains("has 10 pixels")), "{e:?}");
        let e = write_exr_strips(&bad, Format::of(Kind::Exr), 70, 150, &image(0..0), |sink| {
            sink.put(0, &image(0..64))?;
            sink.put(64, &ImageData { height: u32::MAX, ..image(64..128) })
        });
        assert!(matches!(&e, Err(Error::Size(m)) if m.contains("does not continue")), "{e:?}");
        assert!(!bad.exists());
        std::fs::remove_dir_all(&dir).ok();
    }
}
