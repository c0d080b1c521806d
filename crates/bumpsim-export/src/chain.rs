//! The chain with nonlinear links ([`bumpsim_core::chain`]) as LS-DYNA and
//! CalculiX decks (issue 46, item 2: "the exports").
//!
//! Masses, dampers, nodes, ids, units, coupling and force history are those
//! of [`crate::lsdyna`] and [`crate::calculix`]; only the springs change.
//! A link with loading curve `F_L(δ)` (δ > 0 in compression) and unloading
//! rule ([`bumpsim_core::link`]) becomes:
//!
//! | link | LS-DYNA | CalculiX | maps |
//! |---|---|---|---|
//! | linear curve, either rule | `*MAT_SPRING_ELASTIC` K = k | `SPRINGA`, `*SPRING` k | exactly |
//! | nonlinear curve, elastic | `*MAT_SPRING_NONLINEAR_ELASTIC`, odd `*DEFINE_CURVE` | `SPRINGA`, `*SPRING, NONLINEAR` odd table | exactly on the table's points |
//! | nonlinear curve, slope k_u ≥ the curve's steepest slope | `*MAT_SPRING_INELASTIC` (LCFD = the curve in the first quadrant, KU = k_u, CTF = 1: compression only) | `C3D8` brick, `*ELASTIC` E, `*PLASTIC` table | exactly in compression |
//! | nonlinear curve, slope k_u below the steepest slope | as above | as above, E from the steepest slope | approximately |
//!
//! Tables: a bilinear or tabulated curve is written at its corners, then
//! to [`CURVE_SPAN`] along its last slope; a progressive one at
//! [`PROGRESSIVE_POINTS`] points up to δ_lim (chords between them, an
//! error below `(δ_lim/N)² · 3 k3 δ_lim / 4`).
//!
//! **Unloading.** bumpsim unloads from δ_max along `k_e = max(k_u,
//! F_max/δ_max, F_max²/(2 E_L))`. When k_u is at least the curve's steepest
//! slope the other two never exceed it and `k_e = k_u` at every δ_max: a
//! spring with one unloading stiffness (LS-DYNA's KU) or an elastic-plastic
//! continuum with modulus `E = k_u L / A` and hardening curve
//! `σ = F_L(δ)/A` against plastic strain `ε_p = (δ − F_L(δ)/k_u)/L`
//! follows it exactly. Below it, LS-DYNA unloads at the steepest slope
//! (the manual: the larger of KU and the curve's largest slope) and so does
//! the brick: the plastic set is smaller than bumpsim's.
//!
//! **Tension.** bumpsim's unloading line runs on into tension. LS-DYNA's
//! inelastic spring (CTF = 1) carries none; CalculiX's brick (isotropic
//! hardening) yields again at −F_max, where bumpsim stays elastic. Both
//! agree with bumpsim until the link is pulled.
//!
//! **The brick.** CalculiX has no hysteretic spring and expands its truss
//! elements into bricks whose knots fail on yielding, so the link is one
//! `C3D8` of length [`BRICK_LENGTH`] and square section [`BRICK_SIDE`]²
//! beside the axis, small-strain (no NLGEOM), Poisson's ratio 0, two
//! lateral faces on symmetry supports (uniaxial stress), its rear face
//! following mass j and its front face mass j+1 along the axis by
//! `*EQUATION`: its axial strain is the crush over L, and `EA/L = k_E`,
//! `σ A = F`. A 100 m brick keeps a 1 m crush at 1 % strain.
//!
//! **Barrier run** ([`Barrier`]): m1 held at the wall, every other mass at
//! the speed towards it: [`bumpsim_core::chain::Drive::Barrier`] with a
//! massless m1 (bumpsim's penalty wall lets m1 bounce off after the
//! rebound; a light m1 barely differs).

