//! The shared NC corpus of real public programs, read by the tests that
//! run them. It is not in the repository (the programs are other people's
//! files, each under its own licence; see the corpus's SOURCES.md): it is
//! `../shared/nc_corpus` from the project root, or the folder named by the
//! environment variable `MTMOTION_NC_CORPUS`. On a checkout without it, a
//! test that needs it prints one line saying it was skipped and why, and
//! passes.
#![allow(dead_code)] // each test crate uses some of these

use std::io::Write;
use std::path::PathBuf;

/// The environment variable that names the corpus folder.
pub const ENV: &str = "MTMOTION_NC_CORPUS";

/// The corpus folder, or why it is not there.
pub fn dir() -> Result<PathBuf, String> {
    let d = match std::env::var_os(ENV) {
        Some(p) => PathBuf::from(p),
        None => PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/nc_corpus")),
    };
    if d.is_dir() {
        Ok(d)
    } else {
        Err(format!(
            "the NC corpus folder {} is not there (set {ENV} to the shared corpus)",
            d.display()
        ))
    }
}

/// Prints one line on the test's stderr, past the test harness's capture
/// (so `cargo test` shows it for a passing test).
pub fn say(line: &str) {
    let _ = writeln!(std::io::stderr(), "{line}");
}

/// The corpus folder, or `None` after printing that `what` is skipped and
/// why.
pub fn available(what: &str) -> Option<PathBuf> {
    match dir() {
        Ok(d) => Some(d),
        Err(why) => {
            say(&format!("skipped {what}: {why}"));
            None
        }
    }
}

/// The corpus's program files, sorted by name (SOURCES.md left out).
pub fn names(dir: &std::path::Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n != "SOURCES.md" && !n.starts_with('.'))
        .collect();
    names.sort();
    names
}

/// The text of corpus file `name` (every corpus file is UTF-8); the
/// corpus must be there (see [`available`], [`text`]).
pub fn read(name: &str) -> String {
    let d = dir().unwrap_or_else(|why| panic!("{name}: {why}"));
    let bytes = std::fs::read(d.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
    String::from_utf8(bytes).unwrap_or_else(|e| panic!("{name}: not UTF-8: {e}"))
}

/// The text of corpus file `name`, or `None` after printing that the test
/// reading it is skipped and why.
pub fn text(name: &str) -> Option<String> {
    available(&format!("the test of {name}"))?;
    Some(read(name))
}
