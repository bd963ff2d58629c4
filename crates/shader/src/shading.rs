//! A scene's shading, compiled: the shader graph, textures, materials' shader slots,
//! lights, the camera's environment and lens shaders, and the options shaders obey.

use std::sync::Arc;

use glam::Vec3A;
use mi::ast::{Arg, ShaderList, Stmt, TextureSource};
use mi::{Diagnostic, Span};
use scene::instance::LightLink;
use scene::{MaterialKind, Scene};

use super::graph::{Builder, Graph, Names, NodeId};
use super::value::{Color, Value};
use crate::light::{ShadingLight, SimpleLight};
use crate::registry::Registry;
use crate::texture::{self, SearchPath, Texture};

/// The shader lists of a material's slots.
#[derive(Clone, Debug, Default)]
pub struct MaterialShaders {
    /// The material's name.
    pub name: String,
    /// Material (surface) shader list.
    pub surface: Option<NodeId>,
    /// Shadow shader list.
    pub shadow: Option<NodeId>,
    /// Volume shader list.
    pub volume: Option<NodeId>,
    /// The homogeneous participating medium inside the material's objects (MDL's
    /// `material_volume`, the path engine's medium, handed over by the renderer): where the
    /// material has no volume shader, rays travelling inside lose all but exp(−σt·d) of
    /// their colour ([`super::volume`]).
    pub medium: Option<bsdf::Medium>,
    /// Where that medium varies over the surface (an MDL volume whose coefficients depend
    /// on the shading point): how to evaluate it at the point a ray enters the object
    /// through; `medium` is then its value at the material's default point.
    pub varying_medium: Option<MediumAt>,
    /// Where the material has a `medium` behind an index-matched boundary (MDL's specular
    /// transmission with ior 1): the colour that boundary tints light by as it enters.
    /// Shadow rays cross such a surface without a shadow shader ([`super::volume`]).
    pub boundary_tint: Option<bsdf::Rgb>,
    /// Environment shader list.
    pub environment: Option<NodeId>,
    /// Photon shader list.
    pub photon: Option<NodeId>,
    /// Displacement shader list.
    pub displace: Option<NodeId>,
    /// BSDF shader (`bsdf` slot, mental ray 3.7+): a built-in BSDF, which the classic engine
    /// runs as the material shader when the material has none.
    pub bsdf: Option<NodeId>,
    /// `opaque`: shadow rays may stop at it.
    pub opaque: bool,
    /// Its surface shader is a mental ray shader (not mira's stand-in for MDL).
    pub classic: bool,
}

/// A participating medium that depends on the shading point, evaluated at a surface
/// state (world space, as [`crate::State`]); shared, equal only to itself.
#[derive(Clone)]
pub struct MediumAt(pub Arc<dyn Fn(&crate::State) -> bsdf::Medium + Send + Sync>);

impl MediumAt {
    /// The medium at surface point `state`.
    pub fn at(&self, state: &crate::State) -> bsdf::Medium {
        (self.0)(state)
    }
}

impl std::fmt::Debug for MediumAt {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("MediumAt(..)")
    }
}

/// How to compile.
#[derive(Clone, Debug, Default)]
pub struct ShadingOptions {
    /// Where texture files are looked for.
    pub search: SearchPath,
    /// Seed of shaders' sampling.
    pub seed: u32,
    /// Final gather rays at each eye-ray hit (`None`: [`default_gather_rays`] of the
    /// options' accuracy).
    pub finalgather_rays: Option<u32>,
}

