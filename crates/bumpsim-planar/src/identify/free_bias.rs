//! An accelerometer's remaining bias read where the car's acceleration is
//! known: after the contact, when the loads have died away and the car
//! rolls free (rolling resistance, the tyres' side forces, the turn's
//! centripetal term: what the replay gives, none of it the car's mass or
//! links). Over that window of `T_f` s the measured minus the modelled
//! acceleration is the bias plus white noise; its mean is
//! `(Δv_measured − Δv_model) / T_f`, the velocities' change across the
//! window (the readings differenced once). Combined with the pre-trigger's
//! mean (`T_p` s, already removed: the prior `N(0, σ²/n_p)`) by their
//! sample counts, the bias left in the measurement is
//! `b̂ = (Δv_measured − Δv_model) / (T_p + T_f)`, and the measurement with
//! it removed is `measured − b̂ t²/2` (`t` from time zero).
//!
//! Why not the whole window, as the objective's nuisance biases: there a
//! bias reads like a mass error (both bend x by a smooth curve), and a
//! held-out comparison that estimates it there forgives a 1 % mass error
//! (the 40 % offset of issue 44's yaw-rate car 6: x 95.3 % before, 99.5 %
//! with the biases estimated over the window, w28 in docs/planar.md). After
//! the contact the loads are below [`FREE_LOAD`] of their peak: a mass
//! error reaches the estimate only through that remainder's impulse, a
//! relative error of the mass times at most 1 % of the peak load over the
//! window (a 2 % heavier car moves it by less than 1e-3 m/s², a unit test).

use super::PlanarCase;

/// The loads' share of their peak below which the contact has ended.
pub const FREE_LOAD: f64 = 0.01;

/// Time after the loads' last sample above [`FREE_LOAD`] before the free
/// window opens, s: the CFC 180 filter's ringing (its impulse response
/// has decayed to a few per cent after about 5 ms).
pub const FREE_MARGIN: f64 = 0.005;

/// The shortest free window read, s: shorter, its estimate is no better
/// than the pre-trigger's and the bias is left as that gave it.
pub const FREE_SHORTEST: f64 = 0.01;

/// Each of `case`'s sensors' bias left in its measurement, m/s² (0 for a
/// sensor that is not an accelerometer), against the replay's readings
/// `model` (displacement from time zero, as [`PlanarCase::measured`]);
/// `None` without a free window of [`FREE_SHORTEST`]. A case without a
/// pre-trigger (`T_p = 0`) takes the free window's alone.
pub(crate) fn free_biases(case: &PlanarCase, model: &[Vec<f64>]) -> Option<Vec<f64>> {
    let h = case.drive.step;
    let samples = model.iter().chain(&case.measured).map(Vec::len).min()?;
    let (first, last) = free_window(case, samples)?;
    let span = (last - first) as f64 * h;
    let change = |x: &[f64]| (x[last] - x[last - 1] - x[first] + x[first - 1]) / h;
    let sensors = case.drive.sensors.iter().zip(model).zip(&case.measured);
    let biases = sensors.map(|((sensor, model), measured)| {
        match sensor.integrations() != 2 || sensor.displacement() {
            true => 0.0,
            false => (change(measured) - change(model)) / (case.pretrigger.max(0.0) + span),
        }
    });
    Some(biases.collect())
}

/// The free window of `case`'s first `samples`: from [`FREE_MARGIN`] after
/// the last sample whose loads exceed [`FREE_LOAD`] of their peak to the
/// last sample, if it spans [`FREE_SHORTEST`].
fn free_window(case: &PlanarCase, samples: usize) -> Option<(usize, usize)> {
    let h = case.drive.step;
    if h.is_nan() || h <= 0.0 {
        return None;
    }
    let total: Vec<f64> = (0..samples)
        .map(|k| {
            let loads = case.drive.loads.iter();
            loads.filter_map(|l| l.force.get(k)).map(|f| f.abs()).sum()
        })
        .collect();
    let peak = total.iter().fold(0.0, |m: f64, v| m.max(*v));
    let contact = total.iter().rposition(|v| *v > FREE_LOAD * peak)?;
    let first = contact.checked_add((FREE_MARGIN / h).ceil() as usize)?;
    let last = samples.checked_sub(1)?;
    (first >= 1 && last > first && (last - first) as f64 * h >= FREE_SHORTEST)
        .then_some((first, last))
}

/// The bias left in `case`'s measured x (the mean of its first two
/// sensors, the sills), m/s²: the mean of their [`free_biases`]; `None`
/// when the case does not estimate it ([`PlanarCase::nuisance`]) or has no
/// free window. Only x is corrected: after the contact the sills'
/// difference reads the tyres' yaw moment, which is the car's, so the yaw
/// from it is left as measured.
pub(crate) fn x_bias(case: &PlanarCase, model: &[Vec<f64>]) -> Option<f64> {
    if !case.nuisance {
        return None;
    }
    match free_biases(case, model)?.as_slice() {
        [left, right, ..] => Some(0.5 * (left + right)),
        _ => None,
    }
}

/// The spread of the bias left in `case`'s measured x, m/s²: `x_noise /
/// √T`, T the time its bias was read over (the pre-trigger, and the free
/// window when the case reads one there, [`x_bias`]); 0 when either is
/// unknown ([`PlanarCase::x_noise`]). It reads as `σ_b t²/2` in x.
pub(crate) fn x_bias_spread(case: &PlanarCase) -> f64 {
    let samples = case.measured.iter().map(Vec::len).min().unwrap_or(0);
    let free = match case.nuisance {
        true => free_window(case, samples).map_or(0.0, |(a, b)| (b - a) as f64 * case.drive.step),
        false => 0.0,
    };
    let read = case.pretrigger.max(0.0) + free;
    match case.x_noise > 0.0 && read > 0.0 {
        true => case.x_noise / read.sqrt(),
        false => 0.0,
    }
}

