//! Every published figure is a test: the numbers of the paper-comparison
//! tables (`docs/paper-tables.json`, written by
//! `cargo run --release --example paper_tables`) must equal a fresh
//! computation to a relative 1e-9. A change that moves a paper number
//! fails here and prints the committed and the new value; regenerate the
//! file and the docs' tables (docs/reproducing.md, docs/paper-tables.md)
//! if the change is intended.
//! The whole computation takes about 2 s in a debug build.
#![cfg(not(target_arch = "wasm32"))]

#[path = "support/paper_tables.rs"]
mod paper_tables;

use paper_tables::{compute, differences, Row};

fn committed() -> Vec<Row> {
    serde_json::from_str(include_str!("../docs/paper-tables.json")).unwrap()
}

#[test]
fn committed_paper_tables_match_a_fresh_computation() {
    let old = committed();
    let new = compute();
    let diff = differences(&old, &new);
    assert!(
        diff.is_empty(),
        "{} paper number(s) moved (committed → now):\n{}",
        diff.len(),
        diff.join("\n")
    );
    // the markdown next to the JSON is the JSON's rendering
    let md = include_str!("../docs/paper-tables.md");
    assert_eq!(
        md,
        paper_tables::markdown(&old),
        "docs/paper-tables.md is stale: rerun the example"
    );
}

#[test]
fn a_moved_number_is_reported_with_old_and_new_values() {
    let old = committed();
    let mut new = old.clone();
    let i = new.iter().position(|r| r.ours.abs() > 1.0).unwrap();
    new[i].ours *= 1.0 + 1e-6;
    let d = differences(&old, &new);
    assert_eq!(d.len(), 1, "{d:?}");
    assert!(
        d[0].contains(&old[i].id)
            && d[0].contains(&format!("{}", old[i].ours))
            && d[0].contains(&format!("{}", new[i].ours))
    );
}

/// The headline numbers of docs/reproducing.md (moved there from the
/// README), as it quotes them (rounded): a change that moves one fails
/// here even if the JSON were regenerated, and each must appear in that
/// page as quoted, so the page is updated with it.
#[test]
fn headline_numbers_are_pinned_and_quoted_in_the_docs() {
    let old = compute();
    let page = include_str!("../docs/reproducing.md");
    let get = |id: &str| {
        old.iter()
            .find(|r| r.id == id)
            .unwrap_or_else(|| panic!("{id} missing"))
            .ours
    };
    for (id, quoted, digits) in [
        ("suzuki.saturation.presetKffp.5.9.accelSat", 120.3, 1),
        ("suzuki.saturation.preControlOff.5.9.accelSat", 143.5, 1),
        ("suzuki.saturation.preControlOff.5.9.rcMin", 0.363, 3),
        ("qiu.arc.before.maxError", 53.1, 1),
        ("qiu.arc.oneRound.maxError", 13.4, 1),
        ("qiu.arc.default.maxError", 6.8, 1),
        ("qiu.eq3.tightestArc", 60.9, 1),
        ("takayama.fig7.ballBar.dX.90", 14.89, 2),
        ("takayama.fig7-phased.ballBar.dZ.90", 9.40, 2),
        ("thasana.total.repeatability1um", 98.7, 1),
    ] {
        let v = get(id);
        let shown = format!("{v:.digits$}");
        assert_eq!(
            shown,
            format!("{quoted:.digits$}"),
            "{id}: docs/reproducing.md quotes {quoted}, now {v}"
        );
        assert!(
            page.contains(&shown),
            "{id}: {shown} is not in docs/reproducing.md"
        );
    }
}
