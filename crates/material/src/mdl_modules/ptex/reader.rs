//! Reads a Ptex file ([`read`]) into a [`Ptex`]: the file format as the Ptex project
//! documents it (version 1, little-endian).
//!
//! Layout: a 64-byte header (magic `Ptex`, version, mesh type, data type, alpha channel,
//! channel count, level count, face count, the sizes of the sections that follow), an
//! extension header (its size in the header: border modes, the large-meta-data and edit
//! sections), then the sections in order: face infos (zlib; per face its resolution as
//! log2 of u and v, adjacency, flags: 1 = constant, 8 = sub-face), the constant values (zlib; one texel
//! per face), the level infos (per level its data size, its header's zlib size, its face
//! count), the levels' data, the meta data, eight bytes, the large meta data, and edits.
//! Level 0 (the highest resolution) is a zlib block of one 32-bit word per face (bits
//! 0–29 the size of the face's data, 30–31 its encoding), then the faces' data in face
//! order. Reduced level k (after level 0, in turn) is laid out alike for the first n
//! faces (n in its level info) of Ptex's reduction order (faces by their smaller log2
//! side, largest first, ties in face order; a face flagged constant counts as 1), each of
//! 2^(u − k) × 2^(v − k) texels, premultiplied by alpha where the file has an alpha
//! channel (mira divides it out); a face with an edit keeps none of them. Adjacency per
//! face edge: the adjacent face (−1: none) and its edge (2 bits), checked against the
//! face count and edge count. A face's data is: constant (one texel), zipped (zlib of the face's texels, each
//! channel's plane in turn, rows from v = 0), diff-zipped (the same, 8- and 16-bit values
//! stored as differences from the one before, across the whole block) or tiled (the tile
//! resolution, the size of a zlib block of one word per tile as above, then the tiles
//! row by row, each constant, zipped or diff-zipped). An edit (after the sections)
//! replaces a face's info, constant value and data.
//!
//! Hostile files: every size and offset is checked against the file before it is used,
//! face counts, channel counts and resolutions are bounded ([`MAX_FACES`],
//! [`MAX_CHANNELS`], [`MAX_LOG2`], [`MAX_VALUES`]) before anything is allocated, and a
//! zlib block must expand to exactly the size the file says. What is wrong is an error
//! naming the byte offset of the part it was found in; nothing panics.

use super::{Adjacency, FaceTexels, MeshType, Ptex};

/// Most faces a file may have.
pub const MAX_FACES: u64 = 1 << 24;
/// Most channels per texel.
pub const MAX_CHANNELS: u64 = 64;
/// Largest log2 of a face's resolution along u or v (Ptex's own limit is below it).
pub const MAX_LOG2: i8 = 15;
/// Most `f32` values all faces together may hold (1 GiB).
pub const MAX_VALUES: u64 = 1 << 28;

/// What is wrong with a Ptex file, and where.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ReadError {
    /// Byte offset from the start of the file of the part that is wrong.
    pub offset: u64,
    /// What is wrong.
    pub message: String,
}

impl std::fmt::Display for ReadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "byte {}: {}", self.offset, self.message)
    }
}

fn fail<T>(offset: u64, message: impl Into<String>) -> Result<T, ReadError> {
    Err(ReadError { offset, message: message.into() })
}

/// The element type of a file's texels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum DataType {
    U8,
    U16,
    Half,
    F32,
}

impl DataType {
    fn size(self) -> usize {
        match self {
            DataType::U8 => 1,
            DataType::U16 | DataType::Half => 2,
            DataType::F32 => 4,
        }
    }

    /// The value of the element in `b` (its size in bytes, little-endian).
    fn value(self, b: &[u8]) -> f32 {
        match self {
            DataType::U8 => f32::from(b[0]) / 255.0,
            DataType::U16 => f32::from(u16::from_le_bytes([b[0], b[1]])) / 65535.0,
            DataType::Half => half::f16::from_le_bytes([b[0], b[1]]).to_f32(),
            DataType::F32 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]),
        }
    }
}

