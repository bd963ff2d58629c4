//! A plain-text report of a built scene, for `mira check --scene`.

use std::fmt::Write;

use crate::light::{AreaShape, LightKind};
use crate::{MaterialKind, Scene};

fn v3(v: glam::DVec3) -> String {
    let r = |x: f64| {
        let s = format!("{:.4}", x);
        let s = s.trim_end_matches('0').trim_end_matches('.').to_string();
        if s == "-0" {
            "0".into()
        } else {
            s
        }
    };
    format!("({}, {}, {})", r(v.x), r(v.y), r(v.z))
}

/// The report: counts, bounds, camera, lights, materials per object.
pub fn report(scene: &Scene) -> String {
    let mut s = String::new();
    let memory: usize = scene.objects.iter().map(|o| o.geometry.mesh.memory_bytes()).sum();
    let _ = writeln!(
        s,
        "  instances: {} objects, {} lights; objects: {}; triangles: {} unique, {} instanced; mesh memory {:.2} MiB",
        scene.instances.len(),
        scene.lights.len(),
        scene.objects.len(),
        scene.unique_triangles(),
        scene.instanced_triangles(),
        memory as f64 / (1 << 20) as f64
    );
    if let Some((lo, hi)) = scene.bounds() {
        let _ = writeln!(s, "  bounds: {} to {}", v3(lo), v3(hi));
    }
    let c = &scene.camera;
    let _ = writeln!(
        s,
        "  camera '{}' (instance '{}'): at {} looking along {}, up {}, {}x{} pixels, field of view {:.2}° x {:.2}°{}",
        c.name,
        c.instance,
        v3(c.position()),
        v3(c.forward()),
        v3(c.up()),
        c.resolution.0,
        c.resolution.1,
        c.fov_x().to_degrees(),
        c.fov_y().to_degrees(),
        if c.focal.is_none() { " (orthographic)" } else { "" }
    );
    let o = &scene.options;
    let _ = writeln!(
        s,
        "  options '{}': {:?} dialect, samples {} {}, filter {:?} {}x{}, trace depth {} {} {}, progressive max samples {}",
        o.name,
        o.dialect,
        o.samples.0,
        o.samples.1,
        o.filter.kind,
        o.filter.width,
        o.filter.height,
        o.trace_depth.0,
        o.trace_depth.1,
        o.trace_depth.2,
        o.progressive.max_samples
    );
    for l in &scene.lights {
        let kind = match (l.kind, &l.area) {
            (_, Some(a)) => match &a.shape {
                AreaShape::Rectangle { edge_u, edge_v, .. } => {
                    format!("rectangle {} x {}", edge_u.length(), edge_v.length())
                }
                AreaShape::Disc { radius, .. } => format!("disc radius {radius:.4}"),
                AreaShape::Sphere { radius } => format!("sphere radius {radius:.4}"),
                AreaShape::Cylinder { radius, .. } => format!("cylinder radius {radius:.4}"),
                AreaShape::Object { instance } => format!("object light '{instance}'"),
                AreaShape::User => "user area".into(),
            },
            (LightKind::Point, None) => "point".into(),
            (LightKind::Spot, None) => "spot".into(),
            (LightKind::Directional, None) => "directional".into(),
        };
        let facing = l.area_normal().map(|n| format!(", facing {}", v3(n))).unwrap_or_default();
        let dir =
            if matches!(l.kind, LightKind::Point) { String::new() } else { format!(", direction {}", v3(l.direction)) };
        let _ = writeln!(
            s,
            "  light '{}' (instance '{}'): {kind} at {}{dir}{facing}{}",
            l.name,
            l.instance,
            v3(l.position),
            if l.visible { ", visible" } else { "" }
        );
    }
    for obj in &scene.objects {
        let mut names: Vec<String> = Vec::new();
        for inst in scene.instances.iter().filter(|i| scene.objects[i.object as usize].name == obj.name) {
            for m in inst.materials.iter().flatten() {
                let m = &scene.materials[*m as usize];
                let label = match &m.kind {
                    MaterialKind::Material(_) => m.name.clone(),
                    MaterialKind::Shader(d) => match d.list.0.first() {
                        Some(mi::ast::ShaderItem::Call { decl, .. }) => format!("{} ({})", m.name, decl.text),
                        _ => m.name.clone(),
                    },
                };
                if !names.contains(&label) {
                    names.push(label);
                }
            }
        }
        let mesh = &obj.geometry.mesh;
        let hair: usize = obj.geometry.hair.iter().map(|h| h.len()).sum();
        let _ = writeln!(
            s,
            "  object '{}': {} triangles, {} vertices{}; materials: {}",
            obj.name,
            mesh.triangles.len(),
            mesh.positions.len(),
            if hair > 0 { format!(", {hair} hairs") } else { String::new() },
            if names.is_empty() { "none".to_string() } else { names.join(", ") }
        );
    }
    s
}
