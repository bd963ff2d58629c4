//! `mira check`: parse files, print diagnostics and a one-line summary per file.

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use mi::stats::Stats;

use crate::IncludeArgs;

/// Arguments of `mira check`.
#[derive(clap::Args, Debug)]
pub struct CheckArgs {
    /// The .mi files to check.
    #[arg(required = true, value_name = "FILE")]
    files: Vec<PathBuf>,
    #[command(flatten)]
    include: IncludeArgs,
    /// Print warnings too (errors are always printed).
    #[arg(short = 'W', long)]
    warnings: bool,
    /// Also build the world (resolve names, flatten instances, tessellate), check the
    /// image's memory against --max-memory, compile the shaders (reading textures) as
    /// render does, and report instances, triangles, bounds,
    /// camera, lights and materials per object.
    #[arg(long)]
    scene: bool,
    #[command(flatten)]
    memory: crate::limits::MemoryArgs,
}

/// Runs the command.
pub fn run(args: &CheckArgs) -> ExitCode {
    let options = args.include.read_options();
    let mut failed = false;
    let stdout = std::io::stdout();
    let stderr = std::io::stderr();
    for path in &args.files {
        let parsed = match mi::parse_file(path, &options) {
            Ok(p) => p,
            Err(e) => {
                let _ = writeln!(stderr.lock(), "{}: error: {}", path.display(), e.message);
                failed = true;
                continue;
            }
        };
        let mut diags = parsed.diagnostics.clone();
        let mut world = None;
        if args.scene && !diags.has_errors() {
            let mut list = Vec::new();
            world = scene::Scene::build(&parsed, 0, &mut list);
            if let Some(w) = &world {
                let limit = args.memory.limit();
                if let Some(d) = crate::limits::check_film(w, w.camera.resolution, limit, false) {
                    // `mira render` renders such an image in strips when they fit and the
                    // scene writes one EXR file (its own outputs, or SCENE.exr).
                    let strips =
                        crate::limits::strip_rows(w.camera.resolution.0, crate::limits::user_buffers(w), limit.0);
                    let one_exr = crate::output::targets(&w.camera, None, path)
                        .is_ok_and(|t| t.len() == 1 && t[0].format.kind == imageio::Kind::Exr);
                    list.push(match strips {
                        Some(rows) if one_exr => mi::Diagnostic::warning(
                            d.span,
                            format!("{}: mira render renders it in strips of {rows} rows", d.message),
                        ),
                        _ => d,
                    });
                }
                // The shaders are compiled as render compiles them (textures read), so that
                // their errors are reported here too; only for a world without errors, which
                // the shader graph checks have made safe to compile.
                if !list.iter().any(|d| d.is_error()) {
                    let mut dirs: Vec<PathBuf> = path.parent().map(std::path::Path::to_path_buf).into_iter().collect();
                    dirs.extend(options.include_paths.iter().cloned());
                    let shading_options = shader::ShadingOptions {
                        search: shader::texture::SearchPath { dirs },
                        seed: 0,
                        finalgather_rays: None,
                    };
                    let (mut shading, mut shading_diags) = material::compile_shading(w, &shading_options);
                    // A module function named as the environment: compiled, or why not.
                    let search = material::mdl_modules::search_path(&w.library, &args.include.mdl_paths);
                    material::mdl_modules::environment::attach(&mut shading, w, search, &mut shading_diags);
                    list.extend(shading_diags);
                }
            }
            // MDL module materials: modules found, instances bound and type-checked.
            if let Some(w) = &world {
                let search = material::mdl_modules::search_path(&w.library, &args.include.mdl_paths);
                list.extend(material::mdl_modules::compile(&w.library, search).1);
            }
            diags.list.extend(list);
        }
        for d in &diags.list {
            if d.is_error() || args.warnings {
                let _ = write!(stderr.lock(), "{}", d.render(&parsed.sources));
            }
        }
        failed |= diags.has_errors();
        let _ = writeln!(stdout.lock(), "{}", summary(path, &parsed, &diags));
        if let Some(world) = &world {
            let _ = write!(stdout.lock(), "{}", scene::report::report(world));
            let search = material::mdl_modules::search_path(&world.library, &args.include.mdl_paths);
            let _ = write!(
                stdout.lock(),
                "{}",
                mdl_annotations(&material::mdl_modules::annotations::of_scene(&world.library, search))
            );
        }
    }
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}

/// The `MDL annotations:` section: each annotated module material the scene's shaders
/// instance, its definition's annotations, then one line per annotated parameter; empty
/// when there is none.
fn mdl_annotations(list: &[material::mdl_modules::annotations::MaterialAnnotations]) -> String {
    if list.is_empty() {
        return String::new();
    }
    let mut out = String::from("MDL annotations:\n");
    for m in list {
        let shaders: Vec<String> = m.shaders.iter().map(|s| format!("\"{s}\"")).collect();
        out += &format!("  {} (shader {}): {}\n", m.material, shaders.join(", "), m.annotations.join(", "));
        for (param, annotations) in &m.params {
            out += &format!("    {param}: {}\n", annotations.join(", "));
        }
    }
    out
}

fn plural(n: usize, word: &str) -> String {
    if n == 1 || word.ends_with('s') || word == "data" {
        return format!("{n} {word}");
    }
    match word.strip_suffix('y') {
        Some(stem) => format!("{n} {stem}ies"),
        None => format!("{n} {word}s"),
    }
}

/// `file: N errors, N warnings; element counts; geometry counts; shaders used`.
fn summary(path: &std::path::Path, parsed: &mi::Parsed, d: &mi::Diagnostics) -> String {
    let stats = Stats::of(&parsed.items);
    let mut parts = vec![format!("{}, {}", plural(d.error_count(), "error"), plural(d.warning_count(), "warning"))];
    let elements: Vec<String> = stats.elements.iter().map(|(k, n)| plural(*n, k)).collect();
    if !elements.is_empty() {
        parts.push(elements.join(", "));
    }
    let mut geometry = Vec::new();
    if stats.polygons > 0 {
        geometry.push(format!("{} ({} triangles)", plural(stats.polygons, "polygon"), stats.polygon_triangles));
    }
    if stats.trilist_triangles > 0 {
        geometry.push(format!("{} trilist triangles", stats.trilist_triangles));
    }
    if stats.subdivision_faces > 0 {
        geometry.push(plural(stats.subdivision_faces, "subdivision face"));
    }
    if stats.surfaces > 0 {
        geometry.push(plural(stats.surfaces, "free-form surface"));
    }
    if stats.hairs > 0 {
        geometry.push(plural(stats.hairs, "hair"));
    }
    if !geometry.is_empty() {
        parts.push(geometry.join(", "));
    }
    if stats.includes > 0 {
        parts.push(plural(stats.includes, "include"));
    }
    if !stats.shaders_used.is_empty() {
        let names: Vec<&str> = stats.shaders_used.iter().map(String::as_str).collect();
        parts.push(format!("shaders used: {}", names.join(" ")));
    }
    format!("{}: {}", path.display(), parts.join("; "))
}
