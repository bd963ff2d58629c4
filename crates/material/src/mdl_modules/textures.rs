//! The `texture_2d` and `light_profile` resources of module materials: image files named by MDL
//! (`texture_2d("./wood.png")`, relative to the module's file or on the MDL search path) or
//! by a `.mi` parameter (the name of a `color texture` element of the scene, or a file),
//! read once per file through the renderer's texture code (`shader::texture`) and shared by
//! every instance; light profiles likewise (a `.mi` parameter names a `lightprofile`
//! element or an IES file). Texel values are used as stored, as for `.mi` textures (no gamma).
//! `texture_3d` and `texture_cube` resources are read from DDS files ([`super::dds`]): a
//! volume texture (or a 2D one, a volume one slice deep) and a cube map; a cube map may
//! also be an image file of a horizontal or vertical cross ([`CubeMap::from_cross`]), or
//! six face images beside a name that is no file (`_px` … `_nz` suffixes, see
//! `Textures::cube_faces`). `texture_ptex` resources are read from Ptex files
//! ([`super::ptex`]).

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use bsdf::measured_bsdf::{self, MeasuredBsdf};
use shader::light::ies::Profile;
use shader::texture::{self, Texture};

use mdl_lang::ast::TextureShape;

use super::dds;
use super::hit::Image;
use super::ptex::{MeshType, Ptex};
use super::texture_3d::Volume;
use super::texture_cube::CubeMap;
use super::value::Value;

/// The images and light profiles read so far, by file.
#[derive(Default)]
pub struct Textures {
    by_path: HashMap<PathBuf, Result<Image, String>>,
    /// The light profiles read so far, by file.
    profiles: HashMap<PathBuf, Result<Arc<Profile>, String>>,
    /// The 3D textures read so far, by file.
    volumes: HashMap<PathBuf, Result<Arc<Volume>, String>>,
    /// The cube maps read so far, by file.
    cubes: HashMap<PathBuf, Result<Arc<CubeMap>, String>>,
    /// The Ptex textures read so far, by file.
    ptexes: HashMap<PathBuf, Result<Arc<Ptex>, String>>,
    /// The BSDF measurements read so far, by file.
    measurements: HashMap<PathBuf, Result<&'static MeasuredBsdf, String>>,
    /// Directories searched after the one of the module: the scene files' and the MDL
    /// search path's.
    pub dirs: Vec<PathBuf>,
    /// What reading the files found that the user should hear about (NaN or infinite
    /// texels), once per file, until the compiler reports them.
    pub warnings: Vec<String>,
}

impl Textures {
    /// A resource set searching `dirs` (after the naming module's directory).
    pub fn new(dirs: Vec<PathBuf>) -> Textures {
        Textures {
            by_path: HashMap::new(),
            profiles: HashMap::new(),
            volumes: HashMap::new(),
            cubes: HashMap::new(),
            ptexes: HashMap::new(),
            measurements: HashMap::new(),
            dirs,
            warnings: Vec::new(),
        }
    }

    /// Where file `name` of a module in `module_dir` is (as [`Textures::file`] finds it).
    fn resolve(&self, name: &str, module_dir: Option<&Path>, what: &str) -> Result<PathBuf, String> {
        let path = Path::new(name);
        if path.is_absolute() && path.is_file() {
            return Ok(path.to_path_buf());
        }
        let relative = name.trim_start_matches('/').trim_start_matches("./");
        let mut dirs: Vec<PathBuf> = module_dir.map(Path::to_path_buf).into_iter().collect();
        dirs.extend(self.dirs.iter().cloned());
        let search = texture::SearchPath { dirs };
        search
            .resolve(relative)
            .ok_or_else(|| format!("{what} '{name}' not found (searched {})", describe(&search.dirs)))
    }

    /// The `texture_3d` of file `name` (a DDS volume texture; a 2D DDS texture is a volume
    /// one slice deep) as written in a module in `module_dir`, read once. `Err` says why
    /// it could not be read.
    pub fn volume(&mut self, name: &str, module_dir: Option<&Path>) -> Result<Arc<Volume>, String> {
        let path = self.resolve(name, module_dir, "3D texture file")?;
        self.volumes
            .entry(path.clone())
            .or_insert_with(|| {
                let fail = |e: String| format!("3D texture file '{}': {e}", path.display());
                if !is_dds(&path) {
                    return Err(fail("mira reads 3D textures from DDS volume files (.dds)".into()));
                }
                let image = dds::read(&path).map_err(fail)?;
                if image.cube || image.layers.len() != 1 {
                    return Err(fail(format!(
                        "a cube map or texture array ({} layers), not a volume",
                        image.layers.len()
                    )));
                }
                let size = [image.width, image.height, image.depth];
                Volume::from_file_order(size, &image.layers[0]).map(Arc::new).ok_or_else(|| fail("no texels".into()))
            })
            .clone()
    }

