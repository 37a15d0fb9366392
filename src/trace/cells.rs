//! The cells of a delimited text line: the delimiter a file uses, quoted
//! fields, and numbers written with a decimal comma or with thousands
//! separators.
//!
//! Reading chosen (where a number is ambiguous, it is refused, never
//! guessed):
//! - the delimiter is the one of `tab`, `;`, `,`, runs of spaces that
//!   splits the most of the file's last 50 lines into one and the same
//!   number (≥ 2) of fields; a tie goes to the earlier in that list (so
//!   `0;1,5` is `;` with a decimal comma);
//! - a file delimited by `;`, tab or spaces has decimal commas when one of
//!   its cells is written `1,5` and none `1.5`; with both, it is refused
//!   naming both lines;
//! - a thousands separator is read when the groups after it have three
//!   digits and the number has another separator or more than one group
//!   (`1,234.5`, `1.234,5`, `1,234,567`) — or in a comma-delimited file,
//!   where `"1,234"` can only be a quoted thousands group.
//!
//! # Units
//! None: numbers are returned as written.

/// How a file writes its decimal separator.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Decimal {
    /// `1.5`.
    Point,
    /// `1,5`.
    Comma,
}

/// One field of a line: its text without quotes, and whether it was quoted.
#[derive(Debug, Clone, PartialEq)]
pub struct Cell {
    /// The text, trimmed, without its quotes.
    pub text: String,
    /// It was written in double quotes.
    pub quoted: bool,
}

/// Splits `line` at `delim` (`' '`: runs of whitespace), keeping a
/// delimiter inside double quotes in its field (`""` is a quote); a
/// trailing delimiter's empty last field is dropped.
pub fn split_cells(line: &str, delim: char) -> Vec<Cell> {
    let mut out = Vec::new();
    let mut text = String::new();
    let (mut quoted, mut inside) = (false, false);
    let mut chars = line.chars().peekable();
    let push = |out: &mut Vec<Cell>, text: &mut String, quoted: &mut bool| {
        out.push(Cell {
            text: std::mem::take(text).trim().to_string(),
            quoted: std::mem::take(quoted),
        });
    };
    while let Some(c) = chars.next() {
        if c == '"' {
            if inside && chars.peek() == Some(&'"') {
                text.push('"');
                chars.next();
            } else {
                inside = !inside;
                quoted = true;
            }
        } else if !inside && (c == delim || (delim == ' ' && c.is_whitespace())) {
            if delim != ' ' || !text.trim().is_empty() || quoted {
                push(&mut out, &mut text, &mut quoted);
            }
        } else {
            text.push(c);
        }
    }
    if delim != ' ' || !text.trim().is_empty() || quoted {
        push(&mut out, &mut text, &mut quoted);
    }
    if out.len() > 1 && out.last().is_some_and(|c| c.text.is_empty() && !c.quoted) {
        out.pop();
    }
    out
}

/// The delimiter of a file from its (non-comment) `lines`: see the
/// module's reading. `None` when every line is one field.
pub fn sniff(lines: &[&str]) -> Option<char> {
    let tail = &lines[lines.len().saturating_sub(50)..];
    let mut best: Option<(usize, char)> = None;
    for d in ['\t', ';', ',', ' '] {
        let counts: Vec<usize> = tail.iter().map(|l| split_cells(l, d).len()).collect();
        let mode = counts
            .iter()
            .copied()
            .max_by_key(|&m| (counts.iter().filter(|&&c| c == m).count(), m));
        let Some(mode) = mode.filter(|&m| m >= 2) else {
            continue;
        };
        let score = counts.iter().filter(|&&c| c == mode).count();
        if best.is_none_or(|(s, _)| score > s) {
            best = Some((score, d));
        }
    }
    best.map(|(_, d)| d)
}

/// Whether `t` is a number with one decimal separator `sep` and no other
/// (`1,5`, `-0,25e-3`).
fn one_separator(t: &str, sep: char) -> bool {
    let other = if sep == ',' { '.' } else { ',' };
    t.matches(sep).count() == 1
        && !t.contains(other)
        && t.replace(sep, ".").parse::<f64>().is_ok()
        && t.split(sep)
            .nth(1)
            .is_some_and(|f| f.starts_with(|c: char| c.is_ascii_digit()))
}

