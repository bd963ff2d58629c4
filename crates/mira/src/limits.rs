//! Memory limits checked before anything large is allocated: the film and frame buffers
//! an image needs, estimated from its resolution, against `--max-memory`.
//!
//! The estimate counts, per pixel: the film's accumulators ([`render::film::Pixel`]), the
//! classic engine's two splat buffers (five f64 each), the output images made from the film
//! (colour, depth, normal, label and motion, twice: the film's copy and the encoder's
//! channels) and, for each user frame buffer, its four floats and write count plus their
//! output copy. It is an upper bound of what `mira render` allocates for the image, not of
//! geometry, textures or photon maps (those have their own caps where they are built).

use std::path::Path;

/// Bytes per pixel of the classic engine's splat buffers (`[f64; 5]`, the film's and the
/// bands').
const SPLAT_BYTES: u64 = 2 * 5 * 8;

/// Bytes per pixel of the output images: RGBA (16), depth (4), normal (12), label (4),
/// motion (8), once as the film's copy and once as the encoder's channels.
const OUTPUT_BYTES: u64 = 2 * (16 + 4 + 12 + 4 + 8);

/// Bytes per pixel of one user frame buffer: four f32 and a u32 write count in the film,
/// and four f32 in the output.
const USER_BUFFER_BYTES: u64 = 16 + 4 + 16;

/// Used when the available memory cannot be read (no `/proc/meminfo`): 16 GiB.
pub const FALLBACK_LIMIT: u64 = 16 << 30;

/// The `--max-memory` option shared by `check` and `render`.
#[derive(clap::Args, Clone, Debug)]
pub struct MemoryArgs {
    /// Largest film and frame buffer memory an image may need (bytes, or with a K, M, G or
    /// T suffix: powers of 1024). Default: the machine's available memory (MemAvailable in
    /// /proc/meminfo).
    #[arg(long, value_name = "BYTES", value_parser = parse_bytes)]
    pub max_memory: Option<u64>,
}

impl MemoryArgs {
    /// The limit in bytes and where it comes from (for messages).
    pub fn limit(&self) -> (u64, &'static str) {
        match self.max_memory {
            Some(b) => (b, "--max-memory"),
            None => match available_memory(Path::new("/proc/meminfo")) {
                Some(b) => (b, "the available memory; see --max-memory"),
                None => (FALLBACK_LIMIT, "mira's default when the available memory is unknown; see --max-memory"),
            },
        }
    }
}

/// `123`, `64K`, `512M`, `1.5G`, `2T`, with an optional `B` or `iB` (powers of 1024).
pub fn parse_bytes(text: &str) -> Result<u64, String> {
    let upper = text.trim().to_ascii_uppercase();
    let t = upper.strip_suffix("IB").or_else(|| upper.strip_suffix('B')).unwrap_or(&upper);
    let (number, scale) = match t.char_indices().last() {
        Some((i, c)) if c.is_ascii_alphabetic() => {
            let shift = match c {
                'K' => 10,
                'M' => 20,
                'G' => 30,
                'T' => 40,
                _ => return Err(format!("unknown unit '{c}' in '{text}' (use K, M, G or T)")),
            };
            (&t[..i], (1u64 << shift) as f64)
        }
        _ => (t, 1.0),
    };
    let v: f64 = number.trim().parse().map_err(|_| format!("'{text}' is not a size in bytes"))?;
    let bytes = v * scale;
    if !(bytes.is_finite() && bytes >= 1.0 && bytes < u64::MAX as f64) {
        return Err(format!("'{text}' is not a size from 1 byte to 16 EiB"));
    }
    Ok(bytes as u64)
}

/// `MemAvailable` of a `/proc/meminfo`-format file, in bytes.
pub fn available_memory(meminfo: &Path) -> Option<u64> {
    let text = std::fs::read_to_string(meminfo).ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let mut words = line.split_whitespace().skip(1);
    let kb: u64 = words.next()?.parse().ok()?;
    (words.next() == Some("kB")).then_some(kb.checked_mul(1024)?)
}

/// Estimated bytes of the film and frame buffers of a `width` × `height` image with
/// `user_buffers` user frame buffers (see the module documentation).
pub fn film_bytes(width: u64, height: u64, user_buffers: u64) -> u128 {
    let per_pixel = std::mem::size_of::<render::film::Pixel>() as u64
        + SPLAT_BYTES
        + OUTPUT_BYTES
        + user_buffers * USER_BUFFER_BYTES;
    u128::from(width) * u128::from(height) * u128::from(per_pixel)
}

/// User frame buffers a scene asks for (options `frame buffer n`, camera `framebuffer`s
/// marked `user`).
pub fn user_buffers(scene: &scene::Scene) -> u64 {
    let mut names: Vec<String> = scene.options.frame_buffers.iter().map(|(n, _)| format!("fb{n}")).collect();
    for fb in scene.camera.framebuffers.iter().filter(|f| f.user) {
        if !names.contains(&fb.name) {
            names.push(fb.name.clone());
        }
    }
    names.len() as u64
}

