//! Which law each side-member link is identified with (issue 46): linear,
//! progressive or yielding ([`bumpsim_core::link`]), and that law's
//! unknowns. A link's unknowns are, besides its initial slope `k` (the
//! chain's `springs[j]`, as for a linear link):
//!
//! | law | curve | further unknowns (searched in ln θ) |
//! |---|---|---|
//! | linear | `F = k δ` | none |
//! | progressive | `F = k δ + k3 δ³` (δ ≤ δ_lim, the tangent beyond) | `cubic[j]` = k3, N/m³ |
//! | yielding | `F = k δ` to `F_y`, then `F_y + r k (δ − F_y/k)` | `yield_force[j]` = F_y, N; `hardening[j]` = r (≤ 1) |
//!
//! The rest of a link stays the start car's: a progressive link's limit
//! δ_lim, and the unloading rule (elastic, or an elastic slope held at the
//! start's ratio to `k`, so that a yielding link unloads at `k` when the
//! start does). A tabulated link keeps its shape, its forces scaled with
//! `k`. The study's `[model] links` chooses the laws
//! ([`LinkLaws::read`]); a link that the start car gives linearly and the
//! study makes nonlinear starts at [`PROGRESSIVE_SCALE`] or [`YIELD_CRUSH`]
//! and [`HARDENING`].

use crate::car::{PlanarCar, PlanarError, SideChain};
use bumpsim_core::link::{Curve, Link, LinkError, Unloading};

/// A progressive link's start: its cubic term doubles the linear force at
/// this crush, `k3 = k / δ₀²`, m (a crash box's stroke is of the order of
/// 0.1 m; half of it).
pub const PROGRESSIVE_SCALE: f64 = 0.05;

/// A progressive link's limit δ_lim when the start car gives none, m: past
/// a side member's useful stroke.
pub const PROGRESSIVE_LIMIT: f64 = 0.3;

/// A yielding link's start: it yields at this crush, `F_y = k δ_y`, m.
pub const YIELD_CRUSH: f64 = 0.03;

/// A yielding link's start hardening ratio r.
pub const HARDENING: f64 = 0.1;

/// The law of one link.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LinkLaw {
    /// `F = k δ`.
    Linear,
    /// `F = k δ + k3 δ³`.
    Progressive,
    /// Bilinear: yield force and hardening.
    Yielding,
    /// The start's table, scaled with `k`.
    Table,
}

impl LinkLaw {
    /// The law of a study's word.
    pub fn parse(word: &str) -> Option<LinkLaw> {
        match word.trim() {
            "linear" => Some(LinkLaw::Linear),
            "progressive" => Some(LinkLaw::Progressive),
            "yielding" => Some(LinkLaw::Yielding),
            _ => None,
        }
    }

    /// The law of `link`.
    pub fn of(link: &Link) -> LinkLaw {
        match link.curve() {
            Curve::Linear { .. } => LinkLaw::Linear,
            Curve::Progressive { .. } => LinkLaw::Progressive,
            Curve::Bilinear { .. } => LinkLaw::Yielding,
            Curve::Table { .. } => LinkLaw::Table,
        }
    }

    /// The law's unknowns besides `k`: name (within the side) and unit.
    pub fn extra(self) -> &'static [(&'static str, &'static str)] {
        match self {
            LinkLaw::Progressive => &[("cubic", "N/m³")],
            LinkLaw::Yielding => &[("yield_force", "N"), ("hardening", "-")],
            LinkLaw::Linear | LinkLaw::Table => &[],
        }
    }

    /// The word a study writes.
    pub fn word(self) -> &'static str {
        match self {
            LinkLaw::Linear => "linear",
            LinkLaw::Progressive => "progressive",
            LinkLaw::Yielding => "yielding",
            LinkLaw::Table => "table",
        }
    }
}

/// The laws of the two chains' links (left, right; front to back).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LinkLaws {
    /// Left chain, one per link.
    pub left: Vec<LinkLaw>,
    /// Right chain, one per link.
    pub right: Vec<LinkLaw>,
}

const EXPECTED: &str = "\"linear\", \"progressive\" or \"yielding\" (every link), a list of them (link by link, both sides), or { left = ..., right = ... }";

