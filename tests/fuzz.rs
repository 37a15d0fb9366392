//! A stable-Rust fuzz loop over the parsers and the config conversion:
//! seeded mutation of corpus seeds (the repo's NC corpus, generated
//! ball-bar and servo traces, each export's config as JSON), fed to
//!
//! - `nc`: the NC lexer and interpreter (`parse_all`), then the writer
//!   round trip (`write` of the parsed segments parses again);
//! - `ballbar`: the ball-bar trace import, then the ISO 230-4 test on it;
//! - `servo`: the servo trace import (`Table::parse`, the column lookup);
//! - `config`: JSON → each export's config type (native serde_json, the
//!   same derive the wasm binding uses), then its validation or, where the
//!   call is cheap, the call itself.
//!
//! A crash is a panic (caught per input, the input is written to
//! `target/fuzz-crashes/`) or a result with NaN/∞ where the API promises
//! finite numbers. A written program that parses to a different number of
//! segments is a round-trip mismatch: counted and shown, not a crash (the
//! writer rewrites a subprogram body executed twice as two absolute blocks,
//! so `M98 P200 L2` with a `G91` body gains segments). `cargo test --test fuzz` runs a short, fixed loop;
//! `scripts/fuzz` runs the ignored `fuzz_long` with `FUZZ_EXECS` inputs per
//! target (default 1,000,000) and prints counts and times. Each crash
//! found becomes a regression test in `fuzz_regressions` below.
#![cfg(not(target_arch = "wasm32"))]

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::time::Instant;

use mtmotion::ballbar::{circular_test, parse_ballbar_trace, synthetic_trace, ParseOptions};
use mtmotion::nc::program::{parse_all, ParseOptions as NcOptions};
use mtmotion::trace::Table;

/// SplitMix64: a seeded generator, so a run is reproducible from its seed.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            (self.next() % n as u64) as usize
        }
    }
}

/// Tokens a mutation inserts: line ends, encodings, extreme numbers, NC
/// and JSON syntax.
const TOKENS: &[&str] = &[
    "\n",
    "\r",
    "\r\n",
    "\u{feff}",
    "\u{1a}",
    "\u{0}",
    "\u{7}",
    "\t",
    ",",
    ";",
    " ",
    "%",
    "(",
    ")",
    "[",
    "]",
    "{",
    "}",
    "\"",
    ":",
    "-",
    ".",
    "e",
    "E",
    "1e308",
    "-1e308",
    "1e999",
    "5e-324",
    "1e-320",
    "NaN",
    "inf",
    "-0",
    "0",
    "4294967297",
    "9007199254740993",
    "null",
    "true",
    "[]",
    "{}",
    "G0",
    "G1",
    "G2",
    "G3",
    "G4",
    "G17",
    "G18",
    "G19",
    "G20",
    "G81",
    "G90",
    "G91",
    "M98",
    "M99",
    "O1",
    "P",
    "L",
    "Q",
    "R",
    "X",
    "Y",
    "Z",
    "A",
    "B",
    "C",
    "I",
    "J",
    "K",
    "F",
    "N",
    "#1",
    "[#1+1]",
    "/",
    "µ",
    "°",
    "é",
];

/// One mutation of `input` (byte-level; the result is made valid UTF-8
/// the way a browser decodes a file: invalid bytes become U+FFFD).
fn mutate(rng: &mut Rng, input: &str, seeds: &[String]) -> String {
    let mut b = input.as_bytes().to_vec();
    for _ in 0..1 + rng.below(4) {
        let at = rng.below(b.len() + 1);
        match rng.below(8) {
            0 if !b.is_empty() => {
                let i = rng.below(b.len());
                b[i] ^= 1 << rng.below(8);
            }
            1 | 2 => {
                let t = TOKENS[rng.below(TOKENS.len())].as_bytes();
                b.splice(at..at, t.iter().copied());
            }
            3 if !b.is_empty() => {
                let end = (at + 1 + rng.below(16)).min(b.len());
                b.drain(at.min(end)..end);
            }
            4 if !b.is_empty() => {
                let start = rng.below(b.len());
                let end = (start + 1 + rng.below(64)).min(b.len());
                let piece = b[start..end].to_vec();
                b.splice(at..at, piece);
            }
            5 => {
                let other = seeds[rng.below(seeds.len())].as_bytes();
                if !other.is_empty() {
                    let start = rng.below(other.len());
                    let end = (start + 1 + rng.below(256)).min(other.len());
                    b.splice(at..at, other[start..end].iter().copied());
                }
            }
            6 => {
                // Replace a run of digits by an extreme number.
                let nums = [
                    "1e308",
                    "5e-324",
                    "0",
                    "-0",
                    "1e999",
                    "99999999999999999999",
                ];
                let n = nums[rng.below(nums.len())].as_bytes();
                let mut end = at;
                while end < b.len() && (b[end].is_ascii_digit() || b[end] == b'.') {
                    end += 1;
                }
                b.splice(at..end, n.iter().copied());
            }
            _ if !b.is_empty() => {
                let i = rng.below(b.len());
                b[i] = rng.next() as u8;
            }
            _ => {}
        }
    }
    String::from_utf8_lossy(&b).into_owned()
}

