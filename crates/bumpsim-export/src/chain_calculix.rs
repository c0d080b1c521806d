//! The chain with nonlinear links as a CalculiX deck, its barrier run and
//! the link forces read back (issue 46). Which element carries which link,
//! and why a yielding link is a brick: [`crate::chain`].
//!
//! A link j (between masses j and j+1) is element offset + n + j; a front
//! link (the crush zone between the barrier and m1, [`Chain::with_front`])
//! is element offset + 2n in the set `<prefix>EFRONT`, from a wall node
//! one spacing ahead of m1 (id offset + 11n + 1, set `<prefix>WALL`, held).
//! The brick of link j has nodes offset + 3n + 8(j − 1) + 1..8, the front
//! link's the block after the last link's.
//!
//! A wall link (second load path, rebound link) runs from its own held
//! wall node (node and element offset + 11n + 2 and + 3, sets
//! `<prefix>EPATH`, `<prefix>EREBOUND`) to its mass. A linear or elastic
//! one is one `SPRING2` with the loading curve shifted by its gap as a
//! one-sided table: force 0 before the gap and in tension, `F_L(δ − g)`
//! beyond. A yielding one (an unloading slope) is the chain's brick (set
//! `<prefix>EPATHB`, …) from the wall node to a free node, and a one-sided
//! `SPRINGA` from there to the mass (module `walls`, private: the series
//! pair, its ids offset + 11n + 3 + 9(s − 1) + 1..9, and why).
//!
//! **Barrier run** ([`Barrier`]): without a front link m1 is held at the
//! wall and the other masses move at the speed towards it
//! ([`bumpsim_core::chain::Drive::Barrier`] with a massless m1); with one,
//! every mass moves and the front link meets the wall node (which holds
//! on in tension, where bumpsim's front link lets go). `*NODE PRINT` of
//! U, `*EL PRINT` of the bricks' stresses; [`read_link_forces`] turns them
//! into link forces (mean axial less lateral stress × section).

use crate::ExportError;
use crate::calculix::{CalculixOptions, Extra, dynamic_step};
use crate::chain::{
    BRICK_LENGTH, BRICK_SIDE, CURVE_SPAN, check_curves, gapped_points, loading_points, mapping,
    skeleton, solver_unloading, wall_links, wall_note,
};
use crate::inp::{self, Print, real};
use crate::layout::{Layout, UnitSystem};
use bumpsim_core::chain::Chain;
use bumpsim_core::link::{Curve, Link, Unloading};
use bumpsim_core::model::MsdModel;
use std::fmt::Write;
use std::path::Path;

#[path = "chain_calculix_walls.rs"]
mod walls;

/// A barrier run of the CalculiX deck.
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

/// Density of a brick, kg/m³: 1e-4 kg over its 100 m³.
pub const BRICK_DENSITY: f64 = 1e-6;

/// The CalculiX deck of `chain` (see [`crate::calculix`] for the rest):
/// a model, a transient under `options.analysis`'s force, or a `barrier`
/// run (then without force or initial velocity in `options`).
///
/// ```
/// use bumpsim_core::chain::Chain;
/// use bumpsim_core::link::{Curve, Link, Unloading};
/// use bumpsim_export::chain_calculix::calculix_chain_deck;
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
    let n = chain.dof();
    let wall = options.id_offset + 11 * n as u64 + 1;
    if chain.front().is_some() && options.attach.contains(&wall) {
        return Err(ExportError::IdClash {
            node: wall,
            first: wall,
            last: wall,
        });
    }
    let mut spans: Vec<Span> = chain
        .links()
        .iter()
        .enumerate()
        .map(|(j, link)| Span {
            link,
            label: format!("link {}", j + 1),
            elset: format!("{}EK{}", options.prefix, j + 1),
            ends: [j + 1, j + 2].map(|k| options.id_offset + k as u64),
            slot: j,
            at: j as f64,
            gap: None,
        })
        .collect();
    if let Some(link) = chain.front() {
        spans.push(Span {
            link,
            label: "front link".into(),
            elset: format!("{}EFRONT", options.prefix),
            ends: [wall, options.id_offset + 1],
            slot: n.saturating_sub(1),
            at: -1.0,
            gap: None,
        });
    }
    let walls = wall_spans(chain, options)?;
    let extra = walls.iter().map(|w| w.1).max().unwrap_or(0);
    let parts = Parts {
        spans,
        walls: walls.into_iter().map(|w| w.0).collect(),
        front: chain.front().is_some(),
        barrier,
        n,
        extra,
    };
    crate::calculix::deck(&skeleton(chain), Some(&parts), options)
}

