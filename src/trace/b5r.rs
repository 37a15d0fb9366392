//! Renishaw ball-bar results files (`.b5r`, XML), as Renishaw's Ballbar 20
//! software saves a QC10/QC20 test: the test's settings and the features
//! its analysis reports, read so that they can be shown beside ours.
//!
//! Layout read. Renishaw publishes no description of `.b5r`; the layout
//! here is the one two independent public readers of real files rely on
//! (a C# importer, `B5rXmlService`/`B5rAxisMapping`, and a TypeScript
//! upload check, `parseBallbarMetrics`, both found by code search), and a
//! generator of test files in the same layout:
//! - root `TEST_DOCUMENT`; `TEST_SPEC[@NAME]` (the test's name), holding
//!   `INSTRUMENT[@MANUFACTURER, @MODEL]/DYNAMIC_BALLBAR` with
//!   `NOMINAL_LENGTH` (the bar length, mm: the circle's radius),
//!   `PROGRAMMED_FEEDRATE` (mm/min) and `PLANE[@TEST_PLANE]` (`XY`, `ZX`,
//!   …) with `A_AXIS_NAME`, `B_AXIS_NAME`;
//! - `OPERATOR`, `DATE_STARTED`, `DATE_COMPLETED`,
//!   `MACHINE_TESTED[@NAME]`, `SERIAL_NUMBER`, `LAST_CALIBRATED`,
//!   `PART_NUMBER`: kept as metadata, text as written;
//! - `RUN_RESULTS/BALLBAR_RUN`, each with `RUN_DIRECTION` (`CW`/`CCW`)
//!   and its `FEATURE`s (e.g. `AF_CIRCULARITY`, `AF_CALCULATED_FEEDRATE`);
//! - `ANALYSIS[@NAME]` (e.g. `RENISHAW_DIAGNOSTICS`) with its `FEATURE`s:
//!   `AF_CIRCULARITY`, `AF_SQUARENESS`, `AF_SERVO_MISMATCH`,
//!   `AF_SCALE_MISMATCH`, `AF_STRAIGHTNESS_A/B`,
//!   `AF_BACKLASH_{A,B}_{POS,NEG}`, `AF_LATERAL_PLAY_…`,
//!   `AF_REVERSAL_SPIKES_…`, `AF_CYCLIC_ERROR_{A,B}_FWD`, …;
//! - a `FEATURE` is `<FEATURE NAME="…" DT="…">value</FEATURE>`, `DT` its
//!   unit code: `UT_LENGTH_UM` µm, `UT_LENGTH_MM` mm, `UT_LENGTH_M` m,
//!   `UT_FEEDRATE` mm/min, `UT_SPEED` mm/s, `UT_SQUARENESS` µm/m,
//!   `UT_SERVO_MISMATCH` ms, `UT_ANGLE` deg, `UT_PERCENT` %,
//!   `UT_SCALE_ERROR` ppm, `UT_RANKING` (no unit), as the C# importer's
//!   table gives them.
//!
//! Readings chosen:
//! - every `FEATURE` is read with its name, unit code and value as written
//!   (not converted; [`B5rFeature::unit`] names the unit, None for a code
//!   the table above does not list, which is then noted); a feature's
//!   value that is not a number is refused naming its line;
//! - `A`/`B` in a feature's name are the plane's first and second axis
//!   (`A_AXIS_NAME`, `B_AXIS_NAME`);
//! - **not read**: the raw samples. No public source says whether or how a
//!   `.b5r` carries the bar's readings, so none are read and no trace is
//!   made from the file; every element this reader does not know is listed
//!   by name and line in [`B5rReport::unread`], so a file that does carry
//!   them says where;
//! - inch settings are not known from any public source: the settings are
//!   read as mm and mm/min, as the public examples are.
//!
//! # Units
//! `radius` mm, `feed` mm/min; feature values as written, unit in
//! [`B5rFeature::unit`].