/// The compiled shading of a scene (shared by all rendering threads).
#[derive(Debug, Default)]
pub struct Shading {
    /// Every shader node.
    pub graph: Graph,
    /// Textures by index (`Tag::Texture`).
    pub textures: Vec<Texture>,
    /// Light profiles by index (`Tag::Lightprofile`); `None`: could not be read.
    pub lightprofiles: Vec<Option<Arc<crate::light::ies::Profile>>>,
    /// Shader slots of the scene's materials, in scene order.
    pub materials: Vec<MaterialShaders>,
    /// Lights, in scene order (`Tag::Light`).
    pub lights: Vec<ShadingLight>,
    /// Each scene instance's light list (mode 4).
    pub instance_lights: Vec<Option<LightLink>>,
    /// Each scene instance's shadow light list (`light shadow ["exclusive"] [ … ]`, Maya's
    /// shadow linking): the lights it casts shadows for. Empty when no instance has one.
    pub instance_shadow_lights: Vec<Option<LightLink>>,
    /// The scene's user data elements (`Tag::Data`), read as written.
    pub data: Vec<super::user_data::UserData>,
    /// For each scene instance, the user data its object carries (indices into
    /// [`Shading::data`], in the order of the object's `data` statements).
    pub instance_data: Vec<Vec<u32>>,
    /// The camera's environment shader list.
    pub environment: Option<NodeId>,
    /// The camera's volume shader list (the atmosphere rays outside any object's volume
    /// travel through; see [`super::volume`]).
    pub volume: Option<NodeId>,
    /// The camera's lens shaders, in order.
    pub lens: Vec<NodeId>,
    /// Trace-depth limits.
    pub depth: TraceDepth,
    /// `trace on`: secondary rays are cast at all.
    pub trace: bool,
    /// Shadows are traced.
    pub shadows: bool,
    /// Final gathering.
    pub finalgather: FinalGather,
    /// Seed of shaders' sampling.
    pub seed: u32,
    /// Image resolution in pixels (screen-space shaders).
    pub resolution: (u32, u32),
    /// World → camera space.
    pub world_to_camera: glam::Affine3A,
    /// Half the width and height of the camera's image plane at distance 1 in front of it
    /// (the tangents of the half fields of view); for an orthographic camera, half the
    /// view's width and height in camera units.
    pub image_plane: glam::Vec2,
    /// The camera is orthographic.
    pub orthographic: bool,
    /// Data shader nodes compute once per render (pre-blurred environments).
    pub precomputed: super::precomputed::Precomputed,
    /// The photon maps, once the renderer's photon pass made them (`caustic on`,
    /// `globillum on`); unset: `compute_irradiance` is final gathering alone.
    pub photons: std::sync::OnceLock<super::photonmap::PhotonMaps>,
    /// The shader the string option `"shutter shape function"` names (mental ray 3.7:
    /// the shutter's opening as a function of time), if it names one.
    pub shutter_shape: Option<NodeId>,
    /// That shader's result tabulated over the shutter interval, once the renderer
    /// evaluated it (`shutter::tabulate_into`; how far the shutter is open at shutter
    /// times `(i + ½) / n`); `None` when there is no such shader or it could not be used
    /// (a warning says why).
    pub shutter_weights: Option<Vec<f32>>,
    /// Whether some material has a shadow shader list or a medium, found on first use
    /// ([`Shading::has_shadow_shaders`]).
    shadow_shaders: std::sync::OnceLock<bool>,
    /// Whether some material has a shadow shader list, found on first use
    /// ([`Shading::has_surface_shadow_shaders`]).
    surface_shadow_shaders: std::sync::OnceLock<bool>,
    /// Whether some material has a participating medium, found on first use
    /// ([`Shading::has_media`]).
    media: std::sync::OnceLock<bool>,
    /// Whether some material has a medium that varies over its surface, found on first
    /// use ([`Shading::has_varying_media`]).
    varying_media: std::sync::OnceLock<bool>,
    /// Whether the camera or some material has an affine volume shader list, found on
    /// first use ([`Shading::has_affine_volumes`]).
    pub(crate) affine_volumes: std::sync::OnceLock<bool>,
    /// Each light's shader as a [`SimpleLight`] where it is one, found on first use
    /// ([`Shading::simple_light`]).
    simple_lights: std::sync::OnceLock<Vec<Option<SimpleLight>>>,
}

/// Trace-depth limits (`trace depth reflect refract sum`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TraceDepth {
    /// Most reflections on a path.
    pub reflect: u32,
    /// Most refractions and transparency rays on a path.
    pub refract: u32,
    /// Most of both together.
    pub sum: u32,
}

