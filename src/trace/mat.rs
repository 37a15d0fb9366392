//! MATLAB v5 `.mat` captures, as dSPACE ControlDesk and Simulink write
//! them: the signals of a recording read into named columns.
//!
//! Format read (MathWorks, "MAT-File Format", Level 5): a 128-byte header
//! (text starting `MATLAB 5.0 MAT-file`, version 0x0100, endian mark `IM`
//! or `MI`), then data elements, each an 8-byte tag (type, byte count; or
//! a 4-byte "small element" tag with its data in the next 4 bytes) padded
//! to 8 bytes. Read: `miCOMPRESSED` (zlib, one element inside), `miMATRIX`
//! of class `mxDOUBLE`/`mxSINGLE`/integer (real), `mxCHAR`, `mxSTRUCT` and
//! `mxCELL`, with numbers stored as any of the numeric `mi` types.
//! Refused, naming the class or type and the byte offset: complex,
//! sparse, object and function-handle arrays, v7.3 (HDF5) and v4 files.
//!
//! Layouts of the variables read (readings chosen):
//! - dSPACE ControlDesk: a struct with `X` (its `Data` is the time, s) and
//!   `Y`, a struct array whose element i has `Data` and `Name` (and
//!   optionally `Unit`); each `Y(i)` becomes a column named `Name`
//!   (`Name [unit]` when the unit is one the core reads);
//! - Simulink "structure with time": a struct with `time` and `signals`,
//!   whose element i has `values` (one column per signal, or a matrix of
//!   several) and `label`;
//! - otherwise every real numeric vector at the top level, by its
//!   variable name, when all have one length (`t`, `x`, `y`, `c`).
//!
//! All signals must have as many samples as the time. A binary file has
//! no lines: its errors name the byte offset, and a row's "line" is its
//! sample number (1, 2, …).
//!
//! # Units
//! dSPACE and Simulink time in s; values as recorded.

use miniz_oxide::inflate::decompress_to_vec_zlib_with_limit;

use super::reader::{channel_table, Meta, ReadOptions, TableRead};
use super::TraceError;

/// The layout's name in messages.
pub const LAYOUT: &str = "MATLAB .mat";

/// Largest inflated element, bytes (8 M doubles).
pub const MAX_INFLATED: usize = 64 << 20;

/// Deepest nesting of structs and cells read.
const MAX_DEPTH: usize = 16;

/// Whether `bytes` start like a MATLAB v5 file.
pub fn is_mat(bytes: &[u8]) -> bool {
    bytes.starts_with(b"MATLAB 5.0 MAT-file")
}

fn bad(offset: usize, why: impl Into<String>) -> TraceError {
    TraceError::BadBinary {
        offset,
        layout: LAYOUT,
        why: why.into(),
    }
}

/// A value of a `.mat` file.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// A real numeric array, column-major.
    Num {
        /// Dimensions.
        dims: Vec<usize>,
        /// The values as f64.
        re: Vec<f64>,
    },
    /// A character array (its rows joined).
    Char(String),
    /// A struct array: field names and, per element, one value per field.
    Struct {
        /// Field names.
        fields: Vec<String>,
        /// Elements in column-major order.
        elems: Vec<Vec<Value>>,
    },
    /// A cell array.
    Cell(Vec<Value>),
}

impl Value {
    /// Field `name` of struct element `i`.
    pub fn field(&self, i: usize, name: &str) -> Option<&Value> {
        match self {
            Value::Struct { fields, elems } => {
                let k = fields.iter().position(|f| f == name)?;
                elems.get(i).and_then(|e| e.get(k))
            }
            _ => None,
        }
    }

    /// Number of struct elements (0 for anything else).
    pub fn len(&self) -> usize {
        match self {
            Value::Struct { elems, .. } => elems.len(),
            _ => 0,
        }
    }

    /// Whether it is an empty struct array or not a struct.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    fn text(&self) -> Option<String> {
        match self {
            Value::Char(s) => Some(s.clone()),
            Value::Cell(c) => c.first().and_then(Value::text),
            _ => None,
        }
    }
}

/// Byte order of the file.
#[derive(Clone, Copy)]
struct Endian(bool); // true: little

