//! The modes the source-preserving writer ([`super::patch`]) reads of
//! each block's modal state, held compactly: per block a 4-byte index
//! into a table of the distinct states in the order the run met them.
//!
//! A block's whole [`Modal`] is 368 bytes (its position, cycle, cutter
//! compensation, spline state …), 368 MB for a 1 M-line program; the
//! writer reads only the units (G20), G91, G90.1, the feed mode, F and S,
//! the G92/G52 shift and a G68 rotation, which change on few blocks of a
//! CAM program. Read with [`super::program::Keep::Patch`], a program
//! keeps only this table (4 MB and a few states for 1 M lines); with
//! `Keep::All` it keeps both. Not a model of the machine: a data layout.
//!
//! States are compared bit for bit (±0 and NaN payloads kept apart), so
//! the [`Modal`] given back ([`BlockModes::get`]) holds exactly the
//! values of the block's own state in the fields above; its other fields
//! are their defaults, which the writer does not read.

use super::program::{FeedMode, Modal, Plane, Rotation};

/// The part of a block's [`Modal`] that [`super::patch`] reads.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct WriterModes {
    inch: bool,
    incremental: bool,
    arc_center_absolute: bool,
    feed_mode: FeedMode,
    feed: Option<f64>,
    spindle: Option<f64>,
    offset: [f64; 6],
    rotation: Option<Rotation>,
}

/// The bits of a [`WriterModes`] (see [`WriterModes::same`]).
type Bits = (
    [bool; 3],
    FeedMode,
    [Option<u64>; 2],
    [u64; 6],
    Option<(Plane, [u64; 3], u64, usize)>,
);

impl WriterModes {
    fn of(m: &Modal) -> Self {
        Self {
            inch: m.inch,
            incremental: m.incremental,
            arc_center_absolute: m.arc_center_absolute,
            feed_mode: m.feed_mode,
            feed: m.feed,
            spindle: m.spindle,
            offset: m.offset,
            rotation: m.rotation,
        }
    }

    fn modal(&self) -> Modal {
        Modal {
            inch: self.inch,
            incremental: self.incremental,
            arc_center_absolute: self.arc_center_absolute,
            feed_mode: self.feed_mode,
            feed: self.feed,
            spindle: self.spindle,
            offset: self.offset,
            rotation: self.rotation,
            ..Modal::default()
        }
    }

    fn bits(&self) -> Bits {
        (
            [self.inch, self.incremental, self.arc_center_absolute],
            self.feed_mode,
            [self.feed.map(f64::to_bits), self.spindle.map(f64::to_bits)],
            self.offset.map(f64::to_bits),
            self.rotation.map(|r| {
                (
                    r.plane,
                    r.center.map(f64::to_bits),
                    r.angle.to_bits(),
                    r.line,
                )
            }),
        )
    }

    /// Equal bit for bit.
    fn same(&self, other: &Self) -> bool {
        self.bits() == other.bits()
    }
}

/// No state recorded for the block yet.
const NONE: u32 = u32::MAX;

/// The writer's modes after each block (see the module header).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct BlockModes {
    /// Per block, its state's index in `states` ([`NONE`] while the run
    /// has not recorded one).
    of_block: Vec<u32>,
    states: Vec<WriterModes>,
}

impl BlockModes {
    /// A table for `blocks` blocks, none recorded.
    pub(super) fn with_blocks(blocks: usize) -> Self {
        Self {
            of_block: vec![NONE; blocks],
            states: Vec::new(),
        }
    }

    /// Records `m` as the state after block `bi`; with `first`, only when
    /// the block has none yet.
    pub(super) fn record(&mut self, bi: usize, m: &Modal, first: bool) {
        let Some(&now) = self.of_block.get(bi) else {
            return;
        };
        if first && now != NONE {
            return;
        }
        let w = WriterModes::of(m);
        if self.states.get(now as usize).is_some_and(|s| s.same(&w)) {
            return;
        }
        let i = self.intern(w);
        self.of_block[bi] = i;
        // Blocks run many times with changing states (a loop) leave
        // states no block refers to: dropped when they outnumber blocks.
        if self.states.len() > 2 * self.of_block.len() + 1024 {
            self.compact();
        }
    }

    /// The index of `w`: the last state's when it is the same, else a new one.
    fn intern(&mut self, w: WriterModes) -> u32 {
        match self.states.last() {
            Some(l) if l.same(&w) => (self.states.len() - 1) as u32,
            _ => {
                self.states.push(w);
                (self.states.len() - 1) as u32
            }
        }
    }

    /// Keeps only the states a block refers to.
    fn compact(&mut self) {
        let old = std::mem::take(&mut self.states);
        let mut map = vec![NONE; old.len()];
        for i in &mut self.of_block {
            if *i == NONE {
                continue;
            }
            if map[*i as usize] == NONE {
                map[*i as usize] = self.states.len() as u32;
                self.states.push(old[*i as usize]);
            }
            *i = map[*i as usize];
        }
    }