use crate::ExportError;
use crate::calculix::{CalculixOptions, dynamic_step};
use crate::cards;
use crate::inp::{self, Print, real};
use crate::layout::{Layout, UnitSystem};
use crate::lsdyna::LsDynaOptions;
use bumpsim_core::chain::Chain;
use bumpsim_core::link::{Curve, Link, Unloading};
use bumpsim_core::model::MsdModel;
use std::fmt::Write;
use std::path::Path;

/// How far the written curves reach, m (beyond any car's crush).
pub const CURVE_SPAN: f64 = 10.0;

/// Points of a progressive curve up to its limit deformation.
pub const PROGRESSIVE_POINTS: usize = 40;

/// Length of a CalculiX link brick, m.
pub const BRICK_LENGTH: f64 = 100.0;

/// Side of a CalculiX link brick's square section, m.
pub const BRICK_SIDE: f64 = 1.0;

/// The loading curve as (δ m, F N) points from (0, 0) to [`CURVE_SPAN`]
/// (or further along the last slope to the last table point).
pub fn loading_points(curve: &Curve) -> Vec<(f64, f64)> {
    let mut d: Vec<f64> = match curve {
        Curve::Linear { .. } => vec![0.0],
        Curve::Bilinear {
            stiffness,
            yield_force,
            ..
        } => vec![0.0, yield_force / stiffness],
        Curve::Progressive { limit, .. } => (0..=PROGRESSIVE_POINTS)
            .map(|i| limit * i as f64 / PROGRESSIVE_POINTS as f64)
            .collect(),
        Curve::Table { points } => points.iter().map(|p| p[0]).collect(),
    };
    if d.last().is_some_and(|&last| last < CURVE_SPAN) {
        d.push(CURVE_SPAN);
    }
    d.into_iter().map(|d| (d, curve.force(d))).collect()
}

/// The stiffness a solver unloads at, N/m: the larger of k_u and the
/// curve's steepest slope.
pub fn solver_unloading(link: &Link) -> f64 {
    match link.unloading() {
        Unloading::Slope(k) => k.max(link.curve().steepest_slope()),
        Unloading::Elastic => link.curve().steepest_slope(),
    }
}

/// How a link is written, and whether the solvers follow bumpsim exactly.
#[derive(Debug, Clone, PartialEq)]
pub struct LinkMapping {
    /// LS-DYNA material keyword.
    pub lsdyna: &'static str,
    /// CalculiX element and card.
    pub calculix: &'static str,
    /// Whether the decks follow bumpsim's link exactly (in compression).
    pub exact: bool,
    /// One line for the deck header.
    pub note: String,
}

/// The mapping of `link`.
pub fn mapping(link: &Link) -> LinkMapping {
    let curve = link.curve();
    let (lsdyna, calculix) = match (curve, link.unloading()) {
        (Curve::Linear { .. }, _) => ("*MAT_SPRING_ELASTIC", "SPRINGA *SPRING"),
        (_, Unloading::Elastic) => (
            "*MAT_SPRING_NONLINEAR_ELASTIC",
            "SPRINGA *SPRING, NONLINEAR",
        ),
        (_, Unloading::Slope(_)) => ("*MAT_SPRING_INELASTIC", "C3D8 *ELASTIC, *PLASTIC"),
    };
    let (exact, note) = match (curve, link.unloading()) {
        (Curve::Linear { .. }, _) => (true, "linear: exact".to_string()),
        (Curve::Progressive { .. }, Unloading::Elastic) => (
            true,
            format!(
                "elastic along the curve: exact at {PROGRESSIVE_POINTS} points, chords between"
            ),
        ),
        (_, Unloading::Elastic) => (true, "elastic along the curve: exact".to_string()),
        (_, Unloading::Slope(k)) if k >= curve.steepest_slope() => (
            true,
            format!(
                "unloading slope {k:e} N/m: exact in compression (tension: see docs/export.md)"
            ),
        ),
        (_, Unloading::Slope(k)) => (
            false,
            format!(
                "APPROXIMATE: unloads at the curve's steepest slope {:e} N/m, bumpsim at max({k:e} N/m, secant, energy term)",
                curve.steepest_slope()
            ),
        ),
    };
    LinkMapping {
        lsdyna,
        calculix,
        exact,
        note,
    }
}

