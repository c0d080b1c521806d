//! A car of either chain form as a deck: the one place that picks the
//! writer, so `bumpsim export` stays thin (issue 46). A linear car
//! ([`MsdModel`]) goes to [`crate::lsdyna::lsdyna_include`] and
//! [`crate::calculix::calculix_deck`], a chain with nonlinear links
//! ([`Chain`]) to [`crate::chain::lsdyna_chain_include`] and
//! [`crate::chain_calculix::calculix_chain_deck`]; the options are the same.
//!
//! The critical explicit step of a chain ([`critical_time_step`]) is that of
//! [`crate::timestep`] with every link at its steepest slope (loading or
//! unloading, [`bumpsim_core::link::Link::steepest_slope`]), the front link
//! as a spring from m1 to a fixed wall and a wall link (second load path,
//! rebound link) as one from its mass: the largest row sum `ω² = max_i (Σ
//! k_j (1/m_j + 1/m_(j+1)) + Σ k_w / m_i)` over the links and wall springs
//! at mass i (Gershgorin) bounds the highest frequency the links can reach.
//!
//! ```
//! use bumpsim_core::chain::Chain;
//! use bumpsim_core::link::{Curve, Link, Unloading};
//! use bumpsim_export::car_deck::{CarModel, lsdyna_car_include};
//! let link = Link::new(Curve::bilinear(1e6, 5e4, 0.1).unwrap(), Unloading::Slope(2e6)).unwrap();
//! let chain = Chain::new(vec![2.0, 900.0], vec![0.0], vec![link]).unwrap();
//! let deck = lsdyna_car_include(CarModel::Chain(&chain), &Default::default()).unwrap();
//! assert!(deck.contains("*MAT_SPRING_INELASTIC"));
//! ```

use crate::ExportError;
use crate::calculix::CalculixOptions;
use crate::lsdyna::LsDynaOptions;
use bumpsim_core::chain::Chain;
use bumpsim_core::model::MsdModel;

/// The model of a car file, in either chain form.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CarModel<'a> {
    /// Linear springs and dampers.
    Linear(&'a MsdModel),
    /// Nonlinear links (and perhaps a front link).
    Chain(&'a Chain),
}

impl CarModel<'_> {
    /// Number of masses.
    pub fn dof(&self) -> usize {
        match self {
            CarModel::Linear(model) => model.dof(),
            CarModel::Chain(chain) => chain.dof(),
        }
    }
}

/// The LS-DYNA include of the car.
pub fn lsdyna_car_include(
    model: CarModel<'_>,
    options: &LsDynaOptions,
) -> Result<String, ExportError> {
    match model {
        CarModel::Linear(model) => crate::lsdyna::lsdyna_include(model, options),
        CarModel::Chain(chain) => crate::chain::lsdyna_chain_include(chain, options),
    }
}

/// The CalculiX deck of the car (a transient under `options.analysis`'s
/// force when it has one).
pub fn calculix_car_deck(
    model: CarModel<'_>,
    options: &CalculixOptions,
) -> Result<String, ExportError> {
    match model {
        CarModel::Linear(model) => crate::calculix::calculix_deck(model, options),
        CarModel::Chain(chain) => crate::chain_calculix::calculix_chain_deck(chain, options, None),
    }
}

/// The deck's own notes of where it departs from bumpsim's model: every
/// comment line (`$` in LS-DYNA, `**` in CalculiX) that says
/// `APPROXIMATE`, as the front end repeats them to the user (a link whose
/// unloading slope is below its curve's steepest, in either deck).
pub fn approximations(deck: &str) -> Vec<&str> {
    deck.lines()
        .map(str::trim)
        .filter(|l| l.starts_with('$') || l.starts_with("**"))
        .filter(|l| l.contains("APPROXIMATE"))
        .map(|l| l.trim_start_matches(['$', '*', ' ']))
        .collect()
}

