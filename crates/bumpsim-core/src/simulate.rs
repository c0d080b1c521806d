//! Simulation of the chain MSD model under a sampled force on m1.
//!
//! The discrete update of [`crate::discrete`] gives the states `X[k]` at the
//! force samples. From them, per sample:
//!
//! - displacement x_i, velocity v_i (m, m/s; positive in the force direction);
//! - spring force s_j = k_j (x_j − x_(j+1)) and damper force
//!   d_j = c_j (v_j − v_(j+1)) (N, positive in compression);
//! - acceleration a_i = (f δ_i1 − s_i − d_i + s_(i−1) + d_(i−1)) / m_i
//!   (m/s², with `f = f[k]`);
//! - kinetic energy Σ ½ m_i v_i², spring energy Σ ½ k_j (x_j − x_(j+1))²,
//!   and, summed from t0, the energy dissipated by the dampers and the work of
//!   the force (J), integrated exactly over each step ([`crate::energy`]);
//! - the impulse of the force ∫ f dt by the hold rule (N·s), so that
//!   momentum Σ m_i v_i − p0 can be checked against it.
//!
//! ```
//! use bumpsim_core::{model::MsdModel, series::UniformSeries, discrete::Method};
//! use bumpsim_core::simulate::{simulate, InitialState};
//! let car = MsdModel::new(vec![2.0], vec![], vec![]).unwrap();
//! let force = UniformSeries::new(0.0, 0.01, vec![4.0; 101]).unwrap();
//! let r = simulate(&car, &force, Method::Zoh, &InitialState::Rest).unwrap();
//! // x = F t² / 2m at t = 1 s
//! assert!((r.displacement[0][100] - 1.0).abs() < 1e-12);
//! ```

use crate::discrete::{DiscreteModel, DiscretiseError, Method, Substeps};
use crate::energy::StepIntegrals;
use crate::model::MsdModel;
use crate::series::{UniformSeries, peak_of};

/// The state at the first sample.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum InitialState {
    /// Every mass at rest (pendulum test on a parked car).
    #[default]
    Rest,
    /// Every mass moving at this speed, m/s, springs relaxed (moving-car test).
    UniformVelocity(f64),
    /// A full state [x1..xn, v1..vn] in m and m/s.
    State(Vec<f64>),
}

/// Why a simulation cannot run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SimulationError {
    /// The model cannot be discretised at the force's sample interval.
    #[error(transparent)]
    Discretise(#[from] DiscretiseError),
    /// A full initial state of the wrong length.
    #[error(
        "the initial state has {found} values; a {dof}-DOF model needs {expected} (x1..x{dof}, v1..v{dof})"
    )]
    InitialLength {
        /// Number of masses.
        dof: usize,
        /// 2n.
        expected: usize,
        /// Given.
        found: usize,
    },
    /// An initial value is not finite.
    #[error("initial state value {index} is {value}, expected a finite number")]
    InitialValue {
        /// Index in the state.
        index: usize,
        /// The value.
        value: f64,
    },
    /// The force's sample interval differs from the one the simulator was built for.
    #[error(
        "the force is sampled at {found:e} s but the simulator was discretised at {expected:e} s"
    )]
    SampleInterval {
        /// The simulator's T, s.
        expected: f64,
        /// The force's T, s.
        found: f64,
    },
    /// The states left the finite range (cannot happen for a stable discretisation;
    /// checked so that no NaN is ever returned).
    #[error("the simulation diverged at t = {time} s ({method})")]
    Diverged {
        /// First time with a non-finite state, s.
        time: f64,
        /// The method.
        method: Method,
    },
}

/// Energy histories, J. `dissipated` and `work` are summed from the first sample.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Energy {
    /// Σ ½ m v².
    pub kinetic: Vec<f64>,
    /// Σ ½ k Δx².
    pub spring: Vec<f64>,
    /// Energy dissipated by the dampers since t0.
    pub dissipated: Vec<f64>,
    /// Work done by the force on m1 since t0.
    pub work: Vec<f64>,
}

impl Energy {
    /// Balance residual per sample, J:
    /// `E_kin + E_spring + E_dissipated − W − (E_kin + E_spring)(t0)`.
    pub fn residual(&self) -> Vec<f64> {
        let initial = self.kinetic[0] + self.spring[0];
        (0..self.kinetic.len())
            .map(|k| self.kinetic[k] + self.spring[k] + self.dissipated[k] - self.work[k] - initial)
            .collect()
    }

