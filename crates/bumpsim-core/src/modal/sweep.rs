//! The runs of [`super::ModalForm`] on fixed-size arrays (the per-sample
//! kernels are in `modal::kernels`), and the estimate of how precisely a
//! run's results come out of their modal terms.

use super::kernels::{Lane, Moments, Projection, Recursion, Tiles};
use super::propagator::SlotConstants;
use super::{JACOBIAN_PRECISION, ModalError, ModalForm, OUTPUT_PRECISION};

/// One run's inputs: the sample interval (s), initial velocity (m/s) and
/// force (N).
pub(super) struct Run<'a> {
    pub step: f64,
    pub initial_velocity: f64,
    pub force: &'a [f64],
}

/// The estimated relative errors of a run's output and of its Jacobian
/// (relative to the largest column).
pub(super) struct Precision {
    output: f64,
    jacobian: f64,
}

impl Precision {
    /// Ok when both are within [`OUTPUT_PRECISION`] and
    /// [`JACOBIAN_PRECISION`].
    pub fn accept(&self) -> Result<(), ModalError> {
        let refuse = |what, error: f64, limit: f64| match error <= limit {
            true => Ok(()),
            false => Err(ModalError::Imprecise { what, error, limit }),
        };
        refuse("output", self.output, OUTPUT_PRECISION)?;
        refuse("Jacobian", self.jacobian, JACOBIAN_PRECISION)
    }
}

/// `terms / result`, 1 when both are zero.
fn ratio(terms: f64, result: f64) -> f64 {
    match (terms > 0.0, result > 0.0) {
        (_, true) => terms / result,
        (true, false) => f64::INFINITY,
        (false, false) => 1.0,
    }
}

/// Each basis signal's relative rounding (B = 4L + 1, slots innermost):
/// the recursion's own over N steps (a random walk, `ε √N`), and for a
/// slot's signals its eigenvectors' (backward error over gap) and its
/// eigenvalues' error δλ over the time it acts: a mode decaying at
/// `|Re λ|` accumulates at most `δλ t e^(Re λ t) ≤ δλ / |Re λ|`, so
/// `δλ min(duration, 1/|Re λ|)`.
fn basis_rounding<const L: usize, const B: usize>(form: &ModalForm, run: &Run) -> [f64; B] {
    let samples = run.force.len() as f64;
    let walk = f64::EPSILON * samples.sqrt();
    let duration = samples * run.step;
    std::array::from_fn(|u| match u {
        0 => walk,
        _ => {
            // component 0 or 2 (s0, w0) is a real slot's first eigenvalue's,
            // 1 or 3 its second's; a complex slot's both are its pair's
            let (l, component) = ((u - 1) % L, (u - 1) / L);
            let (vectors, values, decay) = form.rounding[l][component % 2];
            walk + vectors + values * duration.min(1.0 / decay.max(f64::MIN_POSITIVE))
        }
    })
}

/// The error of `Σ_u c_u b_u` relative to `result` (its norm) from the
/// terms' roundings `delta` and norms.
fn error<const B: usize>(
    delta: &[f64; B],
    c: impl Fn(usize) -> f64,
    norms: &[f64; B],
    result: f64,
) -> f64 {
    let terms: f64 = (0..B).map(|u| delta[u] * c(u).abs() * norms[u]).sum();
    ratio(terms, result)
}

/// Scratch and results of the normal-equation runs.
pub(super) struct Scratch<'a> {
    /// Basis rows of the window (B wide).
    pub basis: &'a mut [f64],
    /// Jacobian rows of the window with the residual in column P, in
    /// blocks of eight lanes (V of them: the row's length is `8 V`).
    pub rows: &'a mut [Lane],
    /// The measured window (the run's last samples), or with `given` its
    /// residuals, m.
    pub measured: &'a [f64],
    /// Whether `measured` holds the residuals: only the Jacobian is made.
    pub given: bool,
    /// `JᵀJ` (row-major) and `Jᵀr`, added to.
    pub jtj: &'a mut [f64],
    pub gradient: &'a mut [f64],
}

/// The output at every sample into `out` (L slots, B = 4L + 1 basis
/// signals) and how precise it is. Nothing allocated.
pub(super) fn simulate<const L: usize, const B: usize>(
    form: &ModalForm,
    run: &Run,
    out: &mut [f64],
) -> Precision {
    let constants = SlotConstants::<L>::new(&form.slots, run.step);
    let recursion = Recursion::<L, B, false> {
        constants: &constants,
        step: run.step,
        velocity: run.initial_velocity,
        force: run.force,
        first: 0,
        rows: &mut [],
        coefficients: &form.output,
        out,
    };
    let (power, square) = pulp::Arch::new().dispatch(recursion);
    let norms: [f64; B] = std::array::from_fn(|u| power[u].sqrt());
    let delta = basis_rounding::<L, B>(form, run);
    Precision {
        output: error(&delta, |u| form.output[u], &norms, square.sqrt()),
        jacobian: 0.0,
    }
}