/// The file's bytes, read with bounds checks.
struct File<'a>(&'a [u8]);

impl<'a> File<'a> {
    /// `len` bytes at `at`; an error naming `what` when the file is shorter.
    fn slice(&self, at: u64, len: u64, what: &str) -> Result<&'a [u8], ReadError> {
        let end = at.checked_add(len).filter(|&e| e <= self.0.len() as u64);
        match end {
            Some(end) => Ok(&self.0[at as usize..end as usize]),
            None => {
                fail(at, format!("truncated: {what} needs {len} bytes here, the file ends at byte {}", self.0.len()))
            }
        }
    }

    /// The zlib block of `zip_len` bytes at `at`, which must expand to `len` bytes.
    fn inflate(&self, at: u64, zip_len: u64, len: usize, what: &str) -> Result<Vec<u8>, ReadError> {
        let zipped = self.slice(at, zip_len, what)?;
        // zlib expands at most about 1032 times: a larger claim is refused before allocating.
        if len as u64 > zip_len.saturating_mul(1032).saturating_add(64) {
            return fail(at, format!("{what}: {zip_len} bytes of zlib data cannot expand to {len} bytes"));
        }
        let mut out = vec![0u8; len];
        if len == 0 && zip_len == 0 {
            return Ok(out);
        }
        let mut z = flate2::Decompress::new(true);
        let status = z.decompress(zipped, &mut out, flate2::FlushDecompress::Finish);
        match status {
            Ok(flate2::Status::StreamEnd) if z.total_out() == len as u64 => Ok(out),
            Ok(flate2::Status::StreamEnd) => {
                fail(at, format!("{what}: the zlib block expands to {} bytes, not {len}", z.total_out()))
            }
            Ok(_) => fail(at, format!("{what}: the zlib block expands to more than {len} bytes or is cut short")),
            Err(e) => fail(at, format!("{what}: corrupt zlib data ({e})")),
        }
    }
}

/// The fields of the header mira uses.
struct Header {
    mesh: MeshType,
    data: DataType,
    alpha: i32,
    channels: usize,
    levels: u64,
    faces: u64,
    ext_size: u64,
    face_info_size: u64,
    const_size: u64,
    level_info_size: u64,
    level_data_size: u64,
    meta_zip_size: u64,
}

fn header(f: &File) -> Result<Header, ReadError> {
    let h = f.slice(0, 64, "the header")?;
    let u32_at = |at: usize| u64::from(u32::from_le_bytes([h[at], h[at + 1], h[at + 2], h[at + 3]]));
    let u16_at = |at: usize| u64::from(u16::from_le_bytes([h[at], h[at + 1]]));
    if &h[0..4] != b"Ptex" {
        return fail(0, format!("not a Ptex file (it starts {:?}, not \"Ptex\")", String::from_utf8_lossy(&h[0..4])));
    }
    if u32_at(4) != 1 {
        return fail(4, format!("Ptex format version {}, mira reads version 1", u32_at(4)));
    }
    let mesh = match u32_at(8) {
        0 => MeshType::Triangle,
        1 => MeshType::Quad,
        m => return fail(8, format!("unknown mesh type {m} (0 triangles, 1 quads)")),
    };
    let data = match u32_at(12) {
        0 => DataType::U8,
        1 => DataType::U16,
        2 => DataType::Half,
        3 => DataType::F32,
        d => return fail(12, format!("unknown data type {d} (0 uint8, 1 uint16, 2 half, 3 float)")),
    };
    let channels = u16_at(20);
    if channels == 0 || channels > MAX_CHANNELS {
        return fail(20, format!("{channels} channels (mira reads 1 to {MAX_CHANNELS})"));
    }
    let faces = u32_at(24);
    if faces > MAX_FACES {
        return fail(24, format!("{faces} faces, more than mira reads ({MAX_FACES})"));
    }
    Ok(Header {
        mesh,
        data,
        alpha: u32_at(16) as u32 as i32,
        channels: channels as usize,
        levels: u16_at(22),
        faces,
        ext_size: u32_at(28),
        face_info_size: u32_at(32),
        const_size: u32_at(36),
        level_info_size: u32_at(40),
        level_data_size: u64::from_le_bytes(h[48..56].try_into().unwrap_or([0; 8])),
        meta_zip_size: u32_at(56),
    })
}

