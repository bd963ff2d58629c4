//! The classic engine's pre-passes saved to a file (`mira prepass`) and read back by every
//! part of a farm render (`mira render --part K/N --prepass FILE`), so that N parts do not
//! each recompute the photon maps and the final gather points.
//!
//! The file holds exactly what [`crate::prepare::prepare`] made — the photon maps in their
//! kd-tree order with their lookup settings, and the final gather points in the order the
//! pre-pass found them — so a render that reads it is bit for bit the render that computes
//! them. Layout, little-endian:
//!
//! ```text
//! "MIRAPREP"  u32 version  u64 scene hash  u32 n + n bytes of settings text (key=value lines)
//! u8 has photons [PhotonStats, caustic map?, global map?, fast map?]
//! u8 has fg [u64 n, n points, rays, shadow rays, eye rays]
//! u64 FNV-1a of every byte before it
//! ```
//!
//! A map is `u8 present`, then (not for the fast map) its lookup — `u32 count, f32 radius,
//! u8 filter (0 box, 1 cone, 2 gauss), f32 cone constant, 3 × f32 scale` — then
//! `u64 n, n × 12 f32` (position, power, direction, normal) and `n` split axes (`u8`). A
//! final gather point is 11 `f32`: position, normal, irradiance (RGBA), radius; its
//! gradients are estimated again when the cache is rebuilt, from the same points, so they
//! come out the same.
//!
//! A file is refused with a message saying why when it is not one, when it was written
//! by another version of the layout, when its scene hash or settings differ from the
//! render's, or when it is truncated or damaged (the checksum).

use std::time::Duration;

use glam::Vec3A;
use shader::fgcache::FgPoint;
use shader::photonmap::{Filter, Lookup, Photon, PhotonMap, PhotonMaps};

use crate::fgcache::Prepass;
use crate::photons::PhotonStats;
use crate::pipeline::Fnv;
use crate::ray::RayCounts;

/// The first bytes of every pre-pass file.
pub const MAGIC: &[u8; 8] = b"MIRAPREP";

/// Version of the layout this build writes and reads.
pub const VERSION: u32 = 1;

/// What a pre-pass file must match: the scene (a hash of its text and of every file it
/// reads) and the settings the pre-passes depend on (`key=value` lines).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PrepassKey {
    /// Hash of the scene's content.
    pub scene_hash: u64,
    /// The settings, one `key=value` per line.
    pub settings: String,
}

/// The pre-passes of a classic render, as saved.
#[derive(Debug, Default)]
pub struct SavedPrepass {
    /// The photon maps and what the photon pass did, when it ran.
    pub photons: Option<(PhotonMaps, PhotonStats)>,
    /// The final gather points (in the order the pre-pass made them), the rays it cast and
    /// its eye rays, when final gathering used a cache.
    pub fg: Option<(Vec<FgPoint>, RayCounts, u64)>,
}

/// Whether a classic render of a scene with `options` runs a pre-pass worth saving:
/// caustics, photon global illumination, or final gathering through a cache.
pub fn scene_has_prepass(options: &scene::Options) -> bool {
    let fg = &options.finalgather;
    options.caustic || options.globillum || (fg.enabled && fg.points > 0)
}

