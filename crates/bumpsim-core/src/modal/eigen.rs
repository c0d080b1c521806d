//! The eigen-decomposition `A = V Λ U` (`U = V⁻¹`) of the chain's relative
//! system, for [`super::ModalForm`].
//!
//! The eigenvalues are nalgebra's (real Schur form of the balanced matrix);
//! the eigenvectors come from two steps of inverse iteration on the shifted
//! balanced matrix and `U` from an LU solve. Why by hand: nalgebra gives no
//! eigenvectors of a non-symmetric matrix, and the small complex LU here
//! must not refuse the singular matrix inverse iteration factors on purpose.
//! Every step is checked to [`ACCURACY`]; a close pair of eigenvalues
//! ([`SEPARATION`]) is refused.

use super::{ACCURACY, C, ModalError, SEPARATION};
use crate::model::MsdModel;
use crate::state_space::relative_system;
use nalgebra::DMatrix;

/// `A = V Λ U` with the balancing undone. Eigenvalues ordered: complex
/// representatives (Im > 0, by |λ|), real ones (ascending), then the
/// complex partners (conjugates, in the representatives' order).
pub(super) struct Decomposition {
    pub links: usize,
    pub lambda: Vec<C>,
    /// How many complex representatives lead `lambda`.
    pub complex: usize,
    /// Right eigenvectors, column-major 2L × 2L.
    v: Vec<C>,
    /// `U = V⁻¹` (left eigenvectors as rows), column-major.
    u: Vec<C>,
    /// The distance of each eigenvalue to its nearest other, 1/s.
    pub gaps: Vec<f64>,
    /// Each eigenvalue's error bound, 1/s: the eigenpair's backward error
    /// (the residual `‖A v − λ v‖` of unit v in the balanced A, plus the
    /// rounding of computing it, `n ε ‖(|A| + |λ|) |v|‖`) times the
    /// eigenvalue's condition number `‖u‖` (`u v = 1`). Its eigenvector's
    /// relative error is about this over the gap.
    pub errors: Vec<f64>,
}

impl Decomposition {
    pub fn new(model: &MsdModel) -> Result<Decomposition, ModalError> {
        let links = model.dof() - 1;
        let size = 2 * links;
        if links == 0 {
            let (lambda, v, u) = (Vec::new(), Vec::new(), Vec::new());
            return Ok(Decomposition {
                links,
                lambda,
                complex: 0,
                v,
                u,
                gaps: Vec::new(),
                errors: Vec::new(),
            });
        }
        let mut a = relative_system(model);
        let scale = balance(&mut a);
        let norm = a.norm();
        let schur = nalgebra::linalg::Schur::try_new(a.clone(), f64::EPSILON, 10_000)
            .ok_or(ModalError::Eigenvalues { size })?;
        let (mut lambda, complex) = ordered(schur.complex_eigenvalues().as_slice())
            .ok_or(ModalError::Eigenvalues { size })?;
        separated(&lambda, norm)?;
        let representatives = size - complex;
        let mut v = vec![C::ZERO; size * size];
        for (i, &value) in lambda[..representatives].iter().enumerate() {
            let vector = eigenvector(&a, value, norm)?;
            v[i * size..(i + 1) * size].copy_from_slice(&vector);
            if i < complex {
                let partner = representatives + i;
                for (r, x) in vector.iter().enumerate() {
                    v[partner * size + r] = x.conj();
                }
            }
        }
        let mut u = inverse(&v, size)?;
        // the Schur eigenvalues of a stiff matrix are exact to ε ‖A‖ only,
        // much less than a slow eigenvalue's own size: the two-sided
        // Rayleigh quotient (U A V)_ii is exact to second order
        for i in 0..representatives {
            let refined = rayleigh(&a, &u, &v, i);
            lambda[i] = if i < complex {
                refined
            } else {
                C::from(refined.re)
            };
            if i < complex {
                lambda[representatives + i] = refined.conj();
            }
        }
        let gaps = separated(&lambda, norm)?;
        let errors = (0..size)
            .map(|i| {
                let column = if i < representatives {
                    i
                } else {
                    i - representatives
                };
                let condition = (0..size)
                    .map(|r| u[r * size + column].norm_sqr())
                    .sum::<f64>()
                    .sqrt();
                backward_error(&a, &v, column, lambda[column]) * condition
            })
            .collect();
        // undo the balancing: V = D V_b, U = U_b D⁻¹
        for (e, x) in v.iter_mut().enumerate() {
            *x *= scale[e % size];
        }
        for (e, x) in u.iter_mut().enumerate() {
            *x /= scale[e / size];
        }
        Ok(Decomposition {
            links,
            lambda,
            complex,
            v,
            u,
            gaps,
            errors,
        })
    }