fn finite(v: &[f64]) -> bool {
    v.iter().all(|x| x.is_finite())
}

/// The NC target: lexer + interpreter, then the writer round trip.
fn nc_target(text: &str) -> Result<(), String> {
    let opts = NcOptions::default();
    let Ok(p) = parse_all(text, &opts) else {
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
    let written = mtmotion::nc::writer::write(&p, &p.segments);
    if let Ok(q) = parse_all(&written, &opts) {
        if q.segments.len() != p.segments.len() {
            return Err(format!(
                "round trip: the written program has {} segments, the original {}",
                q.segments.len(),
                p.segments.len()
            ));
        }
    }
    Ok(())
}

/// The ball-bar target: import, then the circular test when it imports.
fn ballbar_target(text: &str) -> Result<(), String> {
    let Ok(t) = parse_ballbar_trace(text, ParseOptions::default()) else {
        return Ok(());
    };
    for r in &t.runs {
        if !finite(&r.angle) || !finite(&r.deviation) {
            return Err("an imported run with a non-finite value".into());
        }
    }
    if let Ok(c) = circular_test(&t) {
        let json = serde_json::to_string(&c).map_err(|e| e.to_string())?;
        if json.contains("null") && c.diagnostics.is_none() && c.h_um.is_none() {
            return Ok(());
        }
        for r in &c.runs {
            if !finite(&[r.g_um, r.f_max_um, r.f_min_um, r.radius_mm]) {
                return Err("a circular-test result with a non-finite value".into());
            }
        }
    }
    Ok(())
}

/// The servo-trace target: the table and the column lookup with scaling.
fn servo_target(text: &str) -> Result<(), String> {
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
    Ok(())
}

/// The config target: JSON `{"type": …, "value": …}` chooses the type.
fn config_target(text: &str) -> Result<(), String> {
    use mtmotion::{alignment, ballbar, best_kffp, compensate, cone_frustum, feed_vector};
    use mtmotion::{kinematics, machine, servo, toolpath};
    let Ok(v) = serde_json::from_str::<serde_json::Value>(text) else {
        return Ok(());
    };
    let kind = v.get("type").and_then(|t| t.as_str()).unwrap_or("");
    let value = v.get("value").cloned().unwrap_or(serde_json::Value::Null);
    macro_rules! de {
        ($t:ty) => {
            match serde_json::from_value::<$t>(value.clone()) {
                Ok(x) => x,
                Err(_) => return Ok(()),
            }
        };
    }
    match kind {
        "axis" => {
            let a = de!(servo::AxisParams);
            if a.validate().is_ok() {
                let r = servo::response::frequency_response(&a, &[1.0, 100.0])
                    .map_err(|e| e.to_string())?;
                if !finite(&r.magnitude) || !finite(&r.phase) {
                    return Err("frequency response not finite".into());
                }
            }
        }
        "condition" => {
            let _ = de!(feed_vector::Condition).validate();
        }
        "mapping" => {
            let _ = de!(feed_vector::trace_analysis::ColumnMap);
        }
        "kffpOptions" => {
            let _ = de!(best_kffp::Options);
        }
        "saturation" => {
            let _ = de!(best_kffp::saturation::SaturationQuery);
        }
        "toolpath" => {
            let _ = de!(toolpath::SimConfig).validate();
        }
        "reverse" => {
            let _ = de!(compensate::reverse::ReverseConfig);
        }
        "eq3" => {
            let (f, r, ta, t) = de!((f64, f64, f64, f64));
            if let Ok(dr) = toolpath::identify::radius_reduction(f, r, ta, t) {
                if !dr.is_finite() {
                    return Err(format!("radius_reduction({f}, {r}, {ta}, {t}) = {dr}"));
                }
            }
        }
        "losses" => {
            let d = de!(Vec<toolpath::identify::CircleLoss>);
            if d.len() <= 8 {
                if let Ok(a) = toolpath::identify::identify_acc_dec(&d) {
                    if !finite(&[a.t_a, a.t, a.residual]) {
                        return Err("identify_acc_dec not finite".into());
                    }
                }
            }
        }
        "sweep" => {
            let _ = de!(alignment::SweepConfig).locus.validate("");
        }
        "angleSweep" => {
            let _ = de!(alignment::AngleSweepConfig).locus.validate("");
        }
        "synthetic" => {
            let mut c = de!(ballbar::SyntheticConfig);
            c.samples = c.samples.min(64);
            if let Ok(t) = synthetic_trace(&c) {
                if t.runs.iter().any(|r| !finite(&r.deviation)) {
                    return Err("synthetic trace not finite".into());
                }
            }
        }
        "cone" => {
            let _ = de!(cone_frustum::ConeFrustumConfig);
        }
        "nc5" => {
            let _ = de!(compensate::nc5::Nc5Config);
        }
        "sshape" => {
            let o = de!(compensate::nc5::s_shape::SShapeOptions);
            if let Ok(s) = compensate::nc5::s_shape::s_shape(&o) {
                if s.points.iter().any(|p| !finite(p)) {
                    return Err("S-shape points not finite".into());
                }
            }
        }
        "forward" => {
            let (m, q, e) = de!((machine::MachineRef, [f64; 6], kinematics::GeometricErrors));
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
            let _ = de!(kinematics::Pose);
        }
        "pitch" => {
            let _ = de!(servo::pitch_identify::PitchIdentifyOptions);
        }
        "measured" => {
            let _ = de!(servo::identify::MeasuredTrace);
        }
        "ballbarOptions" => {
            let _ = de!(ParseOptions);
        }
        "ncOptions" => {
            let _ = de!(NcOptions);
        }
        _ => {}
    }
    Ok(())
}

fn nc_seeds() -> Vec<String> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/nc_corpus");
    let mut out: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| !e.file_name().to_string_lossy().ends_with(".md"))
        .map(|e| {
            let t = std::fs::read_to_string(e.path()).unwrap_or_default();
            // A window of the first 4 kB keeps one execution short.
            t.char_indices()
                .take_while(|(i, _)| *i < 4096)
                .map(|(_, c)| c)
                .collect()
        })
        .collect();
    out.sort();
    out.push(mtmotion::toolpath::example::arc_example());
    out.push(mtmotion::toolpath::example::line_example());
    out.push("O100\nG90 G17 G21\nG0 X0 Y0\nG1 X10 F600\nG2 X20 Y0 R5\nG3 X10 Y0 I-5 J0\nG4 P500\nM98 P200 L2\nM30\nO200\nG91 G1 X1\nM99\n".into());
    out
}

