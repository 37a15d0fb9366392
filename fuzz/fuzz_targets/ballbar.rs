#![no_main]
//! libFuzzer target: `mtmotion_fuzz::ballbar_target` (see `tests/support/fuzz_targets.rs`).

libfuzzer_sys::fuzz_target!(|data: &[u8]| mtmotion_fuzz::run(mtmotion_fuzz::ballbar_target, data));
