//! The per-segment statistics as columns (`simulate_columns`, what
//! `simulateToolPathColumns` returns for programs of millions of segments)
//! hold the same numbers, bit for bit, as the serialised fields of
//! `simulate_with_progress`'s `SegmentStats`, and the rest of the
//! simulation (maxima, their time and line, motion time, every series) is
//! the same: the columns are gathered without the halves that only reverse
//! compensation reads, so this proves that leaving them out changes
//! nothing else. Programs: the paper-like examples, a 3D program with
//! rapids, helices and arcs in three planes that passes its own path
//! twice, and a run long enough (over 1 M samples) to thin its series.
//! `simulate_columns_owned`, which drops the program's segments before the
//! run, gives the same columns and series.

use mtmotion::nc::program::parse;
use mtmotion::toolpath::columns::{KIND_ARC, KIND_LINE, KIND_RAPID};
use mtmotion::toolpath::{
    example, simulate_columns, simulate_columns_owned, simulate_with_progress, Lag, SimConfig,
};

fn same(text: &str, cfg: &SimConfig) -> usize {
    let p = parse(text).unwrap();
    let whole = simulate_with_progress(&p.segments, &p.segments, cfg, &mut |_| true).unwrap();
    let (sim, col) = simulate_columns(&p.segments, &p.segments, cfg, &mut |_| true).unwrap();
    assert!(sim.segments.is_empty());
    // The segments taken and dropped before the run: the same run.
    let (owned, owned_col) =
        simulate_columns_owned(p.segments.clone(), cfg, &mut |_| true).unwrap();
    // bit for bit (NaN, "no mean deviation", is not equal to itself)
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(
        (
            &owned_col.segment,
            &owned_col.line,
            &owned_col.kind,
            &owned_col.samples
        ),
        (&col.segment, &col.line, &col.kind, &col.samples)
    );
    for (a, b) in [
        (&owned_col.length, &col.length),
        (&owned_col.radius, &col.radius),
        (&owned_col.max_error_um, &col.max_error_um),
        (&owned_col.mean_deviation, &col.mean_deviation),
    ] {
        assert_eq!(bits(a), bits(b));
    }
    assert_eq!(owned.max_error.to_bits(), sim.max_error.to_bits());
    assert_eq!(owned.max_error_line, sim.max_error_line);
    assert_eq!(owned.error, sim.error);
    assert_eq!(col.len(), whole.segments.len());
    for (i, g) in whole.segments.iter().enumerate() {
        assert_eq!(col.segment[i] as usize, g.segment, "{i}");
        assert_eq!(col.line[i] as usize, g.line, "{i}");
        let kind = match g.kind {
            "line" => KIND_LINE,
            "arc" => KIND_ARC,
            "rapid" => KIND_RAPID,
            k => panic!("kind {k}"),
        };
        assert_eq!(col.kind[i], kind, "{i}");
        assert_eq!(col.length[i].to_bits(), g.length.to_bits(), "{i}");
        assert_eq!(col.radius[i].to_bits(), g.radius.to_bits(), "{i}");
        assert_eq!(
            col.max_error_um[i].to_bits(),
            g.max_error_um.to_bits(),
            "{i}"
        );
        match g.mean_deviation {
            Some(d) => assert_eq!(col.mean_deviation[i].to_bits(), d.to_bits(), "{i}"),
            None => assert!(col.mean_deviation[i].is_nan(), "{i}"),
        }
        assert_eq!(col.samples[i] as usize, g.samples, "{i}");
    }
    assert_eq!(sim.max_error.to_bits(), whole.max_error.to_bits());
    assert_eq!(sim.max_error_time, whole.max_error_time);
    assert_eq!(sim.max_error_line, whole.max_error_line);
    assert_eq!(sim.motion_time, whole.motion_time);
    assert_eq!(sim.nominal_time, whole.nominal_time);
    assert_eq!(
        (sim.samples, sim.series_stride),
        (whole.samples, whole.series_stride)
    );
    assert_eq!(sim.t, whole.t);
    assert_eq!(sim.error, whole.error);
    assert_eq!(sim.segment, whole.segment);
    for ax in 0..3 {
        assert_eq!(sim.sim[ax], whole.sim[ax]);
        assert_eq!(sim.near[ax], whole.near[ax]);
        assert_eq!(sim.vel_cmd[ax], whole.vel_cmd[ax]);
    }
    col.len()
}

#[test]
fn columns_equal_the_segment_statistics_on_the_examples() {
    let cfg = SimConfig::default();
    assert!(same(&example::arc_example(), &cfg) > 5);
    assert!(same(&example::line_example(), &cfg) > 5);
}

#[test]
fn columns_equal_the_segment_statistics_in_3d_with_rapids_and_a_second_pass() {
    let text = "G21 G90 G17\nG0 X5 Y-3 Z4\nG1 Z-0.5 F800\nG1 X17.3 Y2.1 Z-0.7\n\
                G3 X23.3 Y8.1 I0 J6 F1200\nG2 X29.1 Y2.4 Z-1.9 R6.2\nG18 G2 X35 Z0.3 R4\n\
                G19 G3 Y6 Z2.2 R3\nG17 G1 X12 Y9.5 F2500\nG0 Z6\nG0 X5 Y-3\n\
                G1 Z-0.5 F900\nG1 X17.3 Y2.1 Z-0.7\nG3 X23.3 Y8.1 I0 J6\nG0 Z10\nM30";
    let cfg = SimConfig {
        t_a: 0.032,
        t: Lag::PerAxis([0.011, 0.017, 0.02]),
        dt: 0.0007,
        rapid_feed: 12_000.0,
        ..SimConfig::default()
    };
    assert_eq!(same(text, &cfg), 14);
    // The kinds and radii themselves, not only as SegmentStats gives them:
    // five arcs (R6 by I/J, R6.2, R4, R3, R6 again) and four rapids.
    let p = parse(text).unwrap();
    let (_, col) = simulate_columns(&p.segments, &p.segments, &cfg, &mut |_| true).unwrap();
    let of = |k| col.kind.iter().filter(|&&c| c == k).count();
    assert_eq!((of(KIND_ARC), of(KIND_RAPID), of(KIND_LINE)), (5, 4, 5));
    let mut radii: Vec<f64> = col.radius.iter().copied().filter(|&r| r > 0.0).collect();
    radii.sort_by(f64::total_cmp);
    assert_eq!(radii, [3.0, 4.0, 6.0, 6.0, 6.2]);
    assert!(!col.is_empty() && col.len() == col.samples.len());
    assert!(mtmotion::toolpath::SegmentColumns::default().is_empty());
}

#[test]
fn columns_equal_the_segment_statistics_when_the_series_are_thinned() {
    // About 1.2 M samples at dt = 0.1 ms: the series keep every second
    // sample. Half circles up, each row out and back along itself.
    let mut text = String::from("G21 G90 G17 G0 X0 Y0 Z0\nG1 X3 F60\n");
    for k in 0..25 {
        let y = 0.5 * f64::from(k + 1);
        let x = 4 + k % 3;
        text.push_str(&format!("G3 X3 Y{y:.1} I0 J0.25\nG1 X{x}\nG1 X3\n"));
    }
    let cfg = SimConfig {
        dt: 1e-4,
        ..SimConfig::default()
    };
    let p = parse(&text).unwrap();
    let (sim, _) = simulate_columns(&p.segments, &p.segments, &cfg, &mut |_| true).unwrap();
    assert!(
        sim.samples > 1_000_000 && sim.series_stride == 2,
        "{}",
        sim.samples
    );
    assert_eq!(same(&text, &cfg), 76);
}
