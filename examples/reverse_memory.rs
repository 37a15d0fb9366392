//! Heap of one reverse compensation, stage by stage (issue 27's memory
//! target): a counting global allocator prints the live heap at the start
//! of each stage of `reverse_compensate_with` (its progress calls) and the
//! peak of live bytes since the previous stage, then the result's own
//! size. wasm32 has 4-byte pointers and usizes, so the wasm figures of
//! index- and pointer-heavy structures are somewhat below these.
//!
//! ```text
//! LINES=1000000 node bench/node/large-program.bench.mjs --write /tmp/big1m.nc
//! cargo run --release --example reverse_memory -- /tmp/big1m.nc
//! ```
//!
//! tA 40 ms, T 15 ms, dt 2 ms, as `bench/node/reverse-large.bench.mjs`.
//! With `PARTS` set, the size of each part it holds instead, one at a
//! time.

use std::sync::atomic::Ordering::Relaxed;
use std::time::Instant;

#[path = "support/counting_alloc.rs"]
mod counting_alloc;
use counting_alloc::{mib, Counting, LIVE, PEAK};

#[global_allocator]
static A: Counting = Counting;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    use mtmotion::compensate::reverse::{reverse_compensate_with, ReverseConfig};
    let path = std::env::args()
        .nth(1)
        .ok_or("usage: reverse_memory FILE.nc")?;
    let text = std::fs::read_to_string(&path)?;
    let mut cfg = ReverseConfig::default();
    cfg.sim.t_a = 0.04;
    cfg.sim.t = mtmotion::toolpath::Lag::All(0.015);
    cfg.sim.dt = 0.002;
    if std::env::var_os("PARTS").is_some() {
        parts(&text);
        return Ok(());
    }
    let base = LIVE.load(Relaxed);
    PEAK.store(base, Relaxed);
    println!(
        "text {:.0} MiB live before the call; Segment {} B, SegmentStats {} B, Block {} B",
        mib(base),
        std::mem::size_of::<mtmotion::nc::program::Segment>(),
        std::mem::size_of::<mtmotion::toolpath::SegmentStats>(),
        std::mem::size_of::<mtmotion::nc::Block>(),
    );
    let t0 = Instant::now();
    let mut last = String::new();
    let mut overall = 0;
    let c = reverse_compensate_with(&text, &cfg, &mut |f, st| {
        if st != last {
            let peak = PEAK.swap(LIVE.load(Relaxed), Relaxed);
            overall = overall.max(peak);
            println!(
                "{:7.2} s  {f:.2} {st:42} live {:6.0} MiB  (peak since last stage {:6.0} MiB)",
                t0.elapsed().as_secs_f64(),
                mib(LIVE.load(Relaxed) - base),
                mib(peak - base),
            );
            last = st.to_string();
        }
        true
    })?;
    let peak = PEAK.load(Relaxed).max(overall);
    println!(
        "{:7.2} s  returned: live {:.0} MiB; peak {:.0} MiB above the text",
        t0.elapsed().as_secs_f64(),
        mib(LIVE.load(Relaxed) - base),
        mib(peak - base)
    );
    println!(
        "{:.1} -> {:.1} µm (x{:.3}), motion time {:.2} -> {:.2} s, {} regions, history {:?}",
        c.before.max_error_um,
        c.after.max_error_um,
        c.after.max_error_um / c.before.max_error_um,
        c.before.motion_time,
        c.after.motion_time,
        c.regions.len(),
        c.history_um
    );
    Ok(())
}

/// Prints the live bytes taken by what `f` returns, and the peak above
/// the start while it ran, MiB.
fn sized<T>(what: &str, f: impl FnOnce() -> T) -> T {
    let l0 = LIVE.load(Relaxed);
    PEAK.store(l0, Relaxed);
    let v = f();
    println!(
        "  {what:40} keeps {:7.1} MiB, peak above start {:7.1} MiB",
        mib(LIVE.load(Relaxed) - l0),
        mib(PEAK.load(Relaxed) - l0)
    );
    v
}

/// With `PARTS` set: the size of each part the compensation holds, one
/// at a time (parse, simulations, reference path, window base, regions,
/// window plans, edit, rebuilt command, written text and its reading).
fn parts(text: &str) {
    use mtmotion::compensate::reverse::{geometry, region, rounds};
    use mtmotion::nc::program::{parse_with, Keep, ParseOptions};
    let cfg = mtmotion::toolpath::SimConfig {
        t_a: 0.04,
        t: mtmotion::toolpath::Lag::All(0.015),
        dt: 0.002,
        ..Default::default()
    };
    let p = sized("parse (All)", || {
        parse_with(text, &ParseOptions::default()).unwrap()
    });
    println!(
        "  blocks {} modal {} segments {}",
        p.blocks.len(),
        p.modal.len(),
        p.segments.len()
    );
    let orig = &p.segments;
    let sim = sized("simulate original", || {
        mtmotion::toolpath::simulate(orig, orig, &cfg).unwrap()
    });
    println!(
        "  series {} kept, stride {}, stats {}",
        sim.t.len(),
        sim.series_stride,
        sim.segments.len()
    );
    let _st = sized("simulate_stats", || {
        mtmotion::toolpath::simulate_stats(orig, orig, &cfg).unwrap()
    });
    drop(_st);
    let _path = sized("Path::new", || mtmotion::toolpath::contour::Path::new(orig));
    drop(_path);
    let mut work = rounds::Work::for_program(p.segments.len(), sim.samples as u64);
    sized("set_original", || work.set_original(orig, &sim));
    let rg = sized("regions", || region::regions(&p));
    {
        let (cmd, at) =
            geometry::rebuild_indexed(orig, &rounds::identity(orig, vec![0.0; orig.len()]));
        let changed = vec![true; orig.len()];
        let w = sized("plan, all changed", || {
            mtmotion::toolpath::locality::plan(&cmd, &at, &changed, &cfg).unwrap()
        });
        println!("  {} windows", w.len());
        let mut few = vec![false; orig.len()];
        for i in (0..orig.len()).step_by(1000) {
            few[i] = true;
        }
        let w = sized("plan, every 1000th changed", || {
            mtmotion::toolpath::locality::plan(&cmd, &at, &few, &cfg).unwrap()
        });
        println!("  {} windows", w.len());
        let _l = sized("LocalStats::new", || rounds::LocalStats::new(orig, &work));
    }
    let _tl = sized("sample_estimate", || {
        mtmotion::toolpath::sample_estimate(orig, &cfg).unwrap()
    });
    let id = sized("identity edit", || {
        rounds::identity(orig, vec![0.0; orig.len()])
    });
    let cmd = sized("rebuild_indexed", || geometry::rebuild_indexed(orig, &id));
    drop(cmd);
    let segs = sized("rebuild", || geometry::rebuild(orig, &id));
    let nc = sized("write_source", || {
        mtmotion::nc::patch::write_source(text, &p, &segs)
    });
    let w = sized("parse written (Motion)", || {
        mtmotion::nc::files::parse_files_keeping(&nc, &[], &ParseOptions::default(), Keep::Motion)
            .map_err(|e| e.first())
            .unwrap()
    });
    let _s2 = sized("simulate written vs orig", || {
        mtmotion::toolpath::simulate(&w.segments, orig, &cfg).unwrap()
    });
    let _ = (&rg, &work);
}
