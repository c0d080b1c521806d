//! Honest bounds on a probability estimated from `k` successes in `n`
//! draws (issue 45, item 7): the exact Clopper–Pearson interval.
//!
//! - **Interval**: with `0 < k < n`, the two-sided 95 % interval
//!   `[B(α/2; k, n − k + 1), B(1 − α/2; k + 1, n − k)]`, B the beta
//!   quantile (Clopper & Pearson 1934; statsmodels' `proportion_confint`
//!   with `method="beta"`). It holds its coverage for every p, where the
//!   Wald interval `p ± z √(p (1 − p)/n)` collapses to a point at p = 0
//!   or 1: 200 passes in 200 draws gave `100.0 ± 0.0 %`.
//! - **No failure** (`k = n`): the one-sided 95 % lower bound
//!   `α^(1/n)` (the exact bound; about `1 − 3/n`, the rule of three):
//!   98.5 % at 200 draws. The draws that would show a higher bound with no
//!   failure are `⌈ln α / ln p⌉` ([`draws_needed`]): 299 for 99 %.
//!   Likewise with no pass (`k = 0`) the one-sided upper bound
//!   `1 − α^(1/n)`.
//!
//! ```
//! use bumpsim_estimate::binomial::{Bounds, draws_needed};
//! let b = Bounds::of(200, 200);
//! assert!(b.one_sided && (b.low - 0.05f64.powf(1.0 / 200.0)).abs() < 1e-15);
//! assert_eq!(draws_needed(0.99), 299);
//! ```

use serde::Serialize;
use statrs::distribution::{Beta, ContinuousCDF};

/// The confidence of the bounds, 1.
pub const CONFIDENCE: f64 = 0.95;

/// The levels a "would show" sentence names, 1.
const LEVELS: [f64; 6] = [0.9, 0.95, 0.99, 0.995, 0.999, 0.9999];

/// 95 % bounds of a probability from `passed` of `count` draws.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Bounds {
    /// Lower bound, 1.
    pub low: f64,
    /// Upper bound, 1.
    pub high: f64,
    /// Whether the bounds are one-sided (no failure: `high` = 1; no
    /// pass: `low` = 0), else two-sided.
    pub one_sided: bool,
}

impl Bounds {
    /// The Clopper–Pearson bounds of `passed` successes in `count` draws
    /// (NaN without a draw).
    pub fn of(passed: usize, count: usize) -> Bounds {
        let alpha = 1.0 - CONFIDENCE;
        let (k, n) = (passed as f64, count as f64);
        let (low, high, one_sided) = match (passed, count) {
            (_, 0) => (f64::NAN, f64::NAN, false),
            (passed, count) if passed >= count => (alpha.powf(1.0 / n), 1.0, true),
            (0, _) => (0.0, 1.0 - alpha.powf(1.0 / n), true),
            _ => (
                beta_quantile(k, n - k + 1.0, alpha / 2.0),
                beta_quantile(k + 1.0, n - k, 1.0 - alpha / 2.0),
                false,
            ),
        };
        Bounds {
            low,
            high,
            one_sided,
        }
    }
}

/// The `q` quantile of Beta(a, b), a, b > 0.
fn beta_quantile(a: f64, b: f64, q: f64) -> f64 {
    Beta::new(a, b).map_or(f64::NAN, |d| d.inverse_cdf(q))
}

/// The draws that, all passing, give a one-sided 95 % lower bound of at
/// least `level` (0 < level < 1): `⌈ln α / ln level⌉`.
pub fn draws_needed(level: f64) -> usize {
    let alpha = 1.0 - CONFIDENCE;
    (alpha.ln() / level.ln()).ceil() as usize
}

/// A percentage with one decimal that does not round up past a lower
/// bound or down past an upper one (98.51 % stays 98.5 %, not 98.6 %).
fn percent(v: f64, up: bool) -> String {
    let tenths = 1000.0 * v;
    let tenths = match up {
        true => (tenths - 1e-9).ceil(),
        false => (tenths + 1e-9).floor(),
    };
    format!("{:.1}", tenths / 10.0)
}

