//! Human-readable text of DOE results (terminal and reports share it):
//! the coefficient table with standard errors, t, p and 95 % intervals,
//! R², adjusted R², Q² (or why it is undefined), σ and lack of fit; the
//! predictions of a model file, a curve's stiffness and a reachable region.

use crate::model::{Factor, Prediction};
use crate::reachable::Corner;
use crate::stiffness::Stiffness;
use bumpsim_core::units::{Dimension, format_number, format_quantity};

/// The summary of one fitted response; `unit` of the response.
pub fn fit_text(response: &str, unit: Option<&str>, f: &crate::regression::Fit) -> String {
    let u = unit.unwrap_or("-");
    let mut text = format!(
        "{response} [{u}]: R² {}, adjusted R² {}, ",
        format_number(f.r2, 4),
        f.r2_adjusted.map_or("-".into(), |v| format_number(v, 4))
    );
    text += &match (f.q2, &f.q2_note) {
        (Some(q2), _) => format!(
            "Q² {} (PRESS {} {u}²)\n",
            format_number(q2, 4),
            format_number(f.press.unwrap_or(0.0), 4)
        ),
        (None, Some(note)) => format!("{note}\n"),
        _ => "Q² undefined\n".into(),
    };
    text += &coefficient_table(f, u, None);
    if let Some(sd) = f.residual_sd {
        text += &format!(
            "  residual SD {} {u} ({} degrees of freedom)\n",
            format_number(sd, 4),
            f.dof_residual
        );
    }
    if let Some(l) = &f.anova.lack_of_fit {
        text += &format!(
            "  lack of fit: F {} on ({}, {}) df, p {}\n",
            format_number(l.f, 4),
            l.df_lack_of_fit,
            l.df_pure_error,
            format_number(l.p, 3)
        );
    }
    text
}

/// The coefficient table: term, coefficient, standard error, t, p and 95 %
/// interval, and an `extra` column of standard errors (title, values);
/// coefficients, standard errors and intervals in the response's `unit`
/// (the factors are coded, so a coefficient is the response's change per
/// coded unit), t and p without unit.
fn coefficient_table(
    f: &crate::regression::Fit,
    unit: &str,
    extra: Option<(&str, &[Option<f64>])>,
) -> String {
    let opt = |v: Option<f64>| v.map_or("-".to_string(), |v| format_number(v, 4));
    let mut head = vec![
        "term (coded)".to_string(),
        format!("coefficient [{unit}]"),
        format!("std. error [{unit}]"),
        "t".into(),
        "p".into(),
        format!("95 % interval [{unit}]"),
    ];
    head.extend(extra.map(|e| e.0.to_string()));
    let mut rows = vec![head];
    for j in 0..f.terms.len() {
        let ci = f.ci95[j].map_or("-".to_string(), |[a, b]| {
            format!("{} .. {}", format_number(a, 4), format_number(b, 4))
        });
        let mut row = vec![
            f.terms[j].clone(),
            format_number(f.coefficients[j], 5),
            opt(f.std_errors[j]),
            opt(f.t[j]),
            opt(f.p[j]),
            ci,
        ];
        row.extend(extra.map(|e| opt(e.1[j])));
        rows.push(row);
    }
    aligned(&rows, &[12, 12, 12, 9, 9, 28, 14])
}

/// `rows` as lines of columns at least `least` wide (and as wide as their
/// widest cell): the first left-aligned, the others right-aligned.
fn aligned(rows: &[Vec<String>], least: &[usize]) -> String {
    let width = |c: usize| {
        let widest = rows
            .iter()
            .map(|r| r.get(c).map_or(0, |s| s.chars().count()));
        widest
            .max()
            .unwrap_or(0)
            .max(least.get(c).copied().unwrap_or(0))
    };
    let widths: Vec<usize> = (0..rows[0].len()).map(width).collect();
    let mut text = String::new();
    for row in rows {
        let cells: Vec<String> = row
            .iter()
            .zip(&widths)
            .enumerate()
            .map(|(c, (s, &w))| match c {
                0 => format!("{s:<w$}"),
                _ => format!("{s:>w$}"),
            })
            .collect();
        text += &format!("  {}\n", cells.join(" "));
    }
    text
}