/// The film check: an error at the camera's `resolution` statement when the image at
/// `resolution` (the camera's, or a command-line override) needs more than `limit` bytes.
pub fn check_film(
    scene: &scene::Scene,
    resolution: (u32, u32),
    limit: (u64, &str),
    overridden: bool,
) -> Option<mi::Diagnostic> {
    let (w, h) = resolution;
    let need = film_bytes(u64::from(w), u64::from(h), user_buffers(scene));
    if need <= u128::from(limit.0) {
        return None;
    }
    let what = if overridden { "--resolution" } else { "resolution" };
    Some(mi::Diagnostic::error(
        scene.camera.resolution_span,
        format!(
            "{what} {w} x {h} needs {} of film and frame buffers, more than the limit of {} ({})",
            size_text(need),
            size_text(u128::from(limit.0)),
            limit.1
        ),
    ))
}

/// Most rows a strip holds when an image is rendered in strips (more gives no speed).
pub const MAX_STRIP_ROWS: u32 = 1024;

/// Rows of the strips an image `width` pixels wide with `user_buffers` user frame buffers
/// is rendered in when its whole film needs more than `limit` bytes: the most (a multiple
/// of [`imageio::exr_strips::STRIP_ALIGNMENT`], at most [`MAX_STRIP_ROWS`]) whose film,
/// with a classic halo of up to 70 rows (filters up to 64 pixels wide, band alignment),
/// needs at most a quarter of the limit (the rest is left to the scene, the acceleration
/// structure and the encoder). `None` when not even one aligned strip fits.
pub fn strip_rows(width: u32, user_buffers: u64, limit: u64) -> Option<u32> {
    let align = imageio::exr_strips::STRIP_ALIGNMENT;
    let budget = u128::from(limit / 4);
    let fits = |rows: u32| film_bytes(u64::from(width), u64::from(rows + 70), user_buffers) <= budget;
    let mut rows = MAX_STRIP_ROWS;
    while rows >= align {
        if fits(rows) {
            return Some(rows);
        }
        rows -= align;
    }
    None
}

/// Bytes for a message: `1.50 GiB`.
pub fn size_text(bytes: u128) -> String {
    let units = ["bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"];
    let mut v = bytes as f64;
    let mut u = 0;
    while v >= 1024.0 && u + 1 < units.len() {
        v /= 1024.0;
        u += 1;
    }
    if u == 0 {
        format!("{bytes} bytes")
    } else {
        format!("{v:.2} {}", units[u])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_in_powers_of_1024() {
        assert_eq!(parse_bytes("123"), Ok(123));
        assert_eq!(parse_bytes("64K"), Ok(64 << 10));
        assert_eq!(parse_bytes("512MiB"), Ok(512 << 20));
        assert_eq!(parse_bytes("1.5G"), Ok(3 << 29));
        assert_eq!(parse_bytes("2tb"), Ok(2 << 40));
        assert!(parse_bytes("0").is_err());
        assert!(parse_bytes("lots").is_err());
        assert!(parse_bytes("3X").is_err());
        assert!(parse_bytes("1e30G").is_err());
    }

    #[test]
    fn meminfo_is_read_in_kibibytes() {
        let dir = std::env::temp_dir().join(format!("mira-meminfo-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let f = dir.join("meminfo");
        std::fs::write(&f, "MemTotal:       24000000 kB\nMemFree:  1 kB\nMemAvailable:   22000000 kB\n").unwrap();
        assert_eq!(available_memory(&f), Some(22_000_000 * 1024));
        std::fs::write(&f, "MemTotal: 5 kB\n").unwrap();
        assert_eq!(available_memory(&f), None);
        assert_eq!(available_memory(&dir.join("none")), None);
    }

    #[test]
    fn strips_fit_a_quarter_of_the_limit() {
        // 16384 wide: 1024 rows need ≈ 5.2 GiB with their halo, so 8 GiB takes 384 rows.
        let rows = strip_rows(16384, 0, 8 << 30).unwrap();
        assert_eq!(rows % 64, 0);
        assert!(film_bytes(16384, u64::from(rows) + 70, 0) <= 2 << 30);
        assert!(film_bytes(16384, u64::from(rows) + 64 + 70, 0) > 2 << 30);
        assert_eq!(strip_rows(100, 0, 1 << 40), Some(MAX_STRIP_ROWS));
        assert_eq!(strip_rows(65536, 0, 1 << 20), None);
    }

    #[test]
    fn film_bytes_scale_with_pixels_and_user_buffers() {
        let pixel = std::mem::size_of::<render::film::Pixel>() as u128;
        assert_eq!(film_bytes(1, 1, 0), pixel + 80 + 88);
        assert_eq!(film_bytes(10, 20, 2), 200 * (pixel + 80 + 88 + 72));
        // The case does not overflow: 1.6e19 pixels.
        assert!(film_bytes(4_000_000_000, 4_000_000_000, 0) > 1u128 << 70);
        assert_eq!(size_text(3 << 29), "1.50 GiB");
        assert_eq!(size_text(1000), "1000 bytes");
    }
}
