//! An NC program read as its bytes come, chunk by chunk (a file read
//! through a stream), so that its whole text is never held at once: each
//! run of complete lines is decoded, lexed by the lexer of [`super::lex_all`]
//! and dropped; only the unfinished last line waits for the next chunk.
//!
//! The result is the whole-text reading's, [`super::files::parse_files_owned`]
//! with no extra files, of the text the bytes decode to as UTF-8 with
//! every invalid sequence replaced by U+FFFD (what a browser's
//! `File.text()` and `TextDecoder` give, and `String::from_utf8_lossy`).
//! That holds for any cut of the bytes into chunks:
//! - a run ends after a line end (LF, CR or CRLF) that has a character
//!   other than a line end or Ctrl-Z after it, so a CRLF is never split,
//!   a multi-byte character or an invalid sequence never spans two runs
//!   (line ends are ASCII), and the line ends and Ctrl-Z characters the
//!   whole-text reading drops at the end ([`super::split_lines`]) are
//!   never read as lines before the end shows they are the last;
//! - the byte-order mark is dropped from the first run only;
//! - the binary-file check ([`super::unreadable`]) judges the first 512
//!   characters, as the whole-text check does, once they have come (a
//!   text whose start looks like a JPEG read as text waits for `JFIF` to
//!   the end, as the whole-text check searches all of it).
//!
//! Budgets: the text budgets of [`crate::budget::check_texts`] (bytes,
//! lines) are counted as the bytes come, and the word budget as the lines
//! are lexed; a refusal is the whole-text reading's message, at the line
//! where the count passed the limit (the whole-text reading names line 1,
//! having counted the whole text before reading it). A text within the
//! budgets gives exactly the whole-text result; one over them is refused
//! by both (the stream names the line, and may name another budget first).
//!
//! Source: none (the reading of text, not a model).

use super::files::{dialect_refusal, interpret_lexed};
use super::program::{Keep, ParseOptions, Program};
use super::{Block, NcError, NcErrors};
use crate::budget::{self, MAX_TEXT_BYTES};

/// Characters of the text's start the binary-file check judges
/// ([`crate::trace::binary_kind`]).
const HEAD_CHARS: usize = 512;

/// An NC program being read chunk by chunk: [`NcStream::push`] each chunk
/// of its bytes, then [`NcStream::finish`].
///
/// # Examples
/// ```
/// use mtmotion::nc::files::parse_files_owned;
/// use mtmotion::nc::program::{Keep, ParseOptions};
/// use mtmotion::nc::stream::NcStream;
/// let text = "%\r\nG0 X0 (Ø 10)\r\nG1 X10 F100\r\nM30\r\n%\r\n";
/// let mut s = NcStream::new();
/// for chunk in text.as_bytes().chunks(3) {
///     s.push(chunk).unwrap();
/// }
/// let o = ParseOptions::default();
/// let p = s.finish(&o, Keep::Motion).unwrap();
/// assert_eq!(p, parse_files_owned(text.into(), vec![], &o, Keep::Motion).unwrap());
/// assert_eq!(p.segments[1].end.x, 10.0);
/// ```
#[derive(Debug, Default)]
pub struct NcStream {
    /// The bytes not yet read: the unfinished last line, and the line
    /// ends and Ctrl-Z characters that may be the text's last.
    pending: Vec<u8>,
    /// Bytes of the text read so far, decoded (as the whole text counts).
    read_bytes: u64,
    /// Lines read so far: the next is line `read_lines + 1`.
    read_lines: usize,
    /// Line ends in every byte pushed (a CR last pushed is counted once
    /// its next byte shows whether it begins a CRLF).
    line_ends: u64,
    /// The last byte pushed is a CR.
    cr_last: bool,
    /// The last byte pushed ends no line (the text has an unfinished line).
    open_line: bool,
    /// Address words lexed (the word budget's count).
    words: usize,
    blocks: Vec<Block>,
    errors: NcErrors,
    /// The start of the text after its byte-order marks, up to
    /// [`HEAD_CHARS`] characters, until the binary-file check is done.
    head: String,
    head_chars: usize,
    /// `JFIF` was seen (the JPEG-read-as-text check).
    jfif: bool,
    /// The binary-file check is done (the text is text).
    judged: bool,
    /// The refusal, if the text was refused, and whether it was refused
    /// as a whole (over the text budget, or not a text file).
    refused: Option<(NcErrors, bool)>,
    /// The text's length in bytes if known ([`NcStream::with_size_hint`]).
    expected_bytes: u64,
}

