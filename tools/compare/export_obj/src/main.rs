//! Writes mira's tessellated world (scene layer, after `Scene::build`) as one Wavefront
//! OBJ per instance, in WORLD space, plus `scene.json` describing the camera, the lights
//! and the materials (with their diffuse colours as mira renders them).
//!
//! usage: export_obj SCENE.mi OUTDIR

use std::fmt::Write as _;
use std::path::Path;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() != 3 {
        eprintln!("usage: export_obj SCENE.mi OUTDIR");
        std::process::exit(2);
    }
    let out = Path::new(&args[2]);
    std::fs::create_dir_all(out).expect("create OUTDIR");
    let parsed = mi::parse_file(Path::new(&args[1]), &mi::ReadOptions::default()).expect("read scene");
    let mut diags = Vec::new();
    let scene = scene::Scene::build(&parsed, 0, &mut diags).expect("build scene");
    for d in &diags {
        eprintln!("diagnostic: {d:?}");
    }

    let mat_name = |i: Option<u32>| -> String {
        match i {
            Some(i) => scene.materials[i as usize].name.clone(),
            None => "(no material)".to_string(),
        }
    };

    let mut json = String::from("{\n  \"instances\": [\n");
    let mut first = true;
    for (k, inst) in scene.instances.iter().enumerate() {
        let mesh = &scene.objects[inst.object as usize].geometry.mesh;
        if mesh.triangles.is_empty() {
            continue;
        }
        let m = inst.object_to_world;
        // Normals go with the inverse transpose (as mira does).
        let nm = glam::DMat3::from_mat4(m).inverse().transpose();
        let file = format!("inst{k:03}.obj");
        let mut s = String::new();
        writeln!(s, "# instance '{}' object '{}' (world space)", inst.name, mesh.name).unwrap();
        for p in &mesh.positions {
            let w = m.transform_point3(p.as_dvec3());
            writeln!(s, "v {:.9} {:.9} {:.9}", w.x, w.y, w.z).unwrap();
        }
        let has_n = !mesh.normals.is_empty();
        for n in &mesh.normals {
            let w = (nm * n.as_dvec3()).normalize();
            writeln!(s, "vn {:.9} {:.9} {:.9}", w.x, w.y, w.z).unwrap();
        }
        // A transform with negative determinant mirrors: mira keeps the counter-clockwise
        // side (in object space) as the front through the inverse transpose; in world space
        // that is the clockwise side, so flip the winding to keep front = CCW in world.
        let flip = m.determinant() < 0.0;
        let mut current: Option<String> = None;
        let mut used = Vec::new();
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let slot = mesh.triangle_slots[t] as usize;
            let name = mat_name(inst.materials.get(slot).copied().flatten());
            if current.as_deref() != Some(name.as_str()) {
                writeln!(s, "usemtl {name}").unwrap();
                if !used.contains(&name) {
                    used.push(name.clone());
                }
                current = Some(name);
            }
            let [a, b, c] = if flip { [tri[0], tri[2], tri[1]] } else { *tri };
            if has_n {
                writeln!(s, "f {0}//{0} {1}//{1} {2}//{2}", a + 1, b + 1, c + 1).unwrap();
            } else {
                writeln!(s, "f {} {} {}", a + 1, b + 1, c + 1).unwrap();
            }
        }
        std::fs::write(out.join(&file), s).expect("write obj");
        if !first {
            json.push_str(",\n");
        }
        first = false;
        write!(
            json,
            "    {{\"name\": {:?}, \"object\": {:?}, \"file\": {:?}, \"triangles\": {}, \"mirrored\": {}, \"materials\": {:?}}}",
            inst.name,
            mesh.name,
            file,
            mesh.triangles.len(),
            flip,
            used
        )
        .unwrap();
        eprintln!("{file}: '{}' ({} triangles, {} vertices)", inst.name, mesh.triangles.len(), mesh.positions.len());
    }
    json.push_str("\n  ],\n");
    // Camera: camera → world (column-major, column vectors; camera looks down −Z, +Y up).
    let c = &scene.camera;
    let v3 = |v: glam::DVec3| format!("[{}, {}, {}]", v.x, v.y, v.z);
    writeln!(
        json,
        "  \"camera\": {{\"name\": {:?}, \"focal\": {}, \"aperture\": {}, \"aspect\": {}, \"resolution\": [{}, {}], \"camera_to_world\": {:?}}},",
        c.instance,
        c.focal.map_or("null".to_string(), |f| f.to_string()),
        c.aperture,
        c.aspect,
        c.resolution.0,
        c.resolution.1,
        c.camera_to_world.to_cols_array()
    )
    .unwrap();
    json.push_str("  \"lights\": [\n");
    for (i, l) in scene.lights.iter().enumerate() {
        let shape = match l.area.as_ref().map(|a| &a.shape) {
            Some(scene::AreaShape::Rectangle { edge_u, edge_v, normal }) => format!(
                "\"rectangle\", \"edge_u\": {}, \"edge_v\": {}, \"normal\": {}",
                v3(*edge_u),
                v3(*edge_v),
                v3(*normal)
            ),
            Some(other) => format!("{:?}", format!("{other:?}")),
            None => "\"point\"".to_string(),
        };
        write!(
            json,
            "    {{\"name\": {:?}, \"position\": {}, \"visible\": {}, \"shader\": {:?}, \"shape\": {}}}{}\n",
            l.instance,
            v3(l.position),
            l.visible,
            format!("{:?}", l.shader),
            shape,
            if i + 1 < scene.lights.len() { "," } else { "" }
        )
        .unwrap();
    }
    json.push_str("  ]\n}\n");
    std::fs::write(out.join("scene.json"), json).expect("write json");
}