/// A face's info: its resolution (log2 along u and v), adjacency and flags.
#[derive(Clone, Copy)]
struct FaceInfo {
    ulog2: i8,
    vlog2: i8,
    adjedges: u8,
    flags: u8,
    adjfaces: [i32; 4],
}

impl FaceInfo {
    fn parse(b: &[u8]) -> FaceInfo {
        let adj = |k: usize| i32::from_le_bytes([b[4 + 4 * k], b[5 + 4 * k], b[6 + 4 * k], b[7 + 4 * k]]);
        FaceInfo {
            ulog2: b[0] as i8,
            vlog2: b[1] as i8,
            adjedges: b[2],
            flags: b[3],
            adjfaces: [adj(0), adj(1), adj(2), adj(3)],
        }
    }

    /// The resolution Ptex sorts faces by for its reduced levels: the smaller log2 side, a
    /// face flagged constant counting as 1.
    fn min_log2(&self) -> i8 {
        if self.flags & 1 != 0 {
            1
        } else {
            self.ulog2.min(self.vlog2)
        }
    }

    fn constant(&self) -> bool {
        self.flags & 1 != 0 || (self.ulog2 == 0 && self.vlog2 == 0)
    }
}

/// Where a face's data is: its offset and its data header word.
#[derive(Clone, Copy)]
struct Block {
    at: u64,
    word: u32,
}

impl Block {
    fn size(&self) -> u64 {
        u64::from(self.word & 0x3fff_ffff)
    }

    fn encoding(&self) -> u32 {
        self.word >> 30
    }
}

/// Sums section sizes, failing on overflow (at byte 0: the header's sizes are wrong).
fn add(a: u64, b: u64) -> Result<u64, ReadError> {
    a.checked_add(b).map_or_else(|| fail(0, "the header's section sizes overflow"), Ok)
}

