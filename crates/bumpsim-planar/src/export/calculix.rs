//! The planar car as a CalculiX deck (CalculiX CrunchiX User's Manual 2.20),
//! with force histories a complete linear transient analysis, and reading
//! its `.dat` results back.
//!
//! CalculiX's mass elements carry no rotary inertia, so the body is two
//! point masses M/2 at `(0, ±r)` from the CG, `r = √(I_z/M)`: together they
//! have the mass M and the yaw inertia M r² = I_z exactly. Their x
//! displacements give X = (x₁ + x₂)/2 and ψ = (x₂ − x₁)/(2r); an `*EQUATION`
//! keeps their y displacements equal. Every other body point (ξ, η) follows
//! linearly (small yaw): x = X − ψ η, y = Y + ψ ξ. So:
//!
//! - chain masses (`*ELEMENT, TYPE=MASS`) move freely along x; their y
//!   follows the body at the bumper line (ξ = x_f), as in [`crate::drive`];
//! - the links are `SPRING2` on x (a fixed direction: a `SPRINGA` along the
//!   nodes' current line turns over once a crush beyond the spacing crosses
//!   them) and `DASHPOTA`; each chain's last link ends on a body node tied by
//!   `*EQUATION`s: x to the body, y to the chain's line (a DASHPOTA acts along
//!   the current line between its nodes even in a linear step, so every node
//!   of a chain shares one y);
//! - the user's attachment nodes follow their side's front mass in x and
//!   the body in y;
//! - the front forces (lever rule, see [`super`]) act on the front masses'
//!   x; their lateral parts, and everything on a side without masses, act on
//!   the body nodes by the same linear relations (virtual work), summed per
//!   node and direction into one `*AMPLITUDE` each;
//! - z is fixed (`*BOUNDARY`); `*DYNAMIC, DIRECT, ALPHA=0.0` (trapezoidal
//!   rule) with a fixed increment; `*NODE PRINT` of U of the body and mass
//!   nodes (set `<prefix>NOUT`).
//!
//! The deck is geometrically linear (no NLGEOM): it matches the drive model
//! while the yaw stays small (the lever arm of a world-fixed force changes
//! by ψ·x_f; 1 % of the moment needs ψ ≲ 0.01·|η|/x_f when the force is
//! off-centre).

use super::{PlanarExport, PlanarExportError, Side, check, front_forces, half_spacing, sides};
use crate::car::PlanarCar;
use bumpsim_export::ExportError;
use bumpsim_export::calculix::{MAX_CALCULIX_ID, amplitude, check_prefix, dynamic_step};
use bumpsim_export::cards::Link;
use bumpsim_export::inp::{self, Print, real};
use std::collections::BTreeMap;
use std::fmt::Write;
use std::path::Path;

/// A degree of freedom: (node, 1 = x or 2 = y).
type Dof = (u64, u8);

/// A linear combination of independent degrees of freedom.
type Terms = Vec<(Dof, f64)>;

/// The node ids: the two body nodes, then per side the mass nodes and the
/// chain's body end node.
struct Nodes {
    body: [u64; 2],
    /// Per side: mass nodes and end node.
    masses: [Vec<u64>; 2],
    ends: [u64; 2],
    last: u64,
}

impl Nodes {
    fn new(car: &PlanarCar, offset: u64) -> Nodes {
        let mut next = offset + 2;
        let mut side = |n: usize| {
            let masses: Vec<u64> = (1..=n as u64).map(|k| next + k).collect();
            next += n as u64 + 1;
            (masses, next)
        };
        let (left, left_end) = side(car.left().masses.len());
        let (right, right_end) = side(car.right().masses.len());
        Nodes {
            body: [offset + 1, offset + 2],
            masses: [left, right],
            ends: [left_end, right_end],
            last: next,
        }
    }

    /// x of the front of a side: its first mass, or the body at the tip.
    fn front_x(&self, body: &Body, side: &Side) -> Terms {
        match self.masses[side.index].first() {
            Some(front) => vec![((*front, 1), 1.0)],
            None => body.x(side.eta),
        }
    }
}

/// The body's rigid motion at a point, in the two body nodes' dofs.
struct Body {
    nodes: [u64; 2],
    r: f64,
}

impl Body {
    /// x of body point (ξ, η): X − ψ η.
    fn x(&self, eta: f64) -> Terms {
        let [one, two] = self.nodes;
        let k = eta / (2.0 * self.r);
        vec![((one, 1), 0.5 + k), ((two, 1), 0.5 - k)]
    }

