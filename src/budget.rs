//! Work budgets: the most work one call may do, in one place.
//!
//! Every entry point estimates its work from its input (text bytes and
//! lines, samples × series, harmonics, ranges × samples, runs × points)
//! *before* it starts, and refuses above a budget with a [`BudgetError`]
//! that names the quantity, the estimate, the limit and what to change.
//! The estimate is arithmetic on the input's sizes, so a refusal costs
//! microseconds, not the work it avoids.
//!
//! The limits are chosen so that no call needs more than about 512 MB of
//! memory or 10 s, except NC programs: they are bounded by what a 1 GB wasm
//! memory holds (see the NC budgets below). Measured with the wasm build in
//! Node on the project's 2-core build machine, while other builds shared
//! it: a 2 M-sample tool path 4.3 s and 276 MiB of wasm memory, a 1
//! M-sample feed-vector test 4.7 s and 161 MiB, a 10 M-point travel-range
//! sweep 2.1 s and 52 MiB. docs/budgets.md lists them, with what each
//! counts; docs/performance.md gives the NC measurements
//! (`bench/node/large-program.bench.mjs`).
//!
//! Source: none (engineering limits, not a model).

/// Largest text one argument may be, bytes (UTF-8): an NC program (with
/// its files), and any file the page is given (`checkFileSize`), which may
/// be a program. 64 MiB is a 2 M-line finishing program of 32 characters
/// a line. Traces are held to [`MAX_TRACE_BYTES`].
pub const MAX_TEXT_BYTES: usize = 64 << 20;

/// Largest trace text, bytes (UTF-8): 8 MiB is 100,000 lines of 80
/// characters.
pub const MAX_TRACE_BYTES: usize = 8 << 20;

/// Most lines in one trace (each row is parsed into numbers of every
/// column; 100,000 rows: about 1 s).
pub const MAX_LINES: usize = 100_000;

/// Most lines in one NC program and its files: each line is a block held
/// while the program runs (calls and jumps may go back to any), about 72 B
/// of wasm memory with no words (4 M: 290 MB). A program's time and the
/// rest of its memory are counted by [`MAX_NC_WORDS`], the executed
/// blocks and the segments.
pub const MAX_NC_LINES: usize = 4_000_000;

/// Most address words (`X12.5`, `G1`, …) in one NC program and its files,
/// counted as they are lexed: each is about 48 B of wasm memory (32 B and
/// its number as written, kept for writing the program back), and the
/// lexing time grows with them (10 M words: about 480 MB). A 2 M-line
/// finishing program with X, Y and Z on every G1 line has about 8 M.
pub const MAX_NC_WORDS: usize = 10_000_000;

/// Most NC blocks one program may execute, subprogram and cycle repeats
/// included (the interpreter's time: a 2 M-line program executes 2 M).
pub const MAX_EXECUTED_BLOCKS: usize = 4_000_000;

/// Most segments (moves and dwells) one NC program may give: 176 B of
/// wasm memory each (2.5 M: 440 MB). Most blocks give one, but a
/// canned-cycle block gives several per hole (2–3 per peck, up to
/// `nc::cycles::MAX_PECKS` pecks, K/L up to 9,999 holes), so without this
/// one G83 line could ask for 3·10⁸ segments (60 GB).
pub const MAX_SEGMENTS: usize = 2_500_000;

/// Most segments one tool-path simulation (or reverse compensation) may
/// simulate, as many as one program may give ([`MAX_SEGMENTS`]). Each
/// holds wasm memory while the run lasts: its timed command (184 B), its
/// reference-path element (200 B) and hierarchy share (about 32 B), its
/// running statistics (24 B, and 112 B more for reverse compensation's
/// halves), besides the program's own segment (168 B, which
/// `simulateToolPathColumns` drops once the path is built); the statistics
/// returned are 45 B as columns (`simulateToolPathColumns`, what the page
/// calls) or 176 B and a JS object each (`simulateToolPath`). So 2 M
/// segments need about 1.3 GB with columns (the 2 M-line program of
/// `bench/node/large-program.bench.mjs`, docs/performance.md §8) and
/// 2.5 M about 1.6 GB, within the 4 GB a wasm memory may grow to; the
/// samples are budgeted apart ([`MAX_TOOLPATH_SAMPLES`]).
pub const MAX_TOOLPATH_SEGMENTS: usize = MAX_SEGMENTS;

