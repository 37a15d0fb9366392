//! LinuxCNC's HAL capture tools: `halsampler` output and `halscope`'s
//! saved log.
//!
//! Layouts read (LinuxCNC's halsampler(1) manual page and halscope's
//! `scope_files.c`):
//! - halsampler writes one line per sample, the values separated by
//!   spaces, nothing else; with `-t` each line starts with the sample
//!   number. The file has no time axis: the sample period (the thread
//!   period times the sampler's decimation) must be given, and a file of
//!   numbers only is refused without it, saying so;
//! - halscope's "save log" writes `Sampling period is <n> ns`, a blank
//!   line, then one line per sample holding `<channel> <value>` for each
//!   channel in turn.
//!
//! Readings chosen: a headerless file whose first column is non-negative
//! whole numbers that grow by at least 1 from row to row is halsampler's
//! `-t` output: that column is the sample number and the time is sample
//! number × period (so a sample the FIFO dropped keeps its time); any
//! other headerless file's time is row × period. halscope's channel
//! labels and their order must be the same on every line.
//!
//! # Units
//! Generated time in s; values as sampled.

use super::reader::{channel_table, ColumnKind, Meta, ReadOptions, TableRead};
use super::TraceError;

/// The layout's name in messages.
pub const HALSCOPE: &str = "halscope log";

/// Whether `first` (the first non-blank line) is halscope's log header.
pub fn is_halscope(first: &str) -> bool {
    first.trim_start().starts_with("Sampling period is")
}

fn bad(line: usize, why: impl Into<String>) -> TraceError {
    TraceError::BadLayout {
        line,
        layout: HALSCOPE,
        why: why.into(),
    }
}

/// Reads a halscope log (numbered, non-blank `lines`).
///
/// # Errors
/// [`TraceError::BadLayout`] naming the line: a period that is not
/// `<n> ns`, a line whose labels differ from the first sample's, a value
/// that is not a number.
///
/// # Examples
/// ```
/// use mtmotion::trace::{read_table, ReadOptions};
/// let log = "Sampling period is 1000000 ns \n\nx +1.50000000000000 y -2.00000000000000 \nx +1.60000000000000 y -2.10000000000000 \n";
/// let r = read_table(log, &ReadOptions::default()).unwrap();
/// assert_eq!(r.layout.format, "halscope");
/// assert_eq!(r.table.names, ["x", "y", "time [s]"]);
/// assert_eq!(r.table.columns[2], [0.0, 0.001]);
/// ```
pub fn read_halscope(lines: &[(usize, &str)], opts: &ReadOptions) -> Result<TableRead, TraceError> {
    let (first, head) = lines[0];
    let ns: f64 = head
        .trim()
        .strip_prefix("Sampling period is")
        .and_then(|r| r.trim().strip_suffix("ns"))
        .and_then(|n| n.trim().parse().ok())
        .filter(|v: &f64| v.is_finite() && *v > 0.0)
        .ok_or_else(|| {
            bad(
                first,
                format!(
                    "'{}' is not 'Sampling period is <n> ns' with n > 0",
                    super::clip_at(head.trim(), 40)
                ),
            )
        })?;
    let dt = ns / 1e9; // correctly rounded: 2000 ns is 2e-6 s, not 2.0000000000000003e-6
    if let Some(given) = opts.sample_period {
        if (given - dt).abs() > 1e-9 * dt {
            return Err(TraceError::BadOption {
                line: first,
                field: "samplePeriod",
                why: format!("the log states its sample period ({dt} s); leave samplePeriod out"),
            });
        }
    }
    let Some(&(data_line, data_text)) = lines.get(1) else {
        return Err(bad(first, "no sample follows the sampling period"));
    };
    let pairs = |l: &str| -> Vec<String> { l.split_whitespace().map(str::to_string).collect() };
    let first_row = pairs(data_text);
    if first_row.len() < 2 || first_row.len() % 2 != 0 {
        return Err(bad(
            data_line,
            "expected '<channel> <value>' pairs, as halscope writes each sample",
        ));
    }
    let labels: Vec<String> = first_row.iter().step_by(2).cloned().collect();
    let mut columns = vec![Vec::with_capacity(lines.len()); labels.len()];
    let mut rows = Vec::with_capacity(lines.len());
    for &(n, l) in &lines[1..] {
        let f = pairs(l);
        if f.len() != 2 * labels.len() || f.iter().step_by(2).ne(labels.iter()) {
            return Err(bad(
                n,
                format!(
                    "the channels are not those of line {data_line} ({}), in that order",
                    labels.join(", ")
                ),
            ));
        }
        for (k, v) in f.iter().skip(1).step_by(2).enumerate() {
            let x = v
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| TraceError::BadNumber {
                    line: n,
                    column: 2 * k + 2,
                    name: labels[k].clone(),
                    text: v.clone(),
                })?;
            columns[k].push(x);
        }
        rows.push(n);
    }
    let mut names = labels;
    names.push("time [s]".into());
    columns.push((0..rows.len()).map(|i| i as f64 * dt).collect());
    let notes = vec![format!(
        "halscope log: {} channels, one sample every {dt} s (line {first})",
        names.len() - 1
    )];
    let meta = vec![Meta {
        line: first,
        key: "Sampling period".into(),
        value: format!("{ns} ns"),
    }];
    let mut read = channel_table(
        "halscope", "spaces", names, columns, rows, meta, notes, opts,
    );
    if let Some(t) = read.layout.columns.last_mut() {
        t.kind = ColumnKind::Generated;
        t.field = 0;
        t.note = Some(format!("generated: one sample every {dt} s"));
    }
    Ok(read)
}

