//! The per-sample kernels of [`super::ModalForm`], each compiled for the
//! widest vector unit found at run time (pulp's dispatch: AVX-512, AVX2 or
//! the x86-64 baseline): the modal recursion, the projection of the basis
//! rows on the Jacobian's coefficients, and the Gram matrix of the rows.
//!
//! Products are fused (`mul_add`, correctly rounded: the vector units'
//! FMA and the baseline's libm `fma` give the same bits), so every machine
//! computes the same numbers. The recursion is a chain of dependent steps;
//! with FMA each step of a slot costs two fused operations of latency.

use super::propagator::SlotConstants;

/// The recursion of the module over `force` (N): with `BASIS`, the basis
/// row `[ρ | s0 | s1 | w0 | w1]` (B = 4L + 1, slots innermost) of every
/// sample from `first` on into `rows`; without it, only ρ and s, and
/// `out[k]` the output `coefficients · b + v0 t` at every sample, with
/// `Σ b_u²` and `Σ (coefficients · b)²` returned for the cancellation
/// estimate. Each step is the
/// same operation on every slot (vector lanes, no shuffles in the chain).
pub(super) struct Recursion<'a, const L: usize, const B: usize, const BASIS: bool> {
    pub constants: &'a SlotConstants<L>,
    pub step: f64,
    /// The initial velocity v0, m/s.
    pub velocity: f64,
    pub force: &'a [f64],
    pub first: usize,
    pub rows: &'a mut [f64],
    pub coefficients: &'a [f64],
    pub out: &'a mut [f64],
}

impl<const L: usize, const B: usize, const BASIS: bool> pulp::WithSimd
    for Recursion<'_, L, B, BASIS>
{
    type Output = ([f64; B], f64);

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) -> ([f64; B], f64) {
        let t = self.step;
        let half = 0.5 * t * t;
        let SlotConstants { p, q, h } = self.constants;
        // w' = P (w + T s) + h f = P w + (T P) s + h f: the chain through w
        // is two fused steps, the s part is known a step ahead
        let tp: [[f64; L]; 4] = p.map(|row| row.map(|v| t * v));
        let (mut s0, mut s1, mut w0, mut w1) = ([0.0; L], [0.0; L], [0.0; L], [0.0; L]);
        let (mut rho, mut rate) = (0.0, 0.0);
        let (mut power, mut square) = ([0.0; B], 0.0);
        let c: [f64; B] = std::array::from_fn(|u| self.coefficients.get(u).copied().unwrap_or(0.0));
        for (k, &f) in self.force.iter().enumerate() {
            if BASIS && k >= self.first {
                let row = &mut self.rows[(k - self.first) * B..(k - self.first + 1) * B];
                row[0] = rho;
                row[1..1 + L].copy_from_slice(&s0);
                row[1 + L..1 + 2 * L].copy_from_slice(&s1);
                row[1 + 2 * L..1 + 3 * L].copy_from_slice(&w0);
                row[1 + 3 * L..1 + 4 * L].copy_from_slice(&w1);
            }
            if !BASIS {
                let mut value = c[0] * rho;
                power[0] = rho.mul_add(rho, power[0]);
                for l in 0..L {
                    value = c[1 + l].mul_add(s0[l], value);
                    value = c[1 + L + l].mul_add(s1[l], value);
                    power[1 + l] = s0[l].mul_add(s0[l], power[1 + l]);
                    power[1 + L + l] = s1[l].mul_add(s1[l], power[1 + L + l]);
                }
                square = value.mul_add(value, square);
                self.out[k] = self.velocity.mul_add(k as f64 * t, value);
            }
            rho = t.mul_add(rate, half.mul_add(f, rho));
            rate = t.mul_add(f, rate);
            if BASIS {
                for l in 0..L {
                    let known0 = tp[0][l].mul_add(s0[l], tp[1][l].mul_add(s1[l], h[0][l] * f));
                    let known1 = tp[2][l].mul_add(s0[l], tp[3][l].mul_add(s1[l], h[1][l] * f));
                    let (a, b) = (w0[l], w1[l]);
                    w0[l] = p[0][l].mul_add(a, p[1][l].mul_add(b, known0));
                    w1[l] = p[2][l].mul_add(a, p[3][l].mul_add(b, known1));
                }
            }
            for l in 0..L {
                let (a, b) = (s0[l], s1[l]);
                s0[l] = p[0][l].mul_add(a, p[1][l].mul_add(b, q[0][l] * f));
                s1[l] = p[2][l].mul_add(a, p[3][l].mul_add(b, q[1][l] * f));
            }
        }
        (power, square)
    }
}

