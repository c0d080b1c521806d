//! What a planar identification estimates, in the estimation layer's terms:
//! the body's mass and yaw inertia, every mass, damper and spring of the two
//! side chains, optionally the tyres' lateral grip μ_y and cornering
//! stiffness C_α (both axles alike), their relaxation length σ when asked
//! ([`Unknowns::with_relaxation`]), and the lateral position of every
//! force whose line of action the study leaves to the data (a pendulum's
//! single load cell: `lateral = "estimate"`).
//!
//! Each case with wall load cells also carries a nuisance: its cells' arm
//! λ ([`crate::drive::Drive::arm`], `case 'NAME' cells.arm`), each cell's
//! line of action at λ times its lateral position from the segments' rule.
//! Where a real bumper's stiffness ends is not known to the segments (on
//! the independent series of tests/peers/planar_yaw_rate.py the beam's end
//! points carry a whole point's share: a beam 1.653 m wide where the study
//! draws 1.6 m, and the struck cell's moment is 5.5 % low at the truth), so
//! the arm is estimated with a stated prior ([`super::priors`]), searched
//! in ln λ within [`ARM_REACH`] of 1, and left at 1 in the held-out
//! replays (no case's nuisance carries over).
//!
//! The bumper's effective width ([`crate::car::PlanarCar::effective_width`],
//! `bumper.effective_width`), when asked ([`Unknowns::with_width`]): a
//! property of the car, so the identified car carries it into every
//! replay, held-out prediction and forward run (unlike the arm). Searched
//! in ln w_e within [`ARM_REACH`] of the start car's, its prior centred
//! there ([`super::priors`]).
//!
//! A nonlinear link ([`super::links`]) adds its law's unknowns after
//! each side's springs (`left.cubic[j]`, `left.yield_force[j]`,
//! `left.hardening[j]`, the link's index j); a hardening ratio is searched
//! up to 1 at most.
//!
//! The car's parameters are positive and span decades: they are searched
//! in `ln θ`, each within a factor [`REACH`] of its start. A line of
//! action is a position (m, left positive) and may be negative: it is
//! searched as is, within [`LINE_MARGIN`] beyond the bumper's ends, and
//! counts as determined when its 95 % interval is at most a quarter of the
//! bumper wide. The relaxation length is searched from [`RELAXATION`]'s
//! lower end to its upper. The lower end stands for a tyre without
//! transient (the slip-angle law at once): a lag σ/|v| of 0.1 ms at
//! 8 km/h, but the lag grows as the car stops and rebounds, where the
//! relaxed tyre is a lateral spring C_α/σ. At 1 cm that spring (6 kN/mm)
//! still lets the car turn: on the yaw-rate generator, whose tyres have no
//! transient, the off-centre face's yaw replays at 86 % with σ = 1 cm and
//! 95 % with 1 mm, the other parameters held (docs/planar.md, "The tyres'
//! relaxation at its floor (w27)").

use super::PlanarCase;
use super::links::{self, LinkLaw};
use crate::car::{Body, PlanarCar, PlanarError, SideChain};
use bumpsim_core::units::Dimension;
use bumpsim_estimate::uncertainty::Parameter;

/// Each car parameter is searched within this factor of its start.
pub const REACH: f64 = 1000.0;

/// The relaxation lengths searched, m (see the module).
pub const RELAXATION: (f64, f64) = (0.001, 2.0);

/// A line of action is searched this far beyond the bumper's ends, m.
pub const LINE_MARGIN: f64 = 0.25;

/// A case's cells' arm is searched within this factor of 1.
pub const ARM_REACH: f64 = 1.25;

/// The bumper's effective width's name.
pub const EFFECTIVE_WIDTH: &str = "bumper.effective_width";

/// The suffix of a cells' arm's name (`case 'WALL10' cells.arm`).
pub const ARM: &str = " cells.arm";

/// A case's wall cells' arm, estimated.
#[derive(Debug, Clone, PartialEq)]
struct Arm {
    case: usize,
    name: String,
    start: f64,
}

/// A force whose lateral position is estimated.
#[derive(Debug, Clone, PartialEq)]
struct Line {
    case: usize,
    load: usize,
    name: String,
    start: f64,
}

/// The unknowns of one identification (see the module).
#[derive(Debug, Clone, PartialEq)]
pub struct Unknowns {
    template: PlanarCar,
    friction: bool,
    cornering: bool,
    relaxation: bool,
    width: bool,
    arms: Vec<Arm>,
    lines: Vec<Line>,
}

