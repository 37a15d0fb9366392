//! The fuzz targets and their seeds, shared by the stable-Rust loop
//! (`tests/fuzz.rs`) and the cargo-fuzz crate (`fuzz/`, libFuzzer on a
//! nightly toolchain), so both check exactly the same properties:
//!
//! - [`nc_target`]: the NC lexer and interpreter (`parse_all`): every
//!   segment finite;
//! - [`nc_write_target`]: the writer round trips: `parse → write → parse`
//!   gives the same segments within [`WRITTEN_MM`] (the absolute-mm writer,
//!   `nc::writer`), and so does the source-preserving writer
//!   (`nc::patch::write_source`) given the program's own segments;
//! - [`ballbar_target`]: the ball-bar trace import, then the ISO 230-4 test;
//! - [`servo_target`]: the servo trace import (`Table::parse`, the column
//!   lookup, the feed-vector trace analysis);
//! - [`config_target`]: JSON → each config type a wasm export deserialises
//!   (the same serde derive), then the validation or, where cheap, the
//!   call itself, whose result must be finite.
//!
//! A target returns `Err` for a property that fails; a panic is a crash.
#![allow(dead_code)]

use mtmotion::ballbar::{circular_test, parse_ballbar_trace, synthetic_trace, ParseOptions};
use mtmotion::nc::program::{parse_all, Motion, ParseOptions as NcOptions, Program, Segment};
use mtmotion::trace::Table;

/// Largest input the NC targets read, bytes: a window of a real program
/// keeps one execution in milliseconds.
pub const MAX_NC_BYTES: usize = 16 * 1024;

/// The executed-block budget of the NC targets
/// ([`NcOptions::max_executed_blocks`]), 1 % of the product's
/// ([`mtmotion::budget::MAX_EXECUTED_BLOCKS`], 1,000,000): macro loops,
/// subprogram repeats and o-word calls still run, and still meet their
/// budget errors (a loop after 2,500 iterations), but an endless loop
/// costs milliseconds instead of seconds, so the fuzzer reaches a million
/// executions (`scripts/fuzz`).
pub const FUZZ_EXECUTED_BLOCKS: usize = 10_000;

/// The interpreter options of the NC targets: the defaults with the
/// smaller [`FUZZ_EXECUTED_BLOCKS`] budget.
pub fn nc_fuzz_options() -> NcOptions {
    NcOptions {
        max_executed_blocks: FUZZ_EXECUTED_BLOCKS,
        ..NcOptions::default()
    }
}

/// Round-trip tolerance on positions, centres, radii, mm (degrees for
/// A/B/C): the writer rounds each number to 4 decimals (±0.05 µm); a
/// centre read back from I/J/K or R and a radius read back from rounded
/// points move by up to about 0.15 µm (`nc::writer::REREAD_MM` for R).
pub const WRITTEN_MM: f64 = 2e-4;

/// Round-trip tolerance on feeds, relative: 4 written decimals of an inch
/// feed converted to mm/min (feeds below 0.001 mm/min are written exactly).
pub const WRITTEN_REL: f64 = 1e-6;

/// Round-trip tolerance on dwells, s: 4 written decimals of seconds, or an
/// integer millisecond P rounded (when it was not one, it is written exactly).
const WRITTEN_S: f64 = 1e-4;

/// Round-trip tolerance on an arc's sweep, rad: [`WRITTEN_MM`] on a 1 mm
/// radius (a smaller arc gets `WRITTEN_MM / radius`).
const WRITTEN_RAD: f64 = 2e-4;

fn finite(v: &[f64]) -> bool {
    v.iter().all(|x| x.is_finite())
}

/// The NC target: lexer + interpreter.
pub fn nc_target(text: &str) -> Result<(), String> {
    if text.len() > MAX_NC_BYTES {
        return Ok(());
    }
    let Ok(p) = parse_all(text, &nc_fuzz_options()) else {
        return Ok(());
    };
    for s in &p.segments {
        let ends = [s.end.x, s.end.y, s.end.z, s.end.a, s.end.b, s.end.c, s.feed];
        if !finite(&ends) {
            return Err(format!(
                "line {}: a segment with a non-finite value",
                s.line
            ));
        }
    }
    Ok(())
}