    /// Whether any Ptex file (of a triangle or a quad mesh) was read.
    pub fn read_any_ptex(&self) -> bool {
        self.ptexes.values().any(Result::is_ok)
    }

    /// Whether a quad-mesh Ptex file was read.
    pub fn read_quad_ptex(&self) -> bool {
        self.ptexes.values().any(|p| matches!(p, Ok(p) if p.mesh == MeshType::Quad))
    }

    /// The `texture_ptex` of file `name` (a Ptex file of a triangle or quad mesh,
    /// [`super::ptex`]) as written in a module in `module_dir`, read once; NaN and infinite
    /// texels are said once, as a warning. `Err` says why it could not be read
    /// (`file:byte offset: what`).
    pub fn ptex(&mut self, name: &str, module_dir: Option<&Path>) -> Result<Arc<Ptex>, String> {
        let path = self.resolve(name, module_dir, "Ptex file")?;
        let warnings = &mut self.warnings;
        self.ptexes
            .entry(path.clone())
            .or_insert_with(|| {
                let bytes = std::fs::read(&path).map_err(|e| format!("Ptex file '{}': {e}", path.display()))?;
                let (ptex, non_finite) = super::ptex::reader::read(&bytes)
                    .map_err(|e| format!("Ptex file {}:{}: {}", path.display(), e.offset, e.message))?;
                if non_finite > 0 {
                    warnings.push(format!(
                        "Ptex file '{}': {non_finite} texel components are NaN or infinite; they are read as 0",
                        path.display()
                    ));
                }
                Ok(Arc::new(ptex))
            })
            .clone()
    }

    /// The `texture_cube` of file `name` (a DDS cube map, or an image of a horizontal or
    /// vertical cross; where no file `name` is found, six face images named after it, see
    /// `Textures::cube_faces`) as written in a module in `module_dir`, read once. `Err`
    /// says why it could not be read.
    pub fn cube(&mut self, name: &str, module_dir: Option<&Path>) -> Result<Arc<CubeMap>, String> {
        let path = match self.resolve(name, module_dir, "cube map file") {
            Ok(path) => path,
            Err(e) => return self.cube_faces(name, module_dir).unwrap_or(Err(e)),
        };
        self.cubes
            .entry(path.clone())
            .or_insert_with(|| {
                let fail = |e: String| format!("cube map file '{}': {e}", path.display());
                if !is_dds(&path) {
                    // An image file: a horizontal or vertical cross of six faces.
                    let loaded = texture::load_image(&path).map_err(fail)?;
                    return CubeMap::from_cross(&loaded.image).map(Arc::new).ok_or_else(|| {
                        let (w, h) = loaded.image.size();
                        fail(format!(
                            "a cube map is a DDS cube map or an image of a horizontal (4:3) or vertical (3:4) \
                             cross, not {w}×{h} texels"
                        ))
                    });
                }
                let image = dds::read(&path).map_err(fail)?;
                if !image.cube || image.layers.len() != 6 || image.width != image.height || image.depth != 1 {
                    return Err(fail(format!(
                        "not a cube map of six square faces ({}×{}, {} layers)",
                        image.width,
                        image.height,
                        image.layers.len()
                    )));
                }
                CubeMap::new(image.width, image.layers).map(Arc::new).ok_or_else(|| fail("no texels".into()))
            })
            .clone()
    }

    /// The cube map of six face images named after `name`, a file that is not found: MDL
    /// documents no naming of separate cube faces, so mira takes the common suffixes
    /// `_px`, `_nx`, `_py`, `_ny`, `_pz`, `_nz` (+x, −x, +y, −y, +z, −z) before the
    /// extension (`sky.png`: `sky_px.png` … `sky_nz.png`), each face as the cube-map
    /// convention orients it, all square and of one size. `None` when none of the six is
    /// found; `Err` names a missing face file or one of another size.
    fn cube_faces(&mut self, name: &str, module_dir: Option<&Path>) -> Option<Result<Arc<CubeMap>, String>> {
        // The extension's dot, if any, after the last directory separator.
        let dot = name.rfind('.').filter(|&d| d > name.rfind('/').map_or(0, |s| s + 1));
        let (stem, ext) = name.split_at(dot.unwrap_or(name.len()));
        let names = ["px", "nx", "py", "ny", "pz", "nz"].map(|face| format!("{stem}_{face}{ext}"));
        let paths = names.clone().map(|n| self.resolve(&n, module_dir, "cube face file").ok());
        if paths.iter().all(Option::is_none) {
            return None;
        }
        if let Some(i) = paths.iter().position(Option::is_none) {
            return Some(Err(format!(
                "cube map file '{name}' not found, nor its face file '{}' (of six, _px _nx _py _ny _pz _nz)",
                names[i]
            )));
        }
        let paths = paths.map(Option::unwrap);
        // Cached under the (absent) name beside the +x face.
        let key = paths[0].with_file_name(Path::new(name).file_name().unwrap_or_default());
        let read = || {
            let mut images = Vec::with_capacity(6);
            for path in &paths {
                let fail = |e: String| format!("cube face file '{}': {e}", path.display());
                images.push(texture::load_image(path).map_err(fail)?.image);
            }
            let (n, _) = images[0].size();
            for (image, path) in images.iter().zip(&paths) {
                let (w, h) = image.size();
                if (w, h) != (n, n) {
                    return Err(format!(
                        "cube face file '{}': {w}×{h} texels, but the six faces of '{name}' must be square and \
                         of one size ({n}×{n}, as '{}')",
                        path.display(),
                        paths[0].display()
                    ));
                }
            }
            let refs: Vec<_> = images.iter().collect();
            CubeMap::from_faces(&refs).map(Arc::new).ok_or_else(|| format!("cube map '{name}': no texels"))
        };
        Some(self.cubes.entry(key).or_insert_with(read).clone())
    }

