//! The NC stream (`nc::stream::NcStream`) reads a program exactly as the
//! whole-text reading (`nc::files::parse_files_owned`) reads the text its
//! bytes decode to (UTF-8, invalid bytes as U+FFFD, as a browser's
//! `File.text()`), whatever the cut of the bytes into chunks: the same
//! program (blocks, segments, warnings, modal states) or the same errors,
//! compared through their `Debug` text. Proved on every program of the
//! shared corpus (skipped with a printed line when it is absent) at chunk
//! sizes 1, 2, 7, 4096 and the whole, and on texts written to break it
//! (CRLF split between chunks, line ends first and last in a chunk,
//! multi-byte and invalid bytes, no final line end, `%` delimiters, BOM,
//! Ctrl-Z, CR-only files, binary files) at every cut into two chunks as
//! well. The refusals over the budgets name the line where the count
//! passed the limit. A size hint, right or wrong, changes nothing read;
//! both readings tell a refusal as a whole (`notRead`) alike.

use mtmotion::budget::{MAX_NC_LINES, MAX_NC_WORDS, MAX_TEXT_BYTES};
use mtmotion::nc::files::{parse_files_noting_refusal, parse_files_owned, NcFile};
use mtmotion::nc::program::{Keep, ParseOptions, Program};
use mtmotion::nc::stream::NcStream;
use mtmotion::nc::NcErrors;

#[path = "support/corpus.rs"]
mod corpus;

type Read = Result<Program, NcErrors>;

fn whole(bytes: &[u8], keep: Keep) -> Read {
    let text = String::from_utf8_lossy(bytes).into_owned();
    parse_files_owned(text, Vec::new(), &ParseOptions::default(), keep)
}

/// The stream's reading of `chunks` in turn.
fn streamed<'a>(chunks: impl IntoIterator<Item = &'a [u8]>, keep: Keep) -> Read {
    let mut s = NcStream::new();
    for c in chunks {
        s.push(c)?;
    }
    s.finish(&ParseOptions::default(), keep)
}

/// Asserts that the stream reads `bytes` cut into `size`-byte chunks as
/// the whole text is read.
fn same(name: &str, bytes: &[u8], size: usize, keep: Keep, want: &str) {
    let got = format!("{:?}", streamed(bytes.chunks(size.max(1)), keep));
    assert!(
        got == want,
        "{name}, chunks of {size} bytes: the stream differs from the whole text\n stream: {}\n  whole: {}",
        mtmotion::budget::clip(&got, 2000),
        mtmotion::budget::clip(want, 2000)
    );
}

const SIZES: [usize; 4] = [1, 2, 7, 4096];

#[test]
fn every_corpus_program_streams_as_its_whole_text() {
    let Some(dir) = corpus::available("the stream's corpus comparison") else {
        return;
    };
    for name in corpus::names(&dir) {
        let bytes = std::fs::read(dir.join(&name)).unwrap();
        let want = format!("{:?}", whole(&bytes, Keep::All));
        for size in SIZES.into_iter().chain([bytes.len()]) {
            same(&name, &bytes, size, Keep::All, &want);
        }
    }
}

