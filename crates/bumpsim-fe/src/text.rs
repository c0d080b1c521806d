//! The coupled run in words and JSON: the figures of `bumpsim impact`, the
//! unfiltered peak, and the comparison with the equivalent characteristic:
//! its figures and the ISO/TS 18571 ratings ([`bumpsim_signal::rating`]) of
//! the 1-D model's contact force and compression histories against the FE
//! run's (the FE run is the reference), on the span both cover, at 10 kHz.

use crate::run::{FeResult, FeRun};
use bumpsim_core::units::{Dimension, format_quantity};
use bumpsim_impact::impact::Scenario;
use bumpsim_signal::rating::{Rating, RatingError, rate_histories};
use std::path::Path;

/// The ISO/TS 18571 ratings of the equivalent 1-D impact against the FE
/// run: `("force", …)` and `("compression", …)`; empty without the
/// equivalent run.
pub fn ratings(fe: &FeResult) -> Vec<(&'static str, Result<Rating, RatingError>)> {
    let Some(msd) = &fe.equivalent else {
        return Vec::new();
    };
    let r = &fe.impact;
    vec![
        (
            "force",
            rate_histories((&r.time, &r.force), (&msd.time, &msd.force)),
        ),
        (
            "compression",
            rate_histories((&r.time, &r.compression), (&msd.time, &msd.compression)),
        ),
    ]
}

/// The rating lines of the summary.
fn rating_lines(fe: &FeResult) -> String {
    ratings(fe)
        .into_iter()
        .map(|(what, rating)| match rating {
            Ok(r) => format!("  ISO/TS 18571 rating of the 1-D model's {what} against FE: {r}\n"),
            Err(e) => {
                format!("  ISO/TS 18571 rating of the 1-D model's {what} against FE: none ({e})\n")
            }
        })
        .collect()
}

/// The inputs of a run as the report lists them (name, value with unit):
/// the car and bumper files, the impact, the time stepping and the solver.
pub fn inputs(run: &FeRun, car: &Path, bumper: &Path) -> Vec<(String, String)> {
    let q = format_quantity;
    let impact = match run.scenario {
        Scenario::Impactor { mass, speed } => format!(
            "{} pendulum at {}, the car at rest",
            q(mass, Dimension::Mass),
            q(speed, Dimension::Velocity)
        ),
        Scenario::Barrier { speed } => {
            format!(
                "the car into a rigid barrier at {}",
                q(speed, Dimension::Velocity)
            )
        }
    };
    let or_default =
        |v: Option<f64>, default: &str| v.map_or(default.to_string(), |v| q(v, Dimension::Time));
    vec![
        (
            "car".into(),
            format!(
                "{} ({} masses, {} in all)",
                car.display(),
                run.car.dof(),
                q(run.car.total_mass(), Dimension::Mass)
            ),
        ),
        (
            "bumper mesh".into(),
            format!(
                "{}{}",
                bumper.display(),
                run.mesh
                    .name
                    .as_deref()
                    .map_or(String::new(), |n| format!(" ({n})"))
            ),
        ),
        ("impact".into(), impact),
        (
            "duration".into(),
            or_default(
                run.duration,
                "1.3 × the contact time the equivalent characteristic estimates",
            ),
        ),
        (
            "increment".into(),
            or_default(run.increment, "the duration / 1500"),
        ),
        (
            "solver".into(),
            format!("{} in {}", run.solver, run.work.display()),
        ),
    ]
}

/// Why the force history does not start at zero: said on the report.
pub const FORCE_AT_START: &str = "The force does not start at zero: at t = 0 the striker meets the beam at the full impact speed v, and in the first increment Δt it moves v·Δt into the contact springs before the beam's nodes, held back by their inertia, follow; the first printed force is the contact stiffness times that travel (k_contact · v · Δt), and it falls off as the beam takes up the speed. A stiffer contact or a longer increment raises it; a barrier load cell records the same transient when a stiff face meets it.";

/// Tolerance of the energy-balance warning (relative to the initial energy).
pub const ENERGY_TOLERANCE: f64 = 0.02;

/// The summary: impact's lines, then the FE-specific ones.
pub fn summary(fe: &FeResult) -> String {
    let r = &fe.impact;
    let equivalent = match &fe.equivalent {
        Some(e) => format!(
            "peak force {}, maximum compression {}",
            format_quantity(e.peak_force, Dimension::Force),
            format_quantity(e.max_compression, Dimension::Length)
        ),
        None => "not available (impact could not run it)".into(),
    };
    bumpsim_impact::text::summary(r)
        + &format!(
            "  peak force unfiltered {} (the summary's peak is CFC 60, as a barrier load cell)\n  bumper internal energy at the end {} (plastic work and what stays elastic)\n  equivalent characteristic in `impact`: {equivalent}\n  CalculiX: {} printed increments, nominal {}, deck {}\n",
            format_quantity(fe.raw_peak_force, Dimension::Force),
            format_quantity(fe.bumper_internal_energy, Dimension::Energy),
            r.time.len(),
            format_quantity(fe.increment, Dimension::Time),
            fe.deck.display()
        )
        + &rating_lines(fe)
}

/// The result's own checks: the energy balance within [`ENERGY_TOLERANCE`],
/// and the contact over before the run's end.
pub fn warnings(fe: &FeResult) -> Vec<String> {
    let r = &fe.impact;
    let error = r.energy.relative_error;
    let mut out = Vec::new();
    if !(error.is_finite() && error <= ENERGY_TOLERANCE) {
        out.push(format!(
            "energy balance error {error:.3} of the initial energy exceeds {ENERGY_TOLERANCE}: use a smaller --increment"
        ));
    }
    if r.force.last().is_some_and(|&f| f > 1e-2 * r.peak_force) {
        out.push(format!(
            "the contact had not ended at the end of the run ({}): contact time and remaining compression are not final; give a longer --duration",
            format_quantity(r.time.last().copied().unwrap_or(0.0), Dimension::Time)
        ));
    }
    out
}

/// The JSON document (SI).
pub fn json(fe: &FeResult, warnings: &[String]) -> serde_json::Value {
    let r = &fe.impact;
    serde_json::json!({
        "peak_force": r.peak_force,
        "peak_force_unfiltered": fe.raw_peak_force,
        "force_filter": "SAE J211 CFC 60",
        "max_compression": r.max_compression,
        "remaining_compression": r.remaining_compression,
        "contact_start": r.contact_start,
        "contact_time": r.contact_time,
        "bumper_internal_energy": fe.bumper_internal_energy,
        "energy": r.energy,
        "increment": fe.increment,
        "crash_box_y": fe.crash_box_y,
        "deck": fe.deck,
        "equivalent": fe.equivalent.as_ref().map(|e| serde_json::json!({
            "peak_force": e.peak_force,
            "max_compression": e.max_compression,
            "contact_time": e.contact_time,
        })),
        "ratings": ratings(fe)
            .into_iter()
            .map(|(what, rating)| (what.to_string(), serde_json::json!(rating.ok())))
            .collect::<serde_json::Map<_, _>>(),
        "warnings": warnings,
    })
}
