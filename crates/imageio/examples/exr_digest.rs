//! Prints a digest of the pixels of OpenEXR files: every layer's size and every channel's
//! name and samples (their bits, as stored), in channel-name order, hashed with 64-bit
//! FNV-1a. Two files digest alike exactly when they hold the same pixels bit for bit,
//! whatever the compression or the order of header attributes — what `tools/scene_hashes.sh`
//! compares renders with.
//!
//! ```text
//! cargo run --release -p imageio --example exr_digest -- a.exr b.exr
//! ```

use std::process::ExitCode;

use exr::prelude::{read_all_flat_layers_from_file, FlatSamples};

/// 64-bit FNV-1a over a stream of bytes.
struct Fnv(u64);

impl Fnv {
    fn bytes(&mut self, data: &[u8]) {
        for b in data {
            self.0 = (self.0 ^ u64::from(*b)).wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
}

fn digest(path: &str) -> Result<u64, String> {
    let image = read_all_flat_layers_from_file(path).map_err(|e| format!("{path}: {e}"))?;
    let mut hash = Fnv(0xcbf2_9ce4_8422_2325);
    for layer in &image.layer_data {
        hash.bytes(&(layer.size.0 as u64).to_le_bytes());
        hash.bytes(&(layer.size.1 as u64).to_le_bytes());
        let mut channels: Vec<_> = layer.channel_data.list.iter().collect();
        channels.sort_by_key(|c| c.name.to_string());
        for channel in channels {
            hash.bytes(channel.name.to_string().as_bytes());
            hash.bytes(&[0]);
            match &channel.sample_data {
                FlatSamples::F16(v) => v.iter().for_each(|s| hash.bytes(&s.to_bits().to_le_bytes())),
                FlatSamples::F32(v) => v.iter().for_each(|s| hash.bytes(&s.to_bits().to_le_bytes())),
                FlatSamples::U32(v) => v.iter().for_each(|s| hash.bytes(&s.to_le_bytes())),
            }
        }
    }
    Ok(hash.0)
}

fn main() -> ExitCode {
    let mut status = ExitCode::SUCCESS;
    for path in std::env::args().skip(1) {
        match digest(&path) {
            Ok(h) => println!("{h:016x}  {path}"),
            Err(e) => {
                eprintln!("exr_digest: {e}");
                status = ExitCode::FAILURE;
            }
        }
    }
    status
}