/// A link and where it sits.
struct Span<'a> {
    link: &'a Link,
    label: String,
    elset: String,
    /// Node ids of its rear (towards the barrier) and front ends.
    ends: [u64; 2],
    /// Brick node block.
    slot: usize,
    /// Position of its first end, in mass spacings from m1.
    at: f64,
    /// A wall link's gap.
    gap: Option<Gap>,
}

/// The gap of a wall link ([`Chain::path`], [`Chain::rebound`]) and the
/// mass it pushes.
#[derive(Debug, Clone, Copy)]
struct Gap {
    /// The gap, m.
    gap: f64,
    /// The node of the mass it pushes (0-based index `mass − offset − 1`).
    mass: u64,
    /// The id before the block of a yielding wall link's own ids (its free
    /// node, brick nodes and elements; [`walls`]).
    block: u64,
}

struct Parts<'a> {
    spans: Vec<Span<'a>>,
    /// The wall links, after the front link.
    walls: Vec<Span<'a>>,
    front: bool,
    barrier: Option<&'a Barrier>,
    n: usize,
    /// Ids the wall links take after the front link's wall node.
    extra: u64,
}

/// The wall links as spans: wall link of slot s ([`wall_links`]) is node
/// and element offset + 11n + 1 + s (its wall node, held, set
/// `<elset>_WALL`, and its spring), a yielding one also the block of nine
/// ids after offset + 11n + 3 + 9(s − 1) ([`walls`]), with the number of
/// ids it takes beyond the front link's wall node.
fn wall_spans<'a>(
    chain: &'a Chain,
    options: &CalculixOptions,
) -> Result<Vec<(Span<'a>, u64)>, ExportError> {
    let n = chain.dof();
    let mut spans = vec![];
    for (slot, label, wall) in wall_links(chain) {
        let id = options.id_offset + 11 * n as u64 + 1 + slot;
        if options.attach.contains(&id) {
            return Err(ExportError::IdClash {
                node: id,
                first: id,
                last: id,
            });
        }
        let mass = options.id_offset + wall.mass as u64 + 1;
        let tag = match slot {
            1 => "PATH",
            _ => "REBOUND",
        };
        let block = options.id_offset + 11 * n as u64 + 3 + 9 * (slot - 1);
        let yielding = is_brick(&wall.link);
        let block_ids = [block + 1, block + walls::BLOCK];
        if let Some(&node) = options
            .attach
            .iter()
            .find(|a| yielding && (block_ids[0]..=block_ids[1]).contains(a))
        {
            return Err(ExportError::IdClash {
                node,
                first: block_ids[0],
                last: block_ids[1],
            });
        }
        spans.push((
            Span {
                link: &wall.link,
                label: label.to_string(),
                elset: format!("{}E{tag}", options.prefix),
                ends: [id, mass],
                slot: n - 1 + slot as usize, // beside the links' bricks
                at: -1.0,
                gap: Some(Gap {
                    gap: wall.gap,
                    mass,
                    block,
                }),
            },
            match yielding {
                true => block_ids[1] - (options.id_offset + 11 * n as u64 + 1),
                false => slot,
            },
        ));
    }
    Ok(spans)
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

/// The element set of a link's brick: a wall link's spring keeps the
/// link's set, its brick takes the set with a `B` after it.
fn brick_elset(span: &Span) -> String {
    match span.gap {
        Some(_) => format!("{}B", span.elset),
        None => span.elset.clone(),
    }
}

fn is_brick(link: &Link) -> bool {
    !matches!(link.curve(), Curve::Linear { .. }) && matches!(link.unloading(), Unloading::Slope(_))
}

/// The cross directions of the bricks, right-handed with the axis.
fn across(layout: &Layout) -> [usize; 2] {
    let [a, b] = layout.axis.other_dofs().map(|d| d - 1);
    let cyclic = (layout.axis.component + 1) % 3 == a;
    match cyclic == (layout.axis.sign > 0.0) {
        true => [a, b],
        false => [b, a],
    }
}

impl Parts<'_> {
    fn nodes(&self, options: &CalculixOptions, span: &Span) -> [u64; 8] {
        let first = match span.gap {
            Some(gap) => walls::brick_nodes(gap),
            None => options.id_offset + 3 * self.n as u64 + 8 * span.slot as u64 + 1,
        };
        std::array::from_fn(|i| first + i as u64)
    }

    /// The links written as bricks: the chain's, then the wall links'.
    fn bricks(&self) -> impl Iterator<Item = &Span<'_>> {
        let spans = self.spans.iter().chain(&self.walls);
        spans.filter(|s| is_brick(s.link))
    }

    /// A link as element `id`.
    fn element(&self, deck: &mut String, span: &Span, id: u64, options: &CalculixOptions) {
        let (link, elset) = (span.link, &span.elset);
        match span.gap {
            Some(gap) if is_brick(link) => return self.yielding_wall(deck, span, gap, id, options),
            Some(gap) => return self.wall_element(deck, span, gap, id, options),
            None => {}
        }
        let units = options.layout.units;
        let _ = writeln!(deck, "** {}: {}", span.label, mapping(link).note);
        let points = loading_points(link.curve());
        match (link.curve(), link.unloading()) {
            (Curve::Linear { stiffness }, _) => {
                let k = stiffness * units.stiffness();
                let (spring, dof) = (crate::cards::Link::Spring, options.layout.axis.dof());
                inp::axial_link_element(deck, spring, elset, id, span.ends, dof, k);
            }
            (_, Unloading::Elastic) => {
                // SPRING2 on the axis's degree of freedom of both ends: a
                // SPRINGA turned over once its ends crossed
                inp::element_keyword(deck, "SPRING2", elset);
                let ([a, b], dof) = (span.ends, options.layout.axis.dof());
                let _ = writeln!(
                    deck,
                    "{id}, {a}, {b}\n*SPRING, ELSET={elset}, NONLINEAR\n{dof}, {dof}"
                );
                // (force, elongation): compression is negative, odd in δ
                // (so the axis's sign, which flips u_b − u_a, does not matter)
                let mut rows: Vec<(f64, f64)> =
                    points.iter().rev().map(|&(d, f)| (-f, -d)).collect();
                rows.extend(points.iter().skip(1).map(|&(d, f)| (f, d)));
                for (force, elongation) in rows {
                    let (f, e) = (force * units.force(), elongation * units.length());
                    let _ = writeln!(deck, "{}, {}", real(f), real(e));
                }
            }
            (_, Unloading::Slope(_)) => {
                let k = solver_unloading(link);
                self.brick(deck, span, id, options, &points, k)
            }
        }
    }

    /// A wall link's fixed node (held: the barrier).
    fn wall_nodes(&self, deck: &mut String, span: &Span, options: &CalculixOptions) {
        let Some(gap) = span.gap else {
            return;
        };
        let mass = gap.mass - options.id_offset;
        let _ = writeln!(
            deck,
            "** the barrier: the {}'s fixed end, on m{mass} after a gap of {} m",
            span.label,
            real(gap.gap)
        );
        let at = position(&options.layout, -1.0);
        inp::node_keyword(deck, &format!("{}_WALL", span.elset));
        inp::node_line(deck, span.ends[0], at);
    }

    /// A wall link elastic along its curve as element `id`: one `SPRING2`
    /// from the wall node to the mass, its table the loading curve shifted
    /// by the gap in compression, zero before it and in tension (it never
    /// pulls). A yielding one: [`walls`].
    fn wall_element(
        &self,
        deck: &mut String,
        span: &Span,
        gap: Gap,
        id: u64,
        options: &CalculixOptions,
    ) {
        let link = span.link;
        let _ = writeln!(deck, "** {}: {}", span.label, wall_note(link));
        let mut rows: Vec<(f64, f64)> = gapped_points(link.curve(), gap.gap)
            .iter()
            .rev()
            .map(|&(d, f)| (-f, -d))
            .collect();
        rows.push((0.0, CURVE_SPAN));
        spring_table(deck, &span.elset, id, span.ends, &rows, options);
    }

    fn brick(
        &self,
        deck: &mut String,
        span: &Span,
        id: u64,
        options: &CalculixOptions,
        points: &[(f64, f64)],
        k: f64,
    ) {
        let (layout, units, elset) = (&options.layout, options.layout.units, &span.elset);
        let (length, side) = (BRICK_LENGTH * units.length(), BRICK_SIDE * units.length());
        let area = side * side;
        let across = across(layout);
        let axis = layout.axis.vector();
        let base = position(layout, span.at);
        let _ = writeln!(
            deck,
            "** bumpsim-link: link={} elset={elset} area={} component={}\n*NODE, NSET={elset}_NODES",
            span.label.replace(' ', "_"),
            real(area),
            layout.axis.component,
        );
        let nodes = self.nodes(options, span);
        for (corner, node) in CORNERS.iter().zip(nodes) {
            let mut p = base;
            for c in 0..3 {
                p[c] += corner[0] * length * axis[c];
            }
            // beside the axis: 2 m (slot + 1) out along the first cross direction
            p[across[0]] += (2.0 * (span.slot + 1) as f64) * units.length() + corner[1] * side;
            p[across[1]] += corner[2] * side;
            inp::node_line(deck, node, p);
        }
        inp::element_keyword(deck, "C3D8", elset);
        let list: Vec<String> = nodes.iter().map(u64::to_string).collect();
        let _ = writeln!(deck, "{id}, {}", list.join(", "));
        let material = format!("{elset}_MATERIAL");
        // E A / L = 2 k / 3: with the lateral faces tied the brick's axial
        // stiffness is 3 E A / (2 L) (module docs of `crate::chain`)
        let modulus = 2.0 / 3.0 * k * units.stiffness() * length / area;
        let _ = writeln!(
            deck,
            "*SOLID SECTION, ELSET={elset}, MATERIAL={material}\n*MATERIAL, NAME={material}\n*ELASTIC\n{}, 0.0\n*DENSITY\n{}",
            real(modulus),
            real(BRICK_DENSITY * units.mass() / units.length().powi(3))
        );
        let table = hardening(points, solver_unloading(span.link));
        if !table.is_empty() {
            deck.push_str("*PLASTIC\n");
            for (force, strain) in table {
                let stress = force * units.force() / area;
                let _ = writeln!(deck, "{}, {}", real(stress), real(strain));
            }
        }
    }
}