/// Texts that cut badly: each is read in the chunk sizes and at every cut
/// into two chunks (and three, around each byte).
fn nasty() -> Vec<(&'static str, Vec<u8>)> {
    let mut t: Vec<(&'static str, Vec<u8>)> = vec![
        (
            "CRLF, % header and trailer, text after the trailer",
            b"%\r\nO1000 (PART)\r\nG21 G90 G17\r\nG0 X0 Y0\r\nG1 X10 Y0 F600\r\nG2 X20 Y0 I5 J0\r\nM30\r\n%\r\nafter the end\r\n"
                .to_vec(),
        ),
        (
            "no final line end",
            b"G0 X0\nG1 X5 F100\nG1 Y5".to_vec(),
        ),
        (
            "blank lines, trailing line ends and Ctrl-Z",
            b"\n\nG0 X0\n\n\nG1 X1 F100\r\n\r\n\x1a\x1a\r\n".to_vec(),
        ),
        (
            "a Ctrl-Z inside the text is an error at its line",
            b"G0 X0\n\x1a\nG1 X1 F100\n".to_vec(),
        ),
        ("CR alone ends lines (old Macintosh)", b"G0 X0\rG1 X2 F100\r\rG1 Y2\r".to_vec()),
        ("an empty text", Vec::new()),
        ("line ends only", b"\r\n\n\r\x1a".to_vec()),
        (
            "a line error and a warning",
            b"G0 X0\nG1 X F100\nG1 Y1 Q7\nG1 X3\n".to_vec(),
        ),
        (
            "a Heidenhain program",
            b"0 BEGIN PGM TEST MM\n1 L X+10 R0 FMAX\n2 END PGM TEST MM\n".to_vec(),
        ),
        ("a PNG", b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR\0\0\0\x10".to_vec()),
        ("a NUL after the first line", b"G0 X0\n\0\nG1 X1\n".to_vec()),
    ];
    // a byte-order mark, and one multi-byte character and one
    // Windows-1252 byte (Ø = 0xD8, no UTF-8) in comments
    let mut bom = b"\xef\xbb\xbfG0 X0 (\xc3\x98 10 mm)\n".to_vec();
    bom.extend_from_slice(b"G1 X10 F100 (\xd8 10 mm)\r\n(\xe2\x82\xac \xd8\xd8)\nM30\n");
    t.push(("BOM, UTF-8 and Windows-1252 bytes in comments", bom));
    // a JPEG read as text: three U+FFFD first, JFIF only after the first
    // 512 characters (the whole-text check searches all of it)
    let mut jpeg = b"\xff\xd8\xff\xe0 G0 X0\n".to_vec();
    jpeg.extend(b"G1 X1 F100\n".repeat(60));
    jpeg.extend_from_slice(b"(JFIF)\nG1 X2\n");
    t.push(("a JPEG with its JFIF past the head", jpeg.clone()));
    jpeg.truncate(jpeg.len() - 14);
    t.push(("three U+FFFD first without JFIF", jpeg));
    // more than 512 characters of text, then a binary-looking stretch
    let mut long = b"G1 X1 F100\n".repeat(60);
    long.extend_from_slice(b"\x01\x02\x03\n");
    t.push(("a control character past the head", long));
    t
}

#[test]
fn texts_that_cut_badly_stream_as_their_whole_text() {
    for (name, bytes) in nasty() {
        for keep in [Keep::All, Keep::Motion] {
            let want = format!("{:?}", whole(&bytes, keep));
            for size in SIZES.into_iter().chain([bytes.len()]) {
                same(name, &bytes, size, keep, &want);
            }
            for cut in 0..=bytes.len() {
                let (a, b) = bytes.split_at(cut);
                let got = format!("{:?}", streamed([a, b], keep));
                assert!(got == want, "{name}, cut at {cut}:\n{got}\n{want}");
                // the byte at the cut alone: a line end first and last
                if cut < bytes.len() {
                    let parts = [a, &b[..1], &b[1..]];
                    let got = format!("{:?}", streamed(parts, keep));
                    assert!(got == want, "{name}, byte {cut} alone:\n{got}\n{want}");
                }
            }
        }
    }
}

/// A size hint changes the memory only: any hint, right or wrong, gives
/// the whole text's reading (the hint sizes the block list from the lines
/// per byte read, so a text whose first lines are short, then long, and
/// a hint far too short or too long, are read as well).
#[test]
fn a_size_hint_of_any_size_reads_as_the_whole_text() {
    let mut texts = nasty();
    let mut mixed = b"%\nO1\n".to_vec();
    for i in 0..3000 {
        let line = if i < 1000 {
            format!("X{i}\n")
        } else {
            format!("G1 X{i}.125 Y-{i}.5 Z0.25 F1200 (PASS {i})\n")
        };
        mixed.extend(line.into_bytes());
    }
    mixed.extend_from_slice(b"M30\n%\n");
    texts.push(("short lines, then long", mixed));
    for (name, bytes) in texts {
        let want = format!("{:?}", whole(&bytes, Keep::All));
        let n = bytes.len() as u64;
        for hint in [1, n / 2, n, 3 * n + 7] {
            for size in [1, 7, 4096] {
                let mut s = NcStream::with_size_hint(hint);
                let got = bytes
                    .chunks(size)
                    .try_for_each(|c| s.push(c))
                    .and_then(|()| s.finish(&ParseOptions::default(), Keep::All));
                let got = format!("{got:?}");
                assert!(
                    got == want,
                    "{name}, hint {hint}, chunks of {size}:\n{got}\n{want}"
                );
            }
        }
    }
}

#[test]
fn nasty_texts_give_what_their_names_say() {
    // the comparison above is with the whole text; these pin that the
    // texts do reach the cases they are named after
    let get = |name: &str| nasty().into_iter().find(|t| t.0 == name).unwrap().1;
    let e = whole(&get("a PNG"), Keep::Motion).unwrap_err();
    assert!(e.errors[0].message.contains("a PNG image"), "{e}");
    let e = whole(&get("a JPEG with its JFIF past the head"), Keep::Motion).unwrap_err();
    assert!(e.errors[0].message.contains("a JPEG image"), "{e}");
    let e = whole(&get("a Heidenhain program"), Keep::Motion).unwrap_err();
    assert!(e.errors[0].message.contains("this looks like"), "{e}");
    let e = whole(
        &get("a Ctrl-Z inside the text is an error at its line"),
        Keep::Motion,
    )
    .unwrap_err();
    assert_eq!(e.errors[0].line, 2, "{e}");
    let p = whole(
        &get("BOM, UTF-8 and Windows-1252 bytes in comments"),
        Keep::All,
    )
    .unwrap();
    assert_eq!(p.blocks[0].comments, vec!["Ø 10 mm".to_string()]);
    assert_eq!(p.blocks[1].comments, vec!["\u{fffd} 10 mm".to_string()]);
    let p = whole(
        &get("blank lines, trailing line ends and Ctrl-Z"),
        Keep::All,
    )
    .unwrap();
    assert_eq!(p.blocks.len(), 6);
}

/// Feeds `chunks` and returns the first refusal: of a push, or of the
/// finish.
fn refusal(chunks: impl IntoIterator<Item = Vec<u8>>) -> NcErrors {
    let mut s = NcStream::new();
    for c in chunks {
        if let Err(e) = s.push(&c) {
            // a refused stream stays refused
            assert_eq!(s.push(b"G0 X0\n").unwrap_err(), e);
            return e;
        }
    }
    s.finish(&ParseOptions::default(), Keep::Motion)
        .unwrap_err()
}

#[test]
fn the_text_budgets_refuse_at_the_line_that_passes_them() {
    // lines: 4 M line ends, then one more line
    let mb = 1 << 20;
    let ends = MAX_NC_LINES;
    let chunks = (0..ends.div_ceil(mb)).map(|k| vec![b'\n'; mb.min(ends - k * mb)]);
    let e = refusal(chunks.chain([b"G0 X0".to_vec()]));
    let e = &e.errors[0];
    assert_eq!((e.line, e.column), (MAX_NC_LINES + 1, 1), "{e}");
    assert!(
        e.message.starts_with(&format!(
            "program: {} lines, more than the limit of {MAX_NC_LINES}",
            MAX_NC_LINES + 1
        )),
        "{e}"
    );
    // exactly the limit: 4 M lines, the last ended by its LF, are read
    let mut s = NcStream::new();
    for k in 0..ends.div_ceil(mb) {
        s.push(&vec![b'\n'; mb.min(ends - k * mb)]).unwrap();
    }
    // the same with CR-only line ends (a CR is a line end once its next
    // byte is no LF) and with CRLF (one line end each), refused alike
    for end in [&b"\r"[..], b"\r\n"] {
        let chunk = end.repeat(mb);
        let chunks =
            (0..ends.div_ceil(mb)).map(|k| chunk[..end.len() * mb.min(ends - k * mb)].to_vec());
        let e = refusal(chunks.chain([b"G0 X0".to_vec()]));
        let e = &e.errors[0];
        assert_eq!((e.line, e.column), (MAX_NC_LINES + 1, 1), "{end:?}: {e}");
        assert!(
            e.message.contains(&format!("{} lines", MAX_NC_LINES + 1)),
            "{end:?}: {e}"
        );
    }
    // bytes: a 64 MiB comment on line 3
    let head = b"G0 X0\nG1 X1 F100\n(".to_vec();
    let body = (0..MAX_TEXT_BYTES / mb).map(|_| vec![b'x'; mb]);
    let e = refusal([head].into_iter().chain(body));
    let e = &e.errors[0];
    assert_eq!((e.line, e.column), (3, 1), "{e}");
    // refused by the push that takes the count past the limit: the 18
    // bytes of the first chunk and 64 chunks of 1 MiB
    let want = format!(
        "program: {} bytes, more than the limit of {MAX_TEXT_BYTES}",
        MAX_TEXT_BYTES + 18
    );
    assert!(e.message.starts_with(&want), "{e}");
}

#[test]
fn the_word_budget_refuses_at_its_line_as_the_whole_text_does() {
    // a line with more letters than the budget is refused before it is
    // lexed, at its line, by a push once the line is complete
    let mut text = b"G0 X0\nG1 X1 F100\n".to_vec();
    text.extend(std::iter::repeat_n(b'X', MAX_NC_WORDS));
    text.extend_from_slice(b"\nG0 X5\n");
    let want = whole(&text, Keep::Motion).unwrap_err();
    let mut s = NcStream::new();
    let mut got = None;
    for c in text.chunks(1 << 20) {
        if let Err(e) = s.push(c) {
            got = Some(e);
            break;
        }
    }
    let got = got.expect("a push refuses the line");
    assert_eq!(got, want);
    assert_eq!((got.errors[0].line, got.errors[0].column), (3, 1));
}

/// Whether a text was refused as a whole (`checkNc`'s `notRead`), as the
/// whole-text reading says it (`parse_files_noting_refusal`, which
/// `checkNc` of a string reads it from) and as the stream does
/// (`finish_noting_refusal`): the same for every text written to break
/// the stream, whole and in chunks; true for a binary file and over the
/// budgets only, never for a line's own error at line 1, column 1.
#[test]
fn a_refusal_as_a_whole_is_told_by_both_readings() {
    let o = ParseOptions::default();
    let whole_read = |bytes: &[u8], files: Vec<NcFile>| {
        let text = String::from_utf8_lossy(bytes).into_owned();
        let (read, whole) = parse_files_noting_refusal(text, files, &o, Keep::Motion);
        (format!("{read:?}"), whole)
    };
    let stream_read = |bytes: &[u8], size: usize| {
        let mut s = NcStream::new();
        for c in bytes.chunks(size) {
            if s.push(c).is_err() {
                break;
            }
        }
        let (read, whole) = s.finish_noting_refusal(&o, Keep::Motion);
        (format!("{read:?}"), whole)
    };
    let mut refused = 0;
    for (name, bytes) in nasty() {
        let want = whole_read(&bytes, Vec::new());
        assert_eq!(
            want.0,
            format!("{:?}", whole(&bytes, Keep::Motion)),
            "{name}"
        );
        refused += usize::from(want.1);
        for size in [1, 7, bytes.len().max(1)] {
            assert_eq!(stream_read(&bytes, size), want, "{name}, chunks of {size}");
        }
    }
    assert!(
        refused >= 2,
        "the binary files among the nasty texts: {refused}"
    );
    let png = b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR".to_vec();
    assert!(whole_read(&png, Vec::new()).1, "a PNG");
    let over = vec![b'\n'; MAX_NC_LINES + 1];
    let (read, whole) = whole_read(&over, Vec::new());
    assert!(
        whole && read.contains("more than the limit of 4000000"),
        "{read}"
    );
    // a line's error at line 1, column 1, is the line's: the text was read
    let (read, whole) = whole_read(b"X\nG0 X1\n", Vec::new());
    assert!(!whole && read.contains("line: 1, column: 1"), "{read}");
    // the program and its files over the budget together: none is read
    let half = |name: &str| NcFile {
        name: name.into(),
        text: "\n".repeat(MAX_NC_LINES / 2 + 1),
    };
    let (read, whole) = whole_read(b"G0 X1\n", vec![half("a.nc"), half("b.nc")]);
    assert!(whole && read.contains("program and its files"), "{read}");
    // a binary file beside a program that is read is that file's error
    let img = NcFile {
        name: "img.nc".into(),
        text: String::from_utf8_lossy(&png).into_owned(),
    };
    let (read, whole) = whole_read(b"G0 X1\n", vec![img]);
    assert!(!whole && read.contains("img.nc"), "{read}");
    // a program refused beside a file with an error of its own: the file
    // was read, so the text was not refused as a whole
    let bad = NcFile {
        name: "bad.nc".into(),
        text: "G1 X".into(),
    };
    let (read, whole) = whole_read(&png, vec![bad]);
    assert!(!whole && read.contains("bad.nc"), "{read}");
}