/// The pre-pass file's bytes: `key`, the photon maps in `photons` (with `stats`) and the
/// final gather pre-pass `fg`.
pub fn encode(key: &PrepassKey, photons: Option<(&PhotonMaps, &PhotonStats)>, fg: Option<&Prepass>) -> Vec<u8> {
    let mut w = Writer(Vec::new());
    w.0.extend_from_slice(MAGIC);
    w.u32(VERSION);
    w.u64(key.scene_hash);
    w.bytes(key.settings.as_bytes());
    w.u8(u8::from(photons.is_some()));
    if let Some((maps, stats)) = photons {
        for v in [stats.emitted, stats.caustic, stats.global, stats.rays, stats.memory] {
            w.u64(v);
        }
        w.f64(stats.time.as_secs_f64());
        for map in [&maps.caustic, &maps.global] {
            w.u8(u8::from(map.is_some()));
            if let Some((map, lookup)) = map {
                w.lookup(lookup);
                w.map(map);
            }
        }
        w.u8(u8::from(maps.global_fast.is_some()));
        if let Some(map) = &maps.global_fast {
            w.map(map);
        }
    }
    w.u8(u8::from(fg.is_some()));
    if let Some(p) = fg {
        let points = p.cache.points();
        w.u64(points.len() as u64);
        for q in points {
            w.vec3(q.position);
            w.vec3(q.normal);
            for c in q.irradiance.to_array() {
                w.f32(c);
            }
            w.f32(q.radius);
        }
        w.u64(p.counts.rays);
        w.u64(p.counts.shadow_rays);
        w.u64(p.eye_rays);
    }
    let sum = Fnv::of(&w.0);
    w.u64(sum);
    w.0
}

/// Reads a pre-pass file's `bytes` (named `name` in messages) for a render whose key is
/// `expected`. Every way the file can fail to fit is an error that says which.
pub fn decode(bytes: &[u8], name: &str, expected: &PrepassKey) -> Result<SavedPrepass, String> {
    if bytes.len() < MAGIC.len() || &bytes[..MAGIC.len()] != MAGIC {
        return Err(format!("{name} is not a mira pre-pass file"));
    }
    let mut r = Reader { bytes, at: MAGIC.len(), name };
    let version = r.u32()?;
    if version != VERSION {
        return Err(format!(
            "{name} was written in pre-pass layout version {version}; this mira reads version {VERSION} \
             (run mira prepass again)"
        ));
    }
    let body = bytes.len().checked_sub(8).filter(|&n| n >= r.at).ok_or_else(|| r.truncated())?;
    let mut tail = Reader { bytes: &bytes[body..], at: 0, name };
    if tail.u64()? != Fnv::of(&bytes[..body]) {
        return Err(format!("{name} is damaged or truncated (its checksum does not match)"));
    }
    let mut r = Reader { bytes: &bytes[..body], at: r.at, name };
    let scene_hash = r.u64()?;
    let settings = String::from_utf8(r.bytes()?.to_vec()).map_err(|_| format!("{name}: its settings are not text"))?;
    if scene_hash != expected.scene_hash {
        return Err(format!(
            "{name} was computed for another scene or other scene files (scene hash {scene_hash:016x}, this \
             render's {:016x}): run mira prepass again",
            expected.scene_hash
        ));
    }
    if settings != expected.settings {
        let theirs: Vec<&str> = settings.lines().collect();
        let differ: Vec<String> = expected
            .settings
            .lines()
            .filter(|l| !theirs.contains(l))
            .map(|l| {
                let key = l.split('=').next().unwrap_or(l);
                let was = theirs.iter().find(|t| t.split('=').next() == Some(key)).unwrap_or(&"(none)");
                format!("{l} here, {was} in the file")
            })
            .collect();
        return Err(format!("{name} was computed with other settings: {}", differ.join("; ")));
    }
    let mut saved = SavedPrepass::default();
    if r.u8()? != 0 {
        let mut stats = PhotonStats {
            emitted: r.u64()?,
            caustic: r.u64()?,
            global: r.u64()?,
            rays: r.u64()?,
            memory: r.u64()?,
            ..PhotonStats::default()
        };
        stats.time = Duration::try_from_secs_f64(r.f64()?).unwrap_or_default();
        let mut maps = PhotonMaps::default();
        if r.u8()? != 0 {
            maps.caustic = Some({
                let l = r.lookup()?;
                (r.map()?, l)
            });
        }
        if r.u8()? != 0 {
            maps.global = Some({
                let l = r.lookup()?;
                (r.map()?, l)
            });
        }
        if r.u8()? != 0 {
            maps.global_fast = Some(r.map()?);
        }
        saved.photons = Some((maps, stats));
    }
    if r.u8()? != 0 {
        let n = r.count(11 * 4)?;
        let mut points = Vec::with_capacity(n);
        for _ in 0..n {
            let position = r.vec3()?;
            let normal = r.vec3()?;
            let irradiance = shader::Color::new(r.f32()?, r.f32()?, r.f32()?, r.f32()?);
            let radius = r.f32()?;
            // A crafted file passes the checksum: values the pre-pass never makes are refused
            // here rather than reaching the film (NaN) or the cache's index (radii 0 or ∞).
            let sound = position.is_finite()
                && normal.is_finite()
                && irradiance.is_finite()
                && radius.is_finite()
                && radius > 0.0;
            if !sound {
                return Err(format!(
                    "{name}: final gather point {} has a value that is not finite or a radius ≤ 0",
                    points.len()
                ));
            }
            points.push(FgPoint { position, normal, irradiance, radius, gradient: [Vec3A::ZERO; 3] });
        }
        let counts = RayCounts { rays: r.u64()?, shadow_rays: r.u64()? };
        saved.fg = Some((points, counts, r.u64()?));
    }
    if r.at != r.bytes.len() {
        return Err(format!("{name} has {} bytes past its end", r.bytes.len() - r.at));
    }
    Ok(saved)
}