/// The summary of a response fitted with its standard errors (column
/// `column`): τ from REML with the standard errors' range and the weights'
/// shares, the residual heterogeneity, weighted R² and Q², the coefficient
/// table with the OLS standard errors beside, and the notes.
pub fn weighted_text(
    response: &str,
    unit: Option<&str>,
    f: &crate::regression::Fit,
    w: &crate::weighted::Weighting,
    column: &str,
) -> String {
    if w.method == "OLS" {
        return fit_text(response, unit, f)
            + &format!("  standard errors ({column}) all 0: unweighted (τ = residual SD)\n");
    }
    let u = unit.unwrap_or("-");
    let se = &w.standard_errors;
    let (lo, hi) = se
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), s| (a.min(*s), b.max(*s)));
    let [share_lo, share_hi] = w.share_range();
    let tau = w.tau2.map_or("not estimable".into(), |t| {
        format!("{} {u}", format_number(t.sqrt(), 4))
    });
    let mut text = format!(
        "{response} [{u}]: weighted by its standard errors ({column}, {} .. {} {u}): τ (REML) {tau}; weights 1/(τ² + s²) {} .. {} % of their sum\n",
        format_number(lo, 4),
        format_number(hi, 4),
        format_number(100.0 * share_lo, 3),
        format_number(100.0 * share_hi, 3),
    );
    if let Some(h) = &w.heterogeneity {
        text += &format!(
            "  residual heterogeneity Q_E {} on {} df, p {} (small p: the runs scatter beyond their standard errors)\n",
            format_number(h.q, 4),
            h.df,
            format_number(h.p, 3)
        );
    }
    let opt = |v: Option<f64>| v.map_or("-".to_string(), |v| format_number(v, 4));
    text += &format!(
        "  R² (weighted) {}, adjusted R² {}, Q² (weighted) {}\n",
        format_number(f.r2, 4),
        opt(f.r2_adjusted),
        opt(f.q2)
    );
    let extra = format!("OLS std. error [{u}]");
    text += &coefficient_table(f, u, Some((&extra, &w.ols_std_errors)));
    text += &format!(
        "  intervals: Student t on {} degrees of freedom, covariance (XᵀWX)⁻¹\n",
        f.dof_residual
    );
    w.notes
        .iter()
        .for_each(|n| text += &format!("  note: {n}\n"));
    text
}

/// A prediction: its warnings, then each response with its unit and, where
/// known, the 95 % confidence and prediction intervals.
pub fn prediction_text(p: &Prediction) -> String {
    let mut text = String::new();
    for w in &p.warnings {
        text += &format!("warning: {w}\n");
    }
    for v in &p.values {
        let u = v.unit.clone().unwrap_or_default();
        let interval = |i: Option<[f64; 2]>, what: &str| {
            i.map_or(String::new(), |[a, b]| {
                format!(
                    "; {what} {} .. {} {u}",
                    format_number(a, 4),
                    format_number(b, 4)
                )
            })
        };
        text += &format!(
            "{} = {} {u}{}{}\n",
            v.name,
            format_number(v.value, 4),
            interval(v.ci95, "95 % CI"),
            interval(v.pi95, "95 % PI")
        );
    }
    text
}

/// A curve's stiffness with its fit range, intercept, residual and R².
pub fn stiffness_text(s: &Stiffness) -> String {
    format!(
        "stiffness {} (line through {} points, {} .. {}; intercept {}; residual RMS {}; {})\n",
        format_quantity(s.slope, Dimension::Stiffness),
        s.points,
        format_quantity(s.range[0], Dimension::Length),
        format_quantity(s.range[1], Dimension::Length),
        format_quantity(s.intercept, Dimension::Force),
        format_quantity(s.residual_rms, Dimension::Force),
        match s.r2 {
            Some(r2) => format!("R² {}", format_number(r2, 5)),
            None => "R² undefined: the force does not vary".into(),
        }
    )
}

/// The reachable region of responses `x`, `y`: its vertices, then each
/// cell corner with the coded factor set that reaches it (or comes closest).
pub fn reach_text(
    axes: [&str; 2],
    units: [Option<&str>; 2],
    polygon: &[[f64; 2]],
    samples: usize,
    corners: &[Corner],
    factors: &[Factor],
) -> String {
    let [x, y] = axes;
    let mut text = format!(
        "reachable region of ({x}, {y}): {} vertices; {samples} random factor sets\n",
        polygon.len()
    );
    // each vertex names its responses and their units (the model file's)
    let unit = |u: Option<&str>| u.map_or(String::new(), |u| format!(" {u}"));
    let (ux, uy) = (unit(units[0]), unit(units[1]));
    for v in polygon {
        text += &format!(
            "  vertex {x} = {}{ux}, {y} = {}{uy}\n",
            format_number(v[0], 6),
            format_number(v[1], 6)
        );
    }
    corners
        .iter()
        .for_each(|c| text += &corner_line(c, factors, [&ux, &uy]));
    text
}

/// A cell corner `(x ux, y uy)` and how far its closest factor set misses
/// it: a distance in the plane of both responses, in their unit when they
/// share one.
fn corner_line(c: &Corner, factors: &[Factor], units: [&str; 2]) -> String {
    let set: Vec<String> = c
        .factors
        .iter()
        .zip(factors)
        .map(|(t, f)| format!("{}={}", f.name, format_number(*t, 4)))
        .collect();
    let (x, y, set) = (c.target[0], c.target[1], set.join(", "));
    let [ux, uy] = units;
    let distance = match (ux == uy, ux.is_empty() || uy.is_empty()) {
        (true, _) => ux.to_string(),
        (false, false) => format!(" (in {}, {})", ux.trim(), uy.trim()),
        (false, true) => String::new(),
    };
    match c.reachable {
        true => format!(
            "corner ({x}{ux}, {y}{uy}): reachable with coded {set} (residual {}{distance})\n",
            format_number(c.residual, 3)
        ),
        false => format!(
            "corner ({x}{ux}, {y}{uy}): UNREACHABLE; closest coded {set} misses by {}{distance}\n",
            format_number(c.residual, 4)
        ),
    }
}