impl Endian {
    fn u32(self, b: &[u8]) -> u32 {
        let a = [b[0], b[1], b[2], b[3]];
        if self.0 {
            u32::from_le_bytes(a)
        } else {
            u32::from_be_bytes(a)
        }
    }
}

/// One data element: its type, its data, and the offset of its data in
/// the file (for messages).
struct Element<'a> {
    ty: u32,
    data: &'a [u8],
    at: usize,
}

/// Reads the element at `pos` of `buf` (`base`: `buf`'s offset in the
/// file); returns it and the position after it (padded).
fn element(
    buf: &[u8],
    pos: usize,
    base: usize,
    e: Endian,
) -> Result<(Element<'_>, usize), TraceError> {
    let at = base + pos;
    if buf.len() < pos + 8 {
        return Err(bad(
            at,
            format!(
                "a data element's tag needs 8 bytes, {} left",
                buf.len() - pos
            ),
        ));
    }
    let first = e.u32(&buf[pos..]);
    if first >> 16 != 0 {
        // small element: type in the low half, byte count in the high
        let n = (first >> 16) as usize;
        if n > 4 {
            return Err(bad(
                at,
                format!("a small data element of {n} bytes (at most 4)"),
            ));
        }
        return Ok((
            Element {
                ty: first & 0xffff,
                data: &buf[pos + 4..pos + 4 + n],
                at: at + 4,
            },
            pos + 8,
        ));
    }
    let n = e.u32(&buf[pos + 4..]) as usize;
    let end = pos
        .checked_add(8)
        .and_then(|p| p.checked_add(n))
        .filter(|&end| end <= buf.len())
        .ok_or_else(|| {
            bad(
                at,
                format!(
                    "a data element of {n} bytes, but {} bytes are left: the file is cut short",
                    buf.len() - pos - 8
                ),
            )
        })?;
    // miCOMPRESSED is not padded; any other element's data is padded to
    // 8 bytes from its own start (after a compressed element it need not
    // start on a multiple of 8 in the file)
    let next = if first == 15 {
        end
    } else {
        pos + 8 + n.div_ceil(8) * 8
    }
    .min(buf.len());
    Ok((
        Element {
            ty: first,
            data: &buf[pos + 8..end],
            at: at + 8,
        },
        next,
    ))
}

/// Numbers of an element of numeric type `ty`.
fn numbers(el: &Element, e: Endian) -> Result<Vec<f64>, TraceError> {
    let d = el.data;
    let (size, name) = match el.ty {
        1 => (1, "miINT8"),
        2 => (1, "miUINT8"),
        3 => (2, "miINT16"),
        4 => (2, "miUINT16"),
        5 => (4, "miINT32"),
        6 => (4, "miUINT32"),
        7 => (4, "miSINGLE"),
        9 => (8, "miDOUBLE"),
        12 => (8, "miINT64"),
        13 => (8, "miUINT64"),
        16 => (1, "miUTF8"),
        t => return Err(bad(el.at, format!("data type {t} where numbers were expected; read: miINT8 to miUINT64, miSINGLE, miDOUBLE"))),
    };
    if d.len() % size != 0 {
        return Err(bad(
            el.at,
            format!(
                "{} bytes of {name} (a multiple of {size} expected)",
                d.len()
            ),
        ));
    }
    let out = d
        .chunks_exact(size)
        .map(|c| {
            let mut b = [0u8; 8];
            if e.0 {
                b[..size].copy_from_slice(c);
            } else {
                for (i, x) in c.iter().rev().enumerate() {
                    b[i] = *x;
                }
            }
            let le8 = u64::from_le_bytes(b);
            // unsigned types (miUINT8, miUTF8, miUINT16, miUINT32,
            // miUINT64) are le8 itself: the bytes above their size are zero
            match el.ty {
                1 => le8 as u8 as i8 as f64,
                3 => le8 as u16 as i16 as f64,
                5 => le8 as u32 as i32 as f64,
                7 => f32::from_bits(le8 as u32) as f64,
                9 => f64::from_bits(le8),
                12 => le8 as i64 as f64,
                _ => le8 as f64,
            }
        })
        .collect();
    Ok(out)
}