/// The decimal separator of a file delimited by `delim`, from its data
/// cells (`(line, cells)`): see the module's reading.
///
/// # Errors
/// `(comma line, comma text, point line, point text)` when both are found.
pub fn decimal(
    delim: char,
    rows: &[(usize, Vec<Cell>)],
) -> Result<Decimal, (usize, String, usize, String)> {
    if delim == ',' {
        return Ok(Decimal::Point);
    }
    let first = |sep: char| {
        rows.iter().find_map(|(n, cells)| {
            cells
                .iter()
                .find(|c| one_separator(&c.text, sep))
                .map(|c| (*n, c.text.clone()))
        })
    };
    match (first(','), first('.')) {
        (Some((cl, ct)), Some((pl, pt))) => Err((cl, ct, pl, pt)),
        (Some(_), None) => Ok(Decimal::Comma),
        _ => Ok(Decimal::Point),
    }
}

/// A number read from a cell.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Number {
    /// Written plainly (or with a decimal comma in a decimal-comma file).
    Plain(f64),
    /// Written with thousands separators.
    Grouped(f64),
    /// Not a finite number.
    Not,
}

/// Reads `t` with digit groups split by `group` and an optional fraction
/// after `point`, when the grouping is unambiguous (see the module's
/// reading); `lone` allows a single group with no fraction.
fn grouped(t: &str, group: char, point: char, lone: bool) -> Option<f64> {
    let (sign, body) = match t.strip_prefix(['-', '+']) {
        Some(b) => (&t[..1], b),
        None => ("", t),
    };
    let (int, frac) = match body.split_once(point) {
        Some((i, f)) if !f.is_empty() && f.chars().all(|c| c.is_ascii_digit()) => (i, Some(f)),
        Some(_) => return None,
        None => (body, None),
    };
    let groups: Vec<&str> = int.split(group).collect();
    let digits = |g: &str| g.chars().all(|c| c.is_ascii_digit());
    let ok = groups.len() >= 2
        && (1..=3).contains(&groups[0].len())
        && groups.iter().all(|g| digits(g))
        && groups[1..].iter().all(|g| g.len() == 3)
        && (frac.is_some() || groups.len() > 2 || lone);
    if !ok {
        return None;
    }
    format!("{sign}{}.{}", groups.concat(), frac.unwrap_or("0"))
        .parse()
        .ok()
}