    /// Largest |residual| relative to the largest energy involved (0 when no energy moves).
    pub fn relative_error(&self) -> f64 {
        let scale = [&self.kinetic, &self.spring, &self.dissipated, &self.work]
            .iter()
            .flat_map(|v| v.iter())
            .fold(0.0_f64, |m, v| m.max(v.abs()));
        let worst = self.residual().iter().fold(0.0_f64, |m, r| m.max(r.abs()));
        if scale > 0.0 { worst / scale } else { 0.0 }
    }
}

/// Time histories of a simulation; outer index = mass or link, inner = sample.
#[derive(Debug, Clone, PartialEq)]
pub struct Response {
    /// The method used.
    pub method: Method,
    /// Sample times, s.
    pub time: Vec<f64>,
    /// The force on m1, N.
    pub force: Vec<f64>,
    /// Displacements x1..xn, m.
    pub displacement: Vec<Vec<f64>>,
    /// Velocities v1..vn, m/s.
    pub velocity: Vec<Vec<f64>>,
    /// Accelerations a1..an, m/s².
    pub acceleration: Vec<Vec<f64>>,
    /// Spring forces s1..s(n-1), N, positive in compression.
    pub spring_force: Vec<Vec<f64>>,
    /// Damper forces d1..d(n-1), N, positive in compression.
    pub damper_force: Vec<Vec<f64>>,
    /// Energy terms, J.
    pub energy: Energy,
    /// Impulse of the force since t0, N·s.
    pub impulse: Vec<f64>,
    /// Momentum Σ m v, N·s.
    pub momentum: Vec<f64>,
}

impl Response {
    /// Number of masses.
    pub fn dof(&self) -> usize {
        self.displacement.len()
    }

    /// Time (s) and value (m) of the largest |displacement| of mass `index` (0-based).
    pub fn peak_displacement(&self, index: usize) -> (f64, f64) {
        let (k, value) = peak_of(&self.displacement[index]);
        (self.time[k], value)
    }

    /// Largest |momentum − p0 − impulse| relative to the largest |impulse| or |p0|.
    pub fn momentum_error(&self) -> f64 {
        let p0 = self.momentum[0];
        let scale = self.impulse.iter().fold(p0.abs(), |m, v| m.max(v.abs()));
        let worst = self
            .momentum
            .iter()
            .zip(&self.impulse)
            .fold(0.0_f64, |m, (p, i)| m.max((p - p0 - i).abs()));
        if scale > 0.0 { worst / scale } else { 0.0 }
    }

    /// Whether every history is finite (a model the discretisation cannot
    /// represent, or an absurd initial velocity, gives inf or NaN).
    pub fn is_finite(&self) -> bool {
        let e = &self.energy;
        [&self.displacement, &self.velocity, &self.acceleration]
            .iter()
            .flat_map(|h| h.iter().flatten())
            .chain(
                [
                    &e.kinetic,
                    &e.spring,
                    &e.dissipated,
                    &e.work,
                    &self.momentum,
                ]
                .into_iter()
                .flatten(),
            )
            .all(|v| v.is_finite())
    }

    /// The response's own checks against [`CHECK_TOLERANCE`]: the energy
    /// balance (relative to the largest energy term) and the momentum
    /// balance (relative to the impulse). Empty when both hold.
    pub fn warnings(&self) -> Vec<String> {
        let mut out = Vec::new();
        if !self.is_finite() {
            out.push("the response holds non-finite values (inf or NaN)".to_string());
        }
        let energy = self.energy.relative_error();
        if energy > CHECK_TOLERANCE {
            out.push(format!("energy balance error {energy:.3} of the largest energy term exceeds the tolerance {CHECK_TOLERANCE}: the sample interval does not resolve this model (use a finer force sampling or a softer/heavier model)"));
        }
        let momentum = self.momentum_error();
        if momentum > CHECK_TOLERANCE {
            out.push(format!("momentum error {momentum:.3} of the impulse exceeds the tolerance {CHECK_TOLERANCE}"));
        }
        out
    }
}

/// Tolerance of the self-checks of [`Response::warnings`] (relative).
pub const CHECK_TOLERANCE: f64 = 0.01;

/// A model discretised for one sample interval, ready to run many force histories.
#[derive(Debug, Clone)]
pub struct Simulator {
    model: MsdModel,
    discrete: DiscreteModel,
    integrals: StepIntegrals,
}

