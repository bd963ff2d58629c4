//! Writes a generated geometry scene to standard output, for timing whole commands:
//!
//! ```sh
//! cargo run --release -p mi --example gen_mesh -- trilist 1000000 > /tmp/trilist.mi
//! cargo run --release -p mi --example gen_mesh -- group 1000000 > /tmp/group.mi
//! ```

#[path = "../benches/gen/mod.rs"]
mod gen;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let count: usize = args.get(2).and_then(|n| n.parse().ok()).unwrap_or(1_000_000);
    let text = match args.get(1).map(String::as_str) {
        Some("group") => gen::group_scene(count),
        _ => gen::trilist_scene(count),
    };
    print!("{text}");
}
