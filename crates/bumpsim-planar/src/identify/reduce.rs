//! The simpler planar car the data cannot tell apart: the estimation
//! layer's reduced-model advice ([`bumpsim_estimate::reduce`]) on the side
//! chains' links, as the 1-D chain gets it.
//!
//! Link i of a side chain joins its mass i to mass i + 1, or the last mass
//! to the body. Its merge puts both masses on one node (the last one's into
//! the body: `M + m`), removes link i and keeps the others; the merged car
//! is refitted from its merged start within a factor 1000 of it, like the
//! full car.

use super::Unknowns;
use super::objective::Objective;
use crate::car::{Body, PlanarCar, SideChain};
use crate::drive::Sensor;
use bumpsim_estimate::lm::{self, LeastSquares};
use bumpsim_estimate::reduce::{Link, Merged, Reducible, refit};

/// A link of a side chain: the side (0 left, 1 right) and its index.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct ChainLink {
    side: usize,
    index: usize,
}

/// The identified car, its cases and unknowns, as the layer reduces them.
pub(super) struct Car<'a> {
    pub cases: &'a [super::PlanarCase],
    pub car: &'a PlanarCar,
    /// What the identification estimated, its lines of action at their estimates.
    pub unknowns: &'a Unknowns,
    pub solver: lm::Settings,
    /// Where the accelerometers are compared and their biases (the identification's).
    pub domain: (bumpsim_estimate::domain::Domain, super::Bias),
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
        if !chain.links.is_empty() {
            chain.links.remove(l.index);
        }
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
        .and_then(|c| c.with_effective_width(self.car.effective_width()))
        .ok()?
        .with_name(self.car.name().map(str::to_string));
        Some((car, mass))
    }

    /// The cases measured on the car with link `l` merged: a sensor on a
    /// chain mass after the removed one moves down an index; one on a mass
    /// merged into the body becomes the body point where that mass sat
    /// (on the bumper line at its side member).
    fn retargeted(&self, l: ChainLink) -> Vec<super::PlanarCase> {
        let removed = match l.side {
            0 => l.index,
            _ => self.car.left().masses.len() + l.index,
        };
        let into_body = l.index + 1 == self.chain(l.side).masses.len();
        let b = 0.5 * self.car.beam().side_member_spacing;
        let point = [
            self.car.body().cg_behind_bumper,
            if l.side == 0 { b } else { -b },
        ];
        let moved = |sensor: Sensor| match sensor {
            Sensor::Chain(i) if i == removed && into_body => Sensor::Body(point),
            Sensor::Chain(i) if i > removed => Sensor::Chain(i - 1),
            other => other,
        };
        let mut cases = self.cases.to_vec();
        for case in &mut cases {
            case.drive.sensors.iter_mut().for_each(|s| *s = moved(*s));
        }
        cases
    }
}

/// The problem of `cases` with `unknowns`.
fn problem<'b>(
    cases: &'b [super::PlanarCase],
    unknowns: &'b Unknowns,
    domain: (bumpsim_estimate::domain::Domain, super::Bias),
) -> Option<Objective<'b>> {
    Objective::new(cases, unknowns, domain).ok()
}