/// The critical step of a chain: Gershgorin's row sums of `k (1/m_j +
/// 1/m_(j+1))` over the links at their steepest slopes, `k/m` on the mass a
/// wall spring (front link, second load path, rebound link) pushes, and the
/// dampers' rates likewise; `min(2/ω, 2/γ)` as [`crate::timestep`].
fn chain_step(chain: &Chain) -> f64 {
    let slope = |l: &bumpsim_core::link::Link| l.steepest_slope().max(f64::MIN_POSITIVE);
    let m = chain.masses();
    let mut omega2 = vec![0.0; m.len()];
    let mut gamma = vec![0.0; m.len()];
    if let Some(front) = chain.front() {
        omega2[0] += slope(front) / m[0];
    }
    for (j, (link, c)) in chain.links().iter().zip(chain.dampers()).enumerate() {
        let inverse = 1.0 / m[j] + 1.0 / m[j + 1];
        for node in [j, j + 1] {
            omega2[node] += slope(link) * inverse;
            gamma[node] += c * inverse;
        }
    }
    for (_, _, wall) in crate::chain::wall_links(chain) {
        omega2[wall.mass] += slope(&wall.link) / m[wall.mass];
    }
    let limit = |rate: f64| match rate > 0.0 {
        true => 2.0 / rate,
        false => f64::INFINITY,
    };
    let omega = omega2.iter().copied().fold(0.0, f64::max).sqrt();
    limit(omega).min(limit(gamma.iter().copied().fold(0.0, f64::max)))
}

/// The car's critical explicit time step, s (infinite without links).
pub fn critical_time_step(model: CarModel<'_>) -> f64 {
    match model {
        CarModel::Linear(model) => crate::timestep::critical_time_step(model),
        CarModel::Chain(chain) => chain_step(chain),
    }
}