impl Unknowns {
    /// The unknowns of `template` (its chains' sizes), with the grip and
    /// the cornering stiffness when asked, and the estimated lines of
    /// action of `cases`.
    pub fn new(
        template: &PlanarCar,
        friction: bool,
        cornering: bool,
        cases: &[PlanarCase],
    ) -> Unknowns {
        let lines = cases
            .iter()
            .enumerate()
            .flat_map(|(c, case)| {
                case.estimated.iter().map(move |&k| Line {
                    case: c,
                    load: k,
                    name: format!("case '{}' force[{k}].lateral", case.name),
                    start: case.drive.loads[k].lateral,
                })
            })
            .collect();
        let arms = cases
            .iter()
            .enumerate()
            .filter(|(_, case)| {
                case.drive
                    .loads
                    .iter()
                    .any(|l| l.cell.is_some() && l.anchor.is_some())
            })
            .map(|(c, case)| Arm {
                case: c,
                name: format!("case '{}'{ARM}", case.name),
                start: case.drive.arm,
            })
            .collect();
        Unknowns {
            template: template.clone(),
            friction,
            cornering,
            relaxation: false,
            width: false,
            arms,
            lines,
        }
    }

    /// The same unknowns with the rolling tyres' relaxation length σ of
    /// both axles estimated too, when `estimated` and the template's tyres
    /// have one (σ > 0 on both axles: a law without one stays without).
    pub fn with_relaxation(self, estimated: bool) -> Unknowns {
        let tyres = self.template.tyres();
        let relaxed = [tyres.front, tyres.rear]
            .iter()
            .all(|a| a.law == crate::car::TyreLaw::Rolling && a.relaxation_length > 0.0);
        Unknowns {
            relaxation: estimated && relaxed,
            ..self
        }
    }

    /// The same unknowns with the bumper's effective width estimated too
    /// when `estimated` (see the module).
    pub fn with_width(self, estimated: bool) -> Unknowns {
        Unknowns {
            width: estimated,
            ..self
        }
    }

    /// The same unknowns without the cells' arms when `estimated` is false
    /// (each stays at its case's).
    pub fn with_arms(self, estimated: bool) -> Unknowns {
        match estimated {
            true => self,
            false => Unknowns {
                arms: Vec::new(),
                ..self
            },
        }
    }

    /// The same unknowns of another template (a reduced car).
    pub fn with_template(&self, template: &PlanarCar) -> Unknowns {
        Unknowns {
            template: template.clone(),
            ..self.clone()
        }
    }

    /// The same unknowns starting from `theta`'s cells' arms and lines of
    /// action (a refit from an identified car).
    pub fn located(&self, theta: &[f64]) -> Unknowns {
        let cars = theta.len() - self.lines.len();
        let arms = cars - self.arms.len();
        let mut out = self.clone();
        for (arm, &value) in out.arms.iter_mut().zip(&theta[arms..cars]) {
            arm.start = value;
        }
        for (line, &value) in out.lines.iter_mut().zip(&theta[cars..]) {
            line.start = value;
        }
        out
    }

    /// The template car.
    pub fn template(&self) -> &PlanarCar {
        &self.template
    }

    /// Names and SI units, in order: body, left chain, right chain
    /// (masses, dampers, springs), grip, cornering stiffness, relaxation
    /// length, cells' arms, lines.
    pub fn names(&self) -> Vec<(String, &'static str)> {
        let mut out = vec![
            ("body.mass".to_string(), "kg"),
            ("body.yaw_inertia".to_string(), "kg·m²"),
        ];
        let t = &self.template;
        for (side, chain) in [("left", t.left()), ("right", t.right())] {
            for (what, unit) in [("masses", "kg"), ("dampers", "N·s/m"), ("springs", "N/m")] {
                for i in 0..chain.masses.len() {
                    out.push((format!("{side}.{what}[{i}]"), unit));
                }
            }
            for (i, link) in chain.links.iter().enumerate() {
                for (what, unit) in LinkLaw::of(link).extra() {
                    out.push((format!("{side}.{what}[{i}]"), *unit));
                }
            }
        }
        if self.friction {
            out.push(("tyres.mu_lateral".to_string(), "-"));
        }
        if self.cornering {
            out.push(("tyres.cornering_stiffness".to_string(), "N/rad"));
        }
        if self.relaxation {
            out.push(("tyres.relaxation_length".to_string(), "m"));
        }
        if self.width {
            out.push((EFFECTIVE_WIDTH.to_string(), "m"));
        }
        out.extend(self.arms.iter().map(|a| (a.name.clone(), "-")));
        out.extend(self.lines.iter().map(|l| (l.name.clone(), "m")));
        out
    }

