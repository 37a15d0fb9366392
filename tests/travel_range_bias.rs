//! The travel-range sweep (takayama §2.1): at 360° the centre estimate is
//! unbiased; the bias falls as the range grows; it agrees with an
//! independent first-order computation (the least-squares projection of the
//! motion error on {1, cos θ, sin θ} by quadrature); with the ball-bar
//! reading it does not depend on the offset position (Fig. 8); and higher
//! orders bias less (Fig. 6).

use mtmotion::alignment::{examples::example, travel_range_sweep, Locus, Offset, SweepConfig};
use mtmotion::ballbar::Harmonic;

fn fig7_locus(radius: f64) -> Locus {
    let h = |order, a: f64| Harmonic {
        order,
        amplitude: a * 1e-3,
        phase: 0.0,
    };
    Locus {
        harmonics: vec![h(2, 5.0), h(3, 3.0), h(5, 2.5)],
        radius,
        samples: 1000,
        centre_deg: 0.0,
    }
}

fn ranges() -> Vec<f64> {
    (0..10).map(|k| 90.0 + 30.0 * k as f64).collect()
}

#[test]
fn unbiased_at_360_and_falling_with_range() {
    for off in [Offset { z: 0.0, x: 0.0 }, Offset { z: 0.0, x: 0.01 }] {
        let s = travel_range_sweep(&SweepConfig {
            offset: off,
            ranges: ranges(),
            locus: fig7_locus(100.0),
        })
        .unwrap();
        let mag: Vec<f64> = s.iter().map(|p| p.error_z.hypot(p.error_x)).collect();
        assert!(mag[9] < 1e-9, "360°: {}", mag[9]);
        // Strictly falling from 90° to 270°, and below 0.2 µm beyond.
        for k in 0..6 {
            assert!(mag[k + 1] < mag[k], "{:?}", mag);
        }
        assert!(mag[6..].iter().all(|m| *m < 2e-4), "{:?}", mag);
    }
}

#[test]
fn agrees_with_the_first_order_projection() {
    let loc = fig7_locus(1000.0);
    for w in [90.0, 150.0, 240.0] {
        let s = travel_range_sweep(&SweepConfig {
            offset: Offset::default(),
            ranges: vec![w],
            locus: Locus {
                samples: 36_000,
                ..loc.clone()
            },
        })
        .unwrap();
        // Midpoint-rule quadrature of the normal equations on [−w/2, w/2].
        let m = 200_000;
        let (mut g, mut rhs) = ([[0.0f64; 3]; 3], [0.0f64; 3]);
        for i in 0..m {
            let t = (-w / 2.0 + w * (i as f64 + 0.5) / m as f64).to_radians();
            let b = [1.0, t.cos(), t.sin()];
            let d: f64 = loc.harmonics.iter().map(|h| h.eval(t)).sum();
            for r in 0..3 {
                rhs[r] += b[r] * d;
                for c in 0..3 {
                    g[r][c] += b[r] * b[c];
                }
            }
        }
        let gm = nalgebra::Matrix3::from_fn(|r, c| g[r][c]);
        let sol = gm.lu().solve(&nalgebra::Vector3::from(rhs)).unwrap();
        // Discrete sampling with both end points (≈ 1/n_range relative, 1e-6 mm
        // here) and second order Δ²/ρ ≈ 1e-7 mm: 5e-6 mm = 0.005 µm.
        assert!(
            (s[0].error_z - sol[1]).abs() < 5e-6 && (s[0].error_x - sol[2]).abs() < 5e-6,
            "{w}: {:?} vs {sol:?}",
            s[0]
        );
    }
}

#[test]
fn ball_bar_reading_is_independent_of_the_offset_position() {
    let e = example("fig8", 100.0).unwrap();
    let base = &e.curves[0].points;
    for c in &e.curves[1..] {
        for (p, q) in c.points.iter().zip(base) {
            assert!(
                (p.error_z - q.error_z).abs() < 1e-8 && (p.error_x - q.error_x).abs() < 1e-8,
                "{c:?}"
            );
        }
    }
}

#[test]
fn higher_orders_bias_less() {
    let e = example("fig6", 100.0).unwrap();
    let mag = |n: f64| {
        e.curves[0]
            .points
            .iter()
            .find(|p| p.range_deg == n)
            .map(|p| p.error_z.hypot(p.error_x))
            .unwrap()
    };
    // Even orders (odd ones vanish by symmetry with zero phase): 2 > 4 > … > 20.
    let even = [2.0, 4.0, 6.0, 8.0, 10.0, 20.0];
    for w in even.windows(2) {
        assert!(mag(w[1]) < mag(w[0]), "{w:?}");
    }
    for n in [3.0, 5.0, 7.0, 9.0, 15.0] {
        assert!(mag(n) < 5e-5, "order {n}: {}", mag(n));
    }
}

