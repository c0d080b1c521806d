//! The bumper characteristic as a nonlinear discrete spring for FE solvers
//! (spec §5 and §8; issue 16).
//!
//! The characteristic of `bumpsim impact` — a loading curve F(d) from
//! (0, 0) and an elastic unloading slope s_u — becomes:
//!
//! - LS-DYNA: `*MAT_SPRING_GENERAL_NONLINEAR` (MAT_S06) with a loading curve
//!   `LCDL` and an unloading curve `LCDU` (the line F = s_u·d up to the
//!   largest loading force; LS-DYNA shifts it to the point where unloading
//!   starts, which is the elastic unloading of spec §5), a translational
//!   `*SECTION_DISCRETE`, a `*PART`, and with two nodes an
//!   `*ELEMENT_DISCRETE`. LS-DYNA's discrete elements count compression as
//!   negative displacement and force, so both curves lie in the third
//!   quadrant, with zero force in tension (the bumper does not pull).
//! - CalculiX/Abaqus: a `SPRINGA` element set with `*SPRING, NONLINEAR`
//!   (force, elongation) pairs, compression negative, zero in tension.
//!   CalculiX has no hysteretic spring: it unloads along the loading curve
//!   (written as a comment in the deck).
//!
//! The loading curve must be monotone (force not decreasing with
//! compression): a falling branch is a negative tangent stiffness, which
//! explicit codes integrate unstably and implicit ones may not converge on.

use crate::ExportError;
use crate::cards::{self, FieldNames};
use crate::layout::UnitSystem;
use std::fmt::Write;

/// A validated bumper characteristic: loading points and unloading slope.
#[derive(Debug, Clone, PartialEq)]
pub struct SpringCurve {
    /// (compression m, force N), from (0, 0), compression increasing.
    points: Vec<(f64, f64)>,
    /// Unloading slope, N/m.
    unloading: f64,
}

impl SpringCurve {
    /// Checks the curve: at least two points, the first (0, 0), compression
    /// increasing, force finite and not decreasing, unloading slope positive.
    ///
    /// ```
    /// use bumpsim_export::spring::SpringCurve;
    /// assert!(SpringCurve::new(vec![(0.0, 0.0), (0.02, 4e4), (0.1, 6e4)], 5e6).is_ok());
    /// assert!(SpringCurve::new(vec![(0.0, 0.0), (0.02, 4e4), (0.1, 3e4)], 5e6).is_err());
    /// ```
    pub fn new(points: Vec<(f64, f64)>, unloading: f64) -> Result<SpringCurve, ExportError> {
        let bad = |point: usize, reason: &str| ExportError::Curve {
            point,
            reason: reason.to_string(),
        };
        if points.len() < 2 {
            return Err(bad(points.len(), "at least two points are needed"));
        }
        if points[0] != (0.0, 0.0) {
            return Err(bad(1, "the curve must start at (0 m, 0 N)"));
        }
        for (i, w) in points.windows(2).enumerate() {
            if !(w[1].0.is_finite() && w[1].1.is_finite()) {
                return Err(bad(i + 2, "compression and force must be finite"));
            }
            if w[1].0 <= w[0].0 {
                return Err(bad(i + 2, "compression must increase"));
            }
            if w[1].1 < w[0].1 {
                return Err(bad(
                    i + 2,
                    "the loading force falls (not monotone): a negative stiffness the solvers cannot integrate stably",
                ));
            }
        }
        if !(unloading.is_finite() && unloading > 0.0) {
            return Err(ExportError::Curve {
                point: 0,
                reason: format!("unloading slope {unloading} N/m must be positive and finite"),
            });
        }
        Ok(SpringCurve { points, unloading })
    }

    /// The loading points (m, N).
    pub fn points(&self) -> &[(f64, f64)] {
        &self.points
    }

    /// The unloading slope, N/m.
    pub fn unloading(&self) -> f64 {
        self.unloading
    }

    /// The largest loading force, N.
    fn peak(&self) -> f64 {
        self.points.last().map_or(0.0, |p| p.1)
    }
}

/// Options of the spring decks.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SpringOptions {
    /// The deck's units.
    pub units: UnitSystem,
    /// Added to every id (LS-DYNA: part, section, material, curves, element;
    /// CalculiX: element).
    pub id_offset: u64,
    /// The element's nodes (front: barrier side, rear: the car's m1); without
    /// them only the material (and its set) is written.
    pub nodes: Option<(u64, u64)>,
    /// Title comment.
    pub title: String,
    /// CalculiX set-name prefix.
    pub prefix: String,
}

