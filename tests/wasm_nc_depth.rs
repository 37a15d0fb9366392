//! Under Node (the debug wasm build, 1 MiB stack): macro expressions
//! nested 2,000 levels deep — `#1=[[…]]`, `IF[[…]]`, an o-word `[[…]]`,
//! `SIN[SIN[…]]`, `#[#[…]]`, `##…#1`, a `**` tower, `X[[…]]` — given to
//! parseNc, checkNc, simulateToolPath, reverseCompensate and compensateNc5
//! each give the located "nested deeper than 64 levels" error (they used to
//! overflow the stack and kill the instance); the deepest tree the limit
//! allows, a 500,000-term sum and a 100,000-sign run are read with the
//! right value; and after all of it the same instance still parses a
//! program correctly.
#![cfg(target_arch = "wasm32")]

use js_sys::Reflect;
use mtmotion::nc::macro_expr::MAX_EXPR_DEPTH;
use mtmotion::wasm::{kinematics as k, toolpath as tp};
use wasm_bindgen::{JsCast, JsValue};
use wasm_bindgen_test::{console_log, wasm_bindgen_test};

const DEEP: usize = 2_000;
const M: usize = MAX_EXPR_DEPTH;

fn get(v: &JsValue, path: &[&str]) -> JsValue {
    path.iter().fold(v.clone(), |acc, key| {
        Reflect::get(&acc, &JsValue::from_str(key)).unwrap()
    })
}

fn js(s: &str) -> JsValue {
    js_sys::JSON::parse(s).unwrap()
}

fn message(e: wasm_bindgen::JsError) -> String {
    let v: JsValue = e.into();
    let e: js_sys::Error = v.dyn_into().expect("a JS Error");
    e.message().into()
}

fn nest(open: &str, d: usize, close: &str) -> String {
    format!("{}1{}", open.repeat(d), close.repeat(d))
}

/// Each form at 2,000 levels, and where level 65 opens (line, column).
fn deep_programs() -> Vec<(String, usize, usize)> {
    let d = DEEP;
    vec![
        (
            format!("#1={}\nG1 X#1 F100\nM30", nest("[", d, "]")),
            1,
            4 + M,
        ),
        (
            format!("IF{}GOTO5\nN5 G1 X1 F100\nM30", nest("[", d, "]")),
            1,
            3 + M,
        ),
        (
            format!(
                "G1 F100\no100 if {}\nG1 X1\no100 endif\nM30",
                nest("[", d, "]")
            ),
            2,
            9 + M,
        ),
        (
            format!("#1={}\nG1 X#1 F100\nM30", nest("SIN[", d, "]")),
            1,
            3 + 4 * (M + 1),
        ),
        (
            format!("#1=1\n#2={}\nG1 X#2 F100\nM30", nest("#[", d, "]")),
            2,
            3 + 2 * (M + 1),
        ),
        (
            format!("#1=1\n#2={}1\nG1 X#2 F100\nM30", "#".repeat(d)),
            2,
            5 + M,
        ),
        (
            format!("#1=1{}\nG1 X#1 F100\nM30", "**1".repeat(d)),
            1,
            4 + 3 * (M + 1),
        ),
        (format!("G1 X{} F100\nM30", nest("[", d, "]")), 1, 5 + M),
    ]
}

fn assert_located(msg: &str, line: usize, col: usize, via: &str) {
    let at = format!("line {line}, column {col}: expression nested deeper than {M} levels");
    assert!(msg.contains(&at), "{via}: {msg}");
}

/// A normal program and what its parse must give.
fn normal_call_answers() {
    let p = tp::parse_nc(
        JsValue::from_str("#1=[2+3]*[4-1]\nG1 X[#1] Y-#1 F600\nM30"),
        JsValue::UNDEFINED,
    )
    .unwrap();
    assert_eq!(get(&p, &["segments", "0", "end", "x"]).as_f64(), Some(15.0));
    assert_eq!(
        get(&p, &["segments", "0", "end", "y"]).as_f64(),
        Some(-15.0)
    );
}

#[wasm_bindgen_test]
fn deep_expressions_are_located_errors_and_the_instance_lives_on() {
    normal_call_answers();
    let sim = || js(r#"{"tA":0.04,"T":[0.015,0.015,0.015],"dt":0.001}"#);
    let nc5 = || js(r#"{"machine": "pocketnc-v2-10"}"#);
    for (text, line, col) in deep_programs() {
        let t = || JsValue::from_str(&text);
        let m = message(tp::parse_nc(t(), JsValue::UNDEFINED).unwrap_err());
        assert_located(&m, line, col, "parseNc");
        let c = tp::check_nc(t(), JsValue::UNDEFINED).unwrap();
        assert_eq!(
            get(&c, &["errors", "0", "line"]).as_f64(),
            Some(line as f64)
        );
        assert_eq!(
            get(&c, &["errors", "0", "column"]).as_f64(),
            Some(col as f64)
        );
        let m = message(tp::simulate_tool_path(t(), sim(), JsValue::UNDEFINED).unwrap_err());
        assert_located(&m, line, col, "simulateToolPath");
        let m = message(
            tp::reverse_compensate_js(t(), JsValue::UNDEFINED, JsValue::UNDEFINED).unwrap_err(),
        );
        assert_located(&m, line, col, "reverseCompensate");
        let m = message(k::compensate_nc5(t(), nc5()).unwrap_err());
        assert_located(&m, line, col, "compensateNc5");
        normal_call_answers();
    }
}

#[wasm_bindgen_test]
fn the_deepest_tree_the_limit_allows_fits_the_debug_stack() {
    // four operator chains, a sign and a function per level: 0 OR 1 = 1 at
    // every level
    let text = format!(
        "#1={}2{}\nG1 X[#1+1] F100\nM30",
        "0 OR 0 EQ 0 + 0 * -ABS[".repeat(M),
        "]".repeat(M)
    );
    let p = tp::parse_nc(JsValue::from_str(&text), JsValue::UNDEFINED).unwrap();
    assert_eq!(get(&p, &["segments", "0", "end", "x"]).as_f64(), Some(2.0));
    normal_call_answers();
}

#[wasm_bindgen_test]
fn long_operator_and_sign_runs_are_read_flat() {
    let cases = [
        (
            format!("#1={}1\nG1 X#1 F100\nM30", "1+".repeat(499_999)),
            500_000.0,
            "500,000-term sum",
        ),
        (
            format!("#1={}1\nG1 X#1 F100\nM30", "-".repeat(100_000)),
            1.0,
            "100,000 signs",
        ),
        (
            format!("#1={}1\nG1 X#1 F100\nM30", "-".repeat(99_999)),
            -1.0,
            "99,999 signs",
        ),
    ];
    for (text, want, what) in cases {
        let t0 = js_sys::Date::now();
        let p = tp::parse_nc(JsValue::from_str(&text), JsValue::UNDEFINED).unwrap();
        console_log!("{what}: {:.0} ms (debug build)", js_sys::Date::now() - t0);
        assert_eq!(
            get(&p, &["segments", "0", "end", "x"]).as_f64(),
            Some(want),
            "{what}"
        );
    }
    normal_call_answers();
}
