//! LS-DYNA keyword include file of an MSD car model (thesis ch. 3.3, paper B;
//! spec §8; LS-DYNA Keyword User's Manual, vol. I and II).
//!
//! Cards, in fixed format (80 columns; 10-column fields, and the manual's
//! 8/16-column fields for `*NODE`, `*ELEMENT_MASS` and `*ELEMENT_DISCRETE`):
//!
//! - `*NODE`: one node per mass on the axis; `TC`/`RC` leave only
//!   translation along the axis (the thesis: "every lumped mass may only
//!   translate longitudinally");
//! - `*ELEMENT_MASS`: m_i on node i (one keyword per mass);
//! - `*SECTION_DISCRETE` (translational), `*MAT_SPRING_ELASTIC` (K = k_j),
//!   `*MAT_DAMPER_VISCOUS` (DC = c_j), one `*PART` per spring and damper, and
//!   `*ELEMENT_DISCRETE` between nodes j and j+1 (a spring and a damper in
//!   parallel) acting along the model axis (`*DEFINE_SD_ORIENTATION`, a fixed
//!   vector, id = the section's), so a crush beyond the node spacing does not
//!   turn a link over as a link along the nodes' current line would; a zero
//!   damper gets no element;
//! - with attachment nodes: `*SET_NODE_LIST` of m1's node and the user's
//!   bumper attachment nodes, and `*CONSTRAINED_NODAL_RIGID_BODY_SPC` tying
//!   them rigidly, its centre-of-mass constraint leaving translation along the
//!   axis only (the thesis couples m1 to the side-member ends by rigid links);
//! - optional `*INITIAL_VELOCITY_NODE` for every mass;
//! - with a force history: `*DEFINE_CURVE` (time shifted so the first sample
//!   is at 0) and `*LOAD_NODE_POINT` on m1's node along the axis;
//! - with an output interval: `*DATABASE_NODOUT`, `*DATABASE_DEFORC`,
//!   `*DATABASE_GLSTAT` and `*DATABASE_HISTORY_NODE` of the mass nodes;
//! - standalone: `*CONTROL_TERMINATION` at the end of the force history
//!   and the car's critical explicit time step ([`crate::timestep`]) as a comment.
//!
//! Ids: every id is `offset + k` with k small, so the include cannot clash
//! with the user's model when the offset is above the user's ids.

use crate::ExportError;
use crate::cards::{self, FieldNames, Link};
use crate::layout::Layout;
use bumpsim_core::model::MsdModel;
use bumpsim_core::series::UniformSeries;
use std::fmt::Write;

/// Largest id an 8-column field holds.
pub const MAX_ID: u64 = 99_999_999;

/// Options of the LS-DYNA export.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LsDynaOptions {
    /// Units, axis and node placement.
    pub layout: Layout,
    /// Added to every id (nodes, elements, parts, materials, sections, sets).
    pub id_offset: u64,
    /// The user's bumper attachment node ids coupled rigidly to m1.
    pub attach: Vec<u64>,
    /// Initial velocity of every mass along the axis, m/s (SI).
    pub initial_velocity: Option<f64>,
    /// Title line and origin note.
    pub title: String,
    /// Force on m1 along the axis, N (SI): `*DEFINE_CURVE` + `*LOAD_NODE_POINT`.
    pub force: Option<UniformSeries>,
    /// Interval of the history outputs (nodout, deforc, glstat), s.
    pub output_interval: Option<f64>,
    /// A complete run: `*CONTROL_TERMINATION` at the force's end (needs `force`).
    pub standalone: bool,
}

/// The ids the include uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Ids {
    offset: u64,
    dof: u64,
}

impl Ids {
    /// Node (and mass element) of mass `i` (0-based).
    pub fn node(&self, i: usize) -> u64 {
        self.offset + 1 + i as u64
    }

    /// Element, part and material of spring `j` (0-based).
    pub fn spring(&self, j: usize) -> u64 {
        self.offset + self.dof + 1 + j as u64
    }

    /// Element, part and material of damper `j` (0-based).
    pub fn damper(&self, j: usize) -> u64 {
        self.offset + 2 * self.dof + 1 + j as u64
    }

    /// The discrete section, node set and rigid-body part.
    pub fn shared(&self) -> u64 {
        self.offset + 3 * self.dof + 1
    }

    /// The force curve: the shared id, as curves (`*DEFINE_CURVE` LCID)
    /// have their own id space, so every id of the include stays within
    /// `offset + 3n + 1` (docs/export.md) and an include placed after it
    /// (a bumper spring at `offset + 3n + 1`) cannot share a curve id.
    pub fn curve(&self) -> u64 {
        self.shared()
    }
}

