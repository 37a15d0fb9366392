//! Computes every number of the README's and docs' paper-comparison tables
//! and writes `docs/paper-tables.json` and `docs/paper-tables.md`.
//!
//! Run: `cargo run --release --example paper_tables` (2 s of computing). Commit both
//! files; `cargo test --test paper_tables` then fails when a model moves a
//! paper number, printing the old and the new value.

#[cfg(not(target_arch = "wasm32"))]
#[path = "../tests/support/paper_tables.rs"]
mod paper_tables;

#[cfg(not(target_arch = "wasm32"))]
fn main() -> Result<(), Box<dyn std::error::Error>> {
    let rows = paper_tables::compute();
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs");
    std::fs::write(
        root.join("paper-tables.json"),
        serde_json::to_string_pretty(&rows)? + "\n",
    )?;
    std::fs::write(root.join("paper-tables.md"), paper_tables::markdown(&rows))?;
    println!(
        "{} rows written to docs/paper-tables.json and docs/paper-tables.md",
        rows.len()
    );
    Ok(())
}

#[cfg(target_arch = "wasm32")]
fn main() {}
