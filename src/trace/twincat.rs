//! Beckhoff TwinCAT Scope View text export (`.csv`/`.txt`, "Export →
//! CSV"), in its tab and comma dialects (any one-character separator the
//! export offers is read the same way).
//!
//! Layout read (Beckhoff's Scope View export as its files show; the
//! open-source pytcs reader documents the same): a block of the scope's
//! own lines (`Name`, `File`, `Starttime of export`, `Endtime of
//! export` …), then one row per channel property, each written as
//! `key<sep>value` per channel (`Name`, `SymbolComment`, `Data-Type`,
//! `SampleTime[ms]`, `VariableSize`, …, `ScaleFactor`, `Unit`,
//! `Unit ScaleFactor`, `Unit Offset`), then the samples: for each channel
//! a time (ms) and a value. With "exclude double timestamps", channels of
//! one sample time share one time column: the `Name` row then has `Name`
//! once per time column, followed by the names of the channels on it.
//! That one rule reads both: a `Name` cell in the `Name` row is a time
//! column, the cells after it are its channels.
//!
//! Readings chosen:
//! - the time axis is the time column with the most channels (the first
//!   of equals); a channel on another time column that departs from it
//!   (another sample time, or fewer samples) is left out, naming the line
//!   where it departs, never resampled;
//! - values are read as exported: the export has already applied
//!   `ScaleFactor`/`Offset` and the unit scaling, which the channel's note
//!   repeats; a `Unit` the core knows (`mm`, `deg`, `um`, …) becomes the
//!   column's unit, any other is named in the note;
//! - decimal commas are read as in any table ([`super::cells`]).
//!
//! # Units
//! Time in ms (`SampleTime[ms]`), so the time column is `time [ms]`;
//! values in the channel's `Unit`.

use super::cells::{decimal, number, split_cells, Cell, Decimal, Number};
use super::reader::{channel_table, Meta, ReadOptions, TableRead};
use super::units::name_unit;
use super::TraceError;

/// The layout's name in messages.
pub const LAYOUT: &str = "TwinCAT Scope export";

fn bad(line: usize, why: impl Into<String>) -> TraceError {
    TraceError::BadLayout {
        line,
        layout: LAYOUT,
        why: why.into(),
    }
}

/// The separator of a line that starts with `Name`: the character after it.
fn separator(first: &str) -> Option<char> {
    first
        .trim_start_matches('\u{feff}')
        .strip_prefix("Name")
        .and_then(|r| r.chars().next())
        .filter(|c| !c.is_alphanumeric() && *c != '"')
}

fn key(line: &str, sep: char) -> String {
    split_cells(line, sep)
        .into_iter()
        .next()
        .map(|c| c.text)
        .unwrap_or_default()
}

/// Whether the numbered `lines` are a Scope View export: the first starts
/// with `Name` and a separator, and a `SampleTime[ms]` row follows.
pub fn is_twincat(lines: &[(usize, &str)]) -> bool {
    let Some(sep) = lines.first().and_then(|(_, l)| separator(l)) else {
        return false;
    };
    lines
        .iter()
        .take(80)
        .any(|(_, l)| key(l, sep) == "SampleTime[ms]")
}

/// One time column and its channels (0-based fields).
struct Group {
    time: usize,
    channels: Vec<usize>,
}