/// `a` and `b` within `WRITTEN_MM` plus the float error of their size.
fn near(a: f64, b: f64) -> bool {
    (a - b).abs() <= WRITTEN_MM + 1e-12 * a.abs().max(b.abs())
}

fn near_rel(a: f64, b: f64) -> bool {
    (a - b).abs() <= WRITTEN_REL * a.abs().max(b.abs()).max(1.0)
}

/// Why segment `b` (read back) differs from `a` (the original), if it does.
fn segment_difference(a: &Segment, b: &Segment) -> Option<String> {
    for i in 0..6 {
        if !near(a.end.get(i), b.end.get(i)) {
            return Some(format!(
                "end axis {i}: {} became {}",
                a.end.get(i),
                b.end.get(i)
            ));
        }
    }
    if !near_rel(a.feed, b.feed) {
        return Some(format!("feed {} became {}", a.feed, b.feed));
    }
    match (a.motion, b.motion) {
        (Motion::Rapid, Motion::Rapid) | (Motion::Linear, Motion::Linear) => None,
        (Motion::Dwell { seconds: x }, Motion::Dwell { seconds: y }) => {
            ((x - y).abs() > WRITTEN_S).then(|| format!("dwell {x} s became {y} s"))
        }
        (Motion::Arc(x), Motion::Arc(y)) => {
            let centre = (0..3).all(|k| near(x.center[k], y.center[k]));
            let sweep = (x.sweep - y.sweep).abs() <= WRITTEN_RAD.max(WRITTEN_MM / x.radius);
            if x.plane != y.plane || !centre || !near(x.radius, y.radius) || !sweep {
                Some(format!("arc {x:?} became {y:?}"))
            } else {
                None
            }
        }
        (x, y) => Some(format!("motion {x:?} became {y:?}")),
    }
}

/// `q` (a written program read back) has the segments of `p`.
pub fn same_segments(p: &Program, q: &Program) -> Result<(), String> {
    if q.segments.len() != p.segments.len() {
        return Err(format!(
            "round trip: the written program has {} segments, the original {}",
            q.segments.len(),
            p.segments.len()
        ));
    }
    for (k, (a, b)) in p.segments.iter().zip(&q.segments).enumerate() {
        if let Some(d) = segment_difference(a, b) {
            return Err(format!(
                "round trip: segment {k} (line {} → {}): {d}",
                a.line, b.line
            ));
        }
    }
    Ok(())
}

/// The writer target: both writers' round trips of a program that parses.
pub fn nc_write_target(text: &str) -> Result<(), String> {
    if text.len() > MAX_NC_BYTES {
        return Ok(());
    }
    let opts = nc_fuzz_options();
    let Ok(p) = parse_all(text, &opts) else {
        return Ok(());
    };
    let written = mtmotion::nc::writer::write(&p, &p.segments);
    let q = parse_all(&written, &opts).map_err(|e| {
        format!("round trip: the written program does not parse: {e}\n  written: {written:?}")
    })?;
    same_segments(&p, &q).map_err(|e| format!("{e}\n  written: {written:?}"))?;
    let source = mtmotion::nc::patch::write_source(text, &p, &p.segments);
    if source != text {
        return Err(format!(
            "round trip: write_source changed a program with its own segments\n  written: {source:?}"
        ));
    }
    Ok(())
}

/// The ball-bar target: import, then the circular test when it imports.
pub fn ballbar_target(text: &str) -> Result<(), String> {
    let Ok(t) = parse_ballbar_trace(text, ParseOptions::default()) else {
        return Ok(());
    };
    for r in &t.runs {
        if !finite(&r.angle) || !finite(&r.deviation) {
            return Err("an imported run with a non-finite value".into());
        }
    }
    if let Ok(c) = circular_test(&t) {
        for r in &c.runs {
            if !finite(&[r.g_um, r.f_max_um, r.f_min_um, r.radius_mm]) {
                return Err("a circular-test result with a non-finite value".into());
            }
        }
    }
    Ok(())
}

