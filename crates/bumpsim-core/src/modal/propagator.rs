//! The exact one-step propagator of [`super::ModalForm`]'s slots: for a
//! sample interval T, each slot's `e^(λT)` and the weights of the held
//! force, which the per-sample kernels (`modal::kernels`) apply and the
//! runs (`modal::sweep`) make once per run.

use super::{C, Slot};

/// The constants of every slot at one step T, by component (slots
/// innermost): `e^(λT)` as a 2 × 2 real map of `[s0, s1]` (row-major
/// `p[0..4]`), the force weights `T φ1(λT)` of z (`q`) and `T² φ1'(λT)` of
/// w (`h`).
pub(super) struct SlotConstants<const L: usize> {
    pub p: [[f64; L]; 4],
    pub q: [[f64; L]; 2],
    pub h: [[f64; L]; 2],
}

impl<const L: usize> SlotConstants<L> {
    pub(super) fn new(slots: &[Slot], t: f64) -> SlotConstants<L> {
        let each: [([f64; 4], [f64; 2], [f64; 2]); L] =
            std::array::from_fn(|l| slot_constants(slots[l], t));
        SlotConstants {
            p: std::array::from_fn(|c| std::array::from_fn(|l| each[l].0[c])),
            q: std::array::from_fn(|c| std::array::from_fn(|l| each[l].1[c])),
            h: std::array::from_fn(|c| std::array::from_fn(|l| each[l].2[c])),
        }
    }
}

fn slot_constants(slot: Slot, t: f64) -> ([f64; 4], [f64; 2], [f64; 2]) {
    match slot {
        Slot::Complex(lambda) => {
            let e = (lambda * t).exp();
            let (phi, slope) = phi1(lambda * t);
            let (g, h) = (phi * t, slope * (t * t));
            ([e.re, -e.im, e.im, e.re], [g.re, g.im], [h.re, h.im])
        }
        Slot::Real(a, b) => {
            let (ea, eb) = ((a * t).exp(), (b * t).exp());
            let ((pa, sa), (pb, sb)) = (phi1(C::from(a * t)), phi1(C::from(b * t)));
            let tt = t * t;
            (
                [ea, 0.0, 0.0, eb],
                [pa.re * t, pb.re * t],
                [sa.re * tt, sb.re * tt],
            )
        }
    }
}

/// `φ1(x) = (eˣ − 1)/x` and `φ1'(x)`, by their series near 0 (no
/// cancellation) and directly elsewhere.
pub(super) fn phi1(x: C) -> (C, C) {
    if x.norm_sqr() < 0.25 {
        // φ1 = Σ x^k/(k+1)!, φ1' = Σ (k+1) x^k/(k+2)!; 0.5^20/21! is far below 1e-17
        let (mut value, mut slope) = (C::ZERO, C::ZERO);
        let (mut power, mut factorial) = (C::ONE, 1.0);
        for k in 0..20 {
            factorial *= (k + 1) as f64;
            value += power / factorial;
            slope += power * ((k + 1) as f64) / (factorial * (k + 2) as f64);
            power *= x;
        }
        return (value, slope);
    }
    let e = x.exp();
    ((e - 1.0) / x, (e * (x - 1.0) + 1.0) / (x * x))
}
