//! The coupled CalculiX deck: the parametric bumper, the striker and the
//! MSD car of `bumpsim export calculix`, joined by the export's coupling.
//!
//! Geometry (SI, the export's layout): the car's axis is +x, m1 at the
//! origin and the car behind it (+x); the crash boxes run from their rear
//! nodes at (0, ±y_c, 0) forward to the beam at x = −L_box; the beam spans
//! y = ±W/2. Every beam node faces a striker node 0.1 m ahead with a
//! compression-only `SPRINGA` (`*SPRING, NONLINEAR`: zero force in tension,
//! k_contact / n per node in compression): the contact. A barrier's nodes are
//! fixed; a pendulum's follow its mass node along x by `*EQUATION`.
//!
//! Coupling: the crash boxes' rear nodes are the export's attachment nodes
//! (each follows m1 along x by `*EQUATION`), and are held across the axis
//! and in rotation, as if bolted to a rigid rail. Beam nodes are held out
//! of plane (z).
//!
//! Analysis: `*DYNAMIC, ALPHA=-0.05` (Hilber–Hughes–Taylor with CalculiX's
//! default slight damping of the highest frequencies, see [`ALPHA`]; what
//! it dissipates shows in the energy balance) at the given increment, which
//! CalculiX cuts back (to 1/256) where the contact opens or closes and
//! Newton's method would not converge at the full step; small strains
//! (no NLGEOM: the beams stay in the small-strain range where B32R's
//! expansion matches beam theory), fixed increment. Outputs to the `.dat`
//! file: U, V of the car (and pendulum), U of the beam nodes, the barrier's
//! total reaction force (RF of its nodes), total internal
//! (ELSE) and kinetic (ELKE) energies of beam, boxes and contact springs.

use crate::FeError;
use crate::bumper::BumperMesh;
use bumpsim_core::model::MsdModel;
use bumpsim_export::calculix::{CalculixOptions, calculix_deck};
use bumpsim_export::inp::{self, Print, real};
use bumpsim_impact::impact::Scenario;
use std::fmt::Write;

/// Distance of the striker's nodes ahead of the beam, m (the contact
/// springs' length; any positive value, the springs act on elongation).
pub const CONTACT_LENGTH: f64 = 0.1;

/// Span of the contact springs' table, m (beyond any crush).
pub const CONTACT_SPAN: f64 = 1.0;

/// The Hilber–Hughes–Taylor α of the run: CalculiX's default, a slight
/// numerical damping of the highest frequencies. With α = 0 (the
/// trapezoidal rule) the contact's opening and closing pumped energy into
/// the beam's fast modes and a run blew up after separation.
pub const ALPHA: f64 = -0.05;

/// The run settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Run {
    /// Fixed time increment, s.
    pub increment: f64,
    /// Simulated time, s.
    pub duration: f64,
}

/// What the reader needs to know about a written deck.
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    /// Beam node ids, left to right.
    pub beam: Vec<u64>,
    /// Car node ids m1..mn.
    pub car: Vec<u64>,
    /// The pendulum's mass node, if any.
    pub pendulum: Option<u64>,
    /// Contact stiffness per beam node, N/m.
    pub contact_node: f64,
    /// Lateral positions of the crash boxes after snapping, m.
    pub crash_box_y: [f64; 2],
}

/// Builds the deck text and its layout.
pub fn coupled_deck(
    mesh: &BumperMesh,
    car: &MsdModel,
    scenario: Scenario,
    run: &Run,
) -> Result<(String, Layout), FeError> {
    mesh.validate()?;
    let mut deck = String::new();
    let _ = writeln!(
        deck,
        "*HEADING\nbumpsim {}: {} coupled to a {}-DOF MSD car (spec §8)\n** units: kg, m, s, N, Pa",
        env!("CARGO_PKG_VERSION"),
        mesh.name.as_deref().unwrap_or("parametric bumper"),
        car.dof()
    );
    let mut ids = Ids::default();
    let beam = beam_nodes(&mut deck, mesh, &mut ids);
    let (chains, crash_box_y) = crash_boxes(&mut deck, mesh, &beam, &mut ids);
    let rear = chains.clone().map(|c| c[c.len() - 1]);
    let x = -mesh.crash_boxes.length - CONTACT_LENGTH;
    let striker = striker_nodes(&mut deck, &beam, x, &mut ids);
    let pendulum = pendulum_node(&mut deck, scenario, x - CONTACT_LENGTH, &mut ids);
    elements(&mut deck, mesh, &beam, &striker, &chains, &mut ids);
    let contact_node = mesh.contact() / beam.len() as f64;
    materials(&mut deck, mesh, contact_node);
    let speed = match scenario {
        Scenario::Barrier { speed } => Some(-speed),
        Scenario::Impactor { .. } => None,
    };
    // the car's ids follow the bumper's: CalculiX sizes its node arrays by
    // the largest id, and a sparse numbering (offset 100 000) made every
    // increment 20 times slower
    let car_offset = ids.node.max(ids.element);
    let options = CalculixOptions {
        initial_velocity: speed,
        title: "the MSD car".into(),
        id_offset: car_offset,
        attach: rear.to_vec(),
        ..Default::default()
    };
    deck += &calculix_deck(car, &options)?;
    supports(&mut deck, scenario, pendulum, &striker, &rear);
    initial(&mut deck, scenario);
    step(&mut deck, run, pendulum.is_some());
    let layout = Layout {
        beam: beam.iter().map(|b| b.0).collect(),
        car: (1..=car.dof() as u64).map(|i| car_offset + i).collect(),
        pendulum,
        contact_node,
        crash_box_y,
    };
    Ok((deck, layout))
}