impl Reducible for Car<'_> {
    type Model = PlanarCar;

    fn links(&self) -> Vec<Link> {
        let names = self.unknowns.with_template(self.car).names();
        // by name: a nonlinear link's unknowns (cubic, yield force) follow
        // each side's springs and shift the right chain's indices
        let spring = |l: ChainLink| {
            let name = format!("{}.springs[{}]", ["left", "right"][l.side], l.index);
            names.iter().position(|(n, _)| *n == name).unwrap_or(0)
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
        let link = self.links_of()[j];
        let (car, _) = self.merged(link)?;
        let cases = self.retargeted(link);
        let unknowns = self.unknowns.with_template(&car);
        let problem = problem(&cases, &unknowns, self.domain)?;
        let p = unknowns.search(&unknowns.start());
        let mut r = vec![0.0; problem.residual_count()];
        problem
            .evaluate(&p, &mut r, None)
            .then(|| r.iter().map(|v| v * v).sum())
    }

    fn refit(&self, j: usize, target: f64) -> Option<Merged<PlanarCar>> {
        let link = self.links_of()[j];
        let (car, _) = self.merged(link)?;
        let unknowns = self.unknowns.with_template(&car);
        let theta = unknowns.start();
        let (lower, upper) = unknowns.bounds(&theta);
        let cases = self.retargeted(link);
        let problem = problem(&cases, &unknowns, self.domain)?;
        let start = unknowns.search(&theta);
        let outcome = refit(&|| &problem, start, (&lower, &upper), &self.solver, target)?;
        let refitted = unknowns.car(&unknowns.theta(&outcome.parameters)).ok()?;
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

#[cfg(test)]
mod tests {
    use super::super::{PlanarCase, Setup, identify};
    use crate::car::{Layout, PlanarCar, SideChain};
    use crate::drive::Sensor;
    use bumpsim_core::model::MsdModel;
    use bumpsim_impact::bumper::Bumper;

    /// A car whose left chain has two masses joined by a link far stiffer
    /// than anything the tests resolve (1e10 N/m between 4 kg and 2 kg:
    /// about 11 kHz, above the 5 kHz Nyquist frequency of the 10 kHz
    /// samples): the data cannot tell it from one 6 kg mass.
    fn truth() -> PlanarCar {
        let chain = MsdModel::new(vec![8.0, 1200.0], vec![2e3], vec![1.5e6]).unwrap();
        let bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
        let symmetric = PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap();
        let left = SideChain {
            masses: vec![4.0, 2.0],
            dampers: vec![300.0, 2e3],
            springs: vec![1e10, 1.5e6],
            links: Vec::new(),
        };
        PlanarCar::new(
            *symmetric.body(),
            left,
            symmetric.right().clone(),
            symmetric.beam().clone(),
            *symmetric.tyres(),
        )
        .unwrap()
    }

    /// A push of `truth` with white measurement noise of 0.1 mm (a
    /// deterministic hash of the sample), so that the fit has a noise level
    /// to judge the link by.
    fn case(truth: &PlanarCar, name: &str, lateral: f64) -> PlanarCase {
        let mut case = super::super::tests::pushed(truth, name, lateral, Sensor::Chain(2));
        for (s, signal) in case.measured.iter_mut().enumerate() {
            for (k, v) in signal.iter_mut().enumerate() {
                let x = ((k * 7919 + s * 104_729 + name.len() * 31) as f64 * 12.9898).sin()
                    * 43_758.545;
                *v += 1e-4 * (2.0 * (x - x.floor()) - 1.0);
            }
        }
        case
    }

    /// The layer's advice on the planar car, in the 1-D chain's words: the
    /// undetermined stiff link is named, its two masses merged into one of
    /// 6 kg, and the merged car fits as well.
    #[test]
    fn an_undetermined_side_chain_link_is_merged_and_named() {
        let truth = truth();
        let cases = [case(&truth, "left", 0.4), case(&truth, "right", -0.3)];
        let unknowns = crate::identify::Unknowns::new(&truth, false, false, &cases);
        let setup = Setup {
            starts: 2,
            priors: crate::identify::removing_all(&unknowns),
            ..Setup::new(truth.clone())
        };
        let result = identify(&cases, &setup, &|| {}).unwrap();
        let stiff = result
            .parameters
            .iter()
            .find(|p| p.name == "left.springs[0]")
            .unwrap();
        assert_eq!(stiff.determined, Some(false), "{stiff:?}");
        let reduction = result.reduction.as_ref().expect("a reduced car");
        assert_eq!(reduction.parameter, "left.springs[0]");
        assert!(
            reduction
                .statement
                .contains("left.masses[0] and left.masses[1] move as one"),
            "{}",
            reduction.statement
        );
        assert_eq!(reduction.model.left().masses.len(), 1);
        let merged = reduction.model.left().masses[0];
        assert!((merged - 6.0).abs() < 0.3, "merged mass {merged} kg");
        assert!(reduction.relative_objective < 0.01, "{reduction:?}");
        assert!(result.warnings.iter().any(|w| w == &reduction.statement));
    }
}