/// Reads a Scope View export (numbered, non-blank `lines`).
///
/// # Errors
/// [`TraceError::BadLayout`] naming the line for a broken channel block,
/// [`TraceError::BadNumber`] for a sample that is not a number.
///
/// # Examples
/// ```
/// use mtmotion::trace::{read_table, ReadOptions};
/// let text = "Name\tScope\nFile\tC:\\s.svdx\n\nName\tX\tName\tY\nSampleTime[ms]\t1\tSampleTime[ms]\t1\nUnit\tmm\tUnit\t(None)\nUnit ScaleFactor\t1\tUnit ScaleFactor\t1\n\n0\t1,5\t0\t2\n1\t1,25\t1\t3\n";
/// let r = read_table(text, &ReadOptions::default()).unwrap();
/// assert_eq!(r.layout.format, "twincatScope");
/// assert_eq!(r.table.names, ["time [ms]", "X [mm]", "Y"]);
/// assert_eq!(r.table.columns[1], [1.5, 1.25]);
/// assert_eq!(r.layout.first_data_line, 9);
/// ```
pub fn read(lines: &[(usize, &str)], opts: &ReadOptions) -> Result<TableRead, TraceError> {
    let sep = separator(lines[0].1).unwrap_or('\t');
    let sample_row = lines
        .iter()
        .position(|(_, l)| key(l, sep) == "SampleTime[ms]")
        .unwrap_or(0);
    let name_row = (1..sample_row)
        .rev()
        .find(|&i| key(lines[i].1, sep) == "Name")
        .ok_or_else(|| {
            bad(
                lines[sample_row].0,
                "the SampleTime[ms] row has no channel Name row above it",
            )
        })?;
    let cells: Vec<(usize, Vec<Cell>)> = lines
        .iter()
        .map(|&(n, l)| (n, split_cells(l, sep)))
        .collect();
    let numeric_first = |c: &[Cell]| {
        c.first().is_some_and(|c| {
            [Decimal::Point, Decimal::Comma]
                .iter()
                .any(|&d| number(&c.text, d, sep) != Number::Not)
        })
    };
    let data = (name_row..cells.len())
        .find(|&i| numeric_first(&cells[i].1))
        .ok_or_else(|| {
            bad(
                lines[name_row].0,
                format!(
                    "no sample row below the channel block (lines {}–{})",
                    lines[name_row].0,
                    lines[lines.len() - 1].0
                ),
            )
        })?;
    let dec =
        decimal(sep, &cells[data..]).map_err(|(cl, ct, pl, pt)| TraceError::MixedDecimal {
            comma_line: cl,
            comma: ct,
            point_line: pl,
            point: pt,
        })?;
    // groups from the Name row
    let (name_line, name_cells) = &cells[name_row];
    let mut groups: Vec<Group> = Vec::new();
    for (p, c) in name_cells.iter().enumerate() {
        if c.text == "Name" {
            groups.push(Group {
                time: p,
                channels: Vec::new(),
            });
        } else if let Some(g) = groups.last_mut() {
            if c.text.is_empty() {
                return Err(bad(
                    *name_line,
                    format!(
                        "field {} of the Name row is empty: a channel without a name",
                        p + 1
                    ),
                ));
            }
            g.channels.push(p);
        }
    }
    groups.retain(|g| !g.channels.is_empty());
    if groups.is_empty() {
        return Err(bad(*name_line, "the Name row names no channel"));
    }
    // per-channel property: the cell of row `key` at the channel's field
    let prop = |key: &str, p: usize| -> Option<String> {
        cells[name_row..data]
            .iter()
            .find(|(_, c)| c.first().is_some_and(|k| k.text == key))
            .and_then(|(_, c)| c.get(p).map(|c| c.text.clone()))
            .filter(|t| !t.is_empty())
    };
    let cell_number = |r: usize, p: usize| -> Result<Option<f64>, TraceError> {
        let (line, row) = &cells[r];
        match row.get(p).map(|c| c.text.as_str()) {
            None | Some("") => Ok(None),
            Some(t) => match number(t, dec, sep) {
                Number::Plain(v) | Number::Grouped(v) => Ok(Some(v)),
                Number::Not => Err(TraceError::BadNumber {
                    line: *line,
                    column: p + 1,
                    name: name_cells
                        .get(p)
                        .map_or_else(String::new, |c| match c.text.as_str() {
                            "Name" => "time".to_string(),
                            n => n.to_string(),
                        }),
                    text: t.to_string(),
                }),
            },
        }
    };
    let base = groups
        .iter()
        .enumerate()
        .max_by_key(|(i, g)| (g.channels.len(), std::cmp::Reverse(*i)))
        .map_or(0, |(i, _)| i);
    let mut time = Vec::new();
    let mut rows = Vec::new();
    for r in data..cells.len() {
        match cell_number(r, groups[base].time)? {
            Some(t) => {
                time.push(t);
                rows.push(r);
            }
            None => break,
        }
    }
    if let Some(&r) = rows.last() {
        if r + 1 < cells.len() {
            return Err(bad(
                cells[r + 1].0,
                format!(
                    "the time column (field {}) ends here but rows follow",
                    groups[base].time + 1
                ),
            ));
        }
    }
    let mut notes = Vec::new();
    let mut names = vec!["time [ms]".to_string()];
    let mut columns = vec![time.clone()];
    let mut col_notes = vec![None];
    let mut fields: Vec<usize> = Vec::new();
    for (gi, g) in groups.iter().enumerate() {
        if gi != base {
            let mut departs = None;
            for (i, &r) in rows.iter().enumerate() {
                let t = cell_number(r, g.time)?;
                if t != Some(time[i]) {
                    departs = Some((cells[r].0, t));
                    break;
                }
            }
            if let Some((line, t)) = departs {
                let list: Vec<String> = g
                    .channels
                    .iter()
                    .map(|&p| format!("'{}'", name_cells[p].text))
                    .collect();
                notes.push(format!(
                    "channel {} (time in field {}) departs from the time axis on line {line} ({} ms where the axis has {} ms): left out; export the channels with one sample time to read it",
                    list.join(", "),
                    g.time + 1,
                    t.map_or_else(|| "no sample".to_string(), |v| v.to_string()),
                    time[rows.iter().position(|&r| cells[r].0 == line).unwrap_or(0)]
                ));
                continue;
            }
        }
        for &p in &g.channels {
            let channel = name_cells[p].text.clone();
            let unit = prop("Unit", p);
            let written = unit
                .as_deref()
                .and_then(|u| u.split_whitespace().next())
                .unwrap_or("");
            let code = name_unit(&format!("v [{written}]")).1;
            let name = match code {
                Some(_) => format!("{channel} [{written}]"),
                None => channel,
            };
            let mut note = vec![];
            if let Some(s) = prop("SampleTime[ms]", p) {
                note.push(format!("sample time {s} ms"));
            }
            for k in ["ScaleFactor", "Offset", "Unit ScaleFactor", "Unit Offset"] {
                if let Some(s) = prop(k, p) {
                    note.push(format!("{k} {s}"));
                }
            }
            if let Some(last) = note.last_mut() {
                last.push_str(" (applied by the export)");
            }
            if let (Some(u), None) = (&unit, code) {
                if u != "(None)" {
                    note.push(format!("unit '{u}' not read"));
                }
            }
            names.push(name);
            fields.push(p);
            col_notes.push((!note.is_empty()).then(|| note.join(", ")));
        }
    }
    // row by row, so the first offending line is the one named
    columns.resize(names.len(), Vec::with_capacity(rows.len()));
    for &r in &rows {
        for (j, &p) in fields.iter().enumerate() {
            let v = cell_number(r, p)?.ok_or_else(|| {
                bad(
                    cells[r].0,
                    format!(
                        "channel '{}' (field {}) has no sample",
                        name_cells[p].text,
                        p + 1
                    ),
                )
            })?;
            columns[j + 1].push(v);
        }
    }
    let metadata: Vec<Meta> = (0..name_row)
        .map(|i| {
            let c = &cells[i].1;
            Meta {
                line: cells[i].0,
                key: c.first().map(|c| c.text.clone()).unwrap_or_default(),
                value: c[1.min(c.len())..]
                    .iter()
                    .map(|c| c.text.as_str())
                    .filter(|t| !t.is_empty())
                    .collect::<Vec<_>>()
                    .join(" "),
            }
        })
        .collect();
    notes.insert(
        0,
        format!(
            "TwinCAT Scope export: {} channels, channel block on lines {}–{}",
            names.len() - 1,
            cells[name_row].0,
            cells[data - 1].0
        ),
    );
    let delimiter = match sep {
        '\t' => "tab",
        ';' => ";",
        ',' => ",",
        ' ' => "spaces",
        _ => "none",
    };
    let lines = rows.iter().map(|&r| cells[r].0).collect();
    let mut read = channel_table(
        "twincatScope",
        delimiter,
        names,
        columns,
        lines,
        metadata,
        notes,
        opts,
    );
    read.layout.decimal_comma = dec == Decimal::Comma;
    read.layout.header_line = Some(cells[name_row].0);
    for (c, n) in read.layout.columns.iter_mut().zip(col_notes) {
        if c.note.is_none() {
            c.note = n;
        }
    }
    Ok(read)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::trace::read_table;

    fn lines(text: &str) -> Vec<(usize, &str)> {
        text.lines().enumerate().map(|(i, l)| (i + 1, l)).collect()
    }

    #[test]
    fn the_separator_is_the_character_after_name() {
        assert_eq!(separator("Name\tScope"), Some('\t'));
        assert_eq!(separator("\u{feff}Name,Scope"), Some(','));
        // a longer word, or a quote, is no Scope View key
        assert_eq!(separator("Names,x"), None);
        assert_eq!(separator("Name\"x"), None);
        assert_eq!(separator("Name"), None);
        // a first column called 'Name' without a SampleTime[ms] row is a table
        assert!(!is_twincat(&lines("Name\tValue\n1\t2\n")));
        assert!(is_twincat(&lines("Name\tX\nSampleTime[ms]\t1\n0\t1\n")));
        let r = read_table("Name\tValue\n1\t2\n3\t4\n", &ReadOptions::default()).unwrap();
        assert_eq!(r.layout.format, "delimited");
    }

    #[test]
    fn a_bad_sample_names_its_line_column_and_channel() {
        let text = "Name\tS\nName\tX\tName\tY\nSampleTime[ms]\t1\tSampleTime[ms]\t1\n\n0\t1\t0\t2\n1\t1\tq\t3\n2\t1\t2\t3\n";
        let e = read_table(text, &ReadOptions::default()).unwrap_err();
        assert_eq!(
            e.to_string(),
            "line 6, column 3 ('time'): 'q' is not a number"
        );
        let text = text
            .replace("\tq\t", "\t1\t")
            .replace("1\t1\t1\t3", "1\tz\t1\t3");
        let e = read_table(&text, &ReadOptions::default()).unwrap_err();
        assert_eq!(e.to_string(), "line 6, column 2 ('X'): 'z' is not a number");
    }

    #[test]
    fn a_channel_of_another_sample_time_is_left_out_naming_its_line() {
        // X and Z on the 1 ms axis, Y on a 2 ms axis: Y departs on line 7
        let text = "Name\tS\nName\tX\tZ\tName\tY\nSampleTime[ms]\t1\t1\tSampleTime[ms]\t2\nUnit\tV (Volt)\t(None)\tUnit\tmm\n\n0\t1\t5\t0\t2\n1\t1.5\t6\t2\t3\n2\t2\t7\t4\t4\n";
        let r = read_table(text, &ReadOptions::default()).unwrap();
        assert_eq!(r.table.names, ["time [ms]", "X", "Z"]);
        assert_eq!(r.table.columns[1], [1.0, 1.5, 2.0]);
        assert_eq!(r.table.columns[2], [5.0, 6.0, 7.0]);
        let notes = r.layout.notes.join(" | ");
        assert!(
            notes.contains("channel 'Y' (time in field 4) departs from the time axis on line 7 (2 ms where the axis has 1 ms): left out"),
            "{notes}"
        );
        // a unit the core does not know is named; '(None)' is no unit
        assert_eq!(
            r.layout.columns[1].note.as_deref(),
            Some("sample time 1 ms (applied by the export), unit 'V (Volt)' not read")
        );
        assert_eq!(
            r.layout.columns[2].note.as_deref(),
            Some("sample time 1 ms (applied by the export)")
        );
        // the base group is the one with most channels, wherever it is
        let swapped = "Name\tS\nName\tY\tName\tX\tZ\nSampleTime[ms]\t2\tSampleTime[ms]\t1\t1\n\n0\t2\t0\t1\t5\n2\t3\t1\t1.5\t6\n4\t4\t2\t2\t7\n";
        let r = read_table(swapped, &ReadOptions::default()).unwrap();
        assert_eq!(r.table.names, ["time [ms]", "X", "Z"]);
        assert_eq!(r.table.columns[0], [0.0, 1.0, 2.0]);
        // a channel table's columns are numbered 1, 2, … in table order
        let fields: Vec<usize> = r.layout.columns.iter().map(|c| c.field).collect();
        assert_eq!(fields, [1, 2, 3]);
    }

    #[test]
    fn every_separator_is_named() {
        for (sep, name) in [
            (';', ";"),
            (' ', "spaces"),
            (',', ","),
            ('\t', "tab"),
            ('|', "none"),
        ] {
            let text =
                format!("Name{sep}S\nName{sep}X\nSampleTime[ms]{sep}1\n\n0{sep}1\n1{sep}2\n");
            let r = read_table(&text, &ReadOptions::default())
                .unwrap_or_else(|e| panic!("{sep:?}: {e}"));
            assert_eq!(
                (
                    r.layout.format,
                    r.layout.delimiter,
                    r.table.columns[1].as_slice()
                ),
                ("twincatScope", name, [1.0, 2.0].as_slice()),
                "{sep:?}"
            );
        }
    }
}
