//! The configs of the documentation calculators' functions, read from JS.
//!
//! The full module deserialises them strictly ([`super::convert::object`],
//! [`super::strict`]). The embed module (`--no-default-features`,
//! docs/performance.md) reads the few fields by hand from the same plain
//! snapshot ([`super::convert::plain`]), so that serde's deserialiser is
//! not linked at all: the same defaults, the same keys allowed, and the
//! strict deserializer's messages (a missing or unknown key, a string or a
//! non-finite number for a number, a whole number out of range), each
//! naming the path of the value.
//! `tests/node/optimised.test.mjs` checks both builds give the same values
//! and the same messages for the calculators' inputs.

use wasm_bindgen::prelude::*;

/// A config argument the embed calculators pass, read from JS.
pub trait JsArg: Sized {
    /// The config in `value`; `what` names the argument in errors.
    fn arg(value: JsValue, what: &str) -> Result<Self, JsError>;
}

#[cfg(feature = "full")]
impl<T: serde::de::DeserializeOwned> JsArg for T {
    fn arg(value: JsValue, what: &str) -> Result<Self, JsError> {
        super::convert::object(value, what)
    }
}

#[cfg(not(feature = "full"))]
mod by_hand {
    use js_sys::{Array, Float64Array, Reflect};
    use wasm_bindgen::prelude::*;

    use super::JsArg;
    use crate::alignment::travel_range::{default_radius, default_samples};
    use crate::alignment::{Locus, Offset, SweepConfig};
    use crate::ballbar::{BallbarColumns, Harmonic, ParseOptions, PlanePoint};
    use crate::best_kffp::saturation::{SaturationQuery, SaturationReading, READINGS};
    use crate::wasm::convert::{known_keys, plain, require_object};
    use crate::wasm::strict::{js_number, kind};
    use crate::wasm::toolpath::Eq3In;

    /// The snapshot of a config that must be a plain object with only the
    /// keys `allowed` (the full module's serde structs refuse the others).
    fn snapshot(value: &JsValue, what: &str, allowed: &[&str]) -> Result<JsValue, JsError> {
        require_object(value, what)?;
        let o = plain(value, what)?;
        known_keys(&o, allowed, what)?;
        Ok(o)
    }

    /// The field `key`, or `None` when absent.
    fn get(obj: &JsValue, key: &str) -> Option<JsValue> {
        Reflect::get(obj, &JsValue::from_str(key))
            .ok()
            .filter(|v| !v.is_undefined())
    }

    fn missing(what: &str, key: &str) -> JsError {
        JsError::new(&format!("{what}: missing key '{key}'"))
    }

    /// A finite JS number at `path` (the strict deserializer's words).
    fn number(v: &JsValue, path: &str) -> Result<f64, JsError> {
        match v.as_f64() {
            Some(x) if x.is_finite() => Ok(x),
            Some(x) => Err(JsError::new(&format!(
                "{path}: expected a finite number, got {}",
                js_number(x)
            ))),
            None => Err(JsError::new(&format!(
                "{path}: expected a number, got {}",
                kind(v)
            ))),
        }
    }

    /// A required number.
    fn num(obj: &JsValue, key: &str, what: &str) -> Result<f64, JsError> {
        let v = get(obj, key).ok_or_else(|| missing(what, key))?;
        number(&v, &format!("{what}.{key}"))
    }

    /// A number with a default when absent.
    fn num_or(obj: &JsValue, key: &str, what: &str, default: f64) -> Result<f64, JsError> {
        match get(obj, key) {
            None => Ok(default),
            Some(v) => number(&v, &format!("{what}.{key}")),
        }
    }

    /// An optional number: absent or null gives `None` (serde's `Option`).
    fn opt_num(obj: &JsValue, key: &str, what: &str) -> Result<Option<f64>, JsError> {
        match get(obj, key) {
            Some(v) if !v.is_null() => number(&v, &format!("{what}.{key}")).map(Some),
            _ => Ok(None),
        }
    }

