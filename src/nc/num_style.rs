//! The number style of a program's coordinate words, so that a number the
//! source-preserving writer ([`super::patch`]) replaces reads like the
//! program's own.
//!
//! What is read, from the coordinate words X Y Z I J K R (their text as
//! written, sign aside):
//! - *leading zero*: `0.5` or `.5`, by vote of the words below 1 with
//!   digits after the point and a value other than zero (posts that
//!   write `.5` write zero as `0.` or `0.000`, so zero keeps its `0`);
//! - *most decimals*: the most any word has; raised to 3 in mm or 4 in
//!   inch (1 µm, 2.5 µm) when the program is coarser, so a compensation is
//!   not rounded away (a 3-decimal inch program gets `-.7512`, never a
//!   25 µm step);
//! - *fewest decimals*: trailing zeros are trimmed down to this. A word
//!   that ends in `0` after its point (`1.500`, `3.0`) shows that the
//!   program keeps zeros to that many decimals; a word with fewer
//!   decimals and no trailing zero (`1.5` beside `1.500`) shows that it
//!   does not. The largest kept count that the words showing it
//!   outnumber the words against it is taken: `1.500` → 3,
//!   `3.0` → 1, `3.` → 0;
//! - *integer point*: with no decimals kept, `75.` or `75`, by vote of
//!   the integers other than zero (a Fanuc post may write `X0` and `X10.`;
//!   `X10` without a point is 10 µm there), else of the zeros (`75.` when
//!   the program has no integer at all);
//! - a *block* that shows its own style overrides the program's: one
//!   whose words with decimals all have the same count and one of them a
//!   trailing zero is fixed to that count (`X1.50 Y2.25` in a 4-decimal
//!   program is written with 2 — raised to the minimum resolution above);
//!   its own leading-zero and integer-point evidence wins too, and one
//!   with integers other than zero and no fraction (`X2 Y3`) keeps no
//!   trailing zeros (zeros, `X0.`, are often written apart by posts).
//!
//! Units: none (the text of numbers).

use super::Block;

/// Coordinate-number style of a program or block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NumStyle {
    /// Most decimals written.
    pub decimals: usize,
    /// Fewest decimals written: trailing zeros are trimmed down to this
    /// (`1.500`: 3, `3.0`: 1, `3.`: 0).
    pub min_decimals: usize,
    /// `0.5` rather than `.5`.
    pub lead_zero: bool,
    /// Integers with a decimal point (`75.`) when no decimal is kept.
    pub int_point: bool,
}

/// Finest resolution written in mm programs (1 µm), decimals.
pub const MIN_DECIMALS_MM: usize = 3;
/// Finest resolution written in inch programs (0.1 thou = 2.54 µm), decimals.
pub const MIN_DECIMALS_INCH: usize = 4;

/// The evidence of a set of words.
#[derive(Default)]
struct Tally {
    decimals: usize,
    lead: usize,
    nolead: usize,
    point: usize,
    nopoint: usize,
    /// Integers other than zero with a point (`75.`) and without (`75`).
    ipoint: usize,
    inopoint: usize,
    /// Decimals of each word with decimals, and whether it ends in `0`.
    fracs: Vec<(usize, bool)>,
}

fn tally<'a>(words: impl Iterator<Item = &'a super::Word>) -> Tally {
    let mut t = Tally::default();
    for w in words {
        if !"XYZIJKR".contains(w.letter) {
            continue;
        }
        let s = w.text.trim_start_matches(['+', '-']);
        if s.is_empty() || !s.bytes().all(|c| c.is_ascii_digit() || c == b'.') {
            continue;
        }
        match s.find('.') {
            Some(p) => {
                let d = s.len() - p - 1;
                t.decimals = t.decimals.max(d);
                if d == 0 {
                    t.point += 1;
                    t.ipoint += usize::from(w.value != 0.0);
                    continue;
                }
                if w.value == 0.0 {
                    // `0.000` or `.000`: zero, often written apart
                } else if p == 0 {
                    t.nolead += 1;
                } else if &s[..p] == "0" {
                    t.lead += 1;
                }
                t.fracs.push((d, s.ends_with('0')));
            }
            None => {
                t.nopoint += 1;
                t.inopoint += usize::from(w.value != 0.0);
            }
        }
    }
    t
}

