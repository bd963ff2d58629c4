//! The scene layer: from the `.mi` syntax tree to a renderable world.
//!
//! [`Scene::build`] resolves names (namespaces, `incremental`, `delete`), flattens the
//! instance DAG below the `render` statement's root group into world-space instances
//! (each object tessellated once and shared by its instances), binds materials to faces,
//! and reads the camera, lights and options into typed values with mental ray's defaults.
//! Everything downstream (shaders, integrators) reads this layer, never the syntax tree.
//!
//! Spaces: object space (an object's own coordinates), world space, camera space (looking
//! down −Z, +Y up). Transforms are glam `DMat4`s for column vectors.

pub mod build;
pub mod camera;
pub mod displace;
pub mod instance;
pub mod light;
pub mod mesh;
pub mod names;
pub mod options;
pub mod references;
pub mod report;
pub mod sanity;
pub mod shader_graph;
pub mod tessellate;
pub mod transform;
pub mod values;

use std::collections::BTreeMap;

pub use camera::Camera;
pub use instance::{Flags, Instance, Mode};
pub use light::{AreaShape, Light, LightKind};
pub use mesh::{HairGeometry, MaterialSlot, Mesh, TexSpace};
pub use options::{Dialect, Options};
pub use tessellate::ObjectGeometry;

use mi::ast;

/// A renderable world.
#[derive(Clone, Debug)]
pub struct Scene {
    /// Render settings.
    pub options: Options,
    /// The render camera.
    pub camera: Camera,
    /// Every light instance in the rendered DAG.
    pub lights: Vec<Light>,
    /// Every object that is instanced, tessellated once.
    pub objects: Vec<Object>,
    /// Every placement of an object.
    pub instances: Vec<Instance>,
    /// Every material bound to some face.
    pub materials: Vec<Material>,
    /// Named shaders, declarations, textures and other elements shaders refer to.
    pub library: Library,
}

/// An object's geometry and own flags.
#[derive(Clone, Debug)]
pub struct Object {
    /// Full name.
    pub name: String,
    /// Flags written on the object.
    pub flags: instance::FlagSet,
    /// Faces carry labels.
    pub tagged: bool,
    /// `tag` (label for the tag frame buffer).
    pub tag: Option<i64>,
    /// The user data elements its `data` statements name (full names into
    /// [`Library::data`], in the order written; `data null` clears the list).
    pub data: Vec<String>,
    /// The tessellated geometry.
    pub geometry: ObjectGeometry,
    /// Its `approximate displace` and `max displace` (for the renderer's displacement).
    pub displace: displace::DisplaceSettings,
    /// Where the object is defined.
    pub span: mi::Span,
}

/// A material bound to faces.
#[derive(Clone, Debug)]
pub struct Material {
    /// Full name.
    pub name: String,
    /// What it is.
    pub kind: MaterialKind,
}

/// The definition behind a material name.
#[derive(Clone, Debug)]
pub enum MaterialKind {
    /// A mental ray `material` element: its definition and incremental changes.
    Material(Vec<ast::Material>),
    /// A named shader used as a material (Iray: an MDL material instance).
    Shader(ast::ShaderDef),
}

/// Elements shaders refer to by name, and the declarations of shaders.
#[derive(Clone, Debug, Default)]
pub struct Library {
    /// Shader, phenomenon and data declarations by name.
    pub declarations: BTreeMap<String, ast::Declaration>,
    /// Named shaders by full name (the last definition).
    pub shaders: BTreeMap<String, ast::ShaderDef>,
    /// Textures by full name.
    pub textures: BTreeMap<String, ast::Texture>,
    /// User data by full name.
    pub data: BTreeMap<String, ast::Data>,
    /// Light profiles by full name.
    pub lightprofiles: BTreeMap<String, Vec<ast::Block>>,
    /// MDL modules the scene includes.
    pub mdl_modules: Vec<String>,
    /// Where each of `mdl_modules` is included (the `$include`'s file name; same order).
    pub mdl_module_spans: Vec<mi::Span>,
    /// The directories of the scene files that include MDL modules (searched first for
    /// them, in order; see `material::mdl`).
    pub mdl_dirs: Vec<std::path::PathBuf>,
}

