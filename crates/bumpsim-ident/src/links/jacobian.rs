//! The exact Jacobian of the links objective ([`super::LinkObjective`]):
//! each case run on dual numbers by the chain's one mechanism
//! ([`bumpsim_core::chain::Chain::motion`]), [`WIDTH`] log parameters at a
//! time, so a column is `w ∂D[y](t_k)/∂p_j` of the discrete run itself —
//! its plastic sets and its switches between loading and unloading
//! included, the history δ_max carried with its derivatives — with no
//! difference step (D the case's domain, linear, applied to the output's
//! tangents).
//!
//! A parameter is searched as `p = ln θ`, so its direction is seeded with
//! `∂θ/∂p = θ`. The chain of θ is [`Layout::chain`]'s, on any
//! [`Real`]: masses and dampers as they are, link j the bilinear curve
//! `(k_j, F_yj, min(r_j, 1))` unloading at `max(u_j, 1) k_j` (the clamps
//! by value: the branch taken is differentiated).
//!
//! Why [`WIDTH`] = 8 and blocks: a [`Dual`] carries its tangent in a
//! fixed array (no allocation in the steps), so its width is fixed at
//! compile time. An operation costs about `1 + N` (sums) to `1 + 2N`
//! (products) flops, so one run on N directions costs about what N + 1
//! `f64` runs cost (the step logic, branches and history are shared);
//! 8 tangents fill one 64-byte line. A 2-mass chain (7 parameters) is one
//! pass; 13 (3 masses) two, 19 three; the blocks run in parallel.

use super::drive;
use crate::case::LoadCase;
use crate::links::Layout;
use bumpsim_core::chain::{Chain, ChainValues};
use bumpsim_core::dual::{Dual, Real};
use bumpsim_estimate::domain::Domain;
use nalgebra::DMatrix;
use rayon::prelude::*;

/// Log parameters differentiated in one run.
pub const WIDTH: usize = 8;

/// A number with its derivatives along one block of log parameters.
pub type Tangent = Dual<WIDTH>;

/// The chain's values on `T` from the SI parameters `theta` in the
/// layout's order (`chain` = `layout.chain(θ)`, for its shape).
pub fn values<T: Real>(layout: Layout, chain: &Chain, theta: &[T]) -> ChainValues<T> {
    let (n, l) = (layout.dof, layout.dof - 1);
    let part = |kind: usize, j: usize| theta[n + (kind - 1) * l + j];
    let one = T::constant(1.0);
    let links = chain
        .links()
        .iter()
        .enumerate()
        .map(|(j, link)| {
            let (k, fy, r, u) = (part(2, j), part(3, j), part(4, j), part(5, j));
            let r = if r.value() > 1.0 { one } else { r };
            let u = if u.value() < 1.0 { one } else { u };
            link.with_parameters(&[k, fy, r, u * k])
        })
        .collect();
    ChainValues {
        masses: theta[..n].to_vec(),
        dampers: (0..l).map(|j| part(1, j)).collect(),
        links,
        front: None,
        path: None,
        rebound: None,
        path_gap: None,
        rebound_gap: None,
    }
}

/// Quantities of the SI parameters θ computed on dual numbers (residual
/// rows, plastic sets); None when they cannot be computed.
pub type OnDuals<'a> = dyn Fn(&[Tangent]) -> Option<Vec<Tangent>> + Sync + 'a;

