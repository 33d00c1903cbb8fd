//! Sums over many pixels spread over threads, the same to the last bit on every run.

use rayon::prelude::*;

/// Terms summed in order by one thread: the work is split into blocks of this many.
const BLOCK: usize = 4096;

/// The sum of `term(i)` for `i` in `0..n`: fixed blocks summed in parallel, then the blocks' sums
/// in order, so the result does not depend on how the threads shared the work (rayon's own `sum`
/// adds in whatever order its work stealing splits it, so the last bits vary from run to run).
pub(crate) fn ordered_sum(n: usize, term: impl Fn(usize) -> f64 + Sync) -> f64 {
    let blocks: Vec<f64> = (0..n.div_ceil(BLOCK))
        .into_par_iter()
        .map(|b| (b * BLOCK..((b + 1) * BLOCK).min(n)).map(&term).sum())
        .collect();
    blocks.iter().sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sums_across_blocks_in_the_same_order_every_time() {
        let n = 10 * BLOCK + 17;
        let term = |i: usize| 1.0 / (1.0 + i as f64) * if i % 3 == 0 { 1e6 } else { 1e-6 };
        let sequential: f64 = (0..n.div_ceil(BLOCK))
            .map(|b| (b * BLOCK..((b + 1) * BLOCK).min(n)).map(term).sum::<f64>())
            .sum();
        for _ in 0..20 {
            assert_eq!(ordered_sum(n, term).to_bits(), sequential.to_bits());
        }
        assert_eq!(ordered_sum(0, term), 0.0);
    }
}