fn class_name(c: u32) -> String {
    match c {
        1 => "mxCELL".into(),
        2 => "mxSTRUCT".into(),
        3 => "mxOBJECT (a MATLAB object)".into(),
        4 => "mxCHAR".into(),
        5 => "mxSPARSE (a sparse matrix)".into(),
        16 => "mxFUNCTION (a function handle)".into(),
        17 => "mxOPAQUE (a MATLAB object)".into(),
        c => format!("array class {c}"),
    }
}

/// Reads an `miMATRIX` element's contents; returns its name and value.
fn matrix(el: &Element, e: Endian, depth: usize) -> Result<(String, Value), TraceError> {
    if depth > MAX_DEPTH {
        return Err(bad(
            el.at,
            format!("structs or cells nested deeper than {MAX_DEPTH} levels"),
        ));
    }
    let d = el.data;
    let (flags, p) = element(d, 0, el.at, e)?;
    if flags.data.len() < 8 || flags.ty != 6 {
        return Err(bad(
            flags.at,
            "an array's flags (miUINT32, 8 bytes) were expected",
        ));
    }
    let f = e.u32(flags.data);
    let class = f & 0xff;
    let complex = f & 0x800 != 0;
    let (dims_el, p) = element(d, p, el.at, e)?;
    let dims: Vec<usize> = numbers(&dims_el, e)?
        .into_iter()
        .map(|v| v.max(0.0) as usize)
        .collect();
    let count = dims
        .iter()
        .try_fold(1usize, |a, &b| a.checked_mul(b))
        .filter(|&n| n <= MAX_INFLATED / 8)
        .ok_or_else(|| bad(dims_el.at, format!("dimensions {dims:?} are too large")))?;
    let (name_el, mut p) = element(d, p, el.at, e)?;
    let name = String::from_utf8_lossy(name_el.data).into_owned();
    if complex {
        return Err(bad(
            el.at,
            format!("'{name}' is complex; a trace is real numbers"),
        ));
    }
    let value = match class {
        6..=15 => {
            let (re, _) = element(d, p, el.at, e)?;
            let v = numbers(&re, e)?;
            if v.len() != count {
                return Err(bad(re.at, format!("'{name}' has {} values for dimensions {dims:?}", v.len())));
            }
            Value::Num { dims, re: v }
        }
        4 => {
            let (chars, _) = element(d, p, el.at, e)?;
            let codes = match chars.ty {
                16 => String::from_utf8_lossy(chars.data).chars().map(u32::from).collect(),
                _ => numbers(&chars, e)?.into_iter().map(|c| c as u32).collect::<Vec<u32>>(),
            };
            let rows = dims.first().copied().unwrap_or(1).max(1);
            // column-major: row r is codes[r], codes[r + rows], …
            let text: Vec<String> = (0..rows)
                .map(|r| {
                    codes
                        .iter()
                        .skip(r)
                        .step_by(rows)
                        .filter_map(|&c| char::from_u32(c))
                        .collect::<String>()
                        .trim_end()
                        .to_string()
                })
                .collect();
            Value::Char(text.join("\n"))
        }
        2 => {
            let (len_el, q) = element(d, p, el.at, e)?;
            let len = numbers(&len_el, e)?.first().copied().unwrap_or(0.0) as usize;
            let (names_el, q) = element(d, q, el.at, e)?;
            if len == 0 || names_el.data.len() % len != 0 {
                return Err(bad(names_el.at, format!("'{name}': field names of {} bytes with a name length of {len}", names_el.data.len())));
            }
            let fields: Vec<String> = names_el
                .data
                .chunks(len)
                .map(|c| String::from_utf8_lossy(c).trim_end_matches('\0').to_string())
                .collect();
            p = q;
            // every element takes at least 8 bytes of the data: a count
            // the data cannot hold fails below without reserving it
            let mut elems = Vec::with_capacity(count.min(d.len() / 8));
            for _ in 0..count {
                let mut one = Vec::with_capacity(fields.len());
                for _ in 0..fields.len() {
                    let (m, q) = element(d, p, el.at, e)?;
                    one.push(sub(&m, e, depth)?);
                    p = q;
                }
                elems.push(one);
            }
            Value::Struct { fields, elems }
        }
        1 => {
            let mut cells = Vec::with_capacity(count.min(d.len() / 8));
            for _ in 0..count {
                let (m, q) = element(d, p, el.at, e)?;
                cells.push(sub(&m, e, depth)?);
                p = q;
            }
            Value::Cell(cells)
        }
        c => {
            return Err(bad(el.at, format!("'{name}' is {}, which is not read; a trace is real numbers, text, structs and cells", class_name(c))))
        }
    };
    Ok((name, value))
}