/// Eight lanes: one AVX-512 register, two AVX2 ones.
pub(super) type Lane = [f64; 8];

/// The window's basis rows (B wide) projected on `weights` = `[C | output
/// | 0...]` (P + 1 columns padded to `8 V`, in blocks of eight lanes):
/// each sample's Jacobian row and, in column P, the residual
/// `output + v0 t − measured` (into `residuals` too) or, when `given`, the
/// residual `measured` holds, into `rows`; returns `Σ b_u²` and
/// `Σ output²`. Four samples at a time, so that four independent chains
/// of products fill the vector unit.
pub(super) struct Projection<'a, const B: usize, const P: usize, const V: usize> {
    pub basis: &'a [f64],
    pub weights: &'a [[Lane; V]; B],
    pub measured: &'a [f64],
    /// Whether `measured` holds the residuals themselves.
    pub given: bool,
    /// The window's first time, the step (s) and the initial velocity (m/s).
    pub time: (f64, f64, f64),
    /// V blocks a row.
    pub rows: &'a mut [Lane],
    pub residuals: &'a mut [f64],
}

impl<const B: usize, const P: usize, const V: usize> Projection<'_, B, P, V> {
    /// Writes sample k's row and residual from its projection `j`; returns
    /// the output (`j`'s column P before the residual replaces it).
    #[inline(always)]
    fn finish(&mut self, k: usize, mut j: [Lane; V]) -> f64 {
        let (start, step, v0) = self.time;
        let value = j[P / 8][P % 8];
        let e = match self.given {
            true => self.measured[k],
            false => v0.mul_add(start + k as f64 * step, value) - self.measured[k],
        };
        j[P / 8][P % 8] = e;
        if let Some(out) = self.residuals.get_mut(k) {
            *out = e;
        }
        self.rows[k * V..(k + 1) * V].copy_from_slice(&j);
        value
    }

    /// Adds `b` times the weights of basis signal u to `j`.
    #[inline(always)]
    fn add(j: &mut [Lane; V], b: f64, weights: &[Lane; V]) {
        for (block, w) in j.iter_mut().zip(weights) {
            for lane in 0..8 {
                block[lane] = b.mul_add(w[lane], block[lane]);
            }
        }
    }
}

impl<const B: usize, const P: usize, const V: usize> pulp::WithSimd for Projection<'_, B, P, V> {
    type Output = ([f64; B], f64);

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(mut self, simd: S) -> ([f64; B], f64) {
        let n = self.measured.len();
        let (mut power, mut square) = ([0.0; B], 0.0);
        let basis = self.basis;
        let mut k = 0;
        while k + 4 <= n {
            let Some(group) = basis.get(k * B..(k + 4) * B) else {
                break;
            };
            let mut j = [[[0.0; 8]; V]; 4];
            for u in 0..B {
                let b: [S::f64s; 4] = std::array::from_fn(|i| simd.splat_f64s(group[i * B + u]));
                for v in 0..V {
                    let (weights, _) = S::as_simd_f64s(&self.weights[u][v]);
                    for (i, row) in j.iter_mut().enumerate() {
                        let (sums, _) = S::as_mut_simd_f64s(&mut row[v]);
                        for (sum, w) in sums.iter_mut().zip(weights) {
                            *sum = simd.mul_add_f64s(b[i], *w, *sum);
                        }
                    }
                }
            }
            for (i, row) in j.into_iter().enumerate() {
                let value = self.finish(k + i, row);
                square = value.mul_add(value, square);
            }
            k += 4;
        }
        for k in k..n {
            let mut row = [[0.0; 8]; V];
            for u in 0..B {
                Self::add(&mut row, basis[k * B + u], &self.weights[u]);
            }
            let value = self.finish(k, row);
            square = value.mul_add(value, square);
        }
        // Σ b_u² row by row, across the u lanes
        for b in basis.chunks_exact(B) {
            for u in 0..B {
                power[u] = b[u].mul_add(b[u], power[u]);
            }
        }
        (power, square)
    }
}