impl Library {
    fn from_table(table: &names::Table) -> Library {
        let mut lib = Library {
            declarations: table.declarations.iter().map(|(k, d)| (k.clone(), (*d).clone())).collect(),
            mdl_modules: table.mdl_modules.clone(),
            mdl_module_spans: table.mdl_module_spans.clone(),
            ..Library::default()
        };
        for (name, e) in &table.elements {
            match &e.def {
                names::Def::Shader(defs) => {
                    if let Some(d) = defs.last() {
                        lib.shaders.insert(name.clone(), (*d).clone());
                    }
                }
                names::Def::Texture(t) => {
                    lib.textures.insert(name.clone(), (*t).clone());
                }
                names::Def::Data(d) => {
                    lib.data.insert(name.clone(), (*d).clone());
                }
                names::Def::Lightprofile(b) => {
                    lib.lightprofiles.insert(name.clone(), b.iter().map(|b| (*b).clone()).collect());
                }
                _ => {}
            }
        }
        lib
    }
}

/// Appends the directory of each file that `$include`s an MDL module among `items` (once).
fn mdl_include_dirs(items: &[ast::Item], sources: &mi::SourceMap, dirs: &mut Vec<std::path::PathBuf>) {
    for item in items {
        match item {
            ast::Item::Include(inc) => {
                if inc.target == mi::IncludeTarget::Mdl {
                    let dir =
                        sources.file(inc.path.span.file).dir().map(std::path::Path::to_path_buf).unwrap_or_default();
                    let dir = if dir.as_os_str().is_empty() { std::path::PathBuf::from(".") } else { dir };
                    if !dirs.contains(&dir) {
                        dirs.push(dir);
                    }
                }
                mdl_include_dirs(&inc.items, sources, dirs);
            }
            ast::Item::Namespace(ns) => mdl_include_dirs(&ns.items, sources, dirs),
            _ => {}
        }
    }
}

impl Scene {
    /// Builds the world at the `frame`-th `render` statement of a parsed file (0: the
    /// first). Problems are appended to `diagnostics`; `None` when no world can be built
    /// (no render statement, unknown root group, camera or options).
    pub fn build(parsed: &mi::Parsed, frame: usize, diagnostics: &mut Vec<mi::Diagnostic>) -> Option<Scene> {
        let mut scene = build::build(&parsed.items, frame, diagnostics)?;
        mdl_include_dirs(&parsed.items, &parsed.sources, &mut scene.library.mdl_dirs);
        Some(scene)
    }

    /// [`Scene::build`], moving the trilists' vertex numbers and triangle indices out of
    /// the syntax tree into the meshes instead of copying them (`parsed`'s trilists are left
    /// with empty arrays): for a caller that needs the tree's geometry no more.
    pub fn build_taking(parsed: &mut mi::Parsed, frame: usize, diagnostics: &mut Vec<mi::Diagnostic>) -> Option<Scene> {
        let mut scene = build::build_taking(&mut parsed.items, frame, diagnostics)?;
        mdl_include_dirs(&parsed.items, &parsed.sources, &mut scene.library.mdl_dirs);
        Some(scene)
    }

    /// Triangles of all instances (instanced geometry counted once per instance).
    pub fn instanced_triangles(&self) -> usize {
        self.instances.iter().map(|i| self.objects[i.object as usize].geometry.mesh.triangles.len()).sum()
    }

    /// Frees every object's tessellated geometry (meshes and hair), keeping the objects
    /// themselves: for a caller that has translated the geometry (the renderer's world)
    /// and needs the rest of the scene (camera, outputs, library) only. Geometry queries
    /// answer as for empty objects afterwards.
    pub fn release_geometry(&mut self) {
        for o in &mut self.objects {
            o.geometry = tessellate::ObjectGeometry::default();
        }
    }

    /// Triangles of the unique objects.
    pub fn unique_triangles(&self) -> usize {
        self.objects.iter().map(|o| o.geometry.mesh.triangles.len()).sum()
    }

    /// World-space bounds of all instances (`None` if there is no geometry).
    pub fn bounds(&self) -> Option<(glam::DVec3, glam::DVec3)> {
        let mut out: Option<(glam::DVec3, glam::DVec3)> = None;
        for inst in &self.instances {
            let geo = &self.objects[inst.object as usize].geometry;
            let points = geo.mesh.positions.iter().chain(geo.hair.iter().flat_map(|h| h.points.iter()));
            for p in points {
                let w = inst.object_to_world.transform_point3(p.as_dvec3());
                out = Some(match out {
                    None => (w, w),
                    Some((lo, hi)) => (lo.min(w), hi.max(w)),
                });
            }
        }
        out
    }
}
