//! The first stages of a render: **load** a `.mi` file into a scene ([`load`]), apply the
//! settings that change the scene ([`set_resolution`], [`choose_engine`]) and **build the
//! world** the engines trace ([`build_world`]). The stages after these are
//! [`crate::prepare::prepare`], [`crate::render::render_prepared`] and the [`crate::film`];
//! the crate's front page lists them all.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use scene::Scene;
use shader::texture::SearchPath;
use shader::{Shading, ShadingOptions};

use crate::engine::EngineKind;
use crate::world::World;

/// What the load stage read: the parsed file (its sources, for messages), the scene at the
/// chosen `render` statement (`None` when the file has errors) and every message so far.
pub struct Loaded {
    /// The parsed file and everything it included.
    pub parsed: mi::Parsed,
    /// The scene, when the file and the scene layer found no error.
    pub scene: Option<Scene>,
    /// The reader's and the scene layer's messages, in order.
    pub diagnostics: Vec<mi::Diagnostic>,
    /// [`Loaded::content_hash`], taken while the text was at hand (`None` when the load
    /// was asked for no hash, [`load_unhashed`]).
    content_hash: Option<u64>,
    /// How long its parts took.
    pub times: LoadTimes,
}

/// Wall-clock times of the load stage's parts (for `--stats`).
#[derive(Clone, Copy, Debug, Default)]
pub struct LoadTimes {
    /// Reading and parsing the file and its includes (the content hash runs beside it).
    pub parse: Duration,
    /// Building the scene from the syntax tree.
    pub scene: Duration,
}

impl Loaded {
    /// Whether any message is an error.
    pub fn has_errors(&self) -> bool {
        self.diagnostics.iter().any(mi::Diagnostic::is_error)
    }

    /// A hash of every file the scene was read from (the main file and its `$include`s,
    /// in reading order): equal hashes mean the same scene text. FNV-1a, 64 bits: it tells
    /// files apart, it is no protection against a crafted collision. `None` when the file
    /// was loaded without it ([`load_unhashed`]).
    pub fn content_hash(&self) -> Option<u64> {
        self.content_hash
    }
}

/// The hash of every file of `sources` after the first `skip`, in reading order, going on
/// from `h` (see [`Loaded::content_hash`]).
fn sources_hash(mut h: Fnv, sources: &mi::SourceMap, skip: usize) -> u64 {
    for (_, file) in sources.files().skip(skip) {
        file_hash(&mut h, &file.bytes);
    }
    h.finish()
}

/// Adds one file (its length, then its bytes) to a content hash.
fn file_hash(h: &mut Fnv, bytes: &[u8]) {
    h.write(&(bytes.len() as u64).to_le_bytes());
    h.write(bytes);
}

/// Reads and parses the file at `path`; with `hash`, the main file's part of the content
/// hash (FNV is serial, about 0.3 s for a 190 MB file) is computed on a second thread while
/// it parses. Returns the parsed file and the whole content hash (`None` without `hash`).
fn parse_hashing(path: &Path, options: &mi::ReadOptions, hash: bool) -> Result<(mi::Parsed, Option<u64>), String> {
    let bytes = mi::source::read_source(path)
        .map_err(|message| mi::ReadError { path: path.display().to_string(), message }.to_string())?;
    let origin = mi::Origin::Disk(path.to_path_buf());
    if !hash {
        return Ok((mi::parse_source(origin, bytes, options), None));
    }
    let text = bytes.clone();
    let hash_main = move || {
        let mut h = Fnv::new();
        file_hash(&mut h, &text);
        h
    };
    let (parsed, main) = std::thread::scope(|s| {
        let hasher = std::thread::Builder::new().spawn_scoped(s, hash_main);
        let parsed = mi::parse_source(origin, bytes, options);
        let main = hasher.ok().and_then(|h| h.join().ok());
        (parsed, main)
    });
    // The source map's first file is the main file, holding the bytes hashed above (a
    // thread that could not start leaves the whole hash to this one).
    let hash = match main {
        Some(h) => sources_hash(h, &parsed.sources, 1),
        None => sources_hash(Fnv::new(), &parsed.sources, 0),
    };
    Ok((parsed, Some(hash)))
}

/// Source files at least this long have their text freed between parsing and building the
/// scene (read again only if a message quotes them): a 4 M-triangle file's text is 47
/// bytes per triangle, more than the renderer's own geometry.
pub const RELEASE_TEXT_FROM_BYTES: usize = 16 << 20;