/// Loop iterations (backward jumps: END, endwhile, GOTO back) a macro
/// program may make before it is stopped as endless. A quarter of
/// [`MAX_EXECUTED_BLOCKS`], so that a loop (at least its head and its end
/// are blocks) meets this limit, which names the loop's line, before the
/// executed-block limit; far above a real part program (a 1,000-hole
/// pattern with 100 passes).
pub const MAX_LOOP_ITERATIONS: usize = MAX_EXECUTED_BLOCKS / 4;

/// Most numbers in one JS argument (a config or an array), counted over
/// its whole nesting: 8 M numbers are 64 MB in wasm memory.
pub const MAX_ARGUMENT_VALUES: usize = 8_000_000;

/// Longest name one argument may be: a preset, an axis, a reading, a
/// method, a file or column name, an object key. Checked before the name
/// is copied into wasm memory; no real name is near it.
pub const MAX_NAME_CHARS: usize = 1000;

/// Most keys of one object in a JS argument: no config has more (tool
/// radii, error symbols and axes are the largest maps, and tool radii are
/// held to [`MAX_TOOL_RADII`]). Checked as the keys are listed, before any
/// value is copied.
pub const MAX_OBJECT_KEYS: usize = 10_000;

/// Most samples of one tool-path simulation (5.5 h of motion at dt = 1 ms).
/// The run is measured sample by sample and keeps at most
/// [`MAX_TOOLPATH_SERIES`] samples of its series, so its memory does not
/// grow with it; its time does (about 0.1–0.2 µs per sample in wasm).
pub const MAX_TOOLPATH_SAMPLES: usize = 20_000_000;

/// Most samples in the series one tool-path simulation returns: 17 series
/// of f64 and the sample's segment index (140 B per sample), so about
/// 140 MB in wasm memory and as much again as JS arrays. A longer run keeps, of each group of consecutive
/// samples, the one with the largest contour error.
pub const MAX_TOOLPATH_SERIES: usize = 1_000_000;

/// Checks NC texts read in one call together (a program and its files):
/// their count against [`MAX_FILES`], then their bytes and lines summed
/// against [`MAX_TEXT_BYTES`] and [`MAX_NC_LINES`], each text's bytes
/// first, so that 20 files of 10 MB are refused before any is read. Their
/// words are counted as they are lexed ([`MAX_NC_WORDS`]).
///
/// # Examples
/// ```
/// use mtmotion::budget::check_texts;
/// let line = "G1\n".repeat(3_000_000);
/// assert!(check_texts("program and files", [line.as_str()]).is_ok());
/// let e = check_texts("program and files", [line.as_str(), line.as_str()]).unwrap_err();
/// assert_eq!(e.unit, "lines");
/// ```
pub fn check_texts<'a>(
    what: &'static str,
    texts: impl IntoIterator<Item = &'a str> + Clone,
) -> Result<(), BudgetError> {
    let count = texts.clone().into_iter().count();
    check(
        what,
        count as u64,
        MAX_FILES,
        "texts",
        "give fewer files at once",
    )?;
    let bytes: u64 = texts.clone().into_iter().map(|t| t.len() as u64).sum();
    check_bytes(what, bytes)?;
    let n: u64 = texts.into_iter().map(|t| lines(t) as u64).sum();
    check_nc_lines(what, n)
}

/// Checks the lines of NC texts, `n`, against [`MAX_NC_LINES`] (as
/// [`check_texts`]; the NC stream counts them as its bytes come).
pub fn check_nc_lines(what: &'static str, n: u64) -> Result<(), BudgetError> {
    check(
        what,
        n,
        MAX_NC_LINES,
        "lines",
        "split the program into parts and run each",
    )
}

/// Most samples of one constant-feed-speed-vector test: it keeps 15
/// series plus the three axis simulations (about 300 B per sample).
pub const MAX_FEED_VECTOR_SAMPLES: usize = 1_000_000;

/// Most worm-gear pitch-error harmonics on one axis: kato's gear shows 4;
/// each harmonic costs one `sin` per simulation step.
pub const MAX_PITCH_HARMONICS: usize = 64;

