//! Parse + simulate one large NC program natively, stage by stage, the way
//! `simulateToolPath` does in wasm (blocks kept only for the motion, the
//! text and the blocks dropped before the simulation): the time of each
//! stage and the process's peak resident memory after it (Linux `VmHWM`).
//! For profiling the 2 M-line program of `bench/node/large-program.bench.mjs`
//! (docs/performance.md §8):
//!
//! ```text
//! node bench/node/large-program.bench.mjs --write /tmp/big.nc
//! cargo run --release --example large_program -- /tmp/big.nc
//! perf record -g target/release/examples/large_program /tmp/big.nc
//! ```

use std::time::Instant;

use mtmotion::nc::files::parse_files_keeping;
use mtmotion::nc::program::{Keep, ParseOptions};
use mtmotion::toolpath::{simulate_with_progress, SimConfig};

/// Peak resident memory so far, MiB (0 where `/proc` is missing).
fn peak_mib() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        })
        .map_or(0.0, |kib| kib / 1024.0)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args()
        .nth(1)
        .ok_or("usage: large_program FILE.nc")?;
    let t0 = Instant::now();
    let text = std::fs::read_to_string(&path)?;
    println!(
        "read {} bytes in {:.2} s; peak {:.0} MiB",
        text.len(),
        t0.elapsed().as_secs_f64(),
        peak_mib()
    );
    if std::env::var_os("LEX_ONLY").is_some() {
        let t0 = Instant::now();
        let (blocks, _) = mtmotion::nc::lex_all(&text);
        println!(
            "lex alone: {:.2} s, {} blocks; peak {:.0} MiB",
            t0.elapsed().as_secs_f64(),
            blocks.len(),
            peak_mib()
        );
        return Ok(());
    }
    let t0 = Instant::now();
    let mut p = parse_files_keeping(&text, &[], &ParseOptions::default(), Keep::Motion)
        .map_err(|e| e.first().to_string())?;
    println!(
        "parse: {:.2} s, {} blocks, {} segments; peak {:.0} MiB",
        t0.elapsed().as_secs_f64(),
        p.blocks.len(),
        p.segments.len(),
        peak_mib()
    );
    drop(text);
    drop(std::mem::take(&mut p.blocks));
    let t0 = Instant::now();
    let cfg = SimConfig::default();
    let s = simulate_with_progress(&p.segments, &p.segments, &cfg, &mut |_| true)?;
    println!(
        "simulate: {:.2} s, {} samples, max error {:.3} µm at line {}, {} segment statistics; peak {:.0} MiB",
        t0.elapsed().as_secs_f64(),
        s.samples,
        s.max_error * 1e3,
        s.max_error_line,
        s.segments.len(),
        peak_mib()
    );
    Ok(())
}