/// Stage 1, **load**: reads the file at `path` (following `$include`s by `options`) and
/// builds the scene at its `frame`-th `render` statement (0 for the first). An unreadable
/// file is an error; problems in the text are in [`Loaded::diagnostics`].
///
/// The text of big files ([`RELEASE_TEXT_FROM_BYTES`]) is freed once parsed, unless a
/// message needs it; it is read again when the scene layer has something to say, so the
/// sources of the result quote every message in [`Loaded::diagnostics`]. The trilists'
/// vertex numbers and indices move from the syntax tree into the scene's meshes
/// ([`Scene::build_taking`]): the tree of the result holds them empty.
pub fn load(path: &Path, options: &mi::ReadOptions, frame: usize) -> Result<Loaded, String> {
    load_releasing(path, options, frame, RELEASE_TEXT_FROM_BYTES, true)
}

/// [`load`] without the content hash ([`Loaded::content_hash`] is `None`), for a render
/// that writes no part or pre-pass file: hashing a 190 MB scene costs about 0.3 s of CPU,
/// taken from the parse's number lists on a two-core machine.
pub fn load_unhashed(path: &Path, options: &mi::ReadOptions, frame: usize) -> Result<Loaded, String> {
    load_releasing(path, options, frame, RELEASE_TEXT_FROM_BYTES, false)
}

/// [`load`], freeing the text of files of at least `release_from` bytes, hashing the text
/// when `hash` says so.
fn load_releasing(
    path: &Path,
    options: &mi::ReadOptions,
    frame: usize,
    release_from: usize,
    hash: bool,
) -> Result<Loaded, String> {
    let start = Instant::now();
    let (mut parsed, content_hash) = parse_hashing(path, options, hash)?;
    let parse = start.elapsed();
    let mut diagnostics = parsed.diagnostics.list.clone();
    let scene = if parsed.diagnostics.has_errors() {
        None
    } else {
        if diagnostics.is_empty() {
            parsed.sources.release_text(release_from);
        }
        // The syntax tree's trilist arrays move into the meshes (nothing reads them again).
        Scene::build_taking(&mut parsed, frame, &mut diagnostics)
    };
    let times = LoadTimes { parse, scene: start.elapsed() - parse };
    if !diagnostics.is_empty() && parsed.sources.has_released_text() {
        parsed.sources.restore_text()?;
    }
    Ok(Loaded { parsed, scene, diagnostics, content_hash, times })
}

/// Overrides the camera's resolution with `width` × `height` pixels (each clamped to
/// 1 … [`scene::camera::MAX_RESOLUTION`]), keeping the image plane: the field of view, the
/// pixel aspect, and the offset and window scaled to the new size.
pub fn set_resolution(scene: &mut Scene, width: u32, height: u32) {
    let (w, h) = (width.clamp(1, scene::camera::MAX_RESOLUTION), height.clamp(1, scene::camera::MAX_RESOLUTION));
    let cam = &mut scene.camera;
    let old = cam.resolution;
    // Keep the image plane: aspect stays as the camera had it relative to its pixels.
    let pixel_aspect = old.0 as f64 / (cam.aspect * old.1 as f64);
    cam.aspect = w as f64 / (h as f64 * pixel_aspect);
    cam.resolution = (w, h);
    cam.offset = (cam.offset.0 * w as f64 / old.0 as f64, cam.offset.1 * h as f64 / old.1 as f64);
    cam.window = cam.window.map(|[a, b, c, d]| {
        let sx = w as f64 / old.0 as f64;
        let sy = h as f64 / old.1 as f64;
        [(a as f64 * sx) as i64, (b as f64 * sy) as i64, (c as f64 * sx) as i64, (d as f64 * sy) as i64]
    });
}

/// The engine for `scene`: `asked` when given, else the classic engine when the scene's
/// materials are mental ray shaders (and its options do not say `"progressive" on`,
/// `"gi" on` or `"iray" on`) and the path engine otherwise ([`Shading::wants_classic`]).
pub fn choose_engine(scene: &Scene, asked: Option<EngineKind>) -> EngineKind {
    asked.unwrap_or(if Shading::wants_classic(scene) { EngineKind::Classic } else { EngineKind::Path })
}

