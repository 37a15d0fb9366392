//! Conversions at the JS boundary.
//!
//! Every config and array argument is first copied into plain data by a
//! small JavaScript helper ([`plain`], [`floats_arg`]) that wasm-bindgen
//! calls with `catch`. Whatever user code runs while an argument is read —
//! a throwing getter, a Proxy trap, an array-like whose `length` lies or
//! changes — runs there, so a JS exception never unwinds through wasm
//! frames (which would skip the restore of wasm's stack pointer and leak
//! wasm stack on every call until the instance dies). The copy rejects
//! getters/setters, class instances and nesting deeper than
//! [`MAX_DEPTH`], and counts values against [`budget::MAX_ARGUMENT_VALUES`];
//! a Proxy is read once, through its traps, into a plain snapshot; a key
//! whose value is `undefined` is left out, as `JSON.stringify` does. Only the
//! snapshot reaches serde-wasm-bindgen, so the conversion itself can no
//! longer throw, and its recursion is bounded.
//!
//! No other JS call on an argument's value runs outside such a helper
//! either: [`require_object`]'s `Array.isArray` (which throws on a revoked
//! Proxy) runs in `isArrayArg`, and the type checks of [`string_arg`],
//! [`number_arg`] and [`callback_arg`] use `typeof` (which never throws)
//! and name a revoked Proxy through `isRevoked`, which catches. A revoked
//! Proxy anywhere in an argument is an `Error` naming the argument (or the
//! path inside it): "… is a revoked Proxy; pass plain data".

use js_sys::{Float64Array, Object, Reflect};
use serde::{de::DeserializeOwned, Serialize};
use wasm_bindgen::prelude::*;

use crate::budget;

/// Deepest nesting of objects and arrays a config may have: the deepest
/// real config (a machine preset with its axes and harmonics) is 5 levels.
pub const MAX_DEPTH: u32 = 32;