    /// State dimension 2L.
    pub fn size(&self) -> usize {
        2 * self.links
    }

    /// Eigenvalues that are terms of the response: the complex
    /// representatives and the real ones.
    pub fn representatives(&self) -> usize {
        self.size() - self.complex
    }

    /// `V[r, j]`.
    pub fn v(&self, r: usize, j: usize) -> C {
        self.v[j * self.size() + r]
    }

    /// `U[i, r]`.
    pub fn u(&self, i: usize, r: usize) -> C {
        self.u[r * self.size() + i]
    }
}

/// `(U A V)_ii` of the balanced `a` and its eigenvector matrices
/// (column-major), the two-sided Rayleigh quotient of eigenvalue i.
fn rayleigh(a: &DMatrix<f64>, u: &[C], v: &[C], i: usize) -> C {
    let n = a.nrows();
    (0..n)
        .map(|r| {
            let av: C = (0..n).map(|c| v[i * n + c] * a[(r, c)]).sum();
            u[r * n + i] * av
        })
        .sum()
}

/// The backward error of eigenpair `(λ, v_i)` (column i of `v`, a unit
/// vector) of balanced `a`: the residual `‖a v − λ v‖` as computed, plus
/// what rounding may hide in it, `n ε ‖(|a| + |λ|) |v|‖` (componentwise:
/// a slow mode of a stiff chain barely touches the stiff entries, so this
/// is far below `ε ‖a‖`).
fn backward_error(a: &DMatrix<f64>, v: &[C], i: usize, lambda: C) -> f64 {
    let n = a.nrows();
    let x = &v[i * n..(i + 1) * n];
    let (mut residual, mut rounding) = (0.0, 0.0);
    for r in 0..n {
        let row: C = (0..n).map(|c| x[c] * a[(r, c)]).sum();
        residual += (row - lambda * x[r]).norm_sqr();
        let size: f64 = (0..n)
            .map(|c| a[(r, c)].abs() * magnitude(x[c]))
            .sum::<f64>()
            + magnitude(lambda) * magnitude(x[r]);
        rounding += size * size;
    }
    residual.sqrt() + n as f64 * f64::EPSILON * rounding.sqrt()
}

/// Orders eigenvalues as [`Decomposition`] keeps them; the count of complex
/// representatives. None when a value is not finite or the pairs do not
/// match.
fn ordered(values: &[C]) -> Option<(Vec<C>, usize)> {
    let finite = values.iter().all(|z| z.re.is_finite() && z.im.is_finite());
    let mut upper: Vec<C> = values.iter().copied().filter(|z| z.im > 0.0).collect();
    let mut real: Vec<C> = values.iter().copied().filter(|z| z.im == 0.0).collect();
    let lower = values.iter().filter(|z| z.im < 0.0).count();
    if !finite || lower != upper.len() {
        return None;
    }
    upper.sort_by(|p, q| p.norm_sqr().total_cmp(&q.norm_sqr()));
    real.sort_by(|p, q| p.re.total_cmp(&q.re));
    let complex = upper.len();
    let partners: Vec<C> = upper.iter().map(|z| z.conj()).collect();
    Some(([upper, real, partners].concat(), complex))
}

