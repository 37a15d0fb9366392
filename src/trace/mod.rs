//! Trace import: delimited text (CSV, TSV, semicolon or whitespace) with a
//! header row, as exported by SERVO GUIDE and ball-bar software, and the
//! layouts of controls and instruments [`read_table`] recognises, one file
//! each: TwinCAT Scope View exports ([`twincat`]), SINUMERIK Operate trace
//! XML ([`sinumerik`] on the strict [`xml`] reader), halsampler and
//! halscope ([`hal`]), and MATLAB v5 `.mat` captures from their bytes
//! ([`mat`], [`read_bytes`]). [`Layout::format`] says which was read.
//! Renishaw ball-bar results files (`.b5r`) are reports, not traces:
//! [`b5r::read`] reads their settings and reported features.
//!
//! [`Table::parse`] reads the header and every numeric row; [`Table::column`]
//! finds a column by name (case-insensitive, any of several aliases) and
//! scales it to core units. Lines starting with `#` or `//` and blank lines
//! are skipped, as are metadata lines *before* the header that contain no
//! delimiter. Every error names its 1-based line and column.

pub mod b5r;
pub mod cells;
pub mod hal;
pub mod mat;
pub mod reader;
pub mod sinumerik;
pub mod twincat;
pub mod units;
pub mod xml;

pub use reader::{read_bytes, read_table, ColumnInfo, ColumnKind, Layout, ReadOptions, TableRead};
pub use units::name_unit;

/// Errors of trace import.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TraceError {
    /// The text has no header line.
    #[error("the trace is empty: expected a header line such as 'time,x,y,c'")]
    Empty,
    /// The first line is already data.
    #[error("line {line}: expected a header line naming the columns (e.g. 'time,x,y,c') before the data")]
    NoHeader {
        /// Line of the first data row.
        line: usize,
    },
    /// A header without data rows.
    #[error("line {line}: header found, but no data rows follow")]
    NoData {
        /// Line of the header.
        line: usize,
    },
    /// A cell is not a number.
    #[error(
        "line {line}, column {column} ('{}'): '{}' is not a number",
        clip_at(name, 40),
        clip(text)
    )]
    BadNumber {
        /// 1-based line.
        line: usize,
        /// 1-based column (field index).
        column: usize,
        /// Header name of the column.
        name: String,
        /// The cell text.
        text: String,
    },
    /// A row has the wrong number of fields.
    #[error("line {line}: {found} fields, expected {expected} as in the header")]
    FieldCount {
        /// 1-based line.
        line: usize,
        /// Fields found.
        found: usize,
        /// Fields in the header.
        expected: usize,
    },
    /// A requested column is not in the header.
    #[error(
        "no column named {} in the header (columns: {})",
        clip_at(wanted, 200),
        clip_at(available, 200)
    )]
    MissingColumn {
        /// The names tried, e.g. "'x' or 'pos_x'".
        wanted: String,
        /// The header names.
        available: String,
    },
    /// The file is not text (an image, a PDF, a spreadsheet, …).
    #[error(
        "this is not a text trace (it looks like {kind}): export the trace as CSV or TSV text"
    )]
    NotText {
        /// What it looks like, e.g. "a PNG image".
        kind: &'static str,
    },
    /// A control character other than tab inside a line.
    #[error("line {line}, column {column}: control character U+{code:04X} is not allowed in a trace; save it as plain text (CSV or TSV)")]
    ControlChar {
        /// 1-based line.
        line: usize,
        /// 1-based column (characters).
        column: usize,
        /// The character's code point.
        code: u32,
    },
    /// No line below the header is a row of numbers.
    #[error("line {line}: no row of numbers found: {}; a trace needs rows of numbers below one header line", clip_at(found, 400))]
    NoRows {
        /// 1-based line of the first row that should have been numbers.
        line: usize,
        /// What that line holds instead.
        found: String,
    },
    /// Decimal commas and decimal points in one file.
    #[error("line {comma_line}: '{}' has a decimal comma but line {point_line} has '{}' with a decimal point; export the trace with one decimal separator", clip(comma), clip(point))]
    MixedDecimal {
        /// 1-based line of the first decimal comma.
        comma_line: usize,
        /// Its cell.
        comma: String,
        /// 1-based line of the first decimal point.
        point_line: usize,
        /// Its cell.
        point: String,
    },
    /// A read option does not fit the file.
    #[error("line {line}: option {field}: {why}")]
    BadOption {
        /// 1-based line it concerns (the header, or the first data row).
        line: usize,
        /// camelCase option name.
        field: &'static str,
        /// What is wrong and what to do.
        why: String,
    },
    /// An XML file is not well formed.
    #[error("line {line}: XML: {why}")]
    BadXml {
        /// 1-based line.
        line: usize,
        /// What is wrong.
        why: String,
    },
    /// A file in a known layout (a control's or instrument's export)
    /// breaks that layout.
    #[error("line {line}: {layout}: {why}")]
    BadLayout {
        /// 1-based line (0: a binary file's byte offset is in `why`).
        line: usize,
        /// The layout, e.g. "SINUMERIK trace XML".
        layout: &'static str,
        /// What was found and what was expected.
        why: String,
    },
    /// A binary trace (a `.mat` file) breaks its format.
    #[error("byte {offset}: {layout}: {why}")]
    BadBinary {
        /// Byte offset in the file (0: the file as a whole).
        offset: usize,
        /// The format, e.g. "MATLAB .mat".
        layout: &'static str,
        /// What was found and what was expected.
        why: String,
    },
    /// A column index is out of range.
    #[error("column {index} does not exist; the header has {count} columns")]
    BadColumnIndex {
        /// 1-based index asked for.
        index: usize,
        /// Number of columns.
        count: usize,
    },
}

