//! A link's parameters as a vector, and the same link over any [`Real`]
//! (issue 46 item 2): what an identification varies and what the exact
//! Jacobian replays on dual numbers carry. The law is the one of
//! [`super::Link`]; only its numbers change type.
//!
//! Order: the curve's, then the unloading slope when there is one —
//! linear `[k]`; progressive `[k, k3, δ_lim]`; bilinear `[k, F_y, r]`;
//! table `[F_1, .., F_n]` (the forces past (0, 0), deformations fixed).

use super::{Curve, Link, Unloading};
use crate::dual::Real;

impl Link<f64> {
    /// The parameters in the module's order, SI.
    pub fn parameters(&self) -> Vec<f64> {
        let mut out = match self.curve() {
            Curve::Linear { stiffness } => vec![*stiffness],
            Curve::Progressive {
                stiffness,
                cubic,
                limit,
            } => vec![*stiffness, *cubic, *limit],
            Curve::Bilinear {
                stiffness,
                yield_force,
                hardening,
            } => vec![*stiffness, *yield_force, *hardening],
            Curve::Table { points } => points[1..].iter().map(|p| p[1]).collect(),
        };
        if let Unloading::Slope(k) = self.unloading() {
            out.push(k);
        }
        out
    }

    /// The parameters' names in the module's order (`stiffness`, `cubic`,
    /// `limit`, `yield_force`, `hardening`, `force[i]`, `unloading`).
    pub fn parameter_names(&self) -> Vec<String> {
        let mut out: Vec<String> = match self.curve() {
            Curve::Linear { .. } => vec!["stiffness".into()],
            Curve::Progressive { .. } => {
                vec!["stiffness".into(), "cubic".into(), "limit".into()]
            }
            Curve::Bilinear { .. } => {
                vec!["stiffness".into(), "yield_force".into(), "hardening".into()]
            }
            Curve::Table { points } => (1..points.len()).map(|i| format!("force[{i}]")).collect(),
        };
        if let Unloading::Slope(_) = self.unloading() {
            out.push("unloading".into());
        }
        out
    }

    /// The same law with `values` (as [`Link::parameters`] orders them) on
    /// any [`Real`]: seeded duals give the derivatives of every force and
    /// energy by them. Not validated: give values [`Link::parameters`]
    /// of a valid link would hold (the constants of that link, or near them).
    ///
    /// ```
    /// use bumpsim_core::dual::{Dual, Real};
    /// use bumpsim_core::link::{Curve, Link, LinkState, Unloading};
    /// let link = Link::new(Curve::bilinear(1e6, 5e4, 0.1).unwrap(), Unloading::Slope(2e6)).unwrap();
    /// let mut p: Vec<Dual<1>> = link.parameters().iter().map(|v| Dual::constant(*v)).collect();
    /// p[1] = Dual::seeded(5e4, 0, 1.0);                     // d/dF_y
    /// let dual = link.with_parameters(&p);
    /// let f = dual.force(Dual::constant(0.2), &mut LinkState::default());
    /// assert!((f.tangent[0] - 0.9).abs() < 1e-12);           // F = F_y + r (k δ − F_y)
    /// ```
    pub fn with_parameters<T: Real>(&self, values: &[T]) -> Link<T> {
        let at = |i: usize| values.get(i).copied().unwrap_or(T::constant(f64::NAN));
        let (curve, used) = match self.curve() {
            Curve::Linear { .. } => (Curve::Linear { stiffness: at(0) }, 1),
            Curve::Progressive { .. } => (
                Curve::Progressive {
                    stiffness: at(0),
                    cubic: at(1),
                    limit: at(2),
                },
                3,
            ),
            Curve::Bilinear { .. } => (
                Curve::Bilinear {
                    stiffness: at(0),
                    yield_force: at(1),
                    hardening: at(2),
                },
                3,
            ),
            Curve::Table { points } => {
                let mut out = vec![[T::constant(0.0); 2]];
                for (i, p) in points[1..].iter().enumerate() {
                    out.push([T::constant(p[0]), at(i)]);
                }
                (Curve::Table { points: out }, points.len() - 1)
            }
        };
        let unloading = match self.unloading() {
            Unloading::Elastic => Unloading::Elastic,
            Unloading::Slope(_) => Unloading::Slope(at(used)),
        };
        Link { curve, unloading }
    }