impl Simulator {
    /// Discretises `model` at `step` (s) with `method`.
    pub fn new(model: &MsdModel, method: Method, step: f64) -> Result<Self, SimulationError> {
        Self::with_substeps(model, method, step, Substeps::default())
    }

    /// As [`Simulator::new`], with sub-steps for taylor1.
    pub fn with_substeps(
        model: &MsdModel,
        method: Method,
        step: f64,
        substeps: Substeps,
    ) -> Result<Self, SimulationError> {
        let discrete = DiscreteModel::with_substeps(model, method, step, substeps)?;
        Ok(Self {
            model: model.clone(),
            integrals: StepIntegrals::new(model, method, step),
            discrete,
        })
    }

    /// The discretised model.
    pub fn discrete(&self) -> &DiscreteModel {
        &self.discrete
    }

    /// Runs one force history from an initial state.
    pub fn run(
        &self,
        force: &UniformSeries,
        initial: &InitialState,
    ) -> Result<Response, SimulationError> {
        let relative = (force.step() - self.discrete.step()).abs() / self.discrete.step();
        if relative > 1e-9 {
            return Err(SimulationError::SampleInterval {
                expected: self.discrete.step(),
                found: force.step(),
            });
        }
        let x0 = self.initial_vector(initial)?;
        let order = x0.len();
        let mut states = vec![0.0; force.len() * order];
        // lengths are consistent by construction, so propagate cannot fail here
        if let Err(e) = self.discrete.propagate(&x0, force.values(), &mut states) {
            unreachable!("{e}");
        }
        if let Some(row) = states
            .chunks_exact(order)
            .position(|x| x.iter().any(|v| !v.is_finite()))
        {
            return Err(SimulationError::Diverged {
                time: force.time(row),
                method: self.discrete.method(),
            });
        }
        Ok(self.response(force, &states))
    }

    fn initial_vector(&self, initial: &InitialState) -> Result<Vec<f64>, SimulationError> {
        let n = self.model.dof();
        let x0 = match initial {
            InitialState::Rest => vec![0.0; 2 * n],
            InitialState::UniformVelocity(v) => [vec![0.0; n], vec![*v; n]].concat(),
            InitialState::State(x) if x.len() == 2 * n => x.clone(),
            InitialState::State(x) => {
                return Err(SimulationError::InitialLength {
                    dof: n,
                    expected: 2 * n,
                    found: x.len(),
                });
            }
        };
        match x0.iter().position(|v| !v.is_finite()) {
            Some(index) => Err(SimulationError::InitialValue {
                index,
                value: x0[index],
            }),
            None => Ok(x0),
        }
    }

    fn response(&self, force: &UniformSeries, states: &[f64]) -> Response {
        let n = self.model.dof();
        let samples = force.len();
        let column =
            |offset: usize| -> Vec<f64> { states.chunks_exact(2 * n).map(|x| x[offset]).collect() };
        let displacement: Vec<Vec<f64>> = (0..n).map(column).collect();
        let velocity: Vec<Vec<f64>> = (n..2 * n).map(column).collect();
        let link = |coefficients: &[f64], values: &[Vec<f64>]| -> Vec<Vec<f64>> {
            coefficients
                .iter()
                .enumerate()
                .map(|(j, c)| {
                    values[j]
                        .iter()
                        .zip(&values[j + 1])
                        .map(|(a, b)| c * (a - b))
                        .collect()
                })
                .collect()
        };
        let spring_force = link(self.model.springs(), &displacement);
        let damper_force = link(self.model.dampers(), &velocity);
        let acceleration = accelerations(&self.model, force.values(), &spring_force, &damper_force);
        let energy = self.energy(force.values(), states, &velocity, &spring_force);
        Response {
            method: self.discrete.method(),
            time: force.times(),
            force: force.values().to_vec(),
            momentum: (0..samples)
                .map(|k| {
                    (0..n)
                        .map(|i| self.model.masses()[i] * velocity[i][k])
                        .sum()
                })
                .collect(),
            impulse: impulse(self.discrete.method(), force),
            displacement,
            velocity,
            acceleration,
            spring_force,
            damper_force,
            energy,
        }
    }