/// The world and the compiled shading it was translated with (both engines use the
/// shading: the classic one runs the material shaders, the path engine the shaders
/// connected to material parameters).
pub struct Built {
    /// The compiled shaders, lights and final gather settings.
    pub shading: Shading,
    /// The world the engines trace.
    pub world: World,
    /// The shading compiler's messages.
    pub diagnostics: Vec<mi::Diagnostic>,
    /// The text of every MDL module file read for the scene's materials.
    pub mdl_sources: Vec<std::sync::Arc<[u8]>>,
}

/// Where textures are looked up for a scene read from `scene_path`: its directory, then
/// the include directories.
pub fn texture_dirs(scene_path: &Path, include: &[PathBuf]) -> Vec<PathBuf> {
    let mut dirs: Vec<PathBuf> = scene_path.parent().map(Path::to_path_buf).into_iter().collect();
    dirs.extend(include.iter().cloned());
    dirs
}

/// Stage 2, **build the world**: compiles the scene's shading with every library
/// ([`material::compile_shading`]: plug-in shaders get stand-ins) and its MDL module
/// materials (modules found beside the scene, in `mdl_paths`, then `MDL_PATHS`), tabulates
/// its `"shutter shape function"` shader ([`shader::shutter::tabulate_into`]), and
/// translates the scene into the world the engines trace (copying the scene's meshes;
/// [`build_world_taking_meshes`] moves them), then displaces the surfaces of materials with
/// a displacement shader ([`crate::displace`]).
pub fn build_world(scene: &Scene, options: &ShadingOptions, mdl_paths: &[PathBuf]) -> Built {
    let (mut shading, mdl, mut diagnostics) = compile_scene_shading(scene, options, mdl_paths);
    let mut world = World::from_scene_with_mdl(scene, Some(&shading), &mdl);
    crate::displace::displace_world(&mut world, scene, &mut shading, &mut diagnostics);
    share_media(&mut shading, &world);
    Built { shading, world, diagnostics, mdl_sources: mdl.module_sources }
}

/// [`build_world`], moving the scene's vertex, normal and triangle arrays into the world
/// instead of copying them ([`World::from_scene_taking_meshes`]): for callers that need
/// the scene's geometry no more (the scene's object meshes are left empty).
pub fn build_world_taking_meshes(scene: &mut Scene, options: &ShadingOptions, mdl_paths: &[PathBuf]) -> Built {
    let (mut shading, mdl, mut diagnostics) = compile_scene_shading(scene, options, mdl_paths);
    let mut world = World::from_scene_taking_meshes(scene, Some(&shading), &mdl);
    crate::displace::displace_world(&mut world, scene, &mut shading, &mut diagnostics);
    share_media(&mut shading, &world);
    Built { shading, world, diagnostics, mdl_sources: mdl.module_sources }
}

/// Hands the classic engine the world's participating media: each scene material's medium
/// (MDL's `material_volume`) where light can enter it, for the classic engine's volumes
/// ([`shader::volume`]), how to evaluate it where a ray enters when it varies over the
/// surface, and the tint of its boundary where that is index-matched (shadow rays cross
/// it). Scenes without media are unchanged.
fn share_media(shading: &mut Shading, world: &World) {
    for (i, m) in shading.materials.iter_mut().enumerate() {
        // World material 0 is the default; scene material i is world material i + 1.
        let inside = world.materials.get(i + 1).filter(|w| w.has_inside() && w.medium.is_some());
        m.medium = inside.and_then(|w| w.medium);
        m.varying_medium = inside.and_then(|w| w.varying_medium.clone()).map(|varying| {
            shader::shading::MediumAt(std::sync::Arc::new(move |s: &shader::State| varying.0.medium(s)))
        });
        m.boundary_tint = inside.and_then(|w| w.model.index_matched());
    }
}

/// The shading half of [`build_world`]: the compiled shading, the MDL module materials and
/// the messages of both.
fn compile_scene_shading(
    scene: &Scene,
    options: &ShadingOptions,
    mdl_paths: &[PathBuf],
) -> (Shading, material::mdl_modules::MdlMaterials, Vec<mi::Diagnostic>) {
    let (mut shading, mut diagnostics) = material::compile_shading(scene, options);
    let search = material::mdl_modules::search_path(&scene.library, mdl_paths);
    let (mdl, mdl_diagnostics) = material::mdl_modules::compile(&scene.library, search.clone());
    diagnostics.extend(mdl_diagnostics);
    if mdl.quad_ptex {
        unmapped_quad_ptex_polygons(scene, &mut diagnostics);
    }
    material::module_stand_ins(&mut shading, scene, &mdl);
    material::mdl_modules::environment::attach(&mut shading, scene, search, &mut diagnostics);
    shader::shutter::tabulate_into(&mut shading, &scene.options, &mut diagnostics);
    (shading, mdl, diagnostics)
}