impl LinkLaws {
    /// The laws of `car`'s links.
    pub fn of(car: &PlanarCar) -> LinkLaws {
        let laws = |chain: &SideChain| -> Vec<LinkLaw> {
            match chain.links.is_empty() {
                true => vec![LinkLaw::Linear; chain.masses.len()],
                false => chain.links.iter().map(LinkLaw::of).collect(),
            }
        };
        LinkLaws {
            left: laws(car.left()),
            right: laws(car.right()),
        }
    }

    /// The laws of a study's `[model] links` for `car`: a word for every
    /// link, a list of words link by link (both sides), or a table of
    /// `left` and `right`, each a word or a list. An error names the key.
    pub fn read(value: &toml::Value, car: &PlanarCar) -> Result<LinkLaws, PlanarError> {
        let sizes = [car.left().masses.len(), car.right().masses.len()];
        let side = |v: &toml::Value, key: &str, n: usize| -> Result<Vec<LinkLaw>, PlanarError> {
            let word = |w: &toml::Value| {
                w.as_str()
                    .and_then(LinkLaw::parse)
                    .ok_or_else(|| refused(key, &format!("{w}: expected {EXPECTED}")))
            };
            match v {
                toml::Value::Array(list) if list.len() == n => list.iter().map(word).collect(),
                toml::Value::Array(list) => Err(refused(
                    key,
                    &format!("{} laws for a chain of {n} links", list.len()),
                )),
                other => Ok(vec![word(other)?; n]),
            }
        };
        match value {
            toml::Value::Table(t) => {
                if let Some(k) = t.keys().find(|k| *k != "left" && *k != "right") {
                    return Err(refused(
                        &format!("[model] links.{k}"),
                        "unknown key: left or right",
                    ));
                }
                let linear = toml::Value::String("linear".into());
                Ok(LinkLaws {
                    left: side(
                        t.get("left").unwrap_or(&linear),
                        "[model] links.left",
                        sizes[0],
                    )?,
                    right: side(
                        t.get("right").unwrap_or(&linear),
                        "[model] links.right",
                        sizes[1],
                    )?,
                })
            }
            v => Ok(LinkLaws {
                left: side(v, "[model] links", sizes[0])?,
                right: side(v, "[model] links", sizes[1])?,
            }),
        }
    }

    /// Whether every link is linear.
    pub fn all_linear(&self) -> bool {
        self.left
            .iter()
            .chain(&self.right)
            .all(|l| *l == LinkLaw::Linear)
    }

    /// `car` with these laws: a link whose law changes starts at the
    /// defaults of the module from its initial slope; one whose law stays
    /// keeps its curve. All linear: the chains without links.
    pub fn apply(&self, car: &PlanarCar) -> Result<PlanarCar, PlanarError> {
        let chain = |chain: &SideChain, laws: &[LinkLaw], side: &str| {
            if laws.iter().all(|l| *l == LinkLaw::Linear) {
                return Ok(SideChain {
                    links: Vec::new(),
                    ..chain.clone()
                });
            }
            let links = laws
                .iter()
                .enumerate()
                .map(|(j, law)| {
                    let name = format!("{side}.links[{}]", j + 1);
                    let link = chain
                        .link(j)
                        .ok_or_else(|| refused(&name, "no such link"))?;
                    match LinkLaw::of(&link) == *law {
                        true => Ok(link),
                        false => started(*law, link.curve().initial_slope())
                            .map_err(|e| refused(&name, &e.to_string())),
                    }
                })
                .collect::<Result<Vec<_>, PlanarError>>()?;
            Ok(SideChain::linked(
                chain.masses.clone(),
                chain.dampers.clone(),
                links,
            ))
        };
        let left = chain(car.left(), &self.left, "left")?;
        let right = chain(car.right(), &self.right, "right")?;
        rebuilt(car, left, right)
    }
}

/// `car` with chains `left` and `right` (its body, beam, tyres, crash
/// boxes and name).
pub(super) fn rebuilt(
    car: &PlanarCar,
    left: SideChain,
    right: SideChain,
) -> Result<PlanarCar, PlanarError> {
    PlanarCar::new(*car.body(), left, right, car.beam().clone(), *car.tyres())
        .and_then(|c| c.with_crash_boxes(car.crash_boxes()))
        .and_then(|c| c.with_effective_width(car.effective_width()))
        .map(|c| c.with_name(car.name().map(str::to_string)))
}

/// A refused `links` setting: its key and what it expects (no value: the
/// setting is text, and "links = NaN -" stood in the message).
fn refused(key: &str, expected: &str) -> PlanarError {
    PlanarError::Missing {
        name: key.into(),
        expected: expected.into(),
    }
}