impl NcStream {
    /// A stream with nothing read.
    pub fn new() -> Self {
        Self::default()
    }

    /// A stream with nothing read that will be given about `total_bytes`
    /// bytes (a file's size): the block list is then sized from it and
    /// the lines read so far, once, instead of growing by doubling. Only
    /// the memory differs from [`NcStream::new`]: the result is the same
    /// whatever the hint (a wrong one costs a regrowth or unused room).
    ///
    /// Why: in wasm, whose memory never shrinks, each doubling of the
    /// list leaves a hole the program's interpretation fills with small
    /// blocks that outlive the list; the simulation's large blocks then
    /// found no room below the segments and grew the memory (the 2 M-line
    /// program of `bench/node/large-program.bench.mjs`: 940 MiB against
    /// the whole-text reading's 831; docs/performance.md).
    pub fn with_size_hint(total_bytes: u64) -> Self {
        Self {
            // a text over the budget is refused: no more room is made
            expected_bytes: total_bytes.min(MAX_TEXT_BYTES as u64),
            ..Self::default()
        }
    }

    /// Reads `bytes`, the next chunk of the program's text (any cut: a
    /// line, a character or a CRLF may be split between chunks): every
    /// line it completes is lexed.
    ///
    /// # Errors
    /// The text is refused: over the text budget (bytes or lines,
    /// [`budget::check_texts`]) or the word budget
    /// ([`budget::MAX_NC_WORDS`]), named at the line where the count
    /// passed the limit; or not a text file (an image, a PDF, an archive:
    /// line 1, as [`super::unreadable`]). Every later call gives the same
    /// error.
    pub fn push(&mut self, bytes: &[u8]) -> Result<(), NcErrors> {
        if let Some((e, _)) = &self.refused {
            return Err(e.clone());
        }
        self.count_line_ends(bytes);
        self.pending.extend_from_slice(bytes);
        if let Some(e) = self.over_budget(&self.pending, self.lines()) {
            return Err(self.refuse(e, true));
        }
        // The run: up to the last line end before the last byte that is no
        // line end or Ctrl-Z (a CR there is followed by a known byte).
        let ends = |b: &u8| matches!(b, b'\n' | b'\r');
        let Some(last) = self.pending.iter().rposition(|b| !ends(b) && *b != 0x1a) else {
            return Ok(());
        };
        let Some(end) = self.pending[..last].iter().rposition(ends) else {
            return Ok(());
        };
        let mut pending = std::mem::take(&mut self.pending);
        let read = self.read(&String::from_utf8_lossy(&pending[..=end]), false);
        pending.drain(..=end);
        self.pending = pending;
        read
    }

    /// Ends the text and interprets the program: the result of
    /// [`super::files::parse_files_owned`] on the whole text (no extra
    /// files), with the same `options` and `keep`.
    ///
    /// # Errors
    /// The program's errors, as the whole-text reading's; or the refusal
    /// of [`NcStream::push`] (the budgets are checked once more on the
    /// whole text, now known).
    pub fn finish(self, options: &ParseOptions, keep: Keep) -> Result<Program, NcErrors> {
        self.finish_noting_refusal(options, keep).0
    }

    /// As [`NcStream::finish`], and whether the text was refused as a
    /// whole (over the text budget, or not a text file; `checkNc`'s
    /// `notRead`) rather than for its lines.
    pub fn finish_noting_refusal(
        mut self,
        options: &ParseOptions,
        keep: Keep,
    ) -> (Result<Program, NcErrors>, bool) {
        if let Err(e) = self.read_tail() {
            let whole = self.refused.as_ref().is_some_and(|r| r.1);
            return (Err(e), whole);
        }
        let blocks = std::mem::take(&mut self.blocks);
        let errors = std::mem::take(&mut self.errors);
        (interpret_lexed(blocks, errors, options, keep), false)
    }

    /// Reads what is left once the text has ended.
    fn read_tail(&mut self) -> Result<(), NcErrors> {
        if let Some((e, _)) = &self.refused {
            return Err(e.clone());
        }
        let pending = std::mem::take(&mut self.pending);
        let tail = String::from_utf8_lossy(&pending);
        if let Some(e) = self.over_budget(tail.as_bytes(), self.lines()) {
            return Err(self.refuse(e, true));
        }
        self.read(&tail, true)
    }

    /// Lines in the bytes pushed: their line ends, and the last line if
    /// no line end ends it (or it ends in a CR, counted once the next
    /// byte is known).
    fn lines(&self) -> u64 {
        self.line_ends + u64::from(self.cr_last || self.open_line)
    }