/// Final gathering: irradiance gathered with rays, interpolated between final gather
/// points where the renderer built a cache ([`crate::fgcache`]), else gathered at every
/// shading point that asks for it (brute force).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FinalGather {
    /// Whether `compute_irradiance` gathers at all (`finalgather on`).
    pub enabled: bool,
    /// Rays per gather at the first diffuse bounce from the eye.
    pub rays: u32,
    /// Rays per gather at deeper bounces.
    pub secondary_rays: u32,
    /// Diffuse bounces (`finalgather trace depth … diffuse`): gathers from gather hits.
    pub diffuse_depth: u32,
    /// Gather rays stop at this distance and see the environment (`finalgather falloff`).
    pub max_dist: Option<f32>,
    /// `finalgather scale`.
    pub scale: Color,
    /// The interpolation cache's settings; `None`: brute force (`finalgather points 0`).
    pub cache: Option<crate::fgcache::CacheSettings>,
}

/// Gather rays per eye-ray hit for the options' `finalgather accuracy` where final gathering
/// is brute force (no cache, or no valid final gather point there). The cache's points
/// cast the full accuracy ([`super::fgcache`]); a brute-force gather spends a sixteenth of
/// it (4 to 64), the pixel's samples averaging the rest.
pub fn default_gather_rays(accuracy: u32) -> u32 {
    (accuracy / 16).clamp(4, 64)
}

/// Most trace depth mira follows, whatever the options say (deeper recursion would only
/// exhaust the stack for no visible change).
pub const MAX_TRACE_DEPTH: u32 = 64;

