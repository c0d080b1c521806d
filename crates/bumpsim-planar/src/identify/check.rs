//! The identification's input checks, before any simulation: the setup's
//! counts and factors, each case's sensors, weights, measured
//! displacements (finite, as many samples as the forces) and window, the
//! drive against the start car, and a positive start for every parameter
//! estimated on a log scale (bad input gets a clear error naming the case
//! and the parameter).

use super::{MAX_SPREAD, MAX_STARTS, PlanarCase, Setup, Unknowns};
use crate::car::{PlanarError, parameter};
use crate::drive::Sensor;

/// The largest compared reading of a sensor, in size (SI: m, or rad/s):
/// far beyond any crash test, below where the squared residuals overflow.
pub(crate) const MAX_MEASURED: f64 = 1e6;

/// The unknowns of `cases` under `setup`, or the first input error.
pub(super) fn check(cases: &[PlanarCase], setup: &Setup) -> Result<Unknowns, PlanarError> {
    let setting =
        |name: &str, value: f64, unit, expected: &str| Err(parameter(name, value, unit, expected));
    if cases.is_empty() {
        return setting("cases", 0.0, "1", "at least one load case");
    }
    if setup.starts == 0 || setup.starts > MAX_STARTS {
        return setting(
            "starts",
            setup.starts as f64,
            "1",
            &format!("1 to {MAX_STARTS}"),
        );
    }
    if !(setup.spread.is_finite() && setup.spread > 1.0 && setup.spread <= MAX_SPREAD) {
        let expected = format!("a factor above 1, at most {MAX_SPREAD:e} (MAX_SPREAD)");
        return setting("spread", setup.spread, "1", &expected);
    }
    if let Some(m) = setup.mass.filter(|m| !(m.is_finite() && *m > 0.0)) {
        return setting("mass", m, "kg", "the test sheet's mass must be positive");
    }
    for case in cases {
        check_case(case)?;
        crate::drive::validate(&setup.template, &case.drive).map_err(|e| PlanarError::Case {
            case: case.name.clone(),
            message: e.to_string(),
        })?;
    }
    let unknowns = Unknowns::new(&setup.template, setup.friction, setup.cornering, cases)
        .with_relaxation(setup.relaxation)
        .with_arms(setup.arms)
        .with_width(setup.width);
    let relaxes = unknowns
        .names()
        .iter()
        .any(|(n, _)| n == "tyres.relaxation_length");
    if setup.relaxation && !relaxes {
        return Err(PlanarError::Missing {
            name: "relaxation".into(),
            expected: "a start car whose tyres roll with a relaxation length (law \"rolling\", relaxation_length > 0 on both axles) to estimate it from".into(),
        });
    }
    let car_parameters =
        unknowns.names().len() - cases.iter().map(|c| c.estimated.len()).sum::<usize>();
    let start = unknowns.start();
    for ((name, unit), value) in unknowns.names().iter().zip(&start).take(car_parameters) {
        if !(value.is_finite() && *value > 0.0) {
            return setting(
                name,
                *value,
                unit,
                "the start must be positive to be estimated (on a log scale)",
            );
        }
    }
    Ok(unknowns)
}

/// Lateral spacing η_L − η_R of the first two sensors when both are x
/// accelerometers on the body, m; NaN otherwise.
pub(super) fn spacing(case: &PlanarCase) -> f64 {
    match case.drive.sensors.as_slice() {
        [Sensor::Body(left), Sensor::Body(right), ..] => left[1] - right[1],
        _ => f64::NAN,
    }
}

