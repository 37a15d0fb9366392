fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let text = String::from_utf8_lossy(&std::fs::read(&a[0]).unwrap()).into_owned();
    let mut c = mtmotion::compensate::reverse::ReverseConfig::default();
    c.sim.t_a = 0.04;
    c.sim.t = mtmotion::toolpath::Lag::All(0.015);
    c.sim.dt = a.get(1).map_or(2e-3, |s| s.parse::<f64>().unwrap() * 1e-3);
    if let Some(b) = a.get(2) {
        c.time_budget = b.parse().unwrap();
    }
    let t0 = std::time::Instant::now();
    let r = mtmotion::compensate::reverse::reverse_compensate(&text, &c).unwrap();
    println!(
        "{:.1} -> {:.1} µm  time {:.3} -> {:.3}  {:.1}s spikes {} dwells {}",
        r.before.max_error_um,
        r.after.max_error_um,
        r.before.motion_time,
        r.after.motion_time,
        t0.elapsed().as_secs_f64(),
        r.spikes.len(),
        r.dwells.len()
    );
    println!(
        "history {:?}",
        r.history_um
            .iter()
            .map(|x| (x * 10.0).round() / 10.0)
            .collect::<Vec<_>>()
    );
    println!(
        "max after at line {} t {:.3}; before at line {} t {:.3}",
        r.sim_after.max_error_line,
        r.sim_after.max_error_time,
        r.sim_before.max_error_line,
        r.sim_before.max_error_time
    );
    let mut regs = r.regions.clone();
    regs.sort_by(|x, y| y.after_um.total_cmp(&x.after_um));
    for g in regs.iter().take(8) {
        println!(
            "  {}-{} a{} l{} {:.1} -> {:.1} {} {}",
            g.first_line,
            g.last_line,
            g.arcs,
            g.lines,
            g.before_um,
            g.after_um,
            g.changed,
            g.reason
        );
    }
    let mut segs: Vec<_> = r.sim_after.segments.iter().collect();
    segs.sort_by(|x, y| y.max_error_um.total_cmp(&x.max_error_um));
    for s in segs.iter().take(6) {
        println!(
            "  after seg {} line {} {} len {:.3} err {:.1}",
            s.segment, s.line, s.kind, s.length, s.max_error_um
        );
    }
}
