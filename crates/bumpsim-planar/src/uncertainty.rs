//! The planar car's uncertain parameters (issue 39, items 3 and 4):
//! log-normal and correlated around the car file's values, or uniform
//! over a range, read from a planar identification's JSON or a TOML
//! `[uncertainty]` table of relative standard deviations and/or a
//! `[ranges]` table of factors, drawn with a seed. The machinery (reading, the
//! Cholesky factor, seeded draws) is the chain car's
//! ([`bumpsim_impact::uncertainty`]); this module names the planar car's
//! parameters and scales a [`PlanarCar`] by their factors ([`Planar`]).
//!
//! - a planar identification's JSON (`bumpsim identify --json` on a
//!   planar study): `σᵢ = SEᵢ/θ̂ᵢ` of `result.parameters` and `R` their
//!   `result.uncertainty.correlation`; parameters without a standard
//!   error (fixed, at a bound, not determined) and the lines of action
//!   are left out, and said;
//! - a TOML file: `[uncertainty]` then `"body.mass" = 0.02`, one relative
//!   standard deviation per parameter, independent; and/or `[ranges]` then
//!   `"bumper.force" = [0.8, 1.2]`, the parameter uniform on 0.8 to 1.2
//!   times its value, independent ([`Marginal`]).
//!
//! Names as in the car file and the identification: `body.mass`,
//! `body.yaw_inertia`, `left.masses[0]` (`dampers`, `springs`; `right`
//! alike), `tyres.mu_lateral`, `tyres.cornering_stiffness` (both axles),
//! and `bumper.force` (every segment's force scaled alike).
//!
//! ```
//! use bumpsim_planar::uncertainty::Uncertainty;
//! let u = Uncertainty::parse("[uncertainty]\n\"left.springs[0]\" = 0.15\n", "u.toml".as_ref()).unwrap();
//! assert_eq!((u.names[0].as_str(), u.log_sd[0]), ("left.springs[0]", 0.15));
//! let e = Uncertainty::parse("[uncertainty]\n\"wheel.size\" = 0.1\n", "u.toml".as_ref()).unwrap_err();
//! assert!(e.to_string().contains("wheel.size"));
//! ```

use crate::PlanarCar;
use crate::result::PlanarResult;
use bumpsim_core::units::Dimension;
pub use bumpsim_impact::prediction::{History, Outputs, Scalar};
pub use bumpsim_impact::uncertainty::{
    Identified, Marginal, Model, RANGE_FACTORS, SAME_CAR, UncertaintyError, described, foreign,
    unreadable,
};

/// The planar car's parameters ([`Model`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Planar;

/// The planar car's uncertainty.
pub type Uncertainty = bumpsim_impact::uncertainty::Uncertainty<Planar>;

/// Where a parameter lives in the planar car.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Part {
    /// `body.mass`.
    Mass,
    /// `body.yaw_inertia`.
    YawInertia,
    /// `left.masses[0]`, ...: the side, the kind (masses, dampers,
    /// springs) and the index.
    Chain {
        /// The left chain.
        left: bool,
        /// 0 masses, 1 dampers, 2 springs.
        kind: usize,
        /// From 0.
        index: usize,
    },
    /// `tyres.mu_lateral`.
    MuLateral,
    /// `tyres.cornering_stiffness`.
    Cornering,
    /// `bumper.force`.
    BumperForce,
}

const FIXED: [(&str, Part); 5] = [
    ("body.mass", Part::Mass),
    ("body.yaw_inertia", Part::YawInertia),
    ("tyres.mu_lateral", Part::MuLateral),
    ("tyres.cornering_stiffness", Part::Cornering),
    ("bumper.force", Part::BumperForce),
];

/// The part a name denotes (`None`: not a car parameter).
pub fn part(name: &str) -> Option<Part> {
    if let Some((_, p)) = FIXED.iter().find(|(n, _)| *n == name) {
        return Some(*p);
    }
    let (side, rest) = name.split_once('.')?;
    let left = match side {
        "left" => true,
        "right" => false,
        _ => return None,
    };
    let (what, index) = rest.strip_suffix(']')?.split_once('[')?;
    let kind = ["masses", "dampers", "springs"]
        .iter()
        .position(|k| *k == what)?;
    let index = index.parse().ok()?;
    Some(Part::Chain { left, kind, index })
}

/// The names a car's parameters go by.
fn known(car: &PlanarCar) -> String {
    let mut names = vec!["body.mass".to_string(), "body.yaw_inertia".into()];
    for (side, chain) in [("left", car.left()), ("right", car.right())] {
        for what in ["masses", "dampers", "springs"] {
            names.extend((0..chain.masses.len()).map(|i| format!("{side}.{what}[{i}]")));
        }
    }
    let tail = [
        "tyres.mu_lateral",
        "tyres.cornering_stiffness",
        "bumper.force",
    ];
    names.extend(tail.map(String::from));
    names.join(", ")
}

