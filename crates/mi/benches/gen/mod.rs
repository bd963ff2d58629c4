//! Generated ASCII geometry files of a given size, written the way exporters write them
//! (six decimals at most, one vertex or face per line). Used by the parse benchmark and the
//! `gen_mesh` example.

use std::fmt::Write;

/// A number as exporters print it: rounded to six decimals, shortest form.
fn num(out: &mut String, x: f64) {
    let r = (x * 1e6).round() / 1e6;
    let _ = write!(out, "{}", if r == 0.0 { 0.0 } else { r });
}

/// Height of the generated terrain at (u, v).
fn height(u: f64, v: f64) -> f64 {
    (u * 12.9898).sin() * 0.25 + (v * 78.233).cos() * 0.125
}

/// A scene with one `trilist` object of at least `triangles` triangles (vertex layout
/// `p n t 2`, as Maya writes), an instance, and nothing else.
pub fn trilist_scene(triangles: usize) -> String {
    let side = ((triangles as f64 / 2.0).sqrt().ceil() as usize).max(1);
    let verts = (side + 1) * (side + 1);
    let mut s = String::with_capacity(verts * 80 + side * side * 2 * 24);
    let _ = writeln!(
        s,
        "object \"terrain\"\n    visible on\n    trilist vertex {verts} p n t 2\n    triangle {}\n    [",
        side * side * 2
    );
    for j in 0..=side {
        for i in 0..=side {
            let (u, v) = (i as f64 / side as f64, j as f64 / side as f64);
            for x in [u * 100.0, height(u, v), v * 100.0, 0.0, 1.0, 0.0, u, v] {
                num(&mut s, x);
                s.push(' ');
            }
            s.pop();
            s.push('\n');
        }
    }
    s.push_str("    ]\n    [\n");
    let row = side + 1;
    for j in 0..side {
        for i in 0..side {
            let a = j * row + i;
            let _ = writeln!(s, "{} {} {}\n{} {} {}", a, a + 1, a + row + 1, a, a + row + 1, a + row);
        }
    }
    s.push_str("    ]\n    end trilist\nend object\ninstance \"terrain_inst\" \"terrain\" end instance\n");
    s
}

/// A scene with one `group` of at least `polygons` convex quads, positions only.
pub fn group_scene(polygons: usize) -> String {
    let side = ((polygons as f64).sqrt().ceil() as usize).max(1);
    let verts = (side + 1) * (side + 1);
    let mut s = String::with_capacity(verts * 40 + side * side * 30);
    s.push_str("object \"grid\"\n    visible on\n    group\n");
    for j in 0..=side {
        for i in 0..=side {
            let (u, v) = (i as f64 / side as f64, j as f64 / side as f64);
            for x in [u * 100.0, height(u, v), v * 100.0] {
                num(&mut s, x);
                s.push(' ');
            }
            s.pop();
            s.push('\n');
        }
    }
    for k in 0..verts {
        let _ = writeln!(s, "v {k}");
    }
    let row = side + 1;
    for j in 0..side {
        for i in 0..side {
            let a = j * row + i;
            let _ = writeln!(s, "c {} {} {} {}", a, a + 1, a + row + 1, a + row);
        }
    }
    s.push_str("    end group\nend object\ninstance \"grid_inst\" \"grid\" end instance\n");
    s
}