    /// The image of file `name` as written in a module whose file is in `module_dir` (an
    /// MDL path: `/` separators, a leading `/` meaning the search path's roots, `./` the
    /// module's directory). `Err` says why it could not be read.
    pub fn file(&mut self, name: &str, module_dir: Option<&Path>) -> Result<Image, String> {
        let relative = name.trim_start_matches('/').trim_start_matches("./");
        let mut dirs: Vec<PathBuf> = module_dir.map(Path::to_path_buf).into_iter().collect();
        dirs.extend(self.dirs.iter().cloned());
        let search = texture::SearchPath { dirs };
        let Some(path) = search.resolve(relative) else {
            return Err(format!("texture file '{name}' not found (searched {})", describe(&search.dirs)));
        };
        self.load(path)
    }

    /// The BSDF measurement (an MBSDF file, [`bsdf::measured_bsdf::reader`]) of file `name`
    /// as written in a module in `module_dir`, read once (and interned for the process);
    /// what reading it approximated is said once, as a warning. `Err` says why it could
    /// not be read (`file:byte offset: what`).
    pub fn bsdf_measurement(&mut self, name: &str, module_dir: Option<&Path>) -> Result<&'static MeasuredBsdf, String> {
        let path = self.resolve(name, module_dir, "bsdf measurement")?;
        let warnings = &mut self.warnings;
        self.measurements
            .entry(path.clone())
            .or_insert_with(|| {
                let bytes = std::fs::read(&path).map_err(|e| format!("bsdf measurement '{}': {e}", path.display()))?;
                let (m, notes) = measured_bsdf::reader::read(&bytes)
                    .map_err(|e| format!("bsdf measurement {}:{}: {}", path.display(), e.offset, e.message))?;
                warnings.extend(notes.into_iter().map(|n| format!("bsdf measurement '{}': {n}", path.display())));
                measured_bsdf::intern(m).map_err(|e| format!("bsdf measurement '{}': {e}", path.display()))
            })
            .clone()
    }

    /// The light profile (an IES LM-63 file) of file `name` as written in a module whose
    /// file is in `module_dir`, read once; what reading it approximated is said once, as
    /// a warning. `Err` says why it could not be read.
    pub fn light_profile(&mut self, name: &str, module_dir: Option<&Path>) -> Result<Arc<Profile>, String> {
        let relative = name.trim_start_matches('/').trim_start_matches("./");
        let mut dirs: Vec<PathBuf> = module_dir.map(Path::to_path_buf).into_iter().collect();
        dirs.extend(self.dirs.iter().cloned());
        let search = texture::SearchPath { dirs };
        let Some(path) = search.resolve(relative) else {
            return Err(format!("light profile '{name}' not found (searched {})", describe(&search.dirs)));
        };
        let warnings = &mut self.warnings;
        self.profiles
            .entry(path.clone())
            .or_insert_with(|| {
                let (profile, notes) =
                    Profile::load(&path, false).map_err(|e| format!("light profile '{}': {e}", path.display()))?;
                warnings.extend(notes.into_iter().map(|n| format!("light profile '{}': {n}", path.display())));
                Ok(Arc::new(profile))
            })
            .clone()
    }

    /// The light profile a `.mi` parameter names: a `lightprofile` element of `lib` (its
    /// `format ies` file, on the search path, `flags 1` read clockwise, as lights read it),
    /// else an IES file. `Err` says why it could not be read.
    pub fn profile_from_mi(&mut self, name: &str, lib: &scene::Library) -> Result<Arc<Profile>, String> {
        let search = texture::SearchPath { dirs: self.dirs.clone() };
        if let Some(block) = lib.lightprofiles.get(name).and_then(|b| b.last()) {
            let (profile, notes) = shader::light::profiles::load_block(block, &search)
                .map_err(|e| format!("lightprofile '{name}': {e}"))?;
            self.warnings.extend(notes.into_iter().map(|n| format!("lightprofile '{name}': {n}")));
            return Ok(Arc::new(profile));
        }
        let path = Path::new(name);
        if path.is_absolute() && path.is_file() {
            let (profile, notes) =
                Profile::load(path, false).map_err(|e| format!("light profile '{}': {e}", path.display()))?;
            self.warnings.extend(notes.into_iter().map(|n| format!("light profile '{}': {n}", path.display())));
            return Ok(Arc::new(profile));
        }
        self.light_profile(name, None).map_err(|e| format!("'{name}' is no lightprofile element of the scene, and {e}"))
    }

    /// The texture of shape `shape` a `.mi` parameter names: a 2D texture as
    /// [`Textures::from_mi`] finds it, a 3D texture or cube map from a DDS file.
    pub fn value_from_mi(&mut self, shape: TextureShape, name: &str, lib: &scene::Library) -> Result<Value, String> {
        // A `color texture` element of the scene names the file of a 3D texture or cube map.
        let file = match lib.textures.get(name).map(|t| &t.source) {
            Some(mi::ast::TextureSource::File { file, .. }) if shape != TextureShape::Tex2d => file.text.as_str(),
            _ => name,
        };
        match shape {
            TextureShape::Tex3d => self.volume(file, None).map(|v| Value::Texture3d(Some(v))),
            TextureShape::Cube => self.cube(file, None).map(|c| Value::TextureCube(Some(c))),
            TextureShape::Ptex => self.ptex(file, None).map(|p| Value::TexturePtex(Some(p))),
            TextureShape::Tex2d => self.from_mi(name, lib).map(|i| Value::Texture(Some(i))),
        }
    }

    /// The image of the file at `path`, read once.
    fn load(&mut self, path: PathBuf) -> Result<Image, String> {
        let warnings = &mut self.warnings;
        self.by_path
            .entry(path.clone())
            .or_insert_with(|| {
                texture::load_image(&path)
                    .map(|loaded| {
                        // NaN and infinite texels were read as 0 by the loader: said once,
                        // as the `.mi` texture loader says it.
                        if loaded.non_finite > 0 {
                            warnings.push(format!(
                                "texture file '{}': {} texel components are NaN or infinite; they are read as 0",
                                path.display(),
                                loaded.non_finite
                            ));
                        }
                        let kind = mi::ast::TextureKind::Color;
                        Image(Arc::new(Texture::Image { image: Arc::new(loaded.image), filter: None, kind }))
                    })
                    .map_err(|e| format!("texture file '{}': {e}", path.display()))
            })
            .clone()
    }

    /// The image a `.mi` parameter names: a `color texture` element of `lib` (its file or
    /// inline pixels), else a file.
    pub fn from_mi(&mut self, name: &str, lib: &scene::Library) -> Result<Image, String> {
        // A `.mi` file name may be absolute (an MDL name's leading `/` is the search path's).
        let mi_file = |this: &mut Textures, file: &str| {
            let path = Path::new(file);
            if path.is_absolute() && path.is_file() {
                this.load(path.to_path_buf())
            } else {
                this.file(file, None)
            }
        };
        let Some(t) = lib.textures.get(name) else { return mi_file(self, name) };
        match &t.source {
            mi::ast::TextureSource::File { file, .. } => mi_file(self, &file.text),
            mi::ast::TextureSource::Pixels { dims, pieces } => texture::inline_pixels(dims, &pieces.concat())
                .map(|image| Image(Arc::new(Texture::Image { image: Arc::new(image), filter: None, kind: t.kind })))
                .map_err(|e| format!("texture '{name}': {e}")),
            _ => Err(format!("texture '{name}' is a shader texture (not read by module materials)")),
        }
    }
}

/// Whether `path` names a DDS file (by its first four bytes, `DDS `).
fn is_dds(path: &Path) -> bool {
    use std::io::Read;
    let mut magic = [0u8; 4];
    std::fs::File::open(path).and_then(|mut f| f.read_exact(&mut magic)).is_ok() && &magic == b"DDS "
}

/// The invalid texture of shape `shape` (black where looked up).
pub fn invalid(shape: TextureShape) -> Value {
    match shape {
        TextureShape::Tex3d => Value::Texture3d(None),
        TextureShape::Cube => Value::TextureCube(None),
        TextureShape::Ptex => Value::TexturePtex(None),
        _ => Value::Texture(None),
    }
}

fn describe(dirs: &[PathBuf]) -> String {
    if dirs.is_empty() {
        return "the current directory".into();
    }
    dirs.iter().map(|d| d.display().to_string()).collect::<Vec<_>>().join(", ")
}