/// A `SPRING2` `id` between `nodes` (rear, front) on the axis's degree of
/// freedom with the nonlinear table `rows` of (force N, elongation m) along
/// the axis (compression negative), ascending. Written as ccx 2.20 reads a
/// one-sided table: both columns times −(the axis's sign), ascending again.
/// Measured: a `SPRING2` from node 1 to node 2 on x with the table (0, 0),
/// (1e6, 10) stops node 2 moving towards −x (100 kg at 1 m/s: 30.2 mm,
/// `√(m/k)` = 31.6 mm) and lets it go towards +x; the table (−1e6, −10),
/// (0, 0), (0, 10) does the reverse. (An odd table, as the chain's elastic
/// links have, reads the same either way.)
fn spring_table(
    deck: &mut String,
    elset: &str,
    id: u64,
    nodes: [u64; 2],
    rows: &[(f64, f64)],
    options: &CalculixOptions,
) {
    let (units, sign) = (options.layout.units, options.layout.axis.sign);
    let ([a, b], dof) = (nodes, options.layout.axis.dof());
    inp::element_keyword(deck, "SPRING2", elset);
    let _ = writeln!(
        deck,
        "{id}, {a}, {b}\n*SPRING, ELSET={elset}, NONLINEAR\n{dof}, {dof}"
    );
    let mut rows: Vec<(f64, f64)> = rows.iter().map(|&(f, e)| (-sign * f, -sign * e)).collect();
    if sign > 0.0 {
        rows.reverse();
    }
    for (force, elongation) in rows {
        let (f, e) = (force * units.force(), elongation * units.length());
        let _ = writeln!(deck, "{}, {}", real(f), real(e));
    }
}