fn check_ids(options: &SpringOptions, limit: u64) -> Result<(), ExportError> {
    let last = options.id_offset.checked_add(2).filter(|&l| l <= limit);
    let last = last.ok_or(ExportError::IdRange {
        offset: options.id_offset,
        last: options.id_offset.saturating_add(2),
        limit,
    })?;
    if let Some((a, b)) = options.nodes {
        if a == b {
            return Err(ExportError::DuplicateNode { node: a });
        }
        if let Some(&node) = [a, b].iter().find(|&&n| n == 0 || n > limit) {
            return Err(ExportError::NodeId { node, limit });
        }
    }
    let _ = last;
    Ok(())
}

fn check_units(curve: &SpringCurve, units: UnitSystem) -> Result<(), ExportError> {
    let fine = curve
        .points
        .iter()
        .all(|(d, f)| (d * units.length()).is_finite() && (f * units.force()).is_finite())
        && (curve.unloading * units.stiffness()).is_finite();
    match fine {
        true => Ok(()),
        false => Err(ExportError::Overflow {
            what: "the bumper curve".into(),
            units: units.to_string(),
        }),
    }
}

/// Writes the LS-DYNA keyword include of the bumper spring.
///
/// ```
/// use bumpsim_export::spring::{SpringCurve, SpringOptions, lsdyna_spring};
/// let curve = SpringCurve::new(vec![(0.0, 0.0), (0.03, 6e4), (0.2, 6e4)], 8e6).unwrap();
/// let deck = lsdyna_spring(&curve, &SpringOptions { nodes: Some((1, 2)), ..Default::default() }).unwrap();
/// assert!(deck.contains("*MAT_SPRING_GENERAL_NONLINEAR"));
/// ```
pub fn lsdyna_spring(curve: &SpringCurve, options: &SpringOptions) -> Result<String, ExportError> {
    check_ids(options, crate::lsdyna::MAX_ID)?;
    check_units(curve, options.units)?;
    let (id, u) = (options.id_offset + 1, options.units);
    let [_, l, _, f] = u.symbols();
    let mut deck = String::new();
    cards::titled(&mut deck, &options.title);
    let _ = writeln!(
        deck,
        "$ bumpsim {}: bumper characteristic as a nonlinear discrete spring\n$ units: length {l}, force {f}; compression is negative",
        env!("CARGO_PKG_VERSION")
    );
    cards::discrete_section(&mut deck, id, FieldNames::Written);
    cards::nonlinear_spring(&mut deck, id, [id, id + 1]);
    cards::part(&mut deck, "bumpsim bumper characteristic", id, id, id);
    let loading: Vec<(f64, f64)> = curve.points.iter().map(|&(d, f)| (-d, -f)).collect();
    let peak = curve.peak();
    let unloading = [(-peak / curve.unloading, -peak), (0.0, 0.0)];
    for (cid, what, pts) in [
        (id, "loading", loading.as_slice()),
        (id + 1, "unloading", &unloading[..]),
    ] {
        lsdyna_curve(&mut deck, cid, what, pts, u);
    }
    if let Some((front, rear)) = options.nodes {
        cards::element_discrete_header(&mut deck, FieldNames::Written);
        cards::element_discrete_line(&mut deck, id, id, front, rear);
    }
    deck.push_str("*END\n");
    Ok(deck)
}

/// One `*DEFINE_CURVE` of (displacement, force) in the deck's units, with
/// zero force in tension after it.
fn lsdyna_curve(deck: &mut String, id: u64, what: &str, points: &[(f64, f64)], u: UnitSystem) {
    let mut rows: Vec<(f64, f64)> = points.to_vec();
    rows.sort_by(|a, b| a.0.total_cmp(&b.0));
    let span = rows.first().map_or(1.0, |p| -p.0);
    rows.push((span, 0.0));
    let rows = rows
        .into_iter()
        .map(|(d, f)| (d * u.length(), f * u.force()));
    cards::curve(deck, id, Some(what), rows);
}