/// Most resampled points × orders of one pitch-error identification
/// (`samples` per revolution × whole revolutions × (`maxOrder` + 1)): each
/// is one multiply-add of the DFT at the integer orders.
pub const MAX_PITCH_DFT_TERMS: usize = 1_000_000_000;

/// Most (travel ranges × samples per revolution) of one travel-range or
/// angle sweep: each sample enters one least-squares fit.
pub const MAX_SWEEP_POINTS: usize = 10_000_000;

/// Most work of one alignment band: samples over all sections times the
/// square of the coefficients (2·maxOrder + 1), the cost of the streaming
/// least squares of [`crate::alignment::section_fit`] (at the default order
/// 10: 2.2 M samples).
pub const MAX_ALIGNMENT_WORK: usize = 1_000_000_000;

/// Most runs in one ISO 230-4 circular test (a run is one direction of
/// one circle; a test has 2).
pub const MAX_CIRCULAR_RUNS: usize = 64;

/// Most points over all runs of one circular test (its angle and
/// deviation arrays are 4 M numbers, half the argument budget).
pub const MAX_CIRCULAR_POINTS: usize = 2_000_000;

/// Most simulated samples of one reverse compensation's correction
/// rounds and dwell trials, over all their windows: a round simulates only
/// windows around the places it changes (`toolpath::locality`), so this is
/// a budget on corrected places, not on the program's length; the rounds
/// stop early, keeping their best so far, when the next would exceed it.
/// A program's budget is [`REVERSE_SAMPLES_PER_SEGMENT`] per segment,
/// at least [`MIN_REVERSE_SIMULATED_SAMPLES`] and at most this.
/// The whole-program simulations (the original and the checks of the
/// written program) are budgeted apart ([`MAX_REVERSE_CHECK_SAMPLES`],
/// [`MAX_TOOLPATH_SAMPLES`] each). About 0.6 µs per simulated sample in
/// the wasm build.
pub const MAX_REVERSE_SIMULATED_SAMPLES: usize = 16_000_000;

/// The window samples a reverse compensation may spend per segment of
/// the program (see [`MAX_REVERSE_SIMULATED_SAMPLES`]): a longer program
/// has more places to correct. Measured natively at dt 2 ms: the CAMotics
/// botomata pocket (6,216 segments, every corner corrected, each round's
/// windows about 2.45 M of its 2.84 M samples) spent 16 M window samples
/// for ×0.028 in 4.95 s and 8 M for ×0.032 in 3.18 s; the 35,288-line
/// cameo raster fell to ×0.852 at 8 M (×0.062 at 16 M).
pub const REVERSE_SAMPLES_PER_SEGMENT: usize = 400;

/// The window samples a reverse compensation may spend, in simulations of
/// the whole program, when that is more than its segments' share
/// ([`REVERSE_SAMPLES_PER_SEGMENT`]): a finer `dt` or a longer motion time
/// makes every window longer in samples. Botomata at dt 1 ms (5.7 M
/// samples a simulation) was returned unchanged with 8 M window samples.
pub const REVERSE_PROGRAM_SIMULATIONS: usize = 3;

/// The least window budget of a reverse compensation (see
/// [`REVERSE_SAMPLES_PER_SEGMENT`]).
pub const MIN_REVERSE_SIMULATED_SAMPLES: usize = 8_000_000;

/// Most samples of the checks of one reverse compensation's written
/// program (each a whole-program simulation against the original path),
/// or two simulations of the program when that is more: a small program
/// is checked up to five times (each check may revert regions), a large
/// one at least twice.
pub const MAX_REVERSE_CHECK_SAMPLES: usize = 8_000_000;

/// Most servo steps of one cone-frustum test, over all its simulated axes
/// (each axis is simulated at 1 ms or finer for the whole revolution): a
/// feed of 1 mm/min took 47 M steps, 19.8 s and 1.8 GB. About 50 B and
/// 0.4 µs per step in wasm.
pub const MAX_CONE_FRUSTUM_STEPS: usize = 5_000_000;

/// Most terms of one synthetic ball-bar trace: samples × directions ×
/// (1 + harmonics); each harmonic costs one `sin` per sample (1e7 samples
/// with 64 harmonics took 30 s).
pub const MAX_SYNTHETIC_TERMS: usize = 100_000_000;