/// The brick's free lateral faces follow its axial strain ε as an
/// incompressible flow does: `u = −ε w / 2` across (w the side), one
/// three-term `*EQUATION` per free lateral degree of freedom,
/// `u + c s u_front − c s u_rear = 0` with `c = w/(2L)` and s the axis's
/// sign. Left free, the lateral nodes (massless, held by the brick alone)
/// made ccx's Newton diverge on a softening table (the identified NHTSA
/// 10146 car stopped at 13 ms; tied, it runs to the end).
fn lateral_ties(deck: &mut String, nodes: &[u64; 8], ends: [u64; 2], options: &CalculixOptions) {
    let (dof, sign) = (options.layout.axis.dof(), options.layout.axis.sign);
    let c = sign * BRICK_SIDE / (2.0 * BRICK_LENGTH);
    let across = across(&options.layout);
    let [rear, front] = ends;
    for (corner, node) in CORNERS.iter().zip(nodes) {
        for (k, direction) in across.iter().enumerate() {
            if corner[1 + k] == 1.0 {
                let _ = writeln!(
                    deck,
                    "3\n{node}, {}, 1.0, {front}, {dof}, {}, {rear}, {dof}, {}",
                    direction + 1,
                    real(c),
                    real(-c)
                );
            }
        }
    }
}