use serde::{Deserialize, Serialize};

use super::xml::{self, Element};
use super::TraceError;

/// The layout's name in messages.
pub const LAYOUT: &str = "Renishaw .b5r";

/// Unit codes (`DT`) and their units, as the public importer lists them.
pub const UNITS: [(&str, &str); 11] = [
    ("UT_LENGTH_UM", "µm"),
    ("UT_LENGTH_MM", "mm"),
    ("UT_LENGTH_M", "m"),
    ("UT_FEEDRATE", "mm/min"),
    ("UT_SPEED", "mm/s"),
    ("UT_SQUARENESS", "µm/m"),
    ("UT_SERVO_MISMATCH", "ms"),
    ("UT_ANGLE", "deg"),
    ("UT_PERCENT", "%"),
    ("UT_SCALE_ERROR", "ppm"),
    ("UT_RANKING", ""),
];

/// Metadata elements kept as text: (element, attribute holding the value
/// or None for the element's text).
const META: [(&str, Option<&str>); 8] = [
    ("OPERATOR", None),
    ("DATE_STARTED", None),
    ("DATE_COMPLETED", None),
    ("MACHINE_TESTED", Some("NAME")),
    ("SERIAL_NUMBER", None),
    ("LAST_CALIBRATED", None),
    ("PART_NUMBER", None),
    ("COMMENT", None),
];

/// One reported feature.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct B5rFeature {
    /// `NAME` as written, e.g. `AF_CIRCULARITY`.
    pub name: String,
    /// `DT` as written (the unit code), empty when the file gives none.
    pub dt: String,
    /// The unit the code stands for; None for a code not in [`UNITS`].
    pub unit: Option<String>,
    /// The value as written, in `unit`.
    pub value: f64,
    /// 1-based line of the `FEATURE`.
    pub line: usize,
}

/// One run's results.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct B5rRun {
    /// `RUN_DIRECTION` as written (`CW`, `CCW`), empty when missing.
    pub direction: String,
    /// Its features in file order.
    pub features: Vec<B5rFeature>,
    /// 1-based line of the `BALLBAR_RUN`.
    pub line: usize,
}

/// One analysis (`ANALYSIS[@NAME]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct B5rAnalysis {
    /// `NAME`, e.g. `RENISHAW_DIAGNOSTICS`.
    pub name: String,
    /// Its features in file order.
    pub features: Vec<B5rFeature>,
    /// 1-based line of the `ANALYSIS`.
    pub line: usize,
}

/// What a `.b5r` holds that this reader reads (module header).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct B5rReport {
    /// `TEST_SPEC/@NAME`.
    pub test_name: Option<String>,
    /// `INSTRUMENT/@MANUFACTURER` and `@MODEL`, joined by a space.
    pub instrument: Option<String>,
    /// `NOMINAL_LENGTH`: the bar length (the circle's radius), mm.
    pub radius: Option<f64>,
    /// `PROGRAMMED_FEEDRATE`, mm/min.
    pub feed: Option<f64>,
    /// `PLANE/@TEST_PLANE`, e.g. `XY`.
    pub plane: Option<String>,
    /// `A_AXIS_NAME`, `B_AXIS_NAME`: the axes `A` and `B` stand for.
    pub axes: Option<[String; 2]>,
    /// Metadata (operator, dates, machine, …) as (element, text).
    pub metadata: Vec<(String, String)>,
    /// Runs in file order.
    pub runs: Vec<B5rRun>,
    /// Analyses in file order.
    pub analyses: Vec<B5rAnalysis>,
    /// Elements not read, as "NAME (line N)": where raw samples would be
    /// if the file carries them.
    pub unread: Vec<String>,
    /// Notes in words: what was missing, unknown unit codes, and that no
    /// samples are read.
    pub notes: Vec<String>,
}

/// Errors of [`read`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum B5rError {
    /// Malformed XML, or XML that breaks the layout (names the line).
    #[error(transparent)]
    Trace(#[from] TraceError),
}