/// Most load inertias of one torque-saturation study: each runs a C-axis
/// simulation (Fig. 21 has a handful; 1e6 took 22 s).
pub const MAX_SATURATION_LOADS: usize = 1000;

/// Most servo steps of one torque-saturation study, over all its loads
/// (loads × the steps of each load's C-axis run, which grow as 1/dt): 1000
/// loads at dt = 10 µs were 35 M steps and 2.1 s in wasm (about 0.06 µs a
/// step); without this, 1000 loads at the finest dt asked for 3.5·10⁸.
pub const MAX_SATURATION_STEPS: usize = 50_000_000;

/// Most terms of one axis simulation (`simulateAxis`): samples × (1 +
/// worm-gear pitch-error harmonics), each harmonic one `sin` per sample
/// (8 M samples with 64 harmonics took 22 s; 8 M samples alone 0.9 s).
pub const MAX_AXIS_SIM_TERMS: usize = 100_000_000;

/// Most simulated samples of one axis identification (`identifyAxis`):
/// the trace's samples × the fit's simulations so far (one per trial, one
/// more per free parameter where a trial is accepted), counted as the fit
/// runs; the fit is refused when the next simulation would pass it. A
/// 1 M-sample trace fitted in 5 iterations (about 25 simulations) in 2.4 s;
/// the fit may take up to 600 iterations. At 50 M a 4 M-sample trace was
/// refused after 3.7-6.4 s of simulations.
pub const MAX_IDENTIFY_SAMPLES: usize = 30_000_000;

/// Most moves of one 5-axis compensation (`compensateNc5`): each G0/G1 end
/// point is solved and written out (canned cycles and subprogram calls
/// expanded), then the written program is read back and evaluated.
/// 100,000 moves took 4.0 s at load 5 and 8.8 s at load 11 (243 MiB of
/// wasm memory), 200,000 moves 10.3 s and 481 MiB.
pub const MAX_NC5_MOVES: usize = 50_000;

/// Most lines of a program given to `compensateNc5`, checked before it is
/// read (the program and its compensated copy are both parsed).
pub const MAX_NC5_LINES: usize = 100_000;

/// Most work of one circular test's cyclic-error search: pitches on its
/// grid (about 2π·R₀ per mm of bar length R₀) × the trace's points merged
/// by angle (at most 18,000 bins): R₀ = 10 m with 2 × 10⁵ points was
/// 1.1·10⁹ and took 17.6 s in wasm (about 16 ns per unit).
pub const MAX_CYCLIC_SEARCH_WORK: usize = 200_000_000;

/// Most sections (measured heights) of one alignment estimate, band or
/// angle sweep: a section is one ball-bar measurement; the paper uses two.
pub const MAX_SECTIONS: usize = 1000;

/// Most harmonics of one motion-error model (a synthetic ball-bar trace, a
/// travel-range or angle sweep): orders above a few hundred are below any
/// ball bar's resolution, and each costs one `sin` per sample.
pub const MAX_HARMONICS: usize = 256;

/// Most measured circles of one acc/dec identification (qiu Eq. 3; the
/// paper fits four).
pub const MAX_ACCDEC_CIRCLES: usize = 10_000;

/// Most tool radii (D numbers) one program may be given.
pub const MAX_TOOL_RADII: usize = 1000;

/// Most program texts or extra files of one call (`ncMainFile`,
/// `files` of parseNc); their bytes and lines together are held to
/// [`MAX_TEXT_BYTES`] and [`MAX_NC_LINES`].
pub const MAX_FILES: usize = 1000;

/// A list in a JS argument held to a budget by its length (or, for a map
/// such as tool radii, by its number of keys). The JS boundary checks it
/// before it copies a single item (`src/wasm/convert.rs`): a list of 10⁶
/// small objects took 3–9 s to copy before the core could count it. The
/// core checks the same limits on the data it is given.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ListBudget {
    /// The key the list is found under (at any depth), e.g. `pitchError`.
    pub key: &'static str,
    /// The limit.
    pub max: usize,
    /// What the items are, e.g. "harmonics".
    pub unit: &'static str,
    /// What to change.
    pub advice: &'static str,
    /// Counts the keys of an object (a map), not the items of an array.
    pub keys: bool,
}