/// The Gram matrix `Σ_k x_k x_kᵀ` of rows of `8 V` columns (here the
/// Jacobian rows and residuals, zero-padded: `JᵀJ`, `Jᵀr`, `rᵀr`), its
/// first `used` rows, upper triangle by blocks (G is symmetric): four rows
/// of G at a time, held in registers over all samples (writing all of G
/// every sample would make the loop memory-bound), each tile from the
/// block of its diagonal on. The other entries of `g` are left as they are.
pub(super) struct Tiles<'a, const V: usize> {
    /// V blocks a row.
    pub rows: &'a [Lane],
    pub used: usize,
    pub g: &'a mut [[Lane; V]],
}

impl<const V: usize> Tiles<'_, V> {
    /// The tile of G's rows `top..top + 4`, blocks `FROM..V`.
    #[inline(always)]
    fn tile<const FROM: usize>(&mut self, top: usize) {
        let mut tile = [[[0.0; 8]; V]; 4];
        for x in self.rows.chunks_exact(V) {
            let Ok(x) = <&[Lane; V]>::try_from(x) else {
                continue;
            };
            for (r, row) in tile.iter_mut().enumerate() {
                let i = (top + r).min(8 * V - 1);
                let xi = x[i / 8][i % 8];
                for v in FROM..V {
                    for lane in 0..8 {
                        row[v][lane] = xi.mul_add(x[v][lane], row[v][lane]);
                    }
                }
            }
        }
        for (r, row) in tile.iter().enumerate().take(8 * V - top) {
            if let Some(target) = self.g.get_mut(top + r) {
                target[FROM..].copy_from_slice(&row[FROM..]);
            }
        }
    }
}

impl<const V: usize> pulp::WithSimd for Tiles<'_, V> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(mut self, _: S) {
        let mut top = 0;
        while top < self.used.min(8 * V) {
            // the first block a tile needs, as a constant (V ≤ 4)
            match top / 8 {
                0 => self.tile::<0>(top),
                1 => self.tile::<1>(top),
                2 => self.tile::<2>(top),
                _ => self.tile::<3>(top),
            }
            top += 4;
        }
    }
}

/// `Jᵀv` from a window's basis rows: the moments `Bᵀv` of the rows (B per
/// sample) against `v`, mapped by the coefficients (`Cᵀ (Bᵀv)`, row u of C
/// holding P values) and added to `product` (P). Dispatched as the other
/// kernels are, so its fused products are the vector unit's FMA and not
/// calls to libm's `fma` (5–8 % of a lone start's profile, w16-h2).
pub(super) struct Moments<'a, const B: usize> {
    pub basis: &'a [f64],
    pub v: &'a [f64],
    pub coefficients: &'a [f64],
    pub product: &'a mut [f64],
}

impl<const B: usize> pulp::WithSimd for Moments<'_, B> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) {
        let mut moments = [0.0; B];
        for (row, &x) in self.basis.chunks_exact(B).zip(self.v) {
            for (m, b) in moments.iter_mut().zip(row) {
                *m = b.mul_add(x, *m);
            }
        }
        let p = self.product.len();
        for (u, m) in moments.iter().enumerate() {
            let column = &self.coefficients[u * p..(u + 1) * p];
            for (out, c) in self.product.iter_mut().zip(column) {
                *out = c.mul_add(*m, *out);
            }
        }
    }
}