    /// The estimation layer's parameters (names, display units, scales).
    pub fn parameters(&self) -> Vec<Parameter> {
        let width = 0.25 * self.template.beam().width;
        self.names()
            .into_iter()
            .map(|(name, unit)| match unit {
                "kg" => Parameter::new(name, Dimension::Mass),
                "N·s/m" => Parameter::new(name, Dimension::Damping),
                "N/m" => Parameter::new(name, Dimension::Stiffness),
                "N" => Parameter::new(name, Dimension::Force),
                "m" if name == "tyres.relaxation_length" || name == EFFECTIVE_WIDTH => {
                    Parameter::new(name, Dimension::Length)
                }
                "m" => Parameter::new(name, Dimension::Length).linear(width),
                symbol => Parameter::with_symbol(name, symbol),
            })
            .collect()
    }

    /// The start θ (SI): the template's values and the lines' given positions.
    pub fn start(&self) -> Vec<f64> {
        let car = &self.template;
        let mut out = vec![car.body().mass, car.body().yaw_inertia];
        for chain in [car.left(), car.right()] {
            out.extend(
                [&chain.masses, &chain.dampers, &chain.springs]
                    .into_iter()
                    .flatten(),
            );
            out.extend(chain.links.iter().flat_map(links::values));
        }
        if self.friction {
            out.push(car.tyres().front.mu_lateral);
        }
        if self.cornering {
            out.push(car.tyres().front.cornering_stiffness);
        }
        if self.relaxation {
            out.push(car.tyres().front.relaxation_length);
        }
        if self.width {
            out.push(car.effective_width());
        }
        out.extend(self.arms.iter().map(|a| a.start));
        out.extend(self.lines.iter().map(|l| l.start));
        out
    }

    /// The search variables `p` of `theta`.
    pub fn search(&self, theta: &[f64]) -> Vec<f64> {
        self.parameters()
            .iter()
            .zip(theta)
            .map(|(p, t)| p.search(*t))
            .collect()
    }

    /// θ of the search variables `p`.
    pub fn theta(&self, p: &[f64]) -> Vec<f64> {
        let lines = self.lines.len();
        let cars = p.len() - lines;
        let mut out: Vec<f64> = p[..cars].iter().map(|v| v.exp()).collect();
        out.extend_from_slice(&p[cars..]);
        out
    }

    /// The search's bounds in `p`: a factor [`REACH`] around each car
    /// parameter's start, the bumper's width and [`LINE_MARGIN`] for a line.
    pub fn bounds(&self, start: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let reach = REACH.ln();
        let edge = 0.5 * self.template.beam().width + LINE_MARGIN;
        let cars = start.len() - self.lines.len();
        let (mut lower, mut upper): (Vec<f64>, Vec<f64>) = start[..cars]
            .iter()
            .map(|t| (t.ln() - reach, t.ln() + reach))
            .unzip();
        for i in self.ratios() {
            upper[i] = upper[i].min(0.0);
            lower[i] = lower[i].min(upper[i]);
        }
        if let Some(i) = self.relaxation_index() {
            upper[i] = RELAXATION.1.ln().max(start[i].ln());
            lower[i] = RELAXATION.0.ln().min(start[i].ln());
        }
        let nuisances = self.arm_indices().chain(self.width_index());
        for i in nuisances {
            let centre = match self.width_index() == Some(i) {
                true => self.template.effective_width().ln(),
                false => 0.0,
            };
            upper[i] = (centre + ARM_REACH.ln()).max(start[i].ln());
            lower[i] = (centre - ARM_REACH.ln()).min(start[i].ln());
        }
        lower.extend(std::iter::repeat_n(-edge, self.lines.len()));
        upper.extend(std::iter::repeat_n(edge, self.lines.len()));
        (lower, upper)
    }

    /// A random start within a factor `spread` of `start` (`p`) for the car,
    /// anywhere on the bumper for a line ([`bumpsim_estimate::search::Draws`]).
    pub fn draw(&self, start: &[f64], spread: f64, seed: u64, index: u64) -> Vec<f64> {
        let mut draws = bumpsim_estimate::search::Draws::new(seed, index);
        let cars = start.len() - self.lines.len();
        // (a hardening ratio drawn above 1 is clamped into the box by the
        // search; `start` may be a tied car's, shorter than the names)
        let mut point = draws.around(&start[..cars], spread);
        // a nuisance (and the effective width) starts where its prior is
        for i in self.arm_indices().chain(self.width_index()) {
            if let Some(p) = point.get_mut(i) {
                *p = start[i];
            }
        }
        let half = 0.5 * self.template.beam().width;
        point.extend(self.lines.iter().map(|_| half * (2.0 * draws.unit() - 1.0)));
        point
    }