#[wasm_bindgen(inline_js = r#"
const clip = (s) => (s.length > 60 ? s.slice(0, 57) + '...' : s);
const kind = (v) => {
  if (v === null) return 'null';
  if (Array.isArray(v)) return 'an array';
  if (typeof v !== 'object') return v === undefined ? 'undefined' : 'a ' + typeof v;
  const p = Object.getPrototypeOf(v);
  if (p === Object.prototype || p === null) return 'an object';
  const n = p.constructor && p.constructor.name;
  return typeof n === 'string' && n ? 'a ' + clip(n) : 'an object';
};
class Refused extends Error {}
// a typed array's length from its internal slot: no getter of the caller runs
const typedLength = Function.prototype.call.bind(Object.getOwnPropertyDescriptor(Object.getPrototypeOf(Int8Array.prototype), 'length').get);
// Array.isArray throws only for a revoked Proxy (its handler is gone)
const revoked = (v) => {
  if (v === null || (typeof v !== 'object' && typeof v !== 'function')) return false;
  try { Array.isArray(v); return false; } catch { return true; }
};
const revokedMessage = (path) => `${clip(path)}: is a revoked Proxy; pass plain data (numbers, strings, arrays, objects)`;
export function isRevoked(value) { return revoked(value); }
export function isArrayArg(value, what) {
  if (revoked(value)) throw new Error(revokedMessage(what));
  try { return Array.isArray(value); } catch (e) { throw say(e, what); }
}
function say(e, what) {
  if (e instanceof Refused) return new Error(e.message);
  let m = '';
  try { m = e instanceof Error ? String(e.message) : typeof e === 'string' ? e : typeof e; } catch { m = 'an exception'; }
  return new Error(`${what}: reading the argument threw (${clip(m)}); pass plain data (numbers, strings, arrays, objects)`);
}
// lists: [[key, max, unit, advice, keys]], a list found under `key` (the
// argument itself for key '') held to `max` items (an object's keys when
// `keys`), checked before any item is copied
export function plainCopy(value, what, maxDepth, maxItems, maxString, maxKey, maxKeys, lists) {
  let items = 0;
  const tooMany = () => new Refused(`${clip(what)}: more than ${maxItems} values; pass a smaller input`);
  const bounded = new Map(lists.map(([key, max, unit, advice, keys]) => [key, { max, unit, advice, keys }]));
  const overList = (key, n, keys, path) => {
    const b = bounded.get(key);
    if (b && b.keys === keys && n > b.max) throw new Refused(`${clip(path)}: ${n} ${b.unit}, more than the limit of ${b.max}; ${b.advice}`);
  };
  const copy = (v, path, depth, key) => {
    if (++items > maxItems) throw tooMany();
    const t = typeof v;
    if (t === 'string') {
      // a string costs its UTF-8 bytes in wasm memory: at least one per unit
      if (v.length > maxString) throw new Refused(`${clip(path)}: a string of ${v.length} characters, more than the limit of ${maxString}; pass a shorter text`);
      items += v.length >>> 3;
      if (items > maxItems) throw tooMany();
      return v;
    }
    if (t === 'bigint') throw new Refused(`${clip(path)}: expected a number, got a bigint`);
    if (v === null || t === 'undefined' || t === 'boolean' || t === 'number') return v;
    if (revoked(v)) throw new Refused(revokedMessage(path));
    if (t !== 'object') throw new Refused(`${clip(path)}: expected a number, string, array or object, got a ${t}`);
    if (depth >= maxDepth) throw new Refused(`${clip(path)}: nested deeper than ${maxDepth} levels`);
    if (ArrayBuffer.isView(v)) {
      if (v instanceof DataView) throw new Refused(`${clip(path)}: expected an array of numbers, got a DataView`);
      // counted before it is copied
      overList(key, typedLength(v), false, path);
      items += typedLength(v);
      if (items > maxItems) throw tooMany();
      return new Float64Array(v);
    }
    if (Array.isArray(v)) {
      const n = v.length;
      if (!Number.isSafeInteger(n) || n < 0 || n > maxItems - items) throw new Refused(`${clip(path)}: an array of ${clip(String(n))} items; at most ${maxItems} values are accepted`);
      overList(key, n, false, path);
      const out = new Array(n);
      for (let i = 0; i < n; i++) out[i] = copy(v[i], `${path}[${i}]`, depth + 1, undefined);
      return out;
    }
    const proto = Object.getPrototypeOf(v);
    if (proto !== Object.prototype && proto !== null) throw new Refused(`${clip(path)}: expected a plain object, got ${kind(v)}`);
    const out = {};
    // Counted with Object.keys (enumerable string keys, the ones copied)
    // before the full listing: on 1e6 keys it takes about 0.5 s in Node 20,
    // Reflect.ownKeys 1.1-1.6 s (an object of 1e6 unknown keys took 5-19 s
    // to refuse before any count; 1e6 tool radii 5 s).
    const counted = Object.keys(v).length;
    overList(key, counted, true, path);
    if (counted > maxKeys) throw new Refused(`${clip(path)}: an object of ${counted} keys, more than the limit of ${maxKeys}`);
    const keys = Reflect.ownKeys(v);
    // no config has more keys, non-enumerable and symbol keys included
    if (keys.length > maxKeys) throw new Refused(`${clip(path)}: an object of ${keys.length} keys, more than the limit of ${maxKeys}`);
    for (const k of keys) {
      if (typeof k !== 'string') continue;
      if (k.length > maxKey) throw new Refused(`${clip(path)}: a key of ${k.length} characters; a key is a name of at most ${maxKey}`);
      if (++items > maxItems) throw tooMany();
      const d = Object.getOwnPropertyDescriptor(v, k);
      if (!d || !d.enumerable) continue;
      if ('get' in d || 'set' in d) throw new Refused(`${clip(path + '.' + k)}: is a getter or setter; pass plain data`);
      if (d.value === undefined) continue;
      Object.defineProperty(out, k, { value: copy(d.value, `${path}.${k}`, depth + 1, k), enumerable: true, writable: true, configurable: true });
    }
    return out;
  };
  try { return copy(value, what, 0, ''); } catch (e) { throw say(e, what); }
}
export function f64Copy(value, what, maxLen) {
  try {
    if (revoked(value)) throw new Refused(revokedMessage(what));
    if (ArrayBuffer.isView(value) && !(value instanceof DataView)) {
      // checked before it is copied
      const n = typedLength(value);
      if (n > maxLen) throw new Refused(`${clip(what)}: ${n} values; at most ${maxLen} are accepted`);
      return new Float64Array(value);
    }
    if (Array.isArray(value)) {
      const n = value.length;
      if (!Number.isSafeInteger(n) || n < 0 || n > maxLen) throw new Refused(`${what}: an array of ${clip(String(n))} items; at most ${maxLen} values are accepted`);
      const out = new Float64Array(n);
      for (let i = 0; i < n; i++) {
        const x = value[i];
        if (typeof x !== 'number') throw new Refused(`${what}[${i}]: expected a number, got ${kind(x)}`);
        out[i] = x;
      }
      return out;
    }
    throw new Refused(`${what}: expected a Float64Array or an array of numbers, got ${kind(value)}`);
  } catch (e) { throw say(e, what); }
}
"#)]
extern "C" {
    #[wasm_bindgen(catch, js_name = plainCopy)]
    fn plain_copy(
        value: &JsValue,
        what: &str,
        max_depth: u32,
        max_items: f64,
        max_string: f64,
        max_key: f64,
        max_keys: f64,
        lists: &JsValue,
    ) -> Result<JsValue, JsValue>;
    #[wasm_bindgen(catch, js_name = f64Copy)]
    fn f64_copy(value: &JsValue, what: &str, max_len: f64) -> Result<Float64Array, JsValue>;
    #[wasm_bindgen(catch, js_name = isArrayArg)]
    fn is_array_arg(value: &JsValue, what: &str) -> Result<bool, JsValue>;
    #[wasm_bindgen(catch, js_name = isRevoked)]
    fn is_revoked(value: &JsValue) -> Result<bool, JsValue>;
}

