//! Sequence numbers (`N…`) and program regions of a lexed program, for the
//! jumps that name a block by its N number: Fanuc Macro B `GOTO n`
//! ([`super::macro_exec`]), Haas `M97 P n` local subprogram calls and
//! Fanuc/Haas `M99 P n` returns (the run over the blocks, `run.rs`).
//!
//! A program region runs from an `O` header (an `O` number first in its
//! block, or a named `O<NAME>` program) or from the start of a file to the
//! next header or file; a jump finds its N number only inside the region
//! of the block that names it ("the same program", as Fanuc's sequence
//! number search and Haas's M97 do). N values are compared rounded to the
//! nearest whole number.

use std::collections::HashMap;

use super::Block;

/// N number → blocks, and the region of every block.
#[derive(Debug, Default)]
pub struct Sequences {
    /// N number → indices of the blocks that carry it, in text order.
    seq: HashMap<i64, Vec<usize>>,
    /// Index of the first block of each block's region.
    region: Vec<usize>,
}

impl Sequences {
    /// Indexes `blocks`.
    ///
    /// # Examples
    /// ```
    /// use mtmotion::nc::sequence::Sequences;
    /// let b = mtmotion::nc::lex("O1\nN10 G0 X1\nM30\nO2\nN10 G0 X2\nM99").unwrap();
    /// let s = Sequences::new(&b);
    /// assert_eq!(s.first_in_region(10, 2), Some(1));
    /// assert_eq!(s.first_in_region(10, 5), Some(4));
    /// assert_eq!(s.first_in_region(20, 5), None);
    /// ```
    pub fn new(blocks: &[Block]) -> Self {
        let mut s = Self::default();
        let mut region = 0;
        for (i, b) in blocks.iter().enumerate() {
            let header = b.words.first().is_some_and(|w| w.letter == 'O')
                || b.program_name.is_some()
                || (i > 0 && blocks[i - 1].file != b.file);
            if header {
                region = i;
            }
            s.region.push(region);
            if let Some(n) = b.word('N') {
                s.seq.entry(n.value.round() as i64).or_default().push(i);
            }
        }
        s
    }

    /// The region (index of its first block) of block `bi`.
    pub fn region_of(&self, bi: usize) -> Option<usize> {
        self.region.get(bi).copied()
    }

    /// The first block numbered `n` in the region of block `bi`.
    pub fn first_in_region(&self, n: i64, bi: usize) -> Option<usize> {
        let r = self.region_of(bi)?;
        self.seq
            .get(&n)?
            .iter()
            .find(|&&i| self.region[i] == r)
            .copied()
    }

    /// The block numbered `n` in the region of block `bi`, searched from
    /// block `from` to the region's end, then from the region's start
    /// (a forward sequence-number search that wraps round).
    pub fn forward_in_region(&self, n: i64, bi: usize, from: usize) -> Option<usize> {
        let r = self.region_of(bi)?;
        let same: Vec<usize> = self
            .seq
            .get(&n)?
            .iter()
            .copied()
            .filter(|&i| self.region[i] == r)
            .collect();
        same.iter()
            .find(|&&i| i >= from)
            .or_else(|| same.first())
            .copied()
    }
}
