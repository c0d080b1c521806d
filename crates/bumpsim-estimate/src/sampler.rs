//! The affine-invariant ensemble sampler of Goodman & Weare (2010), as
//! emcee runs it (Foreman-Mackey et al. 2013), for any log density.
//!
//! W walkers move together. Each step splits the ensemble into two random
//! halves (emcee's `randomize_split`) and updates them in turn; walker k of one half proposes the *stretch move*
//! `Y = X_j + z (X_k − X_j)` towards a walker j drawn from the other half,
//! with `z` drawn from `g(z) ∝ 1/√z` on `[1/a, a]` (`a` = [`STRETCH`]), and
//! accepts it with probability `min(1, z^{d−1} p(Y)/p(X_k))` (d the
//! dimension). The move is invariant under affine maps, so a posterior
//! with strongly correlated parameters (a mass and a spring that trade
//! against each other) mixes as a round one does.
//!
//! **Parallel and seeded.** The walkers of a half depend only on the other
//! half, so they are evaluated in parallel (rayon; emcee's `pool`). Every
//! random number (the partner j, z, the acceptance draw) is drawn in walker
//! order from one ChaCha8 stream seeded with the seed *before* the half is
//! evaluated, so a run gives the same chain on any number of threads.
//!
//! **Diagnostics** ([`Chain::diagnose`]), on the draws after the burn-in:
//! the integrated autocorrelation time τ of each parameter (Sokal's window
//! over the walkers' centred series, [`crate::effective`]), the effective
//! number of draws `W L/τ`, the split-R̂ of Gelman et al. (2013, *Bayesian
//! Data Analysis*, 3rd ed., sec. 11.4; each walker's draws halved, 2W
//! chains) and the acceptance fraction. A run has converged when its kept
//! length is at least [`LENGTHS`] τ of every parameter (emcee's advice),
//! every τ's window fits in the chain, and every R̂ is below [`R_HAT`];
//! otherwise [`Diagnostics::warnings`] says which failed and what to do.
//!
//! ```
//! use bumpsim_estimate::sampler::{Ensemble, sample};
//! // a correlated 2-D Gaussian: ρ = 0.9, unit variances
//! let density = |p: &[f64]| {
//!     let (x, y) = (p[0], p[1]);
//!     -(x * x - 1.8 * x * y + y * y) / (2.0 * (1.0 - 0.81))
//! };
//! // the starts must span the space: the moves stay in the walkers' affine hull
//! let starts: Vec<Vec<f64>> = (0..16).map(|k| vec![(0.7 * k as f64).sin(), (1.3 * k as f64).cos()]).collect();
//! let ensemble = Ensemble { walkers: 16, steps: 3000, burn: 500, seed: 1 };
//! let chain = sample(&|| density, starts, &ensemble).unwrap();
//! let x: Vec<f64> = chain.draws(0);
//! let mean = x.iter().sum::<f64>() / x.len() as f64;
//! let var = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / x.len() as f64;
//! assert!(mean.abs() < 0.15 && (var - 1.0).abs() < 0.15, "{mean} {var}");
//! let d = chain.diagnose();
//! assert!(d.converged, "{:?}", d.warnings);
//! ```

use crate::effective::{Method, of_series};
use rand_chacha::ChaCha8Rng;
use rand_core::{Rng, SeedableRng};
use rayon::prelude::*;
use serde::Serialize;

/// The stretch scale a of the move (emcee's default).
pub const STRETCH: f64 = 2.0;

/// A run has converged only if it is at least this many autocorrelation
/// times long (emcee's documentation: "N > 50 τ").
pub const LENGTHS: f64 = 50.0;

/// A run has converged only if every split-R̂ is below this: between the
/// 1.1 of Gelman et al. (2013, sec. 11.5) and the 1.01 Vehtari et al.
/// (2021) ask of four long chains, since an ensemble's walkers are many
/// short chains whose R̂ scatters by about `1/(2 ESS)` of each half.
pub const R_HAT: f64 = 1.05;

