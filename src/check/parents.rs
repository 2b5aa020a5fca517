//! The store's parent links, by state number, in about two bits a state.
//!
//! A breadth-first search stores the states in the order their parents were expanded
//! (the merge takes the frontier in order, and each state's successors in order), so the
//! initial states, which have no parent, come first, and the parents never decrease after
//! them. Such a sequence is held as one bit per state plus one per step its parent rises
//! (the parents' "unary gaps"): at 6 cups, 65.6 M states took 16 MB instead of 262 MB in
//! four bytes each, and fresh memory is the costliest thing a search writes in this
//! project's virtual machines (`super::slots`). A parent is read only to rebuild a run to
//! a state (`Graph::path_to`), so a read may scan a few words.
//!
//! Links that do not follow that order (another way of exploring) are held in four bytes
//! each from the first one that does not, all of them converted once.

use super::chunked::Chunked;
use super::store::OutOfMemory;

/// Every `2^SAMPLE`-th one's position is kept: a read scans the bits from there.
const SAMPLE: u32 = 10;

/// Parent links by state number: `None` for an initial state.
pub(super) enum Parents {
    /// The `None`s first, the numbers never decreasing after them.
    Rising(Rising),
    /// Any links, `u32::MAX` standing for `None`.
    Plain(Chunked<u32>),
}

/// See [`Parents::Rising`]. For the `k`-th number `p` (after the `None`s), `p` zeros since
/// the one before (from position 0), then a one: that one is at position `p + k`.
#[derive(Default)]
pub(super) struct Rising {
    /// How many `None`s lead.
    nones: u32,
    /// The bits in full words, lowest first.
    words: Chunked<u64>,
    /// The word being filled, and how many of its bits are placed.
    word: u64,
    used: u32,
    /// Numbers held after the `None`s, and the last.
    ones: u32,
    last: u32,
    /// The position of the `(i << SAMPLE)`-th one.
    samples: Chunked<u64>,
}

impl Default for Parents {
    fn default() -> Parents {
        Parents::Rising(Rising::default())
    }
}

impl Rising {
    fn len(&self) -> usize {
        self.nones as usize + self.ones as usize
    }

    /// Bits placed so far.
    fn position(&self) -> u64 {
        self.words.len() as u64 * 64 + u64::from(self.used)
    }

    /// Word `w` of the bits (the one being filled past the full ones).
    fn word_at(&self, w: usize) -> u64 {
        if w < self.words.len() {
            self.words.get(w)
        } else {
            self.word
        }
    }

    /// Appends `p`, which is at least the last number; false when it is not.
    fn push(&mut self, p: Option<u32>) -> Result<bool, OutOfMemory> {
        let Some(p) = p else {
            if self.ones > 0 || self.nones == u32::MAX {
                return Ok(false);
            }
            self.nones += 1;
            return Ok(true);
        };
        if p < self.last || self.ones == u32::MAX {
            return Ok(false);
        }
        // A push that runs out of memory partway leaves the bits as they were: the search
        // may store more states after it (the job's other successors).
        let mark = self.mark();
        if let Err(e) = self.place(p) {
            self.undo_to(mark);
            return Err(e);
        }
        self.ones += 1;
        self.last = p;
        Ok(true)
    }

    /// The one of `p` placed after its gap of zeros (the counts not yet updated).
    fn place(&mut self, p: u32) -> Result<(), OutOfMemory> {
        // The zeros: whole words of them, then the rest of the gap in this word.
        let mut gap = u64::from(p - self.last);
        while u64::from(self.used) + gap >= 64 {
            gap -= u64::from(64 - self.used);
            self.words.push(std::mem::take(&mut self.word))?;
            self.used = 0;
        }
        self.used += gap as u32;
        if self.ones.is_multiple_of(1 << SAMPLE) {
            self.samples.push(self.position())?;
        }
        self.word |= 1 << self.used;
        self.used += 1;
        if self.used == 64 {
            self.words.push(std::mem::take(&mut self.word))?;
            self.used = 0;
        }
        Ok(())
    }

    /// What [`Rising::undo_to`] goes back to: the words and samples held, and the word
    /// being filled.
    fn mark(&self) -> (usize, usize, u64, u32) {
        (self.words.len(), self.samples.len(), self.word, self.used)
    }

    /// The bits as they were at `mark`, what [`Rising::place`] did since taken back.
    fn undo_to(&mut self, (words, samples, word, used): (usize, usize, u64, u32)) {
        while self.words.len() > words {
            self.words.pop();
        }
        while self.samples.len() > samples {
            self.samples.pop();
        }
        (self.word, self.used) = (word, used);
    }

    /// Link `i` (below [`Rising::len`]).
    fn get(&self, i: usize) -> Option<u32> {
        let k = i.checked_sub(self.nones as usize)?;
        // From the sampled one at or before the k-th, count the ones after it.
        let from = self.samples.get(k >> SAMPLE);
        let mut left = (k & ((1 << SAMPLE) - 1)) as u32;
        let mut w = (from / 64) as usize;
        let mut bits = self.word_at(w) & (u64::MAX << (from % 64));
        loop {
            let here = bits.count_ones();
            if left < here {
                for _ in 0..left {
                    bits &= bits - 1;
                }
                let at = w as u64 * 64 + u64::from(bits.trailing_zeros());
                return Some((at - k as u64) as u32);
            }
            left -= here;
            w += 1;
            bits = self.word_at(w);
        }
    }

