//! Model-error floors of the planar objective's channels (issue 44; the
//! rule of the 1-D links fit, [`bumpsim_estimate::floor`]): on a crash
//! test the residual is model error, not sensor noise, so each sensor's
//! residuals in case c are divided by
//!
//! `s = √(N_c² + (φ S)²)`
//!
//! with `N_c` the noise every weighted residual of the case carries (the x
//! accelerometers' pooled noise, [`PlanarCase::noise`], in the compared
//! domain: the cases module weighs every other sensor to it), S the spread
//! of the sensor's weighted measured series in the compared domain (an
//! accelerometer's displacement differenced as the objective differences
//! it, the yaw rate and displacement channels as measured) over the window,
//! and φ the floor of the sensor's kind ([`Floors`]). Each weight is
//! multiplied by `R / s`, R the root mean square of the x accelerometers'
//! scales over every case, so the objective stays in units of the sills'
//! displacement (m in that domain) and the floors change only how the
//! channels and cases weigh against each other. Without floors
//! (`Setup::floors` `None`, the default) the weights are the noise's alone,
//! as before.

use super::PlanarCase;
use crate::car::PlanarError;
use crate::drive::Sensor;
use bumpsim_estimate::domain::{Domain, integrated_noise};
use bumpsim_estimate::floor::{scale, spread};
use serde::Serialize;

/// The stated model-error floors per sensor kind, each a fraction in
/// [0, 1] of the channel's spread ([`bumpsim_estimate::floor`]); 0: the
/// kind weighs by its noise alone.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Floors {
    /// The accelerometers (body x, chain x, lateral), in the compared domain.
    pub accelerometers: f64,
    /// A yaw-rate sensor, as measured.
    pub yaw_rate: f64,
    /// Displacement channels (film, string pots), as measured.
    pub displacement: f64,
}

impl Floors {
    /// The floor of `sensor`'s kind.
    pub fn of(&self, sensor: &Sensor) -> f64 {
        match sensor {
            Sensor::YawRate => self.yaw_rate,
            s if s.displacement() => self.displacement,
            _ => self.accelerometers,
        }
    }

    /// The first floor outside [0, 1] or not finite, by its key.
    pub fn invalid(&self) -> Option<(&'static str, f64)> {
        [
            ("accelerometers", self.accelerometers),
            ("yaw_rate", self.yaw_rate),
            ("displacement", self.displacement),
        ]
        .into_iter()
        .find(|(_, v)| !(0.0..=1.0).contains(v))
    }
}

/// `cases` with each sensor's weight multiplied by `R / s` (see the
/// module); an error names a floor out of range, or a case and sensor whose
/// scale is zero (no spread and no noise to weigh it by).
pub fn floored(
    cases: &[PlanarCase],
    domain: Domain,
    floors: &Floors,
) -> Result<Vec<PlanarCase>, PlanarError> {
    if let Some((key, value)) = floors.invalid() {
        return Err(PlanarError::Missing {
            name: format!("[identification] floor.{key} = {value}"),
            expected: "a fraction of the channel's spread in [0, 1]".into(),
        });
    }
    let scales: Vec<Vec<f64>> = cases
        .iter()
        .map(|case| scales(case, domain, floors))
        .collect::<Result<_, _>>()?;
    let x: Vec<f64> = cases
        .iter()
        .zip(&scales)
        .flat_map(|(case, s)| {
            case.drive
                .sensors
                .iter()
                .zip(s)
                .filter(|(sensor, _)| sensor.along_x())
                .map(|(_, s)| *s)
        })
        .collect();
    let reference = (x.iter().map(|s| s * s).sum::<f64>() / x.len().max(1) as f64).sqrt();
    let mut out = cases.to_vec();
    for (case, s) in out.iter_mut().zip(&scales) {
        case.weights = s
            .iter()
            .enumerate()
            .map(|(k, s)| case.weight(k) * reference / s)
            .collect();
    }
    Ok(out)
}