#[derive(Default)]
struct Ids {
    node: u64,
    element: u64,
}

impl Ids {
    fn node(&mut self) -> u64 {
        self.node += 1;
        self.node
    }
    fn element(&mut self) -> u64 {
        self.element += 1;
        self.element
    }
}

/// 2·n + 1 nodes (B32R) along y at x = −L_box.
fn beam_nodes(deck: &mut String, mesh: &BumperMesh, ids: &mut Ids) -> Vec<(u64, f64)> {
    let x = -mesh.crash_boxes.length;
    inp::node_keyword(deck, "FE_BEAM");
    mesh.beam_node_y()
        .into_iter()
        .map(|y| {
            let id = ids.node();
            inp::node_line(deck, id, [x, y, 0.0]);
            (id, y)
        })
        .collect()
}

/// Crash-box nodes from the beam node nearest ±offset back to x = 0;
/// returns each box's node chain (front to rear) and the snapped positions.
fn crash_boxes(
    deck: &mut String,
    mesh: &BumperMesh,
    beam: &[(u64, f64)],
    ids: &mut Ids,
) -> ([Vec<u64>; 2], [f64; 2]) {
    let c = &mesh.crash_boxes;
    inp::node_keyword(deck, "FE_BOXN");
    let mut chain = |index: usize| {
        let (front, y) = beam[index];
        let mut nodes = vec![front];
        for j in 1..=2 * c.elements {
            let id = ids.node();
            let x = -c.length + c.length * j as f64 / (2 * c.elements) as f64;
            inp::node_line(deck, id, [x, y, 0.0]);
            nodes.push(id);
        }
        (nodes, y)
    };
    let [l, r] = mesh.crash_box_nodes();
    let (left, right) = (chain(l), chain(r));
    ([left.0, right.0], [left.1, right.1])
}

fn striker_nodes(deck: &mut String, beam: &[(u64, f64)], x: f64, ids: &mut Ids) -> Vec<u64> {
    inp::node_keyword(deck, "FE_STRIKER");
    beam.iter()
        .map(|&(_, y)| {
            let id = ids.node();
            inp::node_line(deck, id, [x, y, 0.0]);
            id
        })
        .collect()
}

fn pendulum_node(deck: &mut String, scenario: Scenario, x: f64, ids: &mut Ids) -> Option<u64> {
    let Scenario::Impactor { mass, .. } = scenario else {
        return None;
    };
    let id = ids.node();
    inp::node_keyword(deck, "FE_PENDULUM");
    inp::node_line(deck, id, [x, 0.0, 0.0]);
    let e = ids.element();
    inp::mass_element(deck, "FE_EPENDULUM", e, id, mass);
    Some(id)
}

fn elements(
    deck: &mut String,
    mesh: &BumperMesh,
    beam: &[(u64, f64)],
    striker: &[u64],
    chains: &[Vec<u64>; 2],
    ids: &mut Ids,
) {
    inp::element_keyword(deck, "B32R", "FE_EBEAM");
    for k in 0..mesh.beam.elements {
        let e = ids.element();
        let (a, b, c) = (beam[2 * k].0, beam[2 * k + 1].0, beam[2 * k + 2].0);
        let _ = writeln!(deck, "{e}, {a}, {b}, {c}");
    }
    inp::element_keyword(deck, "B32R", "FE_EBOX");
    for chain in chains {
        for k in 0..mesh.crash_boxes.elements {
            let e = ids.element();
            let nodes = &chain[2 * k..2 * k + 3];
            let _ = writeln!(deck, "{e}, {}, {}, {}", nodes[0], nodes[1], nodes[2]);
        }
    }
    inp::element_keyword(deck, "SPRINGA", "FE_ECONTACT");
    for (&(b, _), &s) in beam.iter().zip(striker) {
        let e = ids.element();
        let _ = writeln!(deck, "{e}, {b}, {s}");
    }
}