/// A nested `miMATRIX` (an empty one is an empty array).
fn sub(m: &Element, e: Endian, depth: usize) -> Result<Value, TraceError> {
    if m.ty != 14 {
        return Err(bad(
            m.at,
            format!(
                "data type {} inside a struct or cell (miMATRIX expected)",
                m.ty
            ),
        ));
    }
    if m.data.is_empty() {
        return Ok(Value::Num {
            dims: vec![0, 0],
            re: vec![],
        });
    }
    Ok(matrix(m, e, depth + 1)?.1)
}

/// The top-level variables of a `.mat` file, by name.
///
/// # Errors
/// [`TraceError::BadBinary`] naming the byte offset and the cause.
pub fn variables(bytes: &[u8]) -> Result<Vec<(String, Value)>, TraceError> {
    if !is_mat(bytes) {
        return Err(bad(
            0,
            "not a MATLAB 5.0 MAT-file (its header text is missing)",
        ));
    }
    if bytes.len() < 128 {
        return Err(bad(
            bytes.len(),
            format!("the 128-byte header is cut short at {} bytes", bytes.len()),
        ));
    }
    let e = match &bytes[126..128] {
        b"IM" => Endian(true),
        b"MI" => Endian(false),
        m => {
            return Err(bad(
                126,
                format!("endian mark {m:?}, 'IM' or 'MI' expected"),
            ))
        }
    };
    let version = if e.0 {
        u16::from_le_bytes([bytes[124], bytes[125]])
    } else {
        u16::from_be_bytes([bytes[124], bytes[125]])
    };
    if version == 0x0200 {
        return Err(bad(
            124,
            "a v7.3 (HDF5) MAT-file, which is not read; save it with save(..., '-v7') or '-v6'",
        ));
    }
    let mut out = Vec::new();
    let mut pos = 128;
    while pos < bytes.len() {
        let (el, next) = element(bytes, pos, 0, e)?;
        let inflated;
        let el = if el.ty == 15 {
            inflated = decompress_to_vec_zlib_with_limit(el.data, MAX_INFLATED).map_err(|x| {
                bad(el.at, format!("miCOMPRESSED data do not inflate ({:?}); the file is damaged or above {} MiB inflated", x.status, MAX_INFLATED >> 20))
            })?;
            element(&inflated, 0, el.at, e)?.0
        } else {
            el
        };
        if el.ty != 14 {
            return Err(bad(
                el.at,
                format!("data type {} at the top level (miMATRIX expected)", el.ty),
            ));
        }
        out.push(matrix(&el, e, 0)?);
        pos = next;
    }
    Ok(out)
}

/// A real vector's values (a 1×n or n×1 array).
fn vector(v: &Value) -> Option<&[f64]> {
    match v {
        Value::Num { dims, re } if dims.iter().filter(|&&d| d > 1).count() <= 1 => Some(re),
        _ => None,
    }
}

