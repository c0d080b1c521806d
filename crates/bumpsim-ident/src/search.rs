//! The starts of a chain identification (issue 19); the layer's staged
//! search ([`bumpsim_estimate::search`]) runs them.
//!
//! **Exploring starts**, in this order: the user's start, the data-derived start
//! ([`crate::estimate::data_start`]), the continuation starts (below), then
//! log-uniform random points ([`Draws`], seeded by `seed + start index`:
//! the same starts on any number of threads), around the data start and the
//! continuation starts in turn: within a factor 30 of the data start, within
//! [`NEIGHBOURHOOD`] of a continuation start (the neighbourhood of the
//! smaller model's optimum is searched where it is, instead of hoping a wide
//! draw lands there). Every start is clamped into [`VALID_RANGE`], where a
//! model can be evaluated (a split of a wall-like mass would otherwise need a
//! link stiffer than any model can be, and the start would be lost).
//!
//! **Continuation across the DOF table.** When the (n−1)-mass optimum is
//! known, each of its masses is split in turn into two halves joined by a
//! link whose frequency is √(1e5) ≈ 316 times the smaller model's fastest
//! mode bound (damper at 30 % of critical for the halves): n−1 starts whose
//! objective is, within a percent, that of the (n−1)-mass optimum (tested),
//! so the n-mass search begins where the smaller model ended. A link that
//! stiff is a stationary point (the data cannot see it: its Jacobian
//! column is zero), so random starts around such a seed draw the link's
//! frequency and damping over their whole range (`Split` below).

use crate::case::VALID_RANGE;
use bumpsim_core::model::MsdModel;
use bumpsim_estimate::search::Draws;

/// Starts from the (n−1)-mass optimum `previous` for an n-mass model, SI,
/// thesis order `[m.., c.., k..]`: one per mass of `previous`, that mass split
/// into two halves joined by a link with `ω_link² = 1e5 ω²`, where
/// `ω² = max k_j (1/m_j + 1/m_{j+1})` bounds the fastest mode of `previous`.
/// None for a single rigid mass.
///
/// ```
/// use bumpsim_core::model::MsdModel;
/// use bumpsim_ident::search::continuation_starts;
/// let two = MsdModel::new(vec![10.0, 1000.0], vec![2e3], vec![1e6]).unwrap();
/// let starts = continuation_starts(&two);
/// assert_eq!(starts.len(), 2);
/// assert_eq!(&starts[0][..3], &[5.0, 5.0, 1000.0]);      // m1 split in halves
/// let omega2 = 1e6 * (1.0 / 10.0 + 1.0 / 1000.0);
/// assert!((starts[0][5] - 1e5 * omega2 * 2.5).abs() < 1e-6 * starts[0][5]); // k = ω_link² m1/4
/// assert!(continuation_starts(&MsdModel::new(vec![900.0], vec![], vec![]).unwrap()).is_empty());
/// ```
pub fn continuation_starts(previous: &MsdModel) -> Vec<Vec<f64>> {
    let (m, k) = (previous.masses(), previous.springs());
    let omega2 = (0..k.len())
        .map(|j| k[j] * (1.0 / m[j] + 1.0 / m[j + 1]))
        .fold(0.0, f64::max);
    if omega2 <= 0.0 {
        return Vec::new(); // a rigid mass has no time scale to be stiffer than
    }
    (0..previous.dof())
        .map(|j| split(previous, j, 1e5 * omega2))
        .collect()
}

/// `previous` with mass `j` split into halves joined by a link of natural
/// frequency² `omega2` (reduced mass m_j/4), damped at 30 % of critical.
fn split(previous: &MsdModel, j: usize, omega2: f64) -> Vec<f64> {
    let half = 0.5 * previous.masses()[j];
    let stiff = omega2 * 0.5 * half;
    let damper = 2.0 * 0.3 * (stiff * 0.5 * half).sqrt();
    let mut masses = previous.masses().to_vec();
    masses[j] = half;
    masses.insert(j, half);
    let mut dampers = previous.dampers().to_vec();
    dampers.insert(j, damper);
    let mut springs = previous.springs().to_vec();
    springs.insert(j, stiff);
    [masses, dampers, springs].concat()
}

/// The starting points in log space, free parameters only: `user`, `data`,
/// `seeds`, then random points around `data` and the seeds, `count` in all;
/// around a seed with a split link (`links[i]`), that link is drawn over
/// its range (`Split` below).
pub(crate) fn starting_points(
    count: usize,
    seed: u64,
    fixed: (&Option<Vec<f64>>, &[f64], &[Vec<f64>]),
    links: &[Option<usize>],
    free: &[usize],
) -> Vec<Vec<f64>> {
    let (user, data, seeds) = fixed;
    let log = |theta: &[f64]| -> Vec<f64> { free.iter().map(|&i| theta[i].ln()).collect() };
    let mut points: Vec<Vec<f64>> = user.iter().map(|u| log(u)).collect();
    points.push(log(data));
    points.extend(seeds.iter().map(|s| log(s)));
    let split = |(i, s): (usize, &Vec<f64>)| {
        let link = links.get(i).copied().flatten();
        link.and_then(|l| Split::of(s, l, free))
    };
    let centres: Vec<(Vec<f64>, f64, Option<Split>)> = std::iter::once((log(data), 30.0, None))
        .chain(
            seeds
                .iter()
                .enumerate()
                .map(|(i, s)| (log(s), NEIGHBOURHOOD, split((i, s)))),
        )
        .collect();
    let mut index = points.len() as u64;
    while points.len() < count.max(1) {
        let (centre, spread, link) = &centres[index as usize % centres.len()];
        points.push(draw(centre, *spread, link.as_ref(), seed, index));
        index += 1;
    }
    points.truncate(count.max(1));
    let (floor, ceiling) = (VALID_RANGE.start().ln(), VALID_RANGE.end().ln());
    for value in points.iter_mut().flatten() {
        *value = value.clamp(floor, ceiling);
    }
    points
}

