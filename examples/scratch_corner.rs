use mtmotion::compensate::reverse::{reverse_compensate, ReverseConfig};
fn main() {
    let name = std::env::args().nth(1).unwrap();
    let src = std::fs::read_to_string(format!("../shared/nc_corpus/{name}")).unwrap();
    let mut cfg = ReverseConfig::default();
    cfg.sim.dt = 0.002;
    let c = reverse_compensate(&src, &cfg).unwrap();
    println!(
        "{:?} -> {:?} spikes {} dwells {} hist {:?}",
        c.before,
        c.after,
        c.spikes.len(),
        c.dwells.len(),
        c.history_um.iter().map(|x| x.round()).collect::<Vec<_>>()
    );
    for r in &c.regions {
        println!(
            "  {}-{} {:.1} -> {:.1} {} {}",
            r.first_line, r.last_line, r.before_um, r.after_um, r.changed, r.reason
        );
    }
}
