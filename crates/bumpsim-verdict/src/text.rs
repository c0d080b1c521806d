//! The verdict and the target region as text with units: the table of
//! tests × criteria the terminal, the report and the bindings print.

use crate::criteria::{Criterion, Outcome};
use crate::verdict::Verdict;

/// A criterion's outcome as a word.
pub fn outcome(c: &Criterion) -> &'static str {
    match c.outcome {
        Outcome::Pass => "pass",
        Outcome::Fail => "FAIL",
        Outcome::Info => "info",
    }
}

/// The rows of the verdict table: test, criterion, value, limit, margin
/// (with its ratio), outcome, detail; a test not assessed is one row.
pub fn rows(v: &Verdict) -> Vec<[String; 7]> {
    let mut rows = Vec::new();
    for t in &v.tests {
        if let Some(why) = &t.skipped {
            rows.push([
                t.test.name.into(),
                "not assessed".into(),
                String::new(),
                String::new(),
                String::new(),
                "-".into(),
                why.clone(),
            ]);
            continue;
        }
        for c in &t.criteria {
            let q = c.quantity;
            let sign = if c.upper { "≤" } else { "≥" };
            rows.push([
                t.test.name.into(),
                c.name.clone(),
                q.format(c.value),
                format!("{sign} {}", q.format(c.limit)),
                format!("{} ({:+.1} %)", q.format(c.margin), 100.0 * c.ratio),
                outcome(c).into(),
                c.detail.clone(),
            ]);
        }
    }
    rows
}

/// The column headers of [`rows`].
pub const HEADERS: [&str; 7] = [
    "test",
    "criterion",
    "value",
    "limit",
    "margin",
    "verdict",
    "detail",
];

/// The verdict as a text table, then each test's verdict, pulse and assumptions.
pub fn table(v: &Verdict) -> String {
    let rows = rows(v);
    let widths: Vec<usize> = (0..6)
        .map(|i| {
            rows.iter()
                .map(|r| r[i].chars().count())
                .chain([HEADERS[i].len()])
                .max()
                .unwrap_or(0)
        })
        .collect();
    let line = |cells: [&str; 7]| {
        let mut s: String = (0..6)
            .map(|i| format!("{:<w$}  ", cells[i], w = widths[i]))
            .collect();
        s += cells[6];
        s.trim_end().to_string() + "\n"
    };
    let mut out = format!(
        "{}: verdict with a margin of {} %\n",
        v.car,
        100.0 * v.margin
    );
    out += &line(HEADERS);
    for r in &rows {
        out += &line([&r[0], &r[1], &r[2], &r[3], &r[4], &r[5], &r[6]]);
    }
    out += &summary(v);
    out
}

/// One line per test: its verdict, binding criterion and pulse; then the assumptions.
pub fn summary(v: &Verdict) -> String {
    let g = bumpsim_planar::car::GRAVITY;
    let mut out = String::new();
    for t in &v.tests {
        let (Some(passed), Some(m)) = (t.passed(), &t.metrics) else {
            continue;
        };
        let word = if passed { "passes" } else { "FAILS" };
        let binding = t.binding().map_or(String::new(), |c| {
            format!(
                ", binding {} (margin {})",
                c.name,
                c.quantity.format(c.margin)
            )
        });
        let olc = m.olc.map_or("-".into(), |o| format!("{:.2} g", o / g));
        let asi = m.asi.map_or("-".into(), |a| format!("{a:.3}"));
        out += &format!(
            "{} {word}{binding}; peak {:.2} g, 3 ms clip {:.2} g, delta-V {:.2} km/h, OLC {olc}, ASI {asi}\n",
            t.test.name,
            m.peak / g,
            m.clip / g,
            m.delta_v * 3.6
        );
    }
    let failures = v.failures();
    out += &match failures.is_empty() {
        true => "every assessed test passes\n".to_string(),
        false => format!(
            "{} criterion/criteria fail: {}\n",
            failures.len(),
            failures
                .iter()
                .map(|(t, c)| format!("{} in {t} (margin {})", c.name, c.quantity.format(c.margin)))
                .collect::<Vec<_>>()
                .join("; ")
        ),
    };
    for t in v.tests.iter().filter(|t| t.skipped.is_none()) {
        for a in t.assumptions.iter().chain(&t.notes).chain(&t.warnings) {
            out += &format!("  {}: {a}\n", t.test.name);
        }
    }
    out
}
