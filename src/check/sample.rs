//! Random runs, for spaces too large to exhaust (`bdi-check simulate`): the breadth-first
//! search of [`super::explore`] expands, at every depth, only `runs` of the states it
//! reached, chosen at random from a seed. Every state reached is still checked (its
//! invariants, properties and the failures of the transitions into it); the ones not chosen
//! are left unexpanded, as states beyond a bound are. So each expanded state lies on a run
//! of expanded states from an initial one, a violation found comes with a concrete run
//! (the shortest among the runs followed) that replays, and a search that followed random
//! runs never passes: it is incomplete.
//!
//! The generator is SplitMix64 (Steele, Lea and Flood, 2014), written out here rather than
//! taken from `rand`: a seed must give the same runs with every version of bdi-check, which
//! `rand`'s `StdRng` does not promise, and ten lines need no dependency.

/// `--runs N --seed S`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Sample {
    /// How many states each depth expands (runs followed side by side).
    pub runs: u32,
    /// The seed of the choices.
    pub seed: u64,
}

/// SplitMix64: a 64-bit state, one output per step.
#[derive(Clone, Debug)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    /// A generator from `seed`.
    pub fn new(seed: u64) -> SplitMix64 {
        SplitMix64(seed)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// A number below `n` (`n > 0`), by Lemire's multiply-shift (its bias, below
    /// `n / 2⁶⁴`, does not matter here).
    pub fn below(&mut self, n: usize) -> usize {
        ((u128::from(self.next_u64()) * n as u128) >> 64) as usize
    }

    /// Which `k` of `n` items to take, uniformly (a partial Fisher-Yates shuffle): bit `i`
    /// of the result says whether item `i` is taken. All are when `k >= n`.
    pub fn choose(&mut self, n: usize, k: usize) -> Vec<bool> {
        if k >= n {
            return vec![true; n];
        }
        let mut order: Vec<usize> = (0..n).collect();
        let mut taken = vec![false; n];
        for i in 0..k {
            let j = i + self.below(n - i);
            order.swap(i, j);
            taken[order[i]] = true;
        }
        taken
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splitmix64_gives_the_published_sequence() {
        // The first outputs for seed 1234567, as the reference C implementation gives them.
        let mut g = SplitMix64::new(1234567);
        let first: Vec<u64> = (0..3).map(|_| g.next_u64()).collect();
        assert_eq!(
            first,
            [
                6457827717110365317,
                3203168211198807973,
                9817491932198370423
            ]
        );
    }

    #[test]
    fn choose_takes_exactly_k_and_every_item_can_be_taken() {
        let mut g = SplitMix64::new(7);
        let mut seen = [0u32; 10];
        for _ in 0..2000 {
            let c = g.choose(10, 3);
            assert_eq!(c.iter().filter(|&&b| b).count(), 3);
            for (i, &b) in c.iter().enumerate() {
                seen[i] += u32::from(b);
            }
        }
        // Each item is taken about 600 times; none is favoured beyond chance.
        assert!(seen.iter().all(|&n| (450..750).contains(&n)), "{seen:?}");
        assert_eq!(g.choose(4, 9), vec![true; 4]);
    }
}