/// Writes the CalculiX/Abaqus deck lines of the bumper spring: `*SPRING,
/// NONLINEAR` for the element set `<prefix>BUMPER` and, with two nodes, the
/// `SPRINGA` element.
///
/// ```
/// use bumpsim_export::spring::{SpringCurve, SpringOptions, calculix_spring};
/// let curve = SpringCurve::new(vec![(0.0, 0.0), (0.03, 6e4)], 8e6).unwrap();
/// let options = SpringOptions { nodes: Some((1, 2)), prefix: "BUMPSIM_".into(), ..Default::default() };
/// assert!(calculix_spring(&curve, &options).unwrap().contains("*SPRING, ELSET=BUMPSIM_BUMPER, NONLINEAR"));
/// ```
pub fn calculix_spring(
    curve: &SpringCurve,
    options: &SpringOptions,
) -> Result<String, ExportError> {
    check_ids(options, crate::calculix::MAX_CALCULIX_ID)?;
    check_units(curve, options.units)?;
    crate::calculix::check_prefix(&options.prefix)?;
    let (u, set) = (options.units, &options.prefix);
    let [_, l, _, f] = u.symbols();
    let mut deck = format!(
        "** {}\n** bumpsim {}: bumper characteristic as a nonlinear SPRINGA (units: length {l}, force {f})\n** CalculiX springs are elastic: this one unloads along its loading curve, not at the slope {} N/m\n",
        bumpsim_core::names::printable(&options.title),
        env!("CARGO_PKG_VERSION"),
        curve.unloading
    );
    if let Some((front, rear)) = options.nodes {
        crate::inp::element_keyword(&mut deck, "SPRINGA", &format!("{set}BUMPER"));
        let _ = writeln!(deck, "{}, {front}, {rear}", options.id_offset + 1);
    }
    let _ = writeln!(deck, "*SPRING, ELSET={set}BUMPER, NONLINEAR\n");
    let mut rows: Vec<(f64, f64)> = curve.points.iter().map(|&(d, f)| (-f, -d)).collect();
    rows.reverse();
    let span = curve.points.last().map_or(1.0, |p| p.0);
    rows.push((0.0, span));
    for (force, elongation) in rows {
        let _ = writeln!(
            deck,
            "{}, {}",
            crate::inp::real(force * u.force()),
            crate::inp::real(elongation * u.length())
        );
    }
    Ok(deck)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn curve() -> SpringCurve {
        SpringCurve::new(vec![(0.0, 0.0), (0.01, 2e4), (0.05, 6e4)], 1e7).unwrap()
    }

    #[test]
    fn falling_or_unordered_curves_are_refused_with_the_point() {
        let e = SpringCurve::new(vec![(0.0, 0.0), (0.01, 2e4), (0.02, 1e4)], 1e7).unwrap_err();
        assert!(e.to_string().contains("point 3"), "{e}");
        assert!(e.to_string().contains("not monotone"), "{e}");
        let e = SpringCurve::new(vec![(0.0, 0.0), (0.01, 2e4), (0.01, 3e4)], 1e7).unwrap_err();
        assert!(e.to_string().contains("compression must increase"), "{e}");
        assert!(SpringCurve::new(vec![(0.0, 1.0), (0.01, 2e4)], 1e7).is_err());
        assert!(SpringCurve::new(vec![(0.0, 0.0), (f64::NAN, 2e4)], 1e7).is_err());
        assert!(SpringCurve::new(vec![(0.0, 0.0), (0.01, 2e4)], 0.0).is_err());
    }

    #[test]
    fn lsdyna_curves_are_in_compression_and_the_unloading_line_has_the_slope() {
        let deck = lsdyna_spring(&curve(), &SpringOptions::default()).unwrap();
        assert!(!deck.contains("*ELEMENT_DISCRETE"));
        let rows: Vec<(f64, f64)> = deck
            .lines()
            .filter(|l| l.len() == 40 && l.split_whitespace().count() == 2)
            .map(|l| {
                (
                    l[..20].trim().parse().unwrap(),
                    l[20..].trim().parse().unwrap(),
                )
            })
            .collect();
        // loading: -0.05, -0.01, 0, tension; unloading: -6e4/1e7, 0, tension
        assert_eq!(rows.len(), 7);
        approx::assert_relative_eq!(rows[0].0, -0.05);
        approx::assert_relative_eq!(rows[0].1, -6e4);
        approx::assert_relative_eq!(rows[4].0, -6e-3);
        assert_eq!(rows[3].1, 0.0);
        let e = lsdyna_spring(
            &curve(),
            &SpringOptions {
                nodes: Some((7, 7)),
                ..Default::default()
            },
        )
        .unwrap_err();
        assert!(matches!(e, ExportError::DuplicateNode { node: 7 }));
    }

    #[test]
    fn calculix_table_runs_from_compression_to_tension_in_the_units() {
        let options = SpringOptions {
            units: UnitSystem::MmSTonne,
            prefix: "P_".into(),
            ..Default::default()
        };
        let deck = calculix_spring(&curve(), &options).unwrap();
        let rows: Vec<Vec<f64>> = deck
            .lines()
            .skip_while(|l| !l.starts_with("*SPRING"))
            .skip(2)
            .map(|l| l.split(',').map(|w| w.trim().parse().unwrap()).collect())
            .collect();
        assert_eq!(rows.len(), 4);
        approx::assert_relative_eq!(rows[0][1], -50.0); // mm
        approx::assert_relative_eq!(rows[0][0], -6e4); // N
        assert_eq!(rows[3][0], 0.0);
    }
}
