//! The tolerant table reader: every delimited-text trace a user has, read
//! into numeric columns with a preview of how each column was read.
//!
//! [`read_table`] sniffs the delimiter and decimal separator
//! ([`super::cells`]), keeps the lines above the header as key/value
//! metadata, reads numeric columns and ignores text or status columns
//! (listing them), reads a headerless file (columns `column 1` …, with a
//! time column generated from [`ReadOptions::sample_period`]), and reads
//! the unit each header states ([`super::units`]) with its factor to core
//! units. The [`Layout`] says what was found, in words, for the page to
//! show; every refusal names its cause and the first offending line.
//!
//! Reading chosen: the data start at the first row of numbers (at least
//! half its fields numbers) that is not followed by a line of names and a
//! row, so a key/value preamble line such as `Rate;1000` above the header
//! is not taken for data; the header is the line just above it when it has as
//! many fields. A column is numeric when its cell in the first data row is
//! a number, text otherwise.
//!
//! # Units
//! Values are kept as written; [`ColumnInfo::factor`] is the factor to
//! s, mm, rad or N·m. A generated time column is in s.

use serde::{Deserialize, Serialize};

use super::cells::{decimal, number, sniff, split_cells, Cell, Decimal, Number};
use super::units::{name_unit, unit, Quantity, Unit, UNITS};
use super::{data_lines, Table, TraceError};

/// Options of [`read_table`] (the JS `TraceReadOptions`).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", default)]
pub struct ReadOptions {
    /// Sample period of a file without a time column, s: a `time` column
    /// `0, dt, 2·dt, …` is generated.
    pub sample_period: Option<f64>,
    /// Rated torque, N·m: converts a torque column in `%`.
    pub rated_torque: Option<f64>,
}

/// How a column was read.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "camelCase")]
pub enum ColumnKind {
    /// Numbers, in [`TableRead::table`] (JS `'numeric'`).
    #[serde(rename = "numeric")]
    Number,
    /// Text or status: ignored.
    Text,
    /// Generated (the time from the sample period).
    Generated,
}

/// What one column was read as (the layout preview).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct ColumnInfo {
    /// The name as written (`column k` without a header).
    pub name: String,
    /// The name without its unit.
    pub bare: String,
    /// 1-based field in the file; 0 for a generated column.
    pub field: usize,
    /// How it was read.
    pub kind: ColumnKind,
    /// The unit the header states (`ms`, `um`, `deg`, `n·m`, `%`).
    pub unit: Option<&'static str>,
    /// What that unit measures.
    pub quantity: Option<Quantity>,
    /// Core units per unit written; `None` without a unit, or for `%`
    /// without the rated torque.
    pub factor: Option<f64>,
    /// The core unit the factor converts to (s, mm, rad, N·m).
    pub core_unit: Option<&'static str>,
    /// What was done with it, in words, when not plain.
    pub note: Option<String>,
    /// What an import reads it as when its mapping leaves that out
    /// (`time`, `x`, `y`, `c`, `torque`; `angle`, `deviation`,
    /// `direction`), filled by that import's `roles`; `None` here.
    pub role: Option<&'static str>,
}

/// One metadata line above the header.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Meta {
    /// 1-based line.
    pub line: usize,
    /// The key (first field, or the text before `:` or `=`).
    pub key: String,
    /// The rest.
    pub value: String,
}

/// How a file was read.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct Layout {
    /// Which layout was read: `delimited` (a table with or without a
    /// header), `halsampler`, `halscope`, `twincatScope`, `sinumerikTrace`
    /// or `matV5`.
    pub format: &'static str,
    /// `tab`, `;`, `,`, `spaces` or `none` (one column, or not a table).
    pub delimiter: &'static str,
    /// Decimal commas were read.
    pub decimal_comma: bool,
    /// 1-based line of the header (`None`: headerless).
    pub header_line: Option<usize>,
    /// 1-based line of the first data row.
    pub first_data_line: usize,
    /// Data rows read.
    pub rows: usize,
    /// Every column, in file order, then a generated one.
    pub columns: Vec<ColumnInfo>,
    /// The lines above the header, as key/value pairs.
    pub metadata: Vec<Meta>,
    /// What was found and done, in words.
    pub notes: Vec<String>,
    /// Every unit a header may state, with its factor (for unit menus).
    pub units: &'static [Unit],
}