/// The servo-trace target: the table, the column lookup with scaling and
/// the feed-vector analysis of the paper's condition.
pub fn servo_target(text: &str) -> Result<(), String> {
    let Ok(t) = Table::parse(text) else {
        return Ok(());
    };
    for c in &t.columns {
        if !finite(c) {
            return Err("a trace column with a non-finite value".into());
        }
    }
    let _ = t.column(&["time", "t"], 1e-3);
    let _ = t.column_at(1, 1.0);
    for n in &t.names {
        let _ = mtmotion::trace::name_unit(n);
    }
    use mtmotion::feed_vector::{trace_analysis, Condition};
    let map = trace_analysis::ColumnMap::default();
    if let Ok(r) = trace_analysis::analyze_trace(text, &Condition::paper(1.0), &map) {
        let m = &r.summary;
        let summary = [
            m.mean_angle_diff,
            m.half_amplitude,
            m.radius_decrease,
            m.peak_torque,
        ];
        if !finite(&summary) {
            return Err(format!(
                "a feed-vector summary with a non-finite value: {summary:?}"
            ));
        }
        let s = &r.series;
        for (name, v) in [
            ("t", &s.t),
            ("c_cmd", &s.c_cmd),
            ("shape_error", &s.shape_error),
            ("alpha", &s.alpha),
            ("beta", &s.beta),
            ("angle_diff", &s.angle_diff),
            ("radius_error", &s.radius_error),
            ("omega_c", &s.omega_c),
            ("omega_l", &s.omega_l),
        ] {
            if !finite(v) {
                return Err(format!(
                    "a feed-vector series {name} with a non-finite value"
                ));
            }
        }
    }
    Ok(())
}

/// Deserialises `value` as `$t`, or ends the target (rejected input).
macro_rules! de {
    ($value:expr, $t:ty) => {
        match serde_json::from_value::<$t>($value.clone()) {
            Ok(x) => x,
            Err(_) => return Ok(()),
        }
    };
}

/// The config target: JSON `{"type": …, "value": …}` chooses the type.
pub fn config_target(text: &str) -> Result<(), String> {
    let Ok(v) = serde_json::from_str::<serde_json::Value>(text) else {
        return Ok(());
    };
    let kind = v.get("type").and_then(|t| t.as_str()).unwrap_or("");
    let value = v.get("value").cloned().unwrap_or(serde_json::Value::Null);
    config_servo(kind, &value)?;
    config_toolpath(kind, &value)?;
    config_ballbar(kind, &value)?;
    config_geometry(kind, &value)
}

/// The servo exports' configs.
fn config_servo(kind: &str, value: &serde_json::Value) -> Result<(), String> {
    use mtmotion::{best_kffp, feed_vector, servo};
    match kind {
        "axis" => {
            let a = de!(value, servo::AxisParams);
            if a.validate().is_ok() {
                let r = servo::response::frequency_response(&a, &[1.0, 100.0])
                    .map_err(|e| e.to_string())?;
                if !finite(&r.magnitude) || !finite(&r.phase) {
                    return Err("frequency response not finite".into());
                }
            }
        }
        "condition" => {
            let _ = de!(value, feed_vector::Condition).validate();
        }
        "mapping" => {
            let _ = de!(value, feed_vector::trace_analysis::ColumnMap);
        }
        "kffpOptions" => {
            let _ = de!(value, best_kffp::Options);
        }
        "saturation" => {
            let _ = de!(value, best_kffp::saturation::SaturationQuery);
        }
        "pitch" => {
            let _ = de!(value, servo::pitch_identify::PitchIdentifyOptions);
        }
        "measured" => {
            let _ = de!(value, servo::identify::MeasuredTrace);
        }
        "machine" => {
            let m = de!(value, mtmotion::machine::Machine);
            for a in m.axes.values() {
                let _ = a.validate();
            }
        }
        _ => {}
    }
    Ok(())
}

/// The tool-path and NC exports' configs.
fn config_toolpath(kind: &str, value: &serde_json::Value) -> Result<(), String> {
    use mtmotion::{compensate, toolpath};
    match kind {
        "toolpath" => {
            let _ = de!(value, toolpath::SimConfig).validate();
        }
        "reverse" => {
            let _ = de!(value, compensate::reverse::ReverseConfig);
        }
        "eq3" => {
            let (f, r, ta, t) = de!(value, (f64, f64, f64, f64));
            if let Ok(dr) = toolpath::identify::radius_reduction(f, r, ta, t) {
                if !dr.is_finite() {
                    return Err(format!("radius_reduction({f}, {r}, {ta}, {t}) = {dr}"));
                }
            }
        }
        "losses" => {
            let d = de!(value, Vec<toolpath::identify::CircleLoss>);
            if d.len() <= 8 {
                if let Ok(a) = toolpath::identify::identify_acc_dec(&d) {
                    if !finite(&[a.t_a, a.t, a.residual]) {
                        return Err("identify_acc_dec not finite".into());
                    }
                }
            }
        }
        "ncOptions" => {
            let _ = de!(value, NcOptions);
        }
        "files" => {
            let files = de!(value, Vec<mtmotion::nc::program::NcFile>);
            let opts = NcOptions::default();
            let main = "M98 P1000\nM30\n";
            let _ = mtmotion::nc::program::parse_files(main, &files, &opts);
        }
        _ => {}
    }
    Ok(())
}