/// Splits text into lines as a text editor shows them: a UTF-8
/// byte-order mark at the start is dropped, a line ends at LF, CRLF or CR
/// alone (old Macintosh and some DNC files), and trailing Ctrl-Z
/// characters (U+001A, the DOS end-of-file mark) are dropped.
///
/// # Examples
/// ```
/// use mtmotion::trace::split_lines;
/// assert_eq!(split_lines("\u{feff}a\r\nb\rc\n\u{1a}"), vec!["a", "b", "c"]);
/// assert_eq!(split_lines(""), vec![""]);
/// ```
pub fn split_lines(text: &str) -> Vec<&str> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let text = text.trim_end_matches(['\u{1a}', '\r', '\n']);
    let out = split_line_ends(text);
    if out.is_empty() {
        vec![text]
    } else {
        out
    }
}

/// The lines of `text` as they are, without their line ends (LF, CRLF or
/// CR alone): a last line without an end is a line, an empty text has
/// none. Nothing is dropped: [`split_lines`] is this after dropping the
/// byte-order mark and the trailing line ends and Ctrl-Z characters, and
/// the NC stream (`nc::stream`) splits each run of complete lines with it.
pub(crate) fn split_line_ends(text: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let bytes = text.as_bytes();
    let mut start = 0;
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'\n' => {
                out.push(&text[start..i]);
                start = i + 1;
            }
            b'\r' => {
                out.push(&text[start..i]);
                if bytes.get(i + 1) == Some(&b'\n') {
                    i += 1;
                }
                start = i + 1;
            }
            _ => {}
        }
        i += 1;
    }
    if start < text.len() {
        out.push(&text[start..]);
    }
    out
}

/// A parsed table: header names and numeric columns.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// Header names, trimmed, as written.
    pub names: Vec<String>,
    /// Column-major data: `columns[k][row]`.
    pub columns: Vec<Vec<f64>>,
    /// Source line of each row (1-based), for later error messages.
    pub lines: Vec<usize>,
    /// The delimiter that was detected.
    pub delimiter: char,
}

fn split(line: &str, delim: char) -> Vec<&str> {
    if delim == ' ' {
        line.split_whitespace().collect()
    } else {
        line.split(delim).map(str::trim).collect()
    }
}

