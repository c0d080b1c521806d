//! The explicit (central-difference) critical time step of the car model,
//! so that a user knows before a run whether the car limits the step of a
//! bumper model (issue 16; Belytschko, Liu & Moran, *Nonlinear Finite
//! Elements*, ch. 6.3).
//!
//! For each link j between masses j and j+1: `ω_j² = k_j (1/m_j + 1/m_{j+1})`
//! bounds its frequency and `γ_j = c_j (1/m_j + 1/m_{j+1})` its damping rate.
//! Summing over the links that meet at a mass (Gershgorin) bounds the
//! chain's highest frequency `ω²` and damping rate `γ`; the undamped
//! central-difference limit is `2/ω`, and an explicit viscous damper needs
//! `Δt < 2/γ`. The critical step is the smaller: `Δt = min(2/ω, 2/γ)`. For
//! the thesis car (c1 = 6.46e6 N·s/m on m1 = 1.8 kg) the damper governs:
//! about 0.5 µs.

use bumpsim_core::model::MsdModel;

/// The critical explicit time step of `model` alone, s (infinite for a
/// single mass, which has no link).
///
/// ```
/// use bumpsim_core::model::MsdModel;
/// use bumpsim_export::timestep::critical_time_step;
/// let thesis = MsdModel::new(vec![1.8, 74.8, 1670.0], vec![6.46e6, 1.97e5], vec![4.75e5, 5.0e5]).unwrap();
/// let dt = critical_time_step(&thesis);
/// assert!(dt > 4e-7 && dt < 6e-7, "{dt}");      // ≈ 2 m1 / c1
/// assert!(critical_time_step(&MsdModel::new(vec![900.0], vec![], vec![]).unwrap()).is_infinite());
/// ```
pub fn critical_time_step(model: &MsdModel) -> f64 {
    let m = model.masses();
    let mut omega2 = vec![0.0; m.len()];
    let mut gamma = vec![0.0; m.len()];
    for j in 0..m.len().saturating_sub(1) {
        let inverse = 1.0 / m[j] + 1.0 / m[j + 1];
        for node in [j, j + 1] {
            omega2[node] += model.springs()[j] * inverse;
            gamma[node] += model.dampers()[j] * inverse;
        }
    }
    let omega = omega2.iter().copied().fold(0.0, f64::max).sqrt();
    let gamma = gamma.iter().copied().fold(0.0, f64::max);
    let limit = |rate: f64| {
        if rate > 0.0 {
            2.0 / rate
        } else {
            f64::INFINITY
        }
    };
    limit(omega).min(limit(gamma))
}

/// The critical time step of `model` when it is below `minimum` (s), the
/// threshold of the export's warning; `None` when it is not. A negative or
/// non-finite `minimum` is an error: `--min-time-step -1` silently switched
/// the warning off.
pub fn below_minimum(model: &MsdModel, minimum: f64) -> Result<Option<f64>, crate::ExportError> {
    if !(minimum.is_finite() && minimum >= 0.0) {
        return Err(crate::ExportError::MinTimeStep { value: minimum });
    }
    let step = critical_time_step(model);
    Ok((step < minimum).then_some(step))
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn a_spring_between_equal_masses_matches_its_frequency_bound() {
        // two masses m on a spring k: ω² = 2k/m exactly; the bound sums both ends
        let (m, k) = (2.0, 800.0);
        let model = MsdModel::new(vec![m, m], vec![0.0], vec![k]).unwrap();
        assert_relative_eq!(
            critical_time_step(&model),
            2.0 / (2.0 * k / m).sqrt(),
            max_relative = 1e-12
        );
    }

    #[test]
    fn a_negative_minimum_is_refused_not_ignored() {
        let model = MsdModel::new(vec![2.0, 2.0], vec![0.0], vec![800.0]).unwrap();
        for bad in [-1.0, -0.0 - 1e-300, f64::NAN, f64::INFINITY] {
            assert!(matches!(
                below_minimum(&model, bad),
                Err(crate::ExportError::MinTimeStep { .. })
            ));
        }
        assert_eq!(below_minimum(&model, 0.0).unwrap(), None);
        assert!(below_minimum(&model, 1.0).unwrap().is_some());
    }
}