/// Checks the offset and the attachment nodes and returns the ids.
fn ids(model: &MsdModel, options: &LsDynaOptions) -> Result<Ids, ExportError> {
    if options.id_offset >= MAX_ID {
        // checked first: offset + k would overflow (wrap) for offsets near u64::MAX
        return Err(ExportError::IdOffset {
            offset: options.id_offset,
            limit: MAX_ID,
        });
    }
    let ids = Ids {
        offset: options.id_offset,
        dof: model.dof() as u64,
    };
    let last = ids.curve();
    if last > MAX_ID {
        return Err(ExportError::IdRange {
            offset: options.id_offset,
            last,
            limit: MAX_ID,
        });
    }
    crate::check_attach(
        &options.attach,
        ids.node(0)..=ids.node(model.dof() - 1),
        MAX_ID,
    )?;
    Ok(ids)
}

/// Writes the include file text.
pub fn lsdyna_include(model: &MsdModel, options: &LsDynaOptions) -> Result<String, ExportError> {
    include(model, None, options)
}

/// Writes spring `j`'s material, curves and part (ids `id`) on `section`
/// in the deck's units: a nonlinear link's cards.
pub(crate) type SpringCards<'a> = &'a dyn Fn(&mut String, usize, u64, u64);

/// The include of `model`, its springs written by `nonlinear` when given.
pub(crate) fn include(
    model: &MsdModel,
    nonlinear: Option<SpringCards<'_>>,
    options: &LsDynaOptions,
) -> Result<String, ExportError> {
    let ids = ids(model, options)?;
    let interval = options
        .output_interval
        .map(|dt| ("the output interval", dt));
    crate::check_finite(
        model,
        &options.layout,
        options.initial_velocity,
        options.force.as_ref(),
        interval.as_slice(),
    )?;
    let mut deck = String::new();
    header(&mut deck, model, options, nonlinear.is_some());
    nodes(&mut deck, model, options, &ids);
    masses(&mut deck, model, options, &ids);
    links(&mut deck, model, nonlinear, options, &ids);
    if !options.attach.is_empty() {
        coupling(&mut deck, options, &ids);
    }
    if let Some(v) = options.initial_velocity {
        initial_velocity(&mut deck, model, options, &ids, v);
    }
    run_cards(&mut deck, model, options, &ids)?;
    deck.push_str("*END\n");
    Ok(deck)
}

/// The load, output and control cards of the options.
fn run_cards(
    deck: &mut String,
    model: &MsdModel,
    options: &LsDynaOptions,
    ids: &Ids,
) -> Result<(), ExportError> {
    if let Some(force) = &options.force {
        if force.len() < 2 {
            return Err(ExportError::ForceSamples {
                samples: force.len(),
            });
        }
        load(deck, force, options, ids);
    }
    if let Some(dt) = options.output_interval {
        let duration = options.force.as_ref().map(|f| f.end() - f.start());
        crate::check_interval(
            "output interval (--output-interval)",
            dt,
            duration,
            crate::MAX_OUTPUTS,
        )?;
        history(deck, model, options, ids, dt);
    }
    if options.standalone {
        let force = options.force.as_ref().ok_or(ExportError::Standalone)?;
        let units = options.layout.units;
        let _ = writeln!(
            deck,
            "$ critical explicit time step of the car alone: {:e} {}",
            crate::timestep::critical_time_step(model) * units.time(),
            units.symbols()[2]
        );
        cards::termination(deck, (force.end() - force.start()) * units.time());
    }
    Ok(())
}

/// The force history as a curve and a nodal load on m1 along the axis.
fn load(deck: &mut String, force: &UniformSeries, options: &LsDynaOptions, ids: &Ids) {
    let units = options.layout.units;
    let points = (0..force.len()).map(|k| {
        (
            (force.time(k) - force.start()) * units.time(),
            force.values()[k] * units.force(),
        )
    });
    cards::curve(deck, ids.curve(), None, points);
    let axis = options.layout.axis;
    cards::load_node_point(deck, ids.node(0), axis.dof(), ids.curve(), axis.sign);
}

/// History outputs of the mass nodes and the discrete elements every `dt` s.
fn history(deck: &mut String, model: &MsdModel, options: &LsDynaOptions, ids: &Ids, dt: f64) {
    let nodes: Vec<u64> = (0..model.dof()).map(|i| ids.node(i)).collect();
    cards::history(deck, dt * options.layout.units.time(), &nodes);
}

