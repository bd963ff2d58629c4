//! Parses a file several times in one process and prints the best throughput, peak
//! allocation is reported by the operating system (`/usr/bin/time -v`):
//!
//! ```sh
//! cargo run --release -p mi --example parse_speed -- /tmp/trilist.mi 5
//! ```

use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let path = args.get(1).expect("usage: parse_speed FILE [RUNS]");
    let runs: usize = args.get(2).and_then(|n| n.parse().ok()).unwrap_or(5);
    let bytes = std::fs::read(path).expect("readable file");
    let mut best = f64::INFINITY;
    for _ in 0..runs {
        let copy = bytes.clone();
        let start = Instant::now();
        let parsed = mi::parse_source(mi::Origin::Memory(path.clone()), copy, &mi::ReadOptions::default());
        let secs = start.elapsed().as_secs_f64();
        assert!(!parsed.diagnostics.has_errors(), "{}", parsed.diagnostics.render(&parsed.sources));
        best = best.min(secs);
        drop(parsed);
    }
    println!(
        "{path}: {} bytes, best of {runs}: {:.1} ms, {:.0} MB/s",
        bytes.len(),
        best * 1e3,
        bytes.len() as f64 / best / 1e6
    );
}