/// A density evaluated by the sampler: the log of an unnormalised density,
/// `−∞` outside its support.
pub trait LogDensity {
    /// `ln p(x)` (`&mut`: a density may keep buffers; each parallel task
    /// has its own).
    fn log_density(&mut self, x: &[f64]) -> f64;
}

impl<F: Fn(&[f64]) -> f64> LogDensity for F {
    fn log_density(&mut self, x: &[f64]) -> f64 {
        self(x)
    }
}

/// How long and how wide a run is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Ensemble {
    /// Walkers W: even, at least twice the dimension plus two.
    pub walkers: usize,
    /// Steps of every walker, burn-in included.
    pub steps: usize,
    /// Steps discarded at the start.
    pub burn: usize,
    /// Seed of the random stream.
    pub seed: u64,
}

/// Why a run cannot start.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SamplerError {
    /// Too few walkers, an odd number of them, or no steps kept.
    #[error(
        "{walkers} walkers, {steps} steps with {burn} burnt, for {dimension} parameters: need an even number of at least 2 d + 2 walkers and more steps than burnt"
    )]
    Size {
        /// Walkers.
        walkers: usize,
        /// Steps.
        steps: usize,
        /// Burn-in.
        burn: usize,
        /// Parameters.
        dimension: usize,
    },
    /// A start of the wrong length or with no density.
    #[error(
        "start {walker} has {found} values for {dimension} parameters, or no density there (ln p = −∞ or not finite)"
    )]
    Start {
        /// The walker.
        walker: usize,
        /// Its values.
        found: usize,
        /// Parameters.
        dimension: usize,
    },
}

/// The draws of a run after its burn-in.
#[derive(Debug, Clone, PartialEq)]
pub struct Chain {
    /// Parameters d.
    pub dimension: usize,
    /// Walkers W.
    pub walkers: usize,
    /// Steps kept L.
    pub steps: usize,
    /// `[step][walker][parameter]`, row-major: draw `(s, w)` at
    /// `(s W + w) d`.
    pub values: Vec<f64>,
    /// `ln p` of every kept draw, `[step][walker]`.
    pub log_density: Vec<f64>,
    /// Accepted proposals over all proposals, burn-in included.
    pub acceptance: f64,
}

/// Runs the sampler from `starts` (one point per walker) on the density
/// `make()` builds (one per parallel task, so that densities with buffers
/// share nothing).
pub fn sample<D: LogDensity>(
    make: &(dyn Fn() -> D + Sync),
    starts: Vec<Vec<f64>>,
    ensemble: &Ensemble,
) -> Result<Chain, SamplerError> {
    sample_observed(make, starts, ensemble, &|| {})
}