/// Reads the Ptex file `bytes`: the texture, and how many texel values were NaN or
/// infinite (read as 0).
pub fn read(bytes: &[u8]) -> Result<(Ptex, usize), ReadError> {
    let f = File(bytes);
    let h = header(&f)?;
    let pixel = h.channels * h.data.size();
    let nfaces = h.faces as usize;
    // The extension header (zeros past its stored size).
    let mut ext = [0u8; 40];
    let stored = f.slice(64, h.ext_size.min(40), "the extension header")?;
    ext[..stored.len()].copy_from_slice(stored);
    let ext_u64 = |at: usize| u64::from_le_bytes(ext[at..at + 8].try_into().unwrap_or([0; 8]));
    let (lmd_header_zip, lmd_data) = (u64::from(u32::from_le_bytes([ext[8], ext[9], ext[10], ext[11]])), ext_u64(16));
    let (edit_size, edit_pos) = (ext_u64(24), ext_u64(32));

    let face_info_at = add(64, h.ext_size)?;
    let const_at = add(face_info_at, h.face_info_size)?;
    let level_info_at = add(const_at, h.const_size)?;
    let level_data_at = add(level_info_at, h.level_info_size)?;
    let after_levels = add(level_data_at, h.level_data_size)?;
    let after_meta = add(add(add(add(after_levels, h.meta_zip_size)?, 8)?, lmd_header_zip)?, lmd_data)?;

    let info_bytes = f.inflate(face_info_at, h.face_info_size, 20 * nfaces, "the face infos")?;
    let mut infos: Vec<FaceInfo> = info_bytes.chunks_exact(20).map(FaceInfo::parse).collect();
    let mut constants = f.inflate(const_at, h.const_size, pixel * nfaces, "the constant face values")?;

    // Level 0's data headers and where each face's data starts.
    let mut blocks: Vec<Option<Block>> = vec![None; nfaces];
    if h.levels > 0 {
        if h.level_info_size < 16 * h.levels {
            return fail(
                40,
                format!("level infos of {} bytes for {} levels (16 bytes each)", h.level_info_size, h.levels),
            );
        }
        let l0 = f.slice(level_info_at, 16, "the level infos")?;
        let header_zip = u64::from(u32::from_le_bytes([l0[8], l0[9], l0[10], l0[11]]));
        let level_faces = u64::from(u32::from_le_bytes([l0[12], l0[13], l0[14], l0[15]]));
        if level_faces != h.faces {
            return fail(level_info_at, format!("level 0 has {level_faces} faces, the file {}", h.faces));
        }
        let words = f.inflate(level_data_at, header_zip, 4 * nfaces, "level 0's face data headers")?;
        let mut at = add(level_data_at, header_zip)?;
        for (block, w) in blocks.iter_mut().zip(words.chunks_exact(4)) {
            let word = u32::from_le_bytes([w[0], w[1], w[2], w[3]]);
            *block = Some(Block { at, word });
            at = add(at, u64::from(word & 0x3fff_ffff))?;
        }
    }

    let reduced = reduced_levels(&f, &h, &infos, level_info_at, level_data_at)?;
    let mut reduced = reduced;

    // Edits: each replaces a face's info, constant value and (unless constant) data.
    let mut pos = edit_pos.max(after_meta);
    let end = if edit_pos > 0 { add(pos, edit_size)? } else { bytes.len() as u64 };
    while pos < end && pos.saturating_add(5) <= bytes.len() as u64 {
        let head = f.slice(pos, 5, "an edit's header")?;
        let size = u64::from(u32::from_le_bytes([head[1], head[2], head[3], head[4]]));
        if size == 0 {
            break;
        }
        let body = add(pos, 5)?;
        if head[0] == 0 {
            let e = f.slice(body, 28 + pixel as u64, "a face edit")?;
            let face = u32::from_le_bytes([e[0], e[1], e[2], e[3]]) as usize;
            if face >= nfaces {
                return fail(body, format!("an edit of face {face}, the file has {nfaces}"));
            }
            infos[face] = FaceInfo::parse(&e[4..24]);
            constants[face * pixel..(face + 1) * pixel].copy_from_slice(&e[28..]);
            let word = u32::from_le_bytes([e[24], e[25], e[26], e[27]]);
            blocks[face] = Some(Block { at: body + 28 + pixel as u64, word });
            // The file's reductions are of the face before the edit.
            reduced[face].clear();
        }
        pos = add(body, size)?;
    }

    // Resolutions, checked and counted before any texel is stored.
    let mut total: u64 = 0;
    for (id, info) in infos.iter().enumerate() {
        let ok = |l: i8| (0..=MAX_LOG2).contains(&l);
        if !ok(info.ulog2) || !ok(info.vlog2) {
            return fail(
                face_info_at,
                format!(
                    "face {id}: resolution 2^{} × 2^{} (mira reads up to 2^{MAX_LOG2} texels a side)",
                    info.ulog2, info.vlog2
                ),
            );
        }
        if h.mesh == MeshType::Triangle && info.ulog2 != info.vlog2 {
            return fail(
                face_info_at,
                format!("triangle face {id}: resolution 2^{} × 2^{} is not square", info.ulog2, info.vlog2),
            );
        }
        let edges = if h.mesh == MeshType::Triangle { 3 } else { 4 };
        for edge in 0..edges {
            let (adjacent, adjacent_edge) = (info.adjfaces[edge], (info.adjedges >> (2 * edge)) & 3);
            if adjacent < -1 || i64::from(adjacent) >= nfaces as i64 || (adjacent >= 0 && adjacent_edge >= edges as u8)
            {
                return fail(
                    face_info_at,
                    format!(
                        "face {id}: edge {edge} adjoins face {adjacent}'s edge {adjacent_edge} (the file has \
                         {nfaces} faces of {edges} edges; -1 for none)"
                    ),
                );
            }
        }
        let texels = if info.constant() { 1 } else { 1u64 << (info.ulog2 + info.vlog2) };
        // Reduced levels: each a quarter of the one before; the average.
        let reductions = (1..=reduced[id].len() as i8).map(|k| 1u64 << (info.ulog2 + info.vlog2 - 2 * k)).sum::<u64>();
        total = total.saturating_add((texels + reductions + 1) * h.channels as u64);
        if total > MAX_VALUES {
            return fail(
                face_info_at,
                format!("the faces up to {id} hold more than {MAX_VALUES} texel values, more than mira reads"),
            );
        }
    }

    let mut out = Ptex {
        mesh: h.mesh,
        channels: h.channels,
        alpha: usize::try_from(h.alpha).ok().filter(|&a| a < h.channels),
        faces: Vec::with_capacity(nfaces),
        reductions: Vec::with_capacity(nfaces),
        adjacency: infos.iter().map(|i| Adjacency { faces: i.adjfaces, edges: i.adjedges }).collect(),
        subfaces: if h.mesh == MeshType::Quad && infos.iter().any(|i| i.flags & 8 != 0) {
            infos.iter().map(|i| i.flags & 8 != 0).collect()
        } else {
            Vec::new()
        },
        texels: Vec::new(),
    };
    let mut non_finite = 0usize;
    let reader = Texels { file: &f, data: h.data, channels: h.channels };
    for (id, info) in infos.iter().enumerate() {
        let start = out.texels.len();
        if info.constant() {
            non_finite += reader.push_constant(&constants[id * pixel..(id + 1) * pixel], 1, &mut out.texels);
            out.faces.push(FaceTexels { start, ulog2: 0, vlog2: 0 });
            continue;
        }
        let Some(block) = blocks[id] else {
            return fail(22, format!("face {id} is not constant, but the file has no levels"));
        };
        let (ulog2, vlog2) = (info.ulog2 as u8, info.vlog2 as u8);
        non_finite += reader.face(block, ulog2, vlog2, id, &mut out.texels)?;
        out.faces.push(FaceTexels { start, ulog2, vlog2 });
    }
    // Each face's reduced levels, then its average (the constant value the file keeps for
    // every face) unless the last level is already one texel.
    for (id, info) in infos.iter().enumerate() {
        let mut levels = Vec::new();
        if !info.constant() {
            for (k, block) in reduced[id].iter().enumerate() {
                let (ulog2, vlog2) = (info.ulog2 as u8 - (k as u8 + 1), info.vlog2 as u8 - (k as u8 + 1));
                let start = out.texels.len();
                non_finite += reader.face(*block, ulog2, vlog2, id, &mut out.texels)?;
                if let Some(alpha) = out.alpha {
                    unpremultiply(&mut out.texels[start..], h.channels, alpha);
                }
                levels.push(FaceTexels { start, ulog2, vlog2 });
            }
            if levels.last().is_none_or(|l: &FaceTexels| l.ulog2 + l.vlog2 > 0) {
                let start = out.texels.len();
                non_finite += reader.push_constant(&constants[id * pixel..(id + 1) * pixel], 1, &mut out.texels);
                levels.push(FaceTexels { start, ulog2: 0, vlog2: 0 });
            }
        }
        out.reductions.push(levels);
    }
    Ok((out, non_finite))
}

