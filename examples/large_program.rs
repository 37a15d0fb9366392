//! Check and simulate one large NC program natively, stage by stage, the
//! way `checkNc` then `simulateToolPathColumns` do in wasm (blocks kept
//! only for the motion, the text and the blocks dropped before the
//! simulation): the time of each stage, the heap it had live at most (a
//! counting global allocator: the figure that sets the wasm memory, which
//! only grows) and the process's peak resident memory (Linux `VmHWM`).
//! For profiling the 2 M-line program of `bench/node/large-program.bench.mjs`
//! (docs/performance.md §8):
//!
//! ```text
//! node bench/node/large-program.bench.mjs --write /tmp/big.nc
//! cargo run --release --example large_program -- /tmp/big.nc
//! perf record -g target/release/examples/large_program /tmp/big.nc
//! ```
//!
//! `STREAM=1`: the program is read as `NcStream` reads it, in 1 MiB
//! chunks of the file, never whole (`checkNc` and
//! `simulateToolPathColumns` of the wasm `NcStream`).
//!
//! The heap figures are 64-bit: a `usize`, a pointer and a `Vec` header
//! are twice their wasm32 size, so the wasm figures are somewhat smaller.

use std::sync::atomic::Ordering::Relaxed;
use std::time::Instant;

use mtmotion::nc::files::parse_files_owned;
use mtmotion::nc::program::{Keep, ParseOptions, Program};
use mtmotion::nc::stream::NcStream;
use mtmotion::nc::summary::summarize;
use mtmotion::toolpath::{simulate_columns_owned, SimConfig};

#[path = "support/counting_alloc.rs"]
mod counting_alloc;
use counting_alloc::{mib, Counting, LIVE, PEAK};

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Heap live now and at most since the last call, MiB; resets the peak.
fn heap() -> String {
    let live = LIVE.load(Relaxed);
    let peak = PEAK.swap(live, Relaxed);
    format!(
        "heap peak {:.0} MiB, live after {:.0} MiB",
        mib(peak),
        mib(live)
    )
}

/// Peak resident memory so far, MiB (0 where `/proc` is missing).
fn peak_rss() -> f64 {
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
    let stream = std::env::var_os("STREAM").is_some_and(|v| v == "1");
    let opts = ParseOptions::default();
    // the program for the motion, read whole or streamed
    let parse = || -> Result<Program, Box<dyn std::error::Error>> {
        if stream {
            use std::io::Read;
            let mut file = std::fs::File::open(&path)?;
            let mut s = NcStream::new();
            let mut chunk = vec![0; 1 << 20];
            loop {
                let n = file.read(&mut chunk)?;
                if n == 0 {
                    break;
                }
                s.push(&chunk[..n]).map_err(|e| e.first().to_string())?;
            }
            Ok(s.finish(&opts, Keep::Motion)
                .map_err(|e| e.first().to_string())?)
        } else {
            let text = std::fs::read_to_string(&path)?;
            Ok(parse_files_owned(text, Vec::new(), &opts, Keep::Motion)
                .map_err(|e| e.first().to_string())?)
        }
    };
    if std::env::var_os("LEX_ONLY").is_some() {
        let text = std::fs::read_to_string(&path)?;
        let t0 = Instant::now();
        let (blocks, _) = mtmotion::nc::lex_all(&text);
        println!(
            "lex alone: {:.2} s, {} blocks; {}",
            t0.elapsed().as_secs_f64(),
            blocks.len(),
            heap()
        );
        return Ok(());
    }
    let cfg = SimConfig::default();
    // checkNc: parse for the motion, summarise, drop all.
    let t0 = Instant::now();
    let p = parse()?;
    let summary = summarize(&p, cfg.rapid_feed);
    println!(
        "check: {:.2} s, {} blocks, {} segments, {:.0} s of motion; {}",
        t0.elapsed().as_secs_f64(),
        p.blocks.len(),
        p.segments.len(),
        summary.motion_time,
        heap()
    );
    drop(p);
    // simulateToolPathColumns: its own copy of the text, parsed again.
    let t0 = Instant::now();
    let mut p = parse()?;
    drop(std::mem::take(&mut p.blocks));
    println!("parse: {:.2} s; {}", t0.elapsed().as_secs_f64(), heap());
    let t0 = Instant::now();
    let segments = std::mem::take(&mut p.segments);
    let (s, columns) = simulate_columns_owned(segments, &cfg, &mut |_| true)?;
    println!(
        "simulate: {:.2} s, {} samples, max error {:.3} µm at line {}, {} segment statistics; {}",
        t0.elapsed().as_secs_f64(),
        s.samples,
        s.max_error * 1e3,
        s.max_error_line,
        columns.line.len(),
        heap()
    );
    println!("peak RSS {:.0} MiB", peak_rss());
    Ok(())
}