    /// y of body point (ξ, η): Y + ψ ξ.
    fn y(&self, xi: f64) -> Terms {
        let [one, two] = self.nodes;
        let k = xi / (2.0 * self.r);
        vec![((one, 2), 1.0), ((one, 1), -k), ((two, 1), k)]
    }
}

fn radius(car: &PlanarCar) -> f64 {
    (car.body().yaw_inertia / car.body().mass).sqrt()
}

/// Writes the deck text: the model, and with forces the analysis.
pub fn calculix_deck(car: &PlanarCar, options: &PlanarExport) -> Result<String, PlanarExportError> {
    check(car, options)?;
    check_prefix(&options.prefix)?;
    if options.output_every == 0 {
        return Err(ExportError::OutputInterval.into());
    }
    let nodes = checked_nodes(car, options)?;
    let body = Body {
        nodes: nodes.body,
        r: radius(car),
    };
    let mut deck = String::new();
    model(&mut deck, car, options, &nodes);
    constraints(&mut deck, car, options, &nodes, &body);
    if let Some(forces) = &options.forces {
        analysis(&mut deck, car, options, &nodes, &body, forces)?;
    }
    Ok(deck)
}

fn checked_nodes(car: &PlanarCar, options: &PlanarExport) -> Result<Nodes, ExportError> {
    let offset = options.id_offset;
    let masses = car.left().masses.len() + car.right().masses.len();
    // nodes 4 + masses, then elements: masses 2 + masses, links 2 · masses
    let last = offset.saturating_add(6 + 4 * masses as u64);
    if last > MAX_CALCULIX_ID {
        let limit = MAX_CALCULIX_ID;
        return Err(ExportError::IdRange {
            offset,
            last,
            limit,
        });
    }
    let nodes = Nodes::new(car, offset);
    let attach = options.attach.concat();
    bumpsim_export::check_attach(&attach, offset + 1..=nodes.last, MAX_CALCULIX_ID)?;
    Ok(nodes)
}

fn model(deck: &mut String, car: &PlanarCar, options: &PlanarExport, nodes: &Nodes) {
    let (set, u) = (&options.prefix, options.units);
    let [m, l, t, f] = u.symbols();
    let _ = writeln!(
        deck,
        "** {}\n** bumpsim {}: planar car (spec 9), linear, car forward = +x, left = +y\n** units: mass {m}, length {l}, time {t}, force {f}; frictionless tyres",
        bumpsim_core::names::printable(&options.title),
        env!("CARGO_PKG_VERSION")
    );
    let (r, x_f) = (radius(car), car.body().cg_behind_bumper);
    let mut list = vec![(nodes.body[0], [0.0, r]), (nodes.body[1], [0.0, -r])];
    for side in sides(car) {
        for (i, id) in nodes.masses[side.index].iter().enumerate() {
            list.push((*id, [x_f - i as f64 * options.spacing, side.eta]));
        }
        let n = side.chain.masses.len() as f64;
        list.push((
            nodes.ends[side.index],
            [x_f - n * options.spacing, side.eta],
        ));
    }
    inp::node_keyword(deck, &format!("{set}NALL"));
    for (id, [x, y]) in list {
        inp::node_line(deck, id, super::place(options, [x, y, 0.0]));
    }
    let mut element = nodes.last;
    let mut mass = |deck: &mut String, node: u64, value: f64| {
        element += 1;
        let name = format!("{set}M{node}");
        inp::mass_element(deck, &name, element, node, value * u.mass());
    };
    for node in nodes.body {
        mass(deck, node, 0.5 * car.body().mass);
    }
    for side in sides(car) {
        for (id, m) in nodes.masses[side.index].iter().zip(&side.chain.masses) {
            mass(deck, *id, *m);
        }
    }
    links(deck, car, options, nodes, element);
}