/// Reads a cell as a number of a file with the decimal separator `dec`
/// delimited by `delim`.
///
/// # Examples
/// ```
/// use mtmotion::trace::cells::{number, Decimal, Number};
/// assert_eq!(number("1,5", Decimal::Comma, ';'), Number::Plain(1.5));
/// assert_eq!(number("1.234,5", Decimal::Comma, ';'), Number::Grouped(1234.5));
/// assert_eq!(number("1,234", Decimal::Point, ','), Number::Grouped(1234.0));
/// assert_eq!(number("1,234", Decimal::Point, ';'), Number::Not);
/// assert_eq!(number("inf", Decimal::Point, ','), Number::Not);
/// ```
pub fn number(t: &str, dec: Decimal, delim: char) -> Number {
    let finite = |v: f64| v.is_finite().then_some(v);
    let plain = match dec {
        Decimal::Point => t.parse().ok(),
        Decimal::Comma if !t.contains('.') && t.matches(',').count() <= 1 => {
            t.replace(',', ".").parse().ok()
        }
        Decimal::Comma => None,
    };
    if let Some(v) = plain {
        return finite(v).map_or(Number::Not, Number::Plain);
    }
    let g = match dec {
        Decimal::Point => grouped(t, ',', '.', delim == ','),
        Decimal::Comma => grouped(t, '.', ',', false),
    };
    g.and_then(finite).map_or(Number::Not, Number::Grouped)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn texts(line: &str, d: char) -> Vec<String> {
        split_cells(line, d).into_iter().map(|c| c.text).collect()
    }

    #[test]
    fn cells_keep_quoted_delimiters_and_drop_a_trailing_one() {
        assert_eq!(
            texts(r#""1,5", 2 ,"a ""b""""#, ','),
            ["1,5", "2", r#"a "b""#]
        );
        assert_eq!(texts("0;1;", ';'), ["0", "1"]);
        assert_eq!(texts(";", ';'), [""]);
        assert_eq!(texts("  0   1\t2 ", ' '), ["0", "1", "2"]);
        assert_eq!(texts("0,,2", ','), ["0", "", "2"]);
        let c = split_cells(r#""1.5",2"#, ',');
        assert!(c[0].quoted && !c[1].quoted);
        assert_eq!(split_cells(r#"1 "" 2"#, ' ').len(), 3);
        // an empty line is one empty field (its own delimiter is not a
        // trailing one); blanks split at spaces are no field at all
        assert_eq!(texts("", ','), [""]);
        assert_eq!(texts("", '\t'), [""]);
        assert!(split_cells(" \t  ", ' ').is_empty());
    }

    #[test]
    fn the_delimiter_is_the_one_that_splits_the_tail_evenly() {
        assert_eq!(sniff(&["t;x;y", "0;1,5;2,25", "1;1,5;2"]), Some(';'));
        assert_eq!(sniff(&["Machine: A, B", "t,x", "0,1", "1,2"]), Some(','));
        assert_eq!(sniff(&["t\tx y", "0\t1", "1\t2"]), Some('\t'));
        assert_eq!(sniff(&["t x", "0  1", "1 2"]), Some(' '));
        assert_eq!(sniff(&["t", "0", "1"]), None);
        // a comma-delimited file with spaces after its commas
        assert_eq!(sniff(&["a, b, c", "1, 2, 3", "4, 5, 6"]), Some(','));
        // the mode counts, not the largest count
        assert_eq!(sniff(&["a,b,c,d", "1,2", "3,4", "5,6"]), Some(','));
    }

    #[test]
    fn decimal_commas_are_found_and_mixed_separators_refused() {
        let rows = |cells: &[&[&str]]| -> Vec<(usize, Vec<Cell>)> {
            cells
                .iter()
                .enumerate()
                .map(|(i, r)| {
                    (
                        i + 4,
                        r.iter()
                            .map(|t| Cell {
                                text: t.to_string(),
                                quoted: false,
                            })
                            .collect(),
                    )
                })
                .collect()
        };
        assert_eq!(decimal(';', &rows(&[&["0", "1,5"]])), Ok(Decimal::Comma));
        assert_eq!(decimal(',', &rows(&[&["0", "1,5"]])), Ok(Decimal::Point));
        assert_eq!(decimal('\t', &rows(&[&["0", "1"]])), Ok(Decimal::Point));
        assert_eq!(decimal(' ', &rows(&[&["a,b", "1.5"]])), Ok(Decimal::Point));
        assert_eq!(
            decimal(';', &rows(&[&["0", "1"], &["1,5", "2"], &["0.5", "1,25"]])),
            Err((5, "1,5".to_string(), 6, "0.5".to_string()))
        );
        assert!(one_separator("-0,25e-3", ','));
        assert!(!one_separator("1,", ','));
        assert!(!one_separator("1,5,5", ','));
        assert!(!one_separator("1.234,5", ','));
    }

    #[test]
    fn numbers_with_separators_are_read_only_when_unambiguous() {
        use Number::*;
        for (t, dec, delim, want) in [
            ("1.5", Decimal::Point, ',', Plain(1.5)),
            ("-1,5e3", Decimal::Comma, ';', Plain(-1500.0)),
            ("1,234.5", Decimal::Point, ';', Grouped(1234.5)),
            ("+1,234,567", Decimal::Point, '\t', Grouped(1234567.0)),
            ("1,234", Decimal::Point, ',', Grouped(1234.0)),
            ("1,234", Decimal::Point, '\t', Not),
            ("1.234.567,25", Decimal::Comma, ';', Grouped(1234567.25)),
            ("1.234", Decimal::Comma, ';', Not),
            ("1,23,4", Decimal::Point, ',', Not),
            ("1234,567.5", Decimal::Point, ',', Not),
            ("1,234.", Decimal::Point, ',', Not),
            ("1,2a4.5", Decimal::Point, ',', Not),
            ("1.2,3", Decimal::Comma, ';', Not),
            ("nan", Decimal::Point, ',', Not),
            ("1e999", Decimal::Point, ',', Not),
            ("", Decimal::Comma, ';', Not),
        ] {
            assert_eq!(number(t, dec, delim), want, "{t}");
        }
    }
}