/// [`sample`], calling `step` after every step of the ensemble (a
/// progress bar's `inc`).
pub fn sample_observed<D: LogDensity>(
    make: &(dyn Fn() -> D + Sync),
    starts: Vec<Vec<f64>>,
    ensemble: &Ensemble,
    step: &(dyn Fn() + Sync),
) -> Result<Chain, SamplerError> {
    let Ensemble {
        walkers,
        steps,
        burn,
        seed,
    } = *ensemble;
    let d = starts.first().map_or(0, Vec::len);
    if walkers % 2 != 0 || walkers < 2 * d + 2 || starts.len() != walkers || steps <= burn {
        return Err(SamplerError::Size {
            walkers,
            steps,
            burn,
            dimension: d,
        });
    }
    let mut x = starts;
    let mut lp: Vec<f64> = x
        .par_iter()
        .map_init(make, |density, p| density.log_density(p))
        .collect();
    if let Some(walker) = (0..walkers).find(|&k| x[k].len() != d || !lp[k].is_finite()) {
        return Err(SamplerError::Start {
            walker,
            found: x[walker].len(),
            dimension: d,
        });
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut chain = Chain {
        dimension: d,
        walkers,
        steps: steps - burn,
        values: Vec::with_capacity((steps - burn) * walkers * d),
        log_density: Vec::with_capacity((steps - burn) * walkers),
        acceptance: 0.0,
    };
    let mut accepted = 0usize;
    for k in 0..steps {
        let order = shuffled(walkers, &mut rng);
        let (first, second) = order.split_at(walkers / 2);
        accepted += move_half(make, (&mut x, &mut lp), (first, second), &mut rng);
        accepted += move_half(make, (&mut x, &mut lp), (second, first), &mut rng);
        if k >= burn {
            x.iter().for_each(|p| chain.values.extend_from_slice(p));
            chain.log_density.extend_from_slice(&lp);
        }
        step();
    }
    chain.acceptance = accepted as f64 / (steps * walkers) as f64;
    Ok(chain)
}

/// A uniform number in [0, 1) from 53 random bits.
fn unit(rng: &mut ChaCha8Rng) -> f64 {
    (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64
}

/// The numbers `0..n` in a random order (Fisher–Yates).
fn shuffled(n: usize, rng: &mut ChaCha8Rng) -> Vec<usize> {
    let mut order: Vec<usize> = (0..n).collect();
    for k in (1..n).rev() {
        let j = ((unit(rng) * (k + 1) as f64) as usize).min(k);
        order.swap(k, j);
    }
    order
}

/// One stretch move of every walker of `mine` against the walkers of
/// `other`; the number accepted.
fn move_half<D: LogDensity>(
    make: &(dyn Fn() -> D + Sync),
    (x, lp): (&mut [Vec<f64>], &mut [f64]),
    (mine, other): (&[usize], &[usize]),
    rng: &mut ChaCha8Rng,
) -> usize {
    let d = x[0].len();
    // every random number first, in walker order (the same on any threads)
    let draws: Vec<(usize, f64, f64)> = mine
        .iter()
        .map(|_| {
            let j = other[((unit(rng) * other.len() as f64) as usize).min(other.len() - 1)];
            let z = ((STRETCH - 1.0) * unit(rng) + 1.0).powi(2) / STRETCH;
            (j, z, unit(rng))
        })
        .collect();
    let proposals: Vec<Vec<f64>> = mine
        .iter()
        .zip(&draws)
        .map(|(&k, &(j, z, _))| (0..d).map(|i| x[j][i] + z * (x[k][i] - x[j][i])).collect())
        .collect();
    let densities: Vec<f64> = proposals
        .par_iter()
        .map_init(make, |density, p| density.log_density(p))
        .collect();
    let mut accepted = 0;
    for ((&k, &(_, z, u)), (proposal, density)) in mine
        .iter()
        .zip(&draws)
        .zip(proposals.into_iter().zip(densities))
    {
        let ratio = (d as f64 - 1.0) * z.ln() + density - lp[k];
        if density.is_finite() && u.ln() < ratio {
            x[k] = proposal;
            lp[k] = density;
            accepted += 1;
        }
    }
    accepted
}

/// How well a run has mixed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Diagnostics {
    /// Integrated autocorrelation time of each parameter, steps.
    pub autocorrelation_time: Vec<f64>,
    /// Whether each τ's window fitted within the kept steps.
    pub time_reliable: Vec<bool>,
    /// Effective draws of each parameter, `W L/τ`.
    pub effective_draws: Vec<f64>,
    /// Split-R̂ of each parameter.
    pub r_hat: Vec<f64>,
    /// The acceptance fraction.
    pub acceptance: f64,
    /// Whether the run has converged (see the module).
    pub converged: bool,
    /// What failed, and what to do.
    pub warnings: Vec<String>,
}

impl Chain {
    /// The kept draws of parameter `i`, step by step, walker by walker.
    pub fn draws(&self, i: usize) -> Vec<f64> {
        self.values
            .iter()
            .skip(i)
            .step_by(self.dimension)
            .copied()
            .collect()
    }

    /// Walker `w`'s kept draws of parameter `i`.
    pub fn walker(&self, w: usize, i: usize) -> Vec<f64> {
        (0..self.steps)
            .map(|s| self.values[(s * self.walkers + w) * self.dimension + i])
            .collect()
    }

    /// The diagnostics of the run (see the module); `names` name the
    /// parameters in the warnings.
    pub fn diagnose(&self) -> Diagnostics {
        let names: Vec<String> = (0..self.dimension).map(|i| format!("p{i}")).collect();
        self.diagnose_named(&names)
    }

    /// [`Chain::diagnose`] with the parameters' names.
    pub fn diagnose_named(&self, names: &[String]) -> Diagnostics {
        let mut d = Diagnostics {
            autocorrelation_time: Vec::new(),
            time_reliable: Vec::new(),
            effective_draws: Vec::new(),
            r_hat: Vec::new(),
            acceptance: self.acceptance,
            converged: true,
            warnings: Vec::new(),
        };
        for i in 0..self.dimension {
            let walkers: Vec<Vec<f64>> = (0..self.walkers).map(|w| self.walker(w, i)).collect();
            let views: Vec<&[f64]> = walkers.iter().map(Vec::as_slice).collect();
            let e = of_series(&views, Method::Spectral, true);
            d.autocorrelation_time.push(e.time);
            d.time_reliable.push(e.reliable);
            d.effective_draws.push(e.effective);
            d.r_hat.push(split_r_hat(&views));
        }
        d.warnings = self.warnings(&d, names);
        d.converged = d.warnings.is_empty();
        d
    }

    fn warnings(&self, d: &Diagnostics, names: &[String]) -> Vec<String> {
        let mut out = Vec::new();
        let name = |i: usize| names.get(i).cloned().unwrap_or_else(|| format!("p{i}"));
        let worst = (0..self.dimension)
            .max_by(|&a, &b| d.autocorrelation_time[a].total_cmp(&d.autocorrelation_time[b]));
        if let Some(i) = worst {
            let tau = d.autocorrelation_time[i];
            let short = (self.steps as f64) < LENGTHS * tau || !d.time_reliable[i];
            if short {
                out.push(format!(
                    "the posterior chain has not converged: {} kept steps are {:.1} autocorrelation times of {} (τ = {:.0} steps{}); at least {LENGTHS:.0} are needed: run more steps",
                    self.steps,
                    self.steps as f64 / tau,
                    name(i),
                    tau,
                    if d.time_reliable[i] { "" } else { ", at least" }
                ));
            }
        }
        let high: Vec<String> = (0..self.dimension)
            .filter(|&i| d.r_hat[i].is_nan() || d.r_hat[i] >= R_HAT)
            .map(|i| format!("{} {:.3}", name(i), d.r_hat[i]))
            .collect();
        if !high.is_empty() {
            out.push(format!(
                "the posterior chain has not converged: split-R̂ at or above {R_HAT} ({}): the walkers disagree; run more steps or a longer burn-in",
                high.join(", ")
            ));
        }
        out
    }
}

/// The split-R̂ of `chains` (each halved): `√(((L−1)/L W + B/L)/W)` with W
/// the mean within-chain variance and B/L the variance of the chain means.
pub fn split_r_hat(chains: &[&[f64]]) -> f64 {
    let halves: Vec<&[f64]> = chains
        .iter()
        .flat_map(|c| {
            let h = c.len() / 2;
            [&c[..h], &c[c.len() - h..]]
        })
        .collect();
    let l = halves.first().map_or(0, |h| h.len());
    if l < 2 || halves.len() < 2 {
        return f64::INFINITY;
    }
    let means: Vec<f64> = halves
        .iter()
        .map(|h| h.iter().sum::<f64>() / l as f64)
        .collect();
    let within = halves
        .iter()
        .zip(&means)
        .map(|(h, m)| h.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (l - 1) as f64)
        .sum::<f64>()
        / halves.len() as f64;
    let grand = means.iter().sum::<f64>() / means.len() as f64;
    let between_over_l =
        means.iter().map(|m| (m - grand).powi(2)).sum::<f64>() / (means.len() - 1) as f64;
    let pooled = (l as f64 - 1.0) / l as f64 * within + between_over_l;
    match within > 0.0 {
        true => (pooled / within).sqrt(),
        false if between_over_l == 0.0 => 1.0,
        false => f64::INFINITY,
    }
}