    /// The car of `theta` (the template's geometry, beam, crash boxes'
    /// stroke, contact rate and the tyres' other coefficients).
    pub fn car(&self, theta: &[f64]) -> Result<PlanarCar, PlanarError> {
        let t = &self.template;
        let mut next = theta.iter().copied();
        let mut take = |n: usize| next.by_ref().take(n).collect::<Vec<f64>>();
        let body = Body {
            mass: take(1)[0],
            yaw_inertia: take(1)[0],
            ..*t.body()
        };
        let mut chain = |template: &SideChain| -> Result<SideChain, PlanarError> {
            let n = template.masses.len();
            let (masses, dampers, springs) = (take(n), take(n), take(n));
            let linked = template
                .links
                .iter()
                .zip(&springs)
                .map(|(link, &k)| {
                    let extra = take(LinkLaw::of(link).extra().len());
                    links::with_values(link, k, &extra)
                        .map_err(|e| crate::car::parameter("links", k, "N/m", &e.to_string()))
                })
                .collect::<Result<Vec<_>, _>>()?;
            Ok(match linked.is_empty() {
                true => SideChain {
                    masses,
                    dampers,
                    springs,
                    links: Vec::new(),
                },
                false => SideChain::linked(masses, dampers, linked),
            })
        };
        let left = chain(t.left())?;
        let right = chain(t.right())?;
        let mut tyres = *t.tyres();
        if self.friction {
            let mu = take(1)[0];
            for axle in [&mut tyres.front, &mut tyres.rear] {
                // a sliding grip along the wheel equal to the lateral one
                // (the car file's default) follows it: rolling tests do not
                // see it apart
                if axle.mu_longitudinal == axle.mu_lateral {
                    axle.mu_longitudinal = mu;
                }
                axle.mu_lateral = mu;
            }
        }
        if self.cornering {
            let c = take(1)[0];
            tyres.front.cornering_stiffness = c;
            tyres.rear.cornering_stiffness = c;
        }
        if self.relaxation {
            let sigma = take(1)[0];
            tyres.front.relaxation_length = sigma;
            tyres.rear.relaxation_length = sigma;
        }
        let width = match self.width {
            true => take(1)[0],
            false => t.effective_width(),
        };
        PlanarCar::new(body, left, right, t.beam().clone(), tyres)
            .and_then(|c| c.with_crash_boxes(t.crash_boxes()))
            .and_then(|c| c.with_contact_rate(t.contact_rate()))
            .and_then(|c| c.with_effective_width(width))
            .map(|c| c.with_name(t.name().map(str::to_string)))
    }

    /// The indices of the hardening ratios (searched up to 1).
    fn ratios(&self) -> Vec<usize> {
        self.names()
            .iter()
            .enumerate()
            .filter(|(_, (n, _))| n.contains(".hardening["))
            .map(|(i, _)| i)
            .collect()
    }

    /// The indices of the cells' arms.
    fn arm_indices(&self) -> std::ops::Range<usize> {
        let end = self.names().len() - self.lines.len();
        end - self.arms.len()..end
    }

    /// The index of the effective width, when it is estimated.
    pub(crate) fn width_index(&self) -> Option<usize> {
        self.names().iter().position(|(n, _)| n == EFFECTIVE_WIDTH)
    }

    /// The index of the relaxation length, when it is estimated.
    fn relaxation_index(&self) -> Option<usize> {
        self.names()
            .iter()
            .position(|(n, _)| n == "tyres.relaxation_length")
    }