impl ListBudget {
    /// `Ok` when `n ≤ max`, else the [`BudgetError`] naming `what`.
    pub fn check(&self, what: &'static str, n: usize) -> Result<(), BudgetError> {
        check(what, n as u64, self.max, self.unit, self.advice)
    }
}

/// Worm-gear pitch-error harmonics of an axis ([`MAX_PITCH_HARMONICS`]).
pub const PITCH_HARMONICS_LIST: ListBudget = ListBudget {
    key: "pitchError",
    max: MAX_PITCH_HARMONICS,
    unit: "harmonics",
    advice: "the work budget; a worm gear shows a handful",
    keys: false,
};

/// Harmonics of a motion-error model ([`MAX_HARMONICS`]).
pub const HARMONICS_LIST: ListBudget = ListBudget {
    key: "harmonics",
    max: MAX_HARMONICS,
    unit: "harmonics",
    advice: "orders above a few hundred are below any ball bar's resolution",
    keys: false,
};

/// Load inertias of a torque-saturation study ([`MAX_SATURATION_LOADS`]).
pub const SATURATION_LOADS_LIST: ListBudget = ListBudget {
    key: "j1",
    max: MAX_SATURATION_LOADS,
    unit: "load inertias",
    advice: "each runs a simulation of the C axis",
    keys: false,
};

/// Tool radii per D number, keys of a map ([`MAX_TOOL_RADII`]).
pub const TOOL_RADII_LIST: ListBudget = ListBudget {
    key: "toolRadii",
    max: MAX_TOOL_RADII,
    unit: "tool radii",
    advice: "give the radii of the D numbers the program uses",
    keys: true,
};

/// Extra program files ([`MAX_FILES`]).
pub const FILES_LIST: ListBudget = ListBudget {
    key: "files",
    max: MAX_FILES,
    unit: "texts",
    advice: "give fewer files at once",
    keys: false,
};

/// Runs of a circular test ([`MAX_CIRCULAR_RUNS`]).
pub const CIRCULAR_RUNS_LIST: ListBudget = ListBudget {
    key: "runs",
    max: MAX_CIRCULAR_RUNS,
    unit: "runs",
    advice: "test one circle (a CCW and a CW run) at a time",
    keys: false,
};

/// Sections of an alignment estimate ([`MAX_SECTIONS`]).
pub const SECTIONS_LIST: ListBudget = ListBudget {
    key: "sections",
    max: MAX_SECTIONS,
    unit: "sections",
    advice: "a section is one ball-bar measurement; the paper uses two",
    keys: false,
};

/// The lists of JS arguments bounded by key, wherever the key appears.
pub const LIST_BUDGETS: [ListBudget; 7] = [
    PITCH_HARMONICS_LIST,
    HARMONICS_LIST,
    SATURATION_LOADS_LIST,
    TOOL_RADII_LIST,
    FILES_LIST,
    CIRCULAR_RUNS_LIST,
    SECTIONS_LIST,
];

/// The circles of `identifyAccDec` (its argument is the list).
pub const ACCDEC_CIRCLES: ListBudget = ListBudget {
    key: "",
    max: MAX_ACCDEC_CIRCLES,
    unit: "circles",
    advice: "the fit needs a few circles at different F/R",
    keys: false,
};

/// The texts of `ncMainFile` (its argument is the list).
pub const MAIN_FILE_TEXTS: ListBudget = ListBudget {
    key: "",
    max: MAX_FILES,
    unit: "texts",
    advice: "give fewer files at once",
    keys: false,
};

/// Deserializes a list of at most [`MAX_PITCH_HARMONICS`] items, refusing
/// a longer one by its length before any item is read (when the format
/// knows the length, as the JS snapshot and JSON arrays do not always:
/// then at the first item past the limit).
pub fn at_most_pitch_harmonics<'de, D, T>(d: D) -> Result<Vec<T>, D::Error>
where
    D: serde::Deserializer<'de>,
    T: serde::Deserialize<'de>,
{
    struct Bounded<T>(std::marker::PhantomData<T>);
    impl<'de, T: serde::Deserialize<'de>> serde::de::Visitor<'de> for Bounded<T> {
        type Value = Vec<T>;
        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            write!(f, "a list of at most {MAX_PITCH_HARMONICS} harmonics")
        }
        fn visit_seq<A: serde::de::SeqAccess<'de>>(self, mut seq: A) -> Result<Vec<T>, A::Error> {
            let too_many = |n: usize| {
                serde::de::Error::custom(format!(
                    "{n} harmonics, more than the limit of {MAX_PITCH_HARMONICS} (the work budget; a worm gear shows a handful)"
                ))
            };
            if let Some(n) = seq.size_hint().filter(|&n| n > MAX_PITCH_HARMONICS) {
                return Err(too_many(n));
            }
            let mut out = Vec::new();
            while let Some(x) = seq.next_element()? {
                if out.len() == MAX_PITCH_HARMONICS {
                    return Err(too_many(out.len() + 1));
                }
                out.push(x);
            }
            Ok(out)
        }
    }
    d.deserialize_seq(Bounded(std::marker::PhantomData))
}