impl Shading {
    /// Compiles the shading of `scene` with the shaders of `registry`'s libraries. Problems
    /// (unknown shaders, parameters, unreadable textures) come back as diagnostics pointing
    /// into the scene's files.
    pub fn build(scene: &Scene, options: &ShadingOptions, registry: &Arc<Registry>) -> (Shading, Vec<Diagnostic>) {
        let lib = &scene.library;
        let decls = registry.decls(lib.declarations.values());
        let mut names = Names::default();
        for (i, name) in lib.textures.keys().enumerate() {
            names.textures.insert(name.clone(), i as u32);
        }
        for (i, l) in scene.lights.iter().enumerate() {
            names.lights.insert(l.instance.clone(), i as u32);
            names.lights.entry(l.name.clone()).or_insert(i as u32);
        }
        for (i, m) in scene.materials.iter().enumerate() {
            names.materials.insert(m.name.clone(), i as u32);
        }
        for (i, name) in lib.data.keys().enumerate() {
            names.data.insert(name.clone(), i as u32);
        }
        let data_index = names.data.clone();
        let mut unknown_data = Vec::new();
        for o in &scene.objects {
            for n in o.data.iter().filter(|n| !data_index.contains_key(n.as_str())) {
                unknown_data.push(Diagnostic::warning(
                    o.span,
                    format!("object '{}': data '{n}' is not defined; it is left out", o.name),
                ));
            }
        }
        for (i, name) in lib.lightprofiles.keys().enumerate() {
            names.lightprofiles.insert(name.clone(), i as u32);
        }
        let profile_names = names.lightprofiles.clone();
        let mut b = Builder::new(&decls, &lib.shaders, names);
        let (lightprofiles, mut diags) = crate::light::profiles::load_all(lib, &options.search);
        diags.append(&mut unknown_data);

        let mut textures = Vec::with_capacity(lib.textures.len());
        for t in lib.textures.values() {
            textures.push(match &t.source {
                TextureSource::Shader(list) => b.list(list, None).map_or(Texture::Missing, Texture::Shader),
                TextureSource::File { file, .. } => load_file(&file.text, file.span, t, options, &mut diags),
                TextureSource::Pixels { dims, pieces } => {
                    let bytes: Vec<u8> = pieces.concat();
                    match texture::inline_pixels(dims, &bytes) {
                        Ok(m) => image_texture(m, t),
                        Err(e) => {
                            diags.push(Diagnostic::warning(t.span, format!("texture '{}': {e}", t.name.text)));
                            Texture::Missing
                        }
                    }
                }
            });
        }

        let mut materials = Vec::with_capacity(scene.materials.len());
        for m in &scene.materials {
            materials.push(material(&mut b, m, lib, registry));
        }

        let lights = scene
            .lights
            .iter()
            .map(|l| ShadingLight {
                name: l.instance.clone(),
                shader: l.shader.as_ref().and_then(|s| b.list(s, None)),
                kind: l.kind,
                origin: l.position.as_vec3a(),
                direction: l.direction.as_vec3a().normalize_or(Vec3A::NEG_Z),
                spread: l.spread as f32,
                shape: l.area.as_ref().and_then(|a| crate::light::Shape::of_area(&a.shape, scene).ok()),
                user: l.area.as_ref().is_some_and(|a| a.shape == scene::AreaShape::User),
                samples: l.area.as_ref().map_or((1, 1), |a| a.samples),
                low: l.area.as_ref().and_then(|a| a.low),
                visible: l.visible,
                exponent: l.exponent as f32,
                to_local: crate::light::profiles::to_local(l.light_to_world),
                profile: l.lightprofile.as_ref().and_then(|p| profile_names.get(p).copied()),
                photons: l.energy.map(|e| super::photonmap::LightPhotons {
                    energy: Vec3A::new(e[0] as f32, e[1] as f32, e[2] as f32),
                    caustic: l.caustic_photons,
                    globillum: l.globillum_photons,
                }),
            })
            .collect();

        let environment = match &scene.camera.environment {
            Some(e) => b.list(e, None),
            None => iray_environment(&mut b, &scene.options, &mut diags),
        };
        let lens = scene.camera.lens.iter().filter_map(|l| b.list(l, None)).collect();
        let o = &scene.options;
        let fg = &o.finalgather;
        let clamp = |d: u32| d.min(MAX_TRACE_DEPTH);
        let finalgather = FinalGather {
            enabled: fg.enabled,
            rays: options.finalgather_rays.unwrap_or_else(|| default_gather_rays(fg.rays)).max(1),
            secondary_rays: 1,
            diffuse_depth: clamp(fg.trace_depth[2]),
            max_dist: fg.falloff.map(|(_, stop)| stop as f32).filter(|d| *d > 0.0),
            scale: Color::new(fg.scale[0] as f32, fg.scale[1] as f32, fg.scale[2] as f32, fg.scale[3] as f32),
            cache: super::fgcache::CacheSettings::of_options(fg),
        };
        let volume = scene.camera.volume.as_ref().and_then(|v| b.list(v, None));
        let shutter_shape = shutter_shape(&mut b, &scene.options, &mut diags);
        let (graph, graph_diags) = b.finish();
        diags.extend(graph_diags);
        let shading = Shading {
            graph,
            textures,
            lightprofiles,
            materials,
            lights,
            instance_lights: scene.instances.iter().map(|i| i.lights.clone()).collect(),
            instance_shadow_lights: if scene.instances.iter().any(|i| i.shadow_lights.is_some()) {
                scene.instances.iter().map(|i| i.shadow_lights.clone()).collect()
            } else {
                Vec::new()
            },
            data: lib.data.values().map(super::user_data::UserData::read).collect(),
            instance_data: scene
                .instances
                .iter()
                .map(|i| {
                    let names = scene.objects.get(i.object as usize).map_or(&[][..], |o| &o.data[..]);
                    names.iter().filter_map(|n| data_index.get(n.as_str()).copied()).collect()
                })
                .collect(),
            environment,
            volume,
            lens,
            depth: TraceDepth {
                reflect: clamp(o.trace_depth.0),
                refract: clamp(o.trace_depth.1),
                sum: clamp(o.trace_depth.2),
            },
            trace: o.trace,
            shadows: o.shadow != scene::options::ShadowMode::Off,
            finalgather,
            seed: options.seed,
            resolution: scene.camera.resolution,
            world_to_camera: glam::Affine3A::from_mat4(scene.camera.world_to_camera.as_mat4()),
            image_plane: {
                let c = &scene.camera;
                let half_width = 0.5 * c.aperture / c.focal.unwrap_or(1.0).abs().max(1e-12);
                glam::Vec2::new(half_width as f32, (half_width / c.aspect.abs().max(1e-12)) as f32)
            },
            orthographic: scene.camera.focal.is_none(),
            precomputed: Default::default(),
            photons: Default::default(),
            shutter_shape,
            shutter_weights: None,
            shadow_shaders: Default::default(),
            surface_shadow_shaders: Default::default(),
            media: Default::default(),
            varying_media: Default::default(),
            affine_volumes: Default::default(),
            simple_lights: Default::default(),
        };
        (shading, diags)
    }