/// The linear chain the decks share (masses, dampers, and each link's
/// initial slope, for the layout, ids and unit checks).
fn skeleton(chain: &Chain) -> MsdModel {
    let springs = chain
        .links()
        .iter()
        .map(|l| l.curve().initial_slope())
        .collect();
    MsdModel::new(chain.masses().to_vec(), chain.dampers().to_vec(), springs)
        .expect("a valid chain is a valid linear chain")
}

/// Checks that every curve point stays finite in the deck's units.
fn check_curves(chain: &Chain, units: UnitSystem) -> Result<(), ExportError> {
    for (j, link) in chain.links().iter().enumerate() {
        let fine = loading_points(link.curve())
            .iter()
            .all(|(d, f)| (d * units.length()).is_finite() && (f * units.force()).is_finite())
            && (solver_unloading(link) * units.stiffness()).is_finite();
        if !fine {
            return Err(ExportError::Overflow {
                what: format!("link {} (its loading curve to {CURVE_SPAN} m)", j + 1),
                units: units.to_string(),
            });
        }
    }
    Ok(())
}

/// The LS-DYNA include of `chain` (see [`crate::lsdyna`] for the rest).
///
/// ```
/// use bumpsim_core::chain::Chain;
/// use bumpsim_core::link::{Curve, Link, Unloading};
/// use bumpsim_export::chain::lsdyna_chain_include;
/// let link = Link::new(Curve::bilinear(1e6, 5e4, 0.1).unwrap(), Unloading::Slope(2e6)).unwrap();
/// let chain = Chain::new(vec![2.0, 900.0], vec![0.0], vec![link]).unwrap();
/// let deck = lsdyna_chain_include(&chain, &Default::default()).unwrap();
/// assert!(deck.contains("*MAT_SPRING_INELASTIC"));
/// ```
pub fn lsdyna_chain_include(chain: &Chain, options: &LsDynaOptions) -> Result<String, ExportError> {
    check_curves(chain, options.layout.units)?;
    crate::lsdyna::include(&skeleton(chain), Some(chain.links()), options)
}

/// Writes link `j`'s material (id `id`), curve (id `id`) and part.
pub(crate) fn lsdyna_link(
    deck: &mut String,
    link: &Link,
    units: UnitSystem,
    id: u64,
    section: u64,
    j: usize,
) {
    let m = mapping(link);
    let title = format!("link {} between m{} and m{}", j + 1, j + 1, j + 2);
    let _ = writeln!(deck, "$ link {}: {}", j + 1, m.note);
    let [_, l, _, f] = units.symbols();
    let points = loading_points(link.curve());
    match (link.curve(), link.unloading()) {
        (Curve::Linear { stiffness }, _) => {
            let unit = format!("{f}/{l}");
            let k = stiffness * units.stiffness();
            cards::discrete_part(deck, cards::Link::Spring, k, &unit, id, section, &title);
            return;
        }
        (_, Unloading::Elastic) => {
            let _ = writeln!(
                deck,
                "*MAT_SPRING_NONLINEAR_ELASTIC\n$    mid       lcd       lcr\n{}{}{}",
                crate::layout::int_field(id, 10),
                crate::layout::int_field(id, 10),
                crate::layout::int_field(0, 10)
            );
            let mut rows: Vec<(f64, f64)> = points.iter().rev().map(|&(d, f)| (-d, -f)).collect();
            rows.extend(points.iter().skip(1).copied());
            let rows = rows
                .into_iter()
                .map(|(d, f)| (d * units.length(), f * units.force()));
            let note = format!(
                "curve of link {}: force ({f}) against elongation ({l}), odd",
                j + 1
            );
            cards::curve(deck, id, Some(&note), rows);
        }
        (_, Unloading::Slope(k)) => {
            let _ = writeln!(
                deck,
                "*MAT_SPRING_INELASTIC\n$    mid      lcfd        ku       ctf  (ku {f}/{l})\n{}{}{}{}",
                crate::layout::int_field(id, 10),
                crate::layout::int_field(id, 10),
                crate::layout::real_field(k * units.stiffness(), 10),
                crate::layout::real_field(1.0, 10)
            );
            // the manual: in the first quadrant whichever way the spring acts
            let rows = points
                .iter()
                .map(|&(d, f)| (d * units.length(), f * units.force()));
            let note = format!(
                "loading curve of link {}: force ({f}) against crush ({l}), first quadrant",
                j + 1
            );
            cards::curve(deck, id, Some(&note), rows);
        }
    }
    cards::part(deck, &title, id, section, id);
}