/// A point `at` mass spacings from m1 along the axis, in deck units.
fn position(layout: &Layout, at: f64) -> [f64; 3] {
    let axis = layout.axis.vector();
    std::array::from_fn(|c| {
        (layout.origin[c] + at * layout.spacing * axis[c]) * layout.units.length()
    })
}

impl Extra for Parts<'_> {
    fn extra_ids(&self) -> u64 {
        8 * self.n as u64 + 1 + self.extra
    }

    fn spring(
        &self,
        deck: &mut String,
        j: usize,
        _elset: &str,
        id: u64,
        options: &CalculixOptions,
    ) {
        self.element(deck, &self.spans[j], id, options);
    }

    fn front(&self, deck: &mut String, options: &CalculixOptions) {
        if let (true, Some(span)) = (self.front, self.spans.last()) {
            let wall = span.ends[0];
            let _ = writeln!(deck, "** the barrier: the front link's fixed end");
            inp::node_keyword(deck, &format!("{}WALL", options.prefix));
            inp::node_line(deck, wall, position(&options.layout, -1.0));
            let id = options.id_offset + 2 * self.n as u64;
            self.element(deck, span, id, options);
        }
        for span in &self.walls {
            self.wall_nodes(deck, span, options);
            self.element(deck, span, span.ends[0], options);
        }
    }

    fn held(&self, _model: &MsdModel, options: &CalculixOptions) -> Vec<(String, usize, usize)> {
        let across = across(&options.layout);
        let mut held = vec![];
        for span in self.bricks() {
            for (corner, node) in CORNERS.iter().zip(self.nodes(options, span)) {
                for (c, dir) in across.iter().enumerate() {
                    if corner[1 + c] == 0.0 {
                        held.push((node.to_string(), dir + 1, dir + 1));
                    }
                }
            }
        }
        for span in &self.walls {
            held.push((format!("{}_WALL", span.elset), 1, 3));
            if let (Some(gap), true) = (span.gap, is_brick(span.link)) {
                for dof in options.layout.axis.other_dofs() {
                    held.push((walls::free_node(gap).to_string(), dof, dof));
                }
            }
        }
        if self.front {
            held.push((format!("{}WALL", options.prefix), 1, 3));
        } else if self.barrier.is_some() {
            let dof = options.layout.axis.dof();
            held.push(((options.id_offset + 1).to_string(), dof, dof));
        }
        held
    }

    fn ties(&self, deck: &mut String, options: &CalculixOptions) {
        let dof = options.layout.axis.dof();
        for span in self.bricks() {
            let ends = match span.gap {
                Some(gap) => [span.ends[0], walls::free_node(gap)],
                None => span.ends,
            };
            let _ = writeln!(
                deck,
                "** {} brick: rear face follows node {}, front face node {}\n*EQUATION",
                span.label, ends[0], ends[1]
            );
            for (corner, node) in CORNERS.iter().zip(self.nodes(options, span)) {
                let end = ends[corner[0] as usize];
                let _ = writeln!(deck, "2\n{node}, {dof}, 1.0, {end}, {dof}, -1.0");
            }
            lateral_ties(deck, &self.nodes(options, span), ends, options);
        }
    }

    fn run(
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
        let first = if self.front { 1 } else { 2 };
        let nodes: Vec<String> = (first..=model.dof())
            .map(|i| (options.id_offset + i as u64).to_string())
            .collect();
        let rows: Vec<(&str, usize, f64)> = nodes
            .iter()
            .map(|n| (n.as_str(), layout.axis.dof(), v))
            .collect();
        let held = if self.front {
            "the front link on the wall"
        } else {
            "m1 held at the wall"
        };
        let _ = writeln!(deck, "** barrier: {held}, the car at {} m/s", b.speed);
        if !rows.is_empty() {
            inp::initial_velocity(deck, &rows);
        }
        dynamic_step(deck, b.increment, b.duration, layout.units)?;
        let every = Print::Every(b.output_every);
        inp::node_print(deck, &format!("{}NALL", options.prefix), every, "U");
        for span in self.bricks() {
            inp::element_print(deck, &brick_elset(span), every, "S");
        }
        deck.push_str("*END STEP\n");
        Ok(())
    }
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
    /// (link label: `link_1`, …, `front_link`; force N, compression
    /// positive, per time).
    pub links: Vec<(String, Vec<f64>)>,
}