    /// Whether some material has a shadow shader list or a participating medium (without
    /// either, every surface stops shadow rays). Found once, on the first question: the materials are set by then.
    pub fn has_shadow_shaders(&self) -> bool {
        *self.shadow_shaders.get_or_init(|| self.materials.iter().any(|m| m.shadow.is_some() || m.medium.is_some()))
    }

    /// Whether scene instance `instance` casts shadows for light `light` (an index into
    /// [`Shading::lights`]): always, unless the instance has a shadow light list, which
    /// names the only lights it casts shadows for (`exclusive`: the lights it casts none
    /// for).
    pub fn casts_shadow_for(&self, instance: u32, light: Option<u32>) -> bool {
        match (self.instance_shadow_lights.get(instance as usize).and_then(Option::as_ref), light) {
            (Some(link), Some(light)) => link.lights.contains(&light) != link.exclusive,
            _ => true,
        }
    }

    /// Whether some instance has a shadow light list ([`Shading::casts_shadow_for`]).
    pub fn has_shadow_links(&self) -> bool {
        !self.instance_shadow_lights.is_empty()
    }

    /// Whether some material has a shadow shader list of its own (without one, shadow rays
    /// only cross media boundaries or stop: their walk needs no shading state). Found once,
    /// on the first question.
    pub fn has_surface_shadow_shaders(&self) -> bool {
        *self.surface_shadow_shaders.get_or_init(|| self.materials.iter().any(|m| m.shadow.is_some()))
    }

    /// Whether some material has a participating medium (MDL's `material_volume`, handed
    /// over by the renderer before rendering). Found once, on the first question.
    pub fn has_media(&self) -> bool {
        *self.media.get_or_init(|| self.materials.iter().any(|m| m.medium.is_some()))
    }

    /// Light `light`'s shader as a [`SimpleLight`] (one shader, not a list, whose
    /// implementation reads as one with these constant parameters), else `None`. Found for
    /// every light on the first question.
    pub fn simple_light(&self, light: u32) -> Option<SimpleLight> {
        let all = self.simple_lights.get_or_init(|| {
            self.lights
                .iter()
                .map(|l| {
                    let node = self.graph.nodes.get(l.shader? as usize)?;
                    if node.next.is_some() {
                        return None;
                    }
                    (node.imp?.simple_light?)(&node.slots)
                })
                .collect()
        });
        all.get(light as usize).copied().flatten()
    }

    /// Whether some material has a participating medium that varies over its surface
    /// (evaluated where a ray enters: shadow walks then need each surface's shading state).
    /// Found once, on the first question.
    pub fn has_varying_media(&self) -> bool {
        *self.varying_media.get_or_init(|| self.materials.iter().any(|m| m.varying_medium.is_some()))
    }

    /// Whether a final gather ray from `org` along unit `dir` (world space) meets a portal
    /// light (either side; a light whose shader is marked [`portal`](crate::ShaderImpl::portal))
    /// before distance `tmax`: such rays find nothing, the portal brings that light in
    /// directly.
    pub fn blocks_gather(&self, org: Vec3A, dir: Vec3A, tmax: f32) -> bool {
        self.lights.iter().any(|l| {
            let portal =
                l.shader.and_then(|s| self.graph.nodes.get(s as usize)).and_then(|n| n.imp).is_some_and(|i| i.portal);
            portal && l.shape.as_ref().is_some_and(|s| s.intersect(l.origin, org, dir, 0.0, tmax).is_some())
        })
    }

