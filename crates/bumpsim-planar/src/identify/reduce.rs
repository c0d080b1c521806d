//! The simpler planar car the data cannot tell apart: the estimation
//! layer's reduced-model advice ([`bumpsim_estimate::reduce`]) on the side
//! chains' links, as the 1-D chain gets it.
//!
//! Link i of a side chain joins its mass i to mass i + 1, or the last mass
//! to the body. Its merge puts both masses on one node (the last one's into
//! the body: `M + m`), removes link i and keeps the others; the merged car
//! is refitted from its merged start within a factor 1000 of it, like the
//! full car.

use super::objective::Objective;
use super::{Setup, car_with, names, values};
use crate::car::{Body, PlanarCar, SideChain};
use bumpsim_estimate::bounds::Bounds;
use bumpsim_estimate::lm::{self, LeastSquares};
use bumpsim_estimate::reduce::{Link, Merged, Reducible, refit};

/// A link of a side chain: the side (0 left, 1 right) and its index.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct ChainLink {
    side: usize,
    index: usize,
}

/// The identified car, its cases and setup, as the layer reduces them.
pub(super) struct Car<'a> {
    pub cases: &'a [super::PlanarCase],
    pub car: &'a PlanarCar,
    pub setup: &'a Setup,
    pub solver: lm::Settings,
}

impl Car<'_> {
    fn links_of(&self) -> Vec<ChainLink> {
        (0..2)
            .flat_map(|side| {
                let n = self.chain(side).masses.len();
                (0..n).map(move |index| ChainLink { side, index })
            })
            .collect()
    }

    fn chain(&self, side: usize) -> &SideChain {
        match side {
            0 => self.car.left(),
            _ => self.car.right(),
        }
    }

    /// The car with link `l` merged, and the merged node's mass, kg.
    fn merged(&self, l: ChainLink) -> Option<(PlanarCar, f64)> {
        let mut chains = [self.car.left().clone(), self.car.right().clone()];
        let mut body: Body = *self.car.body();
        let chain = &mut chains[l.side];
        let m = chain.masses.remove(l.index);
        chain.dampers.remove(l.index);
        chain.springs.remove(l.index);
        let mass = match chain.masses.get_mut(l.index) {
            Some(next) => {
                *next += m;
                *next
            }
            None => {
                body.mass += m;
                body.mass
            }
        };
        let [left, right] = chains;
        let car = PlanarCar::new(
            body,
            left,
            right,
            self.car.beam().clone(),
            *self.car.tyres(),
        )
        .ok()?
        .with_name(self.car.name().map(str::to_string));
        Some((car, mass))
    }

    fn problem<'b>(&'b self, template: &'b PlanarCar) -> Option<Objective<'b>> {
        let count = names(template, self.setup.friction).len();
        Objective::new(self.cases, template, self.setup.friction, count).ok()
    }
}

impl Reducible for Car<'_> {
    type Model = PlanarCar;

    fn links(&self) -> Vec<Link> {
        let names = names(self.car, self.setup.friction);
        let spring = |l: ChainLink| {
            let (left, right) = (self.car.left().masses.len(), self.car.right().masses.len());
            match l.side {
                0 => 2 + 2 * left + l.index,
                _ => 2 + 3 * left + 2 * right + l.index,
            }
        };
        self.links_of()
            .into_iter()
            .map(|l| {
                let side = ["left", "right"][l.side];
                let first = format!("{side}.masses[{}]", l.index);
                let second = match l.index + 1 < self.chain(l.side).masses.len() {
                    true => format!("{side}.masses[{}]", l.index + 1),
                    false => "body.mass".to_string(),
                };
                debug_assert!(names[spring(l)].0.starts_with(&format!("{side}.springs")));
                Link {
                    spring: spring(l),
                    masses: [first, second],
                }
            })
            .collect()
    }

    fn merged_objective(&self, j: usize) -> Option<f64> {
        let (car, _) = self.merged(self.links_of()[j])?;
        let problem = self.problem(&car)?;
        let p: Vec<f64> = values(&car, self.setup.friction)
            .iter()
            .map(|v| v.ln())
            .collect();
        let mut r = vec![0.0; problem.residual_count()];
        problem
            .evaluate(&p, &mut r, None)
            .then(|| r.iter().map(|v| v * v).sum())
    }

    fn refit(&self, j: usize, target: f64) -> Option<Merged<PlanarCar>> {
        let link = self.links_of()[j];
        let (car, _) = self.merged(link)?;
        let theta = values(&car, self.setup.friction);
        let (lower, upper) = Bounds::around(&theta, super::REACH).log_free();
        let problem = self.problem(&car)?;
        let start = theta.iter().map(|v| v.ln()).collect();
        let outcome = refit(&|| &problem, start, (&lower, &upper), &self.solver, target)?;
        let theta: Vec<f64> = outcome.parameters.iter().map(|p| p.exp()).collect();
        let refitted = car_with(&car, &theta, self.setup.friction).ok()?;
        let chain = [refitted.left(), refitted.right()][link.side];
        let mass = chain
            .masses
            .get(link.index)
            .copied()
            .unwrap_or(refitted.body().mass);
        Some(Merged {
            model: refitted,
            objective: outcome.objective,
            mass,
        })
    }

    fn reduced_name(&self) -> String {
        "car".to_string()
    }
}
