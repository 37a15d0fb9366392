//! The JS binding layer (wasm32 only): thin, no logic.
//!
//! Pattern every binding follows:
//! - fallible functions return `Result<T, JsError>`; the core's error message
//!   becomes the thrown `Error`'s message;
//! - small configs are copied into plain data ([`convert::plain`]) and
//!   read strictly by [`strict`] ([`convert::from_js`], [`convert::object`]:
//!   an unknown key, an array for an object or a string for a number is an
//!   `Error` naming its path); results cross through serde-wasm-bindgen
//!   ([`convert::to_js`]); both have TypeScript shapes in a
//!   `typescript_custom_section`;
//! - no export runs while a progress callback runs
//!   ([`convert::not_reentered`]);
//! - bulk arrays cross as `Float64Array` (`&[f64]` in, [`convert::Obj::arr`]
//!   out), never through serde;
//! - the panic hook is installed at start.

//!
//! Without the default feature `full` (`--no-default-features`) only the
//! bindings the documentation calculators (`www/embed.js`) call are
//! exported: the small embed module (docs/performance.md).

// Helpers that only `full` bindings use are unused without it.
pub mod args;
#[cfg_attr(not(feature = "full"), allow(dead_code, unused_imports))]
pub mod ballbar;
pub mod convert;
#[cfg(feature = "full")]
pub mod kinematics;
#[cfg_attr(not(feature = "full"), allow(dead_code, unused_imports))]
pub mod machine;
#[cfg(feature = "full")]
pub mod nc_stream;
pub mod results;
#[cfg_attr(not(feature = "full"), allow(dead_code, unused_imports))]
pub mod servo;
pub mod strict;
#[cfg_attr(not(feature = "full"), allow(dead_code, unused_imports))]
pub mod toolpath;

use wasm_bindgen::prelude::*;

/// Installs the panic hook; runs once when the module is instantiated.
#[wasm_bindgen(start)]
pub fn start() {
    console_error_panic_hook::set_once();
}

/// The crate version, e.g. `"0.1.0"`.
#[wasm_bindgen]
pub fn version() -> String {
    env!("CARGO_PKG_VERSION").to_string()
}

/// Checks a file's size before the page reads it: an `Error` when a text of
/// `bytes` bytes is over the core's text budget ([`crate::budget::check_bytes`]),
/// naming the file. The page asks this first, so a 50 MB file it would
/// refuse is never read into the page or copied to the worker.
#[cfg(feature = "full")]
#[wasm_bindgen(js_name = checkFileSize)]
pub fn check_file_size(
    #[wasm_bindgen(unchecked_param_type = "string")] name: JsValue,
    #[wasm_bindgen(unchecked_param_type = "number")] bytes: JsValue,
) -> Result<(), JsError> {
    let name = convert::name_arg(&name, "name")?;
    let bytes = convert::number_arg(&bytes, "bytes")?;
    if !(bytes.is_finite() && bytes >= 0.0 && bytes.fract() == 0.0) {
        return Err(JsError::new(&format!(
            "bytes: expected a whole number of bytes, 0 or more, got {}",
            crate::numeric::compact(bytes)
        )));
    }
    let name = crate::budget::clip(&name, 60);
    // above 2^53 a size is no exact integer, and `as u64` saturated 1e308
    // to 18446744073709551615: say the number as given
    if bytes > 9_007_199_254_740_992.0 {
        return Err(JsError::new(&format!(
            "{name}: file size: {} bytes, more than the limit of {}; {}",
            crate::numeric::compact(bytes),
            crate::budget::MAX_TEXT_BYTES,
            crate::budget::TEXT_ADVICE
        )));
    }
    crate::budget::check_bytes("file size", bytes as u64)
        .map_err(|e| JsError::new(&format!("{name}: {e}")))
}