fn bad(line: usize, why: impl Into<String>) -> TraceError {
    TraceError::BadLayout {
        line,
        layout: LAYOUT,
        why: why.into(),
    }
}

/// The first element named `name` at or below `e`, depth first.
fn find<'a>(e: &'a Element, name: &str) -> Option<&'a Element> {
    if e.is(name) {
        return Some(e);
    }
    e.children.iter().find_map(|c| find(c, name))
}

/// The positive number in `e`'s text, or the error naming it.
fn positive(e: &Element, what: &str) -> Result<f64, TraceError> {
    e.text
        .parse::<f64>()
        .ok()
        .filter(|v| v.is_finite() && *v > 0.0)
        .ok_or_else(|| {
            bad(
                e.line,
                format!(
                    "<{}> '{}' is not a {what} > 0",
                    e.name,
                    super::clip(&e.text)
                ),
            )
        })
}

fn feature(e: &Element, notes: &mut Vec<String>) -> Result<B5rFeature, TraceError> {
    let name = e
        .attr("NAME")
        .filter(|n| !n.trim().is_empty())
        .ok_or_else(|| bad(e.line, "<FEATURE> has no NAME attribute"))?
        .to_string();
    let value = e
        .text
        .parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .ok_or_else(|| {
            bad(
                e.line,
                format!(
                    "<FEATURE NAME=\"{}\"> holds '{}', expected a number such as 12.5",
                    super::clip(&name),
                    super::clip(&e.text)
                ),
            )
        })?;
    let dt = e.attr("DT").unwrap_or("").to_string();
    let unit = UNITS
        .iter()
        .find(|(code, _)| code.eq_ignore_ascii_case(&dt))
        .map(|(_, u)| u.to_string());
    if unit.is_none() {
        notes.push(format!(
            "line {}: {name}: unit code DT='{}' is not one this reader knows: the value is shown as written, without a unit",
            e.line,
            super::clip(&dt)
        ));
    }
    Ok(B5rFeature {
        name,
        dt,
        unit,
        value,
        line: e.line,
    })
}

fn features(e: &Element, notes: &mut Vec<String>) -> Result<Vec<B5rFeature>, TraceError> {
    e.children
        .iter()
        .filter(|c| c.is("FEATURE"))
        .map(|c| feature(c, notes))
        .collect()
}

/// Reads a `.b5r` file's text.
///
/// # Units
/// See the module header.
///
/// # Errors
/// [`B5rError::Trace`]: [`TraceError::BadXml`] for malformed XML, [`TraceError::BadLayout`]
/// naming the line for XML whose root is not `TEST_DOCUMENT`, a feature
/// without a name or with a value that is not a number, or a bar length or
/// feed that is not a positive number. The wasm bindings check the text
/// against the trace budget first (`crate::budget::check_text`).
///
/// # Examples
/// ```
/// use mtmotion::trace::b5r::read;
/// let text = r#"<TEST_DOCUMENT><TEST_SPEC NAME="100mm XY">
/// <INSTRUMENT><DYNAMIC_BALLBAR><NOMINAL_LENGTH>100</NOMINAL_LENGTH>
/// <PROGRAMMED_FEEDRATE>1000</PROGRAMMED_FEEDRATE></DYNAMIC_BALLBAR></INSTRUMENT></TEST_SPEC>
/// <ANALYSIS NAME="RENISHAW_DIAGNOSTICS">
/// <FEATURE NAME="AF_SQUARENESS" DT="UT_SQUARENESS">-12.3</FEATURE>
/// </ANALYSIS></TEST_DOCUMENT>"#;
/// let r = read(text).unwrap();
/// assert_eq!((r.radius, r.feed), (Some(100.0), Some(1000.0)));
/// let f = &r.analyses[0].features[0];
/// assert_eq!((f.value, f.unit.as_deref(), f.line), (-12.3, Some("µm/m"), 5));
/// let e = read("<trace/>").unwrap_err().to_string();
/// assert!(e.starts_with("line 1: Renishaw .b5r: the root element is <trace>"), "{e}");
/// ```
pub fn read(text: &str) -> Result<B5rReport, B5rError> {
    Ok(read_checked(text)?)
}

