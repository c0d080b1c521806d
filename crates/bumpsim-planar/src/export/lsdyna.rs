//! The planar car as an LS-DYNA keyword include (LS-DYNA Keyword User's
//! Manual, vol. I), in fixed format through [`bumpsim_export::cards`].
//!
//! - **Body**: `*CONSTRAINED_NODAL_RIGID_BODY_INERTIA_SPC` with mass M, yaw
//!   inertia I_z (I_xx = I_yy = I_z: those rotations are constrained) and the
//!   initial velocity, at a CG node; its centre of mass is constrained in z
//!   and in roll and pitch (CMO = 1, CON1 = 3, CON2 = 4), so the car moves in
//!   x–y and yaws about z. The body's node set: the CG node, the chains' rear
//!   end nodes and the body halves of the chains' joints.
//! - **Chain masses**: each a `*CONSTRAINED_NODAL_RIGID_BODY` of three nodes
//!   (the mass node, one `spacing/2` behind it on the sliding axis and one
//!   `spacing/2` above it), `*ELEMENT_MASS` m/3 on each, and a
//!   `*CONSTRAINED_JOINT_TRANSLATIONAL` to the body: the mass slides along
//!   the body's x axis and is guided laterally by the body, as in
//!   [`crate::drive`]. The front mass's rigid body also holds the user's
//!   attachment nodes of its side.
//! - **Links**: one `*SECTION_DISCRETE`, per spring a `*MAT_SPRING_ELASTIC`
//!   and per non-zero damper a `*MAT_DAMPER_VISCOUS` with its `*PART`, and
//!   `*ELEMENT_DISCRETE` between neighbouring mass nodes (the last to the
//!   body's end node of the side).
//! - Optional: `*INITIAL_VELOCITY_NODE` of the chain nodes, `*DEFINE_CURVE`
//!   and `*LOAD_NODE_POINT` of the front forces per side and direction, and
//!   the history databases of the CG and mass nodes.
//!
//! The chain masses sit `spacing` apart behind the bumper line (discrete
//! elements need distinct nodes), so their share of the yaw inertia,
//! Σ m_i ξ_i², is slightly below that of the drive model (all on the bumper
//! line); a chain rigid body adds `m (spacing/2)²`-sized inertia. Both are
//! negligible against I_z for spacings of a few cm.

use super::{PlanarExport, PlanarExportError, Side, check, front_forces, place, sides};
use crate::car::PlanarCar;
use bumpsim_export::cards::{self, FieldNames, Inertia, Link};
use bumpsim_export::lsdyna::MAX_ID;
use bumpsim_export::{ExportError, check_attach};
use std::fmt::Write;

/// The ids of one chain mass: nodes (mass, axis, off-axis), their body
/// partners, and the rigid body (also its node set).
struct MassIds {
    chain: [u64; 3],
    body: [u64; 3],
    rigid: u64,
}

/// The ids of one side.
struct SideIds {
    masses: Vec<MassIds>,
    /// The body node at the rear end of the chain (the tip, for no masses).
    end: u64,
    /// Spring and damper element (= part = material) ids per link.
    springs: Vec<u64>,
    dampers: Vec<u64>,
    /// Curves of the front force along x and y.
    curves: [u64; 2],
}

/// Every id of the include: `offset + k`, nodes first (dense), then the rest.
struct Ids {
    cg: u64,
    sides: [SideIds; 2],
    body: u64,
    section: u64,
    last_node: u64,
    last: u64,
}

fn allocate(car: &PlanarCar, offset: u64) -> Ids {
    let next = std::cell::Cell::new(offset);
    let id = || {
        next.set(next.get() + 1);
        next.get()
    };
    let cg = id();
    let mut sides = sides(car).map(|side| {
        let masses = side
            .chain
            .masses
            .iter()
            .map(|_| MassIds {
                chain: [id(), id(), id()],
                body: [id(), id(), id()],
                rigid: 0,
            })
            .collect();
        SideIds {
            masses,
            end: id(),
            springs: vec![],
            dampers: vec![],
            curves: [0; 2],
        }
    });
    let last_node = next.get();
    for (side, ids) in self::sides(car).iter().zip(sides.iter_mut()) {
        let n = side.chain.masses.len();
        ids.masses.iter_mut().for_each(|m| m.rigid = id());
        ids.springs = (0..n).map(|_| id()).collect();
        ids.dampers = (0..n).map(|_| id()).collect();
        ids.curves = [id(), id()];
    }
    let (body, section) = (id(), id());
    Ids {
        cg,
        sides,
        body,
        section,
        last_node,
        last: next.get(),
    }
}