/// The distance of each eigenvalue to its nearest other, 1/s; refuses two
/// closer than [`SEPARATION`] relative to the larger, or than ten times
/// what the matrix (norm `norm`) resolves (the error estimates divide by
/// the gap; they judge the rest).
fn separated(lambda: &[C], norm: f64) -> Result<Vec<f64>, ModalError> {
    let resolved = 10.0 * f64::EPSILON * norm;
    let mut gaps = vec![f64::INFINITY; lambda.len()];
    for (i, &first) in lambda.iter().enumerate() {
        for (j, &second) in lambda.iter().enumerate().skip(i + 1) {
            let gap = magnitude(first - second);
            if gap < SEPARATION * magnitude(first).max(magnitude(second)) || gap < resolved {
                return Err(ModalError::Close { first, second });
            }
            gaps[i] = gaps[i].min(gap);
            gaps[j] = gaps[j].min(gap);
        }
    }
    Ok(gaps)
}

/// Balances `a` in place by powers of two (Parlett & Reinsch 1969, as
/// LAPACK's gebal and Numerical Recipes' balanc): `a ← D⁻¹ a D` with row
/// and column norms made comparable; returns D's diagonal. Exact: powers of
/// two change no digit.
fn balance(a: &mut DMatrix<f64>) -> Vec<f64> {
    let n = a.nrows();
    let mut scale = vec![1.0; n];
    for _ in 0..100 {
        let mut done = true;
        for i in 0..n {
            let column: f64 = (0..n).filter(|&j| j != i).map(|j| a[(j, i)].abs()).sum();
            let row: f64 = (0..n).filter(|&j| j != i).map(|j| a[(i, j)].abs()).sum();
            if column == 0.0 || row == 0.0 {
                continue;
            }
            let (mut c, mut f, sum) = (column, 1.0, column + row);
            while c < row / 2.0 {
                f *= 2.0;
                c *= 4.0;
            }
            while c > row * 2.0 {
                f /= 2.0;
                c /= 4.0;
            }
            if (c + row) / f < 0.95 * sum {
                done = false;
                scale[i] *= f;
                a.row_mut(i).scale_mut(1.0 / f);
                a.column_mut(i).scale_mut(f);
            }
        }
        if done {
            break;
        }
    }
    scale
}

/// The unit eigenvector of real `a` (norm `norm`) for eigenvalue `lambda`,
/// by two steps of inverse iteration; refused when it does not satisfy
/// `a v = λ v` to [`ACCURACY`].
fn eigenvector(a: &DMatrix<f64>, lambda: C, norm: f64) -> Result<Vec<C>, ModalError> {
    let n = a.nrows();
    let mut shifted: Vec<C> = (0..n * n)
        .map(|e| C::from(a[(e % n, e / n)]) - if e % n == e / n { lambda } else { C::ZERO })
        .collect();
    let pivots = factor(&mut shifted, n, f64::EPSILON * norm);
    // a start with a part along every eigenvector
    let mut x: Vec<C> = (0..n).map(|r| C::new(1.0 + 0.37 * r as f64, 0.1)).collect();
    for _ in 0..2 {
        solve(&shifted, &pivots, &mut x);
        let length = x.iter().map(|v| v.norm_sqr()).sum::<f64>().sqrt();
        x.iter_mut().for_each(|v| *v /= length);
    }
    let error = (0..n)
        .map(|r| ((0..n).map(|c| x[c] * a[(r, c)]).sum::<C>() - lambda * x[r]).norm_sqr())
        .sum::<f64>()
        .sqrt();
    match error <= ACCURACY * norm {
        true => Ok(x),
        false => Err(ModalError::Inaccurate {
            error: error / norm,
        }),
    }
}

/// `V⁻¹` (column-major n × n), refused when `V⁻¹ V` is not the identity to
/// [`ACCURACY`] (the eigenvectors are nearly dependent).
fn inverse(v: &[C], n: usize) -> Result<Vec<C>, ModalError> {
    let mut lu = v.to_vec();
    let norm = v.iter().map(|x| x.norm_sqr()).sum::<f64>().sqrt();
    let pivots = factor(&mut lu, n, f64::EPSILON * norm);
    let mut inverse = vec![C::ZERO; n * n];
    for (c, column) in inverse.chunks_exact_mut(n).enumerate() {
        column[c] = C::ONE;
        solve(&lu, &pivots, column);
    }
    let identity = |i: usize, j: usize| if i == j { C::ONE } else { C::ZERO };
    let error = (0..n * n)
        .map(|e| {
            let (i, j) = (e % n, e / n);
            let product: C = (0..n).map(|r| inverse[r * n + i] * v[j * n + r]).sum();
            magnitude(product - identity(i, j))
        })
        .fold(0.0, f64::max);
    match error <= ACCURACY {
        true => Ok(inverse),
        false => Err(ModalError::Inaccurate { error }),
    }
}