fn read_checked(text: &str) -> Result<B5rReport, TraceError> {
    let root = xml::parse(text)?;
    if !root.is("TEST_DOCUMENT") {
        return Err(bad(
            root.line,
            format!(
                "the root element is <{}>, but a ball-bar results file's is <TEST_DOCUMENT>",
                super::clip(&root.name)
            ),
        ));
    }
    let mut notes = Vec::new();
    let spec = root.child("TEST_SPEC");
    let test_name = spec.and_then(|s| s.attr("NAME")).map(str::to_string);
    let instrument = spec.and_then(|s| find(s, "INSTRUMENT")).map(|i| {
        [i.attr("MANUFACTURER"), i.attr("MODEL")]
            .into_iter()
            .flatten()
            .collect::<Vec<_>>()
            .join(" ")
    });
    let bar = spec.and_then(|s| find(s, "DYNAMIC_BALLBAR"));
    if bar.is_none() {
        notes.push("no TEST_SPEC/INSTRUMENT/DYNAMIC_BALLBAR: the test's radius, feed and plane are not in the file".into());
    }
    let radius = bar
        .and_then(|b| b.child("NOMINAL_LENGTH"))
        .map(|e| positive(e, "bar length in mm"))
        .transpose()?;
    let feed = bar
        .and_then(|b| b.child("PROGRAMMED_FEEDRATE"))
        .map(|e| positive(e, "feed in mm/min"))
        .transpose()?;
    let plane_el = bar.and_then(|b| b.child("PLANE"));
    let plane = plane_el
        .and_then(|p| p.attr("TEST_PLANE"))
        .map(str::to_string);
    let axes = plane_el.and_then(|p| {
        let a = p.child("A_AXIS_NAME")?.text.clone();
        let b = p.child("B_AXIS_NAME")?.text.clone();
        Some([a, b])
    });
    let mut metadata = Vec::new();
    let mut unread = Vec::new();
    let mut runs = Vec::new();
    let mut analyses = Vec::new();
    for c in &root.children {
        if c.is("TEST_SPEC") {
            continue;
        }
        if let Some((name, attr)) = META.iter().find(|(n, _)| c.is(n)) {
            let v = match attr {
                Some(a) => c.attr(a).unwrap_or_default(),
                None => &c.text,
            };
            metadata.push((name.to_string(), v.to_string()));
        } else if c.is("RUN_RESULTS") {
            for r in &c.children {
                if !r.is("BALLBAR_RUN") {
                    unread.push(format!("{} (line {})", r.name, r.line));
                    continue;
                }
                runs.push(B5rRun {
                    direction: r
                        .child("RUN_DIRECTION")
                        .map(|d| d.text.clone())
                        .unwrap_or_default(),
                    features: features(r, &mut notes)?,
                    line: r.line,
                });
            }
        } else if c.is("ANALYSIS") {
            analyses.push(B5rAnalysis {
                name: c.attr("NAME").unwrap_or_default().to_string(),
                features: features(c, &mut notes)?,
                line: c.line,
            });
        } else {
            unread.push(format!("{} (line {})", c.name, c.line));
        }
    }
    if runs.is_empty() && analyses.is_empty() {
        notes.push(
            "no RUN_RESULTS/BALLBAR_RUN and no ANALYSIS: the file reports no features".into(),
        );
    }
    notes.push("the raw samples are not read: no public description says whether or how a .b5r carries them; export the trace as text to analyse it here".into());
    Ok(B5rReport {
        test_name,
        instrument,
        radius,
        feed,
        plane,
        axes,
        metadata,
        runs,
        analyses,
        unread,
        notes,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const FILE: &str = r#"<?xml version="1.0" encoding="utf-8"?>
<TEST_DOCUMENT>
  <TEST_SPEC NAME="150mm ZX 2000" version="2.0">
    <INSTRUMENT MANUFACTURER="Renishaw" MODEL="QC20-W">
      <DYNAMIC_BALLBAR>
        <NOMINAL_LENGTH>150</NOMINAL_LENGTH>
        <PROGRAMMED_FEEDRATE>2000</PROGRAMMED_FEEDRATE>
        <PLANE VIEW="+A+B" TEST_PLANE="ZX">
          <A_AXIS_NAME>Z</A_AXIS_NAME>
          <B_AXIS_NAME>X</B_AXIS_NAME>
        </PLANE>
      </DYNAMIC_BALLBAR>
    </INSTRUMENT>
  </TEST_SPEC>
  <OPERATOR>A. Fitter</OPERATOR>
  <MACHINE_TESTED NAME="VMC-7"/>
  <RUN_RESULTS>
    <BALLBAR_RUN>
      <RUN_DIRECTION>CW</RUN_DIRECTION>
      <FEATURE NAME="AF_CIRCULARITY" DT="UT_LENGTH_MM">0.0123</FEATURE>
    </BALLBAR_RUN>
    <NOTE_RUN/>
  </RUN_RESULTS>
  <ANALYSIS NAME="RENISHAW_DIAGNOSTICS">
    <FEATURE NAME="AF_BACKLASH_A_POS" DT="UT_LENGTH_UM">1.5</FEATURE>
    <FEATURE NAME="AF_RANK" DT="UT_FANCY">3</FEATURE>
  </ANALYSIS>
  <CAPTURE line="x"/>
</TEST_DOCUMENT>
"#;

    #[test]
    fn settings_runs_analyses_and_what_is_not_read() {
        let r = read(FILE).unwrap();
        assert_eq!(r.test_name.as_deref(), Some("150mm ZX 2000"));
        assert_eq!(r.instrument.as_deref(), Some("Renishaw QC20-W"));
        assert_eq!((r.radius, r.feed), (Some(150.0), Some(2000.0)));
        assert_eq!(r.plane.as_deref(), Some("ZX"));
        assert_eq!(r.axes, Some(["Z".to_string(), "X".to_string()]));
        assert_eq!(
            r.metadata,
            [
                ("OPERATOR".to_string(), "A. Fitter".to_string()),
                ("MACHINE_TESTED".to_string(), "VMC-7".to_string())
            ]
        );
        assert_eq!(r.runs.len(), 1);
        assert_eq!((r.runs[0].direction.as_str(), r.runs[0].line), ("CW", 18));
        let c = &r.runs[0].features[0];
        assert_eq!(
            (c.name.as_str(), c.value, c.unit.as_deref(), c.line),
            ("AF_CIRCULARITY", 0.0123, Some("mm"), 20)
        );
        assert_eq!(r.analyses.len(), 1);
        assert_eq!(
            (r.analyses[0].name.as_str(), r.analyses[0].line),
            ("RENISHAW_DIAGNOSTICS", 24)
        );
        let f = &r.analyses[0].features;
        assert_eq!((f[0].unit.as_deref(), f[0].value), (Some("µm"), 1.5));
        assert_eq!((f[1].unit.as_deref(), f[1].dt.as_str()), (None, "UT_FANCY"));
        assert_eq!(r.unread, ["NOTE_RUN (line 22)", "CAPTURE (line 28)"]);
        assert!(r.notes[0].starts_with("line 26: AF_RANK: unit code DT='UT_FANCY'"));
        assert!(r.notes[1].starts_with("the raw samples are not read"));
        assert_eq!(r.notes.len(), 2);
    }

    #[test]
    fn a_file_without_settings_or_features_says_so() {
        let r = read("<TEST_DOCUMENT>\n<OPERATOR>x</OPERATOR>\n</TEST_DOCUMENT>").unwrap();
        assert_eq!(
            (r.radius, r.feed, r.plane, r.axes),
            (None, None, None, None)
        );
        assert!(r.notes[0].starts_with("no TEST_SPEC/INSTRUMENT/DYNAMIC_BALLBAR"));
        assert!(r.notes[1].starts_with("no RUN_RESULTS/BALLBAR_RUN and no ANALYSIS"));
        assert_eq!(r.notes.len(), 3);
        // a run alone, or an analysis alone, reports features
        for one in [
            "<RUN_RESULTS><BALLBAR_RUN/></RUN_RESULTS>",
            "<ANALYSIS NAME=\"A\"/>",
        ] {
            let r = read(&format!("<TEST_DOCUMENT>{one}</TEST_DOCUMENT>")).unwrap();
            assert_eq!(r.notes.len(), 2, "{one}");
        }
    }

    #[test]
    fn refusals_name_the_line_and_cause() {
        let cases = [
            (
                "<a>\n<b></a>",
                "line 2: XML: </a> closes <b> (opened on line 2); close <b> first",
            ),
            (
                "\n<traceData/>",
                "line 2: Renishaw .b5r: the root element is <traceData>, but a ball-bar results file's is <TEST_DOCUMENT>",
            ),
            (
                "<TEST_DOCUMENT>\n<ANALYSIS>\n<FEATURE DT=\"UT_LENGTH_UM\">1</FEATURE></ANALYSIS></TEST_DOCUMENT>",
                "line 3: Renishaw .b5r: <FEATURE> has no NAME attribute",
            ),
            (
                "<TEST_DOCUMENT>\n<ANALYSIS>\n<FEATURE NAME=\" \">1</FEATURE></ANALYSIS></TEST_DOCUMENT>",
                "line 3: Renishaw .b5r: <FEATURE> has no NAME attribute",
            ),
            (
                "<TEST_DOCUMENT><RUN_RESULTS><BALLBAR_RUN>\n\n<FEATURE NAME=\"AF_CIRCULARITY\">1,5</FEATURE></BALLBAR_RUN></RUN_RESULTS></TEST_DOCUMENT>",
                "line 3: Renishaw .b5r: <FEATURE NAME=\"AF_CIRCULARITY\"> holds '1,5', expected a number such as 12.5",
            ),
            (
                "<TEST_DOCUMENT><ANALYSIS><FEATURE NAME=\"X\">inf</FEATURE></ANALYSIS></TEST_DOCUMENT>",
                "line 1: Renishaw .b5r: <FEATURE NAME=\"X\"> holds 'inf', expected a number such as 12.5",
            ),
            (
                "<TEST_DOCUMENT><TEST_SPEC><INSTRUMENT><DYNAMIC_BALLBAR>\n<NOMINAL_LENGTH>0</NOMINAL_LENGTH></DYNAMIC_BALLBAR></INSTRUMENT></TEST_SPEC></TEST_DOCUMENT>",
                "line 2: Renishaw .b5r: <NOMINAL_LENGTH> '0' is not a bar length in mm > 0",
            ),
            (
                "<TEST_DOCUMENT><TEST_SPEC><INSTRUMENT><DYNAMIC_BALLBAR>\n\n<PROGRAMMED_FEEDRATE>NaN</PROGRAMMED_FEEDRATE></DYNAMIC_BALLBAR></INSTRUMENT></TEST_SPEC></TEST_DOCUMENT>",
                "line 3: Renishaw .b5r: <PROGRAMMED_FEEDRATE> 'NaN' is not a feed in mm/min > 0",
            ),
        ];
        for (text, want) in cases {
            // a line after each fault, so a message that names the last
            // line whatever the fault cannot pass
            let text = format!("{text}\n<!-- more -->\n");
            assert_eq!(read(&text).unwrap_err().to_string(), want, "{text}");
        }
    }
}
