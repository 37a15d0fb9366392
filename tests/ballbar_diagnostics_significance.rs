//! Every ball-bar diagnostic is reported only above a stated threshold and
//! refers to one centre: noise alone (several levels and seeds, on an
//! asymmetric circle: centre off 0, arc not starting at 0°) reports no
//! cyclic error, spike or backlash; each row carries the threshold it was
//! compared with; a spike listed is above the threshold stated; real
//! features on the same circle are still found.

use mtmotion::ballbar::{
    circular_test, parse_ballbar_trace, synthetic_trace, BallbarTrace, Centre, Diagnostics,
    ParseOptions, PlanePoint, SyntheticConfig,
};

/// Centre (12, −7) µm off the pivot, arc −143° … 217°, 2000 mm/min.
fn asymmetric() -> SyntheticConfig {
    SyntheticConfig {
        offset_x: 0.012,
        offset_y: -0.007,
        centre_deg: 37.0,
        feed: 2000.0,
        ..Default::default()
    }
}

/// Adds uniform noise ±`half` (mm) from a seeded xorshift to each run
/// (`runs`: which runs, by index).
fn add_noise(t: &mut BallbarTrace, half: f64, seed: u64, runs: &[usize]) {
    let mut s = seed | 1;
    for &k in runs {
        for d in &mut t.runs[k].deviation {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            *d += ((s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0) * half;
        }
    }
}

fn diagnose(t: &BallbarTrace) -> Diagnostics {
    circular_test(t).unwrap().diagnostics.unwrap()
}

#[test]
fn noise_alone_reports_no_cyclic_error_spike_or_backlash() {
    for half in [0.0002, 0.001, 0.005] {
        for seed in [1u64, 0xDEAD_BEEF, 0x1234_5678_9ABC] {
            let mut t = synthetic_trace(&asymmetric()).unwrap();
            add_noise(&mut t, half, seed, &[0, 1]);
            let d = diagnose(&t);
            let what = format!("noise ±{} µm, seed {seed:#x}", half * 1e3);
            assert!(
                d.reversal_spikes.is_empty(),
                "{what}: {:?}",
                d.reversal_spikes
            );
            assert_eq!(
                (d.backlash_x_um, d.backlash_y_um),
                (0.0, 0.0),
                "{what}: {d:?}"
            );
            let c = d.cyclic_test.unwrap();
            assert!(
                d.cyclic.is_none() && c.f_ratio <= c.f_critical,
                "{what}: {c:?}"
            );
            // The thresholds scale with the noise: σ = half/√3.
            let sigma_um = half * 1e3 / 3f64.sqrt();
            assert!(
                d.residual_rms_um > 0.9 * sigma_um && d.residual_rms_um < 1.1 * sigma_um,
                "{what}: rms {} vs σ {sigma_um}",
                d.residual_rms_um
            );
            // The centre offset is the one put in, in every noise case
            // (to 0.05 µm + 1 % of the noise half-width).
            let tol = 0.05 + 0.01 * half * 1e3;
            assert!(
                (d.centre_offset_x_um - 12.0).abs() < tol
                    && (d.centre_offset_y_um + 7.0).abs() < tol,
                "{what}: {d:?}"
            );
            assert_eq!(d.centre, Centre::BarPivot);
        }
    }
}

#[test]
fn each_row_names_its_threshold_and_listed_spikes_stand_above_it() {
    // Spikes of 4 µm on both runs; the CCW run is much noisier (±3 µm:
    // its threshold ≈ 4.5 µm), the CW run quiet. One threshold serves
    // both: no spike is listed under a threshold it does not exceed.
    let mut t = synthetic_trace(&SyntheticConfig {
        spike: 0.004,
        spike_decay_deg: 2.0,
        ..asymmetric()
    })
    .unwrap();
    add_noise(&mut t, 0.003, 7, &[0]);
    add_noise(&mut t, 0.0002, 8, &[1]);
    let d = diagnose(&t);
    assert!(d.spike_threshold_um > 4.0, "{d:?}");
    for s in &d.reversal_spikes {
        assert_eq!(s.threshold_um, d.spike_threshold_um, "{s:?}");
        assert!(s.height_um.abs() > s.threshold_um, "{s:?}");
    }
    // Every other row states what it was compared with.
    assert!(d.backlash_x_resolution_um > 0.0 && d.backlash_y_resolution_um > 0.0);
    assert!(d.scale_mismatch_resolution_ppm > 0.0 && d.squareness_resolution_urad > 0.0);
    assert!(d.servo_mismatch_resolution_ms.unwrap() > 0.0);
    assert!(d.cyclic_test.unwrap().f_critical > 1.0);
    // A quiet trace with the same spikes lists them all, each above it.
    let mut t = synthetic_trace(&SyntheticConfig {
        spike: 0.004,
        spike_decay_deg: 2.0,
        ..asymmetric()
    })
    .unwrap();
    add_noise(&mut t, 0.0002, 9, &[0, 1]);
    let d = diagnose(&t);
    // −143° … 217°: four reversals inside each run.
    assert_eq!(d.reversal_spikes.len(), 8, "{:?}", d.reversal_spikes);
    for s in &d.reversal_spikes {
        assert!(s.height_um > s.threshold_um && s.threshold_um == d.spike_threshold_um);
    }
}

#[test]
fn features_on_the_asymmetric_circle_are_reported_above_their_thresholds() {
    let mut t = synthetic_trace(&SyntheticConfig {
        backlash_x: 0.004,
        squareness: 20e-6,
        scale_x: 30e-6,
        servo_mismatch: 0.002,
        cyclic_amplitude: 0.002,
        cyclic_pitch: 7.0,
        ..asymmetric()
    })
    .unwrap();
    add_noise(&mut t, 0.0003, 3, &[0, 1]);
    let d = diagnose(&t);
    assert!((d.backlash_x_um - 4.0).abs() < 0.2, "{d:?}");
    assert!(d.backlash_x_um > d.backlash_x_resolution_um);
    assert!((d.squareness_urad - 20.0).abs() < 1.0, "{d:?}");
    assert!(d.squareness_urad > d.squareness_resolution_urad);
    assert!((d.scale_mismatch_ppm - 30.0).abs() < 2.0, "{d:?}");
    assert!(d.scale_mismatch_ppm > d.scale_mismatch_resolution_ppm);
    let servo = d.servo_mismatch_ms.unwrap();
    assert!((servo - 2.0).abs() < 0.1, "{d:?}");
    let c = d.cyclic.unwrap();
    assert!(
        (c.pitch_mm - 7.0).abs() < 0.01 && (c.amplitude_x_um - 2.0).abs() < 0.1,
        "{c:?}"
    );
    let test = d.cyclic_test.unwrap();
    assert!(test.f_ratio > test.f_critical);
}

/// An X/Y trace of a circle of R 50 mm about (10.012, −3.007) mm, 0.5°
/// steps from 23°, CCW then CW.
fn xy_text() -> String {
    let mut s = String::from("x [mm],y [mm]\n");
    let mut put = |deg: f64| {
        let a = deg.to_radians();
        let r = 50.0 + 0.002 * (3.0 * a).sin();
        s += &format!("{:.7},{:.7}\n", 10.012 + r * a.cos(), -3.007 + r * a.sin());
    };
    for i in 0..=720 {
        put(23.0 + i as f64 * 0.5);
    }
    for i in 1..=720 {
        put(383.0 - i as f64 * 0.5);
    }
    s
}

#[test]
fn the_centre_offset_says_which_centre_it_is_about() {
    // About its own LSC: 0 by construction, and the report says so.
    let t = parse_ballbar_trace(&xy_text(), ParseOptions::default()).unwrap();
    let d = diagnose(&t);
    assert_eq!(d.centre, Centre::TraceLsc);
    assert!(
        d.centre_offset_x_um.abs() < 0.01 && d.centre_offset_y_um.abs() < 0.01,
        "{d:?}"
    );
    // About the programmed centre: the 12/−7 µm offset is measured.
    let o = ParseOptions {
        centre: Some(PlanePoint { x: 10.0, y: -3.0 }),
        nominal_radius: Some(50.0),
        ..ParseOptions::default()
    };
    let t = parse_ballbar_trace(&xy_text(), o).unwrap();
    let d = diagnose(&t);
    assert_eq!(d.centre, Centre::Given);
    assert!(
        (d.centre_offset_x_um - 12.0).abs() < 0.01 && (d.centre_offset_y_um + 7.0).abs() < 0.01,
        "{d:?}"
    );
}
