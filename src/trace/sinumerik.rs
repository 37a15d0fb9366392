//! SINUMERIK Operate trace files (XML), as the control's trace function
//! ("Diagnostics → Trace", saved as `.xml`) writes them.
//!
//! Layout read (Siemens SINUMERIK Operate trace; the same layout the
//! open-source Trace-Tools reader documents): a root element holding
//! `traceData/dataFrame`; in the frame, one `dataSignal` per signal with
//! its `name` (the NC variable, e.g. `/Nck/MachineAxis/aaIm[1]`) and often
//! a `description`, then one `rec` per sample with `time` (s) and the
//! values `f1` … `fn`, `fk` being the k-th `dataSignal`.
//!
//! Readings chosen:
//! - a value above 9.2e18 (the file's "no value" mark, near `i64::MAX`)
//!   or a missing `fk` is no value; a signal with no value in every record
//!   is left out (noted), and a record with no value for a kept signal is
//!   dropped (noted with its count and first line), so no value is invented;
//! - the columns are `time [s]` then each signal by its `name`, its
//!   `description` kept in the column's note; `dataFrame` attributes and
//!   the root's are kept as metadata;
//! - any other XML (no `traceData/dataFrame`) is refused, saying what the
//!   root element is.
//!
//! # Units
//! `time` in s; signal values as written (the NC's units: mm, deg).

use super::reader::{channel_table, Meta, ReadOptions, TableRead};
use super::xml::{self, Element};
use super::TraceError;

/// The layout's name in messages.
pub const LAYOUT: &str = "SINUMERIK trace XML";

/// Values above this mean "no value".
pub const NO_VALUE: f64 = 9.2e18;

fn bad(line: usize, why: impl Into<String>) -> TraceError {
    TraceError::BadLayout {
        line,
        layout: LAYOUT,
        why: why.into(),
    }
}

/// The number in attribute `key` of `rec`, or the error naming it.
fn number(rec: &Element, key: &str, text: &str) -> Result<f64, TraceError> {
    text.trim()
        .parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .ok_or_else(|| {
            bad(
                rec.line,
                format!(
                    "<rec> attribute {key}='{}' is not a number",
                    super::clip(text)
                ),
            )
        })
}

