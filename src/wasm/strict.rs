//! A strict serde deserializer over a [`super::convert::plain`] snapshot.
//!
//! serde-wasm-bindgen reads a struct by asking the JS object for the
//! fields the struct names, so a key it does not name is never seen: a
//! misspelt `errors: { Location: … }` left every error at 0 without a
//! word, `#[serde(deny_unknown_fields)]` could not help, and an array was
//! read as a struct (`harmonics: [[2, 0.005, 0.1]]`, its items looked up as
//! `order`, `amplitude`, … on the array). This one reads the snapshot
//! itself and:
//! - refuses a key a struct does not name, at any depth, naming the key,
//!   its path and the keys allowed ("options.errors: unknown key
//!   'Location'; expected one of component, location, tool");
//! - reads a struct only from a plain object, a list only from an array,
//!   a number only from a JS number (finite: NaN and ±Infinity are refused
//!   naming the field), a whole number only from an integer in its type's
//!   range, a string only from a string;
//! - names the path of whatever is wrong (`config.harmonics[0].order:
//!   expected a whole number from 0 to 4294967295, got 1.5`), and never
//!   says serde's internals ("untagged enum …", "expected any value").
//!
//! The snapshot holds only `null`, booleans, numbers, strings, arrays,
//! plain objects and `Float64Array`s (typed arrays are copied into one),
//! so nothing read here runs user code or throws.

use std::fmt;

use js_sys::{Array, Float64Array, JsString, Object, Reflect};
use serde::de::{self, DeserializeSeed, Visitor};
use wasm_bindgen::{JsCast, JsValue};

use crate::budget::clip;

/// A deserialization error; `located` once its message starts with the
/// path of the value it is about.
#[derive(Debug)]
pub struct Error {
    msg: String,
    located: bool,
}

impl Error {
    fn at(path: &Path, msg: impl fmt::Display) -> Self {
        Self {
            msg: format!("{path}: {msg}"),
            located: true,
        }
    }

    /// Puts `path` before a message serde's derive wrote (it does not
    /// know where it is).
    fn locate(self, path: &Path) -> Self {
        if self.located {
            self
        } else {
            Self::at(path, self.msg)
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.msg)
    }
}

impl std::error::Error for Error {}

impl de::Error for Error {
    fn custom<T: fmt::Display>(msg: T) -> Self {
        Self {
            msg: msg.to_string(),
            located: false,
        }
    }

    fn unknown_variant(variant: &str, expected: &'static [&'static str]) -> Self {
        de::Error::custom(format_args!(
            "unknown value '{}'; expected one of {}",
            clip(variant, 40),
            expected.join(", ")
        ))
    }

    fn missing_field(field: &'static str) -> Self {
        de::Error::custom(format_args!("missing key '{field}'"))
    }
}

/// Where a value is: the argument's name, then keys and indices.
#[derive(Clone, Copy)]
pub enum Path<'a> {
    /// The argument, e.g. `options`.
    Root(&'a str),
    /// A key of an object.
    Key(&'a Path<'a>, &'a str),
    /// An item of an array.
    Index(&'a Path<'a>, usize),
}

impl fmt::Display for Path<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Path::Root(s) => f.write_str(s),
            Path::Key(p, k) => write!(f, "{p}.{}", clip(k, 40)),
            Path::Index(p, i) => write!(f, "{p}[{i}]"),
        }
    }
}

/// A number as JS writes it (`NaN`, `Infinity`; Rust says `inf`), with at
/// most 6 significant digits.
pub fn js_number(x: f64) -> String {
    if x.is_nan() {
        "NaN".into()
    } else if x.is_infinite() {
        (if x > 0.0 { "Infinity" } else { "-Infinity" }).into()
    } else {
        crate::numeric::compact(x)
    }
}

/// What a snapshot value is, for a message.
pub fn kind(v: &JsValue) -> &'static str {
    if v.is_null() {
        "null"
    } else if v.is_undefined() {
        "undefined"
    } else if v.as_bool().is_some() {
        "a boolean"
    } else if v.as_f64().is_some() {
        "a number"
    } else if v.is_string() {
        "a string"
    } else if v.is_instance_of::<Float64Array>() || Array::is_array(v) {
        "an array"
    } else if v.is_object() {
        "an object"
    } else {
        "a value of another type"
    }
}