    /// Gives every block not run the state of the block before it (the
    /// first ones `start`'s), as the program's per-block modal states do.
    pub(super) fn fill(&mut self, start: &Modal) {
        let mut last = None;
        for bi in 0..self.of_block.len() {
            match self.of_block[bi] {
                NONE => {
                    let i = *last.get_or_insert_with(|| {
                        let w = WriterModes::of(start);
                        self.states.push(w);
                        (self.states.len() - 1) as u32
                    });
                    self.of_block[bi] = i;
                }
                i => last = Some(i),
            }
        }
        self.compact();
        self.states.shrink_to_fit();
    }

    /// The writer's modes after block `bi` as a [`Modal`] (the fields the
    /// writer does not read at their defaults); `None` past the end or
    /// when the program kept no per-block state.
    pub fn get(&self, bi: usize) -> Option<Modal> {
        let &i = self.of_block.get(bi)?;
        self.states.get(i as usize).map(WriterModes::modal)
    }

    /// The writer's modes after the last block.
    pub fn last(&self) -> Option<Modal> {
        self.get(self.of_block.len().checked_sub(1)?)
    }

    /// Some block is in G20 (inch).
    pub fn any_inch(&self) -> bool {
        self.of_block
            .iter()
            .any(|&i| self.states.get(i as usize).is_some_and(|s| s.inch))
    }

    /// The number of distinct states held.
    pub fn states(&self) -> usize {
        self.states.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocks_share_states_and_keep_their_own_bits() {
        let mut t = BlockModes::with_blocks(5);
        let a = Modal {
            feed: Some(100.0),
            ..Modal::default()
        };
        let mut b = a;
        b.offset[0] = -0.0;
        t.record(0, &a, false);
        t.record(1, &a, false);
        t.record(3, &b, false);
        t.record(3, &a, true); // first: kept as b
        t.fill(&Modal::default());
        assert_eq!(t.states(), 2);
        assert_eq!(t.get(1).unwrap().feed, Some(100.0));
        // block 2 was not run: the state before it
        assert_eq!(t.get(2).unwrap().offset[0].to_bits(), 0.0f64.to_bits());
        assert_eq!(t.get(3).unwrap().offset[0].to_bits(), (-0.0f64).to_bits());
        assert_eq!(t.get(4).unwrap().offset[0].to_bits(), (-0.0f64).to_bits());
        assert!(t.get(5).is_none());
        assert!(!t.any_inch());
    }

    /// Per block, the writer's fields of the whole modal state (read with
    /// `Keep::All`) are those of the compact table, read with either keep;
    /// the blocks change units, G91, G90.1, feed mode, F, S, G92, G68.
    #[test]
    fn the_table_gives_each_blocks_own_writer_modes() {
        use crate::nc::files::parse_files_keeping;
        use crate::nc::program::{Keep, ParseOptions};
        let text = "G21 G90 G17\nG0 X1 Y2\nG1 X3 F200\nG91 Y1\nG90 G92 X0\nG20 G1 X1 F10\n\
                    G21 G95 S1000 F0.1 X2\nG94 F300\nG90.1 G1 X4\nG91.1\n\
                    G68 X1 Y1 R30\nG1 X5\nG69\nM30\nG1 X9\n";
        let read = |keep| parse_files_keeping(text, &[], &ParseOptions::default(), keep).unwrap();
        let (all, patch) = (read(Keep::All), read(Keep::Patch));
        assert_eq!(all.modes, patch.modes);
        assert_eq!((all.modal.len(), patch.modal.len()), (15, 1));
        assert_eq!(patch.modal[0], *all.modal.last().unwrap());
        assert!(
            all.modes.states() >= 8 && all.modes.states() < 15,
            "{}",
            all.modes.states()
        );
        for (b, m) in all.modal.iter().enumerate() {
            let w = patch.modes.get(b).unwrap();
            assert_eq!(
                WriterModes::of(&w).bits(),
                WriterModes::of(m).bits(),
                "block {b}"
            );
        }
        assert!(patch.modes.any_inch());
        assert_eq!(patch.modes.last().unwrap().feed, all.modal[14].feed);
    }

    #[test]
    fn a_loop_of_changing_states_does_not_grow_the_table() {
        // Three blocks run 10,000 times, each run a new state: the table
        // grows by one a record and is compacted (to the 3 states the
        // blocks refer to) when it holds more than 2·3 + 1024 = 1030,
        // first at record 1,031 and then every 1,028: after 10,000,
        // 3 + (10,000 − 1,031) mod 1,028 = 748 states.
        let mut t = BlockModes::with_blocks(3);
        let mut most = 0;
        for k in 0..10_000 {
            let m = Modal {
                feed: Some(f64::from(k)),
                ..Modal::default()
            };
            t.record(k as usize % 3, &m, false);
            most = most.max(t.states());
        }
        assert_eq!((t.states(), most), (748, 1030));
        t.fill(&Modal::default());
        assert_eq!(t.states(), 3);
        assert_eq!(t.get(0).unwrap().feed, Some(9999.0));
        assert_eq!(t.get(1).unwrap().feed, Some(9997.0));
        assert_eq!(t.get(2).unwrap().feed, Some(9998.0));
    }
}
