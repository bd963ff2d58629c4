//! The registry through which shader libraries plug into the shader model: each library
//! (the base library, the Architectural library, MDL's functions, Maya's…) describes itself
//! as a [`Library`] — its shader implementations (each with its optional behaviours: how it
//! scatters photons, whether it is a portal) and the `.mi` declarations it brings — and a
//! [`Registry`] holds the
//! libraries one render uses. The model names no library: whoever renders assembles the
//! registry (the `material` crate has mira's full set).

use std::fmt;
use std::sync::{Arc, OnceLock};

use glam::Vec3A;
use mi::ast;

use crate::decl::{Builtins, Decls};
use crate::ShaderImpl;

/// The classic engine's stand-in colours for a material that has no mental ray shader (an
/// MDL material): its diffuse reflectance and its emitted radiance, linear RGB.
pub type StandInHook = fn(material: &scene::Material, lib: &scene::Library) -> (Vec3A, Vec3A);

/// A shader library as the model sees it.
pub struct Library {
    /// Its name, for messages (`base`, `architectural`).
    pub name: &'static str,
    /// The shaders it implements.
    pub shaders: &'static [&'static ShaderImpl],
    /// Declarations it brings beyond mental ray's standard `.mi` files (`(file name, .mi
    /// text)`), used where a scene does not declare the shader itself.
    pub declarations: &'static [(&'static str, &'static str)],
}

impl Library {
    /// What is wrong with the library's own description, one message each: a shader with no
    /// declaration (among mental ray's standard ones and the library's), a parameter its
    /// code reads that the declaration lacks (it would silently read zero), a name
    /// registered twice. Each library's tests assert that this is empty.
    pub fn problems(&'static self) -> Vec<String> {
        let decls = Registry::new(&[self]).builtin_decls();
        let mut problems = Vec::new();
        for imp in self.shaders {
            let Some(decl) = decls.get(imp.name) else {
                problems.push(format!("{} is not declared", imp.name));
                continue;
            };
            for p in imp.params.iter().filter(|p| decl.param(p).is_none()) {
                problems.push(format!("{} has no parameter '{p}'", imp.name));
            }
        }
        let mut names: Vec<&str> = self.shaders.iter().map(|s| s.name).collect();
        names.sort_unstable();
        for pair in names.windows(2).filter(|w| w[0] == w[1]) {
            problems.push(format!("{} is registered twice", pair[0]));
        }
        problems
    }
}

impl fmt::Debug for Library {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Library").field("name", &self.name).field("shaders", &self.shaders.len()).finish()
    }
}

/// The libraries of one render, with their shaders and declarations indexed by name.
pub struct Registry {
    libraries: Vec<&'static Library>,
    builtins: Arc<Builtins>,
    stand_in: Option<StandInHook>,
}

impl fmt::Debug for Registry {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Registry").field("libraries", &self.libraries).finish()
    }
}

impl Default for Registry {
    /// No library: mental ray's standard declarations and the model's internal ones only.
    fn default() -> Registry {
        Registry::new(&[])
    }
}

impl Registry {
    /// The shared registry without libraries ([`Registry::default`]).
    pub fn empty() -> Arc<Registry> {
        static EMPTY: OnceLock<Arc<Registry>> = OnceLock::new();
        EMPTY.get_or_init(|| Arc::new(Registry::default())).clone()
    }

    /// A registry of `libraries`, earlier ones winning where two implement the same name,
    /// with mental ray's standard declarations (`base.mi`, `physics.mi`, `contour.mi`,
    /// `architectural.mi`, `production.mi`), the model's internal ones and the libraries'.
    pub fn new(libraries: &[&'static Library]) -> Registry {
        let shaders: Vec<_> = libraries.iter().flat_map(|l| l.shaders.iter().copied()).collect();
        let texts = libraries.iter().flat_map(|l| l.declarations.iter().copied());
        Registry { libraries: libraries.to_vec(), builtins: Arc::new(Builtins::new(texts, &shaders)), stand_in: None }
    }

    /// The declarations of a scene (`declarations`, its `declare` statements) over the
    /// built-in ones, with the libraries' implementations.
    pub fn decls<'a>(&self, declarations: impl IntoIterator<Item = &'a ast::Declaration>) -> Decls {
        Decls::new(declarations, self.builtins.clone())
    }

    /// The built-in declarations alone (no scene), with the libraries' implementations.
    pub fn builtin_decls(&self) -> Decls {
        self.decls([])
    }

    /// The same registry, with `hook` giving the classic engine's stand-in colours.
    pub fn with_stand_in(mut self, hook: StandInHook) -> Registry {
        self.stand_in = Some(hook);
        self
    }

    /// The libraries, in lookup order.
    pub fn libraries(&self) -> &[&'static Library] {
        &self.libraries
    }

    /// The implementation of the declared shader `name` (an MDL signature is ignored), if a
    /// library has one.
    pub fn implementation(&self, name: &str) -> Option<&'static ShaderImpl> {
        self.builtins.implementation(name)
    }

    /// The stand-in colours (diffuse, emission) of a material without mental ray shaders;
    /// mid grey and black without a hook.
    pub fn stand_in(&self, material: &scene::Material, lib: &scene::Library) -> (Vec3A, Vec3A) {
        match self.stand_in {
            Some(hook) => hook(material, lib),
            None => (Vec3A::splat(0.5), Vec3A::ZERO),
        }
    }
}