/// In a scene that reads a quad-mesh Ptex file, for each object: a warning at its first
/// polygon that has no quad-mesh Ptex face (an n-gon of over [`MAX_NGON_VERTICES`]
/// vertices: lookups there are black), at its first polygon with holes (given its outer
/// boundary's sub-quads, mira's reading), and at its first free-form surface (Ptex defines
/// no faces for them: black; subdivision surfaces and ccmeshes carry their control faces',
/// `scene::mesh::ptex_refined`).
///
/// [`MAX_NGON_VERTICES`]: scene::mesh::ptex_quads::MAX_NGON_VERTICES
fn unmapped_quad_ptex_polygons(scene: &Scene, diagnostics: &mut Vec<mi::Diagnostic>) {
    for object in &scene.objects {
        let mesh = &object.geometry.mesh;
        if let Some((span, vertices)) = mesh.ptex_unmapped {
            diagnostics.push(mi::Diagnostic::warning(
                span,
                format!(
                    "object '{}': a polygon of {vertices} vertices has no quad-mesh Ptex faces (mira gives \
                     sub-quads to n-gons of at most {} vertices): quad-mesh Ptex lookups on it are black",
                    object.name,
                    scene::mesh::ptex_quads::MAX_NGON_VERTICES
                ),
            ));
        }
        if let Some(span) = mesh.ptex_holed {
            diagnostics.push(mi::Diagnostic::warning(
                span,
                format!(
                    "object '{}': a polygon with holes is given its outer boundary's quad-mesh Ptex sub-quads \
                     (one face for a 4-vertex boundary); Ptex has no faces with holes, so this numbering is a \
                     guess",
                    object.name
                ),
            ));
        }
        if let Some((span, what)) = mesh.ptex_surface {
            let why = if what == "free-form surface" {
                "Ptex defines faces for polygon meshes and subdivision surfaces only"
            } else {
                "its refined triangles are beyond the numbers mira packs per object"
            };
            diagnostics.push(mi::Diagnostic::warning(
                span,
                format!(
                    "object '{}': this {what} has no quad-mesh Ptex faces ({why}): quad-mesh Ptex lookups on it \
                     are black",
                    object.name
                ),
            ));
        }
    }
}

/// A hash of what a scene reads besides its `.mi` text ([`Loaded::content_hash`]): each
/// texture file and light profile (its name as written, then the bytes of the file it
/// resolves to on `search`, or a mark that none was found) and the text of every MDL
/// module `built` read. Two renders of the same text against a changed texture get
/// different hashes. Reads those files again (call it only where the hash is needed).
pub fn inputs_hash(scene: &Scene, search: &SearchPath, built: &Built) -> u64 {
    let mut h = Fnv::new();
    let file = |h: &mut Fnv, name: &str| {
        h.write(&(name.len() as u64).to_le_bytes());
        h.write(name.as_bytes());
        match search.resolve(name).and_then(|p| std::fs::read(p).ok()) {
            Some(bytes) => {
                h.write(&(bytes.len() as u64).to_le_bytes());
                h.write(&bytes);
            }
            None => h.write(&u64::MAX.to_le_bytes()),
        }
    };
    for t in scene.library.textures.values() {
        if let mi::ast::TextureSource::File { file: name, .. } = &t.source {
            file(&mut h, &name.text);
        }
    }
    for blocks in scene.library.lightprofiles.values() {
        if let Some(name) = blocks.last().and_then(shader::light::profiles::file_name) {
            file(&mut h, &name);
        }
    }
    for text in &built.mdl_sources {
        h.write(&(text.len() as u64).to_le_bytes());
        h.write(text);
    }
    h.finish()
}

/// FNV-1a, 64 bits: a small, stable hash for telling files and settings apart (the same
/// value on every machine and build, unlike the standard library's hasher).
#[derive(Clone, Copy, Debug)]
pub struct Fnv(u64);

impl Fnv {
    /// The empty hash.
    pub fn new() -> Fnv {
        Fnv(0xcbf2_9ce4_8422_2325)
    }

