//! The radius schedule of Knaus & Zwicker (2011): pass i gathers in a volume whose radius is
//! the pilot radius times `s_i`, with `s_i² = Π_{j<i} (j + α)/(j + 1)`.

/// The shrink factor `s_i` of pass `pass` for parameter `alpha` (0 < α < 1):
/// `s_0 = 1` and `s_{i+1}² = s_i² (i + α)/(i + 1)`, so `s_i² ≈ i^(α−1)/Γ(α)` for large i.
///
/// Depends on the pass index alone, so any machine computes the same factor for the same pass.
/// Costs O(pass) (a few nanoseconds per pass, once per pass).
pub fn radius_scale(pass: u64, alpha: f64) -> f64 {
    let mut s2 = 1.0f64;
    for j in 0..pass {
        s2 *= (j as f64 + alpha) / (j as f64 + 1.0);
    }
    s2.sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn follows_the_recurrence() {
        let alpha = 2.0 / 3.0;
        assert_eq!(radius_scale(0, alpha), 1.0);
        let mut s2 = 1.0;
        for i in 0..50u64 {
            let s = radius_scale(i, alpha);
            assert!((s * s - s2).abs() < 1e-12, "pass {i}");
            s2 *= (i as f64 + alpha) / (i as f64 + 1.0);
        }
    }

    #[test]
    fn decays_as_a_power_of_the_pass() {
        // s_i² i^(1−α) → 1/Γ(α); Γ(2/3) = 1.354117939...
        let alpha = 2.0 / 3.0;
        let i = 100_000u64;
        let s = radius_scale(i, alpha);
        let limit = s * s * (i as f64).powf(1.0 - alpha);
        assert!((limit - 1.0 / 1.354_117_939_426_4).abs() < 1e-3, "{limit}");
    }
}
