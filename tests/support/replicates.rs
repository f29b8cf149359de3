//! Statistics of independent replicates: their mean and the standard error of that mean.

/// Mean of `values` and the standard error of the mean (sample variance over n − 1, then
/// over n); the error is 0 for a single value.
pub fn mean_and_error(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0).max(1.0);
    (mean, (var / n).sqrt())
}
