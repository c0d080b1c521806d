//! The one place that computes the exact hold discretisation Φ, Γ (and, on
//! request, their exact parameter sensitivities) of the chain model.
//!
//! With the hold-augmented generator `G` of [`crate::discrete`]
//! (`[[A, B], [0, 0]]` for zoh, `[[A, B, 0], [0, 0, 1/T], [0, 0, 0]]` for foh),
//! `e^(G T)` has first block row `[Φ, Γa, (Γb)]` (Van Loan 1978).
//!
//! **Balancing.** A stiff chain makes `G` badly scaled (positions in m,
//! velocities in m/s, force in N). The exponential is taken of the similar
//! matrix `D⁻¹ G D` with the diagonal `D`: velocities scaled by
//! `w = sqrt(max K_ii / M_ii)`, the input(s) by `w² m1`; then
//! `e^(G T) = D e^(D⁻¹ G D T) D⁻¹` without the cancellation of a non-normal
//! matrix.
//!
//! **Sensitivities (zoh).** Parameters are logarithmic, `p = ln θ`, so
//! `∂/∂p = θ ∂/∂θ`: for a mass `dG/dp_i = −(row N+i of G)`; for a damper or
//! spring between masses j and j+1, `dA = −M⁻¹ (θ e eᵀ)` in the velocity or
//! position columns, `e = e_j − e_{j+1}`. The derivative of `e^(G T)` along
//! `dG` is the upper-right block of `exp([[G, dG], [0, G]] T)` (Van Loan
//! 1978), which gives `dΦ/dp` and `dΓ/dp` exactly. The direction is scaled
//! to the size of `G` first (Higham 2008, sec. 10.6): the block exponential
//! is linear in it and its accuracy is relative to the norm of the block.
//! Only the *propagated* parameters get one (m2..mn, then k1..k(n−1)): the
//! sensitivities of m1 and of the dampers follow from the others by exact
//! identities ([`crate::sensitivity`]).

use crate::model::MsdModel;
use crate::state_space::StateSpace;
use nalgebra::DMatrix;

/// How the force is held between samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Hold {
    /// Constant over the step (zoh; taylor1's energies use it too).
    Zero,
    /// Linear between samples (foh).
    First,
}

/// The hold-augmented generator matrix `G` (see [`crate::discrete`]).
pub(crate) fn hold_generator(ss: &StateSpace, hold: Hold, step: f64) -> DMatrix<f64> {
    let n = ss.order();
    let extra = if hold == Hold::First { 2 } else { 1 };
    let mut m = DMatrix::zeros(n + extra, n + extra);
    m.view_mut((0, 0), (n, n)).copy_from(ss.a());
    m.view_mut((0, n), (n, 1)).copy_from(ss.b());
    if hold == Hold::First {
        m[(n, n + 1)] = 1.0 / step;
    }
    m
}

/// Φ, Γ0, Γ1 and the zoh sensitivities, all column-major.
pub(crate) struct Exponential {
    /// Φ, N × N, column-major.
    pub phi: Vec<f64>,
    /// Γ0, the weight of f[k].
    pub gamma0: Vec<f64>,
    /// Γ1, the weight of f[k+1] (zero for zoh).
    pub gamma1: Vec<f64>,
    /// dΦ/dp_i of the propagated parameters (m2..mn, k1..k(n−1)) stacked,
    /// 2(n−1) × N × N, column-major each (empty unless asked).
    pub dphi: Vec<f64>,
    /// dΓ0/dp_i of the same parameters stacked, 2(n−1) × N.
    pub dgamma: Vec<f64>,
}