impl Tally {
    /// Integers with a point, by the vote of the integers other than zero
    /// (a Fanuc post may write zero `X0` and every other integer `X10.`,
    /// and `X10` without a point is 10 µm there), else of the zeros.
    fn int_point(&self) -> Option<bool> {
        vote(self.ipoint, self.inopoint).or(if self.ipoint == 0 {
            vote(self.point, self.nopoint)
        } else {
            None
        })
    }

    /// The fewest decimals these words keep (see the module header).
    fn min_decimals(&self) -> usize {
        let mut kept: Vec<usize> = self
            .fracs
            .iter()
            .filter(|(_, z)| *z)
            .map(|(d, _)| *d)
            .collect();
        kept.sort_unstable();
        kept.dedup();
        kept.into_iter()
            .rev()
            .find(|&m| {
                let for_ = self.fracs.iter().filter(|(d, z)| *z && *d >= m).count();
                let against = self.fracs.iter().filter(|(d, z)| !*z && *d < m).count();
                for_ > against
            })
            .unwrap_or(0)
    }

    /// Fixed decimals of a block: all its words with decimals have the
    /// same count, one of them with a trailing zero.
    fn fixed(&self) -> Option<usize> {
        let (d0, _) = *self.fracs.first()?;
        (self.fracs.iter().all(|(d, _)| *d == d0) && self.fracs.iter().any(|(_, z)| *z))
            .then_some(d0)
    }
}

/// A vote: `Some(true)` when `yes` outnumbers `no`, `Some(false)` the
/// other way, `None` on a tie.
fn vote(yes: usize, no: usize) -> Option<bool> {
    match yes.cmp(&no) {
        std::cmp::Ordering::Greater => Some(true),
        std::cmp::Ordering::Less => Some(false),
        std::cmp::Ordering::Equal => None,
    }
}

fn floor(inch: bool) -> usize {
    if inch {
        MIN_DECIMALS_INCH
    } else {
        MIN_DECIMALS_MM
    }
}

impl NumStyle {
    /// The style of the coordinate words (X Y Z I J K R) of `blocks`.
    ///
    /// # Examples
    /// ```
    /// use mtmotion::nc::num_style::NumStyle;
    /// let b = mtmotion::nc::lex("G1 X0.250 Y1.500\nX2.000").unwrap();
    /// let s = NumStyle::of(&b, false);
    /// assert_eq!(s.format(-0.5), "-0.500");
    /// assert_eq!(s.format(3.0), "3.000");
    /// let b = mtmotion::nc::lex("g1x.25y1.5\nx75.").unwrap();
    /// let s = NumStyle::of(&b, false);
    /// assert_eq!(s.format(-0.5), "-.5");
    /// assert_eq!(s.format(3.0), "3.");
    /// assert_eq!(s.format(0.12345), ".123");
    /// // Zeros written `0.` are no vote for a leading zero.
    /// let b = mtmotion::nc::lex("G20 G1 X0. Y0. Z0.\nX-.75 Y3.0 Z-.967").unwrap();
    /// let s = NumStyle::of(&b, true);
    /// assert_eq!(s.format(-0.96712), "-.9671");
    /// assert_eq!(s.format(-3.0), "-3.0");
    /// ```
    pub fn of(blocks: &[Block], inch: bool) -> Self {
        let t = tally(blocks.iter().flat_map(|b| b.words.iter()));
        let decimals = t.decimals.max(floor(inch));
        Self {
            decimals,
            min_decimals: t.min_decimals().min(decimals),
            lead_zero: t.lead >= t.nolead,
            int_point: t.int_point().unwrap_or(true),
        }
    }