    /// The light profile named `name` (a `lightprofile` element), if it was read.
    pub fn lightprofile(&self, name: &str) -> Option<Arc<crate::light::ies::Profile>> {
        let i = *self.graph.names.lightprofiles.get(name)?;
        self.lightprofiles.get(i as usize).cloned().flatten()
    }

    /// The light profile a `lightprofile` parameter's value tags, if it was read.
    pub fn lightprofile_of(&self, v: &Value) -> Option<&crate::light::ies::Profile> {
        match v.tag()? {
            super::value::Tag::Lightprofile(i) => self.lightprofiles.get(i as usize)?.as_deref(),
            _ => None,
        }
    }

    /// Whether any material is shaded by mental ray shaders (the classic engine's domain).
    pub fn has_classic_materials(&self) -> bool {
        self.materials.iter().any(|m| m.classic)
    }

    /// Whether a scene is for the classic engine: some material of it has a mental ray
    /// material shader (not an MDL material). Decided without compiling anything. A shader
    /// no declaration names (an exporter's helper: the shader graph warns and ignores it)
    /// decides nothing, so that one helper on an MDL scene's lamp does not send the whole
    /// scene to the classic engine. Options that ask for mental ray's progressive rendering,
    /// its brute-force GI "Next" or its iray mode (`"progressive" on`, `"gi" on`,
    /// `"iray" on`: [`scene::Options::asks_for_path_tracing`]) take the path engine whatever
    /// the materials.
    pub fn wants_classic(scene: &Scene) -> bool {
        if scene.options.asks_for_path_tracing() {
            return false;
        }
        let mental_ray = |decl: &str| {
            !decl.starts_with("mdl::") && (decl == "unified_material" || scene.library.declarations.contains_key(decl))
        };
        scene.materials.iter().any(|m| match &m.kind {
            MaterialKind::Material(defs) => defs.last().and_then(|d| d.shaders.as_ref()).is_some_and(|list| {
                list.0.first().is_some_and(|item| match item {
                    mi::ast::ShaderItem::Call { decl, .. } => mental_ray(&decl.text),
                    mi::ast::ShaderItem::Ref(r) => {
                        scene.library.shaders.get(&r.text).is_some_and(|d| match d.list.0.first() {
                            Some(mi::ast::ShaderItem::Call { decl, .. }) => mental_ray(&decl.text),
                            _ => true,
                        })
                    }
                    mi::ast::ShaderItem::Define { .. } => true,
                })
            }),
            MaterialKind::Shader(_) => false,
        })
    }
}

fn image_texture(image: texture::MipMap, t: &mi::ast::Texture) -> Texture {
    Texture::Image { image: Arc::new(image), filter: texture::filter_flag(t), kind: t.kind }
}

fn load_file(
    name: &str,
    span: Span,
    t: &mi::ast::Texture,
    options: &ShadingOptions,
    diags: &mut Vec<Diagnostic>,
) -> Texture {
    let Some(path) = options.search.resolve(name) else {
        diags.push(Diagnostic::warning(span, format!("texture file '{name}' not found; lookups of it give black")));
        return Texture::Missing;
    };
    match texture::load_image(&path) {
        Ok(loaded) => {
            if loaded.non_finite > 0 {
                diags.push(Diagnostic::warning(
                    span,
                    format!(
                        "texture file '{}': {} texel components are NaN or infinite; they are read as 0",
                        path.display(),
                        loaded.non_finite
                    ),
                ));
            }
            image_texture(loaded.image, t)
        }
        Err(e) => {
            diags.push(Diagnostic::warning(span, format!("texture file '{}': {e}", path.display())));
            Texture::Missing
        }
    }
}