/// Deserializes `T` from the snapshot `value` strictly; `what` names the
/// argument.
pub fn from_snapshot<T: de::DeserializeOwned>(value: JsValue, what: &str) -> Result<T, Error> {
    let path = Path::Root(what);
    T::deserialize(De { v: value, path }).map_err(|e| e.locate(&path))
}

/// One value of the snapshot and its path.
pub struct De<'a> {
    v: JsValue,
    path: Path<'a>,
}

impl De<'_> {
    fn wrong(&self, expected: &str) -> Error {
        Error::at(
            &self.path,
            format!("expected {expected}, got {}", kind(&self.v)),
        )
    }

    fn number(&self) -> Result<f64, Error> {
        match self.v.as_f64() {
            Some(x) if x.is_finite() => Ok(x),
            Some(x) => Err(Error::at(
                &self.path,
                format!("expected a finite number, got {}", js_number(x)),
            )),
            None => Err(self.wrong("a number")),
        }
    }

    fn whole(&self, min: f64, max: f64) -> Result<f64, Error> {
        let range = || {
            format!(
                "expected a whole number from {} to {}",
                crate::numeric::compact(min),
                if max >= 9.0e15 {
                    "9007199254740991".to_string()
                } else {
                    format!("{max}")
                }
            )
        };
        let Some(x) = self.v.as_f64() else {
            return Err(Error::at(
                &self.path,
                format!("{}, got {}", range(), kind(&self.v)),
            ));
        };
        if x.fract() == 0.0 && x >= min && x <= max {
            Ok(x)
        } else {
            Err(Error::at(
                &self.path,
                format!("{}, got {}", range(), crate::numeric::compact(x)),
            ))
        }
    }

    fn object(&self) -> Option<&Object> {
        if Array::is_array(&self.v) || self.v.is_instance_of::<Float64Array>() {
            return None;
        }
        self.v.dyn_ref::<Object>()
    }

    fn keys(obj: &Object) -> Vec<String> {
        Object::keys(obj)
            .iter()
            .map(|k| k.as_string().unwrap_or_default())
            .collect()
    }

    fn seq<'de, V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        let path = self.path;
        let access = if let Some(a) = self.v.dyn_ref::<Float64Array>() {
            Seq::Floats(a.to_vec().into_iter(), 0, path)
        } else if Array::is_array(&self.v) {
            let a: Array = self.v.unchecked_into();
            Seq::Items(a, 0, path)
        } else {
            return Err(self.wrong("an array"));
        };
        visitor.visit_seq(access).map_err(|e| e.locate(&path))
    }
}

macro_rules! whole {
    ($($method:ident $visit:ident $t:ty),*) => {$(
        fn $method<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
            const SAFE: f64 = 9_007_199_254_740_991.0;
            let x = self.whole((<$t>::MIN as f64).max(-SAFE), (<$t>::MAX as f64).min(SAFE))?;
            visitor.$visit(x as $t)
        }
    )*};
}