    fn energy(
        &self,
        force: &[f64],
        states: &[f64],
        velocity: &[Vec<f64>],
        spring_force: &[Vec<f64>],
    ) -> Energy {
        let samples = force.len();
        let kinetic = (0..samples)
            .map(|k| {
                self.model
                    .masses()
                    .iter()
                    .zip(velocity)
                    .map(|(m, v)| 0.5 * m * v[k] * v[k])
                    .sum()
            })
            .collect();
        let spring = (0..samples)
            .map(|k| {
                self.model
                    .springs()
                    .iter()
                    .zip(spring_force)
                    .map(|(s, f)| 0.5 * f[k] * f[k] / s)
                    .sum()
            })
            .collect();
        let order = 2 * self.model.dof();
        let mut z = vec![0.0; self.integrals.size()];
        let (mut dissipated, mut work) = (vec![0.0; samples], vec![0.0; samples]);
        for k in 1..samples {
            z[..order].copy_from_slice(&states[(k - 1) * order..k * order]);
            z[order] = force[k - 1];
            if let Some(delta) = z.get_mut(order + 1) {
                *delta = force[k] - force[k - 1];
            }
            dissipated[k] = dissipated[k - 1] + self.integrals.dissipated(&z);
            work[k] = work[k - 1] + self.integrals.work(&z);
        }
        Energy {
            kinetic,
            spring,
            dissipated,
            work,
        }
    }
}

fn accelerations(
    model: &MsdModel,
    force: &[f64],
    springs: &[Vec<f64>],
    dampers: &[Vec<f64>],
) -> Vec<Vec<f64>> {
    let n = model.dof();
    (0..n)
        .map(|i| {
            (0..force.len())
                .map(|k| {
                    let external = if i == 0 { force[k] } else { 0.0 };
                    let behind = if i + 1 < n {
                        springs[i][k] + dampers[i][k]
                    } else {
                        0.0
                    };
                    let ahead = if i > 0 {
                        springs[i - 1][k] + dampers[i - 1][k]
                    } else {
                        0.0
                    };
                    (external - behind + ahead) / model.masses()[i]
                })
                .collect()
        })
        .collect()
}

/// Impulse since t0 by the hold rule of the method (exact for that hold).
fn impulse(method: Method, force: &UniformSeries) -> Vec<f64> {
    let step = force.step();
    let values = force.values();
    let mut total = 0.0;
    std::iter::once(0.0)
        .chain(values.windows(2).map(|f| {
            total += match method {
                Method::Foh => 0.5 * (f[0] + f[1]) * step,
                _ => f[0] * step,
            };
            total
        }))
        .collect()
}

/// Simulates `model` under `force` (on m1) with `method` from `initial`.
pub fn simulate(
    model: &MsdModel,
    force: &UniformSeries,
    method: Method,
    initial: &InitialState,
) -> Result<Response, SimulationError> {
    Simulator::new(model, method, force.step())?.run(force, initial)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn uniform_velocity_drifts_without_force() {
        let car = MsdModel::new(vec![1.0, 2.0], vec![10.0], vec![100.0]).unwrap();
        let force = UniformSeries::new(0.0, 1e-3, vec![0.0; 11]).unwrap();
        let r = simulate(
            &car,
            &force,
            Method::Zoh,
            &InitialState::UniformVelocity(2.0),
        )
        .unwrap();
        assert_relative_eq!(r.displacement[1][10], 0.02, max_relative = 1e-12);
        assert_relative_eq!(r.spring_force[0][10], 0.0, epsilon = 1e-9);
    }

    #[test]
    fn bad_initial_states_are_refused() {
        let car = MsdModel::new(vec![1.0], vec![], vec![]).unwrap();
        let force = UniformSeries::new(0.0, 1e-3, vec![0.0; 3]).unwrap();
        let short = simulate(&car, &force, Method::Zoh, &InitialState::State(vec![0.0]));
        assert!(matches!(
            short,
            Err(SimulationError::InitialLength { expected: 2, .. })
        ));
        let nan = simulate(
            &car,
            &force,
            Method::Zoh,
            &InitialState::UniformVelocity(f64::NAN),
        );
        assert!(matches!(nan, Err(SimulationError::InitialValue { .. })));
    }

    #[test]
    fn simulator_refuses_another_sample_interval() {
        let car = MsdModel::new(vec![1.0], vec![], vec![]).unwrap();
        let sim = Simulator::new(&car, Method::Zoh, 1e-3).unwrap();
        let force = UniformSeries::new(0.0, 2e-3, vec![0.0; 3]).unwrap();
        assert!(matches!(
            sim.run(&force, &InitialState::Rest),
            Err(SimulationError::SampleInterval { .. })
        ));
    }
}
