//! The Pareto front of (time, error) points and the time a configuration takes to converge.

use super::measure::Measurement;
use super::metric::Metric;

/// The Pareto front of `points` (time, error), both to be small: the indices of the points no
/// other point dominates (one at most as slow and at most as wrong, and better in one of the two),
/// by increasing time. Points with a non-finite coordinate are neither on the front nor dominate.
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<usize> {
    let finite = |&(x, y): &(f64, f64)| x.is_finite() && y.is_finite();
    let dominates =
        |q: (f64, f64), p: (f64, f64)| q.0 <= p.0 && q.1 <= p.1 && (q.0 < p.0 || q.1 < p.1);
    let mut front: Vec<usize> = (0..points.len())
        .filter(|&i| finite(&points[i]))
        .filter(|&i| {
            !points
                .iter()
                .filter(|q| finite(q))
                .any(|&q| dominates(q, points[i]))
        })
        .collect();
    front.sort_by(|&a, &b| {
        points[a]
            .0
            .total_cmp(&points[b].0)
            .then(points[a].1.total_cmp(&points[b].1))
    });
    front
}

/// The cumulative GPU time of the first measurement whose `metric` falls below `target` (its
/// actual time, not the target time it was taken for); `None` if none does.
pub fn time_to_converge(rows: &[Measurement], metric: Metric, target: f64) -> Option<f64> {
    rows.iter()
        .find(|row| metric.of(row) < target)
        .map(|row| row.gpu_ms)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pareto_front_is_the_points_nothing_beats_in_both() {
        // (ms per frame, error)
        let points = [
            (1.0, 0.50),     // 0: fastest: on the front
            (2.0, 0.20),     // 1: on the front
            (2.5, 0.30),     // 2: dominated by 1 (slower and worse)
            (4.0, 0.05),     // 3: most accurate: on the front
            (4.0, 0.06),     // 4: as slow as 3 and worse: dominated
            (2.0, 0.20),     // 5: equal to 1: neither dominates the other
            (0.5, f64::NAN), // 6: no error: not on the front, dominates nothing
            (8.0, 0.05),     // 7: as accurate as 3, slower: dominated
        ];
        assert_eq!(pareto_front(&points), vec![0, 1, 5, 3]);
        assert_eq!(pareto_front(&[]), Vec::<usize>::new());
        assert_eq!(pareto_front(&[(3.0, 0.1)]), vec![0]);
    }

    #[test]
    fn time_to_converge_is_the_first_time_below_the_target() {
        let row = |frame, gpu_ms, dssim| Measurement {
            frame,
            target_ms: None,
            gpu_ms,
            frame_ms: 2.0,
            dssim,
            flip: 0.5,
            rel_mse: 0.5,
        };
        let rows = [
            row(1, 2.0, 0.3),
            row(2, 4.0, 0.09),
            row(3, 6.0, 0.12),
            row(4, 8.0, 0.05),
        ];
        assert_eq!(time_to_converge(&rows, Metric::Dssim, 0.1), Some(4.0));
        assert_eq!(time_to_converge(&rows, Metric::Dssim, 0.09), Some(8.0));
        assert_eq!(time_to_converge(&rows, Metric::Flip, 0.1), None);
    }
}
