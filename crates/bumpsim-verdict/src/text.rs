//! The verdict and the target region as text with units: the table of
//! tests × criteria the terminal, the report and the bindings print.

use crate::criteria::{Criterion, Outcome};
use crate::target::{Bound, Region};
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
                margin(c),
                outcome(c).into(),
                c.detail.clone(),
            ]);
        }
    }
    rows
}

/// A criterion's margin with its ratio, `53.33 mm (+88.9 %)` (a share of
/// the limit), or with the ratio's reference where that is not the limit:
/// `6.400 mm (+6.3 % of 101.6 mm)`.
pub fn margin(c: &Criterion) -> String {
    let q = c.quantity;
    match c.of_limit() {
        true => format!("{} ({:+.1} %)", q.format(c.margin), 100.0 * c.ratio),
        false => format!(
            "{} ({:+.1} % of {})",
            q.format(c.margin),
            100.0 * c.ratio,
            q.format(c.reference)
        ),
    }
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

/// A criterion's probability of passing with its exact 95 % bounds,
/// `93.8 % (90.0–96.4 %)`, or `≥ 98.5 %` when no draw failed (empty when
/// not propagated or not judged; [`bumpsim_estimate::binomial`]).
pub fn chance(c: &Criterion) -> String {
    c.probability.map_or(String::new(), |p| p.cell())
}

/// The headers and rows of the verdict table: [`rows`], with each
/// criterion's probability of passing (`P(pass)`) before the detail when
/// the verdict was propagated ([`crate::probability`]).
pub fn columns(v: &Verdict) -> (Vec<&'static str>, Vec<Vec<String>>) {
    let mut headers = HEADERS.to_vec();
    let chances = v.tests.iter().flat_map(|t| match &t.skipped {
        Some(_) => vec![String::new()],
        None => t.criteria.iter().map(chance).collect(),
    });
    let propagated = v.propagation.is_some();
    let rows = rows(v)
        .into_iter()
        .zip(chances)
        .map(|(row, p)| {
            let mut row = row.to_vec();
            if propagated {
                row.insert(6, p);
            }
            row
        })
        .collect();
    if propagated {
        headers.insert(6, "P(pass)");
    }
    (headers, rows)
}

/// The verdict as a text table, then each test's verdict, pulse and assumptions.
pub fn table(v: &Verdict) -> String {
    let (headers, rows) = columns(v);
    let last = headers.len() - 1;
    let widths: Vec<usize> = (0..last)
        .map(|i| {
            rows.iter()
                .map(|r| r[i].chars().count())
                .chain([headers[i].chars().count()])
                .max()
                .unwrap_or(0)
        })
        .collect();
    let line = |cells: &[&str]| {
        let mut s: String = (0..last)
            .map(|i| format!("{:<w$}  ", cells[i], w = widths[i]))
            .collect();
        s += cells[last];
        s.trim_end().to_string() + "\n"
    };
    let mut out = format!(
        "{}: verdict with a margin of {} %\n",
        v.car,
        100.0 * v.margin
    );
    out += &line(&headers);
    for r in &rows {
        out += &line(&r.iter().map(String::as_str).collect::<Vec<_>>());
    }
    out += &summary(v);
    out += &propagation(v);
    out += &crate::requirements::lines(&v.requirements);
    out
}

/// The probability of passing of each test and of the verdict, with what
/// was propagated (empty when not propagated).
pub fn propagation(v: &Verdict) -> String {
    let Some(p) = &v.propagation else {
        return String::new();
    };
    let u = &p.uncertainty;
    let mut out = format!(
        "probability of passing with exact 95 % bounds over {} ({} draws, seed {}, {} failed; {}): every test: {}\n",
        u.source,
        p.samples,
        p.seed,
        p.failed,
        u.described(),
        p.passing.sentence()
    );
    for t in &v.tests {
        if let Some(chance) = &t.probability {
            out += &format!("  {}: {}\n", t.test.name, chance.sentence());
        }
    }
    for left in &u.left_out {
        out += &format!("  not propagated: {left}\n");
    }
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
            "{} {word}{binding}; peak {:.2} g, 3 ms clip {:.2} g, delta-V {:.2} km/h to the contact end at {:.1} ms, OLC {olc}, ASI {asi} ({})\n",
            t.test.name,
            m.peak / g,
            m.clip / g,
            m.delta_v * 3.6,
            m.contact_end * 1e3,
            m.asi_method.name()
        );
        if let Some(b) = t.bottomed {
            out += &format!(
                "  {}: the bumper bottomed at segment {} (y = {:.0} mm) at t = {:.1} ms: what is reached after it is on the blocked load path\n",
                t.test.name,
                b.segment + 1,
                b.centre * 1e3,
                b.time * 1e3
            );
        }
        if let Some(b) = t.box_bottomed {
            out += &format!(
                "  {}: the {} crash box (y = {:.0} mm) bottomed at t = {:.1} ms: from then on its force goes into the rail through the block\n",
                t.test.name,
                b.side.name(),
                b.y * 1e3,
                b.time * 1e3
            );
        }
    }
    out += &sequence(&v.tests);
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

/// The protocols and their tests, each test with its source and what is
/// uncertain (`bumpsim verdict --list`), heights for the default market.
pub fn protocols() -> String {
    protocols_for(bumpsim_io::protocols::Market::default())
}