/// Appends little-endian values.
struct Writer(Vec<u8>);

impl Writer {
    fn u8(&mut self, v: u8) {
        self.0.push(v);
    }
    fn u32(&mut self, v: u32) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
    fn u64(&mut self, v: u64) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
    fn f32(&mut self, v: f32) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
    fn f64(&mut self, v: f64) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
    fn vec3(&mut self, v: Vec3A) {
        for c in v.to_array() {
            self.f32(c);
        }
    }
    fn bytes(&mut self, b: &[u8]) {
        self.u32(b.len() as u32);
        self.0.extend_from_slice(b);
    }
    fn lookup(&mut self, l: &Lookup) {
        self.u32(l.count);
        self.f32(l.radius);
        let (kind, k) = match l.filter {
            Filter::Box => (0, 0.0),
            Filter::Cone(k) => (1, k),
            Filter::Gauss => (2, 0.0),
        };
        self.u8(kind);
        self.f32(k);
        self.vec3(l.scale);
    }
    fn map(&mut self, map: &PhotonMap) {
        self.u64(map.len() as u64);
        for p in map.photons() {
            for v in [p.position, p.power, p.dir, p.normal] {
                self.vec3(v);
            }
        }
        self.0.extend_from_slice(map.axes());
    }
}

/// Reads little-endian values, every read checked against the end.
struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
    name: &'a str,
}

