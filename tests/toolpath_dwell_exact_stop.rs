//! qiu §4-3(2): with `dwellExactStop`, every G4 dwell first waits
//! `tA + 5·max T` (exact stop, in-position check). Oracle: the closed form
//! — the motion time grows by exactly that per dwell (to one sample), and a
//! program without dwells is unchanged.

use mtmotion::nc::program::parse;
use mtmotion::toolpath::{simulate::simulate_program, Lag, SimConfig};

fn motion_time(src: &str, stop: bool, t_a: f64, t: f64) -> f64 {
    let p = parse(src).unwrap();
    let cfg = SimConfig {
        t_a,
        t: Lag::All(t),
        dwell_exact_stop: stop,
        ..Default::default()
    };
    simulate_program(&p, &cfg).unwrap().motion_time
}

#[test]
fn each_dwell_adds_ta_plus_5t() {
    let src = "G1 X10 F600\nG4 P0.1\nG1 X20\nG4 P0.2\nG1 Y10";
    for (t_a, t) in [(0.04, 0.015), (0.1, 0.03), (0.0, 0.02)] {
        let plain = motion_time(src, false, t_a, t);
        let stop = motion_time(src, true, t_a, t);
        let expect = 2.0 * (t_a + 5.0 * t);
        assert!(
            (stop - plain - expect).abs() <= 1e-3 + 1e-9,
            "tA {t_a}, T {t}: {plain} → {stop}, expected +{expect}"
        );
    }
    let no_dwell = "G1 X10 F600\nG1 X20";
    assert_eq!(
        motion_time(no_dwell, false, 0.04, 0.015),
        motion_time(no_dwell, true, 0.04, 0.015)
    );
}
