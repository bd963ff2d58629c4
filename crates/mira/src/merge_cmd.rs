//! `mira merge`: reassemble the parts of an image rendered by `mira render --part K/N` into
//! one image, after checking that they belong together.

use std::collections::HashMap;
use std::path::PathBuf;
use std::process::ExitCode;

use render::tonemap::ToneMapper;

use crate::output;
use crate::part_file::{self, PartFile};
use crate::render_cmd::load_scene;

/// Arguments of `mira merge`.
#[derive(clap::Args, Debug)]
pub struct MergeArgs {
    /// The part files (`mira render --part K/N` output), in any order.
    #[arg(value_name = "PART", required = true)]
    parts: Vec<PathBuf>,
    /// The image to write (format from the extension, as `mira render -o`).
    #[arg(short, long, value_name = "FILE")]
    output: PathBuf,
    /// Merge parts whose render was stopped early (SIGINT, SIGTERM) too.
    #[arg(long)]
    allow_partial: bool,
}

/// What makes parts belong to one image.
fn identity(p: &PartFile) -> (u64, u64, u64, u32, &'static str, usize, (u32, u32)) {
    let i = &p.info;
    (i.scene_hash, i.inputs_hash, i.settings_hash, i.part.count, i.split.name(), i.frame, i.size)
}

/// Every reason the `parts` (with their file names) do not make one whole image.
pub fn problems(parts: &[(PathBuf, PartFile)], allow_partial: bool) -> Vec<String> {
    let mut out = Vec::new();
    // The identity most parts share is the image's; the others are foreign.
    let mut votes: HashMap<_, usize> = HashMap::new();
    for (_, p) in parts {
        *votes.entry(identity(p)).or_default() += 1;
    }
    let Some((reference, _)) = votes.iter().max_by_key(|(k, n)| (**n, std::cmp::Reverse(**k))) else {
        return vec!["no parts given".into()];
    };
    let reference = *reference;
    let first = parts.iter().find(|(_, p)| identity(p) == reference).map(|(_, p)| &p.info);
    for (path, p) in parts {
        let (i, name) = (&p.info, path.display());
        if identity(p) == reference {
            continue;
        }
        let Some(r) = first else { continue };
        if i.scene_hash != r.scene_hash {
            out.push(format!(
                "{name} belongs to another scene ({}, text hash {:016x}; the other parts: {}, {:016x})",
                i.scene.display(),
                i.scene_hash,
                r.scene.display(),
                r.scene_hash
            ));
        } else if i.inputs_hash != r.inputs_hash {
            out.push(format!(
                "{name} was rendered against other files than the other parts (textures, light profiles or MDL \
                 modules changed: hash {:016x}, the other parts' {:016x})",
                i.inputs_hash, r.inputs_hash
            ));
        } else if i.settings_hash != r.settings_hash {
            let theirs: Vec<&str> = r.settings.lines().collect();
            let differ: Vec<&str> = i.settings.lines().filter(|l| !theirs.contains(l)).collect();
            out.push(format!("{name} was rendered with other settings ({})", differ.join(", ")));
        } else if i.frame != r.frame {
            out.push(format!("{name} is of frame {}, the other parts of frame {}", i.frame, r.frame));
        } else {
            out.push(format!(
                "{name} is part {} of a {}×{} image cut by {}, the others of {} parts of {}×{} by {}",
                i.part,
                i.size.0,
                i.size.1,
                i.split.name(),
                r.part.count,
                r.size.0,
                r.size.1,
                r.split.name()
            ));
        }
    }
    let Some(r) = first else { return out };
    let mut seen: HashMap<u32, &PathBuf> = HashMap::new();
    for (path, p) in parts.iter().filter(|(_, p)| identity(p) == reference) {
        if let Some(other) = seen.insert(p.info.part.index, path) {
            out.push(format!("part {} is given twice: {} and {}", p.info.part, other.display(), path.display()));
        }
        if p.info.partial && !allow_partial {
            out.push(format!(
                "{} is partial (its render was stopped at {} samples per pixel); merge it with --allow-partial",
                path.display(),
                p.info.spp
            ));
        }
    }
    for k in 1..=r.part.count {
        if !seen.contains_key(&k) {
            out.push(format!("part {k}/{} is missing", r.part.count));
        }
    }
    out
}

/// Runs the command.
pub fn run(args: &MergeArgs) -> ExitCode {
    let err = |msg: String| {
        eprintln!("mira: error: {msg}");
        ExitCode::FAILURE
    };
    let mut parts = Vec::new();
    let mut unreadable = Vec::new();
    for path in &args.parts {
        match part_file::read(path) {
            Ok(p) => parts.push((path.clone(), p)),
            Err(e) => unreadable.push(format!("cannot read part {}: {e}", path.display())),
        }
    }
    let mut all = unreadable;
    all.extend(problems(&parts, args.allow_partial));
    if !all.is_empty() {
        for p in &all {
            eprintln!("mira: error: {p}");
        }
        return err("the parts do not make one image; nothing written".into());
    }
    let info = &parts[0].1.info;
    // The scene gives the tone mapping and the buffers the outputs ask for.
    let loaded = match load_scene(&info.scene, &info.include, info.frame, Some(info.size), false, true) {
        Ok(l) => l,
        Err(e) => return err(format!("cannot read the parts' scene {}: {e}", info.scene.display())),
    };
    if loaded.content_hash != info.scene_hash {
        return err(format!(
            "the scene {} changed since the parts were rendered (text hash {:016x}, the parts': {:016x})",
            info.scene.display(),
            loaded.content_hash,
            info.scene_hash
        ));
    }
    let sc = &loaded.scene;
    let mut film = part_file::empty_film(info);
    for (path, p) in &parts {
        if let Err(e) = p.copy_into(&mut film) {
            return err(format!("cannot read part {}: {e}", path.display()));
        }
    }
    // The camera's output shaders (Maya's glow) on the reassembled image.
    for w in render::output_shaders::run(&mut film, &sc.camera, &sc.library) {
        eprintln!("mira: warning: {w}");
    }
    let tone = ToneMapper::for_camera(&sc.camera, &sc.library, info.classic);
    // -o's format by its extension, with the buffers the scene's outputs ask for.
    let targets = match output::targets(&sc.camera, Some(&args.output), &info.scene) {
        Ok(t) => t,
        Err(e) => return err(e),
    };
    for target in &targets {
        if let Err(e) = output::write(&film, target, &tone) {
            return err(format!("cannot write {}: {e}", target.path.display()));
        }
    }
    eprintln!("mira: wrote {} ({} parts)", args.output.display(), parts.len());
    ExitCode::SUCCESS
}