/// A refused call: the estimate of its work is above the budget.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{what}: {amount} {unit}, more than the limit of {limit}; {advice}")]
pub struct BudgetError {
    /// What was measured, e.g. "program text".
    pub what: &'static str,
    /// The estimate (64-bit, so a product of sizes does not wrap on wasm32).
    pub amount: u64,
    /// The limit.
    pub limit: usize,
    /// The unit of both, e.g. "bytes".
    pub unit: &'static str,
    /// What to change, e.g. "split the program".
    pub advice: &'static str,
}

/// `Ok` when `amount ≤ limit`, else the [`BudgetError`].
///
/// # Examples
/// ```
/// use mtmotion::budget::{check, MAX_LINES};
/// assert!(check("program", 10, MAX_LINES, "lines", "split it").is_ok());
/// let e = check("program", 300_000, MAX_LINES, "lines", "split it").unwrap_err();
/// assert_eq!(e.to_string(), "program: 300000 lines, more than the limit of 100000; split it");
/// ```
pub fn check(
    what: &'static str,
    amount: u64,
    limit: usize,
    unit: &'static str,
    advice: &'static str,
) -> Result<(), BudgetError> {
    if amount <= limit as u64 {
        Ok(())
    } else {
        Err(BudgetError {
            what,
            amount,
            limit,
            unit,
            advice,
        })
    }
}

/// Checks a trace's size in bytes ([`MAX_TRACE_BYTES`]), then its lines
/// ([`MAX_LINES`]; LF, CRLF or CR alone; a last line without an end
/// counts). The bytes are checked first, so the line count is one pass
/// over at most [`MAX_TRACE_BYTES`]. NC programs: [`check_texts`].
///
/// # Examples
/// ```
/// use mtmotion::budget::{check_text, lines};
/// assert!(check_text("trace", "a,b\n1,2\n").is_ok());
/// assert_eq!(lines("a\r\nb\rc"), 3);
/// assert!(check_text("trace", &"\r".repeat(300_000)).is_err());
/// ```
pub fn check_text(what: &'static str, text: &str) -> Result<(), BudgetError> {
    check_trace_texts(what, [text])
}

/// As [`check_text`] for several traces read in one call (an alignment
/// band's sections): their bytes, then their lines, summed over them all.
pub fn check_trace_texts<'a>(
    what: &'static str,
    texts: impl IntoIterator<Item = &'a str> + Clone,
) -> Result<(), BudgetError> {
    let bytes: u64 = texts.clone().into_iter().map(|t| t.len() as u64).sum();
    check(what, bytes, MAX_TRACE_BYTES, "bytes", TEXT_ADVICE)?;
    let n: u64 = texts.into_iter().map(|t| lines(t) as u64).sum();
    check(
        what,
        n,
        MAX_LINES,
        "lines",
        "split the file into parts and run each",
    )
}

/// What to change when a text is over [`MAX_TEXT_BYTES`].
pub const TEXT_ADVICE: &str = "split the file or remove what the calculation does not need";

/// Checks a text's size in bytes against [`MAX_TEXT_BYTES`] before it is
/// read: the page asks this of a dropped file's size, so a file the core
/// would refuse is never read into the page at all.
///
/// # Examples
/// ```
/// use mtmotion::budget::{check_bytes, MAX_TEXT_BYTES};
/// assert!(check_bytes("file", MAX_TEXT_BYTES as u64).is_ok());
/// let e = check_bytes("file", 100 << 20).unwrap_err();
/// assert!(e.to_string().starts_with("file: 104857600 bytes, more than the limit of 67108864"));
/// ```
pub fn check_bytes(what: &'static str, bytes: u64) -> Result<(), BudgetError> {
    check(what, bytes, MAX_TEXT_BYTES, "bytes", TEXT_ADVICE)
}