fn detect(line: &str) -> Option<char> {
    ['\t', ',', ';']
        .into_iter()
        .find(|d| line.contains(*d))
        .or_else(|| (line.split_whitespace().count() > 1).then_some(' '))
}

/// At most `max` characters of user text for a message (an ellipsis marks
/// the cut). `crate::budget::clip` does the same; it sits beside this
/// module in the layer table, so it cannot be imported here.
pub(crate) fn clip_at(text: &str, max: usize) -> String {
    match text.char_indices().nth(max.saturating_sub(1)) {
        Some((i, _)) if text[i..].chars().nth(1).is_some() => format!("{}…", &text[..i]),
        _ => text.to_string(),
    }
}

/// A number the caller gave, for a message: as written when short, else
/// with 6 significant digits (`1.23457e-300`, never 300 digits).
/// `crate::numeric::compact` does the same; it sits beside this module in
/// the layer table.
pub(crate) fn short_number(x: f64) -> String {
    let plain = format!("{x}");
    if plain.len() <= 12 {
        return plain;
    }
    let s = format!("{x:.5e}");
    match s.split_once('e') {
        Some((m, e)) if m.contains('.') => {
            format!("{}e{e}", m.trim_end_matches('0').trim_end_matches('.'))
        }
        _ => s,
    }
}

/// The first 16 characters of a cell, for a message.
fn clip(text: &str) -> String {
    // 16 characters: enough to recognise a cell, too few to echo a number
    // of 20 digits back.
    match text.char_indices().nth(16) {
        Some((i, _)) => format!("{}…", &text[..i]),
        None => text.to_string(),
    }
}

/// A file in which no row is plain numbers: the tolerant reader's error,
/// or what it found that this strict import does not read, at the first
/// data line.
fn strict_diagnosis(text: &str) -> TraceError {
    match read_table(text, &ReadOptions::default()) {
        Err(e) => e,
        Ok(r) => {
            // The first two notes; the message stays short whatever the file.
            let notes = &r.layout.notes;
            let more = match notes.len() {
                0..=2 => String::new(),
                n => format!("; and {} more", n - 2),
            };
            TraceError::NoRows {
                line: r.layout.first_data_line,
                found: format!(
                    "the rows are not plain numbers ({}{more}); this import reads plain numbers only: re-export with '.' decimals, no quotes, no text columns",
                    notes[..notes.len().min(2)].join("; ")
                ),
            }
        }
    }
}

/// The numbered (1-based) lines of `text` that are not comments or blank,
/// after refusing a binary file and a control character (naming its line
/// and column): the start both readers share.
fn data_lines(text: &str) -> Result<Vec<(usize, &str)>, TraceError> {
    if let Some(kind) = binary_kind(text) {
        return Err(TraceError::NotText { kind });
    }
    let lines: Vec<(usize, &str)> = split_lines(text)
        .into_iter()
        .enumerate()
        .map(|(i, l)| (i + 1, l))
        .collect();
    if let Some(e) = control_char(&lines) {
        return Err(e);
    }
    Ok(lines.into_iter().filter(|(_, l)| !is_comment(l)).collect())
}

fn is_comment(line: &str) -> bool {
    let t = line.trim();
    t.is_empty() || t.starts_with('#') || t.starts_with("//")
}

/// The first control character other than tab in the numbered `lines`, as
/// an error naming its line and 1-based character column.
fn control_char(lines: &[(usize, &str)]) -> Option<TraceError> {
    lines.iter().find_map(|&(n, l)| {
        l.chars()
            .position(|c| c.is_control() && c != '\t')
            .map(|k| TraceError::ControlChar {
                line: n,
                column: k + 1,
                code: l.chars().nth(k).map_or(0, u32::from),
            })
    })
}