/// SPRING2 on x and DASHPOTA along each chain, the last link to the body
/// end node: a SPRINGA along the nodes' current line turns over once a
/// crush beyond the spacing crosses them ([`inp::axial_link_element`]);
/// the chain masses move along x (small yaw), so x is the link's axis.
fn links(deck: &mut String, car: &PlanarCar, options: &PlanarExport, nodes: &Nodes, first: u64) {
    let (set, u) = (&options.prefix, options.units);
    let mut element = first;
    for side in sides(car) {
        let c = side.chain;
        let ids = &nodes.masses[side.index];
        for j in 0..c.masses.len() {
            let back = ids.get(j + 1).copied().unwrap_or(nodes.ends[side.index]);
            let kinds = [
                (Link::Spring, "K", c.springs[j] * u.stiffness()),
                (Link::Damper, "C", c.dampers[j] * u.damping()),
            ];
            for (link, letter, value) in kinds.into_iter().filter(|k| k.2 > 0.0) {
                element += 1;
                let name = format!("{set}{letter}{element}");
                inp::axial_link_element(deck, link, &name, element, [ids[j], back], 1, value);
            }
        }
    }
}

/// `*EQUATION`: `dependent` = Σ terms (zero terms left out).
fn equation(deck: &mut String, dependent: Dof, terms: &[(Dof, f64)]) {
    let terms: Vec<&(Dof, f64)> = terms.iter().filter(|(_, c)| *c != 0.0).collect();
    let mut line = format!("{}\n{}, {}, 1.0", terms.len() + 1, dependent.0, dependent.1);
    for ((node, dof), c) in terms {
        let _ = write!(line, ", {node}, {dof}, {}", real(-c));
    }
    let _ = writeln!(deck, "*EQUATION\n{line}");
}

fn constraints(
    deck: &mut String,
    car: &PlanarCar,
    options: &PlanarExport,
    nodes: &Nodes,
    body: &Body,
) {
    let set = &options.prefix;
    let x_f = car.body().cg_behind_bumper;
    let [one, two] = nodes.body;
    let _ = writeln!(deck, "** the body: its two nodes move together in y");
    equation(deck, (two, 2), &[((one, 2), 1.0)]);
    let _ = writeln!(
        deck,
        "** chain masses follow the body in y; chain ends in x"
    );
    for side in sides(car) {
        for id in &nodes.masses[side.index] {
            equation(deck, (*id, 2), &body.y(x_f));
        }
        let end = nodes.ends[side.index];
        equation(deck, (end, 1), &body.x(side.eta));
        // on the chain's line: a DASHPOTA acts along the current node line
        equation(deck, (end, 2), &body.y(x_f));
    }
    for side in sides(car) {
        attachments(deck, options, nodes, body, &side, x_f);
    }
    inp::boundary(deck, &[(format!("{set}NALL"), 3, 3)]);
    let moving: Vec<String> = std::iter::once(nodes.body.to_vec())
        .chain(nodes.masses.iter().cloned())
        .flatten()
        .map(|n| n.to_string())
        .collect();
    let _ = writeln!(deck, "*NSET, NSET={set}NOUT");
    for chunk in moving.chunks(8) {
        let _ = writeln!(deck, "{}", chunk.join(", "));
    }
    if let Some(v) = options.speed {
        let v = v * options.units.velocity();
        inp::initial_velocity(deck, &[(&format!("{set}NOUT"), 1, v)]);
    }
}

/// The user's nodes of one side follow its front mass in x (the body, for
/// a side without masses) and the body in y.
fn attachments(
    deck: &mut String,
    options: &PlanarExport,
    nodes: &Nodes,
    body: &Body,
    side: &Side,
    x_f: f64,
) {
    let attach = &options.attach[side.index];
    if attach.is_empty() {
        return;
    }
    let x = nodes.front_x(body, side);
    let name = ["left", "right"][side.index];
    let _ = writeln!(
        deck,
        "** {name} attachment nodes follow the front of the side"
    );
    for node in attach {
        equation(deck, (*node, 1), &x);
        equation(deck, (*node, 2), &body.y(x_f));
    }
}