    /// This (program) style refined by `block`'s own words where they show
    /// a style (see the module header); `inch` is the block's unit.
    ///
    /// # Examples
    /// ```
    /// use mtmotion::nc::num_style::NumStyle;
    /// let b = mtmotion::nc::lex("G1 X1.2345 Y2.5\nX1.50 Y2.25").unwrap();
    /// let p = NumStyle::of(&b, false);
    /// assert_eq!(p.format(1.5), "1.5");
    /// let s = p.in_block(&b[1], false);
    /// assert_eq!((s.format(1.5), s.format(1.5014)), ("1.50".into(), "1.501".into()));
    /// ```
    pub fn in_block(&self, block: &Block, inch: bool) -> Self {
        let t = tally(block.words.iter());
        let mut s = *self;
        if let Some(d) = t.fixed() {
            s.decimals = d.max(floor(inch));
            s.min_decimals = d;
        } else if t.fracs.is_empty() && t.ipoint + t.inopoint > 0 {
            // Integers other than zero and no fraction: `X2 Y3`, `X2. Y3.`.
            s.min_decimals = 0;
        }
        if let Some(lead) = vote(t.lead, t.nolead) {
            s.lead_zero = lead;
        }
        if let Some(point) = vote(t.ipoint, t.inopoint) {
            s.int_point = point;
        }
        s
    }

    /// `v` in this style.
    pub fn format(&self, v: f64) -> String {
        let mut s = format!("{v:.*}", self.decimals);
        if s.trim_start_matches('-')
            .chars()
            .all(|c| c == '0' || c == '.')
        {
            s = s.trim_start_matches('-').to_string();
        }
        if let Some(p) = s.find('.') {
            let keep = p + 1 + self.min_decimals.min(self.decimals);
            while s.len() > keep && s.ends_with('0') {
                s.pop();
            }
        }
        if s.ends_with('.') && !self.int_point {
            s.pop();
        }
        if !s.contains('.') && self.int_point {
            s.push('.');
        }
        if !self.lead_zero {
            if let Some(rest) = s.strip_prefix("0.") {
                if !rest.is_empty() && !rest.bytes().all(|c| c == b'0') {
                    s = format!(".{rest}");
                }
            } else if let Some(rest) = s.strip_prefix("-0.") {
                s = format!("-.{rest}");
            }
        }
        s
    }
}

