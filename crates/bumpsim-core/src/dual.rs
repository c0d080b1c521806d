//! Forward-mode automatic differentiation by dual numbers: a value carried
//! with its derivatives along `N` directions, `x = a + Σ_i b_i ε_i` with
//! `ε_i ε_j = 0`, so that every operation applies the chain rule exactly
//! (Griewank & Walther 2008, *Evaluating Derivatives*, ch. 3; the tangent
//! mode). A computation written once over [`Real`] runs on `f64` for its
//! value and on [`Dual`] for its value and its exact first derivatives with
//! respect to the quantities seeded ([`Dual::seeded`]): the forward
//! sensitivity equations of an integrator, without writing them by hand.
//!
//! Rules, for `x = a + b·ε`, `y = c + d·ε`:
//! `x y = ac + (ad + bc) ε`, `x / y = a/c + (b c − a d)/c² ε`,
//! `f(x) = f(a) + f'(a) b ε` for `sqrt`, `sin`, `cos`, `tanh`, `exp`, `atan2`, `abs`.
//! Comparisons, `max`/`min` and `clamp` act on the values (the branch taken
//! is differentiated; at a kink the side taken's derivative).
//!
//! ```
//! use bumpsim_core::dual::{Dual, Real};
//! // f(x, y) = x² sin y at (3, 0.5): ∂f/∂x = 2 x sin y, ∂f/∂y = x² cos y
//! let (x, y) = (Dual::<2>::seeded(3.0, 0, 1.0), Dual::<2>::seeded(0.5, 1, 1.0));
//! let f = x * x * y.sin_cos().0;
//! assert!((f.value() - 9.0 * 0.5f64.sin()).abs() < 1e-15);
//! assert!((f.tangent[0] - 6.0 * 0.5f64.sin()).abs() < 1e-14);
//! assert!((f.tangent[1] - 9.0 * 0.5f64.cos()).abs() < 1e-14);
//! ```

use std::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

/// A real number that a computation can be written over once: `f64`, or a
/// [`Dual`] carrying its derivatives.
pub trait Real:
    Copy
    + std::fmt::Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + Add<f64, Output = Self>
    + Sub<f64, Output = Self>
    + Mul<f64, Output = Self>
    + Div<f64, Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign<f64>
{
    /// A constant (no derivatives).
    fn constant(value: f64) -> Self;
    /// The value.
    fn value(&self) -> f64;
    /// The square root.
    fn sqrt(self) -> Self;
    /// Sine and cosine.
    fn sin_cos(self) -> (Self, Self);
    /// The hyperbolic tangent.
    fn tanh(self) -> Self;
    /// The exponential.
    fn exp(self) -> Self;
    /// The four-quadrant arc tangent of `self / x`.
    fn atan2(self, x: Self) -> Self;
    /// The absolute value (derivative `sign(a)`, 0 at 0).
    fn abs(self) -> Self {
        match self.value() < 0.0 {
            true => -self,
            false => self,
        }
    }
    /// `self` limited to `[low, high]` by value.
    fn clamp(self, low: Self, high: Self) -> Self {
        if self.value() < low.value() {
            low
        } else if self.value() > high.value() {
            high
        } else {
            self
        }
    }
    /// The larger of `self` and a constant, by value.
    fn max_constant(self, other: f64) -> Self {
        match self.value() < other {
            true => Self::constant(other),
            false => self,
        }
    }
}

impl Real for f64 {
    fn constant(value: f64) -> f64 {
        value
    }
    fn value(&self) -> f64 {
        *self
    }
    fn sqrt(self) -> f64 {
        f64::sqrt(self)
    }
    fn sin_cos(self) -> (f64, f64) {
        f64::sin_cos(self)
    }
    fn tanh(self) -> f64 {
        f64::tanh(self)
    }
    fn exp(self) -> f64 {
        f64::exp(self)
    }
    fn atan2(self, x: f64) -> f64 {
        f64::atan2(self, x)
    }
    fn abs(self) -> f64 {
        f64::abs(self)
    }
    fn clamp(self, low: f64, high: f64) -> f64 {
        // f64::clamp panics on low > high; the callers' limits are ordered
        self.max(low).min(high)
    }
    fn max_constant(self, other: f64) -> f64 {
        self.max(other)
    }
}

/// A value and its derivatives along `N` directions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dual<const N: usize> {
    /// The value.
    pub real: f64,
    /// Its derivative along each direction.
    pub tangent: [f64; N],
}

impl<const N: usize> Dual<N> {
    /// `value` varying along direction `direction` at the rate `rate`
    /// (1 for the quantity itself; `value` for its logarithm).
    pub fn seeded(value: f64, direction: usize, rate: f64) -> Self {
        let mut tangent = [0.0; N];
        tangent[direction] = rate;
        Dual {
            real: value,
            tangent,
        }
    }

    /// `f(self)` from `f(a)` and `f'(a)`.
    fn chain(self, value: f64, slope: f64) -> Self {
        let mut tangent = self.tangent;
        tangent.iter_mut().for_each(|t| *t *= slope);
        Dual {
            real: value,
            tangent,
        }
    }
}

impl<const N: usize> Add for Dual<N> {
    type Output = Self;
    fn add(mut self, y: Self) -> Self {
        self += y;
        self
    }
}