/// Index in `lines` (numbered, comments dropped) of the header: the line
/// just before the first all-numeric line; anything above it is metadata.
/// Errors when the first line is data, when no line is, or when there is
/// no line at all.
fn header_index(lines: &[(usize, &str)]) -> Result<usize, TraceError> {
    let numeric = |l: &str| {
        detect(l).is_some_and(|d| split(l, d).iter().all(|f| f.parse::<f64>().is_ok()))
            || l.trim().parse::<f64>().is_ok()
    };
    match lines.iter().position(|(_, l)| numeric(l)) {
        Some(0) => Err(TraceError::NoHeader { line: lines[0].0 }),
        Some(k) => Ok(k - 1),
        None => match lines.last() {
            Some((n, _)) => Err(TraceError::NoData { line: *n }),
            None => Err(TraceError::Empty),
        },
    }
}

/// Reads data row `l` (source line `n`) split at `delimiter` into
/// `columns`, one finite number per header name in `names`; a trailing
/// delimiter's empty extra field is tolerated.
fn read_row(
    n: usize,
    l: &str,
    delimiter: char,
    names: &[String],
    columns: &mut [Vec<f64>],
) -> Result<(), TraceError> {
    let fields = split(l, delimiter);
    let fields = match fields.split_last() {
        Some((last, rest)) if last.is_empty() && rest.len() == names.len() => rest,
        _ => &fields[..],
    };
    if fields.len() != names.len() {
        return Err(TraceError::FieldCount {
            line: n,
            found: fields.len(),
            expected: names.len(),
        });
    }
    for (k, f) in fields.iter().enumerate() {
        let text = f.trim_matches('"');
        let v: f64 = text
            .parse()
            .ok()
            .filter(|v: &f64| v.is_finite())
            .ok_or_else(|| TraceError::BadNumber {
                line: n,
                column: k + 1,
                name: names[k].clone(),
                text: text.to_string(),
            })?;
        columns[k].push(v);
    }
    Ok(())
}

impl Table {
    /// Parses delimited text with a header row.
    ///
    /// # Examples
    /// ```
    /// let t = mtmotion::trace::Table::parse("time\tX\n0\t1.5\n0.001\t1.6\n").unwrap();
    /// assert_eq!(t.column(&["x"], 1.0).unwrap(), vec![1.5, 1.6]);
    /// let e = mtmotion::trace::Table::parse("t,x\n0,1\n1,abc\n").unwrap_err();
    /// assert_eq!(e.to_string(), "line 3, column 2 ('x'): 'abc' is not a number");
    /// ```
    pub fn parse(text: &str) -> Result<Self, TraceError> {
        let lines = data_lines(text)?;
        let h = header_index(&lines).map_err(|e| match e {
            TraceError::NoData { .. } => strict_diagnosis(text),
            e => e,
        })?;
        let (header_line, header) = lines[h];
        let delimiter = detect(lines[h + 1].1)
            .or_else(|| detect(header))
            .unwrap_or(',');
        let names: Vec<String> = split(header, delimiter)
            .into_iter()
            .map(|s| s.trim_matches('"').trim().to_string())
            .collect();
        let mut columns = vec![Vec::new(); names.len()];
        let mut row_lines = Vec::new();
        for (n, l) in lines.into_iter().skip(h + 1) {
            read_row(n, l, delimiter, &names, &mut columns)?;
            row_lines.push(n);
        }
        if row_lines.is_empty() {
            return Err(TraceError::NoData { line: header_line });
        }
        Ok(Self {
            names,
            columns,
            lines: row_lines,
            delimiter,
        })
    }

    /// Number of data rows.
    pub fn rows(&self) -> usize {
        self.lines.len()
    }

    /// Index of the first column whose name matches any alias
    /// (case-insensitive; a unit suffix such as `X [mm]`, `X(mm)` or
    /// `X_mm` is ignored, and spaces or dashes match underscores:
    /// `POS X(um)` is `pos_x`).
    pub fn find(&self, aliases: &[&str]) -> Option<usize> {
        let bare = |s: &str| {
            s.split(['[', '('])
                .next()
                .unwrap_or("")
                .trim()
                .to_ascii_lowercase()
        };
        // "POS X(um)" is pos_x, "X_mm" is x, "TCMD C(%)" is tcmd_c.
        let loose = |s: &str| name_unit(s).0.to_ascii_lowercase().replace([' ', '-'], "_");
        aliases.iter().find_map(|a| {
            let full = a.trim().to_ascii_lowercase();
            self.names
                .iter()
                .position(|n| n.trim().to_ascii_lowercase() == full)
                .or_else(|| self.names.iter().position(|n| bare(n) == bare(a)))
                .or_else(|| self.names.iter().position(|n| loose(n) == loose(a)))
        })
    }