/// A barrier run of the CalculiX deck: m1 held, the other masses at
/// `speed` towards it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Barrier {
    /// Closing speed, m/s.
    pub speed: f64,
    /// Simulated time, s.
    pub duration: f64,
    /// Fixed time increment, s.
    pub increment: f64,
    /// Print every this many increments.
    pub output_every: usize,
}

/// The CalculiX deck of `chain` (see [`crate::calculix`] for the rest):
/// a model, a transient under `options.analysis`'s force, or a `barrier`
/// run (then without force or initial velocity in `options`).
///
/// ```
/// use bumpsim_core::chain::Chain;
/// use bumpsim_core::link::{Curve, Link, Unloading};
/// use bumpsim_export::chain::calculix_chain_deck;
/// let link = Link::new(Curve::bilinear(1e6, 5e4, 0.0).unwrap(), Unloading::Slope(1e6)).unwrap();
/// let chain = Chain::new(vec![2.0, 900.0], vec![0.0], vec![link]).unwrap();
/// let deck = calculix_chain_deck(&chain, &Default::default(), None).unwrap();
/// assert!(deck.contains("*PLASTIC"));
/// ```
pub fn calculix_chain_deck(
    chain: &Chain,
    options: &CalculixOptions,
    barrier: Option<&Barrier>,
) -> Result<String, ExportError> {
    check_curves(chain, options.layout.units)?;
    if let Some(b) = barrier {
        let clash = options.analysis.is_some() || options.initial_velocity.is_some();
        let speed = b.speed.is_finite() && b.speed > 0.0;
        if clash || !speed || b.output_every == 0 {
            return Err(ExportError::Barrier {
                reason: match (clash, speed) {
                    (true, _) => "a barrier run sets its own velocities and has no force",
                    (_, false) => "the barrier speed must be positive and finite",
                    _ => "the output interval must be at least 1 increment",
                },
            });
        }
    }
    let parts = ChainParts {
        links: chain.links(),
        barrier,
    };
    crate::calculix::deck(&skeleton(chain), Some(&parts), options)
}

/// What [`crate::calculix`] needs of a chain.
pub(crate) struct ChainParts<'a> {
    links: &'a [Link],
    barrier: Option<&'a Barrier>,
}

/// The brick of link j: its 8 node ids.
fn brick_nodes(options: &CalculixOptions, n: usize, j: usize) -> [u64; 8] {
    let first = options.id_offset + 3 * n as u64 + 8 * j as u64 + 1;
    std::array::from_fn(|i| first + i as u64)
}

/// Local corner i of a brick: (along, across 1, across 2) in 0/1.
const CORNERS: [[f64; 3]; 8] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [1.0, 0.0, 1.0],
    [1.0, 1.0, 1.0],
    [0.0, 1.0, 1.0],
];

