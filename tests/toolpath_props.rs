//! Property tests: for random line/arc programs, superposing per-segment
//! responses equals direct filtering (linearity, qiu §4-2), the contour
//! error never exceeds the distance to the commanded point at the same
//! instant, and parse → write → parse reproduces the segments.
#![cfg(not(target_arch = "wasm32"))]
#![allow(clippy::needless_range_loop)]

use mtmotion::nc::program::{parse, Motion};
use mtmotion::toolpath::{
    filter::filter, simulate_program, superpose::superpose, timeline::Timeline, Lag, SimConfig,
};
use proptest::prelude::*;

fn program(moves: &[(f64, f64, bool, f64)], feed: f64) -> String {
    let mut s = format!("G0 X0 Y0\nG1 X1 Y0 F{feed:.0}\n");
    let (mut x, mut y) = (1.0f64, 0.0f64);
    for &(dx, dy, arc, r) in moves {
        let (nx, ny) = (x + dx, y + dy);
        let chord = dx.hypot(dy);
        if arc && chord > 0.1 {
            let rr = (chord / 2.0 + r).copysign(if r > 1.0 { -1.0 } else { 1.0 });
            s.push_str(&format!("G3 X{nx:.4} Y{ny:.4} R{rr:.4}\n"));
        } else {
            s.push_str(&format!("G1 X{nx:.4} Y{ny:.4}\n"));
        }
        (x, y) = (nx, ny);
    }
    s
}

fn moves() -> impl Strategy<Value = Vec<(f64, f64, bool, f64)>> {
    prop::collection::vec(
        (-20.0f64..20.0, -20.0f64..20.0, any::<bool>(), 0.5f64..2.0),
        1..8,
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn superposition_equals_filtering(m in moves(), feed in 500.0f64..6000.0, ta in 0.0f64..0.1, t in 0.0f64..0.05) {
        let p = parse(&program(&m, feed)).unwrap();
        let tl = Timeline::new(&p.segments, 2e4, 1.0);
        let n = ((tl.end_time + 0.3) / 1e-3) as usize;
        let a = superpose(&tl, ta, [t, 0.5 * t, 0.0], 1e-3, n);
        let b = filter(&tl, ta, [t, 0.5 * t, 0.0], 1e-3, n);
        for ax in 0..3 {
            for k in 0..n {
                prop_assert!((a[ax][k] - b.sim[ax][k]).abs() < 1e-9);
            }
        }
    }

    #[test]
    fn contour_error_bounded_by_lag(m in moves(), feed in 500.0f64..6000.0) {
        let p = parse(&program(&m, feed)).unwrap();
        let s = simulate_program(&p, &SimConfig { t: Lag::All(0.02), ..Default::default() }).unwrap();
        for k in 0..s.t.len() {
            let lag = (s.cmd[0][k] - s.sim[0][k]).hypot(s.cmd[1][k] - s.sim[1][k]);
            prop_assert!(s.error[k] <= lag + 1e-9, "k {}: {} > {}", k, s.error[k], lag);
        }
    }

    #[test]
    fn parse_write_parse(m in moves(), feed in 500.0f64..6000.0) {
        let p = parse(&program(&m, feed)).unwrap();
        let q = parse(&p.write()).unwrap();
        prop_assert_eq!(p.segments.len(), q.segments.len());
        for (a, b) in p.segments.iter().zip(&q.segments) {
            prop_assert!((a.end.x - b.end.x).abs() < 1e-4 && (a.end.y - b.end.y).abs() < 1e-4);
            if let (Motion::Arc(x), Motion::Arc(y)) = (a.motion, b.motion) {
                prop_assert!((x.sweep - y.sweep).abs() < 1e-3 && (x.radius - y.radius).abs() < 1e-3);
            }
        }
    }
}
