//! Identical numbers everywhere: one golden case per capability, computed
//! by the native build and kept in `tests/golden/golden.json`, which
//! `tests/node/golden.test.mjs` compares with the wasm build in Node (bit
//! for bit, or within the bound documented there where the two builds'
//! libm differ). Arrays are kept as their length, an FNV-1a hash of their
//! IEEE-754 bytes, their largest magnitude and 33 samples; scalars and
//! small results as numbers (serde_json with `float_roundtrip` prints and
//! reads each f64 exactly).
//!
//! This test recomputes the cases and fails when the fixture is stale;
//! after an intended change of a model, rewrite it with
//! `GOLDEN_WRITE=1 cargo test --test golden` and say why in the commit.
#![cfg(not(target_arch = "wasm32"))]

use serde_json::{json, Value};

use mtmotion::alignment::{estimate_alignment, Section};
use mtmotion::ballbar::{circular_test, fit_circle, synthetic_trace, SyntheticConfig};
use mtmotion::cone_frustum::{cone_frustum_test, ConeFrustumConfig};
use mtmotion::feed_vector::{feed_vector_test, Condition};
use mtmotion::kinematics::{forward, q_from_degrees, GeometricErrors};
use mtmotion::machine::preset;
use mtmotion::servo::simulate::simulate_axis;

/// FNV-1a (32 bit) of the little-endian bytes of every value; the Node test
/// computes the same with `Math.imul`.
fn fnv(v: &[f64]) -> u32 {
    let mut h: u32 = 0x811c_9dc5;
    for x in v {
        for b in x.to_le_bytes() {
            h = (h ^ u32::from(b)).wrapping_mul(16_777_619);
        }
    }
    h
}

/// An array as its length, hash, largest magnitude and 33 evenly spaced
/// samples (index `k·(n−1)/32`, integer division; first and last included),
/// enough to bound a difference where the hashes differ.
fn arr(v: &[f64]) -> Value {
    let m = v.len().min(33);
    let sample: Vec<f64> = (0..m)
        .map(|k| {
            v[if m > 1 {
                k * (v.len() - 1) / (m - 1)
            } else {
                0
            }]
        })
        .collect();
    let max_abs = v.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    json!({ "len": v.len(), "fnv": fnv(v), "maxAbs": max_abs, "sample": sample })
}

/// The command of the servo case: a 20 mm/s ramp after 50 ms at rest.
fn ramp() -> Vec<f64> {
    (0..400)
        .map(|i| (i as f64 * 1e-3 - 0.05).max(0.0) * 20.0)
        .collect()
}

fn servo_case() -> Value {
    let m = preset("nmv5000").unwrap();
    let r = simulate_axis(&m.axes["x"], 1e-3, &ramp()).unwrap();
    json!({ "position": arr(&r.position), "velocity": arr(&r.velocity), "torque": arr(&r.torque) })
}

const FEED_VECTOR: &str =
    r#"{"rc":5,"rw":8,"omega":3,"accelTime":0.064,"j1":1.7,"duration":1.5,"dt":0.001}"#;

fn feed_vector_case() -> Value {
    let m = preset("nmv5000").unwrap();
    let c: Condition = serde_json::from_str(FEED_VECTOR).unwrap();
    let r = feed_vector_test(&m, &c).unwrap();
    let s = &r.series;
    json!({
        "summary": serde_json::to_value(r.summary).unwrap(),
        "x": arr(&s.x), "y": arr(&s.y), "c": arr(&s.c), "torqueC": arr(&s.torque_c),
        "shapeError": arr(&s.shape_error), "angleDiff": arr(&s.angle_diff),
    })
}

const TOOLPATH: &str = r#"{"tA":0.04,"T":0.015,"dt":0.001}"#;

fn toolpath_case() -> Value {
    let text = mtmotion::toolpath::example::arc_example();
    let p = mtmotion::nc::program::parse(&text).unwrap();
    let cfg = serde_json::from_str(TOOLPATH).unwrap();
    let s = mtmotion::toolpath::simulate_program(&p, &cfg).unwrap();
    json!({
        "t": arr(&s.t), "simX": arr(&s.sim[0]), "simY": arr(&s.sim[1]),
        "nearX": arr(&s.near[0]), "velSimX": arr(&s.vel_sim[0]),
        "motionTime": s.motion_time, "maxErrorTime": s.max_error_time,
    })
}

const SYNTHETIC: &str =
    r#"{"samples":720,"backlashX":0.004,"offsetX":0.003,"scaleY":2e-5,"noise":0.0005}"#;