/// Divides the colour channels of `texels` (`channels` a texel) by their alpha (channel
/// `alpha`): Ptex stores reduced levels premultiplied by alpha, level 0 and the averages
/// not. The colour channels are those before the alpha channel, or all after it when it
/// is the first (Ptex's convention); a texel of alpha 0 is left as it is.
fn unpremultiply(texels: &mut [f32], channels: usize, alpha: usize) {
    let colour = if alpha == 0 { 1..channels } else { 0..alpha };
    for texel in texels.chunks_exact_mut(channels) {
        let a = texel[alpha];
        if a != 0.0 {
            for c in colour.clone() {
                texel[c] /= a;
            }
        }
    }
}

/// Ptex's reduction order: the face ids sorted by their smaller log2 side, largest first,
/// ties in face order (a reduced level holds the first faces of this order).
fn reduction_order(infos: &[FaceInfo]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..infos.len()).collect();
    order.sort_by_key(|&id| std::cmp::Reverse(infos[id].min_log2()));
    order
}

/// Where each face's reduced levels 1, 2, … are (level `k` of 2^(u − k) × 2^(v − k)
/// texels): level `k`'s info gives its size and face count `n`, its data is a zlib block
/// of `n` data headers then the data of the first `n` faces in [`reduction_order`].
/// Levels follow level 0 in the level data. Constant faces keep none.
fn reduced_levels(
    f: &File,
    h: &Header,
    infos: &[FaceInfo],
    level_info_at: u64,
    level_data_at: u64,
) -> Result<Vec<Vec<Block>>, ReadError> {
    let mut reduced: Vec<Vec<Block>> = vec![Vec::new(); infos.len()];
    if h.levels < 2 {
        return Ok(reduced);
    }
    let order = reduction_order(infos);
    let mut level_at = level_data_at;
    for level in 0..h.levels {
        let info_at = level_info_at + 16 * level;
        let l = f.slice(info_at, 16, "the level infos")?;
        let size = u64::from_le_bytes(l[0..8].try_into().unwrap_or([0; 8]));
        let header_zip = u64::from(u32::from_le_bytes([l[8], l[9], l[10], l[11]]));
        let count = u64::from(u32::from_le_bytes([l[12], l[13], l[14], l[15]]));
        if level > 0 {
            if count > h.faces {
                return fail(info_at, format!("level {level} has {count} faces, the file {}", h.faces));
            }
            let what = format!("level {level}'s face data headers");
            let words = f.inflate(level_at, header_zip, 4 * count as usize, &what)?;
            let mut at = add(level_at, header_zip)?;
            for (word, &id) in words.chunks_exact(4).zip(&order) {
                let block = Block { at, word: u32::from_le_bytes([word[0], word[1], word[2], word[3]]) };
                at = add(at, block.size())?;
                let info = infos[id];
                if info.constant() || reduced[id].len() + 1 != level as usize {
                    continue;
                }
                if i64::from(info.ulog2.min(info.vlog2)) < level as i64 {
                    return fail(
                        info_at,
                        format!(
                            "level {level} reduces face {id} of 2^{} × 2^{} below one texel",
                            info.ulog2, info.vlog2
                        ),
                    );
                }
                reduced[id].push(block);
            }
            if at > add(level_at, size)? {
                return fail(level_at, format!("level {level}'s faces need more than its {size} bytes"));
            }
        }
        level_at = add(level_at, size)?;
    }
    Ok(reduced)
}

