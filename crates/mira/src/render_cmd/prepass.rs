//! The classic engine's pre-passes of a frame: computed within `--time`, or read from a
//! `mira prepass` file.

use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use render::prepare::Prepared;
use render::prepass_file::PrepassKey;

/// Runs the pre-passes (`prepare`) with a stop flag that is set once `time` seconds have
/// passed or `cancel` is set, so that `--time` bounds the photon and final gather passes as
/// well as the sample passes (they stop early with what they have); warns when the clock
/// stopped them.
pub(super) fn prepare_within<T>(time: Option<f64>, cancel: &AtomicBool, prepare: impl FnOnce(&AtomicBool) -> T) -> T {
    let stop = AtomicBool::new(false);
    let start = Instant::now();
    let done = AtomicBool::new(false);
    let out = std::thread::scope(|s| {
        s.spawn(|| {
            while !done.load(Ordering::Relaxed) {
                if cancel.load(Ordering::Relaxed) || time.is_some_and(|t| start.elapsed().as_secs_f64() >= t) {
                    stop.store(true, Ordering::SeqCst);
                    return;
                }
                std::thread::sleep(Duration::from_millis(5));
            }
        });
        let out = prepare(&stop);
        done.store(true, Ordering::Relaxed);
        out
    });
    if stop.load(Ordering::SeqCst) && !cancel.load(Ordering::Relaxed) {
        if let Some(t) = time {
            eprintln!(
                "mira: warning: --time {t} s ran out in the pre-passes (photon maps, final gather points); they \
                 stopped early with what they had, and one sample pass follows"
            );
        }
    }
    out
}

/// The pre-passes saved in `file` (`--prepass`) by `mira prepass` for the scene and
/// settings `key` names, put into `shading`; an error when the engine is not the classic
/// one (`classic`), the file cannot be read or was made for something else.
pub(super) fn read_saved<'a>(
    file: &Path,
    classic: bool,
    key: &PrepassKey,
    shading: &shader::Shading,
) -> Result<Prepared<'a>, String> {
    if !classic {
        return Err(format!(
            "--prepass {}: the path engine has no pre-pass to read (it is for the classic engine)",
            file.display()
        ));
    }
    let bytes = std::fs::read(file).map_err(|e| format!("cannot read {}: {e}", file.display()))?;
    let saved = render::prepass_file::decode(&bytes, &file.display().to_string(), key)?;
    render::prepare::prepare_saved(shading, saved).ok_or_else(|| "the pre-passes were already made".into())
}
