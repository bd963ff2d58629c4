//! `mira render` writes the motion buffer (`m`) to EXR files when an output asks for it.

use std::path::Path;
use std::process::Command;

use exr::prelude::*;

/// An orthographic 2×2 view at 8×8 pixels (4 pixels per unit) onto a quad at z = −5
/// moving +1 in x and −0.5 in y (world) over the shutter: (4, −2) raster pixels (y up).
fn scene(out: &Path, output: &str) -> String {
    format!(
        r#"
options "opt" filter box 1 1 shutter 0 1 end options
camera "cam" focal infinity aperture 2 aspect 1 resolution 8 8
    {output} "{}"
end camera
instance "cam_inst" "cam" end instance
material "m" "mib_illum_lambert" ("ambience" 1 1 1, "ambient" 0.5 0.5 0.5) end material
object "quad" group
    -2 -2 -5  2 -2 -5  2 2 -5  -2 2 -5
    v 0 v 1 v 2 v 3
    c "m" 0 1 2 3
end group end object
instance "quad_inst" "quad" motion transform 1 0 0 0  0 1 0 0  0 0 1 0  -1 0.5 0 1 end instance
instgroup "root" "cam_inst" "quad_inst" end instgroup
render "root" "cam_inst" "opt"
"#,
        out.display()
    )
}

/// Renders `output` (an `output` statement without its file name) with `engine`; the EXR's
/// channels by name.
fn render(tag: &str, output: &str, engine: &str) -> Vec<(String, Vec<f32>)> {
    let dir = std::env::temp_dir().join(format!("mira-motion-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("m.exr");
    let mi = dir.join("m.mi");
    std::fs::write(&mi, scene(&out, output)).unwrap();
    let run = Command::new(env!("CARGO_BIN_EXE_mira"))
        .args(["render", "--spp", "1", "--engine", engine, mi.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let image = read_all_flat_layers_from_file(&out).unwrap();
    let channels = image.layer_data[0]
        .channel_data
        .list
        .iter()
        .map(|c| (c.name.to_string(), c.sample_data.values_as_f32().collect()))
        .collect();
    std::fs::remove_dir_all(&dir).ok();
    channels
}

fn channel<'a>(channels: &'a [(String, Vec<f32>)], name: &str) -> Option<&'a Vec<f32>> {
    channels.iter().find(|(n, _)| n == name).map(|(_, v)| v)
}

#[test]
fn a_moving_quad_writes_its_raster_motion() {
    for engine in ["classic", "path"] {
        let channels = render(engine, r#"output "+rgba,m" "exr""#, engine);
        let (mx, my) = (channel(&channels, "M.X").unwrap(), channel(&channels, "M.Y").unwrap());
        assert_eq!(mx.len(), 64);
        for (i, (x, y)) in mx.iter().zip(my).enumerate() {
            assert!((x - 4.0).abs() < 1e-3 && (y + 2.0).abs() < 1e-3, "{engine}: pixel {i}: ({x}, {y})");
        }
        assert!(channel(&channels, "R").is_some(), "colour is written too");
    }
}

#[test]
fn motion_is_written_only_when_asked() {
    let channels = render("plain", r#"output "rgba" "exr""#, "classic");
    assert!(channel(&channels, "M.X").is_none());
    assert!(channel(&channels, "R").is_some());
}