    /// Every link, in order.
    fn iter(&self) -> impl Iterator<Item = Option<u32>> + '_ {
        let ones = (0..self.words.len() + 1).flat_map(move |w| {
            let mut bits = self.word_at(w);
            std::iter::from_fn(move || {
                (bits != 0).then(|| {
                    let at = w as u64 * 64 + u64::from(bits.trailing_zeros());
                    bits &= bits - 1;
                    at
                })
            })
        });
        let numbers = ones.enumerate().map(|(k, at)| Some((at - k as u64) as u32));
        std::iter::repeat_n(None, self.nones as usize).chain(numbers)
    }
}

impl Parents {
    /// Number of links.
    pub(super) fn len(&self) -> usize {
        match self {
            Parents::Rising(r) => r.len(),
            Parents::Plain(c) => c.len(),
        }
    }

    /// Link `i` (panics past the end, as slices do).
    pub(super) fn get(&self, i: usize) -> Option<u32> {
        assert!(i < self.len(), "link {i} past the end ({})", self.len());
        match self {
            Parents::Rising(r) => r.get(i),
            Parents::Plain(c) => Some(c.get(i)).filter(|&p| p != u32::MAX),
        }
    }

    /// Appends a link; memory that cannot be had is [`OutOfMemory`].
    pub(super) fn push(&mut self, p: Option<u32>) -> Result<(), OutOfMemory> {
        if let Parents::Rising(r) = self {
            if r.push(p)? {
                return Ok(());
            }
            let mut plain = Chunked::default();
            for q in r.iter() {
                plain.push(q.unwrap_or(u32::MAX))?;
            }
            *self = Parents::Plain(plain);
        }
        match self {
            Parents::Plain(c) => c.push(p.unwrap_or(u32::MAX)),
            Parents::Rising(_) => unreachable!("converted above"),
        }
    }

    /// Bytes allocated.
    pub(super) fn bytes(&self) -> usize {
        match self {
            Parents::Rising(r) => r.words.bytes() + r.samples.bytes(),
            Parents::Plain(c) => c.bytes(),
        }
    }

    /// Whether the links are held in bits ([`Parents::Rising`]).
    #[cfg(test)]
    fn rising(&self) -> bool {
        matches!(self, Parents::Rising(_))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Links read back as pushed: a breadth-first search's (a thousand initial states,
    /// then parents rising by 0 to 2, or by a jump past several words) in bits, and after
    /// a link that falls, every link in four bytes.
    #[test]
    fn links_read_back_as_pushed() {
        let mut rng = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move |n: u64| {
            rng ^= rng << 13;
            rng ^= rng >> 7;
            rng ^= rng << 17;
            rng % n
        };
        let mut links: Vec<Option<u32>> = vec![None; 1000];
        let mut p = 0u32;
        for _ in 0..200_000 {
            p += match next(100) {
                0 => 500 + next(1000) as u32,
                r => (r % 3) as u32,
            };
            links.push(Some(p));
        }
        let mut a = Parents::default();
        for (i, &l) in links.iter().enumerate() {
            a.push(l).unwrap();
            assert!(a.rising(), "link {i}");
        }
        let check = |a: &Parents, links: &[Option<u32>]| {
            assert_eq!(a.len(), links.len());
            for (i, &l) in links.iter().enumerate() {
                assert_eq!(a.get(i), l, "link {i}");
            }
        };
        check(&a, &links);
        // A bit per link after the `None`s, and one per step up to the last.
        let Parents::Rising(r) = &a else {
            unreachable!("checked above")
        };
        assert_eq!(r.position(), (links.len() - 1000) as u64 + u64::from(p));
        for l in [Some(3), None, Some(7)] {
            a.push(l).unwrap();
            links.push(l);
            assert!(!a.rising());
            check(&a, &links);
        }
        // A link placed, then taken back (as a push that ran out of memory partway is),
        // leaves the bits as they were: a jump past several words, at a sampled one.
        let mut c = Parents::default();
        let mut held = Vec::new();
        for k in 0..(1u32 << SAMPLE) {
            c.push(Some(k / 2)).unwrap();
            held.push(Some(k / 2));
        }
        let Parents::Rising(r) = &mut c else {
            unreachable!("rising links")
        };
        let mark = r.mark();
        r.place(r.last + 700).unwrap();
        r.undo_to(mark);
        for p in [r.last + 3, r.last + 300] {
            c.push(Some(p)).unwrap();
            held.push(Some(p));
        }
        assert!(c.rising());
        check(&c, &held);
        // A `None` after a number also ends the bits.
        let mut b = Parents::default();
        for l in [None, Some(0), Some(0), None] {
            b.push(l).unwrap();
        }
        assert!(!b.rising());
        check(&b, &[None, Some(0), Some(0), None]);
    }
}