impl Reader<'_> {
    fn truncated(&self) -> String {
        format!("{} is truncated (it ends at byte {})", self.name, self.bytes.len())
    }
    fn take<const N: usize>(&mut self) -> Result<[u8; N], String> {
        let end = self.at.checked_add(N).filter(|&e| e <= self.bytes.len()).ok_or_else(|| self.truncated())?;
        let mut out = [0u8; N];
        out.copy_from_slice(&self.bytes[self.at..end]);
        self.at = end;
        Ok(out)
    }
    fn u8(&mut self) -> Result<u8, String> {
        Ok(self.take::<1>()?[0])
    }
    fn u32(&mut self) -> Result<u32, String> {
        Ok(u32::from_le_bytes(self.take()?))
    }
    fn u64(&mut self) -> Result<u64, String> {
        Ok(u64::from_le_bytes(self.take()?))
    }
    fn f32(&mut self) -> Result<f32, String> {
        Ok(f32::from_le_bytes(self.take()?))
    }
    fn f64(&mut self) -> Result<f64, String> {
        Ok(f64::from_le_bytes(self.take()?))
    }
    fn vec3(&mut self) -> Result<Vec3A, String> {
        Ok(Vec3A::new(self.f32()?, self.f32()?, self.f32()?))
    }
    /// A count of items of `size` bytes each, refused when they cannot fit in what is left
    /// (so a damaged count never allocates more than the file holds).
    fn count(&mut self, size: usize) -> Result<usize, String> {
        let n = self.u64()?;
        let left = (self.bytes.len() - self.at) as u64;
        if n.checked_mul(size as u64).is_none_or(|b| b > left) {
            return Err(self.truncated());
        }
        Ok(n as usize)
    }
    fn bytes(&mut self) -> Result<&[u8], String> {
        let n = self.u32()? as usize;
        let end = self.at.checked_add(n).filter(|&e| e <= self.bytes.len()).ok_or_else(|| self.truncated())?;
        let out = &self.bytes[self.at..end];
        self.at = end;
        Ok(out)
    }
    fn lookup(&mut self) -> Result<Lookup, String> {
        let count = self.u32()?;
        let radius = self.f32()?;
        let (kind, k) = (self.u8()?, self.f32()?);
        let filter = match kind {
            0 => Filter::Box,
            1 => Filter::Cone(k),
            2 => Filter::Gauss,
            _ => return Err(format!("{}: unknown photon filter {kind}", self.name)),
        };
        let scale = self.vec3()?;
        // The scene's options never give a lookup more than MAX_ACCURACY photons (a lookup
        // allocates room for `count`), a negative or NaN radius, a cone constant below 1
        // (its normalisation would be ≤ 0) or a NaN scale.
        let max = scene::options::MAX_ACCURACY as u32;
        if !(1..=max).contains(&count) {
            return Err(format!("{}: a photon lookup of {count} photons is outside 1 … {max}", self.name));
        }
        let cone_ok = kind != 1 || (k.is_finite() && k >= 1.0);
        if !(radius >= 0.0 && cone_ok && !scale.is_nan()) {
            return Err(format!(
                "{}: a photon lookup's radius {radius}, cone constant {k} or scale {scale} is out of its range",
                self.name
            ));
        }
        Ok(Lookup { count, radius, filter, scale })
    }
    fn map(&mut self) -> Result<PhotonMap, String> {
        let n = self.count(12 * 4 + 1)?;
        let mut photons = Vec::with_capacity(n);
        for i in 0..n {
            let photon =
                Photon { position: self.vec3()?, power: self.vec3()?, dir: self.vec3()?, normal: self.vec3()? };
            if ![photon.position, photon.power, photon.dir, photon.normal].iter().all(|v| v.is_finite()) {
                return Err(format!("{}: photon {i} of a map has a value that is not finite", self.name));
            }
            photons.push(photon);
        }
        let end = self.at.checked_add(n).filter(|&e| e <= self.bytes.len()).ok_or_else(|| self.truncated())?;
        let axes = self.bytes[self.at..end].to_vec();
        self.at = end;
        PhotonMap::from_tree(photons, axes)
            .ok_or_else(|| format!("{}: a photon map's split axes are damaged", self.name))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use shader::fgcache::FgCache;

    fn key() -> PrepassKey {
        PrepassKey { scene_hash: 0x1234, settings: "resolution=8x6\nseed=0".into() }
    }

    fn sample() -> (PhotonMaps, PhotonStats, Prepass) {
        let photons: Vec<Photon> = (0..40)
            .map(|i| {
                let f = i as f32;
                Photon {
                    position: Vec3A::new(f.sin(), (0.3 * f).cos(), 0.1 * f),
                    power: Vec3A::splat(0.01 * f),
                    dir: -Vec3A::Z,
                    normal: Vec3A::Z,
                }
            })
            .collect();
        let lookup = Lookup { count: 7, radius: 0.5, filter: Filter::Cone(1.1), scale: Vec3A::new(1.0, 2.0, 3.0) };
        let maps = PhotonMaps {
            caustic: Some((PhotonMap::new(photons.clone()), lookup)),
            global: Some((PhotonMap::new(photons[..20].to_vec()), Lookup { filter: Filter::Box, ..lookup })),
            global_fast: Some(PhotonMap::new(photons[..5].to_vec())),
        };
        let stats =
            PhotonStats { emitted: 100, caustic: 40, global: 20, rays: 300, memory: 2000, ..Default::default() };
        let points: Vec<FgPoint> = (0..30)
            .map(|i| {
                let f = i as f32 * 0.1;
                FgPoint::new(Vec3A::new(f, 0.0, f * f), Vec3A::Y, shader::Color::new(f, 1.0, 0.5, 1.0), 1.0, 0.05, 0.5)
            })
            .collect();
        let fg = Prepass {
            cache: FgCache::new(points, Some(4)),
            counts: RayCounts { rays: 9, shadow_rays: 3 },
            eye_rays: 30,
        };
        (maps, stats, fg)
    }

    /// What is written is read back the same, photon for photon and point for point; the
    /// cache rebuilt from the read points has the same gradients.
    #[test]
    fn a_saved_prepass_reads_back_exactly() {
        let (maps, stats, fg) = sample();
        let bytes = encode(&key(), Some((&maps, &stats)), Some(&fg));
        let saved = decode(&bytes, "f", &key()).unwrap();
        let (m, s) = saved.photons.unwrap();
        assert_eq!(s, stats);
        for (a, b) in [(&maps.caustic, &m.caustic), (&maps.global, &m.global)] {
            let ((a, la), (b, lb)) = (a.as_ref().unwrap(), b.as_ref().unwrap());
            assert_eq!(la, lb);
            assert_eq!(a.photons(), b.photons());
            assert_eq!(a.axes(), b.axes());
        }
        assert_eq!(maps.global_fast.unwrap().photons(), m.global_fast.unwrap().photons());
        let (points, counts, eye) = saved.fg.unwrap();
        assert_eq!((counts.rays, counts.shadow_rays, eye), (fg.counts.rays, fg.counts.shadow_rays, fg.eye_rays));
        let cache = FgCache::new(points, Some(4));
        assert_eq!(cache.points(), fg.cache.points(), "same points and re-estimated gradients");
    }

    /// Another scene, other settings, another layout version, a damaged or truncated file:
    /// each refused with a message that says which.
    #[test]
    fn a_mismatched_or_damaged_file_is_refused() {
        let (maps, stats, fg) = sample();
        let bytes = encode(&key(), Some((&maps, &stats)), Some(&fg));
        let other_scene = PrepassKey { scene_hash: 0x999, ..key() };
        assert!(decode(&bytes, "f", &other_scene).unwrap_err().contains("another scene"));
        let other_settings = PrepassKey { settings: "resolution=8x6\nseed=7".into(), ..key() };
        let e = decode(&bytes, "f", &other_settings).unwrap_err();
        assert!(e.contains("other settings: seed=7 here, seed=0 in the file"), "{e}");
        let mut v2 = bytes.clone();
        v2[8] = 2;
        assert!(decode(&v2, "f", &key()).unwrap_err().contains("layout version 2"));
        let mut flipped = bytes.clone();
        let mid = bytes.len() / 2;
        flipped[mid] ^= 1;
        assert!(decode(&flipped, "f", &key()).unwrap_err().contains("damaged or truncated"));
        assert!(decode(&bytes[..bytes.len() - 3], "f", &key()).is_err());
        assert!(decode(b"P6 1 1", "f", &key()).unwrap_err().contains("not a mira pre-pass file"));
        // No cut of the file makes the reader panic.
        for n in 0..bytes.len() {
            assert!(decode(&bytes[..n], "f", &key()).is_err());
        }
    }

    /// `bytes` with its checksum made right again: what a crafted (not a damaged) file is.
    fn reseal(mut bytes: Vec<u8>) -> Vec<u8> {
        let body = bytes.len() - 8;
        let sum = Fnv::of(&bytes[..body]);
        bytes[body..].copy_from_slice(&sum.to_le_bytes());
        bytes
    }

    /// Where the values after the settings text begin.
    fn after_settings() -> usize {
        MAGIC.len() + 4 + 8 + 4 + key().settings.len()
    }

    /// Crafted files whose checksum is right but whose values the pre-passes never make are
    /// refused with a message, never read into an allocation the size of a count (a photon
    /// lookup of 2^32 − 1 photons allocated a 32 GiB heap per lookup before) nor an index
    /// the size of a radius, nor NaN onto the film.
    #[test]
    fn a_crafted_file_with_a_good_checksum_is_refused() {
        let (maps, stats, fg) = sample();
        let bytes = encode(&key(), Some((&maps, &stats)), Some(&fg));
        // The caustic lookup: has photons, 5 u64 + f64 of stats, caustic present, count.
        let count_at = after_settings() + 1 + 48 + 1;
        assert_eq!(&bytes[count_at..count_at + 4], &7u32.to_le_bytes());
        for (count, word) in [(u32::MAX, "4294967295"), (0, "0")] {
            let mut b = bytes.clone();
            b[count_at..count_at + 4].copy_from_slice(&count.to_le_bytes());
            let e = decode(&reseal(b), "f", &key()).unwrap_err();
            assert!(e.contains(&format!("a photon lookup of {word} photons is outside 1 … 1048576")), "{e}");
        }
        // Its radius NaN, then its cone constant 0.5 (the filter's norm would be ≤ 0).
        for (at, v) in [(count_at + 4, f32::NAN), (count_at + 9, 0.5)] {
            let mut b = bytes.clone();
            b[at..at + 4].copy_from_slice(&v.to_le_bytes());
            let e = decode(&reseal(b), "f", &key()).unwrap_err();
            assert!(e.contains("a photon lookup's radius"), "{e}");
        }
        // The first caustic photon's power NaN.
        let photon_at = count_at + 4 + 4 + 1 + 4 + 12 + 8;
        let mut b = bytes.clone();
        b[photon_at + 12..photon_at + 16].copy_from_slice(&f32::NAN.to_le_bytes());
        let e = decode(&reseal(b), "f", &key()).unwrap_err();
        assert!(e.contains("photon 0 of a map has a value that is not finite"), "{e}");
        // Final gather points alone: a huge count, a NaN irradiance, radii 0 and ∞.
        let bytes = encode(&key(), None, Some(&fg));
        let n_at = after_settings() + 2;
        assert_eq!(&bytes[n_at..n_at + 8], &30u64.to_le_bytes());
        let mut b = bytes.clone();
        b[n_at..n_at + 8].copy_from_slice(&(u64::MAX / 4).to_le_bytes());
        assert!(decode(&reseal(b), "f", &key()).unwrap_err().contains("is truncated"));
        let point_at = n_at + 8 + 44;
        for (offset, v) in [(24, f32::NAN), (40, 0.0), (40, f32::INFINITY)] {
            let mut b = bytes.clone();
            b[point_at + offset..point_at + offset + 4].copy_from_slice(&v.to_le_bytes());
            let e = decode(&reseal(b), "f", &key()).unwrap_err();
            assert!(e.contains("final gather point 1 has a value that is not finite or a radius ≤ 0"), "{e}");
        }
        // Untouched, both files still read.
        assert!(decode(&bytes, "f", &key()).is_ok());
    }

    /// A file with neither pre-pass (nothing to save) still round-trips.
    #[test]
    fn an_empty_prepass_round_trips() {
        let bytes = encode(&key(), None, None);
        let saved = decode(&bytes, "f", &key()).unwrap();
        assert!(saved.photons.is_none() && saved.fg.is_none());
    }
}