    /// Adds the line ends of `bytes` (LF, CRLF or CR alone, as
    /// [`budget::lines`]) to the count.
    fn count_line_ends(&mut self, bytes: &[u8]) {
        for &b in bytes {
            if self.cr_last && b != b'\n' {
                self.line_ends += 1;
            }
            self.cr_last = b == b'\r';
            if b == b'\n' {
                self.line_ends += 1;
            }
        }
        if let Some(&b) = bytes.last() {
            self.open_line = !matches!(b, b'\n' | b'\r');
        }
    }

    /// The text budgets' refusal, if the text is over them, with `unread`
    /// bytes not yet read (the pending bytes, or the decoded tail) and
    /// `lines` lines known.
    fn over_budget(&self, unread: &[u8], lines: u64) -> Option<NcError> {
        let bytes = self.read_bytes + unread.len() as u64;
        let (e, line) = if let Err(e) = budget::check_bytes("program", bytes) {
            // the line holding the first byte over the limit
            let over = (MAX_TEXT_BYTES as u64).saturating_sub(self.read_bytes) as usize;
            (e, self.read_lines + 1 + line_ends_before(unread, over))
        } else if let Err(e) = budget::check_nc_lines("program", lines) {
            (e, budget::MAX_NC_LINES + 1)
        } else {
            return None;
        };
        Some(NcError::new(line, 1, e.to_string()))
    }

    /// Reads `text`, a run of complete lines (`last`: the rest of the
    /// text, which the whole-text reading trims at its end).
    fn read(&mut self, text: &str, last: bool) -> Result<(), NcErrors> {
        self.read_bytes += text.len() as u64;
        if let Some(kind) = self.judge(text, last) {
            let e = NcError::new(1, 1, super::not_text_message(kind));
            return Err(self.refuse(e, true));
        }
        let mut text = text;
        if self.read_lines == 0 {
            text = text.strip_prefix('\u{feff}').unwrap_or(text);
        }
        let lines = if last {
            let text = text.trim_end_matches(['\u{1a}', '\r', '\n']);
            let lines = crate::trace::split_line_ends(text);
            if lines.is_empty() && self.read_lines == 0 {
                vec![text]
            } else {
                lines
            }
        } else {
            crate::trace::split_line_ends(text)
        };
        let n = lines.len();
        self.reserve_blocks(n);
        let first = self.read_lines + 1;
        let over = super::lex_lines(
            lines,
            first,
            &mut self.words,
            &mut self.blocks,
            &mut self.errors,
        );
        self.read_lines += n;
        if over.is_err() {
            let errors = std::mem::take(&mut self.errors);
            let e = dialect_refusal(&errors).unwrap_or(errors);
            return Err(self.refuse_all(e, false));
        }
        Ok(())
    }

    /// Makes room for `n` more blocks (a run's lines): with
    /// a size hint, room for the lines the text's remaining bytes hold at
    /// the lines per byte read so far, and a tenth more (one allocation
    /// instead of doublings; see [`NcStream::with_size_hint`]).
    fn reserve_blocks(&mut self, n: usize) {
        let room = self.blocks.capacity() - self.blocks.len();
        if self.expected_bytes == 0 || n <= room {
            return;
        }
        let read = self.read_bytes.max(1) as f64;
        let lines_per_byte = (self.read_lines + n) as f64 / read;
        let left = self.expected_bytes.saturating_sub(self.read_bytes) as f64;
        if left == 0.0 {
            // more than the hint said: grow as without one (doubling)
            self.blocks.reserve(n);
            return;
        }
        let more = ((left * lines_per_byte * 1.1).ceil() as usize).min(budget::MAX_NC_LINES);
        self.blocks.reserve_exact(n + more);
    }

    /// The binary-file check on the text so far, `text` its newest run
    /// (`end`: the last): the kind of file when it is no text, once known.
    fn judge(&mut self, text: &str, end: bool) -> Option<&'static str> {
        if self.judged {
            return None;
        }
        for c in text.chars() {
            if self.head_chars == HEAD_CHARS {
                break;
            }
            if c == '\u{feff}' && self.head_chars == 0 {
                continue;
            }
            self.head.push(c);
            self.head_chars += 1;
        }
        self.jfif = self.jfif || text.contains("JFIF");
        let jpeg_as_text = self.head.starts_with("\u{fffd}\u{fffd}\u{fffd}") && !self.jfif;
        if !end && (self.head_chars < HEAD_CHARS || jpeg_as_text) {
            return None;
        }
        self.judged = true;
        let head = std::mem::take(&mut self.head);
        crate::trace::binary_kind_of_head(&head, || self.jfif)
    }

    /// Refuses the text with `e` (`whole`: as a whole) and frees what was
    /// read.
    fn refuse(&mut self, e: NcError, whole: bool) -> NcErrors {
        self.refuse_all(NcErrors::from(e), whole)
    }

    fn refuse_all(&mut self, e: NcErrors, whole: bool) -> NcErrors {
        self.blocks = Vec::new();
        self.pending = Vec::new();
        self.errors = NcErrors::default();
        self.refused = Some((e.clone(), whole));
        e
    }
}