/// Set while a progress callback runs ([`progress`]): a call into the
/// module from it is refused ([`not_reentered`]). Such a call nested a
/// whole run inside the callback, and a callback that called back again
/// grew wasm memory to 4 GB at depth 102 and trapped.
static IN_CALLBACK: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Calls progress callback `cb` with `(fraction, stage)`; its return value,
/// or `None` when it threw (the throw is caught by wasm-bindgen). While it
/// runs, every export refuses to start.
pub fn progress(cb: &js_sys::Function, fraction: f64, stage: &str) -> Option<JsValue> {
    use std::sync::atomic::Ordering;
    IN_CALLBACK.store(true, Ordering::Relaxed);
    let r = cb
        .call2(
            &JsValue::NULL,
            &JsValue::from_f64(fraction),
            &JsValue::from_str(stage),
        )
        .ok();
    IN_CALLBACK.store(false, Ordering::Relaxed);
    r
}

/// An `Error` when called from inside a progress callback (see
/// [`progress`]); every argument reader below asks it first, so no export
/// does any work when re-entered.
pub fn not_reentered() -> Result<(), JsError> {
    if IN_CALLBACK.load(std::sync::atomic::Ordering::Relaxed) {
        return Err(JsError::new(
            "mtmotion is busy: a progress callback may not call into the module; call it after the run returns",
        ));
    }
    Ok(())
}

/// True when `value` is a revoked Proxy (checked in JS, where the throw is
/// caught).
pub fn revoked(value: &JsValue) -> bool {
    is_revoked(value).unwrap_or(false)
}

