//! Reverse compensation over the shared NC corpus, one line per program:
//! the measurement behind issue 27's must-shows (after/before maximum
//! error, motion-time growth, unchanged programs with their reason,
//! refusals, time per program).
//!
//! Run: `cargo run --release --example reverse_corpus [dt_ms] [file…]`
//! (tA 40 ms, T 15 ms, dt 2 ms unless given; with `RC_STAGES` set, the
//! time at which each stage starts is printed; with `RC_DIGEST` set, a
//! hash of each written program and its numbers to full precision, to
//! compare two builds bit for bit). The corpus is read from
//! `../shared/nc_corpus` or `MTMOTION_NC_CORPUS` (see
//! `tests/support/corpus.rs`).

#[cfg(not(target_arch = "wasm32"))]
#[path = "../tests/support/corpus.rs"]
mod corpus;

#[cfg(not(target_arch = "wasm32"))]
fn main() -> Result<(), Box<dyn std::error::Error>> {
    use mtmotion::compensate::reverse::ReverseConfig;
    let mut args = std::env::args().skip(1);
    let dt_ms: f64 = args.next().map(|s| s.parse()).transpose()?.unwrap_or(2.0);
    let only: Vec<String> = args.collect();
    let dir = corpus::dir()?;
    let mut cfg = ReverseConfig::default();
    cfg.sim.t_a = 0.04;
    cfg.sim.t = mtmotion::toolpath::Lag::All(0.015);
    cfg.sim.dt = dt_ms * 1e-3;
    // PAPER set: qiu's method (step 1, no corner spikes) for comparison.
    if std::env::var_os("PAPER").is_some() {
        cfg.step = 1.0;
        cfg.corner_spikes = false;
    }
    let mut ratios = Vec::new();
    let (mut unchanged, mut refused) = (0, 0);
    for name in corpus::names(&dir) {
        if !only.is_empty() && !only.iter().any(|o| name.contains(o.as_str())) {
            continue;
        }
        let text = std::fs::read_to_string(dir.join(&name)).unwrap_or_else(|_| {
            String::from_utf8_lossy(&std::fs::read(dir.join(&name)).unwrap()).into_owned()
        });
        if mtmotion::nc::program::parse(&text).is_err() {
            println!("{name:48} does not parse (out of scope)");
            continue;
        }
        let start = std::time::Instant::now();
        let t0 = std::time::Instant::now();
        let mut last = String::new();
        let res =
            mtmotion::compensate::reverse::reverse_compensate_with(&text, &cfg, &mut |f, st| {
                if std::env::var("RC_STAGES").is_ok() && st != last {
                    eprintln!("  {:7.2} s  {f:.2} {st}", t0.elapsed().as_secs_f64());
                    last = st.to_string();
                }
                true
            });
        match res {
            Ok(c) => {
                let r = c.after.max_error_um / c.before.max_error_um;
                ratios.push(r);
                let changed = c.regions.iter().filter(|n| n.changed).count();
                if std::env::var_os("RC_DIGEST").is_some() {
                    // To compare two builds bit for bit: the written text's
                    // hash and the summaries as stored.
                    use std::hash::{Hash, Hasher};
                    let mut h = std::collections::hash_map::DefaultHasher::new();
                    c.nc.hash(&mut h);
                    println!(
                        "  digest {:016x} after {:?} {:?} before {:?} {:?} history {:?}",
                        h.finish(),
                        c.after.max_error_um,
                        c.after.motion_time,
                        c.before.max_error_um,
                        c.before.motion_time,
                        c.history_um
                    );
                }
                println!(
                    "{name:48} {:9.1} -> {:9.1} µm ×{r:.3}  time {:+.2} %  regions {changed}/{}  {:.2} s{}{}{}",
                    c.before.max_error_um,
                    c.after.max_error_um,
                    100.0 * (c.after.motion_time / c.before.motion_time - 1.0),
                    c.regions.len(),
                    start.elapsed().as_secs_f64(),
                    c.unchanged.as_deref().map(|u| format!("\n    unchanged: {u}")).unwrap_or_default(),
                    c.budget_note.as_deref().map(|u| format!("\n    budget: {u}")).unwrap_or_default(),
                    c.expand_note.as_deref().map(|u| format!("\n    {}: {u}", if c.expanded { "expanded" } else { "in place" })).unwrap_or_default(),
                );
                unchanged += usize::from(c.unchanged.is_some());
            }
            Err(e) => {
                refused += 1;
                println!("{name:48} refused: {e}");
            }
        }
    }
    ratios.sort_by(f64::total_cmp);
    let m = ratios.len();
    if m > 0 {
        let median = if m % 2 == 1 {
            ratios[m / 2]
        } else {
            0.5 * (ratios[m / 2 - 1] + ratios[m / 2])
        };
        println!("{m} compensated, median after/before ×{median:.3}, {unchanged} unchanged, {refused} refused");
    }
    Ok(())
}

#[cfg(target_arch = "wasm32")]
fn main() {}