    /// The items of an array field; absent: "missing key" when `required`,
    /// else none (serde's `#[serde(default)]`).
    fn items(
        obj: &JsValue,
        key: &str,
        what: &str,
        required: bool,
    ) -> Result<Vec<JsValue>, JsError> {
        match get(obj, key) {
            None if required => Err(missing(what, key)),
            None => Ok(Vec::new()),
            Some(v) if Array::is_array(&v) => Ok(Array::from(&v).iter().collect()),
            Some(v) => match v.dyn_ref::<Float64Array>() {
                Some(a) => Ok(a.to_vec().into_iter().map(JsValue::from_f64).collect()),
                None => Err(JsError::new(&format!(
                    "{what}.{key}: expected an array, got {}",
                    kind(&v)
                ))),
            },
        }
    }

    fn nums(obj: &JsValue, key: &str, what: &str) -> Result<Vec<f64>, JsError> {
        items(obj, key, what, true)?
            .iter()
            .enumerate()
            .map(|(i, v)| number(v, &format!("{what}.{key}[{i}]")))
            .collect()
    }

    /// A whole number from 0 to `max` at `path` (`max` as the strict
    /// deserializer gives it: `u32::MAX` for a `u32`, 2⁵³ − 1 for a
    /// `usize`, read as a `u64`).
    fn whole(v: &JsValue, path: &str, max: u64) -> Result<u64, JsError> {
        let range = format!("expected a whole number from 0 to {max}");
        match v.as_f64() {
            Some(x) if x.fract() == 0.0 && x >= 0.0 && x <= max as f64 => Ok(x as u64),
            Some(x) => Err(JsError::new(&format!(
                "{path}: {range}, got {}",
                crate::numeric::compact(x)
            ))),
            None => Err(JsError::new(&format!("{path}: {range}, got {}", kind(v)))),
        }
    }

    impl JsArg for Eq3In {
        fn arg(value: JsValue, what: &str) -> Result<Self, JsError> {
            let o = snapshot(&value, what, &["feed", "radius", "tA", "T"])?;
            Ok(Eq3In {
                feed: num(&o, "feed", what)?,
                radius: num(&o, "radius", what)?,
                t_a: num(&o, "tA", what)?,
                t: num(&o, "T", what)?,
            })
        }
    }

    fn reading(o: &JsValue, what: &str) -> Result<SaturationReading, JsError> {
        let Some(v) = get(o, "reading") else {
            return Ok(SaturationReading::default());
        };
        let Some(name) = v.as_string() else {
            return Err(JsError::new(&format!(
                "{what}.reading: expected a string, got {}",
                kind(&v)
            )));
        };
        let all = [
            SaturationReading::PreControlOff,
            SaturationReading::PresetKffp,
            SaturationReading::InertiaOnly,
        ];
        match READINGS.iter().position(|r| *r == name) {
            Some(k) => Ok(all[k]),
            None => Err(JsError::new(&format!(
                "{what}.reading: unknown value '{}'; expected one of {}",
                crate::budget::clip(&name, 40),
                READINGS.join(", ")
            ))),
        }
    }

    impl JsArg for SaturationQuery {
        fn arg(value: JsValue, what: &str) -> Result<Self, JsError> {
            let o = snapshot(
                &value,
                what,
                &[
                    "j1",
                    "torqueMax",
                    "accelTime",
                    "feedAtCuttingPoint",
                    "dt",
                    "reading",
                ],
            )?;
            Ok(SaturationQuery {
                j1: nums(&o, "j1", what)?,
                torque_max: opt_num(&o, "torqueMax", what)?,
                accel_time: num(&o, "accelTime", what)?,
                feed_at_cutting_point: num(&o, "feedAtCuttingPoint", what)?,
                dt: opt_num(&o, "dt", what)?,
                reading: reading(&o, what)?,
            })
        }
    }

    fn harmonic(h: &JsValue, what: &str) -> Result<Harmonic, JsError> {
        if !h.is_object() || Array::is_array(h) || h.is_instance_of::<Float64Array>() {
            return Err(JsError::new(&format!(
                "{what}: expected an object {{ … }}, got {}",
                kind(h)
            )));
        }
        known_keys(h, &["order", "amplitude", "phase"], what)?;
        let order = get(h, "order").ok_or_else(|| missing(what, "order"))?;
        Ok(Harmonic {
            order: whole(&order, &format!("{what}.order"), u32::MAX.into())? as u32,
            amplitude: num(h, "amplitude", what)?,
            phase: num_or(h, "phase", what, 0.0)?,
        })
    }