/// What a value that is not of the expected type is, for a message: its
/// `typeof` ("number", "object", "null"), or "a revoked Proxy".
pub fn got(value: &JsValue) -> String {
    if value.is_null() {
        "null".into()
    } else if revoked(value) {
        "a revoked Proxy".into()
    } else {
        value.js_typeof().as_string().unwrap_or_default()
    }
}

/// The message of an `Error` the copy helpers threw.
fn message(e: JsValue) -> JsError {
    let m = e
        .dyn_into::<js_sys::Error>()
        .map(|e| String::from(e.message()))
        .unwrap_or_else(|_| "the argument could not be read".into());
    JsError::new(&m)
}

/// A plain-data snapshot of `value` (see the module header); `what` names
/// the argument in the error. A list under a key of
/// [`budget::LIST_BUDGETS`], at any depth, is refused by its length before
/// any of its items is copied.
pub fn plain(value: &JsValue, what: &str) -> Result<JsValue, JsError> {
    plain_with(value, what, None)
}

/// [`plain`] of an argument that is itself a bounded list (`identifyAccDec`'s
/// circles, `ncMainFile`'s texts): its length is checked against `list`
/// before any item is copied.
pub fn plain_list(
    value: &JsValue,
    what: &str,
    list: &budget::ListBudget,
) -> Result<JsValue, JsError> {
    plain_with(value, what, Some(list))
}

fn plain_with(
    value: &JsValue,
    what: &str,
    root: Option<&budget::ListBudget>,
) -> Result<JsValue, JsError> {
    not_reentered()?;
    let lists = js_sys::Array::new();
    for b in budget::LIST_BUDGETS.iter().chain(root) {
        lists.push(
            &[
                JsValue::from_str(b.key),
                JsValue::from_f64(b.max as f64),
                JsValue::from_str(b.unit),
                JsValue::from_str(b.advice),
                JsValue::from_bool(b.keys),
            ]
            .into_iter()
            .collect::<js_sys::Array>(),
        );
    }
    plain_copy(
        value,
        what,
        MAX_DEPTH,
        budget::MAX_ARGUMENT_VALUES as f64,
        budget::MAX_TEXT_BYTES as f64,
        budget::MAX_NAME_CHARS as f64,
        budget::MAX_OBJECT_KEYS as f64,
        &lists,
    )
    .map_err(message)
}

/// A `Float64Array` or an array of numbers, copied into a `Vec`; anything
/// else (an array-like, a non-number item, more than
/// [`budget::MAX_ARGUMENT_VALUES`] values) is an `Error` naming `what`.
pub fn floats_arg(value: &JsValue, what: &str) -> Result<Vec<f64>, JsError> {
    not_reentered()?;
    Ok(f64_copy(value, what, budget::MAX_ARGUMENT_VALUES as f64)
        .map_err(message)?
        .to_vec())
}

/// A list of numbers read from a [`plain`] snapshot. The snapshot already
/// holds a fresh `Float64Array` of its own for any typed array that was
/// passed (and counted it against [`budget::MAX_ARGUMENT_VALUES`]), so it
/// is copied straight into the `Vec`: [`floats_arg`]'s defensive copy would
/// be a second copy of the whole input. An array of numbers, or anything
/// else, goes through [`floats_arg`] (checked and named as there).
pub fn plain_floats(value: &JsValue, what: &str) -> Result<Vec<f64>, JsError> {
    match value.dyn_ref::<Float64Array>() {
        Some(a) => Ok(a.to_vec()),
        None => floats_arg(value, what),
    }
}

/// Serialises a small result to a plain JS object (maps become objects,
/// not `Map`s).
pub fn to_js<T: Serialize + ?Sized>(value: &T) -> Result<JsValue, JsError> {
    value
        .serialize(&serde_wasm_bindgen::Serializer::json_compatible())
        .map_err(|e| JsError::new(&format!("cannot convert the result to JS: {e}")))
}

