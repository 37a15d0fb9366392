//! The text of an NC number as written (`X10.2000`'s `10.2000`), kept for
//! writing a program back and for the readings that depend on how a
//! number is written (a decimal point or not). No model: a compact string.
//!
//! Memory: a word's number text is held for every word of a program while
//! it is read (8 M words in the 2 M-line program of
//! `bench/node/large-program.bench.mjs`). A `String` is a 12 B header in
//! wasm32 plus a heap block of at least 16 B; a text of up to
//! [`INLINE`] bytes (every number the lexer accepts but the longest) is
//! held here inline, in 16 B with no heap block (a [`super::Word`] stays
//! 32 B in wasm32), and a longer one as a `Box<str>`.

use std::fmt;
use std::ops::Deref;

/// The longest text held inline, bytes.
pub const INLINE: usize = 15;

/// A number's text as written: a `str` (it derefs to one).
///
/// # Examples
/// ```
/// use mtmotion::nc::num_text::NumText;
/// let t = NumText::from("10.2000");
/// assert_eq!(t.as_str(), "10.2000");
/// assert!(t.contains('.'));
/// assert_eq!(format!("X{t}"), "X10.2000");
/// let long = NumText::from("1234567890.12345678");
/// assert_eq!(long.as_str(), "1234567890.12345678");
/// ```
#[derive(Clone, PartialEq, Eq, Hash)]
pub struct NumText(Repr);

#[derive(Clone, PartialEq, Eq, Hash)]
enum Repr {
    /// The first `len` bytes of the array (the rest zero).
    Inline([u8; INLINE], Len),
    Heap(Box<str>),
}

/// A length of 0 to [`INLINE`]: an enum, so that [`Repr`] keeps its
/// variant in the values a length never takes and is 16 B in wasm32.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
#[repr(u8)]
enum Len {
    L0,
    L1,
    L2,
    L3,
    L4,
    L5,
    L6,
    L7,
    L8,
    L9,
    L10,
    L11,
    L12,
    L13,
    L14,
    L15,
}

const LENS: [Len; INLINE + 1] = [
    Len::L0,
    Len::L1,
    Len::L2,
    Len::L3,
    Len::L4,
    Len::L5,
    Len::L6,
    Len::L7,
    Len::L8,
    Len::L9,
    Len::L10,
    Len::L11,
    Len::L12,
    Len::L13,
    Len::L14,
    Len::L15,
];

impl NumText {
    /// The text.
    pub fn as_str(&self) -> &str {
        match &self.0 {
            // The bytes were copied from a `str` whole, so they are UTF-8;
            // the check cannot fail.
            Repr::Inline(b, n) => std::str::from_utf8(&b[..*n as usize]).unwrap_or_default(),
            Repr::Heap(s) => s,
        }
    }
}

impl Default for NumText {
    fn default() -> Self {
        Self(Repr::Inline([0; INLINE], Len::L0))
    }
}

impl From<&str> for NumText {
    fn from(s: &str) -> Self {
        match LENS.get(s.len()) {
            Some(&n) => {
                let mut b = [0; INLINE];
                b[..s.len()].copy_from_slice(s.as_bytes());
                Self(Repr::Inline(b, n))
            }
            None => Self(Repr::Heap(s.into())),
        }
    }
}

impl From<String> for NumText {
    fn from(s: String) -> Self {
        if s.len() <= INLINE {
            Self::from(s.as_str())
        } else {
            Self(Repr::Heap(s.into_boxed_str()))
        }
    }
}

impl From<NumText> for String {
    fn from(t: NumText) -> Self {
        t.as_str().to_string()
    }
}

impl Deref for NumText {
    type Target = str;
    fn deref(&self) -> &str {
        self.as_str()
    }
}

impl fmt::Display for NumText {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(self.as_str(), f)
    }
}

impl fmt::Debug for NumText {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(self.as_str(), f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every length round-trips, inline up to [`INLINE`] bytes and boxed
    /// past it, and equal texts compare equal whichever way they were made.
    #[test]
    fn texts_of_every_length_round_trip() {
        let digits = "-1234567890.1234567890123";
        for n in 0..=digits.len() {
            let s = &digits[..n];
            let a = NumText::from(s);
            let b = NumText::from(s.to_string());
            assert_eq!(a.as_str(), s);
            assert_eq!(b.as_str(), s);
            assert_eq!(a, b);
            assert_eq!(matches!(a.0, Repr::Inline(..)), n <= INLINE, "{s}");
            assert_eq!(String::from(a.clone()), s);
            assert_eq!(format!("{a}|{a:?}"), format!("{s}|{s:?}"));
        }
        assert_eq!(NumText::default().as_str(), "");
        assert_ne!(NumText::from("1.0"), NumText::from("1.00"));
        // Non-ASCII text (never a number, but the type takes any str).
        assert_eq!(NumText::from("µm").as_str(), "µm");
    }

    /// The size the memory budget counts on: a word is 48 B on a 64-bit
    /// target, 32 B in wasm32 (checked by compiling for
    /// `wasm32-unknown-unknown`: the length's unused values mark the boxed
    /// text, so the text takes 16 B), with no heap block for its text.
    #[test]
    fn a_word_holds_its_text_inline() {
        let word = std::mem::size_of::<super::super::Word>();
        assert!(
            word <= if cfg!(target_pointer_width = "64") {
                48
            } else {
                32
            }
        );
        let w = super::super::lex_line("G1 X10.2000", 1).unwrap();
        assert!(w.words.iter().all(|w| matches!(w.text.0, Repr::Inline(..))));
    }
}
