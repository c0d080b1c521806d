//! A car of either chain form as a deck: the one place that picks the
//! writer, so `bumpsim export` stays thin (issue 46). A linear car
//! ([`MsdModel`]) goes to [`crate::lsdyna::lsdyna_include`] and
//! [`crate::calculix::calculix_deck`], a chain with nonlinear links
//! ([`Chain`]) to [`crate::chain::lsdyna_chain_include`] and
//! [`crate::chain_calculix::calculix_chain_deck`]; the options are the same.
//!
//! The critical explicit step of a chain ([`critical_time_step`]) is that of
//! [`crate::timestep`] with every link at its steepest slope (loading or
//! unloading, [`bumpsim_core::link::Link::steepest_slope`]), the front link
//! as a spring from m1 to a fixed wall and a wall link (second load path,
//! rebound link) as one from its mass: the largest row sum `ω² = max_i (Σ
//! k_j (1/m_j + 1/m_(j+1)) + Σ k_w / m_i)` over the links and wall springs
//! at mass i (Gershgorin) bounds the highest frequency the links can reach.
//!
//! ```
//! use bumpsim_core::chain::Chain;
//! use bumpsim_core::link::{Curve, Link, Unloading};
//! use bumpsim_export::car_deck::{CarModel, lsdyna_car_include};
//! let link = Link::new(Curve::bilinear(1e6, 5e4, 0.1).unwrap(), Unloading::Slope(2e6)).unwrap();
//! let chain = Chain::new(vec![2.0, 900.0], vec![0.0], vec![link]).unwrap();
//! let deck = lsdyna_car_include(CarModel::Chain(&chain), &Default::default()).unwrap();
//! assert!(deck.contains("*MAT_SPRING_INELASTIC"));
//! ```

use crate::ExportError;
use crate::calculix::CalculixOptions;
use crate::lsdyna::LsDynaOptions;
use bumpsim_core::chain::Chain;
use bumpsim_core::model::MsdModel;

/// The model of a car file, in either chain form.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CarModel<'a> {
    /// Linear springs and dampers.
    Linear(&'a MsdModel),
    /// Nonlinear links (and perhaps a front link).
    Chain(&'a Chain),
}

impl CarModel<'_> {
    /// Number of masses.
    pub fn dof(&self) -> usize {
        match self {
            CarModel::Linear(model) => model.dof(),
            CarModel::Chain(chain) => chain.dof(),
        }
    }
}

/// The LS-DYNA include of the car.
pub fn lsdyna_car_include(
    model: CarModel<'_>,
    options: &LsDynaOptions,
) -> Result<String, ExportError> {
    match model {
        CarModel::Linear(model) => crate::lsdyna::lsdyna_include(model, options),
        CarModel::Chain(chain) => crate::chain::lsdyna_chain_include(chain, options),
    }
}

/// The CalculiX deck of the car (a transient under `options.analysis`'s
/// force when it has one).
pub fn calculix_car_deck(
    model: CarModel<'_>,
    options: &CalculixOptions,
) -> Result<String, ExportError> {
    match model {
        CarModel::Linear(model) => crate::calculix::calculix_deck(model, options),
        CarModel::Chain(chain) => crate::chain_calculix::calculix_chain_deck(chain, options, None),
    }
}

/// The critical step of a chain: Gershgorin's row sums of `k (1/m_j +
/// 1/m_(j+1))` over the links at their steepest slopes, `k/m` on the mass a
/// wall spring (front link, second load path, rebound link) pushes, and the
/// dampers' rates likewise; `min(2/ω, 2/γ)` as [`crate::timestep`].
fn chain_step(chain: &Chain) -> f64 {
    let slope = |l: &bumpsim_core::link::Link| l.steepest_slope().max(f64::MIN_POSITIVE);
    let m = chain.masses();
    let mut omega2 = vec![0.0; m.len()];
    let mut gamma = vec![0.0; m.len()];
    if let Some(front) = chain.front() {
        omega2[0] += slope(front) / m[0];
    }
    for (j, (link, c)) in chain.links().iter().zip(chain.dampers()).enumerate() {
        let inverse = 1.0 / m[j] + 1.0 / m[j + 1];
        for node in [j, j + 1] {
            omega2[node] += slope(link) * inverse;
            gamma[node] += c * inverse;
        }
    }
    for (_, _, wall) in crate::chain::wall_links(chain) {
        omega2[wall.mass] += slope(&wall.link) / m[wall.mass];
    }
    let limit = |rate: f64| match rate > 0.0 {
        true => 2.0 / rate,
        false => f64::INFINITY,
    };
    let omega = omega2.iter().copied().fold(0.0, f64::max).sqrt();
    limit(omega).min(limit(gamma.iter().copied().fold(0.0, f64::max)))
}

/// The car's critical explicit time step, s (infinite without links).
pub fn critical_time_step(model: CarModel<'_>) -> f64 {
    match model {
        CarModel::Linear(model) => crate::timestep::critical_time_step(model),
        CarModel::Chain(chain) => chain_step(chain),
    }
}

/// [`crate::timestep::below_minimum`] of the car: its critical step when
/// below `minimum` (s).
pub fn below_minimum(model: CarModel<'_>, minimum: f64) -> Result<Option<f64>, ExportError> {
    match model {
        CarModel::Linear(model) => crate::timestep::below_minimum(model, minimum),
        CarModel::Chain(_) if !(minimum.is_finite() && minimum >= 0.0) => {
            Err(ExportError::MinTimeStep { value: minimum })
        }
        CarModel::Chain(_) => {
            let step = critical_time_step(model);
            Ok((step < minimum).then_some(step))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use bumpsim_core::link::{Curve, Link, Unloading};

    /// One link: the bound is that of a linear spring at the steepest slope
    /// (here the unloading's, 4e6 N/m on 1 kg and 1 kg: ω² = 8e6).
    #[test]
    fn the_steepest_slope_bounds_the_step() {
        let link = Link::new(
            Curve::bilinear(1e6, 5e4, 0.1).unwrap(),
            Unloading::Slope(4e6),
        )
        .unwrap();
        let chain = Chain::new(vec![1.0, 1.0], vec![0.0], vec![link.clone()]).unwrap();
        let dt = critical_time_step(CarModel::Chain(&chain));
        assert!((dt - 2.0 / 8e6_f64.sqrt()).abs() < 1e-12 * dt, "{dt}");
        // a front link adds k/m1 at m1 (the wall does not move)
        let front = chain.clone().with_front(link);
        let dt = critical_time_step(CarModel::Chain(&front));
        assert!((dt - 2.0 / 12e6_f64.sqrt()).abs() < 1e-9 * dt, "{dt}");
        let deck = calculix_car_deck(CarModel::Chain(&chain), &Default::default()).unwrap();
        assert!(deck.contains("*PLASTIC"));
    }
}