/// `x` (sampled every `step` from time zero) less the reading `b t²/2` of
/// a bias `b`.
pub(crate) fn removed(x: &mut [f64], b: f64, step: f64) {
    for (k, v) in x.iter_mut().enumerate() {
        *v -= b * 0.5 * (k as f64 * step).powi(2);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::PlanarCar;
    use crate::car::Layout;
    use crate::drive::{Drive, Load, Sensor, drive};
    use bumpsim_core::model::MsdModel;
    use bumpsim_impact::bumper::Bumper;

    fn car(body: f64) -> PlanarCar {
        let chain = MsdModel::new(vec![8.0, body], vec![2e3], vec![1.5e6]).unwrap();
        let bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
        PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap()
    }

    /// `truth`'s sills under a 40 kN half-sine push of 30 ms from 2 m/s,
    /// recorded for 80 ms (45 ms free after the margin), each sill read
    /// with its bias (m/s²) left after a 20 ms pre-trigger.
    fn case(truth: &PlanarCar, biases: [f64; 2]) -> PlanarCase {
        let step = 1e-4;
        let force = (0..800)
            .map(|k| 4e4 * (std::f64::consts::PI * (k as f64 / 300.0).min(1.0)).sin())
            .collect();
        let load = Load {
            lateral: 0.3,
            anchor: None,
            cell: None,
            direction: [-1.0, 0.0],
            force,
        };
        let drive_ = Drive {
            step,
            loads: vec![load],
            speed: 2.0,
            arm: 1.0,
            sensors: vec![Sensor::Body([0.6, 0.7]), Sensor::Body([0.6, -0.7])],
        };
        let mut measured = drive(truth, &drive_, 0.05).unwrap().sensor_reading;
        for (x, b) in measured.iter_mut().zip(biases) {
            removed(x, -b, step);
        }
        PlanarCase {
            pretrigger: 0.02,
            nuisance: true,
            ..PlanarCase::replayed("offset", drive_, measured)
        }
    }

    fn readings(car: &PlanarCar, case: &PlanarCase) -> Vec<Vec<f64>> {
        drive(car, &case.drive, 0.05).unwrap().sensor_reading
    }

    #[test]
    fn the_free_window_reads_the_bias_shrunk_by_the_pretrigger_it_joins() {
        let truth = car(1200.0);
        let case = case(&truth, [0.06, -0.02]);
        // the push's last sample above 1 % of its peak is k = 299: the
        // free window opens 5 ms later, at 349, and ends at 799
        let free = (799 - 349) as f64 * 1e-4;
        let shrink = free / (0.02 + free);
        let b = free_biases(&case, &readings(&truth, &case)).unwrap();
        assert!((b[0] - 0.06 * shrink).abs() < 1e-6, "{b:?}");
        assert!((b[1] + 0.02 * shrink).abs() < 1e-6, "{b:?}");
        let x = x_bias(&case, &readings(&truth, &case)).unwrap();
        assert!((x - 0.02 * shrink).abs() < 1e-6, "{x}");
    }

    #[test]
    fn a_wrong_mass_is_not_forgiven() {
        let truth = car(1200.0);
        let case = case(&truth, [0.06, -0.02]);
        let heavy = car(1224.0);
        let (right, wrong) = (readings(&truth, &case), readings(&heavy, &case));
        // the free window's estimate does not see the mass
        let gap = x_bias(&case, &wrong).unwrap() - x_bias(&case, &right).unwrap();
        assert!(gap.abs() < 1e-3, "{gap}");
        // and the 2 % heavier car keeps its x error
        let fit = |c: &PlanarCar| super::super::predict(c, &case).unwrap().fit.fit_x;
        assert!(
            fit(&truth) > 99.9 && fit(&heavy) < 99.0,
            "{} {}",
            fit(&truth),
            fit(&heavy)
        );
    }

    #[test]
    fn the_bias_spread_shrinks_with_the_time_it_was_read_over() {
        let truth = car(1200.0);
        let mut case = case(&truth, [0.0, 0.0]);
        case.x_noise = 0.01;
        let free = (799 - 349) as f64 * 1e-4;
        let spread = x_bias_spread(&case);
        assert!(
            (spread - 0.01 / (0.02 + free).sqrt()).abs() < 1e-12,
            "{spread}"
        );
        case.nuisance = false;
        assert!((x_bias_spread(&case) - 0.01 / 0.02f64.sqrt()).abs() < 1e-12);
        case.x_noise = 0.0;
        assert_eq!(x_bias_spread(&case), 0.0);
    }

    #[test]
    fn without_nuisance_biases_or_a_free_window_nothing_is_removed() {
        let truth = car(1200.0);
        let mut plain = case(&truth, [0.06, -0.02]);
        plain.nuisance = false;
        assert_eq!(x_bias(&plain, &readings(&truth, &plain)), None);
        let mut short = case(&truth, [0.06, -0.02]);
        short.measured.iter_mut().for_each(|m| m.truncate(400));
        assert_eq!(free_biases(&short, &readings(&truth, &short)), None);
        assert_eq!(x_bias(&short, &readings(&truth, &short)), None);
        // without a pre-trigger the free window's reading stands alone
        let mut bare = case(&truth, [0.06, -0.02]);
        bare.pretrigger = 0.0;
        let b = free_biases(&bare, &readings(&truth, &bare)).unwrap();
        assert!(
            (b[0] - 0.06).abs() < 1e-6 && (b[1] + 0.02).abs() < 1e-6,
            "{b:?}"
        );
    }
}