/// [`protocols`] with the heights of the vehicle's target market.
pub fn protocols_for(market: bumpsim_io::protocols::Market) -> String {
    use bumpsim_io::protocols::{Market, RCAR_BACKSTOP};
    let mut out = format!(
        "the tests of the one table (bumpsim impact --case list, bumpsim planar --case list), by protocol; heights for the market {} (--market)\n",
        market.name()
    );
    for p in crate::protocol::PROTOCOLS {
        out += &format!("{}: {}\n", p.name, p.description);
        if let Some(r) = crate::requirements::of(p.name) {
            out += &crate::requirements::described(r, "  ");
        }
        for t in p
            .tests
            .iter()
            .filter_map(|name| crate::protocol::test_in(name, market))
        {
            out += &format!(
                "  {}: {}\n    speed {:.3} km/h; height: {}\n    source: {}\n    uncertain: {}\n",
                t.name,
                t.description,
                t.speed() * 3.6,
                height(&t.height),
                t.source,
                t.uncertain
            );
            if t.entry.height == bumpsim_io::protocols::Height::RcarBarrier {
                let other = match market {
                    Market::NorthAmerica => Market::Europe,
                    Market::Europe => Market::NorthAmerica,
                };
                let (b, h) = other.rcar_face();
                out += &format!(
                    "    barrier: {}; rigid backstop {:.0} mm tall above it, {:.0} mm behind the face (specification Issue 1, 2007, §2.2); {}: {:.0}-{:.0} mm; {}\n",
                    height(&t.height),
                    1e3 * RCAR_BACKSTOP.0,
                    1e3 * RCAR_BACKSTOP.1,
                    other.name(),
                    1e3 * b,
                    1e3 * h,
                    bumpsim_io::protocols::MARKET_UNCERTAIN
                );
            }
        }
    }
    out
}

fn height(h: &crate::protocol::Height) -> String {
    use crate::protocol::Height;
    match *h {
        Height::Ridge { low, high } if low == high => format!("line at {:.0} mm", 1e3 * low),
        Height::Ridge { low, high } => {
            format!("line at any height {:.0}-{:.0} mm", 1e3 * low, 1e3 * high)
        }
        Height::Face { bottom, top } => format!("face {:.0}-{:.0} mm", 1e3 * bottom, 1e3 * top),
        Height::Full => "taller than any bumper".into(),
        Height::Unknown => "not given by the source read here".into(),
    }
}

/// The target region as a table: per whole-bumper stiffness (kN/mm), the
/// passing force levels (kN) and the criterion binding at each boundary.
pub fn region(r: &Region) -> String {
    let bound = |b: &Bound| {
        let binding = b.binding.as_deref().unwrap_or("the search range");
        format!("{:.1} kN ({binding})", b.force / 1e3)
    };
    let mut out = format!(
        "bumper target with a margin of {} % ({} impacts in {:.2} s, {:.0} impacts/s); the car's bumper: {:.2} kN/mm, {:.1} kN\n",
        100.0 * r.margin,
        r.impacts,
        r.seconds,
        r.rate(),
        r.origin[0] / 1e6,
        r.origin[1] / 1e3
    );
    for row in &r.rows {
        let own = match r.own_row() == Some(row) {
            true => " (the car's)",
            false => "",
        };
        out += &format!("  stiffness {:.2} kN/mm{own}: ", row.stiffness / 1e6);
        out += &match (&row.interval, &row.failing) {
            (Some([low, high]), _) => format!(
                "force from {} to {}, stroke needed {}\n",
                bound(low),
                bound(high),
                row.stroke
                    .map_or("-".into(), |s| format!("{:.1} mm", 1e3 * s))
            ),
            (None, failing) => format!(
                "nothing passes ({})\n",
                failing.as_deref().unwrap_or("every level fails")
            ),
        };
    }
    out += &own(r);
    if let Some(why) = &r.diagnosis {
        out += &format!("  {why}\n");
    }
    out
}

/// The lines that say what each test of a sequence inherited and what it
/// changed (empty without a sequence).
pub fn sequence(tests: &[crate::verdict::TestVerdict]) -> String {
    let mut out = String::new();
    for t in tests {
        let Some(i) = &t.inherited else { continue };
        out += &format!(
            "  {} in sequence after {}: inherits a permanent set of up to {:.2} mm (segment {})",
            t.test.name,
            i.from.join(", "),
            i.set * 1e3,
            i.segment + 1
        );
        out += &match i.changes.is_empty() {
            true => "; every criterion as run alone (the set is not reached or nil)\n".into(),
            false => {
                let each: Vec<String> = i
                    .changes
                    .iter()
                    .map(|c| {
                        format!(
                            "{} {} (alone {})",
                            c.criterion,
                            c.quantity.format(c.sequence),
                            c.quantity.format(c.alone)
                        )
                    })
                    .collect();
                format!(
                    "; against the test run alone, the inherited damage changes: {}\n",
                    each.join(", ")
                )
            }
        };
    }
    out
}

/// Where the car's own bumper lies against its stiffness's row: inside
/// the passing force interval, below or above it, or in a row where
/// nothing passes.
pub fn own(r: &Region) -> String {
    let Some(row) = r.own_row() else {
        return String::new();
    };
    let force = r.origin[1];
    let place = match &row.interval {
        None => "nothing passes at its stiffness".to_string(),
        Some([low, _]) if force < low.force => format!(
            "below the least passing force {:.1} kN at its stiffness: it fails",
            low.force / 1e3
        ),
        Some([_, high]) if force > high.force => format!(
            "above the largest passing force {:.1} kN at its stiffness: it fails",
            high.force / 1e3
        ),
        Some(_) => "within the passing force interval at its stiffness".to_string(),
    };
    format!(
        "  the car's bumper ({:.2} kN/mm, {:.1} kN): {place}\n",
        r.origin[0] / 1e6,
        force / 1e3
    )
}