/// The quantities `of` at the SI parameters `theta` and their exact
/// derivatives in the free log parameters (`free`: their indices in θ,
/// each seeded with `∂θ/∂p = θ`), [`WIDTH`] at a time, the blocks in
/// parallel: their values and the matrix (rows: quantities, columns: the
/// free parameters); None when a run fails or a value or derivative is
/// not finite.
pub fn tangents(theta: &[f64], free: &[usize], of: &OnDuals) -> Option<(Vec<f64>, DMatrix<f64>)> {
    let blocks: Vec<&[usize]> = match free.is_empty() {
        true => vec![&[]],
        false => free.chunks(WIDTH).collect(),
    };
    let runs: Vec<Option<Vec<Tangent>>> = blocks
        .par_iter()
        .map(|block| of(&seeded(theta, block)))
        .collect();
    let mut values: Option<Vec<f64>> = None;
    let mut matrix = DMatrix::zeros(0, free.len());
    for (b, run) in runs.into_iter().enumerate() {
        let run = run?;
        if values.is_none() {
            values = Some(run.iter().map(|q| q.real).collect());
            matrix = DMatrix::zeros(run.len(), free.len());
        }
        if run.len() != matrix.nrows() {
            return None;
        }
        for (row, q) in run.iter().enumerate() {
            for (d, value) in q.tangent.iter().take(blocks[b].len()).enumerate() {
                matrix[(row, b * WIDTH + d)] = *value;
            }
        }
    }
    let values = values?;
    let finite = values.iter().chain(matrix.iter()).all(|v| v.is_finite());
    finite.then_some((values, matrix))
}

/// θ on dual numbers, the parameters `block` (indices in θ, at most
/// [`WIDTH`]) seeded in order with `∂θ/∂p = θ`, the others constant.
fn seeded(theta: &[f64], block: &[usize]) -> Vec<Tangent> {
    theta
        .iter()
        .enumerate()
        .map(|(i, &v)| match block.iter().position(|&b| b == i) {
            Some(d) => Dual::seeded(v, d, v),
            None => Dual::constant(v),
        })
        .collect()
}

/// The Jacobian of the residuals `of` gives (on dual numbers, from the SI
/// parameters) in the free log parameters at `theta`, into `jacobian`
/// ([`tangents`]); false when they cannot be computed or their count is
/// not the Jacobian's rows.
pub fn fill(theta: &[f64], free: &[usize], of: &OnDuals, jacobian: &mut DMatrix<f64>) -> bool {
    match tangents(theta, free, of) {
        Some((_, matrix)) if matrix.shape() == jacobian.shape() => {
            jacobian.copy_from(&matrix);
            true
        }
        _ => false,
    }
}

/// Sample `k` of the series `y` (displacements, m, sampled every `step`
/// s) in `domain`, on any [`Real`]: the same differences as
/// [`Domain::strided`], so on `f64` its value bit for bit.
pub fn in_domain<T: Real>(domain: Domain, y: &[T], k: usize, step: f64) -> T {
    match domain {
        Domain::Displacement => y[k],
        Domain::Velocity => (y[k] - y[k - 1]) / step,
        Domain::Acceleration => (y[k] - y[k - 1] * 2.0 + y[k - 2]) / (step * step),
    }
}

/// The Jacobian in the free log parameters (`free`: their indices in θ)
/// of the residuals of every case, at the SI parameters `theta`, into
/// `jacobian`; false when the chain cannot run.
pub fn exact(
    cases: &[LoadCase],
    layout: Layout,
    theta: &[f64],
    free: &[usize],
    jacobian: &mut DMatrix<f64>,
) -> bool {
    let Ok(chain) = layout.chain(theta) else {
        return false;
    };
    let rows = |theta: &[Tangent]| rows(cases, layout, &chain, theta);
    fill(theta, free, &rows, jacobian)
}