/// The residuals of the measured window into `out` and its normal
/// equations (L slots, B = 4L + 1 basis signals, P = 3L + 1 parameters,
/// rows of P + 1 padded to `8 V`): the recursion writes the window's basis
/// rows, the projection turns each into its Jacobian row `Cᵀ b` and its
/// output, hence residual; then `[J r]ᵀ [J r]` is added to `scratch.jtj`
/// and `.gradient` when precise enough. Nothing allocated.
pub(super) fn normal<const L: usize, const B: usize, const P: usize, const V: usize>(
    form: &ModalForm,
    run: &Run,
    out: &mut [f64],
    scratch: Scratch,
) -> Precision {
    let t = run.step;
    let window = scratch.measured.len();
    let first = run.force.len() - window;
    let constants = SlotConstants::<L>::new(&form.slots, t);
    let basis = &mut scratch.basis[..window * B];
    pulp::Arch::new().dispatch(Recursion::<L, B, true> {
        constants: &constants,
        step: t,
        velocity: 0.0,
        force: run.force,
        first,
        rows: basis,
        coefficients: &[],
        out: &mut [],
    });
    // [C | output | 0...] by basis row: the Jacobian row and the output together
    let weights: [[Lane; V]; B] = std::array::from_fn(|u| {
        std::array::from_fn(|v| {
            std::array::from_fn(|lane| match (8 * v + lane).cmp(&P) {
                std::cmp::Ordering::Less => form.coefficients[u * P + 8 * v + lane],
                std::cmp::Ordering::Equal => form.output[u],
                std::cmp::Ordering::Greater => 0.0,
            })
        })
    });
    let rows = &mut scratch.rows[..window * V];
    let (power, square) = pulp::Arch::new().dispatch(Projection::<B, P, V> {
        basis,
        weights: &weights,
        measured: scratch.measured,
        given: scratch.given,
        time: (first as f64 * t, t, run.initial_velocity),
        rows,
        residuals: out,
    });
    // the rows of G used: P + 1 ≤ 3 (MAX_DOF − 1) + 2 = 29
    let mut gram = [[[0.0; 8]; V]; 32];
    pulp::Arch::new().dispatch(Tiles::<V> {
        rows,
        used: P + 1,
        g: &mut gram,
    });
    // the upper triangle by blocks is filled: read (p, q) from the row of
    // the smaller block
    let g = |p: usize, q: usize| match p / 8 <= q / 8 {
        true => gram[p][q / 8][q % 8],
        false => gram[q][p / 8][p % 8],
    };
    let weight = |u: usize, p: usize| weights[u][p / 8][p % 8];
    let norms: [f64; B] = std::array::from_fn(|u| power[u].sqrt());
    let delta = basis_rounding::<L, B>(form, run);
    // each column's terms against the largest column
    let largest = (0..P).map(|p| g(p, p)).fold(0.0, f64::max).sqrt();
    let widest = (0..P)
        .map(|p| error(&delta, |u| weight(u, p), &norms, largest))
        .fold(0.0, f64::max);
    let precision = Precision {
        output: match scratch.given {
            true => 0.0,
            false => error(&delta, |u| weight(u, P), &norms, square.sqrt()),
        },
        jacobian: widest,
    };
    if precision.accept().is_ok() {
        for p in 0..P {
            scratch.gradient[p] += g(p, P);
            for q in 0..P {
                scratch.jtj[p * P + q] += g(p, q);
            }
        }
    }
    precision
}

/// `Jᵀv` of the window (the run's last `v.len()` samples) added to
/// `product` (P): the recursion writes the window's basis rows into
/// `basis`, their moments `Bᵀv` are summed and `Cᵀ (Bᵀv)` added (J = B C).
/// No projection and no Gram matrix: about a simulation's cost. Nothing
/// allocated.
pub(super) fn transposed<const L: usize, const B: usize>(
    form: &ModalForm,
    run: &Run,
    v: &[f64],
    basis: &mut [f64],
    product: &mut [f64],
) {
    let window = v.len();
    let constants = SlotConstants::<L>::new(&form.slots, run.step);
    let basis = &mut basis[..window * B];
    pulp::Arch::new().dispatch(Recursion::<L, B, true> {
        constants: &constants,
        step: run.step,
        velocity: 0.0,
        force: run.force,
        first: run.force.len() - window,
        rows: basis,
        coefficients: &[],
        out: &mut [],
    });
    pulp::Arch::new().dispatch(Moments::<B> {
        basis,
        v,
        coefficients: &form.coefficients,
        product,
    });
}
