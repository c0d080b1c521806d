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

use super::frame;
use crate::links::Layout;
use crate::case::LoadCase;
use bumpsim_core::chain::{Chain, ChainValues, Drive};
use bumpsim_core::dual::{Dual, Real};
use nalgebra::DMatrix;
use rayon::prelude::*;

/// Log parameters differentiated in one run.
pub const WIDTH: usize = 8;

type Tangent = Dual<WIDTH>;

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
    let blocks: Vec<&[usize]> = free.chunks(WIDTH).collect();
    let columns: Vec<Option<Vec<[f64; WIDTH]>>> = blocks
        .par_iter()
        .map(|block| block_rows(cases, layout, &chain, theta, block))
        .collect();
    for (b, rows) in columns.into_iter().enumerate() {
        let Some(rows) = rows else {
            return false;
        };
        for (row, tangent) in rows.iter().enumerate() {
            for (d, value) in tangent.iter().take(blocks[b].len()).enumerate() {
                jacobian[(row, b * WIDTH + d)] = *value;
            }
        }
    }
    true
}

/// Every residual's derivatives along the parameters `block` (at most
/// [`WIDTH`], indices in θ), one run per case; None when a run fails or a
/// derivative is not finite.
fn block_rows(
    cases: &[LoadCase],
    layout: Layout,
    chain: &Chain,
    theta: &[f64],
    block: &[usize],
) -> Option<Vec<[f64; WIDTH]>> {
    let seeded: Vec<Tangent> = theta
        .iter()
        .enumerate()
        .map(|(i, &v)| match block.iter().position(|&b| b == i) {
            Some(d) => Dual::seeded(v, d, v),
            None => Dual::constant(v),
        })
        .collect();
    let values = values(layout, chain, &seeded);
    let mut rows = Vec::with_capacity(cases.iter().map(LoadCase::residual_len).sum());
    for case in cases {
        let drive = Drive::Force {
            force: &case.force,
            step: case.step,
            initial_velocity: case.initial_velocity,
            frame: frame(case),
        };
        let motion = chain.motion(&drive, &values).ok()?;
        let y = motion.displacement.get(case.output_dof.checked_sub(1)?)?;
        let (domain, weight) = (case.compare.domain, case.compare.weight());
        for k in case.first_compared()..=case.window.1 {
            let mut row = [0.0; WIDTH];
            for (d, value) in row.iter_mut().enumerate() {
                *value = weight * domain.strided(|i| y[i].tangent[d], k, case.step);
            }
            rows.push(row);
        }
    }
    rows.iter().flatten().all(|v| v.is_finite()).then_some(rows)
}