impl<'de> de::Deserializer<'de> for De<'_> {
    type Error = Error;

    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        let path = self.path;
        let v = &self.v;
        let r = if v.is_null() || v.is_undefined() {
            visitor.visit_unit()
        } else if let Some(b) = v.as_bool() {
            visitor.visit_bool(b)
        } else if let Some(x) = v.as_f64() {
            if !x.is_finite() {
                return Err(Error::at(
                    &path,
                    format!("expected a finite number, got {}", js_number(x)),
                ));
            }
            if x.fract() == 0.0 && x.abs() <= 9_007_199_254_740_991.0 {
                visitor.visit_i64(x as i64)
            } else {
                visitor.visit_f64(x)
            }
        } else if let Some(s) = v.as_string() {
            visitor.visit_string(s)
        } else if v.is_instance_of::<Float64Array>() || Array::is_array(v) {
            return self.seq(visitor);
        } else if let Some(o) = self.object() {
            let keys = De::keys(o);
            visitor.visit_map(Map::new(o.clone(), keys, path))
        } else {
            return Err(self.wrong("plain data"));
        };
        r.map_err(|e| e.locate(&path))
    }

    fn deserialize_bool<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        match self.v.as_bool() {
            Some(b) => visitor.visit_bool(b),
            None => Err(self.wrong("true or false")),
        }
    }

    whole!(deserialize_i8 visit_i8 i8, deserialize_i16 visit_i16 i16, deserialize_i32 visit_i32 i32,
        deserialize_i64 visit_i64 i64, deserialize_u8 visit_u8 u8, deserialize_u16 visit_u16 u16,
        deserialize_u32 visit_u32 u32, deserialize_u64 visit_u64 u64);

    fn deserialize_f32<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_f32(self.number()? as f32)
    }

    fn deserialize_f64<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_f64(self.number()?)
    }

    fn deserialize_char<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        self.deserialize_string(visitor)
    }

    fn deserialize_str<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        self.deserialize_string(visitor)
    }

    fn deserialize_string<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        match self.v.dyn_ref::<JsString>() {
            Some(s) => visitor
                .visit_string(String::from(s))
                .map_err(|e: Error| e.locate(&self.path)),
            None => Err(self.wrong("a string")),
        }
    }

    fn deserialize_bytes<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        self.seq(visitor)
    }

    fn deserialize_byte_buf<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        self.seq(visitor)
    }

    fn deserialize_option<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        if self.v.is_null() || self.v.is_undefined() {
            visitor.visit_none()
        } else {
            visitor.visit_some(self)
        }
    }

    fn deserialize_unit<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        if self.v.is_null() || self.v.is_undefined() {
            visitor.visit_unit()
        } else {
            Err(self.wrong("null"))
        }
    }

    fn deserialize_unit_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        visitor: V,
    ) -> Result<V::Value, Error> {
        self.deserialize_unit(visitor)
    }

    fn deserialize_newtype_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        visitor: V,
    ) -> Result<V::Value, Error> {
        visitor.visit_newtype_struct(self)
    }

    fn deserialize_seq<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        self.seq(visitor)
    }

    fn deserialize_tuple<V: Visitor<'de>>(self, len: usize, visitor: V) -> Result<V::Value, Error> {
        let n = if let Some(a) = self.v.dyn_ref::<Float64Array>() {
            a.length() as usize
        } else if Array::is_array(&self.v) {
            Array::from(&self.v).length() as usize
        } else {
            return Err(self.wrong(&format!("an array of {len}")));
        };
        if n != len {
            return Err(Error::at(
                &self.path,
                format!("expected an array of {len}, got {n} items"),
            ));
        }
        self.seq(visitor)
    }

    fn deserialize_tuple_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        len: usize,
        visitor: V,
    ) -> Result<V::Value, Error> {
        self.deserialize_tuple(len, visitor)
    }

    fn deserialize_map<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        let path = self.path;
        let Some(o) = self.object() else {
            return Err(self.wrong("an object { … }"));
        };
        let keys = De::keys(o);
        visitor
            .visit_map(Map::new(o.clone(), keys, path))
            .map_err(|e| e.locate(&path))
    }

    fn deserialize_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, Error> {
        let path = self.path;
        let Some(o) = self.object() else {
            return Err(self.wrong("an object { … }"));
        };
        let keys = De::keys(o);
        if let Some(k) = keys.iter().find(|k| !fields.contains(&k.as_str())) {
            let mut all = fields.to_vec();
            all.sort_unstable();
            return Err(Error::at(
                &path,
                format!(
                    "unknown key '{}'; expected one of {}",
                    clip(k, 40),
                    all.join(", ")
                ),
            ));
        }
        visitor
            .visit_map(Map::new(o.clone(), keys, path))
            .map_err(|e| e.locate(&path))
    }

    fn deserialize_enum<V: Visitor<'de>>(
        self,
        _name: &'static str,
        variants: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, Error> {
        let path = self.path;
        let (tag, payload) = if let Some(s) = self.v.as_string() {
            (s, JsValue::UNDEFINED)
        } else if let Some(o) = self.object() {
            let keys = De::keys(o);
            if keys.len() != 1 {
                return Err(Error::at(
                    &path,
                    format!("expected one of {}", variants.join(", ")),
                ));
            }
            let v = Reflect::get(o, &JsValue::from_str(&keys[0])).unwrap_or(JsValue::UNDEFINED);
            (keys[0].clone(), v)
        } else {
            return Err(self.wrong(&format!("one of {}", variants.join(", "))));
        };
        visitor
            .visit_enum(Enum { tag, payload, path })
            .map_err(|e| e.locate(&path))
    }

    fn deserialize_identifier<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        self.deserialize_string(visitor)
    }

    fn deserialize_ignored_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_unit()
    }
}