#[test]
fn partial_range_centre_can_be_moved() {
    // −100°…180° (the paper's DBB5 measurement range) = 280° centred on 40°.
    let s = travel_range_sweep(&SweepConfig {
        offset: Offset::default(),
        ranges: vec![280.0],
        locus: Locus {
            centre_deg: 40.0,
            ..fig7_locus(100.0)
        },
    })
    .unwrap();
    let c = travel_range_sweep(&SweepConfig {
        offset: Offset::default(),
        ranges: vec![280.0],
        locus: fig7_locus(100.0),
    })
    .unwrap();
    assert!(
        (s[0].error_z - c[0].error_z).abs() > 1e-5 || (s[0].error_x - c[0].error_x).abs() > 1e-5
    );
}

/// The travel range is cut about `centre_deg`, with the angle wrapped:
/// `fit_range` equals a circle fitted to the points picked independently
/// (angular distance from the centre by atan2, |Δ| ≤ W/2), for centres off
/// 0°, one near ±180° (the cut straddles the wrap), and a range that does
/// not (the picked arcs differ, so a wrong centre or wrap is seen).
#[test]
fn the_range_is_cut_about_its_centre_across_the_wrap() {
    use mtmotion::ballbar::fit_circle;
    let c = Offset {
        z: 0.004,
        x: -0.007,
    };
    for (centre, w) in [
        (50.0, 120.0),
        (-170.0, 90.0),
        (175.0, 200.0),
        (-30.0, 300.0),
    ] {
        let locus = Locus {
            centre_deg: centre,
            ..fig7_locus(100.0)
        };
        let pts = locus.points(c);
        let got = locus.fit_range(&pts, w).unwrap();
        let (mut zs, mut xs) = (Vec::new(), Vec::new());
        for i in 0..pts.0.len() {
            let d = pts.0[i] - f64::to_radians(centre);
            let d = d.sin().atan2(d.cos()).to_degrees();
            if d.abs() <= w / 2.0 + 1e-9 {
                zs.push(pts.1[i]);
                xs.push(pts.2[i]);
            }
        }
        // the count picked is the range's share of the 1000 samples
        assert!(
            (zs.len() as f64 - 1000.0 * w / 360.0).abs() <= 2.0,
            "centre {centre}°, {w}°: {} points",
            zs.len()
        );
        let want = fit_circle(&zs, &xs).unwrap();
        assert!(
            (got.z - want.cx).abs() < 1e-12 && (got.x - want.cy).abs() < 1e-12,
            "centre {centre}°, {w}°: {got:?} against {:?}",
            (want.cx, want.cy)
        );
        // and the cut is not the one about 0°: the harmonics bias it differently
        let at0 = Locus {
            centre_deg: 0.0,
            ..locus.clone()
        }
        .fit_range(&pts, w)
        .unwrap();
        assert!(
            (at0.z - got.z).hypot(at0.x - got.x) > 1e-5,
            "centre {centre}°, {w}°: the cut about 0° gave the same centre"
        );
    }
}

/// Bad sweeps are refused by name before any work: a range of 0° (the
/// range is in (0, 360]), an offset with one non-finite part, and a sweep
/// whose work, (ranges + harmonics) × samples, is over the budget even
/// with no harmonic at all.
#[test]
fn bad_sweeps_are_refused_by_name() {
    let cfg = |offset: Offset, ranges: Vec<f64>, locus: Locus| SweepConfig {
        offset,
        ranges,
        locus,
    };
    let good = Offset { z: 0.0, x: 0.01 };
    let e = travel_range_sweep(&cfg(good, vec![90.0, 0.0], fig7_locus(100.0))).unwrap_err();
    assert!(
        e.to_string().contains("ranges[1]") && e.to_string().contains("(0, 360]"),
        "{e}"
    );
    for off in [
        Offset {
            z: 0.0,
            x: f64::NAN,
        },
        Offset {
            z: f64::INFINITY,
            x: 0.0,
        },
    ] {
        let e = travel_range_sweep(&cfg(off, vec![90.0], fig7_locus(100.0))).unwrap_err();
        assert!(e.to_string().contains("offset"), "{e}");
    }
    let big = Locus {
        harmonics: vec![],
        samples: mtmotion::budget::MAX_SWEEP_POINTS / 3 + 1,
        ..fig7_locus(100.0)
    };
    let e = travel_range_sweep(&cfg(good, vec![90.0, 180.0, 270.0], big)).unwrap_err();
    assert!(e.to_string().contains("travel-range sweep"), "{e}");
    // at 1000 samples the same sweep runs
    assert_eq!(
        travel_range_sweep(&cfg(good, vec![90.0, 180.0, 270.0], fig7_locus(100.0)))
            .unwrap()
            .len(),
        3
    );
}