/// A headerless delimited read as halsampler's output: refused without a
/// sample period; with `-t`'s sample numbers in the first column, the
/// time is sample number × period. Any other read is returned as it is.
///
/// # Errors
/// [`TraceError::BadOption`] for a headerless file without `samplePeriod`.
pub fn halsampler_index(mut read: TableRead, opts: &ReadOptions) -> Result<TableRead, TraceError> {
    if read.layout.header_line.is_some() {
        return Ok(read);
    }
    let line = read.layout.first_data_line;
    let Some(dt) = opts.sample_period else {
        return Err(TraceError::BadOption {
            line,
            field: "samplePeriod",
            why: "this file is numbers only (no header line, as halsampler writes it), so it has no time axis: give samplePeriod, the time between samples in s (halsampler: the thread period × the sampler's decimation)".into(),
        });
    };
    read.layout.format = "halsampler";
    let first = read.table.columns[0].clone();
    let index = read.table.columns.len() > 2
        && first.iter().all(|v| v.fract() == 0.0 && *v >= 0.0)
        && first.windows(2).all(|w| w[1] >= w[0] + 1.0);
    if index {
        let time: Vec<f64> = first.iter().map(|i| i * dt).collect();
        let last = read.table.columns.len() - 1;
        read.table.columns[last] = time;
        read.table.names[0] = "sample".into();
        let c = &mut read.layout.columns[0];
        c.name = "sample".into();
        c.bare = "sample".into();
        c.note = Some("halsampler -t: the sample number".into());
        if let Some(g) = read.layout.columns.last_mut() {
            g.note = Some(format!("generated: sample number × {dt} s"));
        }
        read.layout.notes.push(format!(
            "halsampler -t: column 1 holds the sample numbers ({} to {}); time = sample number × {dt} s",
            first[0],
            first[first.len() - 1]
        ));
    }
    Ok(read)
}

#[cfg(test)]
mod tests {
    use crate::trace::{read_table, ReadOptions};

    fn read(text: &str, dt: Option<f64>) -> Result<crate::trace::TableRead, String> {
        let opts = ReadOptions {
            sample_period: dt,
            ..ReadOptions::default()
        };
        read_table(text, &opts).map_err(|e| e.to_string())
    }

    #[test]
    fn halscope_checks_its_period_against_the_given_one() {
        let log = "Sampling period is 2000 ns\n\nx +1 y +2\nx +1.5 y +2.5\nx +2 y +3\n";
        // the same period given (or none) is accepted; the time is row × 2 µs
        for dt in [None, Some(2e-6)] {
            let r = read(log, dt).unwrap();
            assert_eq!(r.table.columns[2], [0.0, 2e-6, 4e-6], "{dt:?}");
        }
        // one part in a million off is another period
        let e = read(log, Some(2e-6 * (1.0 + 1e-6))).unwrap_err();
        assert!(
            e.starts_with(
                "line 1: option samplePeriod: the log states its sample period (0.000002 s)"
            ),
            "{e}"
        );
        // a period of 0 ns is no period
        let e = read(&log.replace("2000 ns", "0 ns"), None).unwrap_err();
        assert_eq!(
            e,
            "line 1: halscope log: 'Sampling period is 0 ns' is not 'Sampling period is <n> ns' with n > 0"
        );
    }

    #[test]
    fn a_bad_halscope_value_names_its_field() {
        let log = "Sampling period is 1000 ns\n\nx +1 y +2 z +3\nx bad y +2 z +3\nx +1 y +2 z +3\n";
        assert_eq!(
            read(log, None).unwrap_err(),
            "line 4, column 2 ('x'): 'bad' is not a number"
        );
        let log = log.replace("x bad y +2 z +3", "x +1 y +2 z inf");
        assert_eq!(
            read(&log, None).unwrap_err(),
            "line 4, column 6 ('z'): 'inf' is not a number"
        );
    }

    #[test]
    fn a_single_column_of_whole_numbers_is_data_not_sample_numbers() {
        // halsampler -t needs a value beside the sample number
        let r = read("0\n1\n2\n5\n", Some(0.5)).unwrap();
        assert_eq!(r.table.names, ["column 1", "time"]);
        assert_eq!(
            r.table.columns,
            [vec![0.0, 1.0, 2.0, 5.0], vec![0.0, 0.5, 1.0, 1.5]]
        );
        let r = read("0 7\n1 8\n2 9\n5 3\n", Some(0.5)).unwrap();
        assert_eq!(r.table.names, ["sample", "column 2", "time"]);
        assert_eq!(r.table.columns[2], [0.0, 0.5, 1.0, 2.5]);
        // sample numbers are whole and not negative
        for first in [["-3", "-2", "-1"], ["0.5", "1.5", "2.5"]] {
            let text: String = first.iter().map(|f| format!("{f} 7\n")).collect();
            let r = read(&text, Some(0.5)).unwrap();
            assert_eq!(r.table.names[0], "column 1", "{text}");
            assert_eq!(r.table.columns[2], [0.0, 0.5, 1.0], "{text}");
        }
    }
}