/// Decodes faces' data into `f32` texels.
struct Texels<'a, 'b> {
    file: &'b File<'a>,
    data: DataType,
    channels: usize,
}

impl Texels<'_, '_> {
    /// Appends `count` copies of the texel in `pixel` (interleaved channels); the count of
    /// non-finite values (stored as 0).
    fn push_constant(&self, pixel: &[u8], count: usize, out: &mut Vec<f32>) -> usize {
        let values: Vec<f32> = pixel.chunks_exact(self.data.size()).map(|b| self.data.value(b)).collect();
        let bad = values.iter().filter(|v| !v.is_finite()).count();
        for _ in 0..count {
            out.extend(values.iter().map(|v| if v.is_finite() { *v } else { 0.0 }));
        }
        bad * count
    }

    /// Appends face `id`'s texels (2^`ulog2` × 2^`vlog2`) from `block`; the count of
    /// non-finite values.
    fn face(&self, block: Block, ulog2: u8, vlog2: u8, id: usize, out: &mut Vec<f32>) -> Result<usize, ReadError> {
        let (w, h) = (1usize << ulog2, 1usize << vlog2);
        if block.encoding() != 3 {
            return self.image(block, w, h, id, out);
        }
        // Tiled: the tile resolution, the zipped tile headers, the tiles.
        let head = self.file.slice(block.at, 6, "a tiled face's header")?;
        let (tu, tv) = (head[0] as i8, head[1] as i8);
        if !(0..=ulog2 as i8).contains(&tu) || !(0..=vlog2 as i8).contains(&tv) {
            return fail(block.at, format!("face {id}: tiles of 2^{tu} × 2^{tv} in a face of 2^{ulog2} × 2^{vlog2}"));
        }
        let (tw, th) = (1usize << tu, 1usize << tv);
        let (across, down) = (w / tw, h / th);
        let zip = u64::from(u32::from_le_bytes([head[2], head[3], head[4], head[5]]));
        let words = self.file.inflate(block.at + 6, zip, 4 * across * down, "a tiled face's tile headers")?;
        let mut face = vec![0.0f32; w * h * self.channels];
        let mut at = block.at + 6 + zip;
        let mut bad = 0;
        for (t, word) in words.chunks_exact(4).enumerate() {
            let tile = Block { at, word: u32::from_le_bytes([word[0], word[1], word[2], word[3]]) };
            at = add(at, tile.size())?;
            if tile.encoding() == 3 {
                return fail(tile.at, format!("face {id}: a tiled tile"));
            }
            let mut texels = Vec::with_capacity(tw * th * self.channels);
            bad += self.image(tile, tw, th, id, &mut texels)?;
            let (x0, y0) = ((t % across) * tw, (t / across) * th);
            for (row, values) in texels.chunks_exact(tw * self.channels).enumerate() {
                let start = ((y0 + row) * w + x0) * self.channels;
                face[start..start + values.len()].copy_from_slice(values);
            }
        }
        out.extend_from_slice(&face);
        Ok(bad)
    }