/// [`crate::timestep::below_minimum`] of the car: its critical step when
/// below `minimum` (s).
pub fn below_minimum(model: CarModel<'_>, minimum: f64) -> Result<Option<f64>, ExportError> {
    match model {
        CarModel::Linear(model) => crate::timestep::below_minimum(model, minimum),
        CarModel::Chain(_) if !(minimum.is_finite() && minimum >= 0.0) => {
            Err(ExportError::MinTimeStep { value: minimum })
        }
        CarModel::Chain(_) => {
            let step = critical_time_step(model);
            Ok((step < minimum).then_some(step))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ExportError;
    use bumpsim_core::link::{Curve, Link, Unloading};

    /// One link: the bound is that of a linear spring at the steepest slope
    /// (here the unloading's, 4e6 N/m on 1 kg and 1 kg: ω² = 8e6).
    #[test]
    fn the_steepest_slope_bounds_the_step() {
        let link = Link::new(
            Curve::bilinear(1e6, 5e4, 0.1).unwrap(),
            Unloading::Slope(4e6),
        )
        .unwrap();
        let chain = Chain::new(vec![1.0, 1.0], vec![0.0], vec![link.clone()]).unwrap();
        let dt = critical_time_step(CarModel::Chain(&chain));
        assert!((dt - 2.0 / 8e6_f64.sqrt()).abs() < 1e-12 * dt, "{dt}");
        // a front link adds k/m1 at m1 (the wall does not move)
        let front = chain.clone().with_front(link);
        let dt = critical_time_step(CarModel::Chain(&front));
        assert!((dt - 2.0 / 12e6_f64.sqrt()).abs() < 1e-9 * dt, "{dt}");
        let deck = calculix_car_deck(CarModel::Chain(&chain), &Default::default()).unwrap();
        assert!(deck.contains("*PLASTIC"));
    }

    /// Two masses, a yielding front link, a yielding second load path on
    /// m2 after 0.15 m and an elastic rebound link on m2 after 0.3 m.
    fn walled() -> Chain {
        let yielding = || {
            Link::new(
                Curve::bilinear(1e6, 5e4, 0.1).unwrap(),
                Unloading::Slope(2e6),
            )
            .unwrap()
        };
        let elastic = Link::new(
            Curve::progressive(2e5, 5e6, 0.5).unwrap(),
            Unloading::Elastic,
        );
        Chain::new(vec![5.0, 900.0], vec![0.0], vec![yielding()])
            .unwrap()
            .with_front(yielding())
            .with_path(1, 0.15, yielding())
            .unwrap()
            .with_rebound(1, 0.3, elastic.unwrap())
            .unwrap()
    }

    /// The first fields (width `width`) of the data lines of every
    /// `keyword` block, the first `skip` data lines of each left out and at
    /// most `take` read.
    fn fields(deck: &str, keyword: &str, width: usize, skip: usize, take: usize) -> Vec<String> {
        let mut out = vec![];
        let mut lines = deck.lines().peekable();
        while let Some(line) = lines.next() {
            if line.trim() != keyword {
                continue;
            }
            let data = std::iter::from_fn(|| lines.next_if(|l| !l.starts_with('*')));
            let data: Vec<&str> = data.filter(|l| !l.starts_with('$')).collect();
            for l in data.iter().skip(skip).take(take) {
                out.push(l[..width.min(l.len())].trim().to_string());
            }
        }
        out
    }

    fn unique(ids: &[String]) -> bool {
        let set: std::collections::BTreeSet<&String> = ids.iter().collect();
        set.len() == ids.len()
    }

    /// LS-DYNA: each wall link on its own fixed node (ids offset + 3n + 3
    /// and + 4), the path inelastic with its curve at zero up to the gap,
    /// the rebound link nonlinear elastic with zero force in tension and
    /// up to −gap; every node, part, curve and element id once.
    #[test]
    fn the_lsdyna_include_writes_both_wall_links_with_their_gaps() {
        let options = LsDynaOptions {
            id_offset: 100,
            ..Default::default()
        };
        let deck = lsdyna_car_include(CarModel::Chain(&walled()), &options).unwrap();
        assert!(deck.contains("$ second load path: the barrier's fixed node 109 to m2, touching after a gap of 0.15 m"), "{deck}");
        assert!(
            deck.contains(
                "$ rebound link: the barrier's fixed node 110 to m2, touching after a gap of 0.3 m"
            ),
            "{deck}"
        );
        assert_eq!(deck.matches("*MAT_SPRING_INELASTIC").count(), 3);
        assert_eq!(deck.matches("*MAT_SPRING_NONLINEAR_ELASTIC").count(), 1);
        let nodes = fields(&deck, "*NODE", 8, 0, usize::MAX);
        assert!(
            nodes.contains(&"109".to_string()) && unique(&nodes),
            "{nodes:?}"
        );
        let parts = fields(&deck, "*PART", 10, 1, 1);
        assert!(unique(&parts) && parts.len() == 4, "{parts:?}");
        let curves = fields(&deck, "*DEFINE_CURVE", 10, 0, 1);
        assert!(unique(&curves) && curves.len() == 4, "{curves:?}");
        let elements = fields(&deck, "*ELEMENT_DISCRETE", 8, 0, usize::MAX);
        assert!(unique(&elements) && elements.len() == 4, "{elements:?}");
        // the curves' points (two 20-wide fields after the id line)
        let points = |id: &str| -> Vec<(f64, f64)> {
            let block = deck.split("*DEFINE_CURVE").skip(1).find(|b| {
                b.lines()
                    .filter(|l| !l.starts_with('$'))
                    .nth(1)
                    .is_some_and(|l| l.get(..10).map(str::trim) == Some(id))
            });
            let rows = block
                .unwrap()
                .lines()
                .filter(|l| !l.starts_with('$'))
                .skip(2);
            rows.take_while(|l| !l.starts_with('*'))
                .map(|l| {
                    (
                        l[..20].trim().parse().unwrap(),
                        l[20..].trim().parse().unwrap(),
                    )
                })
                .collect()
        };
        let path = points("109");
        assert_eq!(
            &path[..3],
            &[(0.0, 0.0), (0.15, 0.0), (0.2, 5e4)],
            "{path:?}"
        );
        let rebound = points("110");
        let tail = &rebound[rebound.len() - 3..];
        assert_eq!(tail, &[(-0.3, 0.0), (0.0, 0.0), (10.0, 0.0)], "{rebound:?}");
        // no force before the gap nor in tension, compression beyond it
        let pushes = |p: &(f64, f64)| (p.0 >= -0.3) == (p.1 == 0.0);
        assert!(rebound.iter().all(pushes), "{rebound:?}");
    }

    /// CalculiX: each wall link from its held wall node (ids offset +
    /// 11n + 2 and + 3: 124 and 125 here); the elastic rebound link a `SPRING2`
    /// with its table zero up to the gap, the yielding path a brick to its
    /// free node 126 and a one-sided `SPRINGA` from there (k_p = 2 k_u =
    /// 4e6 N/m after 0.15 m); neither approximate; every node and element
    /// id once.
    #[test]
    fn the_calculix_deck_writes_both_wall_links_with_their_gaps() {
        let options = CalculixOptions {
            id_offset: 100,
            ..Default::default()
        };
        let deck = calculix_car_deck(CarModel::Chain(&walled()), &options).unwrap();
        for set in ["BUMPSIM_EPATH_WALL, 1, 3", "BUMPSIM_EREBOUND_WALL, 1, 3"] {
            assert!(deck.contains(set), "{set}: {deck}");
        }
        assert!(deck.contains("124, 126, 102\n*SPRING, ELSET=BUMPSIM_EPATH, NONLINEAR\n-4.000000000000e7, -1.015000000000e1\n0.000000000000e0, -1.500000000000e-1\n0.000000000000e0, 1.000000000000e1"), "{deck}");
        assert!(deck.contains("*ELEMENT, TYPE=C3D8, ELSET=BUMPSIM_EPATHB\n126, 127,"));
        assert!(deck.contains(
            "** second load path brick: rear face follows node 124, front face node 126"
        ));
        assert!(deck.contains("125, 125, 102\n*SPRING, ELSET=BUMPSIM_EREBOUND, NONLINEAR"));
        assert!(approximations(&deck).is_empty(), "{deck}");
        // axis +x: compression is positive in ccx's table (its measure)
        assert!(
            deck.contains(
                "0.000000000000e0, 0.000000000000e0\n0.000000000000e0, 3.000000000000e-1"
            )
        );
        let mut nodes = vec![];
        let mut elements = vec![];
        let mut block = "";
        for line in deck.lines() {
            if line.starts_with('*') {
                block = line;
            } else if !line.starts_with("**") {
                let first = line.split(',').next().unwrap().trim().to_string();
                match block {
                    b if b.starts_with("*NODE,") => nodes.push(first),
                    b if b.starts_with("*ELEMENT,") => elements.push(first),
                    _ => {}
                }
            }
        }
        assert!(
            unique(&nodes) && unique(&elements),
            "{nodes:?} {elements:?}"
        );
        assert!(nodes.contains(&"124".to_string()) && elements.contains(&"125".to_string()));
    }

    /// Hostile gaps: one that folds the curve's first point onto it (the
    /// deck's 13 digits), and one beyond any unit; a wall link on a mass
    /// the chain does not have is refused when the chain is built.
    #[test]
    fn a_gap_that_folds_the_curve_is_refused_by_name() {
        let link = || {
            Link::new(
                Curve::bilinear(1e6, 5e4, 0.1).unwrap(),
                Unloading::Slope(2e6),
            )
            .unwrap()
        };
        let chain = Chain::new(vec![5.0, 900.0], vec![0.0], vec![link()]).unwrap();
        let folded = chain.clone().with_path(1, 1e12, link()).unwrap();
        for deck in [
            lsdyna_car_include(CarModel::Chain(&folded), &Default::default()).err(),
            calculix_car_deck(CarModel::Chain(&folded), &Default::default()).err(),
        ] {
            let error = deck.expect("refused").to_string();
            assert!(
                error.contains(
                    "the second load path: its gap of 1000000000000 m leaves its curve degenerate"
                ),
                "{error}"
            );
        }
        let huge = chain.clone().with_rebound(0, 1e307, link()).unwrap();
        let options = LsDynaOptions {
            layout: crate::layout::Layout {
                units: crate::layout::UnitSystem::MmSTonne,
                ..Default::default()
            },
            ..Default::default()
        };
        let error = lsdyna_car_include(CarModel::Chain(&huge), &options).unwrap_err();
        assert!(matches!(error, ExportError::Overflow { .. }), "{error}");
        assert!(error.to_string().contains("the rebound link"), "{error}");
        assert!(chain.with_path(2, 0.0, link()).is_err());
    }
}