/// The diagonal of the balancing similarity `D` (see the module overview).
fn balance(model: &MsdModel, generator: &DMatrix<f64>) -> Vec<f64> {
    let dof = model.dof();
    let w = (0..dof)
        .map(|i| generator[(dof + i, i)].abs())
        .fold(0.0_f64, f64::max)
        .sqrt()
        .max(1.0);
    let mut d = vec![1.0; generator.nrows()];
    d[dof..2 * dof].iter_mut().for_each(|v| *v = w);
    d[2 * dof..]
        .iter_mut()
        .for_each(|v| *v = w * w * model.masses()[0]);
    d
}

/// `dG/dp` for the propagated log parameters: m2..mn, then k1..k(n−1)
/// (m1 and the dampers follow by identities, [`crate::sensitivity`]).
fn derivatives(model: &MsdModel, generator: &DMatrix<f64>) -> Vec<DMatrix<f64>> {
    let (dof, size) = (model.dof(), generator.nrows());
    let mut out = Vec::with_capacity(2 * dof - 2);
    for i in 1..dof {
        let mut d = DMatrix::zeros(size, size);
        let row = -generator.row(dof + i);
        d.row_mut(dof + i).copy_from(&row);
        out.push(d);
    }
    for (j, &theta) in model.springs().iter().enumerate() {
        let mut d = DMatrix::zeros(size, size);
        for (a, sa) in [(j, 1.0), (j + 1, -1.0)] {
            for (b, sb) in [(j, 1.0), (j + 1, -1.0)] {
                d[(dof + a, b)] = -sa * sb * theta / model.masses()[a];
            }
        }
        out.push(d);
    }
    out
}

/// The exact hold discretisation of `model` at step `step` (s), with the
/// zoh sensitivities when `sensitivities` is set (ignored for foh). The only
/// function in the workspace that computes Φ and Γ of an exact hold.
pub(crate) fn hold_exponential(
    model: &MsdModel,
    hold: Hold,
    step: f64,
    sensitivities: bool,
) -> Exponential {
    let ss = StateSpace::from_model(model);
    let n = ss.order();
    let generator = hold_generator(&ss, hold, step);
    let d = balance(model, &generator);
    let similar =
        |x: &DMatrix<f64>| DMatrix::from_fn(x.nrows(), x.ncols(), |r, c| x[(r, c)] * d[c] / d[r]);
    // entry (r, c) of D E D⁻¹ from entry (r, c0 + c) of E
    let back = |e: &DMatrix<f64>, c0: usize, c: usize| -> Vec<f64> {
        (0..n).map(|r| e[(r, c0 + c)] * d[r] / d[c]).collect()
    };
    let m = similar(&generator) * step;
    let size = m.nrows();
    let e = m.clone().exp();
    let phi = (0..n).flat_map(|c| back(&e, 0, c)).collect();
    let gamma_a = back(&e, 0, n);
    let (gamma0, gamma1) = match hold {
        Hold::First => {
            let gamma_b = back(&e, 0, n + 1);
            (
                gamma_a.iter().zip(&gamma_b).map(|(a, b)| a - b).collect(),
                gamma_b,
            )
        }
        Hold::Zero => (gamma_a, vec![0.0; n]),
    };
    let mut out = Exponential {
        phi,
        gamma0,
        gamma1,
        dphi: Vec::new(),
        dgamma: Vec::new(),
    };
    if sensitivities && hold == Hold::Zero {
        for dm in derivatives(model, &generator) {
            let mut block = DMatrix::zeros(2 * size, 2 * size);
            block.view_mut((0, 0), (size, size)).copy_from(&m);
            block.view_mut((size, size), (size, size)).copy_from(&m);
            let direction = similar(&dm) * step;
            let scale = m.amax() / direction.amax().max(f64::MIN_POSITIVE);
            block
                .view_mut((0, size), (size, size))
                .copy_from(&(direction * scale));
            let e = block.exp();
            for c in 0..n {
                out.dphi.extend(back(&e, size, c).iter().map(|v| v / scale));
            }
            out.dgamma
                .extend(back(&e, size, n).iter().map(|v| v / scale));
        }
    }
    out
}