/// Every case's residuals on dual numbers (one run per case), from θ.
fn rows(
    cases: &[LoadCase],
    layout: Layout,
    chain: &Chain,
    theta: &[Tangent],
) -> Option<Vec<Tangent>> {
    let values = values(layout, chain, theta);
    let mut rows = Vec::with_capacity(cases.iter().map(LoadCase::residual_len).sum());
    for case in cases {
        let motion = chain.motion(&drive(case), &values).ok()?;
        let y = motion.displacement.get(case.output_dof.checked_sub(1)?)?;
        let (domain, weight) = (case.compare.domain, case.compare.weight());
        for k in case.first_compared()..=case.window.1 {
            let measured = domain.at(&case.measured, k, case.step);
            rows.push((in_domain(domain, y, k, case.step) - measured) * weight);
        }
    }
    Some(rows)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::super::LinkObjective;
    use crate::case::{Comparison, LoadCase};
    use crate::links::Layout;
    use bumpsim_estimate::domain::Domain;
    use bumpsim_estimate::lm::LeastSquares;
    use nalgebra::DMatrix;

    /// The worst difference between `exact`'s columns and the central
    /// differences (step `h` in each log parameter) of `of`, each over its
    /// column's largest central value; panics on a column of zeros.
    pub(crate) fn worst_column(
        exact: &DMatrix<f64>,
        p: &[f64],
        h: f64,
        of: &dyn Fn(&[f64]) -> Vec<f64>,
    ) -> f64 {
        (0..p.len())
            .map(|column| {
                let at = |by: f64| {
                    let mut q = p.to_vec();
                    q[column] += by;
                    of(&q)
                };
                let (up, down) = (at(h), at(-h));
                let central: Vec<f64> = up
                    .iter()
                    .zip(&down)
                    .map(|(a, b)| (a - b) / (2.0 * h))
                    .collect();
                let scale = central.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
                assert!(scale > 0.0, "column {column} is zero");
                let worst = (0..central.len())
                    .map(|k| (exact[(k, column)] - central[k]).abs())
                    .fold(0.0_f64, f64::max);
                worst / scale
            })
            .fold(0.0_f64, f64::max)
    }

    /// A 2-mass chain's case driven by a half-sine of 60 kN on m1 (the
    /// link yields at 30 kN and unloads), measured on mass `output` in
    /// `domain`, simulated at `theta`.
    fn case(theta: &[f64], output: usize, domain: Domain, noise: Option<f64>) -> LoadCase {
        let force: Vec<f64> = (0..600)
            .map(|k| match k < 300 {
                true => 6e4 * (std::f64::consts::PI * k as f64 / 300.0).sin(),
                false => 0.0,
            })
            .collect();
        let mut case = LoadCase {
            name: format!("{domain}-{output}"),
            start: 0.0,
            step: 1e-4,
            force,
            measured: vec![],
            output_dof: output,
            initial_velocity: 0.0,
            window: (0, 599),
            compare: Comparison::new(domain, noise),
        };
        let chain = Layout { dof: 2 }.chain(theta).unwrap();
        case.measured = super::super::simulate(&case, &chain).unwrap();
        case
    }

    /// The links objective's exact Jacobian (two cases, displacement of m2
    /// and the acceleration of m1 weighted by a noise) against central
    /// differences of its own residuals in every log parameter (step
    /// 1e-4): within 1e-6 of each column's largest entry (measured: 7e-8
    /// at worst; the forward differences of step 1e-6 it replaces were off
    /// by up to 1.7e-5), away from the truth so the residuals do not
    /// vanish.
    #[test]
    fn the_exact_jacobian_matches_central_differences_of_the_residuals() {
        let truth = [60.0, 900.0, 800.0, 1.5e6, 3e4, 0.15, 4.0];
        let cases = [
            case(&truth, 2, Domain::Displacement, None),
            case(&truth, 1, Domain::Acceleration, Some(50.0)),
        ];
        let layout = Layout { dof: 2 };
        let objective = LinkObjective::new(&cases, layout, &[None; 7]);
        let p: Vec<f64> = truth
            .iter()
            .zip([1.1, 0.95, 1.3, 0.9, 1.08, 1.2, 0.85])
            .map(|(t, f)| (t * f).ln())
            .collect();
        let rows = objective.residual_count();
        let (mut r, mut j) = (vec![0.0; rows], DMatrix::zeros(rows, 7));
        assert!(objective.evaluate(&p, &mut r, Some(&mut j)));
        let residuals = |q: &[f64]| {
            let mut r = vec![0.0; rows];
            assert!(objective.evaluate(q, &mut r, None));
            r
        };
        let worst = worst_column(&j, &p, 1e-4, &residuals);
        assert!(worst <= 1e-6, "worst {worst:.3e} of a column");
    }
}
