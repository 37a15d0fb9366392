//! Trace import: delimited text (CSV, TSV, semicolon or whitespace) with a
//! header row, as exported by SERVO GUIDE and ball-bar software.
//!
//! [`Table::parse`] reads the header and every numeric row; [`Table::column`]
//! finds a column by name (case-insensitive, any of several aliases) and
//! scales it to core units. Lines starting with `#` or `//` and blank lines
//! are skipped, as are metadata lines *before* the header that contain no
//! delimiter. Every error names its 1-based line and column.

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
    #[error("line {line}, column {column} ('{name}'): '{text}' is not a number")]
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
    #[error("no column named {wanted} in the header (columns: {available})")]
    MissingColumn {
        /// The names tried, e.g. "'x' or 'pos_x'".
        wanted: String,
        /// The header names.
        available: String,
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

fn is_comment(line: &str) -> bool {
    let t = line.trim();
    t.is_empty() || t.starts_with('#') || t.starts_with("//")
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
        let lines: Vec<(usize, &str)> = text
            .lines()
            .enumerate()
            .map(|(i, l)| (i + 1, l.trim_start_matches('\u{feff}')))
            .filter(|(_, l)| !is_comment(l))
            .collect();
        // The header is the line just before the first all-numeric line;
        // anything above it is metadata.
        let numeric = |l: &str| {
            detect(l).is_some_and(|d| split(l, d).iter().all(|f| f.parse::<f64>().is_ok()))
                || l.trim().parse::<f64>().is_ok()
        };
        let first_data = lines.iter().position(|(_, l)| numeric(l));
        let (h, header_line, header) = match first_data {
            Some(0) => return Err(TraceError::NoHeader { line: lines[0].0 }),
            Some(k) => (k - 1, lines[k - 1].0, lines[k - 1].1),
            None => match lines.last() {
                Some((n, _)) => return Err(TraceError::NoData { line: *n }),
                None => return Err(TraceError::Empty),
            },
        };
        let delimiter = detect(lines[h + 1].1)
            .or_else(|| detect(header))
            .unwrap_or(',');
        let lines = lines.into_iter().skip(h + 1);
        let names: Vec<String> = split(header, delimiter)
            .into_iter()
            .map(|s| s.trim_matches('"').trim().to_string())
            .collect();
        let mut columns = vec![Vec::new(); names.len()];
        let mut row_lines = Vec::new();
        for (n, l) in lines {
            let fields = split(l, delimiter);
            // A trailing delimiter gives one empty extra field: tolerate it.
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
    /// (case-insensitive; a unit suffix in brackets such as `X [mm]` or
    /// `X(mm)` is ignored).
    pub fn find(&self, aliases: &[&str]) -> Option<usize> {
        let bare = |s: &str| {
            s.split(['[', '('])
                .next()
                .unwrap_or("")
                .trim()
                .to_ascii_lowercase()
        };
        aliases.iter().find_map(|a| {
            let a = a.to_ascii_lowercase();
            self.names.iter().position(|n| bare(n) == a)
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
                    .map(|a| format!("'{a}'"))
                    .collect::<Vec<_>>()
                    .join(" or "),
                available: self.names.join(", "),
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

#[cfg(test)]
mod tests {
    use super::*;

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
    }

    #[test]
    fn errors_name_lines_and_columns() {
        assert_eq!(Table::parse("\n# x\n"), Err(TraceError::Empty));
        assert_eq!(Table::parse("a,b\n"), Err(TraceError::NoData { line: 1 }));
        assert_eq!(Table::parse("1,2\n"), Err(TraceError::NoHeader { line: 1 }));
        let e = Table::parse("a,b\n1,2\n3\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            "line 3: 1 fields, expected 2 as in the header"
        );
        let e = Table::parse("a,b\n1,nan\n").unwrap_err();
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
        assert!(t.column_at(3, 1.0).is_err());
    }
}
