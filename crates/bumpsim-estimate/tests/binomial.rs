//! Issue 45 item 7: a probability's exact bounds are statsmodels'
//! `proportion_confint(method="beta")` (Clopper–Pearson), two-sided at
//! 95 % inside and one-sided (its 90 % two-sided end) with no failure or
//! no pass.

use bumpsim_estimate::binomial::Bounds;
use std::process::Command;

/// statsmodels' Clopper–Pearson bounds of `k` of `n` at `alpha`.
fn theirs(cases: &[(usize, usize, f64)]) -> Vec<[f64; 2]> {
    let list: Vec<String> = cases
        .iter()
        .map(|(k, n, a)| format!("({k}, {n}, {a})"))
        .collect();
    let code = format!(
        "from statsmodels.stats.proportion import proportion_confint\n\
         for k, n, a in [{}]:\n    print(*proportion_confint(k, n, alpha=a, method='beta'))",
        list.join(", ")
    );
    let run = Command::new("python3")
        .args(["-c", &code])
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let numbers: Vec<f64> = String::from_utf8_lossy(&run.stdout)
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect();
    numbers.chunks(2).map(|c| [c[0], c[1]]).collect()
}

#[test]
fn the_bounds_are_statsmodels_clopper_pearson() {
    if !bumpsim_peers::python_available("statsmodels") {
        return;
    }
    let inside = [
        (1, 50),
        (7, 40),
        (193, 200),
        (100, 200),
        (399, 400),
        (3, 10),
    ];
    // a one-sided 95 % bound is the end of the two-sided 90 % interval
    let ends = [(200, 200), (40, 40), (0, 200), (0, 13)];
    let cases: Vec<(usize, usize, f64)> = inside
        .iter()
        .map(|&(k, n)| (k, n, 0.05))
        .chain(ends.iter().map(|&(k, n)| (k, n, 0.10)))
        .collect();
    for ((k, n, _), [low, high]) in cases.iter().zip(theirs(&cases)) {
        let b = Bounds::of(*k, *n);
        let near = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs().max(1e-6);
        assert_eq!(b.one_sided, k == n || *k == 0, "{k} of {n}");
        assert!(
            near(b.low, low) && near(b.high, high),
            "{k} of {n}: ours {}–{}, statsmodels {low}–{high}",
            b.low,
            b.high
        );
    }
}
