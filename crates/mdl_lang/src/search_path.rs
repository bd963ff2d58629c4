//! The MDL search path: the directories a module name `::a::b` is looked up in, as `a/b.mdl`.

use std::ffi::OsStr;
use std::path::{Path, PathBuf};

/// Directories searched for MDL modules, in order: the first that holds the file wins.
///
/// The order mira uses for a scene is: the scene's own directory, then each `-M DIR` given on
/// the command line, then the entries of the `MDL_PATHS` environment variable (split on `:`).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct MdlSearchPath {
    dirs: Vec<PathBuf>,
}

impl MdlSearchPath {
    /// An empty search path (only the built-in modules resolve).
    pub fn new() -> MdlSearchPath {
        MdlSearchPath::default()
    }

    /// The search path for a scene: `scene_dir` (if any), then `extra` (`-M` entries), then the
    /// entries of `mdl_paths` (the value of `MDL_PATHS`, split on `:`; empty entries skipped).
    pub fn for_scene(scene_dir: Option<&Path>, extra: &[PathBuf], mdl_paths: Option<&OsStr>) -> MdlSearchPath {
        let mut path = MdlSearchPath::new();
        if let Some(dir) = scene_dir {
            path.push(dir);
        }
        for dir in extra {
            path.push(dir);
        }
        if let Some(list) = mdl_paths.and_then(OsStr::to_str) {
            for entry in list.split(':').filter(|e| !e.is_empty()) {
                path.push(Path::new(entry));
            }
        }
        path
    }

    /// [`MdlSearchPath::for_scene`] with `MDL_PATHS` read from the environment.
    pub fn from_env(scene_dir: Option<&Path>, extra: &[PathBuf]) -> MdlSearchPath {
        let env = std::env::var_os("MDL_PATHS");
        MdlSearchPath::for_scene(scene_dir, extra, env.as_deref())
    }

    /// Appends a directory (a directory already on the path is not added twice).
    pub fn push(&mut self, dir: &Path) {
        if !self.dirs.iter().any(|d| d == dir) {
            self.dirs.push(dir.to_path_buf());
        }
    }

    /// The directories, in search order.
    pub fn dirs(&self) -> &[PathBuf] {
        &self.dirs
    }

    /// The relative file path of an absolute module name: `::a::b` gives `a/b.mdl`. `None` for a
    /// name that is not a sequence of MDL identifiers.
    pub fn relative_file(module: &str) -> Option<PathBuf> {
        let parts: Vec<&str> = module.strip_prefix("::")?.split("::").collect();
        let valid = |p: &&str| {
            !p.is_empty()
                && p.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_')
                && !p.as_bytes()[0].is_ascii_digit()
        };
        if !parts.iter().all(valid) {
            return None;
        }
        let mut path: PathBuf = parts.iter().collect();
        path.set_extension("mdl");
        Some(path)
    }

    /// The first file on the path for module `module` (absolute, `::a::b`).
    pub fn find(&self, module: &str) -> Option<PathBuf> {
        let rel = MdlSearchPath::relative_file(module)?;
        self.dirs.iter().map(|d| d.join(&rel)).find(|p| p.is_file())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn order_is_scene_then_m_then_env() {
        let p = MdlSearchPath::for_scene(
            Some(Path::new("/scene")),
            &[PathBuf::from("/m1"), PathBuf::from("/m2")],
            Some(OsStr::new("/e1::/e2:/m1")),
        );
        let dirs: Vec<_> = p.dirs().iter().map(|d| d.display().to_string()).collect();
        assert_eq!(dirs, ["/scene", "/m1", "/m2", "/e1", "/e2"]);
    }

    #[test]
    fn module_names_map_to_files() {
        assert_eq!(MdlSearchPath::relative_file("::a::b"), Some(PathBuf::from("a/b.mdl")));
        assert_eq!(MdlSearchPath::relative_file("::m"), Some(PathBuf::from("m.mdl")));
        assert_eq!(MdlSearchPath::relative_file("a::b"), None);
        assert_eq!(MdlSearchPath::relative_file("::a::..::b"), None);
        assert_eq!(MdlSearchPath::relative_file("::a::"), None);
    }
}