/// A log-uniform point within a factor `spread` of `centre` (log space),
/// from the draws of start `index`; with a split link, that link drawn over
/// its range.
fn draw(centre: &[f64], spread: f64, link: Option<&Split>, seed: u64, index: u64) -> Vec<f64> {
    let mut draws = Draws::new(seed, index);
    let mut point = draws.around(centre, spread);
    if let Some(link) = link {
        let (frequency, damping) = (draws.unit(), draws.unit());
        link.draw(&mut point, frequency, damping);
    }
    point
}

/// The link that joins the halves of a mass split by a continuation start,
/// in free log parameters: its spring and damper positions, the seed's
/// `ln k` (the link at `1e5 ω²`, far above the data's bandwidth: a
/// stationary point, whose Jacobian column is zero), and `ln μ` of the
/// halves (μ = m/4).
///
/// Random starts around the seed draw the link's frequency log-uniform
/// from the smaller model's fastest mode to the seed's (`ω_link² / ω² ∈
/// [1, 1e5]`) and its damping ratio from 0.05 to 1, so that they begin
/// where the data can see the new mass, and descend from there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Split {
    spring: usize,
    damper: usize,
    ln_k: f64,
    ln_mu: f64,
}

/// The split link's frequency range, `ω_link² / ω²` (see `Split`).
pub const SPLIT_STIFFNESS: f64 = 1e5;

/// The split link's damping ratios drawn (see `Split`).
pub const SPLIT_DAMPING: (f64, f64) = (0.05, 1.0);

impl Split {
    /// The split link `l` of continuation seed `theta` (SI, thesis order)
    /// when its spring and damper are free.
    fn of(theta: &[f64], l: usize, free: &[usize]) -> Option<Split> {
        // 3n − 2 parameters
        let dof = theta.len().div_ceil(3);
        let (spring, damper) = (2 * dof - 1 + l, dof + l);
        let position = |i: usize| free.iter().position(|&f| f == i);
        let (m1, m2) = (*theta.get(l)?, *theta.get(l + 1)?);
        Some(Split {
            spring: position(spring)?,
            damper: position(damper)?,
            ln_k: theta.get(spring)?.ln(),
            ln_mu: (m1 * m2 / (m1 + m2)).ln(),
        })
    }

    /// Sets the link in `point` from two uniform numbers.
    fn draw(&self, point: &mut [f64], frequency: f64, damping: f64) {
        let ln_k = self.ln_k - frequency * SPLIT_STIFFNESS.ln();
        let (low, high) = SPLIT_DAMPING;
        let ln_zeta = low.ln() + damping * (high / low).ln();
        // c = 2 ζ √(k μ)
        point[self.spring] = ln_k;
        point[self.damper] = 2f64.ln() + ln_zeta + 0.5 * (ln_k + self.ln_mu);
    }
}

/// Random starts around a continuation start lie within this factor of
/// it: they explore the basin the smaller model's optimum leads into (±20 %); the wide draws around the data start
/// explore elsewhere. A factor of 3 around continuation starts threw most
/// of them into other basins: on ten synthetic 5-DOF problems
/// (tests/identification/five_dof.rs) many ended 1e5 × above the best.
pub const NEIGHBOURHOOD: f64 = 1.2;

#[cfg(test)]
mod tests {
    use super::*;
    use bumpsim_core::discrete::Method;
    use bumpsim_core::series::UniformSeries;
    use bumpsim_core::simulate::{InitialState, simulate};

    #[test]
    fn a_split_start_responds_like_the_smaller_model() {
        let two = MsdModel::new(vec![20.0, 1000.0], vec![3e3], vec![8e5]).unwrap();
        let force: Vec<f64> = (0..600)
            .map(|k| 2e4 * (k as f64 * 1e-4 * 60.0).sin().max(0.0))
            .collect();
        let force = UniformSeries::new(0.0, 1e-4, force).unwrap();
        let x = |m: &MsdModel| {
            let r = simulate(m, &force, Method::Zoh, &InitialState::Rest).unwrap();
            r.displacement[0].clone()
        };
        let reference = x(&two);
        let peak = reference.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        for start in continuation_starts(&two) {
            let three = MsdModel::from_parameters(3, &start).unwrap();
            let split = x(&three);
            let worst = split
                .iter()
                .zip(&reference)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(
                worst < 2e-3 * peak,
                "split start differs by {worst} of {peak}"
            );
        }
    }
}