/// Reads the bricks' axial forces of a deck written by
/// [`calculix_chain_deck`] from the `.dat` beside it: the mean over the
/// integration points of the axial stress less the mean lateral stress,
/// times the section (the work of the tied lateral faces goes to the
/// ends: `F = (σ_axial − σ_lateral) A`).
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
            let area: f64 = value("area")?.parse().ok()?;
            let component: usize = value("component")?.parse().ok()?;
            Some((value("link")?, value("elset")?, area, component))
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
            // the axial stress less the lateral faces' mean (which carry
            // the tied flow's share; zero on a deck with free faces)
            let stress: Vec<f64> = b
                .rows
                .iter()
                .filter_map(|r| {
                    let s = r.values.get(1..4)?;
                    let lateral = (s.iter().sum::<f64>() - s.get(component)?) / 2.0;
                    Some(s.get(component)? - lateral)
                })
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
        out.links.push((link.to_string(), force));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Elastic-plastic with E = k_u: yield where δ = F/k_u, then the
    /// plastic strain of each point over L.
    #[test]
    fn the_hardening_table_starts_at_yield_and_follows_the_curve() {
        let curve = Curve::bilinear(1e6, 5e4, 0.1).unwrap();
        let table = hardening(&loading_points(&curve), 1e6);
        assert_eq!(table.len(), 2);
        assert_eq!(table[0], (5e4, 0.0));
        let top = curve.force(CURVE_SPAN);
        assert!((table[1].0 - top).abs() < 1e-6 * top);
        let strain = (CURVE_SPAN - top / 1e6) / BRICK_LENGTH;
        assert!((table[1].1 - strain).abs() < 1e-12);
        // stiffer unloading: plastic from the start
        let table = hardening(&loading_points(&curve), 2e6);
        assert_eq!(table[0], (0.0, 0.0));
        assert!((table[1].1 - (0.05 - 5e4 / 2e6) / BRICK_LENGTH).abs() < 1e-15);
        // a linear curve at its own slope never yields
        assert!(hardening(&loading_points(&Curve::linear(1e6).unwrap()), 1e6).is_empty());
    }
}