/// Checks the offset, the id range and the attachment nodes.
fn ids(car: &PlanarCar, options: &PlanarExport) -> Result<Ids, ExportError> {
    let offset = options.id_offset;
    if offset >= MAX_ID {
        let limit = MAX_ID;
        return Err(ExportError::IdOffset { offset, limit });
    }
    let ids = allocate(car, offset);
    if ids.last > MAX_ID {
        let (last, limit) = (ids.last, MAX_ID);
        return Err(ExportError::IdRange {
            offset,
            last,
            limit,
        });
    }
    let attach: Vec<u64> = options.attach.concat();
    check_attach(&attach, offset + 1..=ids.last_node, MAX_ID)?;
    Ok(ids)
}

/// Writes the include text.
pub fn lsdyna_include(
    car: &PlanarCar,
    options: &PlanarExport,
) -> Result<String, PlanarExportError> {
    check(car, options)?;
    let ids = ids(car, options)?;
    let mut deck = String::new();
    header(&mut deck, car, options);
    nodes(&mut deck, car, options, &ids);
    body(&mut deck, car, options, &ids);
    for side in sides(car) {
        chain(&mut deck, &side, options, &ids.sides[side.index]);
    }
    links(&mut deck, car, options, &ids);
    if let Some(v) = options.speed {
        let nodes: Vec<u64> = ids
            .sides
            .iter()
            .flat_map(|s| s.masses.iter().flat_map(|m| m.chain))
            .collect();
        let [_, l, t, _] = options.units.symbols();
        let velocity = [v * options.units.velocity(), 0.0, 0.0];
        cards::initial_velocity_nodes(&mut deck, &nodes, velocity, [l, t]);
    }
    loads(&mut deck, car, options, &ids);
    if let Some(dt) = options.output_interval {
        let mass_nodes = ids
            .sides
            .iter()
            .flat_map(|s| s.masses.iter().map(|m| m.chain[0]));
        let nodes: Vec<u64> = std::iter::once(ids.cg).chain(mass_nodes).collect();
        cards::history(&mut deck, dt * options.units.time(), &nodes);
    }
    deck.push_str("*END\n");
    Ok(deck)
}

fn header(deck: &mut String, car: &PlanarCar, options: &PlanarExport) {
    let what = format!(
        "planar car, {} + {} chain masses on a rigid body (spec 9)",
        car.left().masses.len(),
        car.right().masses.len()
    );
    cards::header(deck, &options.title, &what, options.units);
    let _ = writeln!(
        deck,
        "$ car forward = global +x, left = +y; frictionless tyres; ids from {}",
        options.id_offset + 1
    );
}

/// Positions (body frame from the CG, m) of a chain mass's three nodes.
fn mass_points(side: &Side, i: usize, spacing: f64, x_f: f64) -> [[f64; 3]; 3] {
    let xi = x_f - i as f64 * spacing;
    [
        [xi, side.eta, 0.0],
        [xi - 0.5 * spacing, side.eta, 0.0],
        [xi, side.eta, 0.5 * spacing],
    ]
}

fn nodes(deck: &mut String, car: &PlanarCar, options: &PlanarExport, ids: &Ids) {
    let x_f = car.body().cg_behind_bumper;
    let mut list = vec![(ids.cg, place(options, [0.0; 3]))];
    for side in sides(car) {
        let side_ids = &ids.sides[side.index];
        for (i, m) in side_ids.masses.iter().enumerate() {
            let points = mass_points(&side, i, options.spacing, x_f);
            for ((chain, body), point) in m.chain.iter().zip(m.body).zip(points) {
                list.push((*chain, place(options, point)));
                list.push((body, place(options, point)));
            }
        }
        let n = side.chain.masses.len() as f64;
        let end = [x_f - n * options.spacing, side.eta, 0.0];
        list.push((side_ids.end, place(options, end)));
    }
    list.sort_by_key(|(id, _)| *id);
    // every node belongs to a rigid body, which carries the constraints
    cards::node(deck, &list, Some([0, 0]));
}

