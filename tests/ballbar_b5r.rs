//! Renishaw `.b5r` reports beside ours (issue 26, item 2): a `.b5r` the
//! team wrote in the published layout (tests/b5r/, the layout of
//! src/trace/b5r.rs) reads back to its settings, metadata, runs and
//! features with their units and lines; beside a synthetic run with the
//! same errors (squareness 20 µrad, servo mismatch 0.5 ms, X backlash
//! 3 µm), each feature pairs with our value of the same feature in our
//! unit (mm → µm, µm/m → µrad), a run's circularity with our run of the
//! same direction, and a feature we do not compute (straightness, the
//! measured feed) or one in a unit of another quantity (scale mismatch in
//! µm vs our ppm) says so instead of pairing.
#![cfg(not(target_arch = "wasm32"))]

use mtmotion::ballbar::b5r_beside::beside;
use mtmotion::ballbar::{circular_test, synthetic_trace, Direction, SyntheticConfig};
use mtmotion::trace::b5r::read;

const FILE: &str = include_str!("b5r/xy_100mm_1000.b5r");

#[test]
fn the_file_reads_back_to_its_settings_and_features() {
    let r = read(FILE).unwrap();
    assert_eq!(r.test_name.as_deref(), Some("100mm XY 1000"));
    assert_eq!(r.instrument.as_deref(), Some("Renishaw QC20-W"));
    assert_eq!((r.radius, r.feed), (Some(100.0), Some(1000.0)));
    assert_eq!(r.plane.as_deref(), Some("XY"));
    assert_eq!(r.axes, Some(["X".to_string(), "Y".to_string()]));
    let keys: Vec<&str> = r.metadata.iter().map(|(k, _)| k.as_str()).collect();
    assert_eq!(
        keys,
        [
            "OPERATOR",
            "DATE_STARTED",
            "DATE_COMPLETED",
            "MACHINE_TESTED",
            "SERIAL_NUMBER"
        ]
    );
    assert_eq!(r.metadata[3].1, "synthetic VMC");
    let dirs: Vec<&str> = r.runs.iter().map(|r| r.direction.as_str()).collect();
    assert_eq!(dirs, ["CCW", "CW"]);
    assert_eq!(r.runs[1].features[0].value, 0.016);
    assert_eq!(r.runs[1].features[0].line, 32);
    let a = &r.analyses[0];
    assert_eq!(
        (a.name.as_str(), a.features.len()),
        ("RENISHAW_DIAGNOSTICS", 8)
    );
    let sq = &a.features[0];
    assert_eq!(
        (
            sq.name.as_str(),
            sq.dt.as_str(),
            sq.unit.as_deref(),
            sq.value,
            sq.line
        ),
        ("AF_SQUARENESS", "UT_SQUARENESS", Some("µm/m"), 20.0, 37)
    );
    assert!(r.unread.is_empty(), "{:?}", r.unread);
    assert_eq!(r.notes.len(), 1);
    assert!(r.notes[0].starts_with("the raw samples are not read"));
}

#[test]
fn each_feature_stands_beside_ours() {
    let trace = synthetic_trace(&SyntheticConfig {
        radius: 100.0,
        feed: 1000.0,
        squareness: 20e-6,
        servo_mismatch: 0.5e-3,
        backlash_x: 0.003,
        ..SyntheticConfig::default()
    })
    .unwrap();
    let ours = circular_test(&trace).unwrap();
    let d = ours.diagnostics.clone().unwrap();
    let rows = beside(&read(FILE).unwrap(), &ours);
    let names: Vec<(&str, &str)> = rows
        .iter()
        .map(|r| (r.source.as_str(), r.feature.as_str()))
        .collect();
    assert_eq!(names.len(), 12);
    assert_eq!(names[0], ("run CCW", "AF_CIRCULARITY"));
    assert_eq!(names[4], ("RENISHAW_DIAGNOSTICS", "AF_SQUARENESS"));
    let row = |source: &str, f: &str| {
        rows.iter()
            .find(|r| r.source == source && r.feature == f)
            .unwrap()
    };
    let g = |dir| ours.runs.iter().find(|r| r.direction == dir).unwrap().g_um;
    let ccw = row("run CCW", "AF_CIRCULARITY");
    assert_eq!(
        (ccw.ours, ccw.theirs_in_ours),
        (Some(g(Direction::Ccw)), Some(15.0))
    );
    let cw = row("run CW", "AF_CIRCULARITY");
    assert_eq!(
        (cw.ours, cw.theirs_in_ours),
        (Some(g(Direction::Cw)), Some(16.0))
    );
    assert_ne!(g(Direction::Ccw), g(Direction::Cw));
    let all = row("RENISHAW_DIAGNOSTICS", "AF_CIRCULARITY");
    assert_eq!(all.ours, Some(g(Direction::Ccw).max(g(Direction::Cw))));
    assert_eq!(
        (all.theirs_in_ours, all.ours_unit.as_str()),
        (Some(16.0), "µm")
    );
    // the synthetic errors come back on our side, beside the file's
    let near = |f: &str, want: f64, tol: f64| {
        let r = row("RENISHAW_DIAGNOSTICS", f);
        let (o, t) = (r.ours.unwrap(), r.theirs_in_ours.unwrap());
        assert!((o - want).abs() < tol, "{f}: ours {o}");
        assert!((t - want).abs() < 1e-12, "{f}: theirs {t}");
    };
    near("AF_SQUARENESS", 20.0, 0.5);
    near("AF_SERVO_MISMATCH", 0.5, 0.02);
    near("AF_BACKLASH_A_POS", 3.0, 0.1);
    near("AF_BACKLASH_A_NEG", 3.0, 0.1);
    let by = row("RENISHAW_DIAGNOSTICS", "AF_BACKLASH_B_POS");
    assert_eq!(by.ours, Some(d.backlash_y_um));
    assert!(by.ours.unwrap().abs() < 0.1);
    // units of another quantity: both shown, no conversion
    let scale = row("RENISHAW_DIAGNOSTICS", "AF_SCALE_MISMATCH");
    assert_eq!(
        (scale.ours, scale.ours_unit.as_str(), scale.theirs_in_ours),
        (Some(d.scale_mismatch_ppm), "ppm", None)
    );
    assert_eq!(scale.theirs_unit.as_deref(), Some("µm"));
    // features we do not compute
    for (source, f) in [
        ("RENISHAW_DIAGNOSTICS", "AF_STRAIGHTNESS_A"),
        ("run CW", "AF_CALCULATED_FEEDRATE"),
    ] {
        let r = row(source, f);
        assert_eq!(
            (r.ours, r.ours_unit.as_str(), r.theirs_in_ours),
            (None, "", None),
            "{f}"
        );
    }
}
