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
//! 1978), which gives `dΦ/dp` and `dΓ/dp` exactly. It is computed as the
//! Fréchet derivative `L(G T, dG T)` by Al-Mohy & Higham's algorithm
//! ([`Frechet`]), which shares the Padé work of `G T` among all parameters
//! instead of taking one 2n × 2n exponential per parameter.
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
        let frechet = Frechet::new(&m);
        for dm in derivatives(model, &generator) {
            let e = frechet.derivative(&(similar(&dm) * step));
            for c in 0..n {
                out.dphi.extend(back(&e, 0, c));
            }
            out.dgamma.extend(back(&e, 0, n));
        }
    }
    out
}

/// Coefficients of the [13/13] Padé approximant of the exponential.
const PADE13: [f64; 14] = [
    64764752532480000.0,
    32382376266240000.0,
    7771770303897600.0,
    1187353796428800.0,
    129060195264000.0,
    10559470521600.0,
    670442572800.0,
    33522128640.0,
    1323241920.0,
    40840800.0,
    960960.0,
    16380.0,
    182.0,
    1.0,
];

/// Largest 1-norm for which the [13/13] Padé approximant gives the
/// exponential and its Fréchet derivative to double precision (Al-Mohy &
/// Higham 2009, table 6.1: ℓ13).
const ELL13: f64 = 4.74;

/// The Fréchet derivatives `L(M, E)` of `e^M` along several directions E:
/// the upper-right block of `exp([[M, E], [0, M]])` (Van Loan 1978), by
/// Al-Mohy & Higham 2009, "Computing the Fréchet derivative of the matrix
/// exponential", algorithm 6.4, always with the [13/13] Padé approximant
/// and scaling and squaring. Everything that depends on M alone (its
/// powers, the Padé numerator and denominator, the LU factors, the squares
/// of e^(M/2^s)) is computed once; a direction then costs about 13 + 2s
/// products of the size of M, where the 2n × 2n block exponential cost the
/// work of eight exponentials of M. Written here because nalgebra has no
/// Fréchet derivative; scipy's `expm_frechet` is the same algorithm.
struct Frechet {
    a: DMatrix<f64>,
    a2: DMatrix<f64>,
    a4: DMatrix<f64>,
    a6: DMatrix<f64>,
    w1: DMatrix<f64>,
    z1: DMatrix<f64>,
    w: DMatrix<f64>,
    denominator: nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>,
    /// `R_0`, the approximant of `e^(M/2^s)`.
    r: DMatrix<f64>,
    /// `R_k = R_0^(2^k)` for k = 0 .. s − 1, one per squaring.
    squares: Vec<DMatrix<f64>>,
    /// `2^−s`.
    scale: f64,
}

impl Frechet {
    fn new(m: &DMatrix<f64>) -> Frechet {
        let norm = m
            .column_iter()
            .map(|c| c.iter().map(|v| v.abs()).sum::<f64>())
            .fold(0.0, f64::max);
        let s = if norm > ELL13 {
            (norm / ELL13).log2().ceil() as i32
        } else {
            0
        };
        let scale = 2f64.powi(-s);
        let b = PADE13;
        let identity = DMatrix::<f64>::identity(m.nrows(), m.ncols());
        let a = m * scale;
        let a2 = &a * &a;
        let a4 = &a2 * &a2;
        let a6 = &a2 * &a4;
        let w1 = &a6 * b[13] + &a4 * b[11] + &a2 * b[9];
        let w2 = &a6 * b[7] + &a4 * b[5] + &a2 * b[3] + &identity * b[1];
        let z1 = &a6 * b[12] + &a4 * b[10] + &a2 * b[8];
        let z2 = &a6 * b[6] + &a4 * b[4] + &a2 * b[2] + &identity * b[0];
        let w = &a6 * &w1 + w2;
        let u = &a * &w;
        let v = &a6 * &z1 + z2;
        let denominator = (&v - &u).lu();
        // after scaling, the denominator of the approximant is far from
        // singular (its eigenvalues lie near 1 for ‖A‖₁ ≤ ℓ13)
        let r = denominator.solve(&(u + v)).unwrap_or(identity);
        let mut squares: Vec<DMatrix<f64>> = Vec::with_capacity(s as usize);
        for k in 0..s as usize {
            let next = match k {
                0 => r.clone(),
                _ => &squares[k - 1] * &squares[k - 1],
            };
            squares.push(next);
        }
        Frechet {
            a,
            a2,
            a4,
            a6,
            w1,
            z1,
            w,
            denominator,
            r,
            squares,
            scale,
        }
    }

    /// `L(M, E)`, the derivative of `e^M` along `e`.
    fn derivative(&self, e: &DMatrix<f64>) -> DMatrix<f64> {
        let b = PADE13;
        let e = e * self.scale;
        let (a, a2, a4, a6) = (&self.a, &self.a2, &self.a4, &self.a6);
        let m2 = a * &e + &e * a;
        let m4 = a2 * &m2 + &m2 * a2;
        let m6 = a4 * &m2 + &m4 * a2;
        let lw1 = &m6 * b[13] + &m4 * b[11] + &m2 * b[9];
        let lw2 = &m6 * b[7] + &m4 * b[5] + &m2 * b[3];
        let lz1 = &m6 * b[12] + &m4 * b[10] + &m2 * b[8];
        let lz2 = &m6 * b[6] + &m4 * b[4] + &m2 * b[2];
        let lw = a6 * lw1 + &m6 * &self.w1 + lw2;
        let lu = a * lw + &e * &self.w;
        let lv = a6 * lz1 + &m6 * &self.z1 + lz2;
        let rhs = &lu + &lv + (&lu - &lv) * &self.r;
        let mut l = self.denominator.solve(&rhs).unwrap_or(rhs);
        for r in &self.squares {
            l = r * &l + &l * r;
        }
        l
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Van Loan block: `exp([[M, E], [0, M]])`'s upper-right block.
    fn block(m: &DMatrix<f64>, e: &DMatrix<f64>) -> DMatrix<f64> {
        let n = m.nrows();
        let mut big = DMatrix::zeros(2 * n, 2 * n);
        big.view_mut((0, 0), (n, n)).copy_from(m);
        big.view_mut((n, n), (n, n)).copy_from(m);
        big.view_mut((0, n), (n, n)).copy_from(e);
        big.exp().view((0, n), (n, n)).into_owned()
    }

    /// The shared-work derivatives equal the Van Loan block's for a small,
    /// a moderate and a stiff generator (no scaling, a few squarings, many):
    /// to 1e-12 of their size, 1e-10 after many squarings, whose rounding
    /// both methods carry (5e-12 seen).
    #[test]
    fn frechet_derivatives_equal_the_van_loan_block() {
        let car = MsdModel::new(vec![40.0, 300.0, 900.0], vec![3e3, 1e4], vec![8e5, 3e5]).unwrap();
        let ss = StateSpace::from_model(&car);
        let generator = hold_generator(&ss, Hold::Zero, 1e-4);
        for step in [1e-5, 1e-3, 0.05] {
            let m = &generator * step;
            let frechet = Frechet::new(&m);
            for dm in derivatives(&car, &generator) {
                let e = dm * step;
                let (fast, reference) = (frechet.derivative(&e), block(&m, &e));
                let size = reference.amax().max(f64::MIN_POSITIVE);
                let worst = (&fast - &reference).amax();
                let tolerance = if step > 1e-3 { 1e-10 } else { 1e-12 };
                assert!(worst <= tolerance * size, "step {step}: {worst} of {size}");
            }
        }
    }
}