/// Line ends (LF, CRLF or CR alone) in `bytes` before index `at`.
fn line_ends_before(bytes: &[u8], at: usize) -> usize {
    let at = at.min(bytes.len());
    (0..at)
        .filter(|&i| bytes[i] == b'\n' || (bytes[i] == b'\r' && bytes.get(i + 1) != Some(&b'\n')))
        .count()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 10,000 lines of 16 bytes, the same text as `n` whole lines.
    fn uniform(n: usize) -> Vec<u8> {
        (0..n)
            .flat_map(|i| format!("G1 X{i:05} Y1 Z0\n").into_bytes())
            .collect()
    }

    #[test]
    fn a_size_hint_sizes_the_block_list_once() {
        let text = uniform(10_000);
        assert_eq!(text.len(), 160_000);
        let mut s = NcStream::with_size_hint(text.len() as u64);
        let mut capacities = Vec::new();
        for c in text.chunks(4096) {
            s.push(c).unwrap();
            capacities.push(s.blocks.capacity());
        }
        s.read_tail().unwrap();
        capacities.push(s.blocks.capacity());
        assert_eq!(s.blocks.len(), 10_000);
        // sized at the first run (the 255 lines of its first 4,080 bytes:
        // the 256th line's end may be the text's last), for its lines
        // and 1.1 × the 155,920 bytes left at 16 bytes a line: 255 +
        // ⌈9,745 × 1.1⌉; never grown after
        let first = capacities[0];
        assert_eq!(first, 255 + 10_720);
        assert!(capacities.iter().all(|&c| c == first), "{capacities:?}");
        // without the hint the list grows by doubling: 16,384 blocks
        let mut s = NcStream::new();
        for c in text.chunks(4096) {
            s.push(c).unwrap();
        }
        s.read_tail().unwrap();
        assert_eq!(s.blocks.capacity(), 16_384);
    }

    #[test]
    fn lines_shorter_than_the_first_regrow_the_list_once_more() {
        // 300 lines of 32 bytes, then 5,000 of 16, told the exact length
        let mut text: Vec<u8> = (0..300)
            .flat_map(|i| format!("G1 X{i:05} Y1 Z0 F1000 (LONGER.)\n").into_bytes())
            .collect();
        assert_eq!(text.len(), 300 * 32);
        text.extend(uniform(5_000));
        let mut s = NcStream::with_size_hint(text.len() as u64);
        let mut capacities = vec![];
        for c in text.chunks(4096) {
            s.push(c).unwrap();
            if capacities.last() != Some(&s.blocks.capacity()) {
                capacities.push(s.blocks.capacity());
            }
        }
        s.read_tail().unwrap();
        assert_eq!(s.blocks.len(), 5_300);
        // sized at the first run for 32 bytes a line (127 + ⌈85,536 / 32
        // × 1.1⌉), then, once full, again from the lines per byte read by
        // then (not by doubling to 6,136, nor at every run as the lines
        // got shorter): within a tenth of the lines
        assert_eq!(capacities[0], 127 + 2_941);
        assert!(capacities.len() <= 3, "{capacities:?}");
        let last = *capacities.last().unwrap();
        assert!((5_300..5_830).contains(&last), "{capacities:?}");
    }

    #[test]
    fn a_short_hint_regrows_from_the_lines_per_byte_read() {
        let text = uniform(10_000);
        // told 8,000 bytes (500 lines): the first run, 255 lines, makes
        // room for them and 1.1 × the 245 lines of the 3,920 bytes left
        // (255 + ⌈269.5⌉); past the hint the list grows by doubling
        let mut s = NcStream::with_size_hint(8_000);
        let mut chunks = text.chunks(4096);
        s.push(chunks.next().unwrap()).unwrap();
        assert_eq!(s.blocks.capacity(), 525);
        for c in chunks {
            s.push(c).unwrap();
        }
        s.read_tail().unwrap();
        assert_eq!(s.blocks.len(), 10_000);
        assert_eq!(s.blocks.capacity(), 525 << 5);
    }
}