/// The ball-bar and alignment exports' configs.
fn config_ballbar(kind: &str, value: &serde_json::Value) -> Result<(), String> {
    use mtmotion::{alignment, ballbar};
    match kind {
        "sweep" => {
            let _ = de!(value, alignment::SweepConfig).locus.validate("");
        }
        "angleSweep" => {
            let _ = de!(value, alignment::AngleSweepConfig).locus.validate("");
        }
        "synthetic" => {
            let mut c = de!(value, ballbar::SyntheticConfig);
            c.samples = c.samples.min(64);
            if let Ok(t) = synthetic_trace(&c) {
                if t.runs.iter().any(|r| !finite(&r.deviation)) {
                    return Err("synthetic trace not finite".into());
                }
            }
        }
        "ballbarOptions" => {
            let _ = de!(value, ParseOptions);
        }
        _ => {}
    }
    Ok(())
}

/// The kinematics and 5-axis exports' configs.
fn config_geometry(kind: &str, value: &serde_json::Value) -> Result<(), String> {
    use mtmotion::{compensate, cone_frustum, kinematics, machine};
    match kind {
        "cone" => {
            let _ = de!(value, cone_frustum::ConeFrustumConfig);
        }
        "nc5" => {
            let _ = de!(value, compensate::nc5::Nc5Config);
        }
        "sshape" => {
            let o = de!(value, compensate::nc5::s_shape::SShapeOptions);
            if let Ok(s) = compensate::nc5::s_shape::s_shape(&o) {
                if s.points.iter().any(|p| !finite(p)) {
                    return Err("S-shape points not finite".into());
                }
            }
        }
        "forward" => {
            let (m, q, e) = de!(
                value,
                (machine::MachineRef, [f64; 6], kinematics::GeometricErrors)
            );
            if let Ok((_, chain)) = m.resolve() {
                if let Ok(p) = kinematics::forward(&chain, &q, &e, 0.0) {
                    if q.iter().all(|v| v.abs() < 1e6)
                        && (!finite(&p.position) || !finite(&p.orientation))
                    {
                        return Err(format!("forward({q:?}) not finite"));
                    }
                }
            }
        }
        "pose" => {
            let _ = de!(value, kinematics::Pose);
        }
        _ => {}
    }
    Ok(())
}

/// A target: text in, a failed property out.
pub type Target = fn(&str) -> Result<(), String>;

/// Every target by name, with its seeds.
pub fn targets() -> Vec<(&'static str, Target, Vec<String>)> {
    vec![
        ("nc", nc_target as Target, nc_seeds()),
        ("nc_write", nc_write_target, nc_seeds()),
        ("ballbar", ballbar_target, ballbar_seeds()),
        ("servo", servo_target, servo_seeds()),
        ("config", config_target, config_seeds()),
    ]
}

