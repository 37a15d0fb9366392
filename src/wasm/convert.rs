//! Conversions at the JS boundary.

use js_sys::{Float64Array, Object, Reflect};
use serde::{de::DeserializeOwned, Serialize};
use wasm_bindgen::prelude::*;

/// Serialises a small result to a plain JS object (maps become objects,
/// not `Map`s).
pub fn to_js<T: Serialize + ?Sized>(value: &T) -> Result<JsValue, JsError> {
    value
        .serialize(&serde_wasm_bindgen::Serializer::json_compatible())
        .map_err(|e| JsError::new(&format!("cannot convert the result to JS: {e}")))
}

/// Deserialises a small config; `what` names the argument in the message,
/// e.g. `"axis"` gives `axis: missing field `kpp``.
pub fn from_js<T: DeserializeOwned>(value: JsValue, what: &str) -> Result<T, JsError> {
    serde_wasm_bindgen::from_value(value).map_err(|e| JsError::new(&format!("{what}: {e}")))
}

/// Builder for a result object that mixes numbers, `Float64Array`s and
/// serialised values.
pub struct Obj(Object);

impl Default for Obj {
    fn default() -> Self {
        Self::new()
    }
}

impl Obj {
    /// An empty object.
    pub fn new() -> Self {
        Self(Object::new())
    }

    fn set(self, key: &str, value: &JsValue) -> Self {
        // Reflect::set on a fresh plain object cannot fail.
        let _ = Reflect::set(&self.0, &JsValue::from_str(key), value);
        self
    }

    /// Sets a number.
    pub fn num(self, key: &str, value: f64) -> Self {
        self.set(key, &JsValue::from_f64(value))
    }

    /// Sets a boolean.
    pub fn flag(self, key: &str, value: bool) -> Self {
        self.set(key, &JsValue::from_bool(value))
    }

    /// Sets a `Float64Array` copied from `values`.
    pub fn arr(self, key: &str, values: &[f64]) -> Self {
        self.set(key, &Float64Array::from(values).into())
    }

    /// Sets any JS value.
    pub fn val(self, key: &str, value: JsValue) -> Self {
        self.set(key, &value)
    }

    /// Sets a serialised value.
    pub fn ser<T: Serialize + ?Sized>(self, key: &str, value: &T) -> Result<Self, JsError> {
        let v = to_js(value)?;
        Ok(self.set(key, &v))
    }

    /// The finished object.
    pub fn build(self) -> JsValue {
        self.0.into()
    }
}

/// A string argument. wasm-bindgen's own `&str` conversion traps on a
/// non-string (memory access out of bounds), so bindings take a `JsValue`
/// and come here: anything else is a thrown `Error` naming the argument.
pub fn string_arg(value: &JsValue, what: &str) -> Result<String, JsError> {
    value.as_string().ok_or_else(|| {
        let got = value.js_typeof().as_string().unwrap_or_default();
        let got = if value.is_null() { "null".into() } else { got };
        JsError::new(&format!("{what}: expected a string, got {got}"))
    })
}