impl ChainParts<'_> {
    /// Ids beyond the linear deck's: the bricks' nodes.
    pub(crate) fn extra_ids(&self) -> u64 {
        8 * self.links.len() as u64
    }

    fn bricks(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.links.len()).filter(|&j| is_brick(&self.links[j]))
    }

    /// The cross directions of the bricks, in right-handed order with the axis.
    fn across(layout: &Layout) -> [usize; 2] {
        let [a, b] = layout.axis.other_dofs().map(|d| d - 1);
        // det[e_axis·sign, e_a, e_b] > 0 for (x, y, z) cyclic order
        let cyclic = (layout.axis.component + 1) % 3 == a;
        match cyclic == (layout.axis.sign > 0.0) {
            true => [a, b],
            false => [b, a],
        }
    }

    /// Supports beyond the cross directions of the mass nodes: the bricks'
    /// symmetry faces and, in a barrier run, m1 along the axis.
    pub(crate) fn held(
        &self,
        model: &MsdModel,
        options: &CalculixOptions,
    ) -> Vec<(String, usize, usize)> {
        let across = Self::across(&options.layout);
        let mut held = vec![];
        for j in self.bricks() {
            let nodes = brick_nodes(options, model.dof(), j);
            for (corner, node) in CORNERS.iter().zip(nodes) {
                for (c, dir) in across.iter().enumerate() {
                    if corner[1 + c] == 0.0 {
                        held.push((node.to_string(), dir + 1, dir + 1));
                    }
                }
            }
        }
        if self.barrier.is_some() {
            let dof = options.layout.axis.dof();
            held.push(((options.id_offset + 1).to_string(), dof, dof));
        }
        held
    }

    /// The bricks' faces follow their masses along the axis.
    pub(crate) fn ties(&self, deck: &mut String, model: &MsdModel, options: &CalculixOptions) {
        let dof = options.layout.axis.dof();
        for j in self.bricks() {
            let _ = writeln!(
                deck,
                "** link {} brick: rear face follows m{}, front face m{}\n*EQUATION",
                j + 1,
                j + 1,
                j + 2
            );
            for (corner, node) in CORNERS.iter().zip(brick_nodes(options, model.dof(), j)) {
                let mass = options.id_offset + j as u64 + 1 + corner[0] as u64;
                let _ = writeln!(deck, "2\n{node}, {dof}, 1.0, {mass}, {dof}, -1.0");
            }
        }
    }

    /// Link `j` as element `id` in the set `elset`.
    pub(crate) fn calculix_link(
        &self,
        deck: &mut String,
        j: usize,
        elset: &str,
        id: u64,
        options: &CalculixOptions,
    ) {
        let link = &self.links[j];
        let units = options.layout.units;
        let nodes = [j + 1, j + 2].map(|k| options.id_offset + k as u64);
        let _ = writeln!(deck, "** link {}: {}", j + 1, mapping(link).note);
        let points = loading_points(link.curve());
        match (link.curve(), link.unloading()) {
            (Curve::Linear { stiffness }, _) => {
                let k = stiffness * units.stiffness();
                inp::link_element(deck, crate::cards::Link::Spring, elset, id, nodes, k);
            }
            (_, Unloading::Elastic) => {
                inp::element_keyword(deck, "SPRINGA", elset);
                let _ = writeln!(
                    deck,
                    "{id}, {}, {}\n*SPRING, ELSET={elset}, NONLINEAR\n",
                    nodes[0], nodes[1]
                );
                // (force, elongation): compression is negative, odd in δ
                let mut rows: Vec<(f64, f64)> =
                    points.iter().rev().map(|&(d, f)| (-f, -d)).collect();
                rows.extend(points.iter().skip(1).map(|&(d, f)| (f, d)));
                for (force, elongation) in rows {
                    let (f, e) = (force * units.force(), elongation * units.length());
                    let _ = writeln!(deck, "{}, {}", real(f), real(e));
                }
            }
            (_, Unloading::Slope(_)) => self.brick(deck, j, elset, id, options, &points),
        }
    }

    fn brick(
        &self,
        deck: &mut String,
        j: usize,
        elset: &str,
        id: u64,
        options: &CalculixOptions,
        points: &[(f64, f64)],
    ) {
        let (layout, units) = (&options.layout, options.layout.units);
        let (length, side) = (BRICK_LENGTH * units.length(), BRICK_SIDE * units.length());
        let area = side * side;
        let across = Self::across(layout);
        let axis = layout.axis.vector();
        let base = layout.node_position(j);
        let nodes = brick_nodes(options, self.links.len() + 1, j);
        let _ = writeln!(
            deck,
            "** bumpsim-link: link={} elset={elset} area={} component={}\n*NODE, NSET={}NBRICK{}",
            j + 1,
            real(area),
            layout.axis.component,
            options.prefix,
            j + 1
        );
        for (corner, node) in CORNERS.iter().zip(nodes) {
            let mut p = base;
            for c in 0..3 {
                p[c] += corner[0] * length * axis[c];
            }
            // beside the axis: 2 m (j + 1) out along the first cross direction
            p[across[0]] += (2.0 * (j + 1) as f64) * units.length() + corner[1] * side;
            p[across[1]] += corner[2] * side;
            inp::node_line(deck, node, p);
        }
        inp::element_keyword(deck, "C3D8", elset);
        let list: Vec<String> = nodes.iter().map(u64::to_string).collect();
        let _ = writeln!(deck, "{id}, {}", list.join(", "));
        let link = &self.links[j];
        let k = solver_unloading(link);
        let material = format!("{elset}_MATERIAL");
        let modulus = k * units.stiffness() * length / area;
        let _ = writeln!(
            deck,
            "*SOLID SECTION, ELSET={elset}, MATERIAL={material}\n*MATERIAL, NAME={material}\n*ELASTIC\n{}, 0.0\n*DENSITY\n{}",
            real(modulus),
            real(BRICK_DENSITY * units.mass() / units.length().powi(3))
        );
        let table = hardening(points, k);
        if !table.is_empty() {
            deck.push_str("*PLASTIC\n");
            for (force, strain) in table {
                let _ = writeln!(
                    deck,
                    "{}, {}",
                    real(force * units.force() / area),
                    real(strain)
                );
            }
        }
    }

    /// The barrier run's velocities, step and prints.
    pub(crate) fn barrier_run(
        &self,
        deck: &mut String,
        model: &MsdModel,
        options: &CalculixOptions,
    ) -> Result<(), ExportError> {
        let Some(b) = self.barrier else {
            return Ok(());
        };
        let layout = &options.layout;
        let v = -b.speed * layout.axis.sign * layout.units.velocity();
        let nodes: Vec<String> = (2..=model.dof())
            .map(|i| (options.id_offset + i as u64).to_string())
            .collect();
        let rows: Vec<(&str, usize, f64)> = nodes
            .iter()
            .map(|n| (n.as_str(), layout.axis.dof(), v))
            .collect();
        let _ = writeln!(
            deck,
            "** barrier: m1 held at the wall, the car at {} m/s",
            b.speed
        );
        inp::initial_velocity(deck, &rows);
        dynamic_step(deck, b.increment, b.duration, layout.units)?;
        let set = &options.prefix;
        inp::node_print(
            deck,
            &format!("{set}NALL"),
            Print::Every(b.output_every),
            "U",
        );
        for j in self.bricks() {
            let elset = format!("{set}EK{}", j + 1);
            inp::element_print(deck, &elset, Print::Every(b.output_every), "S");
        }
        deck.push_str("*END STEP\n");
        Ok(())
    }
}