/// The shared NC corpus when it is there (`MTMOTION_NC_CORPUS`, else
/// `../shared/nc_corpus` from the project root or, for the `fuzz/` crate,
/// from its parent; a window of each file's first 4 kB), the tool-path
/// examples, a program with a subprogram called twice, an inch program,
/// one with G68/G69 coordinate rotations and a Haas-style one (M97 local
/// subprograms with repeats, M99 P, G187, G103).
pub fn nc_seeds() -> Vec<String> {
    let root = env!("CARGO_MANIFEST_DIR");
    let dir = std::env::var("MTMOTION_NC_CORPUS")
        .ok()
        .into_iter()
        .chain([
            format!("{root}/../shared/nc_corpus"),
            format!("{root}/../../shared/nc_corpus"),
        ])
        .find(|d| std::path::Path::new(d).is_dir());
    let mut out: Vec<String> = dir
        .and_then(|d| std::fs::read_dir(d).ok())
        .into_iter()
        .flatten()
        .filter_map(|e| e.ok())
        .filter(|e| !e.file_name().to_string_lossy().ends_with(".md"))
        .map(|e| {
            let t = std::fs::read_to_string(e.path()).unwrap_or_default();
            t.char_indices()
                .take_while(|(i, _)| *i < 4096)
                .map(|(_, c)| c)
                .collect()
        })
        .collect();
    out.sort();
    out.push(mtmotion::toolpath::example::arc_example());
    out.push(mtmotion::toolpath::example::line_example());
    out.push("G21 G90\nG0 X0 Y0 Z10\nG66 P9110 R2 Z-5 F100 L2\nX10 Y10\nM8\nG91 X5\nG90 G67\nX30\nG66 P9110 R1 Z-1\nM98 P9110\nG67\nM30\nO9110\nG1 Z#26 F#9\nG0 Z#18 X[#5001+1]\nM99\n".into());
    out.push("G21 G90 G17\nG0 @10 ^30 Z1\nG1 ^90 F600\nG91 G1 @-2 ^45\nG92 X0 Y0\nG90 G1 @5\nG91 G81 R1 Z-2 ^60 L6\nG80 G90 G0 Z5\nM30\n".into());
    out.push("O100\nG90 G17 G21\nG0 X0 Y0\nG1 X10 F600\nG2 X20 Y0 R5\nG3 X10 Y0 I-5 J0\nG4 P500\nM98 P200 L2\nM30\nO200\nG91 G1 X1\nM99\n".into());
    out.push("%\nO1234\nN10 G187 P1 E0.01\nN20 G103 P1\nN30 G0 X0 Y0\nN40 M97 P1000 L2\nN50 M98 P200\nN60 G1 X5 F600\nN70 M30\nN1000 G91 G1 X1 F500\nY1\nG90\nM99\nO200\nG91 G2 X0 Y0 I2 J0\nG90\nM99 P60\n%\n".into());
    out.push(
        "G20 G90 G17\nG0 X0 Y0\nG2 X0.5 Y0.5 R0.5 F20\nG3 X1.0 Y0 R-0.5\nG18 G2 X1.2 Z0.2 R0.2\n"
            .into(),
    );
    out.push(
        "G90 G17 G21\nG0 X0 Y0 Z5\nG68 X5 Y5 R30\nG1 X10 F600\nG2 X20 Y0 R5\nG91 G3 X-10 Y0 I-5 J0\nG68 R15\nG90 G81 X3 Y3 Z-1 R1\nG80\nG69 G0 X0 Y0\nG19 G68 Y1 Z2 R-45\nG1 Y4 Z4\nG69\nM30\n"
            .into(),
    );
    out
}

/// Generated ball-bar traces: angle + deviation, X/Y, a short one.
pub fn ballbar_seeds() -> Vec<String> {
    let mut t = synthetic_trace(&mtmotion::ballbar::SyntheticConfig {
        samples: 72,
        backlash_x: 0.004,
        ..Default::default()
    })
    .unwrap();
    t.runs.iter_mut().for_each(|r| r.deviation.truncate(80));
    let mut ad = String::from("time [s],angle [deg],deviation [um],direction\n");
    for (k, r) in t.runs.iter().enumerate() {
        for (i, (a, d)) in r.angle.iter().zip(&r.deviation).enumerate() {
            let dir = if k == 0 { 1 } else { -1 };
            ad += &format!("{},{},{},{dir}\n", i as f64 * 0.01, a.to_degrees(), d * 1e3);
        }
    }
    let mut xy = String::from("X [mm]\tY [mm]\n");
    for i in 0..90 {
        let th = (i as f64 * 4.0).to_radians();
        xy += &format!("{}\t{}\n", 100.0 * th.cos(), 100.0 * th.sin());
    }
    vec![ad, xy, "angle,deviation\n0,1\n90,2\n180,1\n270,0\n".into()]
}

