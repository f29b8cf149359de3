//! The radius schedule of Knaus & Zwicker (2011): pass i gathers in a volume whose radius is
//! the pilot radius times `s_i`, with `s_i² = Π_{j<i} (j + α)/(j + 1)`, in closed form so that
//! any pass index costs the same.

pub use crate::limits::MAX_PASS;

/// The pass index whose photon streams trace the pilot map (never a render pass).
pub const PILOT_PASS: u64 = u64::MAX;

const _: () = assert!(MAX_PASS == PILOT_PASS - 1);

/// Below this pass the product is multiplied out (at most this many factors); from it on the
/// asymptotic series of `ln Γ` is accurate to f64 rounding.
const SERIES_FROM: u64 = 64;

/// `ln Γ(x + a) − ln Γ(x + 1)` for `x ≥ SERIES_FROM` and `0 < a < 1`, by the asymptotic
/// expansion `ln Γ(x + a) ~ (x + a − ½) ln x − x + ½ ln 2π + Σ_n (−1)^(n+1) B_(n+1)(a) / (n (n+1) xⁿ)`
/// (B the Bernoulli polynomials): the large terms cancel in closed form, which a difference
/// of two `ln Γ` values near 10²⁰ could not do in f64.
fn ln_gamma_ratio(x: f64, a: f64) -> f64 {
    // B_2 … B_6 at a, minus the same at 1.
    let b = |a: f64| {
        let (a2, a3) = (a * a, a * a * a);
        let (a4, a5, a6) = (a2 * a2, a2 * a3, a3 * a3);
        [
            a2 - a + 1.0 / 6.0,
            a3 - 1.5 * a2 + 0.5 * a,
            a4 - 2.0 * a3 + a2 - 1.0 / 30.0,
            a5 - 2.5 * a4 + 5.0 / 3.0 * a3 - a / 6.0,
            a6 - 3.0 * a5 + 2.5 * a4 - 0.5 * a2 + 1.0 / 42.0,
        ]
    };
    let (ba, b1) = (b(a), b(1.0));
    let mut series = 0.0;
    let mut x_n = 1.0;
    for n in 1..=5 {
        x_n *= x;
        let sign = if n % 2 == 1 { 1.0 } else { -1.0 };
        series += sign * (ba[n - 1] - b1[n - 1]) / ((n * (n + 1)) as f64 * x_n);
    }
    (a - 1.0) * x.ln() + series
}

/// The shrink factor `s_i` of pass `pass` for parameter `alpha` (0 < α < 1):
/// `s_0 = 1` and `s_{i+1}² = s_i² (i + α)/(i + 1)`, so
/// `s_i² = Γ(i + α) / (Γ(α) Γ(i + 1)) ≈ i^(α−1)/Γ(α)` for large i.
///
/// Depends on the pass index alone, so any machine computes the same factor for the same pass.
/// Costs the same for every pass (at most 64 factors, then a ratio of Gamma functions through
/// the asymptotic series of `ln Γ`), up to [`MAX_PASS`] and beyond.
pub fn radius_scale(pass: u64, alpha: f64) -> f64 {
    let mut s2 = 1.0f64;
    for j in 0..pass.min(SERIES_FROM) {
        s2 *= (j as f64 + alpha) / (j as f64 + 1.0);
    }
    if pass > SERIES_FROM {
        // s_i² = s_T² · Γ(i + α) Γ(T + 1) / (Γ(T + α) Γ(i + 1)).
        let t = SERIES_FROM as f64;
        s2 *= (ln_gamma_ratio(pass as f64, alpha) - ln_gamma_ratio(t, alpha)).exp();
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
        for i in 0..5000u64 {
            let s = radius_scale(i, alpha);
            assert!((s * s / s2 - 1.0).abs() < 1e-12, "pass {i}: {} vs {s2}", s * s);
            s2 *= (i as f64 + alpha) / (i as f64 + 1.0);
        }
    }

    #[test]
    fn follows_the_recurrence_for_other_alphas() {
        for alpha in [0.01, 0.3, 0.5, 0.99] {
            let mut s2 = 1.0;
            for i in 0..300u64 {
                let s = radius_scale(i, alpha);
                assert!((s * s / s2 - 1.0).abs() < 1e-12, "α {alpha} pass {i}");
                s2 *= (i as f64 + alpha) / (i as f64 + 1.0);
            }
        }
    }

    #[test]
    fn decays_as_a_power_of_the_pass() {
        // s_i² i^(1−α) → 1/Γ(α); Γ(2/3) = 1.354117939...
        let alpha = 2.0 / 3.0;
        let inverse_gamma = 1.0 / 1.354_117_939_426_400_4;
        for i in [100_000u64, 1 << 40, 1_000_000_000_000, MAX_PASS] {
            let s = radius_scale(i, alpha);
            let limit = s * s * (i as f64).powf(1.0 - alpha);
            // The next term of the expansion is (α−1)α/(2i) relative.
            let tolerance = 1e-12 + 0.2 / i as f64;
            assert!(
                (limit / inverse_gamma - 1.0).abs() < tolerance,
                "pass {i}: {limit}"
            );
        }
    }

    #[test]
    fn the_last_pass_costs_what_the_first_does() {
        // A loop to the pass index would not return within the test's lifetime.
        let s = radius_scale(MAX_PASS, 2.0 / 3.0);
        assert!(s.is_finite() && s > 0.0 && s < 1e-3, "{s}");
    }
}
