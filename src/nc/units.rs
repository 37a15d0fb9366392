//! The length unit of a program that never states one (G20/G21, or
//! G70/G71 where they are units: without the I/J/K/L of a Haas bolt-hole
//! pattern).
//!
//! A program without G20/G21 runs in the control's power-on unit (a
//! machine setting: Fanuc parameter 0000#2 INI, [`super::program::ParseOptions::units`],
//! default mm). Read in the wrong unit, an inch program's path is 25.4
//! times too small and every error with it, in silence (a field program
//! gave 9.4 µm read as mm against 186.5 µm with G20). So a program that
//! never states its units and whose numbers look like the other unit is
//! warned about, once, at its first coordinate word.
//!
//! The reading of "looks like" (stated thresholds, in the program's own
//! numbers): read as mm, the numbers look like inch when the largest
//! |X|, |Y|, |Z| is at most [`INCH_LIKE_EXTENT`] and either most
//! coordinate words carry four decimals (inch posts write 4, mm posts 3)
//! or there are at least [`MIN_WORDS`] coordinate words and no feed is
//! above [`INCH_LIKE_FEED`]. Read as inch, they look like mm when the
//! largest coordinate is above [`MM_LIKE_EXTENT`] (2.5 m read as inch).

use super::program::{Program, Units, Warning};
use super::Block;

/// Largest coordinate of an inch-looking program, its own numbers.
pub const INCH_LIKE_EXTENT: f64 = 40.0;
/// Largest feed of an inch-looking program (inch/min read as mm/min).
pub const INCH_LIKE_FEED: f64 = 250.0;
/// Coordinate words needed before the feed alone makes it inch-looking.
pub const MIN_WORDS: usize = 10;
/// Largest coordinate above which an inch reading looks like mm.
pub const MM_LIKE_EXTENT: f64 = 100.0;

/// True when a block states the unit.
fn states_units(b: &Block) -> bool {
    b.words_of('G').any(|g| {
        let code = super::gcodes::code10(g);
        matches!(code, 200 | 210) || super::gcodes::units_g70_g71(b, code).is_some()
    })
}

/// Adds the warning of a program that never states its units and whose
/// numbers look like the other unit (see the module header).
pub fn check(p: &mut Program) {
    if p.blocks.iter().any(states_units) {
        return;
    }
    let coords: Vec<(&Block, &super::Word)> = p
        .blocks
        .iter()
        .flat_map(|b| b.words.iter().map(move |w| (b, w)))
        .filter(|(_, w)| matches!(w.letter, 'X' | 'Y' | 'Z'))
        .collect();
    let Some((first_b, first_w)) = coords.first().copied() else {
        return;
    };
    let extent = coords
        .iter()
        .map(|(_, w)| w.value.abs())
        .fold(0.0, f64::max);
    let four = coords
        .iter()
        .filter(|(_, w)| w.text.split_once('.').is_some_and(|(_, d)| d.len() == 4))
        .count();
    let feeds = p.blocks.iter().flat_map(|b| b.words_of('F'));
    let max_feed = feeds.map(|w| w.value).fold(0.0, f64::max);
    let (read, other, why) = match p.options.units {
        Units::Mm => {
            let decimals = 2 * four > coords.len();
            let slow = coords.len() >= MIN_WORDS && max_feed <= INCH_LIKE_FEED;
            if extent > INCH_LIKE_EXTENT || !(decimals || slow) {
                return;
            }
            let how = if decimals {
                "most coordinates are written with 4 decimals, as inch posts write them".to_string()
            } else {
                format!("no feed is above F{INCH_LIKE_FEED}")
            };
            (
                "mm",
                "inch",
                format!("the largest coordinate is {extent} and {how}"),
            )
        }
        Units::Inch => {
            if extent <= MM_LIKE_EXTENT {
                return;
            }
            ("inch", "mm", format!("the largest coordinate is {extent}"))
        }
    };
    p.warnings.push(Warning::at(
        first_b.line,
        first_w.column,
        format!(
            "units: the program never states its units (no G20/G21) and was read in {read} (the option units), but its numbers look like {other}: {why}; if it is an {other} program, add {} or set the option units to '{other}'",
            if other == "inch" { "G20" } else { "G21" }
        ),
    ));
}
