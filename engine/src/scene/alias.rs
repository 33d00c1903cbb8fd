//! Walker/Vose alias tables for O(1) sampling of discrete distributions.

/// One column of an alias table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AliasEntry {
    /// Probability of keeping this column's own index.
    pub threshold: f32,
    /// Index returned otherwise.
    pub alias: u32,
}

/// A discrete distribution over `n` outcomes with its alias table, pdf and
/// CDF (either can drive sampling on the GPU).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct AliasTable {
    /// Alias columns, one per outcome.
    pub entries: Vec<AliasEntry>,
    /// Normalised probability of each outcome.
    pub pdf: Vec<f32>,
    /// Inclusive cumulative distribution; the last value is 1.
    pub cdf: Vec<f32>,
}

impl AliasTable {
    /// Builds from non-negative weights. Returns an empty table if the
    /// weights are empty or sum to zero (negative and non-finite weights
    /// count as zero).
    pub fn new(weights: &[f32]) -> Self {
        let w: Vec<f64> = weights
            .iter()
            .map(|&x| {
                if x.is_finite() && x > 0.0 {
                    x as f64
                } else {
                    0.0
                }
            })
            .collect();
        let total: f64 = w.iter().sum();
        let n = w.len();
        if n == 0 || total <= 0.0 {
            return Self::default();
        }
        let pdf: Vec<f64> = w.iter().map(|x| x / total).collect();
        let mut scaled: Vec<f64> = pdf.iter().map(|p| p * n as f64).collect();
        let mut entries = vec![
            AliasEntry {
                threshold: 1.0,
                alias: 0,
            };
            n
        ];
        let (mut small, mut large): (Vec<usize>, Vec<usize>) =
            (0..n).partition(|&i| scaled[i] < 1.0);
        while let (Some(s), Some(&l)) = (small.pop(), large.last()) {
            entries[s] = AliasEntry {
                threshold: scaled[s] as f32,
                alias: l as u32,
            };
            scaled[l] -= 1.0 - scaled[s];
            if scaled[l] < 1.0 {
                large.pop();
                small.push(l);
            }
        }
        // Leftovers are 1 up to rounding.
        for i in small.into_iter().chain(large) {
            entries[i] = AliasEntry {
                threshold: 1.0,
                alias: i as u32,
            };
        }
        let mut acc = 0.0;
        let mut cdf: Vec<f32> = pdf
            .iter()
            .map(|p| {
                acc += p;
                acc as f32
            })
            .collect();
        if let Some(last) = cdf.last_mut() {
            *last = 1.0;
        }
        Self {
            entries,
            pdf: pdf.into_iter().map(|p| p as f32).collect(),
            cdf,
        }
    }

    /// Number of outcomes.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether the distribution is empty.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// Samples an outcome from two uniform numbers in `[0, 1)` (the GPU
    /// does the same with one number split into column and remainder).
    pub fn sample(&self, u_column: f32, u_keep: f32) -> Option<usize> {
        if self.is_empty() {
            return None;
        }
        let n = self.entries.len();
        let i = ((u_column * n as f32) as usize).min(n - 1);
        let e = self.entries[i];
        Some(if u_keep < e.threshold {
            i
        } else {
            e.alias as usize
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn alias_table_reproduces_weights_exactly() {
        let weights = [1.0, 0.0, 3.0, 0.5, 10.0, 2.5];
        let t = AliasTable::new(&weights);
        let n = weights.len() as f64;
        let total: f64 = weights.iter().map(|&w| w as f64).sum();
        for (i, &w) in weights.iter().enumerate() {
            let mut p = t.entries[i].threshold as f64 / n;
            for e in &t.entries {
                if e.alias as usize == i {
                    p += (1.0 - e.threshold as f64) / n;
                }
            }
            assert!((p - w as f64 / total).abs() < 1e-6, "outcome {i}: {p}");
            assert!((t.pdf[i] as f64 - w as f64 / total).abs() < 1e-6);
        }
        assert_eq!(*t.cdf.last().unwrap(), 1.0);
        for k in 0..100 {
            let s = t
                .sample(k as f32 / 100.0, (k * 37 % 100) as f32 / 100.0)
                .unwrap();
            assert!(weights[s] > 0.0);
        }
        assert!(AliasTable::new(&[0.0, 0.0]).is_empty());
        assert!(AliasTable::new(&[]).sample(0.5, 0.5).is_none());
    }
}