fn ballbar_seeds() -> Vec<String> {
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

fn servo_seeds() -> Vec<String> {
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

fn config_seeds() -> Vec<String> {
    let m = mtmotion::machine::preset("nmv5000").unwrap();
    let wrap = |t: &str, v: String| format!(r#"{{"type":"{t}","value":{v}}}"#);
    let j = |v: &dyn erased::Ser| v.json();
    vec![
        wrap("axis", j(&m.axes["c"])),
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

type Target = fn(&str) -> Result<(), String>;

fn targets() -> Vec<(&'static str, Target, Vec<String>)> {
    vec![
        ("nc", nc_target as Target, nc_seeds()),
        ("ballbar", ballbar_target, ballbar_seeds()),
        ("servo", servo_target, servo_seeds()),
        ("config", config_target, config_seeds()),
    ]
}

/// Findings of one run: failures (panics, non-finite results; at most 20
/// kept) and writer round-trip mismatches (counted; the first 5 kept).
#[derive(Default)]
struct Findings {
    failures: Vec<(String, String)>,
    round_trips: u64,
    round_trip_examples: Vec<(String, String)>,
}

/// Runs `execs` mutated inputs through `target`.
fn run(name: &str, target: Target, seeds: &[String], execs: u64, seed: u64) -> Findings {
    let mut rng = Rng(seed);
    let mut found = Findings::default();
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let mut current = seeds[0].clone();
    // FUZZ_SAVE_CURRENT=path writes each input there before it runs.
    let save_current = std::env::var("FUZZ_SAVE_CURRENT").ok();
    for k in 0..execs {
        // Mostly mutate a fresh seed; sometimes keep mutating the last input.
        if k % 4 == 0 || current.len() > 64 * 1024 {
            current = seeds[rng.below(seeds.len())].clone();
        }
        current = mutate(&mut rng, &current, seeds);
        let input = current.clone();
        if let Some(path) = &save_current {
            // Kept for an input that aborts the process (out of memory).
            let _ = std::fs::write(path, &input);
        }
        let outcome = catch_unwind(AssertUnwindSafe(|| target(&input)));
        let failure = match outcome {
            Ok(Ok(())) => None,
            Ok(Err(e)) => Some(e),
            Err(p) => Some(format!(
                "panic: {}",
                p.downcast_ref::<String>()
                    .cloned()
                    .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_default()
            )),
        };
        let Some(f) = failure else { continue };
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/target/fuzz-crashes");
        let _ = std::fs::create_dir_all(dir);
        if f.starts_with("round trip") {
            found.round_trips += 1;
            if found.round_trip_examples.len() < 5 {
                let _ = std::fs::write(format!("{dir}/roundtrip-{name}-{seed}-{k}.txt"), &input);
                found.round_trip_examples.push((input, f));
            }
        } else if found.failures.len() < 20 {
            let _ = std::fs::write(format!("{dir}/{name}-{seed}-{k}.txt"), &input);
            found.failures.push((input, f));
        }
    }
    std::panic::set_hook(hook);
    found
}

fn report(failures: &[(String, String)]) -> String {
    failures
        .iter()
        .map(|(i, f)| format!("{f}\n  input: {:?}", mtmotion::budget::clip(i, 300)))
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn fuzz_short() {
    for (name, target, seeds) in targets() {
        let found = run(name, target, &seeds, 300, 7);
        assert!(
            found.failures.is_empty(),
            "{name}:\n{}",
            report(&found.failures)
        );
    }
}

/// `FUZZ_EXECS` (default 1,000,000) inputs per target, `FUZZ_SEED`,
/// `FUZZ_TARGET` (one name, or all).
#[test]
#[ignore]
fn fuzz_long() {
    let execs: u64 = std::env::var("FUZZ_EXECS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1_000_000);
    let seed: u64 = std::env::var("FUZZ_SEED")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1);
    let only = std::env::var("FUZZ_TARGET").ok();
    let mut all = Vec::new();
    for (name, target, seeds) in targets() {
        if only.as_deref().is_some_and(|o| o != name) {
            continue;
        }
        let t0 = Instant::now();
        let found = run(name, target, &seeds, execs, seed);
        println!(
            "fuzz {name}: {execs} executions in {:.1} s, {} failures, {} writer round-trip mismatches",
            t0.elapsed().as_secs_f64(),
            found.failures.len(),
            found.round_trips
        );
        if !found.round_trip_examples.is_empty() {
            println!("{}", report(&found.round_trip_examples));
        }
        if !found.failures.is_empty() {
            all.push(format!("{name}:\n{}", report(&found.failures)));
        }
    }
    assert!(all.is_empty(), "{}", all.join("\n"));
}

/// Inputs the fuzz loop once crashed on, each with what it now gives.
#[test]
fn fuzz_regressions() {
    // G83 with a 1e20 mm deep hole and Q0.21: 4.7e20 pecks; the loop
    // allocated until the process was killed (22 GB), and past 2^53 mm
    // `done + q == done` would never have ended.
    let text = "G90 G17 G21 F100\nG83 X0 Y0 R1 Z-99999999999999999999 Q0.21\n";
    let e = mtmotion::nc::program::parse(text).unwrap_err();
    assert_eq!((e.line, e.column), (2, 37));
    assert_eq!(
        e.message,
        "4.7619e20 pecks of Q0.21 mm for a 1e20 mm deep hole; at most 10000 per hole: check Q, R and the bottom level"
    );
    assert!(mtmotion::nc::program::parse("G90 G21 F100\nG83 X0 Y0 R1 Z-999 Q0.125\n").is_ok());
}