/// Density of a brick, kg/m³: 1e-4 kg over its 100 m³.
pub const BRICK_DENSITY: f64 = 1e-6;

fn is_brick(link: &Link) -> bool {
    !matches!(link.curve(), Curve::Linear { .. }) && matches!(link.unloading(), Unloading::Slope(_))
}

/// The hardening table (F N, ε_p) of a curve unloading at `k` (N/m): from
/// the last point still elastic (δ = F/k), plastic strain strictly growing.
fn hardening(points: &[(f64, f64)], k: f64) -> Vec<(f64, f64)> {
    let strain = |(d, f): (f64, f64)| ((d - f / k) / BRICK_LENGTH).max(0.0);
    let tol = |d: f64| 1e-9 * d / BRICK_LENGTH;
    let first = points
        .iter()
        .rposition(|&p| strain(p) <= tol(p.0))
        .unwrap_or(0);
    let mut table: Vec<(f64, f64)> = vec![];
    for &p in &points[first..] {
        let e = if table.is_empty() { 0.0 } else { strain(p) };
        if table.last().is_none_or(|last| e > last.1) {
            table.push((p.1, e));
        }
    }
    if table.len() < 2 {
        return vec![]; // never yields within the span
    }
    table
}

/// Link forces read back from a barrier run (bricks only).
#[derive(Debug, Clone, PartialEq)]
pub struct LinkForces {
    /// Times, s.
    pub time: Vec<f64>,
    /// (0-based link, force N, compression positive, per time).
    pub links: Vec<(usize, Vec<f64>)>,
}

