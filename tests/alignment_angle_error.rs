//! Angle errors of a rotary axis from two sections (takayama §2.2, Fig. 2):
//! the centre of each section is the least-squares centre of its ball-bar
//! trace, and ΔBz, ΔBx follow from the Fig. 2 formula. Exact on partial
//! traces without motion error; with a common motion error the ball-bar
//! reading cancels it (translation invariance), the DBB5 reading does not.

use mtmotion::alignment::{
    angle_sweep, estimate_alignment, AngleSweepConfig, Locus, Offset, Section, SectionOffset,
};
use mtmotion::ballbar::Harmonic;

/// The trace of a 100 mm bar about the nominal centre when the axis centre is
/// at (cz, cx) and the table point carries the radial motion error `h`.
fn section(y: f64, cz: f64, cx: f64, from: f64, to: f64, h: &[Harmonic]) -> Section {
    let angle_deg: Vec<f64> = (0..=200)
        .map(|i| from + (to - from) * i as f64 / 200.0)
        .collect();
    let deviation = angle_deg
        .iter()
        .map(|a| {
            let t = a.to_radians();
            let r = 100.0 + h.iter().map(|k| k.eval(t)).sum::<f64>();
            let (pz, px) = (cz + r * t.cos(), cx + r * t.sin());
            // The bar's length, measured at the commanded angle t.
            pz.hypot(px) - 100.0
        })
        .collect();
    Section {
        y,
        angle_deg,
        deviation,
    }
}

#[test]
fn two_sections_give_the_angle_error() {
    // 10 µm / 350 mm in Z, 4 µm / 700 mm in X; 10 µm Z offset at Y = 0.
    let (bz, bx) = (0.010 / 350.0, 0.004 / 700.0);
    let s1 = section(350.0, 0.010 + 350.0 * bz, 350.0 * bx, -45.0, 45.0, &[]);
    let s2 = section(-350.0, 0.010 - 350.0 * bz, -350.0 * bx, -45.0, 45.0, &[]);
    let e = estimate_alignment(&[s1.clone(), s2.clone()], 100.0).unwrap();
    // The bar measures length at the commanded angle, so an offset e is
    // seen with a second-order error ~e²/R (4e-6 mm for e = 20 µm): the
    // angle is right to 2e-8 rad = 0.014 µm / 700 mm.
    assert!((e.delta_bz.unwrap() - bz).abs() < 2e-8, "{e:?}");
    assert!((e.delta_bx.unwrap() - bx).abs() < 2e-8, "{e:?}");
    assert!((e.sections[0].z - 0.020).abs() < 1e-5 && e.sections[1].z.abs() < 1e-5);
    // A third section on the same line does not change the slope.
    let s0 = section(0.0, 0.010, 0.0, -45.0, 45.0, &[]);
    let e3 = estimate_alignment(&[s0, s1, s2], 100.0).unwrap();
    assert!((e3.delta_bz.unwrap() - bz).abs() < 2e-8);
}

#[test]
fn a_common_motion_error_biases_offsets_but_not_the_angle() {
    let h = [
        Harmonic {
            order: 2,
            amplitude: 0.005,
            phase: 0.0,
        },
        Harmonic {
            order: 3,
            amplitude: 0.003,
            phase: 0.0,
        },
    ];
    let s1 = section(350.0, 0.020, 0.0, -45.0, 45.0, &h);
    let s2 = section(-350.0, 0.0, 0.0, -45.0, 45.0, &h);
    let e = estimate_alignment(&[s1, s2], 100.0).unwrap();
    // Each offset is off by many µm at 90° travel …
    assert!((e.sections[1].x).abs() > 0.005, "{e:?}");
    // … but the same amount in both, so ΔBz is right to the second-order
    // 0.01 µm / 700 mm of the bar (see above).
    assert!(
        (e.delta_bz.unwrap() - 0.020 / 700.0).abs() * 700.0 < 1e-5,
        "{e:?}"
    );
}

#[test]
fn angle_sweep_matches_estimate_alignment_on_the_same_loci() {
    let h = vec![Harmonic {
        order: 2,
        amplitude: 0.005,
        phase: 0.0,
    }];
    let cfg = AngleSweepConfig {
        sections: vec![
            SectionOffset {
                y: 350.0,
                offset: Offset { z: 0.02, x: 0.0 },
            },
            SectionOffset {
                y: -350.0,
                offset: Offset { z: 0.0, x: 0.0 },
            },
        ],
        ranges: vec![90.0, 180.0, 360.0],
        locus: Locus {
            harmonics: h,
            radius: 0.0,
            samples: 1000,
            centre_deg: 0.0,
        },
    };
    let r = angle_sweep(&cfg).unwrap();
    // DBB5 reading: biased at 90°, and the bias shrinks towards 360°.
    assert!(r[0].error_bz.abs() > r[2].error_bz.abs());
    for p in &r {
        assert!((p.delta_bz - p.error_bz - 0.02 / 700.0).abs() < 1e-15);
    }
    let e = angle_sweep(&AngleSweepConfig {
        sections: vec![cfg.sections[0]],
        ..cfg.clone()
    })
    .unwrap_err();
    assert!(e.to_string().starts_with("sections:"), "{e}");
}

#[test]
fn bad_sections_are_named() {
    let s = section(0.0, 0.0, 0.0, -45.0, 45.0, &[]);
    let e = estimate_alignment(&[s.clone(), s.clone()], 100.0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("same y"), "{e}");
    let e = estimate_alignment(std::slice::from_ref(&s), -1.0)
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("radius:"), "{e}");
    let mut t = s.clone();
    t.deviation.pop();
    let e = estimate_alignment(&[s, t], 100.0).unwrap_err().to_string();
    assert!(
        e.starts_with("sections[1]: angleDeg has 201 values but deviation has 200"),
        "{e}"
    );
}