    /// Adds bytes.
    pub fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }

    /// The hash.
    pub fn finish(self) -> u64 {
        self.0
    }

    /// The hash of `bytes`.
    pub fn of(bytes: &[u8]) -> u64 {
        let mut h = Fnv::new();
        h.write(bytes);
        h.finish()
    }
}

impl Default for Fnv {
    fn default() -> Fnv {
        Fnv::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A scene the scene layer has nothing to say about is built with its text freed; one
    /// it warns or errs about gets its text back, so the message quotes the line. The
    /// content hash is the text's either way.
    #[test]
    fn text_is_freed_unless_a_message_quotes_it() {
        let dir = std::env::temp_dir().join(format!("render-release-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let scene = |root: &str| {
            format!(
                "options \"opt\" end options\ncamera \"cam\" resolution 8 8 end camera\n\
                 instance \"cam_inst\" \"cam\" end instance\n{root}\nrender \"root\" \"cam_inst\" \"opt\"\n"
            )
        };
        let hash = |text: &str| {
            let mut h = Fnv::new();
            h.write(&(text.len() as u64).to_le_bytes());
            h.write(text.as_bytes());
            h.finish()
        };
        let clean = scene("instgroup \"root\" \"cam_inst\" end instgroup");
        let path = dir.join("clean.mi");
        std::fs::write(&path, &clean).unwrap();
        let loaded = load_releasing(&path, &mi::ReadOptions::default(), 0, 1, true).unwrap();
        assert!(loaded.diagnostics.is_empty() && loaded.scene.is_some());
        assert!(loaded.parsed.sources.has_released_text());
        assert!(loaded.parsed.sources.files().all(|(_, f)| f.bytes.is_empty()));
        assert_eq!(loaded.content_hash(), Some(hash(&clean)));

        let broken = scene("instgroup \"root\" \"cam_inst\" \"no_such_thing\" end instgroup");
        let path = dir.join("broken.mi");
        std::fs::write(&path, &broken).unwrap();
        let loaded = load_releasing(&path, &mi::ReadOptions::default(), 0, 1, true).unwrap();
        assert!(!loaded.diagnostics.is_empty());
        assert!(!loaded.parsed.sources.has_released_text());
        let message = loaded.diagnostics[0].render(&loaded.parsed.sources);
        assert!(message.contains("\"no_such_thing\" end instgroup"), "{message}");
        assert_eq!(loaded.content_hash(), Some(hash(&broken)));
        std::fs::remove_dir_all(&dir).ok();
    }

    /// The content hash covers the main file and then each included file in reading
    /// order, whichever thread hashed the main file; a load asked for no hash has none.
    #[test]
    fn content_hash_covers_included_files_in_reading_order() {
        let dir = std::env::temp_dir().join(format!("render-hash-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let included = "instgroup \"root\" \"cam_inst\" end instgroup\n";
        let main = "options \"opt\" end options\ncamera \"cam\" resolution 8 8 end camera\n\
                    instance \"cam_inst\" \"cam\" end instance\n$include \"part.mi\"\n\
                    render \"root\" \"cam_inst\" \"opt\"\n";
        std::fs::write(dir.join("part.mi"), included).unwrap();
        let path = dir.join("main.mi");
        std::fs::write(&path, main).unwrap();
        let loaded = load(&path, &mi::ReadOptions::default(), 0).unwrap();
        assert!(loaded.diagnostics.is_empty() && loaded.scene.is_some());
        let mut h = Fnv::new();
        for text in [main, included] {
            h.write(&(text.len() as u64).to_le_bytes());
            h.write(text.as_bytes());
        }
        assert_eq!(loaded.content_hash(), Some(h.finish()));
        // Loaded without the hash: the same scene, no hash.
        let unhashed = load_unhashed(&path, &mi::ReadOptions::default(), 0).unwrap();
        assert!(unhashed.diagnostics.is_empty() && unhashed.scene.is_some());
        assert_eq!(unhashed.content_hash(), None);
        std::fs::remove_dir_all(&dir).ok();
    }

    /// FNV-1a's published test vectors (64-bit): "" and "a".
    #[test]
    fn fnv_matches_reference_vectors() {
        assert_eq!(Fnv::of(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(Fnv::of(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(Fnv::of(b"foobar"), 0x8594_4171_f739_67e8);
    }
}