fn body(deck: &mut String, car: &PlanarCar, options: &PlanarExport, ids: &Ids) {
    let u = options.units;
    let mut members = vec![ids.cg];
    for side in sides(car) {
        let s = &ids.sides[side.index];
        members.extend(s.masses.iter().flat_map(|m| m.body));
        members.push(s.end);
        if s.masses.is_empty() {
            members.extend(&options.attach[side.index]);
        }
    }
    cards::node_set(deck, ids.body, &members);
    let b = car.body();
    let inertia = b.yaw_inertia * u.mass() * u.length().powi(2);
    let speed = options.speed.unwrap_or(0.0) * u.velocity();
    let body = Inertia {
        centre: place(options, [0.0; 3]),
        node: ids.cg,
        mass: b.mass * u.mass(),
        moments: [inertia; 3],
        velocity: [speed, 0.0, 0.0],
    };
    let _ = writeln!(
        deck,
        "$ body: mass, yaw inertia about the CG; z, roll and pitch fixed"
    );
    cards::nodal_rigid_body_inertia_spc(deck, ids.body, ids.body, &body, [3, 4]);
}

fn chain(deck: &mut String, side: &Side, options: &PlanarExport, ids: &SideIds) {
    let unit = options.units.symbols()[0];
    let name = ["left", "right"][side.index];
    for (i, (m, mass)) in ids.masses.iter().zip(&side.chain.masses).enumerate() {
        let _ = writeln!(deck, "$ {name} chain mass {}", i + 1);
        for node in m.chain {
            let third = mass / 3.0 * options.units.mass();
            cards::element_mass(deck, node, node, third, unit);
        }
        let mut members = m.chain.to_vec();
        if i == 0 {
            members.extend(&options.attach[side.index]);
        }
        cards::node_set(deck, m.rigid, &members);
        cards::nodal_rigid_body(deck, m.rigid, m.rigid);
        let [c, b] = [m.chain, m.body];
        cards::joint_translational(deck, [c[0], b[0], c[1], b[1], c[2], b[2]]);
    }
}

fn links(deck: &mut String, car: &PlanarCar, options: &PlanarExport, ids: &Ids) {
    let u = options.units;
    let [_, l, t, f] = u.symbols();
    cards::discrete_section(deck, ids.section, FieldNames::All);
    let mut elements = vec![];
    for side in sides(car) {
        let s = &ids.sides[side.index];
        let c = side.chain;
        let name = ["left", "right"][side.index];
        for j in 0..c.masses.len() {
            let front = s.masses[j].chain[0];
            let back = s.masses.get(j + 1).map_or(s.end, |m| m.chain[0]);
            let to = if j + 1 < c.masses.len() {
                format!("m{}", j + 2)
            } else {
                "body".into()
            };
            let title = format!("{name} spring k{} between m{} and {to}", j + 1, j + 1);
            let (k, unit) = (c.springs[j] * u.stiffness(), format!("{f}/{l}"));
            cards::discrete_part(
                deck,
                Link::Spring,
                k,
                &unit,
                s.springs[j],
                ids.section,
                &title,
            );
            elements.push((s.springs[j], front, back));
            if c.dampers[j] > 0.0 {
                let title = title.replace("spring k", "damper c");
                let (d, unit) = (c.dampers[j] * u.damping(), format!("{f}*{t}/{l}"));
                cards::discrete_part(
                    deck,
                    Link::Damper,
                    d,
                    &unit,
                    s.dampers[j],
                    ids.section,
                    &title,
                );
                elements.push((s.dampers[j], front, back));
            }
        }
    }
    if elements.is_empty() {
        return;
    }
    cards::element_discrete_header(deck, FieldNames::All);
    for (id, n1, n2) in elements {
        cards::element_discrete_line(deck, id, id, n1, n2);
    }
}

/// Per side and direction, the summed front force as a curve and a nodal
/// load on the front node (the tip body node for a side without masses).
fn loads(deck: &mut String, car: &PlanarCar, options: &PlanarExport, ids: &Ids) {
    let Some(forces) = &options.forces else {
        return;
    };
    let u = options.units;
    let histories = front_forces(car, forces);
    for (side, per_side) in histories.iter().enumerate() {
        let s = &ids.sides[side];
        let node = s.masses.first().map_or(s.end, |m| m.chain[0]);
        for (c, history) in per_side.iter().enumerate() {
            if history.iter().all(|f| *f == 0.0) {
                continue;
            }
            let points = history
                .iter()
                .enumerate()
                .map(|(k, f)| (k as f64 * forces.step * u.time(), f * u.force()));
            cards::curve(deck, s.curves[c], None, points);
            cards::load_node_point(deck, node, c + 1, s.curves[c], 1.0);
        }
    }
}
