//! The tool-path simulation holds about 0.4 to 0.7 KB of memory per segment while
//! it runs, so it refuses a program of more than
//! `budget::MAX_TOOLPATH_SEGMENTS` segments before any work, naming the
//! count, the limit and the source line of the first segment over it; a
//! program of exactly the budget is not refused by it (here it is then
//! refused as empty, which needs the timeline and the path of every
//! segment).

use mtmotion::budget::MAX_TOOLPATH_SEGMENTS;
use mtmotion::nc::program::parse;
use mtmotion::toolpath::{simulate, SimConfig, ToolpathError};

#[test]
fn more_segments_than_the_budget_are_refused_naming_the_first_line_over_it() {
    // A zero-length move (G1 X0 from X0) has no length: a program of only
    // such moves simulates nothing and is refused as empty.
    let p = parse("G1 X0 F100").unwrap();
    let still = p.segments[0].clone();
    let mut segs: Vec<_> = (0..MAX_TOOLPATH_SEGMENTS)
        .map(|i| {
            let mut s = still.clone();
            s.line = i + 1;
            s
        })
        .collect();
    let cfg = SimConfig::default();
    assert!(matches!(
        simulate(&segs, &segs, &cfg),
        Err(ToolpathError::Empty)
    ));
    let mut over = still;
    over.line = 4_321_000;
    segs.push(over);
    let e = simulate(&segs, &segs, &cfg).unwrap_err();
    assert!(
        matches!(e, ToolpathError::TooManySegments { segments, limit, next, line: 4_321_000 }
            if segments == MAX_TOOLPATH_SEGMENTS + 1 && limit == MAX_TOOLPATH_SEGMENTS && next == limit + 1),
        "{e:?}"
    );
    assert!(e.to_string().starts_with(&format!(
        "the simulation would hold {} segments, more than the limit of {MAX_TOOLPATH_SEGMENTS}",
        MAX_TOOLPATH_SEGMENTS + 1
    )));
    assert!(
        e.to_string()
            .contains("is line 4321000: split the program there"),
        "{e}"
    );
}