/// Whether two number texts read as the same value (`-.750` and
/// `-0.75`): a replaced number that reads as the original keeps the
/// original's text.
pub fn same_number(a: &str, b: &str) -> bool {
    matches!((a.parse::<f64>(), b.parse::<f64>()), (Ok(x), Ok(y)) if x == y)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nc::lex;

    fn style(src: &str, inch: bool) -> NumStyle {
        NumStyle::of(&lex(src).unwrap(), inch)
    }

    #[test]
    fn styles_of_real_posts() {
        // Fanuc inch post: leading dot, trailing dot, 4 decimals trimmed.
        let s = style("G20\nG0 X0. Y0.\nG1 X-.75 Y1.2345 Z-.967\nX3.", true);
        assert_eq!(s.format(-0.7512), "-.7512");
        assert_eq!(s.format(-3.0), "-3.");
        assert_eq!(s.format(0.0), "0.");
        // Fixed 3 decimals in an inch program: padded to 3, up to 4.
        let s = style("G20\nG1 X-.750 Y1.250\nX.100", true);
        assert_eq!(
            (s.format(-0.75), s.format(-0.751), s.format(-0.75123)),
            ("-.750".into(), "-.751".into(), "-.7512".into())
        );
        // Fixed 4 decimals in mm with a leading zero.
        let s = style("G1 X0.1000 Y-12.5000", false);
        assert_eq!(s.format(-0.05), "-0.0500");
        assert_eq!(s.format(7.0), "7.0000");
        // One decimal kept (`3.0`), more when needed.
        let s = style("G1 X1.5 Y3.0 Z-0.25", false);
        assert_eq!(
            (s.format(3.0), s.format(2.125)),
            ("3.0".into(), "2.125".into())
        );
        // Zeros without a point, other integers with one (Fanuc).
        let s = style("G0 X0 Y0 Z0\nG1 X10. Y-1.5", false);
        assert_eq!(s.format(11.0), "11.");
        // Integers without a point (LinuxCNC style).
        let s = style("G1 X10 Y20 Z-1.5", false);
        assert_eq!(s.format(10.0), "10");
        assert_eq!(s.format(-0.0004), "0");
    }

    #[test]
    fn a_stray_padded_word_does_not_pad_the_program() {
        // One header word `25.000` against many trimmed ones.
        let s = style("G0 Z25.000\nG1 X1.5 Y2.25\nX1.75 Y2.5\nX1.125", false);
        assert_eq!(s.min_decimals, 0);
        assert_eq!(s.format(2.0), "2.");
        // Two padded against one trimmed: padded.
        let s = style("G1 X1.500 Y2.250\nX1.5", false);
        assert_eq!(s.min_decimals, 3);
    }

    #[test]
    fn a_block_with_its_own_style_keeps_it() {
        let b = lex("G1 X.5 Y2.\nN2 X0.50 Y2.25\nN3 X2 Y3").unwrap();
        let p = NumStyle::of(&b, false);
        let s = p.in_block(&b[1], false);
        assert_eq!(
            (s.format(0.5), s.format(0.501)),
            ("0.50".into(), "0.501".into())
        );
        let s = p.in_block(&b[2], false);
        assert_eq!(s.format(4.0), "4");
        assert_eq!(p.in_block(&lex("G4 P1").unwrap()[0], false), p);
    }

    #[test]
    fn zeros_vote_for_the_point_when_no_other_integer_does() {
        // Only zeros are integers: `0.` outvotes `0`, and the other way.
        let s = style("G0 X0. Y0. Z0.\nG1 X1.5 Y2.25 Z0", false);
        assert!(s.int_point);
        assert_eq!(s.format(3.0), "3.");
        let s = style("G0 X0 Y0 Z0.\nG1 X1.5 Y2.25", false);
        assert!(!s.int_point);
        assert_eq!(s.format(3.0), "3");
        // A tie of the other integers (`10.` and `20`) is no vote, and the
        // zeros do not break it: the point stays (the default).
        let s = style("G1 X10. Y20 Z0\nX0 Y1.5", false);
        assert!(s.int_point);
        // A block's own vote on the leading zero and the point wins; its tie does not.
        let b = lex("G1 X.5 Y.25 Z10.\nX0.5 Y0.25 Z10\nX0.5 Y.25").unwrap();
        let p = NumStyle::of(&b, false);
        // ties in the program: a leading zero (the default) and the point (the default)
        assert_eq!((p.lead_zero, p.int_point), (true, true));
        let s = p.in_block(&b[1], false);
        assert!(s.lead_zero && !s.int_point);
        let s = p.in_block(&b[2], false);
        assert_eq!((s.lead_zero, s.int_point), (p.lead_zero, p.int_point));
    }

    #[test]
    fn a_block_of_integers_trims_but_a_block_with_a_fraction_does_not() {
        // The program keeps 3 decimals (`1.500`, `2.250`).
        let b = lex("G1 X1.500 Y2.250\nX2.000\nN4 X2 Y3\nN5 X1.5 Y2\nG4 P1").unwrap();
        let p = NumStyle::of(&b, false);
        assert_eq!(p.min_decimals, 3);
        // `X2 Y3`: integers and no fraction: no trailing zeros, no point.
        let s = p.in_block(&b[2], false);
        assert_eq!((s.min_decimals, s.format(4.0)), (0, "4".into()));
        // `X1.5 Y2`: a fraction without a trailing zero is no fixed count,
        // and the block is no integer-only block: the program's 3 stay.
        let s = p.in_block(&b[3], false);
        assert_eq!(s.min_decimals, 3);
        assert_eq!(s.format(4.0), "4.000");
        // No coordinate word at all: the program's style.
        assert_eq!(p.in_block(&b[4], false), p);
    }

    #[test]
    fn same_number_reads_values() {
        assert!(same_number("-.750", "-0.75") && same_number("3.", "3") && same_number("+1", "1"));
        assert!(!same_number("-.751", "-.75") && !same_number("x", "x"));
    }
}