/// Reads the bricks' axial forces of a deck written by
/// [`calculix_chain_deck`] from the `.dat` beside it: the mean axial
/// stress of the integration points times the section.
pub fn read_link_forces(deck_path: &Path) -> Result<LinkForces, ExportError> {
    let fail = |path: &Path, reason: String| ExportError::Dat {
        path: path.into(),
        line: 0,
        reason,
    };
    let deck = std::fs::read_to_string(deck_path)
        .map_err(|e| fail(deck_path, format!("cannot read: {e}")))?;
    let units: UnitSystem = deck
        .lines()
        .find_map(|l| l.strip_prefix("** bumpsim-deck:"))
        .and_then(|l| l.split_whitespace().find_map(|w| w.strip_prefix("units=")))
        .and_then(|u| u.parse().ok())
        .ok_or_else(|| fail(deck_path, "no '** bumpsim-deck:' line".into()))?;
    let dat_path = deck_path.with_extension("dat");
    let text = std::fs::read_to_string(&dat_path)
        .map_err(|e| fail(&dat_path, format!("cannot read: {e}")))?;
    let blocks = crate::dat::parse(&text, &dat_path)?;
    let mut out = LinkForces {
        time: vec![],
        links: vec![],
    };
    for line in deck
        .lines()
        .filter_map(|l| l.strip_prefix("** bumpsim-link:"))
    {
        let value = |key: &str| {
            line.split_whitespace()
                .find_map(|w| w.strip_prefix(key)?.strip_prefix('='))
        };
        let parsed = (|| {
            let link: usize = value("link")?.parse().ok()?;
            let area: f64 = value("area")?.parse().ok()?;
            let component: usize = value("component")?.parse().ok()?;
            Some((link, value("elset")?, area, component))
        })();
        let (link, elset, area, component) =
            parsed.ok_or_else(|| fail(deck_path, format!("bad line '{line}'")))?;
        let blocks = crate::dat::history(&blocks, "stresses", elset)
            .ok_or_else(|| fail(&dat_path, format!("no stresses for set {elset}")))?;
        if out.time.is_empty() {
            out.time = blocks.iter().map(|b| b.time / units.time()).collect();
        }
        let mut force = Vec::with_capacity(blocks.len());
        for b in blocks {
            let stress: Vec<f64> = b
                .rows
                .iter()
                .filter_map(|r| r.values.get(1 + component).copied())
                .collect();
            if stress.is_empty() {
                return Err(fail(
                    &dat_path,
                    format!("an empty stress block for {elset}"),
                ));
            }
            let mean = stress.iter().sum::<f64>() / stress.len() as f64;
            force.push(-mean * area / units.force());
        }
        out.links.push((link - 1, force));
    }
    Ok(out)
}