/// `car` with each part's value multiplied by its factor; `None` when the
/// result is not a valid car.
pub fn scaled(car: &PlanarCar, parts: &[Part], factors: &[f64]) -> Option<PlanarCar> {
    let (mut body, mut tyres, mut beam) = (*car.body(), *car.tyres(), car.beam().clone());
    let (mut left, mut right) = (car.left().clone(), car.right().clone());
    for (part, &f) in parts.iter().zip(factors) {
        match *part {
            Part::Mass => body.mass *= f,
            Part::YawInertia => body.yaw_inertia *= f,
            Part::Chain {
                left: l,
                kind,
                index,
            } => {
                let chain = if l { &mut left } else { &mut right };
                // a linked chain's spring is its link's initial slope: the
                // link is scaled with it (its yield force alike)
                if kind == 2 && !chain.links.is_empty() {
                    let link = chain.links.get_mut(index)?;
                    *link = crate::car::scaled_link(link, f).ok()?;
                }
                let values = [&mut chain.masses, &mut chain.dampers, &mut chain.springs];
                *values.into_iter().nth(kind)?.get_mut(index)? *= f;
            }
            Part::MuLateral => {
                tyres.front.mu_lateral *= f;
                tyres.rear.mu_lateral *= f;
            }
            Part::Cornering => {
                tyres.front.cornering_stiffness *= f;
                tyres.rear.cornering_stiffness *= f;
            }
            Part::BumperForce => {
                let segments = beam.segments.iter();
                let scaled = segments.map(|s| crate::car::scaled(s, f).ok());
                beam.segments = scaled.collect::<Option<Vec<_>>>()?;
            }
        }
    }
    let name = car.name().map(str::to_string);
    PlanarCar::new(body, left, right, beam, tyres)
        .and_then(|c| c.with_crash_boxes(car.crash_boxes()))
        .and_then(|c| c.with_contact_rate(car.contact_rate()))
        .and_then(|c| c.with_effective_width(car.effective_width()))
        .and_then(|c| c.with_damage(car.damage().to_vec()))
        .ok()
        .map(|c| c.with_name(name))
}

impl Model for Planar {
    type Car = PlanarCar;
    type Part = Part;
    const NAMES: &'static str = "body.mass, body.yaw_inertia, left.springs[0], ..., tyres.mu_lateral, tyres.cornering_stiffness, bumper.force";

    fn part(name: &str) -> Option<Part> {
        part(name)
    }

    fn known(car: &PlanarCar) -> String {
        known(car)
    }

    fn scaled(car: &PlanarCar, parts: &[Part], factors: &[f64]) -> Option<PlanarCar> {
        scaled(car, parts, factors)
    }

    fn identified(doc: &serde_json::Value, source: &str) -> Result<Identified, UncertaintyError> {
        identified(doc, source)
    }

    fn value(car: &PlanarCar, part: Part) -> Option<f64> {
        value(car, part)
    }
}

/// A parameter's value in the car, SI (the front axle's for the tyres;
/// `None` for the bumper's force scale).
pub fn value(car: &PlanarCar, part: Part) -> Option<f64> {
    match part {
        Part::Mass => Some(car.body().mass),
        Part::YawInertia => Some(car.body().yaw_inertia),
        Part::Chain { left, kind, index } => {
            let chain = if left { car.left() } else { car.right() };
            let values = [&chain.masses, &chain.dampers, &chain.springs];
            values.get(kind)?.get(index).copied()
        }
        Part::MuLateral => Some(car.tyres().front.mu_lateral),
        Part::Cornering => Some(car.tyres().front.cornering_stiffness),
        Part::BumperForce => None,
    }
}

/// The spreads of a planar identification's JSON document.
fn identified(doc: &serde_json::Value, source: &str) -> Result<Identified, UncertaintyError> {
    let no_parameters = "expected a planar identification's JSON (bumpsim identify --json on a planar study): no result.parameters";
    let no_correlation =
        "no result.uncertainty.correlation: expected a planar identification's JSON";
    let result = doc.get("result").unwrap_or(doc);
    let parameters = result.get("parameters").and_then(|p| p.as_array());
    let parameters = parameters.ok_or_else(|| unreadable(source, no_parameters))?;
    let mut found = Identified::default();
    let mut kept = Vec::new();
    for (i, p) in parameters.iter().enumerate() {
        let name = p.get("name").and_then(|n| n.as_str()).unwrap_or("?");
        let value = p.get("value").and_then(|v| v.as_f64());
        let se = p.get("standard_error").and_then(|v| v.as_f64());
        match (part(name), value, se) {
            (None, ..) => found.left_out.push(format!("{name}: not a car parameter")),
            (_, Some(v), Some(se)) if v > 0.0 && se > 0.0 => {
                kept.push(i);
                found.names.push(name.into());
                found.values.push(v);
                found.log_sd.push(se / v);
            }
            _ => found.left_out.push(format!(
                "{name}: no standard error (fixed, at a bound or not determined)"
            )),
        }
    }
    let matrix = result
        .get("uncertainty")
        .and_then(|u| u.get("correlation"))
        .and_then(|c| c.as_array())
        .ok_or_else(|| unreadable(source, no_correlation))?;
    let pointer = "result.uncertainty.correlation";
    found.correlation =
        bumpsim_impact::uncertainty::kept_correlation(matrix, &kept, pointer, source)?;
    Ok(found)
}

