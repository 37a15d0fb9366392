//! The JS binding layer (wasm32 only): thin, no logic.
//!
//! Pattern every binding follows:
//! - fallible functions return `Result<T, JsError>`; the core's error message
//!   becomes the thrown `Error`'s message;
//! - small configs and results cross through serde-wasm-bindgen
//!   ([`convert::from_js`], [`convert::to_js`]) and have TypeScript shapes
//!   in a `typescript_custom_section`;
//! - bulk arrays cross as `Float64Array` (`&[f64]` in, [`convert::Obj::arr`]
//!   out), never through serde;
//! - the panic hook is installed at start.

//!
//! Without the default feature `full` (`--no-default-features`) only the
//! bindings the documentation calculators (`www/embed.js`) call are
//! exported: the small embed module (docs/performance.md).

// Helpers that only `full` bindings use are unused without it.
#[cfg_attr(not(feature = "full"), allow(dead_code, unused_imports))]
pub mod ballbar;
pub mod convert;
#[cfg(feature = "full")]
pub mod kinematics;
#[cfg_attr(not(feature = "full"), allow(dead_code, unused_imports))]
pub mod machine;
#[cfg_attr(not(feature = "full"), allow(dead_code, unused_imports))]
pub mod servo;
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