/// Deserialises a small config from its plain snapshot ([`plain`]); `what`
/// names the argument in the message, e.g. `"axis"` gives
/// `axis: missing field `kpp``.
pub fn from_js<T: DeserializeOwned>(value: JsValue, what: &str) -> Result<T, JsError> {
    from_plain(plain(&value, what)?, what)
}

/// Deserialises a config that is already a [`plain`] snapshot, strictly
/// ([`super::strict`]): an unknown key at any depth, an array for an
/// object, a string for a number or a non-finite number is an `Error`
/// naming its path; quoted input in the message is clipped.
pub fn from_plain<T: DeserializeOwned>(copy: JsValue, what: &str) -> Result<T, JsError> {
    super::strict::from_snapshot(copy, what)
        .map_err(|e| JsError::new(&budget::clip_quoted(&e.to_string(), 60)))
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

    /// Sets a `Uint32Array` copied from `values` (indices).
    pub fn indices(self, key: &str, values: &[u32]) -> Self {
        self.set(key, &js_sys::Uint32Array::from(values).into())
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
/// A string longer than [`budget::MAX_TEXT_BYTES`] is refused before it is
/// copied into wasm memory (UTF-8 needs at least one byte per UTF-16 unit).
pub fn string_arg(value: &JsValue, what: &str) -> Result<String, JsError> {
    not_reentered()?;
    let Some(s) = value.dyn_ref::<js_sys::JsString>() else {
        return Err(JsError::new(&format!(
            "{what}: expected a string, got {}",
            got(value)
        )));
    };
    if s.length() as usize > budget::MAX_TEXT_BYTES {
        return Err(JsError::new(&format!(
            "{what}: {} characters, more than the limit of {} bytes; {}",
            s.length(),
            budget::MAX_TEXT_BYTES,
            budget::TEXT_ADVICE
        )));
    }
    Ok(String::from(s))
}

/// Grows the wasm memory in large steps for a call that will allocate about
/// `bytes` (more than [`RESERVE_FROM`]), by allocating blocks of
/// [`RESERVE_STEP`] and freeing them: the allocator otherwise grows the
/// memory by 64 KiB pages as it needs them, and Node 20 took 1.4-1.8 ms
/// per grow (15,000 one-page grows of a `WebAssembly.Memory` to 938 MiB:
/// 21-26 s), so a 2 M-line program spent most of its `checkNc` growing the
/// memory. Blocks go first into the free memory a call before left (the
/// memory only grows where that is too little), and the freed blocks are
/// free memory the call's allocations then use. A block the memory cannot
/// give ends the reservation (the call then grows as before, and fails
/// where it would have).
pub fn reserve(bytes: usize) {
    if bytes <= RESERVE_FROM {
        return;
    }
    let n = bytes.min(RESERVE_AT_MOST).div_ceil(RESERVE_STEP);
    let mut blocks: Vec<Vec<u8>> = Vec::with_capacity(n);
    for _ in 0..n {
        let mut block = Vec::new();
        if block.try_reserve_exact(RESERVE_STEP).is_err() {
            break;
        }
        blocks.push(block);
    }
}

/// Calls that allocate less than this grow the memory as they go.
pub const RESERVE_FROM: usize = 16 << 20;
/// The size of one reserved block (256 pages: one grow instead of 256).
pub const RESERVE_STEP: usize = 16 << 20;
/// The largest reservation (a quarter of the 4 GiB address space).
pub const RESERVE_AT_MOST: usize = 1 << 30;

/// Wasm memory an NC program needs while it is read, per byte of its text
/// (blocks and words, then the segments, the text freed once lexed: the
/// 59 MiB of the 2 M-line program of `bench/node/large-program.bench.mjs`
/// grew the memory to 780 MiB in `checkNc` without a reservation, so 13 B
/// a byte, 764 MiB beside the text's own copy).
pub const NC_BYTES_PER_TEXT_BYTE: usize = 13;

/// Wasm memory the tool-path simulation holds per segment (timeline,
/// reference path, statistics; see `budget::MAX_TOOLPATH_SEGMENTS`).
pub const SIM_BYTES_PER_SEGMENT: usize = 1100;

/// A trace argument: the file's text, or its bytes.
pub enum TraceArg {
    /// A string (a text trace).
    Text(String),
    /// A `Uint8Array` (a file's bytes: a MATLAB `.mat` capture, or text).
    Bytes(Vec<u8>),
}

/// A trace argument: a string, or a `Uint8Array` of the file's bytes (a
/// `.mat` capture, which is not text); anything else is a thrown `Error`
/// naming the argument. Either is refused above
/// [`budget::MAX_TEXT_BYTES`] before it is copied into wasm memory.
pub fn trace_arg(value: &JsValue, what: &str) -> Result<TraceArg, JsError> {
    not_reentered()?;
    if let Some(a) = value.dyn_ref::<js_sys::Uint8Array>() {
        if a.length() as usize > budget::MAX_TEXT_BYTES {
            return Err(JsError::new(&format!(
                "{what}: {} bytes, more than the limit of {} bytes; {}",
                a.length(),
                budget::MAX_TEXT_BYTES,
                budget::TEXT_ADVICE
            )));
        }
        return Ok(TraceArg::Bytes(a.to_vec()));
    }
    if value.dyn_ref::<js_sys::JsString>().is_none() {
        return Err(JsError::new(&format!(
            "{what}: expected a string or a Uint8Array (the file's bytes), got {}",
            got(value)
        )));
    }
    string_arg(value, what).map(TraceArg::Text)
}

/// A name argument (a preset, an axis, a reading, a file name): a string
/// of at most [`budget::MAX_NAME_CHARS`] characters, refused before it is
/// copied into wasm memory (a 100 MB machine name held 573 MiB of wasm
/// memory for good and came back in the message).
pub fn name_arg(value: &JsValue, what: &str) -> Result<String, JsError> {
    not_reentered()?;
    if let Some(s) = value.dyn_ref::<js_sys::JsString>() {
        if s.length() as usize > budget::MAX_NAME_CHARS {
            return Err(JsError::new(&format!(
                "{what}: a name of {} characters; a name has at most {}",
                s.length(),
                budget::MAX_NAME_CHARS
            )));
        }
    }
    string_arg(value, what)
}

/// A config argument that must be a plain object (not an array, a string
/// or a number), converted from its snapshot by [`from_plain`], which
/// refuses a key the struct does not name at any depth: a misspelt
/// `omgea` would otherwise leave ω at its default without a word.
pub fn object<T: DeserializeOwned>(value: JsValue, what: &str) -> Result<T, JsError> {
    require_object(&value, what)?;
    // read from the plain snapshot: a Proxy's traps or a throwing getter
    // never run inside the conversion
    let copy = plain(&value, what)?;
    from_plain(copy, what)
}

/// An `Error` naming the first own key of `obj` (a [`plain`] snapshot,
/// whose keys are data) that is not in `allowed`: the hand-written readers'
/// check ("input: unknown key 'travelRange'; expected one of …").
pub fn known_keys(obj: &JsValue, allowed: &[&str], what: &str) -> Result<(), JsError> {
    let Some(o) = obj.dyn_ref::<Object>() else {
        return Ok(());
    };
    for k in Object::keys(o).iter() {
        let k = k.as_string().unwrap_or_default();
        if !allowed.contains(&k.as_str()) {
            let mut all = allowed.to_vec();
            all.sort_unstable();
            return Err(JsError::new(&format!(
                "{what}: unknown key '{}'; expected one of {}",
                budget::clip(&k, 40),
                all.join(", ")
            )));
        }
    }
    Ok(())
}

/// An `Error` unless `value` is a non-array object. `Array.isArray` runs in
/// the catching helper: on a revoked Proxy it throws, and the `Error` says
/// so, naming `what`.
pub fn require_object(value: &JsValue, what: &str) -> Result<(), JsError> {
    not_reentered()?;
    let got = if value.is_null() {
        "null".to_string()
    } else if !value.is_object() || value.is_function() {
        if revoked(value) {
            return Err(JsError::new(&format!(
                "{what}: is a revoked Proxy; pass plain data (numbers, strings, arrays, objects)"
            )));
        }
        format!("a {}", value.js_typeof().as_string().unwrap_or_default())
    } else if is_array_arg(value, what).map_err(message)? {
        "an array".to_string()
    } else {
        return Ok(());
    };
    Err(JsError::new(&format!(
        "{what}: expected an object {{ … }}, got {got}"
    )))
}

/// A number argument, read without JS's conversion (wasm-bindgen's own
/// `f64` runs `ToNumber`, which reads `"5"` as 5 and throws an unnamed
/// `TypeError` on a revoked Proxy): anything but a JS number is an `Error`
/// naming `what`.
pub fn number_arg(value: &JsValue, what: &str) -> Result<f64, JsError> {
    not_reentered()?;
    value
        .as_f64()
        .ok_or_else(|| JsError::new(&format!("{what}: expected a number, got {}", got(value))))
}

/// An optional callback argument: `undefined`/`null` give `None`, a
/// function `Some`; anything else, a revoked Proxy included, is an `Error`
/// naming `what` (wasm-bindgen's own `Option<Function>` takes any object
/// unchecked, and calling it failed without a word).
pub fn callback_arg(value: JsValue, what: &str) -> Result<Option<js_sys::Function>, JsError> {
    not_reentered()?;
    if value.is_undefined() || value.is_null() {
        return Ok(None);
    }
    if value.is_function() && !revoked(&value) {
        return Ok(Some(value.unchecked_into()));
    }
    Err(JsError::new(&format!(
        "{what}: expected a function, got {}",
        got(&value)
    )))
}

/// An optional number field of a plain snapshot: absent (`undefined` or
/// `null`) gives `None`; anything but a finite number is an `Error` naming
/// `what` (a string such as `"200"` is not read as 200, nor ignored).
pub fn opt_number(obj: &JsValue, key: &str, what: &str) -> Result<Option<f64>, JsError> {
    let v = Reflect::get(obj, &JsValue::from_str(key)).unwrap_or(JsValue::UNDEFINED);
    opt_number_arg(&v, &format!("{what}.{key}"))
}

/// An optional number argument: `undefined`/`null` give `None`; anything
/// but a finite number (a string, NaN, ±Infinity) is an `Error` naming
/// `what`. wasm-bindgen's own `Option<f64>` would read `"abc"` as NaN.
pub fn opt_number_arg(value: &JsValue, what: &str) -> Result<Option<f64>, JsError> {
    not_reentered()?;
    if value.is_undefined() || value.is_null() {
        return Ok(None);
    }
    match value.as_f64() {
        Some(x) if x.is_finite() => Ok(Some(x)),
        Some(x) => Err(JsError::new(&format!(
            "{what}: expected a finite number, got {}",
            crate::numeric::compact(x)
        ))),
        None if revoked(value) => Err(JsError::new(&format!(
            "{what}: expected a number, got a revoked Proxy"
        ))),
        None => Err(JsError::new(&format!(
            "{what}: expected a number, got a {}",
            value.js_typeof().as_string().unwrap_or_default()
        ))),
    }
}

/// A whole count given as a JS number (wasm-bindgen's own `usize`
/// conversion wraps 2³² + 1 to 1): an `Error` unless it is an integer in
/// `0 ..= max`.
pub fn count_arg(value: f64, what: &str, max: usize) -> Result<usize, JsError> {
    if value.is_finite() && value >= 0.0 && value.fract() == 0.0 && value <= max as f64 {
        Ok(value as usize)
    } else {
        Err(JsError::new(&format!(
            "{what}: expected a whole number from 0 to {max}, got {}",
            crate::numeric::compact(value)
        )))
    }
}