/// The deepest crush of any segment at each instant, m.
fn deepest(r: &PlanarResult) -> Vec<f64> {
    let at = |k: usize| {
        r.crush
            .iter()
            .filter_map(|c| c.get(k))
            .fold(0.0, |m, &c| c.max(m))
    };
    (0..r.time.len()).map(at).collect()
}

/// The largest absolute value, 0 for none.
fn largest(values: &[f64]) -> f64 {
    values.iter().fold(0.0, |m, v| m.max(v.abs()))
}

impl Outputs for PlanarResult {
    fn scalars(&self) -> Vec<Scalar> {
        let scalar = |name, dimension, value| Scalar {
            name,
            dimension,
            value,
        };
        let remaining = self.remaining_crush.iter().copied().fold(0.0, f64::max);
        vec![
            scalar("peak force", Dimension::Force, self.peak_force),
            scalar("maximum crush", Dimension::Length, self.max_compression),
            scalar("largest remaining crush", Dimension::Length, remaining),
            scalar(
                "peak side-member force, left",
                Dimension::Force,
                largest(&self.side_force_left),
            ),
            scalar(
                "peak side-member force, right",
                Dimension::Force,
                largest(&self.side_force_right),
            ),
            scalar(
                "peak yaw rate",
                Dimension::AngularVelocity,
                self.peak_yaw_rate,
            ),
        ]
    }

    fn histories(&self) -> Vec<History> {
        let history = |name, dimension, values: Vec<f64>| History {
            name,
            dimension,
            time: self.time.clone(),
            values,
        };
        vec![
            history("force", Dimension::Force, self.force.clone()),
            history("deepest crush", Dimension::Length, deepest(self)),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_denote_the_car_parts() {
        let right = Part::Chain {
            left: false,
            kind: 1,
            index: 1,
        };
        assert_eq!(part("right.dampers[1]"), Some(right));
        for bad in [
            "left.springs",
            "middle.masses[0]",
            "left.masses[x]",
            "body.width",
        ] {
            assert_eq!(part(bad), None, "{bad}");
        }
    }

    /// A drawn car keeps what the identification gave it: a yielding side
    /// member's link scales with its spring (yield force alike), the
    /// bumper fit's contact rate stays.
    #[test]
    fn a_linked_car_scales_its_links_and_keeps_its_contact_rate() {
        use crate::identify::{LinkLaw, LinkLaws};
        use bumpsim_core::model::MsdModel;
        use bumpsim_impact::bumper::Bumper;
        let chain = MsdModel::new(vec![12.0, 1250.0], vec![3e3], vec![2.5e6]).unwrap();
        let bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
        let car = PlanarCar::symmetric(&chain, &bumper, &crate::car::Layout::default()).unwrap();
        let laws = LinkLaws {
            left: vec![LinkLaw::Yielding],
            right: vec![LinkLaw::Linear],
        };
        let car = laws.apply(&car).unwrap().with_contact_rate(0.3).unwrap();
        let spring = Part::Chain {
            left: true,
            kind: 2,
            index: 0,
        };
        let drawn = scaled(&car, &[spring], &[1.1]).expect("a valid car");
        let (k, slope) = (
            car.left().springs[0],
            drawn.left().links[0].curve().initial_slope(),
        );
        approx::assert_relative_eq!(drawn.left().springs[0], 1.1 * k, max_relative = 1e-12);
        approx::assert_relative_eq!(slope, 1.1 * k, max_relative = 1e-12);
        approx::assert_relative_eq!(drawn.contact_rate(), 0.3, max_relative = 1e-12);
    }

    #[test]
    fn a_chain_identification_is_refused_by_name() {
        let chain = r#"{"dof": 1, "masses": [1.0], "uncertainty": {"names": ["m1"]}}"#;
        let e = Uncertainty::parse(chain, "c.json".as_ref()).unwrap_err();
        assert!(e.to_string().contains("planar identification"), "{e}");
    }
}