    /// The column matching any alias, multiplied by `scale` (to core units).
    ///
    /// # Errors
    /// [`TraceError::MissingColumn`] naming the aliases and the header.
    pub fn column(&self, aliases: &[&str], scale: f64) -> Result<Vec<f64>, TraceError> {
        let k = self
            .find(aliases)
            .ok_or_else(|| TraceError::MissingColumn {
                wanted: aliases
                    .iter()
                    .map(|a| format!("'{}'", clip_at(a, 40)))
                    .collect::<Vec<_>>()
                    .join(" or "),
                available: self
                    .names
                    .iter()
                    .map(|n| clip_at(n, 40))
                    .collect::<Vec<_>>()
                    .join(", "),
            })?;
        Ok(self.columns[k].iter().map(|v| v * scale).collect())
    }

    /// The column at 1-based `index`, multiplied by `scale`.
    pub fn column_at(&self, index: usize, scale: f64) -> Result<Vec<f64>, TraceError> {
        if index == 0 || index > self.columns.len() {
            return Err(TraceError::BadColumnIndex {
                index,
                count: self.columns.len(),
            });
        }
        Ok(self.columns[index - 1].iter().map(|v| v * scale).collect())
    }
}

/// What a non-text file looks like, from its first characters as the page
/// reads them (a browser decodes bytes as UTF-8, so a byte ≥ 0x80 that is
/// not valid UTF-8 becomes U+FFFD): `None` for text.
///
/// Signatures: PNG `\x89PNG`, JPEG `FF D8 FF`, GIF `GIF8`, PDF `%PDF`,
/// ZIP (xlsx, docx) `PK\x03\x04`, gzip `1F 8B`; otherwise a NUL character,
/// or more than 10 % replacement/control characters in the first 512
/// characters of a text of 32 characters or more, means binary.
///
/// # Examples
/// ```
/// use mtmotion::trace::binary_kind;
/// assert_eq!(binary_kind("\u{fffd}PNG\r\n\u{1a}\n\0\0"), Some("a PNG image"));
/// assert_eq!(binary_kind("time,x\n0,1\n"), None);
/// ```
pub fn binary_kind(text: &str) -> Option<&'static str> {
    binary_kind_of_head(text, || text.contains("JFIF"))
}