/// Number of lines of `text` (LF, CRLF or CR alone end a line).
pub fn lines(text: &str) -> usize {
    let bytes = text.as_bytes();
    let ends = bytes
        .iter()
        .enumerate()
        .filter(|&(i, &b)| b == b'\n' || (b == b'\r' && bytes.get(i + 1) != Some(&b'\n')))
        .count();
    ends + usize::from(!matches!(bytes.last(), None | Some(b'\n' | b'\r')))
}

/// Clips user text echoed in an error message to at most `max` characters
/// (an ellipsis marks the cut), so a message never repeats a huge input.
///
/// # Examples
/// ```
/// use mtmotion::budget::clip;
/// assert_eq!(clip("abc", 80), "abc");
/// assert_eq!(clip(&"x".repeat(100), 10).chars().count(), 10);
/// ```
pub fn clip(text: &str, max: usize) -> String {
    if text.chars().count() <= max {
        return text.to_string();
    }
    let mut s: String = text.chars().take(max.saturating_sub(1)).collect();
    s.push('…');
    s
}

/// Clips every quoted run (`"…"` or `'…'`) of a message to at most `max`
/// characters: parsers quote the user's text, and a message must not
/// repeat a 50 MB input.
///
/// # Examples
/// ```
/// use mtmotion::budget::clip_quoted;
/// let m = format!("invalid value: string \"{}\", expected a number", "9".repeat(500));
/// assert!(clip_quoted(&m, 20).len() < 80);
/// assert_eq!(clip_quoted("unknown key 'ab'", 20), "unknown key 'ab'");
/// ```
pub fn clip_quoted(message: &str, max: usize) -> String {
    let mut out = String::with_capacity(message.len().min(4 * max + 200));
    let mut quote: Option<char> = None;
    let mut inside = 0usize;
    for c in message.chars() {
        match quote {
            Some(q) if c == q => {
                quote = None;
                out.push(c);
            }
            Some(_) => {
                inside += 1;
                if inside < max {
                    out.push(c);
                } else if inside == max {
                    out.push('…');
                }
            }
            None => {
                if c == '"' || c == '\'' {
                    quote = Some(c);
                    inside = 0;
                }
                out.push(c);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_limits_count_every_line_ending() {
        let ok = "G1 X1\n".repeat(MAX_LINES);
        assert!(check_text("p", &ok).is_ok());
        for end in ["\n", "\r\n", "\r"] {
            let long = format!("G1{end}").repeat(MAX_LINES + 1);
            let e = check_text("p", &long).unwrap_err();
            assert_eq!(e.unit, "lines", "{end:?}");
        }
        let big = "x".repeat(MAX_TRACE_BYTES + 1);
        assert_eq!(check_text("p", &big).unwrap_err().unit, "bytes");
    }

    #[test]
    fn program_texts_are_held_to_the_nc_budgets() {
        // A program may be far longer than a trace: 200,000 lines and
        // 9 MiB pass, the NC line budget is counted over all the texts,
        // and the bytes are checked before the lines.
        let long = "G1 X12.3456 Y65.4321 Z-1.2345 F1000\n".repeat(270_000);
        assert!(long.len() > MAX_TRACE_BYTES);
        assert!(check_texts("p", [long.as_str()]).is_ok());
        assert!(check_text("t", &long).is_err());
        let lines = "\n".repeat(MAX_NC_LINES / 2 + 1);
        let e = check_texts("p", [lines.as_str(), lines.as_str()]).unwrap_err();
        assert_eq!((e.unit, e.amount), ("lines", MAX_NC_LINES as u64 + 2));
        let big = "x".repeat(MAX_TEXT_BYTES / 2 + 1);
        let e = check_texts("p", [big.as_str(), big.as_str()]).unwrap_err();
        assert_eq!(e.unit, "bytes");
    }

    #[test]
    fn clip_keeps_short_text_and_cuts_long_text() {
        assert_eq!(clip("αβγ", 3), "αβγ");
        assert_eq!(clip("αβγδ", 3), "αβ…");
    }
}