impl<const N: usize> AddAssign for Dual<N> {
    fn add_assign(&mut self, y: Self) {
        self.real += y.real;
        self.tangent
            .iter_mut()
            .zip(&y.tangent)
            .for_each(|(a, b)| *a += b);
    }
}

impl<const N: usize> Sub for Dual<N> {
    type Output = Self;
    fn sub(mut self, y: Self) -> Self {
        self -= y;
        self
    }
}

impl<const N: usize> SubAssign for Dual<N> {
    fn sub_assign(&mut self, y: Self) {
        self.real -= y.real;
        self.tangent
            .iter_mut()
            .zip(&y.tangent)
            .for_each(|(a, b)| *a -= b);
    }
}

impl<const N: usize> Mul for Dual<N> {
    type Output = Self;
    fn mul(self, y: Self) -> Self {
        let mut tangent = [0.0; N];
        for ((t, a), b) in tangent.iter_mut().zip(&self.tangent).zip(&y.tangent) {
            *t = a * y.real + self.real * b;
        }
        Dual {
            real: self.real * y.real,
            tangent,
        }
    }
}

impl<const N: usize> Div for Dual<N> {
    type Output = Self;
    fn div(self, y: Self) -> Self {
        let inverse = 1.0 / y.real;
        let real = self.real * inverse;
        let mut tangent = [0.0; N];
        for ((t, a), b) in tangent.iter_mut().zip(&self.tangent).zip(&y.tangent) {
            *t = (a - real * b) * inverse;
        }
        Dual { real, tangent }
    }
}

impl<const N: usize> Neg for Dual<N> {
    type Output = Self;
    fn neg(self) -> Self {
        self.chain(-self.real, -1.0)
    }
}

impl<const N: usize> Add<f64> for Dual<N> {
    type Output = Self;
    fn add(mut self, y: f64) -> Self {
        self.real += y;
        self
    }
}

impl<const N: usize> Sub<f64> for Dual<N> {
    type Output = Self;
    fn sub(mut self, y: f64) -> Self {
        self.real -= y;
        self
    }
}

impl<const N: usize> Mul<f64> for Dual<N> {
    type Output = Self;
    fn mul(mut self, y: f64) -> Self {
        self *= y;
        self
    }
}

impl<const N: usize> MulAssign<f64> for Dual<N> {
    fn mul_assign(&mut self, y: f64) {
        self.real *= y;
        self.tangent.iter_mut().for_each(|t| *t *= y);
    }
}

impl<const N: usize> Div<f64> for Dual<N> {
    type Output = Self;
    fn div(self, y: f64) -> Self {
        self.chain(self.real / y, 1.0 / y)
    }
}

impl<const N: usize> Real for Dual<N> {
    fn constant(value: f64) -> Self {
        Dual {
            real: value,
            tangent: [0.0; N],
        }
    }
    fn value(&self) -> f64 {
        self.real
    }
    fn sqrt(self) -> Self {
        let root = self.real.sqrt();
        self.chain(root, 0.5 / root)
    }
    fn sin_cos(self) -> (Self, Self) {
        let (s, c) = self.real.sin_cos();
        (self.chain(s, c), self.chain(c, -s))
    }
    fn tanh(self) -> Self {
        let t = self.real.tanh();
        self.chain(t, 1.0 - t * t)
    }
    fn exp(self) -> Self {
        let e = self.real.exp();
        self.chain(e, e)
    }
    fn atan2(self, x: Self) -> Self {
        // d atan2(y, x) = (x dy − y dx) / (x² + y²)
        let (y, r2) = (self.real, self.real * self.real + x.real * x.real);
        let mut tangent = [0.0; N];
        for ((t, dy), dx) in tangent.iter_mut().zip(&self.tangent).zip(&x.tangent) {
            *t = (x.real * dy - y * dx) / r2;
        }
        Dual {
            real: y.atan2(x.real),
            tangent,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each rule against a central difference of the same expression on
    /// `f64` (step 1e-6: truncation ~1e-12, rounding ~1e-10 of the scale).
    #[test]
    fn every_rule_matches_a_central_difference() {
        fn f<T: Real>(x: T, y: T) -> T {
            let (s, c) = (x * y).sin_cos();
            let a = (x * x + y * 3.0).sqrt() / (y + 2.0) - x.atan2(y) * c;
            a * s.tanh() + (x - y * 4.0).abs() + x.clamp(y, y * 3.0) - (-x / 2.0) + (x * y).exp()
        }
        let (x0, y0) = (0.7, 0.4);
        let x = Dual::<2>::seeded(x0, 0, 1.0);
        let y = Dual::<2>::seeded(y0, 1, 1.0);
        let d = f(x, y);
        assert!((d.real - f(x0, y0)).abs() < 1e-15);
        let h = 1e-6;
        let dx = (f(x0 + h, y0) - f(x0 - h, y0)) / (2.0 * h);
        let dy = (f(x0, y0 + h) - f(x0, y0 - h)) / (2.0 * h);
        assert!((d.tangent[0] - dx).abs() < 1e-8, "{} {dx}", d.tangent[0]);
        assert!((d.tangent[1] - dy).abs() < 1e-8, "{} {dy}", d.tangent[1]);
    }
}