fn header(deck: &mut String, model: &MsdModel, options: &LsDynaOptions, nonlinear: bool) {
    let what = match nonlinear {
        false => format!(
            "{}-DOF chain MSD car model (Isaksson 2006, ch. 3.3)",
            model.dof()
        ),
        true => format!("{}-DOF chain car model with nonlinear links", model.dof()),
    };
    cards::header(deck, &options.title, &what, options.layout.units);
    let axis = options.layout.axis;
    let _ = writeln!(
        deck,
        "$ model +x = global {axis}: direction of the bumper force on m1"
    );
    let _ = writeln!(
        deck,
        "$ ids: offset {}; masses on nodes {}..",
        options.id_offset,
        options.id_offset + 1
    );
}

fn nodes(deck: &mut String, model: &MsdModel, options: &LsDynaOptions, ids: &Ids) {
    // TC: 5 = y and z fixed, 6 = z and x, 4 = x and y; RC 7 = all rotations
    let tc = [5, 6, 4][options.layout.axis.component];
    cards::node_keyword(deck, true);
    for i in 0..model.dof() {
        // m1 under a nodal rigid body is constrained through the rigid body
        let (tc, rc) = if i == 0 && !options.attach.is_empty() {
            (0, 0)
        } else {
            (tc, 7)
        };
        let position = options.layout.node_position(i);
        cards::node_line(deck, ids.node(i), position, Some([tc, rc]));
    }
}

fn masses(deck: &mut String, model: &MsdModel, options: &LsDynaOptions, ids: &Ids) {
    let unit = options.layout.units.symbols()[0];
    for (i, m) in model.masses().iter().enumerate() {
        let mass = m * options.layout.units.mass();
        cards::element_mass(deck, ids.node(i), ids.node(i), mass, unit);
    }
}

fn links(
    deck: &mut String,
    model: &MsdModel,
    nonlinear: Option<SpringCards<'_>>,
    options: &LsDynaOptions,
    ids: &Ids,
) {
    if model.dof() < 2 {
        return; // a rigid vehicle: no links, no section, no discrete elements
    }
    let units = options.layout.units;
    let [_, l, t, f] = units.symbols();
    let section = ids.shared();
    cards::discrete_section(deck, section, FieldNames::All);
    let links = [
        (
            Link::Spring,
            format!("{f}/{l}"),
            "spring k",
            model.springs(),
            units.stiffness(),
            ids.spring(0),
        ),
        (
            Link::Damper,
            format!("{f}*{t}/{l}"),
            "damper c",
            model.dampers(),
            units.damping(),
            ids.damper(0),
        ),
    ];
    for (link, unit, what, values, factor, first_id) in links {
        // a zero damper gets no part and no element
        for (j, value) in values.iter().enumerate().filter(|(_, v)| **v > 0.0) {
            let title = format!("{what}{} between m{} and m{}", j + 1, j + 1, j + 2);
            let id = first_id + j as u64;
            if let (Link::Spring, Some(cards)) = (link, nonlinear) {
                cards(deck, j, id, section);
                continue;
            }
            cards::discrete_part(deck, link, value * factor, &unit, id, section, &title);
        }
    }
    // along the model axis, not the line between the nodes: a crush beyond
    // the node spacing must not turn a link over (cards::sd_orientation)
    cards::sd_orientation(deck, section, options.layout.axis.vector());
    cards::element_discrete_header(deck, FieldNames::All);
    for j in 0..model.springs().len() {
        let (id, ends) = (ids.spring(j), [ids.node(j), ids.node(j + 1)]);
        cards::element_discrete_oriented(deck, id, id, ends, section);
    }
    for (j, _) in model
        .dampers()
        .iter()
        .enumerate()
        .filter(|(_, c)| **c > 0.0)
    {
        let (id, ends) = (ids.damper(j), [ids.node(j), ids.node(j + 1)]);
        cards::element_discrete_oriented(deck, id, id, ends, section);
    }
}

fn coupling(deck: &mut String, options: &LsDynaOptions, ids: &Ids) {
    let set = ids.shared();
    let members: Vec<u64> = std::iter::once(ids.node(0))
        .chain(options.attach.iter().copied())
        .collect();
    cards::node_set(deck, set, &members);
    let tc = [5, 6, 4][options.layout.axis.component];
    cards::nodal_rigid_body_spc(deck, set, set, tc, 7);
}

fn initial_velocity(
    deck: &mut String,
    model: &MsdModel,
    options: &LsDynaOptions,
    ids: &Ids,
    v: f64,
) {
    let units = options.layout.units;
    let velocity = options
        .layout
        .axis
        .vector()
        .map(|a| a * v * units.velocity());
    let nodes: Vec<u64> = (0..model.dof()).map(|i| ids.node(i)).collect();
    let [_, l, t, _] = units.symbols();
    cards::initial_velocity_nodes(deck, &nodes, velocity, [l, t]);
}