fn material(deck: &mut String, name: &str, m: &crate::bumper::Material) {
    let _ = writeln!(
        deck,
        "*MATERIAL, NAME={name}\n*ELASTIC\n{}, {}\n*DENSITY\n{}",
        real(m.youngs_modulus),
        real(m.poisson),
        real(m.density)
    );
    if !m.yield_curve.is_empty() {
        deck.push_str("*PLASTIC\n");
        for p in &m.yield_curve {
            let _ = writeln!(deck, "{}, {}", real(p[0]), real(p[1]));
        }
    }
}

/// A box `*BEAM SECTION`; `first` is the section's local 1-direction
/// (its depth).
fn section(deck: &mut String, set: &str, s: &crate::bumper::BoxSection, first: &str) {
    let _ = writeln!(
        deck,
        "*BEAM SECTION, ELSET=FE_E{set}, MATERIAL=FE_{set}_MATERIAL, SECTION=BOX\n{}, {}, {w}, {w}, {w}, {w}\n{first}",
        real(s.depth),
        real(s.height),
        w = real(s.wall)
    );
}

fn materials(deck: &mut String, mesh: &BumperMesh, contact_node: f64) {
    material(deck, "FE_BEAM_MATERIAL", &mesh.beam.material);
    material(deck, "FE_BOX_MATERIAL", &mesh.crash_boxes.material);
    section(deck, "BEAM", &mesh.beam.section, "1.0, 0.0, 0.0");
    section(deck, "BOX", &mesh.crash_boxes.section, "0.0, 1.0, 0.0");
    let _ = writeln!(
        deck,
        "** contact: compression only, {} N/m per beam node\n*SPRING, ELSET=FE_ECONTACT, NONLINEAR\n\n{}, {}\n0.0, 0.0\n0.0, {}",
        real(contact_node),
        real(-contact_node * CONTACT_SPAN),
        real(-CONTACT_SPAN),
        real(CONTACT_SPAN)
    );
}

fn supports(
    deck: &mut String,
    scenario: Scenario,
    pendulum: Option<u64>,
    striker: &[u64],
    rear: &[u64; 2],
) {
    let mut held = vec![("FE_BEAM".to_string(), 3, 3)];
    held.extend(rear.iter().map(|r| (r.to_string(), 2, 6)));
    match (scenario, pendulum) {
        (Scenario::Impactor { .. }, Some(p)) => {
            held.extend([("FE_STRIKER".into(), 2, 3), (p.to_string(), 2, 3)]);
            inp::boundary(deck, &held);
            deck.push_str("*EQUATION\n");
            for s in striker {
                let _ = writeln!(deck, "2\n{s}, 1, 1.0, {p}, 1, -1.0");
            }
        }
        _ => {
            held.push(("FE_STRIKER".into(), 1, 3));
            inp::boundary(deck, &held);
        }
    }
}

fn initial(deck: &mut String, scenario: Scenario) {
    let ([first, second], v) = match scenario {
        Scenario::Barrier { speed } => (["FE_BEAM", "FE_BOXN"], -speed),
        Scenario::Impactor { speed, .. } => (["FE_STRIKER", "FE_PENDULUM"], speed),
    };
    inp::initial_velocity(deck, &[(first, 1, v), (second, 1, v)]);
}

fn step(deck: &mut String, run: &Run, pendulum: bool) {
    let count = 4 * ((run.duration / run.increment).ceil() as u64 + 10);
    let _ = writeln!(
        deck,
        "*STEP, INC={count}\n*DYNAMIC, ALPHA={ALPHA}\n{}, {}, {}, {}",
        real(run.increment),
        real(run.duration),
        real(run.increment / 256.0),
        real(run.increment)
    );
    inp::node_print(deck, "BUMPSIM_NALL", Print::Every(1), "U, V");
    if pendulum {
        inp::node_print(deck, "FE_PENDULUM", Print::Default, "U, V");
    }
    inp::node_print(deck, "FE_BEAM", Print::Default, "U");
    if !pendulum {
        // the barrier's reaction: its force, for campaigns reading the .dat
        inp::node_print(deck, "FE_STRIKER", Print::Totals, "RF");
    }
    for set in ["FE_EBEAM", "FE_EBOX", "FE_ECONTACT"] {
        inp::element_print(deck, set, Print::Totals, "ELSE");
    }
    for set in ["FE_EBEAM", "FE_EBOX"] {
        inp::element_print(deck, set, Print::Totals, "ELKE");
    }
    deck.push_str("*END STEP\n");
}