    /// Appends the `w` × `h` texels of a constant, zipped or diff-zipped `block`.
    fn image(&self, block: Block, w: usize, h: usize, id: usize, out: &mut Vec<f32>) -> Result<usize, ReadError> {
        let size = self.data.size();
        let pixel = self.channels * size;
        match block.encoding() {
            0 => {
                let texel = self.file.slice(block.at, pixel as u64, "a constant face's texel")?;
                Ok(self.push_constant(texel, w * h, out))
            }
            1 | 2 => {
                let what = format!("face {id}'s texels");
                let mut planes = self.file.inflate(block.at, block.size(), pixel * w * h, &what)?;
                if block.encoding() == 2 {
                    undo_differences(&mut planes, self.data);
                }
                // Planar (each channel's w × h values in turn) to interleaved.
                let plane = w * h * size;
                let mut bad = 0;
                out.reserve(w * h * self.channels);
                for k in 0..w * h {
                    for c in 0..self.channels {
                        let at = c * plane + k * size;
                        let v = self.data.value(&planes[at..at + size]);
                        bad += usize::from(!v.is_finite());
                        out.push(if v.is_finite() { v } else { 0.0 });
                    }
                }
                Ok(bad)
            }
            e => fail(block.at, format!("face {id}: data encoding {e} where a tile or face's texels are")),
        }
    }
}

/// Undoes the difference encoding of 8- and 16-bit values (each stored as the difference
/// from the one before, wrapping; the others are stored as they are).
fn undo_differences(bytes: &mut [u8], data: DataType) {
    match data {
        DataType::U8 => {
            let mut prev = 0u8;
            for b in bytes.iter_mut() {
                *b = b.wrapping_add(prev);
                prev = *b;
            }
        }
        DataType::U16 => {
            let mut prev = 0u16;
            for pair in bytes.chunks_exact_mut(2) {
                let v = u16::from_le_bytes([pair[0], pair[1]]).wrapping_add(prev);
                pair.copy_from_slice(&v.to_le_bytes());
                prev = v;
            }
        }
        DataType::Half | DataType::F32 => {}
    }
}