/// The probability with its bounds, short for a table cell: `93.8 %
/// (90.0–96.4 %)`; `≥ 98.5 %` with no failure, `≤ 1.5 %` with no pass.
pub fn cell(p: f64, b: &Bounds) -> String {
    match (b.one_sided, b.high >= 1.0) {
        (true, true) => format!("≥ {} %", percent(b.low, false)),
        (true, false) => format!("≤ {} %", percent(b.high, true)),
        (false, _) => format!(
            "{:.1} % ({}–{} %)",
            100.0 * p,
            percent(b.low, false),
            percent(b.high, true)
        ),
    }
}

/// The probability with its bounds as a sentence: `no failure in 200
/// draws: P(pass) ≥ 98.5 % (95 % one-sided); 299 draws would show ≥ 99 %`,
/// `193 of 200 draws pass: 96.5 % (95 %: 92.9–98.6 %)`.
pub fn sentence(passed: usize, count: usize, b: &Bounds) -> String {
    let p = passed as f64 / count as f64;
    match (b.one_sided, passed >= count) {
        _ if count == 0 => "no draw could be judged".into(),
        (true, true) => {
            let next = LEVELS.iter().find(|l| **l > b.low + 1e-12);
            let more = next.map_or(String::new(), |l| {
                let shown = format!("{:.2}", 100.0 * l);
                let shown = shown.trim_end_matches('0').trim_end_matches('.');
                format!("; {} draws would show ≥ {shown} %", draws_needed(*l))
            });
            format!(
                "no failure in {count} draws: P(pass) ≥ {} % (95 % one-sided){more}",
                percent(b.low, false)
            )
        }
        (true, false) => format!(
            "no pass in {count} draws: P(pass) ≤ {} % (95 % one-sided)",
            percent(b.high, true)
        ),
        (false, _) => format!(
            "{passed} of {count} draws pass: {:.1} % (95 %: {}–{} %)",
            100.0 * p,
            percent(b.low, false),
            percent(b.high, true)
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// No failure in 200 draws: the exact one-sided bound 0.05^(1/200) =
    /// 98.51 %, printed 98.5 % (never rounded up), and 299 draws for 99 %
    /// (0.99^298 = 0.0501 > 0.05 ≥ 0.99^299 = 0.0496); not 100.0 ± 0.0 %.
    #[test]
    fn no_failure_in_200_draws_bounds_the_probability_at_98_5_percent() {
        let b = Bounds::of(200, 200);
        assert!(b.one_sided && b.low >= 0.985 && b.low < 0.9852 && b.high == 1.0);
        assert_eq!(cell(1.0, &b), "≥ 98.5 %");
        assert_eq!(
            sentence(200, 200, &b),
            "no failure in 200 draws: P(pass) ≥ 98.5 % (95 % one-sided); 299 draws would show ≥ 99 %"
        );
        assert!(0.99f64.powi(298) > 0.05 && 0.99f64.powi(299) <= 0.05);
        assert_eq!(draws_needed(0.99), 299);
    }

    /// No pass: the mirror bound; no draw: NaN, said.
    #[test]
    fn no_pass_and_no_draw_are_said() {
        let b = Bounds::of(0, 200);
        assert!(
            b.one_sided && b.low == 0.0 && (b.high - (1.0 - 0.05f64.powf(0.005))).abs() < 1e-15
        );
        assert_eq!(cell(0.0, &b), "≤ 1.5 %");
        assert!(Bounds::of(0, 0).low.is_nan());
        assert_eq!(sentence(0, 0, &Bounds::of(0, 0)), "no draw could be judged");
    }

    /// The two-sided interval against the closed form of its ends at
    /// k = 1 and k = n − 1, where the beta quantile has one: B(α/2; 1, n)
    /// = 1 − (1 − α/2)^(1/n).
    #[test]
    fn the_two_sided_ends_match_their_closed_forms() {
        let n = 50;
        let b = Bounds::of(1, n);
        let low = 1.0 - (1.0 - 0.025f64).powf(1.0 / n as f64);
        assert!(
            (b.low - low).abs() < 1e-12 * low.max(1e-3),
            "{} vs {low}",
            b.low
        );
        let b = Bounds::of(n - 1, n);
        let high = (1.0 - 0.025f64).powf(1.0 / n as f64);
        assert!((b.high - high).abs() < 1e-12, "{} vs {high}", b.high);
    }
}