/// As [`binary_kind`], from the text's start alone: `head` holds at least
/// its first 512 characters after the leading byte-order marks (or all of
/// it), and `jfif` says whether the whole text contains `JFIF` (asked only
/// when the head starts with three U+FFFD). The NC stream (`nc::stream`)
/// judges a text it has not yet read to its end with it.
pub(crate) fn binary_kind_of_head(head: &str, jfif: impl FnOnce() -> bool) -> Option<&'static str> {
    let t = head.trim_start_matches('\u{feff}');
    let head: String = t.chars().take(8).collect();
    let after_junk = head.trim_start_matches(['\u{fffd}', '\u{89}']);
    let kind = if after_junk.starts_with("PNG") && head.len() > after_junk.len() {
        Some("a PNG image")
    } else if t.starts_with("MATLAB 5.0 MAT-file") {
        Some("a MATLAB .mat file, which is read from its bytes (a Uint8Array), not as text")
    } else if head.starts_with("%PDF") {
        Some("a PDF document")
    } else if head.starts_with("GIF8") {
        Some("a GIF image")
    } else if head.starts_with("PK\u{3}\u{4}") {
        Some("a ZIP archive or an Excel/Office file")
    } else if (head.starts_with("\u{fffd}\u{fffd}\u{fffd}") && jfif())
        || t.starts_with("\u{ff}\u{d8}\u{ff}")
    {
        Some("a JPEG image")
    } else if head.starts_with('\u{1f}') {
        Some("a gzip archive")
    } else {
        None
    };
    if kind.is_some() {
        return kind;
    }
    let sample: Vec<char> = t.chars().take(512).collect();
    let bad = sample
        .iter()
        .filter(|&&c| {
            c == '\u{fffd}' || (c.is_control() && !matches!(c, '\n' | '\r' | '\t' | '\u{c}'))
        })
        .count();
    // the share is judged over 32 characters or more: a short text with
    // one control character ("G0 X\u{7}1") is text with a fault at its
    // column, not a binary file
    (sample.contains(&'\0') || (sample.len() >= 32 && bad * 10 > sample.len()))
        .then_some("a binary file")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_clip_text_and_shorten_numbers() {
        assert_eq!(clip_at("abc", 3), "abc");
        assert_eq!(clip_at("abcd", 3), "ab…");
        assert_eq!(clip_at(&"h".repeat(1_000_000), 40).chars().count(), 40);
        assert_eq!(short_number(0.001), "0.001");
        assert_eq!(short_number(1.234567890123e-300), "1.23457e-300");
        assert_eq!(short_number(5e-324), "4.94066e-324");
        assert_eq!(short_number(1e300), "1e300");
    }

    #[test]
    fn binary_files_are_refused_with_what_they_look_like() {
        // A PNG as a browser's File.text() returns it: 0x89 → U+FFFD.
        let png = "\u{fffd}PNG\r\n\u{1a}\n\0\0\0\rIHDR\0\0\u{1}\0";
        let e = Table::parse(png).unwrap_err().to_string();
        assert!(
            e.starts_with("this is not a text trace (it looks like a PNG image)"),
            "{e}"
        );
        assert!(Table::parse("%PDF-1.7\n%\u{fffd}\u{fffd}\n")
            .unwrap_err()
            .to_string()
            .contains("a PDF document"));
        let junk: String = (0..200)
            .map(|i| if i % 3 == 0 { '\u{fffd}' } else { 'a' })
            .collect();
        assert!(Table::parse(&junk)
            .unwrap_err()
            .to_string()
            .contains("a binary file"));
        // Text with a few non-ASCII characters (µ, °) stays text.
        assert_eq!(binary_kind("Zeit [s];X [µm];C [°]\n0;1;2\n"), None);
        // each signature, and what is not one
        for (text, kind) in [
            ("PNG,x\n1,2\n", None), // a column named PNG
            ("\u{89}PNG\r\n", Some("a PNG image")),
            ("GIF89a\u{1}\u{0}", Some("a GIF image")),
            (
                "PK\u{3}\u{4}\u{14}\u{0}",
                Some("a ZIP archive or an Excel/Office file"),
            ),
            (
                "\u{fffd}\u{fffd}\u{fffd}\u{fffd}\u{0}\u{10}JFIF\u{0}",
                Some("a JPEG image"),
            ),
            ("\u{fffd}\u{fffd}\u{fffd}x,y\n1,2\n", None), // no JFIF: not a JPEG by its head
            ("\u{ff}\u{d8}\u{ff}\u{e0}", Some("a JPEG image")),
            ("\u{1f}\u{fffd}\u{8}\u{0}", Some("a gzip archive")),
            ("t,x\n0,\u{0}1\n", Some("a binary file")), // a NUL, however short
        ] {
            assert_eq!(binary_kind(text), kind, "{text:?}");
        }
        // more than 10 % replacement or control characters in 32 or more
        let share = |bad: usize, c: char| -> String {
            (0..40).map(|i| if i < bad { c } else { 'a' }).collect()
        };
        assert_eq!(binary_kind(&share(4, '\u{fffd}')), None); // 4 of 40: 10 %
        assert_eq!(binary_kind(&share(5, '\u{fffd}')), Some("a binary file"));
        assert_eq!(binary_kind(&share(5, '\u{7}')), Some("a binary file"));
        // line ends, tabs and form feeds are text
        assert_eq!(binary_kind(&share(20, '\u{c}')), None);
        assert_eq!(binary_kind(&share(20, '\t')), None);
        // under 32 characters the share is not judged
        let short: String = "\u{7}".repeat(31);
        assert_eq!(binary_kind(&short), None);
        assert_eq!(binary_kind(&(short + "\u{7}")), Some("a binary file"));
    }

    #[test]
    fn detects_delimiters_and_skips_metadata() {
        let src = "SERVO GUIDE export\n# comment\nTime [ms];X(mm);C\n0;1;2\n1;1.1;2.1;\n";
        let t = Table::parse(src).unwrap();
        assert_eq!(t.delimiter, ';');
        assert_eq!(t.rows(), 2);
        assert_eq!(t.column(&["time"], 1e-3).unwrap(), vec![0.0, 1e-3]);
        assert_eq!(t.column(&["pos_x", "x"], 1.0).unwrap(), vec![1.0, 1.1]);
        assert_eq!(t.lines, vec![4, 5]);
        let w = Table::parse("a b\n1 2\n").unwrap();
        assert_eq!(w.delimiter, ' ');
        // one column: one word per line is no space-delimited table
        let one = Table::parse("x\n1\n2\n").unwrap();
        assert_eq!(
            (one.delimiter, one.columns.as_slice()),
            (',', [vec![1.0, 2.0]].as_slice())
        );
        assert_eq!(detect("x"), None);
        // the delimiter is the data's: a header name may hold another one
        let c = Table::parse("X [mm, ist];Y [mm, ist]\n1;2\n3;4\n").unwrap();
        assert_eq!((c.delimiter, c.names[1].as_str()), (';', "Y [mm, ist]"));
        assert_eq!(detect("x y"), Some(' '));
    }

    #[test]
    fn errors_name_lines_and_columns() {
        assert_eq!(Table::parse("\n# x\n"), Err(TraceError::Empty));
        assert_eq!(Table::parse("a,b\n"), Err(TraceError::NoData { line: 1 }));
        // a one-line file of a control's layout says what that layout lacks
        assert_eq!(
            Table::parse("Sampling period is 1000 ns\n")
                .unwrap_err()
                .to_string(),
            "line 1: halscope log: no sample follows the sampling period"
        );
        assert_eq!(Table::parse("1,2\n"), Err(TraceError::NoHeader { line: 1 }));
        let e = Table::parse("a,b\n1,2\n3\n4,5\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            "line 3: 1 fields, expected 2 as in the header"
        );
        // one trailing delimiter is tolerated, an extra value is not
        assert_eq!(
            Table::parse("a,b\n1,2\n3,4,\n").unwrap().columns[1],
            [2.0, 4.0]
        );
        let e = Table::parse("a,b\n1,2\n1,2,3\n4,5\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            "line 3: 3 fields, expected 2 as in the header"
        );
        let e = Table::parse("a,b\n1,2\n1,\n4,5\n").unwrap_err();
        assert_eq!(e.to_string(), "line 3, column 2 ('b'): '' is not a number");
        let e = Table::parse("a,b\n1,nan\n2,3\n").unwrap_err();
        assert!(matches!(
            e,
            TraceError::BadNumber {
                line: 2,
                column: 2,
                ..
            }
        ));
        let t = Table::parse("a,b\n1,2\n").unwrap();
        let e = t.column(&["x", "pos_x"], 1.0).unwrap_err().to_string();
        assert!(e.contains("'x' or 'pos_x'") && e.contains("a, b"), "{e}");
        assert!(t.column_at(3, 1.0).is_err() && t.column_at(0, 1.0).is_err());
        // the 1-based column, scaled to core units
        assert_eq!(t.column_at(2, 1e-3).unwrap(), [2e-3]);
        assert_eq!(t.column(&["a"], 4.0).unwrap(), [4.0]);
    }
}
