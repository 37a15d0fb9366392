//! Proves the tool-path model of qiu §4-1/§4-2: the simulator's
//! steady-state radius loss on a full circle matches Eq. 3 to 0.5 %;
//! superposing per-segment responses equals filtering the whole command;
//! the contour error is the distance to the path (zero on a straight line
//! at constant speed however large the lag), and the built-in examples
//! give errors of the paper's order.

#![allow(clippy::needless_range_loop)]

use mtmotion::nc::program::parse;
use mtmotion::toolpath::{
    example, filter::filter, identify::radius_reduction, simulate_program, simulate_text,
    superpose::superpose, timeline::Timeline, Lag, SimConfig,
};

#[test]
fn steady_state_radius_loss_matches_eq3() {
    for &(feed, r, ta, t) in &[
        (2000.0, 10.0, 0.04, 0.015),
        (6000.0, 5.0, 0.064, 0.033),
        (1000.0, 3.0, 0.1, 0.0),
        (3000.0, 20.0, 0.0, 0.05),
    ] {
        // Five full circles; measure the fourth.
        let prog = format!(
            "G0 X{r} Y0\nG3 X{r} Y0 I{} J0 F{feed}\nX{r} I{}\nX{r} I{}\nX{r} I{}\nX{r} I{}",
            -r, -r, -r, -r, -r
        );
        let cfg = SimConfig {
            t_a: ta,
            t: Lag::All(t),
            dt: 1e-4,
            ..Default::default()
        };
        let p = parse(&prog).unwrap();
        let s = simulate_program(&p, &cfg).unwrap();
        let period = std::f64::consts::TAU * r / (feed / 60.0);
        let t0 = p.segments[0].length() / (cfg.rapid_feed / 60.0) + 3.0 * period;
        let (mut sum, mut cnt) = (0.0, 0);
        for k in 0..s.t.len() {
            if s.t[k] >= t0 && s.t[k] < t0 + period {
                sum += r - s.sim[0][k].hypot(s.sim[1][k]);
                cnt += 1;
            }
        }
        let sim = sum / cnt as f64;
        let eq3 = radius_reduction(feed, r, ta, t).unwrap();
        assert!(
            (sim - eq3).abs() / eq3 < 0.005,
            "F{feed} R{r}: sim {sim} eq3 {eq3}"
        );
        // The contour error there is the radius loss too.
        let k = s.t.iter().position(|&x| x >= t0).unwrap();
        assert!((s.error[k] - eq3).abs() / eq3 < 0.005);
    }
}

#[test]
fn superposition_equals_direct_filtering() {
    for text in [example::arc_example(), example::line_example()] {
        let p = parse(&text).unwrap();
        let tl = Timeline::new(&p.segments, 20000.0, 1.0);
        let n = ((tl.end_time + 0.5) / 1e-3) as usize;
        let lag = [0.015, 0.02, 0.01];
        let a = superpose(&tl, 0.04, lag, 1e-3, n);
        let b = filter(&tl, 0.04, lag, 1e-3, n);
        let mut worst: f64 = 0.0;
        for ax in 0..3 {
            for k in 0..n {
                worst = worst.max((a[ax][k] - b.sim[ax][k]).abs());
            }
        }
        assert!(worst < 1e-9, "max difference {worst} mm");
        // And the filters really moved the tool away from the command.
        let lagged = (0..n)
            .map(|k| (b.cmd[0][k] - b.sim[0][k]).abs())
            .fold(0.0, f64::max);
        assert!(lagged > 0.5);
    }
}

#[test]
fn contour_error_is_distance_to_path_not_to_commanded_point() {
    let s = simulate_text("G1 X100 Y50 F3000", &SimConfig::default()).unwrap();
    let lag = (0..s.t.len())
        .map(|k| (s.cmd[0][k] - s.sim[0][k]).hypot(s.cmd[1][k] - s.sim[1][k]))
        .fold(0.0, f64::max);
    assert!(lag > 1.0, "the tool lags by {lag} mm");
    assert!(s.max_error < 1e-9, "but stays on the line: {}", s.max_error);
    assert!((s.nominal_time - 111.803_398_874_989_5_f64.hypot(0.0) / 50.0).abs() < 1e-9);
}

#[test]
fn examples_give_errors_of_the_papers_order() {
    let cfg = SimConfig::default();
    for (name, text) in [
        ("arcs", example::arc_example()),
        ("lines", example::line_example()),
    ] {
        let s = simulate_text(&text, &cfg).unwrap();
        println!(
            "{name}: max {:.1} µm at line {} t={:.3}, motion {:.3} s nominal {:.3}",
            s.max_error * 1e3,
            s.max_error_line,
            s.max_error_time,
            s.motion_time,
            s.nominal_time
        );
        assert!(
            s.max_error > 0.02 && s.max_error < 0.2,
            "{name}: {}",
            s.max_error
        );
    }
}
