//! The repository's NC corpus (`tests/nc_corpus/`, see its SOURCES.md),
//! read by the tests that run its programs.

/// The text of corpus file `name` (every corpus file is UTF-8).
pub fn read(name: &str) -> String {
    let bytes = std::fs::read(format!(
        "{}/tests/nc_corpus/{name}",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap_or_else(|e| panic!("{name}: {e}"));
    String::from_utf8(bytes).unwrap_or_else(|e| panic!("{name}: not UTF-8: {e}"))
}