/// The shader slots of one material.
fn material(b: &mut Builder, m: &scene::Material, lib: &scene::Library, registry: &Registry) -> MaterialShaders {
    let mut out = MaterialShaders { name: m.name.clone(), ..MaterialShaders::default() };
    match &m.kind {
        MaterialKind::Material(defs) => {
            // An incremental redefinition replaces the material as a whole.
            let Some(def) = defs.last() else { return out };
            out.surface = def.shaders.as_ref().and_then(|l| b.list(l, None));
            out.classic = out.surface.is_some();
            for stmt in &def.stmts {
                let Stmt::Kw(k) = stmt else { continue };
                let list = || match k.args.first() {
                    Some(Arg::Shaders(l)) => Some(l),
                    _ => None,
                };
                let build = |b: &mut Builder, l: Option<&ShaderList>| l.and_then(|l| b.list(l, None));
                match k.key {
                    "opaque" => out.opaque = true,
                    "shadow" => out.shadow = build(b, list()),
                    "volume" => out.volume = build(b, list()),
                    "environment" => out.environment = build(b, list()),
                    "photon" => out.photon = build(b, list()),
                    "displace" => out.displace = build(b, list()),
                    "bsdf" => out.bsdf = build(b, list()),
                    _ => {}
                }
            }
            if out.surface.is_none() && out.bsdf.is_some() {
                out.surface = out.bsdf;
                out.classic = true;
            }
            if out.surface.is_none() {
                out.surface = stand_in(b, m, lib, registry, def.span);
            }
        }
        MaterialKind::Shader(def) => {
            // An MDL material is no node itself; this builds the functions its parameters
            // connect to, which the path engine evaluates per hit.
            b.named(&def.name.text, def.name.span);
            out.surface = stand_in(b, m, lib, registry, def.name.span);
        }
    }
    out
}

/// The shader the options' string option `"shutter shape function"` names, if it names
/// one; a warning at the string option's statement when it names none (the full open/close
/// shape is used then).
fn shutter_shape(b: &mut Builder, options: &scene::Options, diags: &mut Vec<Diagnostic>) -> Option<NodeId> {
    const OPTION: &str = "shutter shape function";
    let value = options.string_options.get(OPTION)?;
    let span = options.string_option_spans.get(OPTION).copied().unwrap_or_default();
    let warn = |diags: &mut Vec<Diagnostic>, why: String| {
        diags.push(Diagnostic::warning(
            span,
            format!(
                "string option \"{OPTION}\" {why}: the shutter's shape is that of \"shutter full open\" and \
                 \"shutter full close\""
            ),
        ))
    };
    let scene::values::AttrValue::Str(name) = value else {
        warn(diags, "is not a shader's name".into());
        return None;
    };
    let node = b.named(name, span);
    if node.is_none() {
        warn(diags, format!("names '{name}', which is no shader"));
    }
    node
}

/// Iray: the shader named by the options attribute `environment_function` (the scene's
/// environment when the camera has none); a warning when no such shader is defined.
fn iray_environment(b: &mut Builder, options: &scene::Options, diags: &mut Vec<Diagnostic>) -> Option<NodeId> {
    let Some(scene::values::AttrValue::Str(name)) = options.attributes.get("environment_function") else {
        return None;
    };
    let node = b.named(name, Span::default());
    if node.is_none() {
        diags.push(Diagnostic::warning(
            Span::default(),
            format!("options attribute environment_function names '{name}', which is no shader: no environment"),
        ));
    }
    node
}

/// mira's Lambertian stand-in for a material without mental ray shaders, with the diffuse
/// colour and emission the path engine's translation finds.
fn stand_in(
    b: &mut Builder,
    m: &scene::Material,
    lib: &scene::Library,
    registry: &Registry,
    span: Span,
) -> Option<NodeId> {
    let (diffuse, emission) = registry.stand_in(m, lib);
    let c = |c: Vec3A| Value::Color(Color::new(c.x, c.y, c.z, 1.0));
    b.internal("mira_diffuse", &[("diffuse", c(diffuse)), ("emission", c(emission))], span)
}