/// The X/Y points of the circle fit: computed here and kept as an input,
/// so the fit's input does not depend on either build's `cos`.
fn circle_points() -> (Vec<f64>, Vec<f64>) {
    (0..360)
        .map(|i| {
            let a = (i as f64).to_radians();
            let r = 50.0 + 0.002 * (3.0 * a).sin();
            (1.5 + r * a.cos(), -2.0 + r * a.sin())
        })
        .unzip()
}

fn ballbar_case() -> Value {
    let cfg: SyntheticConfig = serde_json::from_str(SYNTHETIC).unwrap();
    let t = synthetic_trace(&cfg).unwrap();
    let run = &t.runs[0];
    let (x, y) = circle_points();
    json!({
        "deviation": arr(&run.deviation),
        "fitCircle": serde_json::to_value(fit_circle(&x, &y).unwrap()).unwrap(),
        "circularTest": serde_json::to_value(circular_test(&t).unwrap()).unwrap(),
    })
}

const FORWARD_Q: [f64; 6] = [10.0, -5.0, 3.0, 20.0, 45.0, 0.0];
const FORWARD_ERRORS: &str = r#"{"location":{"EX0A":0.01,"EB0A":2e-5}}"#;

fn kinematics_case() -> Value {
    let chain = preset("pocketnc-v2-10").unwrap().kinematics.unwrap();
    let e: GeometricErrors = serde_json::from_str(FORWARD_ERRORS).unwrap();
    let p = forward(&chain, &q_from_degrees(&FORWARD_Q), &e, 25.0).unwrap();
    serde_json::to_value(p).unwrap()
}

const CONE: &str = r#"{"machine":"trunnion-ac","halfApexDeg":15,"inclinationDeg":10,"method":"perpendicular","barLength":100,"feed":1000,"points":720}"#;

fn cone_case() -> Value {
    let cfg: ConeFrustumConfig = serde_json::from_str(CONE).unwrap();
    let r = cone_frustum_test(&cfg).unwrap();
    json!({
        "deviation": arr(&r.deviation), "time": arr(&r.time),
        "x": arr(&r.path[0]), "z": arr(&r.path[2]),
        "maxDeviation": r.max_deviation, "minDeviation": r.min_deviation,
    })
}

/// Two sections of a 120° partial-range trace with a centre offset and a
/// second harmonic, in degrees and mm.
fn sections() -> Vec<Section> {
    [(0.0, 0.01, -0.004), (100.0, 0.014, 0.002)]
        .into_iter()
        .map(|(y, z, x)| {
            let angle_deg: Vec<f64> = (0..=120).map(|i| -60.0 + i as f64).collect();
            let deviation = angle_deg
                .iter()
                .map(|a: &f64| {
                    let t = a.to_radians();
                    z * t.cos() + x * t.sin() + 0.002 * (2.0 * t).sin()
                })
                .collect();
            Section {
                y,
                angle_deg,
                deviation,
            }
        })
        .collect()
}

fn alignment_case() -> Value {
    serde_json::to_value(estimate_alignment(&sections(), 100.0).unwrap()).unwrap()
}

fn golden() -> Value {
    let s = sections();
    let (x, y) = circle_points();
    let parse = |t: &str| serde_json::from_str::<Value>(t).unwrap();
    json!({
        "inputs": {
            "servoRamp": ramp(), "feedVector": serde_json::from_str::<Value>(FEED_VECTOR).unwrap(),
            "toolpath": serde_json::from_str::<Value>(TOOLPATH).unwrap(),
            "synthetic": parse(SYNTHETIC), "circleX": x, "circleY": y,
            "forwardQ": FORWARD_Q, "forwardErrors": parse(FORWARD_ERRORS), "toolLength": 25.0, "cone": serde_json::from_str::<Value>(CONE).unwrap(),
            "sections": s.iter().map(|s| json!({"y": s.y, "angleDeg": s.angle_deg, "deviation": s.deviation})).collect::<Vec<_>>(),
        },
        "servo": servo_case(),
        "feedVector": feed_vector_case(),
        "toolpath": toolpath_case(),
        "ballbar": ballbar_case(),
        "kinematics": kinematics_case(),
        "cone": cone_case(),
        "alignment": alignment_case(),
    })
}

#[test]
fn golden_fixture_is_current() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/golden/golden.json");
    let now = golden();
    if std::env::var_os("GOLDEN_WRITE").is_some() {
        std::fs::create_dir_all(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/golden")).unwrap();
        std::fs::write(path, serde_json::to_string_pretty(&now).unwrap() + "\n").unwrap();
        return;
    }
    let text = std::fs::read_to_string(path)
        .expect("tests/golden/golden.json: run GOLDEN_WRITE=1 cargo test --test golden");
    let kept: Value = serde_json::from_str(&text).unwrap();
    assert!(kept == now, "tests/golden/golden.json is stale: the native results changed; if intended, rewrite it with GOLDEN_WRITE=1 cargo test --test golden");
}
