//! The fuzz targets: the same functions the stable loop in `tests/fuzz.rs`
//! runs (`tests/support/fuzz_targets.rs`), here for libFuzzer.

#[path = "../../tests/support/fuzz_targets.rs"]
mod targets;

pub use targets::*;

/// Runs `target` on `data` read as a browser reads a file (invalid UTF-8
/// becomes U+FFFD); a failed property panics, which libFuzzer reports as a
/// crash and saves the input.
pub fn run(target: Target, data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    if let Err(e) = target(&text) {
        panic!("{e}");
    }
}