    /// `case` (index `index`) with the cells' arm and the lines of action
    /// of `theta`, when it has estimated ones.
    pub fn case(&self, theta: &[f64], index: usize, case: &PlanarCase) -> Option<PlanarCase> {
        let cars = theta.len() - self.lines.len();
        let arm = (self.arms.iter().enumerate())
            .find(|(_, a)| a.case == index)
            .map(|(j, _)| theta[cars - self.arms.len() + j]);
        let mine: Vec<(usize, f64)> = self
            .lines
            .iter()
            .enumerate()
            .filter(|(_, l)| l.case == index)
            .map(|(j, l)| (l.load, theta[cars + j]))
            .collect();
        (!mine.is_empty() || arm.is_some()).then(|| {
            let mut case = case.clone();
            if let Some(arm) = arm {
                case.drive.arm = arm;
            }
            for (load, lateral) in mine {
                case.drive.loads[load].lateral = lateral;
            }
            case
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::car::{Axle, Layout};
    use bumpsim_core::model::MsdModel;
    use bumpsim_impact::bumper::Bumper;

    fn car(relaxation: f64) -> PlanarCar {
        let chain = MsdModel::new(vec![8.0, 1200.0], vec![2e3], vec![1.5e6]).unwrap();
        let bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
        let car = PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap();
        let mut tyres = *car.tyres();
        tyres.front = Axle {
            relaxation_length: relaxation,
            ..Axle::rolling(0.015, 0.8)
        };
        tyres.rear = tyres.front;
        PlanarCar::new(
            *car.body(),
            car.left().clone(),
            car.right().clone(),
            car.beam().clone(),
            tyres,
        )
        .unwrap()
    }

    /// A car made of θ keeps what θ does not hold: the template's crash
    /// boxes' stroke, name and bumper contact rate (a fitted bumper's rate
    /// was dropped by a re-made car).
    #[test]
    fn a_made_car_keeps_the_templates_contact_rate() {
        let template = car(0.4).with_contact_rate(0.3).unwrap();
        let unknowns = Unknowns::new(&template, true, true, &[]);
        let made = unknowns.car(&unknowns.start()).unwrap();
        assert_eq!(made.contact_rate(), 0.3);
        assert_eq!(made, template);
        let plain = Unknowns::new(&car(0.4), false, false, &[]);
        assert_eq!(plain.car(&plain.start()).unwrap().contact_rate(), 0.0);
    }

    /// The relaxation length is an unknown only when asked and when the
    /// start's tyres have one; it is searched in ln σ from 1 mm to 2 m and
    /// lands on both axles.
    #[test]
    fn the_relaxation_length_is_estimated_when_asked_and_the_tyres_relax() {
        let relaxed = Unknowns::new(&car(0.4), false, true, &[]);
        assert!(
            relaxed
                .names()
                .iter()
                .all(|(n, _)| n != "tyres.relaxation_length")
        );
        let asked = relaxed.with_relaxation(true);
        let names = asked.names();
        let i = names
            .iter()
            .position(|(n, _)| n == "tyres.relaxation_length")
            .expect("estimated");
        assert_eq!(names[i].1, "m");
        let start = asked.start();
        assert_eq!(start[i], 0.4);
        let p = asked.search(&start);
        assert!((p[i] - 0.4f64.ln()).abs() < 1e-12, "searched in ln σ");
        let (lower, upper) = asked.bounds(&start);
        assert!((lower[i] - RELAXATION.0.ln()).abs() < 1e-12);
        assert!((upper[i] - RELAXATION.1.ln()).abs() < 1e-12);
        let mut theta = start.clone();
        theta[i] = 0.05;
        let tyres = *asked.car(&theta).unwrap().tyres();
        assert_eq!(tyres.front.relaxation_length, 0.05);
        assert_eq!(tyres.rear.relaxation_length, 0.05);
        // an instantaneous law stays instantaneous (σ = 0 has no log)
        let instant = Unknowns::new(&car(0.0), false, true, &[]).with_relaxation(true);
        assert!(
            instant
                .names()
                .iter()
                .all(|(n, _)| n != "tyres.relaxation_length")
        );
    }
    /// The effective width is an unknown only when asked: searched in
    /// ln w_e within [`ARM_REACH`] of the start car's, started there by
    /// every draw, and carried by the car made of θ.
    #[test]
    fn the_effective_width_is_estimated_when_asked_and_lands_on_the_car() {
        let plain = Unknowns::new(&car(0.4), true, true, &[]);
        assert!(plain.names().iter().all(|(n, _)| n != EFFECTIVE_WIDTH));
        let asked = plain.with_width(true);
        let i = asked.width_index().expect("estimated");
        let start = asked.start();
        let drawn = car(0.4).beam().width;
        assert_eq!(start[i], drawn);
        let p = asked.search(&start);
        assert!((p[i] - drawn.ln()).abs() < 1e-12, "searched in ln w_e");
        let (lower, upper) = asked.bounds(&start);
        assert!((upper[i] - (drawn * ARM_REACH).ln()).abs() < 1e-12);
        assert!((lower[i] - (drawn / ARM_REACH).ln()).abs() < 1e-12);
        assert_eq!(asked.draw(&p, 10.0, 1, 3)[i], p[i]);
        let mut theta = start.clone();
        theta[i] = 1.03 * drawn;
        let made = asked.car(&theta).unwrap();
        assert_eq!(made.effective_width(), 1.03 * drawn);
        assert_eq!(made.beam().width, drawn, "the drawn width stays");
        assert_eq!(asked.with_template(&made).start()[i], 1.03 * drawn);
    }
}