/// Reads a SINUMERIK trace (`text` is XML; `first`: its first line).
///
/// # Errors
/// [`TraceError::BadXml`] for malformed XML, [`TraceError::BadLayout`]
/// naming the line for XML that is not such a trace or breaks its layout.
///
/// # Examples
/// ```
/// use mtmotion::trace::{read_table, ReadOptions};
/// let xml = r#"<trace><traceData><dataFrame>
/// <dataSignal name="X"/><dataSignal name="Y"/>
/// <rec time="0" f1="1.5" f2="9.223372036854775807E18"/>
/// <rec time="0.001" f1="1.6" f2="2"/>
/// </dataFrame></traceData></trace>"#;
/// let r = read_table(xml, &ReadOptions::default()).unwrap();
/// assert_eq!(r.layout.format, "sinumerikTrace");
/// assert_eq!(r.table.names, ["time [s]", "X", "Y"]);
/// assert_eq!(r.table.columns[1], [1.6]);
/// assert_eq!(r.table.lines, [4]);
/// ```
pub fn read(text: &str, first: usize, opts: &ReadOptions) -> Result<TableRead, TraceError> {
    let root = xml::parse(text)?;
    let frame = root
        .child("traceData")
        .and_then(|d| d.child("dataFrame"))
        .ok_or_else(|| {
            bad(
                first.max(root.line),
                format!(
                    "this XML file's root is <{}> without traceData/dataFrame, so it is not a SINUMERIK trace; export the trace as CSV or TSV text, or save it from SINUMERIK Operate's trace",
                    root.name
                ),
            )
        })?;
    let signals: Vec<&Element> = frame
        .children
        .iter()
        .filter(|c| c.is("dataSignal"))
        .collect();
    if signals.is_empty() {
        return Err(bad(
            frame.line,
            "<dataFrame> has no <dataSignal> naming a signal",
        ));
    }
    let mut names = Vec::new();
    for (k, s) in signals.iter().enumerate() {
        let name = s
            .attr("name")
            .map(str::trim)
            .filter(|n| !n.is_empty())
            .ok_or_else(|| bad(s.line, format!("<dataSignal> {} has no name", k + 1)))?;
        names.push(name.to_string());
    }
    let recs: Vec<&Element> = frame.children.iter().filter(|c| c.is("rec")).collect();
    let n = signals.len();
    // values[k][r]: None = no value
    let mut values: Vec<Vec<Option<f64>>> = vec![Vec::with_capacity(recs.len()); n];
    let mut time = Vec::with_capacity(recs.len());
    for rec in &recs {
        let t = rec
            .attr("time")
            .ok_or_else(|| bad(rec.line, "<rec> has no time attribute"))?;
        time.push(number(rec, "time", t)?);
        let mut row = vec![None; n];
        for (key, v) in &rec.attrs {
            let Some(idx) = key.strip_prefix('f').and_then(|d| d.parse::<usize>().ok()) else {
                continue;
            };
            if idx == 0 || idx > n {
                return Err(bad(
                    rec.line,
                    format!("<rec> has {key}, but the frame names {n} signals (f1 to f{n})"),
                ));
            }
            let v = number(rec, key, v)?;
            row[idx - 1] = (v <= NO_VALUE).then_some(v);
        }
        for (k, v) in row.into_iter().enumerate() {
            values[k].push(v);
        }
    }
    let Some(first_rec) = recs.first() else {
        return Err(bad(frame.line, "<dataFrame> has no <rec> samples"));
    };
    let mut notes = Vec::new();
    let kept: Vec<usize> = (0..n)
        .filter(|&k| {
            let any = values[k].iter().any(Option::is_some);
            if !any {
                notes.push(format!(
                    "signal '{}' (f{}) has no value in any record: left out",
                    names[k],
                    k + 1
                ));
            }
            any
        })
        .collect();
    if kept.is_empty() {
        return Err(bad(first_rec.line, "no signal has a value in any <rec>"));
    }
    let full: Vec<usize> = (0..recs.len())
        .filter(|&r| kept.iter().all(|&k| values[k][r].is_some()))
        .collect();
    if full.len() < recs.len() {
        let first_gap = (0..recs.len())
            .find(|&r| kept.iter().any(|&k| values[k][r].is_none()))
            .unwrap_or(0);
        notes.push(format!(
            "{} of {} records have no value for a signal (first on line {}): dropped",
            recs.len() - full.len(),
            recs.len(),
            recs[first_gap].line
        ));
    }
    if full.is_empty() {
        return Err(bad(
            first_rec.line,
            "no <rec> has a value for every signal that has values",
        ));
    }
    let mut columns = vec![full.iter().map(|&r| time[r]).collect::<Vec<f64>>()];
    let mut col_names = vec!["time [s]".to_string()];
    for &k in &kept {
        columns.push(full.iter().map(|&r| values[k][r].unwrap_or(0.0)).collect());
        col_names.push(names[k].clone());
    }
    let lines = full.iter().map(|&r| recs[r].line).collect();
    let metadata: Vec<Meta> = root
        .attrs
        .iter()
        .chain(&frame.attrs)
        .map(|(k, v)| Meta {
            line: frame.line,
            key: k.clone(),
            value: v.clone(),
        })
        .collect();
    notes.insert(
        0,
        format!(
            "SINUMERIK trace: {} signals, {} records",
            kept.len(),
            full.len()
        ),
    );
    let mut read = channel_table(
        "sinumerikTrace",
        "none",
        col_names,
        columns,
        lines,
        metadata,
        notes,
        opts,
    );
    for (j, &k) in kept.iter().enumerate() {
        if let Some(d) = signals[k].attr("description") {
            read.layout.columns[j + 1].note = Some(format!("description: {d}"));
        }
    }
    Ok(read)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(body: &str) -> String {
        format!("<?xml version=\"1.0\"?>\n<root>\n<traceData>\n<dataFrame>\n{body}</dataFrame>\n</traceData>\n</root>\n")
    }

    #[test]
    fn no_values_drop_records_and_empty_signals() {
        let body = "<dataSignal name=\"A\" description=\"pos\"/>\n<dataSignal name=\"B\"/>\n<dataSignal name=\"C\"/>\n<rec time=\"0\" f1=\"9.3e18\" f3=\"9.3e18\"/>\n<rec time=\"1\" f1=\"1\" f2=\"2\"/>\n<rec time=\"2\" f2=\"3\" f1=\"4\"/>\n";
        let r = read(&frame(body), 1, &ReadOptions::default()).unwrap();
        assert_eq!(r.table.names, ["time [s]", "A", "B"]);
        assert_eq!(
            r.table.columns,
            [vec![1.0, 2.0], vec![1.0, 4.0], vec![2.0, 3.0]]
        );
        assert_eq!(r.table.lines, [9, 10]);
        let notes = r.layout.notes.join(" | ");
        assert!(
            notes.contains("'C' (f3) has no value in any record: left out"),
            "{notes}"
        );
        assert!(
            notes.contains("1 of 3 records have no value for a signal (first on line 8): dropped"),
            "{notes}"
        );
        assert_eq!(
            r.layout.columns[1].note.as_deref(),
            Some("description: pos")
        );
        assert_eq!(r.layout.columns[0].factor, Some(1.0));
        // every record whole: nothing dropped, and no note says so
        let whole =
            "<dataSignal name=\"A\"/>\n<rec time=\"0\" f1=\"1\"/>\n<rec time=\"1\" f1=\"2\"/>\n";
        let r = read(&frame(whole), 1, &ReadOptions::default()).unwrap();
        assert_eq!(r.table.columns[1], [1.0, 2.0]);
        assert!(
            !r.layout.notes.iter().any(|n| n.contains("dropped")),
            "{:?}",
            r.layout.notes
        );
    }

    #[test]
    fn refusals_name_the_line_and_cause() {
        for (text, line, cause) in [
            ("<a>\n<b/>\n</a>\n".to_string(), 1, "root is <a> without traceData/dataFrame"),
            (frame("<rec time=\"0\" f1=\"1\"/>\n"), 4, "no <dataSignal>"),
            (frame("<dataSignal/>\n"), 5, "<dataSignal> 1 has no name"),
            (frame("<dataSignal name=\"A\"/>\n"), 4, "no <rec> samples"),
            (frame("<dataSignal name=\"A\"/>\n<rec f1=\"1\"/>\n"), 6, "no time attribute"),
            (frame("<dataSignal name=\"A\"/>\n<rec time=\"0\" f2=\"1\"/>\n"), 6, "has f2, but the frame names 1 signals"),
            (frame("<dataSignal name=\"A\"/>\n<rec time=\"0\" f1=\"1,5\"/>\n"), 6, "f1='1,5' is not a number"),
            (frame("<dataSignal name=\"A\"/>\n<rec time=\"x\" f1=\"1\"/>\n"), 6, "time='x' is not a number"),
            (frame("<dataSignal name=\"A\"/>\n<rec time=\"0\" f1=\"1e19\"/>\n<rec time=\"1\"/>\n"), 6, "no signal has a value"),
            (frame("<dataSignal name=\"A\"/>\n<dataSignal name=\"B\"/>\n<rec time=\"0\" f1=\"1\"/>\n<rec time=\"1\" f2=\"1\"/>\n"), 7, "no <rec> has a value for every signal"),
        ] {
            let e = read(&text, 1, &ReadOptions::default()).unwrap_err().to_string();
            assert!(e.starts_with(&format!("line {line}: ")), "{text}: {e}");
            assert!(e.contains(cause), "{text}: {e}");
        }
    }
}