/// The amplitudes, loads, step and output.
fn analysis(
    deck: &mut String,
    car: &PlanarCar,
    options: &PlanarExport,
    nodes: &Nodes,
    body: &Body,
    forces: &super::Forces,
) -> Result<(), PlanarExportError> {
    let (set, u) = (&options.prefix, options.units);
    let x_f = car.body().cg_behind_bumper;
    let histories = front_forces(car, forces);
    let mut loads: BTreeMap<Dof, Vec<f64>> = BTreeMap::new();
    let mut add = |terms: &[(Dof, f64)], history: &[f64]| {
        for (dof, c) in terms.iter().filter(|(_, c)| *c != 0.0) {
            let sum = loads
                .entry(*dof)
                .or_insert_with(|| vec![0.0; history.len()]);
            sum.iter_mut().zip(history).for_each(|(s, f)| *s += c * f);
        }
    };
    for side in sides(car) {
        let [fx, fy] = &histories[side.index];
        add(&nodes.front_x(body, &side), fx);
        add(&body.y(x_f), fy);
    }
    for ((node, dof), history) in &loads {
        let points = history
            .iter()
            .enumerate()
            .map(|(k, f)| (k as f64 * forces.step * u.time(), f * u.force()));
        amplitude(deck, &format!("{set}F{node}_{dof}"), points);
    }
    let duration = forces.duration();
    dynamic_step(deck, options.increment.unwrap_or(forces.step), duration, u)?;
    for (node, dof) in loads.keys() {
        let _ = writeln!(
            deck,
            "*CLOAD, AMPLITUDE={set}F{node}_{dof}\n{node}, {dof}, 1.0"
        );
    }
    let every = Print::Every(options.output_every);
    inp::node_print(deck, &format!("{set}NOUT"), every, "U");
    deck.push_str("*END STEP\n");
    Ok(())
}

/// The histories of a CalculiX run of a deck from [`calculix_deck`], SI.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FeHistories {
    /// Time, s (from the start of the step).
    pub time: Vec<f64>,
    /// CG displacement along world x, m.
    pub x: Vec<f64>,
    /// CG displacement along world y, m.
    pub y: Vec<f64>,
    /// Yaw, rad (counter-clockwise seen from above).
    pub yaw: Vec<f64>,
    /// Displacement u_i of each chain mass relative to the body along x, m
    /// (left chain first, as [`crate::drive::Driven::chains`]).
    pub chains: Vec<Vec<f64>>,
}

impl FeHistories {
    /// World-x displacement of the body point (ξ, η), m: X − ψ η (linear,
    /// as the deck).
    pub fn sensor_x(&self, point: [f64; 2]) -> Vec<f64> {
        self.x
            .iter()
            .zip(&self.yaw)
            .map(|(x, psi)| x - psi * point[1])
            .collect()
    }
}

/// Reads the `.dat` results of a run of the deck that `car` and `options`
/// wrote (the same values: ids, units, prefix).
pub fn read_calculix(
    car: &PlanarCar,
    options: &PlanarExport,
    dat: &Path,
) -> Result<FeHistories, PlanarExportError> {
    let text = std::fs::read_to_string(dat).map_err(|e| ExportError::Dat {
        path: dat.into(),
        line: 0,
        reason: format!("cannot read: {e}"),
    })?;
    let blocks = bumpsim_export::dat::parse(&text, dat)?;
    let set = format!("{}NOUT", options.prefix);
    let missing = |line: usize, reason: String| ExportError::Dat {
        path: dat.into(),
        line,
        reason,
    };
    let blocks = bumpsim_export::dat::history(&blocks, "displacements", &set)
        .ok_or_else(|| missing(0, format!("no displacement blocks for set {set}")))?;
    let nodes = Nodes::new(car, options.id_offset);
    let (u, r, b) = (options.units, radius(car), half_spacing(car));
    let mut out = FeHistories {
        chains: vec![vec![]; nodes.masses[0].len() + nodes.masses[1].len()],
        ..Default::default()
    };
    for block in blocks {
        let first = block.rows.first().map_or(0, |row| row.line);
        let at = |node: u64, c: usize| {
            block
                .rows
                .iter()
                .find(|row| row.id == Some(node) && row.values.len() == 3)
                .map(|row| row.values[c] / u.length())
                .ok_or_else(|| missing(first, format!("node {node} missing from the block")))
        };
        let [one, two] = nodes.body;
        let (x1, x2) = (at(one, 0)?, at(two, 0)?);
        let (x, psi) = (0.5 * (x1 + x2), (x2 - x1) / (2.0 * r));
        out.time.push(block.time / u.time());
        out.x.push(x);
        out.y.push(at(one, 1)?);
        out.yaw.push(psi);
        let chain_nodes = nodes.masses[0].iter().map(|n| (n, b));
        let chain_nodes = chain_nodes.chain(nodes.masses[1].iter().map(|n| (n, -b)));
        for (k, (node, eta)) in chain_nodes.enumerate() {
            out.chains[k].push(at(*node, 0)? - (x - psi * eta));
        }
    }
    Ok(out)
}