/// LU factorisation with partial pivoting in place (column-major n × n);
/// a pivot below `floor` is raised to it (the shifted matrix of inverse
/// iteration is singular on purpose). Returns the row swaps.
fn factor(a: &mut [C], n: usize, floor: f64) -> Vec<usize> {
    let mut pivots = Vec::with_capacity(n);
    for k in 0..n {
        let p = (k..n)
            .max_by(|&i, &j| a[k * n + i].norm_sqr().total_cmp(&a[k * n + j].norm_sqr()))
            .unwrap_or(k);
        pivots.push(p);
        for c in 0..n {
            a.swap(c * n + k, c * n + p);
        }
        if magnitude(a[k * n + k]) < floor {
            a[k * n + k] = C::from(floor.max(f64::MIN_POSITIVE));
        }
        let pivot = a[k * n + k];
        for i in k + 1..n {
            a[k * n + i] /= pivot;
        }
        for c in k + 1..n {
            let factor = a[c * n + k];
            for i in k + 1..n {
                let l = a[k * n + i];
                a[c * n + i] -= l * factor;
            }
        }
    }
    pivots
}

/// `|z|` as `√(re² + im²)`: libm's `hypot` (behind `Complex::norm`)
/// guards against overflow these magnitudes never reach, at several times
/// the cost.
fn magnitude(z: C) -> f64 {
    z.norm_sqr().sqrt()
}

/// Solves `A x = b` in place with [`factor`]'s result.
fn solve(lu: &[C], pivots: &[usize], x: &mut [C]) {
    let n = pivots.len();
    for (k, &p) in pivots.iter().enumerate() {
        x.swap(k, p);
    }
    for k in 0..n {
        let xk = x[k];
        for i in k + 1..n {
            x[i] -= lu[k * n + i] * xk;
        }
    }
    for k in (0..n).rev() {
        x[k] /= lu[k * n + k];
        let xk = x[k];
        for i in 0..k {
            x[i] -= lu[k * n + i] * xk;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_small_complex_system_is_solved_and_inverted() {
        let v = vec![
            C::new(2.0, 1.0),
            C::new(0.0, -1.0),
            C::new(1.0, 0.5),
            C::new(3.0, 0.0),
        ];
        let u = inverse(&v, 2).unwrap();
        // U V = I
        for i in 0..2 {
            for j in 0..2 {
                let p: C = (0..2).map(|r| u[r * 2 + i] * v[j * 2 + r]).sum();
                let expected = if i == j { 1.0 } else { 0.0 };
                assert!((p - expected).norm() < 1e-14, "{i} {j}: {p}");
            }
        }
        // dependent columns are refused
        let singular = vec![C::ONE, C::ONE, C::ONE, C::ONE];
        assert!(matches!(
            inverse(&singular, 2),
            Err(ModalError::Inaccurate { .. })
        ));
    }

    #[test]
    fn balancing_is_a_similarity_by_powers_of_two() {
        let mut a = DMatrix::from_row_slice(2, 2, &[1.0, 1e6, 1e-6, 2.0]);
        let original = a.clone();
        let d = balance(&mut a);
        for (i, j) in [(0, 1), (1, 0)] {
            assert_eq!(a[(i, j)], original[(i, j)] * d[j] / d[i]);
        }
        assert!(d.iter().all(|s| s.log2().fract() == 0.0));
        assert!(a[(0, 1)] < 1e3 && a[(1, 0)] > 1e-3, "{a}");
    }

    #[test]
    fn close_eigenvalues_are_refused() {
        let close = [C::new(-1.0, 10.0), C::new(-1.0, 10.00001)];
        assert!(matches!(
            separated(&close, 10.0),
            Err(ModalError::Close { .. })
        ));
        let apart = [C::new(-1.0, 10.0), C::new(-1.0, 11.0)];
        assert!(separated(&apart, 10.0).is_ok());
    }
}