/// A link of `law` with initial slope `k` at the module's default start.
fn started(law: LinkLaw, k: f64) -> Result<Link, LinkError> {
    match law {
        LinkLaw::Progressive => Link::new(
            Curve::progressive(
                k,
                k / (PROGRESSIVE_SCALE * PROGRESSIVE_SCALE),
                PROGRESSIVE_LIMIT,
            )?,
            Unloading::Elastic,
        ),
        LinkLaw::Yielding => Link::new(
            Curve::bilinear(k, k * YIELD_CRUSH, HARDENING)?,
            Unloading::Slope(k),
        ),
        LinkLaw::Linear | LinkLaw::Table => Link::linear(k),
    }
}

/// The further unknowns' values of `link` (see [`LinkLaw::extra`]).
pub(super) fn values(link: &Link) -> Vec<f64> {
    match link.curve() {
        Curve::Progressive { cubic, .. } => vec![*cubic],
        Curve::Bilinear {
            yield_force,
            hardening,
            ..
        } => vec![*yield_force, *hardening],
        Curve::Linear { .. } | Curve::Table { .. } => Vec::new(),
    }
}

/// `template` with initial slope `k` and further unknowns `extra` (its
/// other features kept, see the module).
pub(super) fn with_values(template: &Link, k: f64, extra: &[f64]) -> Result<Link, LinkError> {
    let k0 = template.curve().initial_slope();
    let unloading = match template.unloading() {
        Unloading::Elastic => Unloading::Elastic,
        Unloading::Slope(u) => Unloading::Slope(u * k / k0),
    };
    let curve = match (template.curve(), extra) {
        (Curve::Progressive { limit, .. }, [cubic]) => Curve::progressive(k, *cubic, *limit)?,
        (Curve::Bilinear { .. }, [yield_force, hardening]) => {
            Curve::bilinear(k, *yield_force, *hardening)?
        }
        (Curve::Table { points }, _) => {
            Curve::table(points.iter().map(|p| [p[0], p[1] * k / k0]).collect())?
        }
        _ => Curve::linear(k)?,
    };
    Link::new(curve, unloading)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::car::Layout;
    use bumpsim_core::model::MsdModel;
    use bumpsim_impact::bumper::Bumper;

    fn car() -> PlanarCar {
        let chain =
            MsdModel::new(vec![8.0, 20.0, 1200.0], vec![2e3, 3e3], vec![1.5e6, 2e6]).unwrap();
        let bumper = Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
        PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap()
    }

    fn laws(text: &str) -> Result<LinkLaws, PlanarError> {
        let table: toml::Table = toml::from_str(&format!("links = {text}")).unwrap();
        LinkLaws::read(&table["links"], &car())
    }

    #[test]
    fn a_study_names_the_laws_and_the_car_takes_them() {
        use LinkLaw::*;
        assert_eq!(laws("\"progressive\"").unwrap().left, [Progressive; 2]);
        let l = laws("[\"yielding\", \"linear\"]").unwrap();
        assert_eq!(
            (l.left.as_slice(), l.right.as_slice()),
            (&[Yielding, Linear][..], &[Yielding, Linear][..])
        );
        let l = laws("{ left = \"progressive\" }").unwrap();
        assert_eq!((l.left[0], l.right[0]), (Progressive, Linear));
        let applied = l.apply(&car()).unwrap();
        assert_eq!(LinkLaws::of(&applied), l);
        let link = &applied.left().links[0];
        assert_eq!(link.curve().initial_slope(), car().left().springs[0]);
        // a link's values come back through its unknowns
        let again = with_values(link, 2e6, &[4e8]).unwrap();
        assert_eq!(values(&again), [4e8]);
        assert_eq!(again.curve().initial_slope(), 2e6);
        assert!(
            laws("\"linear\"")
                .unwrap()
                .apply(&car())
                .unwrap()
                .left()
                .is_linear()
        );
    }

    #[test]
    fn hostile_laws_are_named() {
        for (text, words) in [
            ("\"plastic\"", "[model] links"),
            ("[\"linear\"]", "1 laws for a chain of 2"),
            ("{ middle = \"linear\" }", "links.middle"),
            ("{ left = 3 }", "links.left"),
            ("[\"linear\", 1.0]", "expected"),
        ] {
            let e = laws(text).unwrap_err().to_string();
            assert!(e.contains(words), "{text}: {e}");
        }
    }
}