/// Each sensor's error scale `s` in `case` (the module's rule), in the
/// objective's units.
fn scales(case: &PlanarCase, domain: Domain, floors: &Floors) -> Result<Vec<f64>, PlanarError> {
    let (first, last) = case.window;
    let h = case.drive.step;
    let order = domain.order();
    let duration = h * (last - first) as f64;
    // the objective's rescaling of an undifferenced channel (its `compared`)
    let rescaled = match order {
        0 => 1.0,
        _ => integrated_noise(1.0, h, duration, 2 - order) / integrated_noise(1.0, h, duration, 2),
    };
    let noise = case.noise * rescaled;
    case.drive
        .sensors
        .iter()
        .enumerate()
        .map(|(k, sensor)| {
            let mut y: Vec<f64> = case.measured[k][first..=last]
                .iter()
                .map(|v| case.weight(k) * v)
                .collect();
            if sensor.integrations() == 2 {
                for _ in 0..order {
                    y = y.windows(2).map(|w| (w[1] - w[0]) / h).collect();
                }
            } else {
                y.iter_mut().for_each(|v| *v *= rescaled);
            }
            let s = scale(noise, floors.of(sensor), spread(&y));
            match s.is_finite() && s > 0.0 {
                true => Ok(s),
                false => Err(PlanarError::Case {
                    case: case.name.clone(),
                    message: format!(
                        "sensor {}: a model-error floor needs a channel with a spread or a noise to weigh it by (spread 0, noise {noise})",
                        k + 1
                    ),
                }),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::car::{Layout, PlanarCar};
    use bumpsim_core::model::MsdModel;
    use bumpsim_impact::bumper::Bumper;

    /// A push at `lateral` (0: no yaw) with the sills, a chain
    /// accelerometer and a yaw-rate sensor.
    fn case(lateral: f64) -> PlanarCase {
        let chain = MsdModel::new(vec![8.0, 1200.0], vec![2e3], vec![1.5e6]).unwrap();
        let bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
        let car = PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap();
        crate::identify::tests::pushed(&car, "push", lateral, Sensor::YawRate)
    }

    /// In displacement, each sensor's new weight is its old one times
    /// `R/√(N² + (φ S)²)`, S its weighted series' spread over the window and
    /// R the x accelerometers' root mean square scale: checked by hand on a
    /// push with two sills, a chain accelerometer and a yaw-rate sensor.
    #[test]
    fn each_weight_is_divided_by_its_scale_against_the_sills() {
        let mut case = case(0.3);
        case.noise = 1e-4;
        case.weights = vec![1.0, 1.0, 1.0, 0.5];
        let floors = Floors {
            accelerometers: 0.01,
            yaw_rate: 0.05,
            displacement: 0.0,
        };
        let out = floored(std::slice::from_ref(&case), Domain::Displacement, &floors).unwrap();
        let (a, b) = case.window;
        let spread_of = |k: usize| {
            let y: Vec<f64> = case.measured[k][a..=b]
                .iter()
                .map(|v| case.weights[k] * v)
                .collect();
            spread(&y)
        };
        let s: Vec<f64> = (0..4)
            .map(|k| {
                let phi = [0.01, 0.01, 0.01, 0.05][k];
                (1e-8 + (phi * spread_of(k)).powi(2)).sqrt()
            })
            .collect();
        let reference = ((s[0].powi(2) + s[1].powi(2) + s[2].powi(2)) / 3.0).sqrt();
        for k in 0..4 {
            let expected = case.weights[k] * reference / s[k];
            assert!(
                (out[0].weights[k] - expected).abs() < 1e-12 * expected,
                "sensor {k}: {} against {expected}",
                out[0].weights[k]
            );
        }
    }

    /// Zero floors weigh by the noise alone: every sensor's weight is kept
    /// (all weighted residuals carry the same noise).
    #[test]
    fn zero_floors_keep_the_weights() {
        let mut case = case(0.3);
        case.noise = 2e-4;
        case.weights = vec![1.0, 1.0, 1.0, 0.3];
        let out = floored(
            std::slice::from_ref(&case),
            Domain::Velocity,
            &Floors::default(),
        )
        .unwrap();
        for (w, v) in out[0].weights.iter().zip(&case.weights) {
            assert!((w - v).abs() < 1e-12, "{:?}", out[0].weights);
        }
    }

    /// A floor out of [0, 1] is refused by key; a case without noise whose
    /// channel is flat cannot be weighted and is named.
    #[test]
    fn a_bad_floor_and_a_flat_channel_are_refused() {
        let case = case(0.0);
        let bad = Floors {
            yaw_rate: 1.5,
            ..Floors::default()
        };
        let e = floored(std::slice::from_ref(&case), Domain::Displacement, &bad)
            .unwrap_err()
            .to_string();
        assert!(e.contains("floor.yaw_rate = 1.5"), "{e}");
        let mut flat = case.clone();
        flat.noise = 0.0;
        // a centred push does not yaw
        let floors = Floors {
            accelerometers: 0.01,
            yaw_rate: 0.05,
            displacement: 0.0,
        };
        let e = floored(&[flat], Domain::Displacement, &floors)
            .unwrap_err()
            .to_string();
        assert!(e.contains("sensor 4") && e.contains("push"), "{e}");
    }
}