/// The first error in one case's sensors, weights, measured signals or window.
pub(super) fn check_case(case: &PlanarCase) -> Result<(), PlanarError> {
    let name = |what: &str| format!("case '{}': {what}", case.name);
    let samples = case.drive.loads.first().map_or(0, |l| l.force.len());
    let speed = case.drive.speed;
    if !(speed.is_finite() && speed.abs() <= crate::drive::MAX_SPEED) {
        return Err(parameter(
            &name("speed"),
            speed,
            "m/s",
            &format!(
                "finite, at most {} m/s in size (a crash test's is a few m/s)",
                crate::drive::MAX_SPEED
            ),
        ));
    }
    let spacing = spacing(case);
    let sensors = &case.drive.sensors;
    if let Some(k) = (0..2).find(|&k| !matches!(sensors.get(k), Some(Sensor::Body(_)))) {
        // a sill given `chain = 99` printed "sensors = NaN m" (issue 44's
        // hostile pass): name the sensor and what it is instead
        let found = match sensors.get(k) {
            None => format!("the case has {} sensors", sensors.len()),
            Some(sensor) => format!("sensor[{k}] is {}", sensor_kind(sensor)),
        };
        return Err(PlanarError::Case {
            case: case.name.clone(),
            message: format!(
                "sensors: the first two must be x accelerometers on the body (body = [ξ, η] m), left (larger η) then right: {found}"
            ),
        });
    }
    if !(spacing.is_finite() && spacing > 0.0) {
        return Err(parameter(
            &name("sensors"),
            spacing,
            "m",
            "the first two sensors x accelerometers on the body, left (larger η) then right",
        ));
    }
    if !case.weights.is_empty() && case.weights.len() != case.drive.sensors.len() {
        return Err(parameter(
            &name("weights"),
            case.weights.len() as f64,
            "1",
            &format!("one per sensor ({})", case.drive.sensors.len()),
        ));
    }
    if let Some(k) = case
        .weights
        .iter()
        .position(|w| !(w.is_finite() && *w > 0.0))
    {
        return Err(parameter(
            &name(&format!("sensor[{k}] weight")),
            case.weights[k],
            "1",
            "must be finite and positive",
        ));
    }
    if case.measured.len() != case.drive.sensors.len() {
        let n = case.measured.len() as f64;
        return Err(parameter(
            &name("measured"),
            n,
            "signals",
            &format!("one per sensor ({})", case.drive.sensors.len()),
        ));
    }
    for (s, m) in case.measured.iter().enumerate() {
        if m.len() != samples {
            return Err(parameter(
                &name(&format!("sensor[{s}] displacement")),
                m.len() as f64,
                "samples",
                &format!("as many samples as the forces ({samples})"),
            ));
        }
        if let Some(k) = m.iter().position(|v| !v.is_finite()) {
            return Err(parameter(
                &name(&format!("sensor[{s}] displacement[{k}]")),
                m[k],
                "m",
                "must be finite",
            ));
        }
        // a yaw-rate sample of 1e308 left "no start could be evaluated"
        if let Some(k) = m.iter().position(|v| v.abs() > MAX_MEASURED) {
            return Err(parameter(
                &name(&format!("sensor[{s}] reading[{k}]")),
                m[k],
                "SI",
                &format!(
                    "at most {MAX_MEASURED:e} in size (m, or rad/s for a yaw rate): check the channel's samples"
                ),
            ));
        }
    }
    let (a, b) = case.window;
    if !(a < b && b < samples) {
        return Err(parameter(
            &name("window end"),
            b as f64,
            "sample",
            &format!("a window of at least two samples within 0..{samples}"),
        ));
    }
    Ok(())
}

/// What a sensor is, in a message.
fn sensor_kind(sensor: &Sensor) -> &'static str {
    match sensor {
        Sensor::Body(_) => "an x accelerometer on the body",
        Sensor::Chain(_) => "an x accelerometer on a chain mass (chain = i)",
        Sensor::Lateral(_) => "a lateral accelerometer",
        Sensor::YawRate => "a yaw-rate sensor",
        Sensor::Film(_) => "a film target's displacement",
        Sensor::Crush(_) => "a chain mass's displacement (a string pot)",
    }
}