/// The items of an array (or a `Float64Array`'s numbers).
enum Seq<'a> {
    Items(Array, u32, Path<'a>),
    Floats(std::vec::IntoIter<f64>, usize, Path<'a>),
}

impl<'de> de::SeqAccess<'de> for Seq<'_> {
    type Error = Error;

    fn next_element_seed<T: DeserializeSeed<'de>>(
        &mut self,
        seed: T,
    ) -> Result<Option<T::Value>, Error> {
        match self {
            Seq::Items(a, i, path) => {
                if *i >= a.length() {
                    return Ok(None);
                }
                let v = a.get(*i);
                let p = Path::Index(path, *i as usize);
                *i += 1;
                seed.deserialize(De { v, path: p })
                    .map(Some)
                    .map_err(|e| e.locate(&p))
            }
            Seq::Floats(it, i, path) => {
                let Some(x) = it.next() else {
                    return Ok(None);
                };
                let p = Path::Index(path, *i);
                *i += 1;
                seed.deserialize(De {
                    v: JsValue::from_f64(x),
                    path: p,
                })
                .map(Some)
                .map_err(|e| e.locate(&p))
            }
        }
    }

    fn size_hint(&self) -> Option<usize> {
        Some(match self {
            Seq::Items(a, i, _) => (a.length() - *i) as usize,
            Seq::Floats(it, _, _) => it.len(),
        })
    }
}

/// The keys of a plain object and their values.
struct Map<'a> {
    obj: Object,
    keys: std::vec::IntoIter<String>,
    key: String,
    path: Path<'a>,
}

impl<'a> Map<'a> {
    fn new(obj: Object, keys: Vec<String>, path: Path<'a>) -> Self {
        Self {
            obj,
            keys: keys.into_iter(),
            key: String::new(),
            path,
        }
    }
}

impl<'de> de::MapAccess<'de> for Map<'_> {
    type Error = Error;

    fn next_key_seed<K: DeserializeSeed<'de>>(
        &mut self,
        seed: K,
    ) -> Result<Option<K::Value>, Error> {
        let Some(k) = self.keys.next() else {
            return Ok(None);
        };
        self.key = k;
        let p = Path::Key(&self.path, &self.key);
        seed.deserialize(De {
            v: JsValue::from_str(&self.key),
            path: p,
        })
        .map(Some)
        .map_err(|e| e.locate(&p))
    }

    fn next_value_seed<V: DeserializeSeed<'de>>(&mut self, seed: V) -> Result<V::Value, Error> {
        let v =
            Reflect::get(&self.obj, &JsValue::from_str(&self.key)).unwrap_or(JsValue::UNDEFINED);
        let p = Path::Key(&self.path, &self.key);
        seed.deserialize(De { v, path: p })
            .map_err(|e| e.locate(&p))
    }

    fn size_hint(&self) -> Option<usize> {
        Some(self.keys.len())
    }
}

/// An enum given as `"variant"` or `{ variant: payload }`.
struct Enum<'a> {
    tag: String,
    payload: JsValue,
    path: Path<'a>,
}

impl<'de, 'a> de::EnumAccess<'de> for Enum<'a> {
    type Error = Error;
    type Variant = Self;

    fn variant_seed<V: DeserializeSeed<'de>>(self, seed: V) -> Result<(V::Value, Self), Error> {
        let tag = seed.deserialize(De {
            v: JsValue::from_str(&self.tag),
            path: self.path,
        })?;
        Ok((tag, self))
    }
}

impl<'de> de::VariantAccess<'de> for Enum<'_> {
    type Error = Error;

    fn unit_variant(self) -> Result<(), Error> {
        if self.payload.is_undefined() || self.payload.is_null() {
            Ok(())
        } else {
            Err(Error::at(
                &self.path,
                format!("'{}' takes no value", clip(&self.tag, 40)),
            ))
        }
    }

    fn newtype_variant_seed<T: DeserializeSeed<'de>>(self, seed: T) -> Result<T::Value, Error> {
        let p = Path::Key(&self.path, &self.tag);
        seed.deserialize(De {
            v: self.payload.clone(),
            path: p,
        })
    }

    fn tuple_variant<V: Visitor<'de>>(self, len: usize, visitor: V) -> Result<V::Value, Error> {
        let p = Path::Key(&self.path, &self.tag);
        de::Deserializer::deserialize_tuple(
            De {
                v: self.payload.clone(),
                path: p,
            },
            len,
            visitor,
        )
    }

    fn struct_variant<V: Visitor<'de>>(
        self,
        fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, Error> {
        let p = Path::Key(&self.path, &self.tag);
        de::Deserializer::deserialize_struct(
            De {
                v: self.payload.clone(),
                path: p,
            },
            "",
            fields,
            visitor,
        )
    }
}