/// A table read by [`read_table`]: the numeric columns and the layout.
#[derive(Debug, Clone, PartialEq)]
pub struct TableRead {
    /// The numeric (and generated) columns, values as written.
    pub table: Table,
    /// How the file was read.
    pub layout: Layout,
}

impl TableRead {
    /// The layout of the table's column `k` (0-based, as in `table`).
    pub fn info(&self, k: usize) -> Option<&ColumnInfo> {
        self.layout
            .columns
            .iter()
            .filter(|c| c.kind != ColumnKind::Text)
            .nth(k)
    }

    /// Marks the column each role's names find (`(role, names)`, the
    /// first found) with that role, for the layout preview: what an
    /// import reads each column as when its mapping leaves it out.
    pub fn mark_roles(&mut self, roles: &[(&'static str, &[&str])]) {
        for &(role, names) in roles {
            if let Some(k) = self.table.find(names) {
                if let Some(c) = self
                    .layout
                    .columns
                    .iter_mut()
                    .filter(|c| c.kind != ColumnKind::Text)
                    .nth(k)
                {
                    c.role.get_or_insert(role);
                }
            }
        }
    }
}

/// Whether `cells` is a row of numbers: `n` fields, at least half numbers.
fn is_row(cells: &[Cell], n: usize, dec: Decimal, delim: char) -> bool {
    let numbers = cells
        .iter()
        .filter(|c| number(&c.text, dec, delim) != Number::Not)
        .count();
    cells.len() == n && numbers >= 1 && 2 * numbers >= n
}

/// Index of the first data row: the first row of numbers that is not a
/// preamble line above a header (a line of names followed by a row).
fn data_start(rows: &[(usize, Vec<Cell>)], n: usize, dec: Decimal, delim: char) -> Option<usize> {
    let row = |i: usize| rows.get(i).is_some_and(|r| is_row(&r.1, n, dec, delim));
    let names = |i: usize| {
        rows.get(i).is_some_and(|r| {
            r.1.len() == n
                && r.1
                    .iter()
                    .all(|c| !c.text.is_empty() && number(&c.text, dec, delim) == Number::Not)
        })
    };
    (0..rows.len()).find(|&i| row(i) && !(names(i + 1) && row(i + 2)))
}

/// The error for a file with no row of numbers: at the first line below
/// the first, saying what it holds.
fn no_rows(rows: &[(usize, Vec<Cell>)], n: usize) -> TraceError {
    let Some((line, cells)) = rows.get(1) else {
        return TraceError::NoData { line: rows[0].0 };
    };
    let found = if cells.len() != n {
        format!("{} fields where most lines have {n}", cells.len())
    } else {
        let words: Vec<String> = cells
            .iter()
            .enumerate()
            .take(3)
            .map(|(k, c)| format!("'{}' (field {})", super::clip(&c.text), k + 1))
            .collect();
        format!("{} are not numbers", words.join(", "))
    };
    TraceError::NoRows { line: *line, found }
}

fn delimiter_name(d: Option<char>) -> &'static str {
    match d {
        Some('\t') => "tab",
        Some(';') => ";",
        Some(',') => ",",
        Some(_) => "spaces",
        None => "none",
    }
}

/// The key/value pair of a metadata line.
fn meta(line: usize, text: &str, cells: &[Cell]) -> Meta {
    let filled: Vec<&str> = cells
        .iter()
        .map(|c| c.text.as_str())
        .filter(|t| !t.is_empty())
        .collect();
    let (key, value) = match filled.split_first() {
        Some((k, rest)) if !rest.is_empty() => (k.to_string(), rest.join(" ")),
        _ => match text.split_once([':', '=']) {
            Some((k, v)) => (k.trim().to_string(), v.trim().to_string()),
            None => (text.trim().to_string(), String::new()),
        },
    };
    Meta { line, key, value }
}

/// The layout of a header (or headerless) column: its unit and factor.
fn column_info(name: String, field: usize, opts: &ReadOptions) -> ColumnInfo {
    let (bare, code) = name_unit(&name);
    let u = code.and_then(unit);
    let (factor, core_unit, note) = match u {
        Some(u) if u.quantity == Quantity::Percent => match opts.rated_torque {
            Some(r) => (
                Some(u.factor * r),
                Some("N·m"),
                Some(format!(
                    "% of the rated torque {} N·m",
                    super::short_number(r)
                )),
            ),
            None => (
                None,
                None,
                Some("% of the rated torque: give the rated torque (N·m) to convert it".into()),
            ),
        },
        Some(u) => (Some(u.factor), Some(u.quantity.core_unit()), None),
        None => (None, None, None),
    };
    ColumnInfo {
        name,
        bare,
        field,
        kind: ColumnKind::Number,
        unit: code,
        quantity: u.map(|u| {
            if u.quantity == Quantity::Percent && opts.rated_torque.is_some() {
                Quantity::Torque
            } else {
                u.quantity
            }
        }),
        factor,
        core_unit,
        note,
        role: None,
    }
}

/// Largest sample period, s (about 3 hours between samples).
pub const MAX_SAMPLE_PERIOD: f64 = 1e4;

/// Checks the options against the file (`line`: where they apply).
fn check_options(opts: &ReadOptions, line: usize) -> Result<(), TraceError> {
    if let Some(dt) = opts.sample_period {
        if !(dt.is_finite() && dt > 0.0 && dt <= MAX_SAMPLE_PERIOD) {
            return Err(TraceError::BadOption {
                line,
                field: "samplePeriod",
                why: format!("{} s is not a sample period; give the time between samples in s (> 0, at most 1e4 s; 0.001 for 1 ms)", super::short_number(dt)),
            });
        }
    }
    if let Some(r) = opts.rated_torque {
        if !(r.is_finite() && r > 0.0 && r <= 1e7) {
            return Err(TraceError::BadOption {
                line,
                field: "ratedTorque",
                why: format!(
                    "{} N·m is not a rated torque; give the motor's rated torque in N·m (> 0)",
                    super::short_number(r)
                ),
            });
        }
    }
    Ok(())
}

/// Reads a delimited-text trace tolerantly (see the module's reading).
///
/// # Units
/// Values as written; the layout states each column's unit and factor.
///
/// # Errors
/// [`TraceError`], naming the first offending line and its cause.
///
/// # Examples
/// ```
/// use mtmotion::trace::{read_table, ReadOptions};
/// let text = "Machine;NMV5000\nZeit [ms];X [mm];Status\n0;1,5;ok\n1;1,25;ok\n";
/// let r = read_table(text, &ReadOptions::default()).unwrap();
/// assert_eq!(r.table.names, ["Zeit [ms]", "X [mm]"]);
/// assert_eq!(r.table.columns[1], [1.5, 1.25]);
/// assert_eq!(r.layout.columns[0].factor, Some(1e-3));
/// assert_eq!(r.layout.metadata[0].value, "NMV5000");
/// assert!(r.layout.notes.iter().any(|n| n.contains("'Status' (field 3) is text")));
/// let e = read_table("t;x\n0;1,5\n1;oops\n", &ReadOptions::default()).unwrap_err();
/// assert_eq!(e.to_string(), "line 3, column 2 ('x'): 'oops' is not a number");
/// ```
pub fn read_table(text: &str, opts: &ReadOptions) -> Result<TableRead, TraceError> {
    let lines = data_lines(text)?;
    let Some(&(first, first_text)) = lines.first() else {
        return Err(TraceError::Empty);
    };
    if first_text.trim_start().starts_with('<') {
        return super::sinumerik::read(text, first, opts);
    }
    if super::twincat::is_twincat(&lines) {
        return super::twincat::read(&lines, opts);
    }
    if super::hal::is_halscope(first_text) {
        return super::hal::read_halscope(&lines, opts);
    }
    let read = read_delimited(&lines, opts)?;
    super::hal::halsampler_index(read, opts)
}

/// Reads a trace from its bytes: a MATLAB v5 `.mat` capture
/// ([`super::mat`]), or text (UTF-8) read by [`read_table`].
///
/// # Errors
/// As [`read_table`]; [`TraceError::BadBinary`] for a `.mat` file.
///
/// # Examples
/// ```
/// use mtmotion::trace::{read_bytes, ReadOptions};
/// let r = read_bytes(b"t;x\n0;1,5\n1;2\n", &ReadOptions::default()).unwrap();
/// assert_eq!(r.table.columns[1], [1.5, 2.0]);
/// let e = read_bytes(b"MATLAB 5.0 MAT-file", &ReadOptions::default()).unwrap_err();
/// assert_eq!(e.to_string(), "byte 19: MATLAB .mat: the 128-byte header is cut short at 19 bytes");
/// ```
pub fn read_bytes(bytes: &[u8], opts: &ReadOptions) -> Result<TableRead, TraceError> {
    if super::mat::is_mat(bytes) {
        return super::mat::read(bytes, opts);
    }
    read_table(&String::from_utf8_lossy(bytes), opts)
}

/// [`read_table`] for a delimited table (the numbered, non-comment
/// `lines`): see the module's reading.
fn read_delimited(lines: &[(usize, &str)], opts: &ReadOptions) -> Result<TableRead, TraceError> {
    let texts: Vec<&str> = lines.iter().map(|(_, l)| *l).collect();
    let sniffed = sniff(&texts);
    let delim = sniffed.unwrap_or(',');
    let rows: Vec<(usize, Vec<Cell>)> = lines
        .iter()
        .map(|&(n, l)| (n, split_cells(l, delim)))
        .collect();
    let n = match sniffed {
        Some(_) => {
            let counts: Vec<usize> = rows.iter().rev().take(50).map(|r| r.1.len()).collect();
            counts
                .iter()
                .copied()
                .max_by_key(|&m| (counts.iter().filter(|&&c| c == m).count(), m))
                .unwrap_or(1)
        }
        None => 1,
    };
    let dec = decimal(delim, &rows).map_err(|(comma_line, comma, point_line, point)| {
        TraceError::MixedDecimal {
            comma_line,
            comma,
            point_line,
            point,
        }
    })?;
    let start = data_start(&rows, n, dec, delim).ok_or_else(|| no_rows(&rows, n))?;
    let header = start.checked_sub(1).filter(|&h| rows[h].1.len() == n);
    let mut notes = Vec::new();
    let meta_end = header.unwrap_or(start);
    let metadata: Vec<Meta> = (0..meta_end)
        .map(|i| meta(rows[i].0, lines[i].1, &rows[i].1))
        .collect();
    if let (Some(a), Some(b)) = (metadata.first(), metadata.last()) {
        notes.push(format!(
            "lines {}–{} above the header kept as metadata ({} key/value pairs)",
            a.line,
            b.line,
            metadata.len()
        ));
    }
    let names: Vec<String> = match header {
        Some(h) => rows[h]
            .1
            .iter()
            .enumerate()
            .map(|(k, c)| match c.text.is_empty() {
                true => format!("column {}", k + 1),
                false => c.text.clone(),
            })
            .collect(),
        None => {
            notes.push(format!(
                "no header line: the columns are named 'column 1' to 'column {n}'"
            ));
            (1..=n).map(|k| format!("column {k}")).collect()
        }
    };
    let mut infos: Vec<ColumnInfo> = names
        .iter()
        .enumerate()
        .map(|(k, name)| column_info(name.clone(), k + 1, opts))
        .collect();
    let (first_line, first_cells) = &rows[start];
    check_options(opts, header.map_or(*first_line, |h| rows[h].0))?;
    for (k, info) in infos.iter_mut().enumerate() {
        let cell = &first_cells[k].text;
        if number(cell, dec, delim) == Number::Not {
            info.kind = ColumnKind::Text;
            info.note = Some("text: ignored".into());
            notes.push(format!(
                "column '{}' (field {}) is text ('{}' on line {first_line}): ignored",
                info.name,
                k + 1,
                super::clip(cell)
            ));
        }
    }
    let numeric: Vec<usize> = (0..n)
        .filter(|&k| infos[k].kind == ColumnKind::Number)
        .collect();
    let mut columns = vec![Vec::new(); numeric.len()];
    let mut row_lines = Vec::new();
    let (mut quoted, mut grouped) = (None, None);
    for (line, cells) in &rows[start..] {
        if cells.len() != n {
            return Err(TraceError::FieldCount {
                line: *line,
                found: cells.len(),
                expected: n,
            });
        }
        for (j, &k) in numeric.iter().enumerate() {
            let c = &cells[k];
            let v = match number(&c.text, dec, delim) {
                Number::Plain(v) => v,
                Number::Grouped(v) => {
                    grouped.get_or_insert((*line, c.text.clone(), v));
                    v
                }
                Number::Not => {
                    return Err(TraceError::BadNumber {
                        line: *line,
                        column: k + 1,
                        name: names[k].clone(),
                        text: c.text.clone(),
                    })
                }
            };
            if c.quoted {
                quoted.get_or_insert((*line, c.text.clone()));
            }
            columns[j].push(v);
        }
        row_lines.push(*line);
    }
    if dec == Decimal::Comma {
        let at = rows[start..].iter().find_map(|(l, cs)| {
            cs.iter()
                .find(|c| c.text.contains(','))
                .map(|c| (*l, c.text.clone()))
        });
        if let Some((l, t)) = at {
            notes.push(format!(
                "decimal commas with '{}' found (line {l}: '{t}'): read as such",
                delimiter_name(sniffed)
            ));
        }
    }
    if let Some((l, t)) = quoted {
        notes.push(format!(
            "quoted numbers (line {l}: \"{t}\"): read as numbers"
        ));
    }
    if let Some((l, t, v)) = grouped {
        notes.push(format!(
            "thousands separators (line {l}: '{t}'): read as {v}"
        ));
    }
    let mut table_names: Vec<String> = numeric.iter().map(|&k| names[k].clone()).collect();
    if let Some(dt) = opts.sample_period {
        if let Some(t) = infos.iter().find(|c| {
            c.kind == ColumnKind::Number
                && (c.quantity == Some(Quantity::Time)
                    || ["time", "t", "zeit"].contains(&c.bare.to_ascii_lowercase().as_str()))
        }) {
            return Err(TraceError::BadOption {
                line: header.map_or(*first_line, |h| rows[h].0),
                field: "samplePeriod",
                why: format!(
                    "the file has its own time column '{}' (field {}); leave samplePeriod out, or map the time column",
                    super::clip_at(&t.name, 40),
                    t.field
                ),
            });
        }
        columns.push((0..row_lines.len()).map(|i| i as f64 * dt).collect());
        table_names.push("time".into());
        let mut t = column_info("time".into(), 0, opts);
        t.kind = ColumnKind::Generated;
        (t.unit, t.quantity, t.factor, t.core_unit) =
            (Some("s"), Some(Quantity::Time), Some(1.0), Some("s"));
        t.note = Some(format!(
            "generated: one sample every {} s",
            super::short_number(dt)
        ));
        notes.push(format!(
            "time generated from samplePeriod = {} s",
            super::short_number(dt)
        ));
        infos.push(t);
    }
    let layout = Layout {
        format: "delimited",
        delimiter: delimiter_name(sniffed),
        decimal_comma: dec == Decimal::Comma,
        header_line: header.map(|h| rows[h].0),
        first_data_line: *first_line,
        rows: row_lines.len(),
        columns: infos,
        metadata,
        notes,
        units: &UNITS,
    };
    Ok(TableRead {
        table: Table {
            names: table_names,
            columns,
            lines: row_lines,
            delimiter: delim,
        },
        layout,
    })
}

/// A table of named numeric channels read from a control's or
/// instrument's own layout (not a delimited table): each name's unit is
/// read as in a header (`time [s]`), the values are kept as given.
///
/// `columns[k][row]` holds channel `names[k]`; `lines[row]` is the source
/// line of each row (0 for a binary file).
#[allow(clippy::too_many_arguments)]
pub fn channel_table(
    format: &'static str,
    delimiter: &'static str,
    names: Vec<String>,
    columns: Vec<Vec<f64>>,
    lines: Vec<usize>,
    metadata: Vec<Meta>,
    notes: Vec<String>,
    opts: &ReadOptions,
) -> TableRead {
    let infos = names
        .iter()
        .enumerate()
        .map(|(k, n)| column_info(n.clone(), k + 1, opts))
        .collect();
    let layout = Layout {
        format,
        delimiter,
        decimal_comma: false,
        header_line: None,
        first_data_line: lines.first().copied().unwrap_or(0),
        rows: lines.len(),
        columns: infos,
        metadata,
        notes,
        units: &UNITS,
    };
    TableRead {
        table: Table {
            names,
            columns,
            lines,
            delimiter: ',',
        },
        layout,
    }
}