/// Generated servo traces: a SERVO GUIDE-like export and small tables.
pub fn servo_seeds() -> Vec<String> {
    let mut s =
        String::from("SERVO GUIDE export\n# comment\nTime [ms];X(mm);Y [um];C [deg];Torque (Nm)\n");
    for i in 0..60 {
        let t = i as f64;
        s += &format!(
            "{t};{};{};{};{}\n",
            (t / 9.0).cos(),
            (t / 9.0).sin() * 1e3,
            t * 0.5,
            (t / 3.0).sin()
        );
    }
    vec![
        s,
        "time,x\n0,1\n1,2\n".into(),
        "a b c\n1 2 3\n4 5 6\n".into(),
    ]
}

/// Each export's config as JSON `{"type": …, "value": …}`.
pub fn config_seeds() -> Vec<String> {
    let m = mtmotion::machine::preset("nmv5000").unwrap();
    let wrap = |t: &str, v: String| format!(r#"{{"type":"{t}","value":{v}}}"#);
    let j = |v: &dyn erased::Ser| v.json();
    vec![
        wrap("axis", j(&m.axes["c"])),
        wrap("machine", j(&m)),
        wrap("condition", j(&mtmotion::feed_vector::Condition::paper(1.0))),
        wrap("mapping", j(&mtmotion::feed_vector::trace_analysis::ColumnMap::default())),
        wrap("kffpOptions", j(&mtmotion::best_kffp::Options::default())),
        wrap("saturation", r#"{"j1":[0,1.7],"torqueMax":725,"accelTime":0.064,"feedAtCuttingPoint":200,"dt":0.001}"#.into()),
        wrap("toolpath", j(&mtmotion::toolpath::SimConfig::default())),
        wrap("reverse", j(&mtmotion::compensate::reverse::ReverseConfig::default())),
        wrap("eq3", "[2000, 10, 0.04, 0.015]".into()),
        wrap("losses", r#"[{"feed":2000,"radius":3,"radiusLoss":0.01},{"feed":4000,"radius":5,"radiusLoss":0.02},{"feed":1000,"radius":10,"radiusLoss":0.001}]"#.into()),
        wrap("sweep", r#"{"offset":{"z":0,"x":0.01},"harmonics":[{"order":2,"amplitude":0.005,"phase":0}],"ranges":[180,360],"radius":100,"samples":1000}"#.into()),
        wrap("angleSweep", r#"{"sections":[{"y":0,"offset":{"z":0,"x":0.01}},{"y":100,"offset":{"z":0.01,"x":0}}],"ranges":[90,180],"samples":500}"#.into()),
        wrap("synthetic", j(&mtmotion::ballbar::SyntheticConfig::default())),
        wrap("cone", r#"{"machine":"trunnion-ac","halfApexDeg":15,"inclinationDeg":10,"method":"perpendicular","barLength":100,"feed":1000}"#.into()),
        wrap("nc5", r#"{"machine":"pocketnc-v2-10","monteCarlo":{"seed":3,"sigmaMm":0.01},"compensateAxes":["x","y"]}"#.into()),
        wrap("sshape", r#"{"machine":"pocketnc-v2-10","scale":0.5,"feed":1000,"origin":[0,0,0]}"#.into()),
        wrap("forward", r#"["trunnion-ac",[10,0,0,20,0,90],{"location":{"EC0C":0.001},"component":{"EXX":[0,1e-5]}}]"#.into()),
        wrap("pose", r#"{"position":[1,2,3],"orientation":[0,0,1]}"#.into()),
        wrap("pitch", r#"{"samples":4096,"maxOrder":20,"threshold":1e-6,"maxPeaks":4}"#.into()),
        wrap("measured", r#"{"dt":0.001,"command":[0,1,2],"position":[0,0.5,1.5],"torque":[0,1,1]}"#.into()),
        wrap("ballbarOptions", r#"{"nominalRadius":100,"feed":1000}"#.into()),
        wrap("ncOptions", r#"{"dwellP":"ms","skipBlockDelete":true,"cAxis":false}"#.into()),
        wrap("files", r#"[{"name":"O1000.nc","text":"O1000\nG91 G1 X1 F100\nM99\n"}]"#.into()),
    ]
}

/// Serialises any config to JSON without naming its type at the call.
mod erased {
    pub trait Ser {
        fn json(&self) -> String;
    }
    impl<T: serde::Serialize> Ser for T {
        fn json(&self) -> String {
            serde_json::to_string(self).unwrap()
        }
    }
}