/// Reads a `.mat` capture into named columns (see the module's layouts).
///
/// # Errors
/// [`TraceError::BadBinary`] naming the byte offset, or the variable and
/// what it holds instead of a capture.
pub fn read(bytes: &[u8], opts: &ReadOptions) -> Result<TableRead, TraceError> {
    let vars = variables(bytes)?;
    let mut names = Vec::new();
    let mut columns: Vec<Vec<f64>> = Vec::new();
    let mut notes = Vec::new();
    let unit_name = |n: String, unit: Option<String>| match unit {
        Some(u) if super::units::name_unit(&format!("v [{u}]")).1.is_some() => format!("{n} [{u}]"),
        _ => n,
    };
    for (var, v) in &vars {
        let dspace = v.field(0, "X").zip(v.field(0, "Y"));
        let simulink = v.field(0, "time").zip(v.field(0, "signals"));
        if let Some((x, y)) = dspace {
            let t = x
                .field(0, "Data")
                .and_then(vector)
                .ok_or_else(|| bad(0, format!("'{var}.X' has no Data vector (the time)")))?;
            names.push("time [s]".to_string());
            columns.push(t.to_vec());
            for i in 0..y.len() {
                let name = y
                    .field(i, "Name")
                    .and_then(Value::text)
                    .unwrap_or_else(|| format!("Y({})", i + 1));
                let data = y.field(i, "Data").and_then(vector).ok_or_else(|| {
                    bad(
                        0,
                        format!("'{var}.Y({})' ('{name}') has no Data vector", i + 1),
                    )
                })?;
                names.push(unit_name(name, y.field(i, "Unit").and_then(Value::text)));
                columns.push(data.to_vec());
            }
            notes.push(format!(
                "dSPACE capture '{var}': X (time) and {} signals Y",
                y.len()
            ));
            break;
        }
        if let Some((t, s)) = simulink {
            let t = vector(t).ok_or_else(|| bad(0, format!("'{var}.time' is not a vector")))?;
            names.push("time [s]".to_string());
            columns.push(t.to_vec());
            for i in 0..s.len() {
                let label = s
                    .field(i, "label")
                    .and_then(Value::text)
                    .filter(|l| !l.is_empty());
                let Some(Value::Num { dims, re }) = s.field(i, "values") else {
                    return Err(bad(0, format!("'{var}.signals({})' has no values", i + 1)));
                };
                let rows = dims.first().copied().unwrap_or(0);
                let cols = re.len().checked_div(rows).unwrap_or(0);
                for c in 0..cols {
                    let base = label
                        .clone()
                        .unwrap_or_else(|| format!("signals({})", i + 1));
                    names.push(if cols > 1 {
                        format!("{base}({})", c + 1)
                    } else {
                        base
                    });
                    columns.push(re[c * rows..(c + 1) * rows].to_vec());
                }
            }
            notes.push(format!(
                "Simulink structure with time '{var}': {} signals",
                s.len()
            ));
            break;
        }
    }
    if names.is_empty() {
        for (var, v) in &vars {
            match vector(v) {
                Some(d) if !d.is_empty() => {
                    names.push(var.clone());
                    columns.push(d.to_vec());
                }
                _ => notes.push(format!("variable '{var}' is not a real vector: ignored")),
            }
        }
        if names.is_empty() {
            let list: Vec<&str> = vars.iter().map(|(n, _)| n.as_str()).collect();
            return Err(bad(128, format!("no capture found: no struct with X and Y (dSPACE) or time and signals (Simulink), and no real vector (variables: {})", list.join(", "))));
        }
        notes.push(format!(
            "{} vectors read by their variable names",
            names.len()
        ));
    }
    let n = columns[0].len();
    if let Some(k) = columns.iter().position(|c| c.len() != n) {
        return Err(bad(
            0,
            format!(
                "'{}' has {} samples, '{}' has {n}; every signal needs one sample per time",
                names[k],
                columns[k].len(),
                names[0]
            ),
        ));
    }
    if let Some((k, i)) = columns
        .iter()
        .enumerate()
        .find_map(|(k, c)| c.iter().position(|v| !v.is_finite()).map(|i| (k, i)))
    {
        return Err(bad(
            0,
            format!(
                "'{}' sample {} is {}, not a finite number",
                names[k],
                i + 1,
                columns[k][i]
            ),
        ));
    }
    let meta = vars
        .iter()
        .map(|(n, _)| Meta {
            line: 0,
            key: "variable".into(),
            value: n.clone(),
        })
        .collect();
    notes.push("a .mat file has no lines: rows are numbered by sample (1, 2, …)".into());
    Ok(channel_table(
        "matV5",
        "none",
        names,
        columns,
        (1..=n).collect(),
        meta,
        notes,
        opts,
    ))
}