    /// The same link on any [`Real`], every parameter a constant.
    pub fn real<T: Real>(&self) -> Link<T> {
        let values: Vec<T> = self.parameters().iter().map(|v| T::constant(*v)).collect();
        self.with_parameters(&values)
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Curve, Link, LinkState, Unloading};
    use crate::dual::{Dual, Real};

    /// A load–unload–reload history of δ, m.
    fn history() -> Vec<f64> {
        let up = (0..=200).map(|i| 0.3 * i as f64 / 200.0);
        let down = (1..=100).map(|i| 0.3 - 0.2 * i as f64 / 100.0);
        let again = (1..=150).map(|i| 0.1 + 0.35 * i as f64 / 150.0);
        up.chain(down).chain(again).collect()
    }

    fn links() -> Vec<Link> {
        let slope = Unloading::Slope(4e6);
        vec![
            Link::new(Curve::bilinear(2e6, 4e4, 0.05).unwrap(), slope).unwrap(),
            Link::new(Curve::progressive(1e6, 2e8, 0.4).unwrap(), slope).unwrap(),
            Link::new(
                Curve::table(vec![[0.02, 3e4], [0.1, 5e4], [0.5, 4e4]]).unwrap(),
                slope,
            )
            .unwrap(),
            Link::new(
                Curve::progressive(1e6, 2e8, 0.4).unwrap(),
                Unloading::Elastic,
            )
            .unwrap(),
        ]
    }

    /// The law on duals gives the f64 law's values bit for bit, and its
    /// derivatives by every parameter along a load–unload–reload history
    /// match central differences (relative step 1e-6) to 1e-5 of the
    /// largest force derivative.
    #[test]
    fn one_law_for_f64_and_duals() {
        for link in links() {
            let base = link.parameters();
            let n = base.len();
            let seeded: Vec<Dual<4>> = base
                .iter()
                .enumerate()
                .map(|(i, v)| Dual::seeded(*v, i, 1.0))
                .collect();
            let dual = link.with_parameters(&seeded);
            assert_eq!(link.real::<f64>(), link);
            let (mut s, mut ds) = (LinkState::default(), LinkState::<Dual<4>>::default());
            let exact: Vec<Dual<4>> = history()
                .iter()
                .map(|d| {
                    let f = link.force(*d, &mut s);
                    let g = dual.force(Dual::constant(*d), &mut ds);
                    assert_eq!(f.to_bits(), g.value().to_bits());
                    g
                })
                .collect();
            assert_eq!(s.dissipated(&link), ds.dissipated(&dual).value());
            for i in 0..n {
                let h = 1e-6 * base[i].abs().max(1e-3);
                let run = |x: f64| {
                    let mut v = base.clone();
                    v[i] = x;
                    let law = link.with_parameters(&v);
                    let mut s = LinkState::default();
                    history()
                        .iter()
                        .map(|d| law.force(*d, &mut s))
                        .collect::<Vec<_>>()
                };
                let (up, down) = (run(base[i] + h), run(base[i] - h));
                let column: Vec<f64> = up
                    .iter()
                    .zip(&down)
                    .map(|(a, b)| (a - b) / (2.0 * h))
                    .collect();
                let scale = column.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                for (k, c) in column.iter().enumerate() {
                    let d = exact[k].tangent[i];
                    assert!(
                        (d - c).abs() <= 1e-5 * scale.max(1e-300),
                        "{:?} parameter {i} step {k}: {d} against {c}",
                        link.curve()
                    );
                }
            }
        }
    }
}