    impl JsArg for SweepConfig {
        fn arg(value: JsValue, what: &str) -> Result<Self, JsError> {
            let o = snapshot(
                &value,
                what,
                &[
                    "offset",
                    "ranges",
                    "harmonics",
                    "radius",
                    "samples",
                    "centreDeg",
                ],
            )?;
            let offset = match get(&o, "offset") {
                None => Offset::default(),
                Some(v) => {
                    let at = format!("{what}.offset");
                    if !v.is_object() || Array::is_array(&v) {
                        return Err(JsError::new(&format!(
                            "{at}: expected an object {{ … }}, got {}",
                            kind(&v)
                        )));
                    }
                    known_keys(&v, &["z", "x"], &at)?;
                    Offset {
                        z: num(&v, "z", &at)?,
                        x: num(&v, "x", &at)?,
                    }
                }
            };
            let harmonics = items(&o, "harmonics", what, false)?
                .iter()
                .enumerate()
                .map(|(i, h)| harmonic(h, &format!("{what}.harmonics[{i}]")))
                .collect::<Result<_, _>>()?;
            let samples = match get(&o, "samples") {
                None => default_samples(),
                Some(v) => {
                    let path = format!("{what}.samples");
                    let n = whole(&v, &path, (1 << 53) - 1)?;
                    usize::try_from(n).map_err(|_| {
                        JsError::new(&format!("{path}: {n} is too large for this platform"))
                    })?
                }
            };
            Ok(SweepConfig {
                offset,
                ranges: nums(&o, "ranges", what)?,
                locus: Locus {
                    harmonics,
                    radius: num_or(&o, "radius", what, default_radius())?,
                    samples,
                    centre_deg: num_or(&o, "centreDeg", what, 0.0)?,
                },
            })
        }
    }

    impl JsArg for ParseOptions {
        fn arg(value: JsValue, what: &str) -> Result<Self, JsError> {
            // `trim`: the ball-bar trimming option (src/ballbar/)
            let o = snapshot(
                &value,
                what,
                &["nominalRadius", "feed", "centre", "trim", "columns"],
            )?;
            let columns = match get(&o, "columns") {
                None => BallbarColumns::default(),
                Some(v) if v.is_null() => BallbarColumns::default(),
                Some(v) => {
                    let path = format!("{what}.columns");
                    require_object(&v, &path)?;
                    known_keys(
                        &v,
                        &["x", "y", "angle", "deviation", "time", "direction"],
                        &path,
                    )?;
                    let name = |key: &str| -> Result<Option<String>, JsError> {
                        match get(&v, key) {
                            Some(n) if !n.is_null() => {
                                crate::wasm::convert::name_arg(&n, &format!("{path}.{key}"))
                                    .map(Some)
                            }
                            _ => Ok(None),
                        }
                    };
                    BallbarColumns {
                        x: name("x")?,
                        y: name("y")?,
                        angle: name("angle")?,
                        deviation: name("deviation")?,
                        time: name("time")?,
                        direction: name("direction")?,
                    }
                }
            };
            let centre = match get(&o, "centre") {
                None => None,
                Some(v) => Some({
                    known_keys(&v, &["x", "y"], &format!("{what}.centre"))?;
                    PlanePoint {
                        x: num(&v, "x", &format!("{what}.centre"))?,
                        y: num(&v, "y", &format!("{what}.centre"))?,
                    }
                }),
            };
            Ok(ParseOptions {
                nominal_radius: opt_num(&o, "nominalRadius", what)?,
                feed: opt_num(&o, "feed", what)?,
                centre,
                trim: match get(&o, "trim") {
                    None => true,
                    Some(v) => v.as_bool().ok_or_else(|| {
                        JsError::new(&format!("{what}.trim: expected true or false"))
                    })?,
                },
                columns,
            })
        }
    }
}
