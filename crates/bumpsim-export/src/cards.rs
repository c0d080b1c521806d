//! LS-DYNA keyword cards in fixed format, shared by every include bumpsim
//! writes (the MSD chain of [`crate::lsdyna`] and the planar car of
//! bumpsim-planar). Field widths follow the LS-DYNA Keyword User's Manual,
//! vol. I: 8/16-column `*NODE`, `*ELEMENT_MASS` and `*ELEMENT_DISCRETE`,
//! 10-column fields elsewhere; 20-column curve points.
//!
//! Every writer appends complete cards (keyword line, a `$` comment naming
//! the fields, the data lines) to a `String`; values are in the deck's units.
//!
//! ```
//! use bumpsim_export::cards;
//! let mut deck = String::new();
//! cards::node(&mut deck, &[(7, [0.0, 0.5, 0.0])], Some([0, 0]));
//! cards::element_mass(&mut deck, 7, 7, 12.5, "kg");
//! assert!(deck.starts_with("*NODE\n"));
//! assert!(deck.contains("       7       7            12.5"));
//! ```

use crate::layout::{UnitSystem, int_field, real_field};
use std::fmt::Write;

/// `*KEYWORD` and the comment lines every include opens with: the title
/// (78 characters at most, control characters escaped: a car name's line
/// break or escape must not break the deck), bumpsim's version with `what`
/// the include holds, and the units.
pub fn header(deck: &mut String, title: &str, what: &str, units: UnitSystem) {
    let title: String = bumpsim_core::names::printable(title)
        .chars()
        .take(78)
        .collect();
    let _ = writeln!(deck, "*KEYWORD\n$ {title}");
    let _ = writeln!(deck, "$ bumpsim {}: {what}", env!("CARGO_PKG_VERSION"));
    units_comment(deck, units);
}

/// `*KEYWORD` and `*TITLE` with its line, for a deck that names itself
/// (a complete run, a bumper spring); control characters escaped.
pub fn titled(deck: &mut String, title: &str) {
    let title = bumpsim_core::names::printable(title);
    let _ = writeln!(deck, "*KEYWORD\n*TITLE\n{title}");
}

/// The comment naming the deck's units: `$ units: mass .., length ..,
/// time .., force ..`.
pub fn units_comment(deck: &mut String, units: UnitSystem) {
    let [m, l, t, f] = units.symbols();
    let _ = writeln!(deck, "$ units: mass {m}, length {l}, time {t}, force {f}");
}

/// How much of a card's fields its `$` comment names: every field of the
/// manual's card, or only those the writer fills (the decks written so
/// far use both, and a deck's text must not change).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FieldNames {
    /// Every field of the card.
    All,
    /// The fields written.
    Written,
}

/// A row of 10-column integers, eight to a line.
fn id_rows(deck: &mut String, ids: &[u64]) {
    for chunk in ids.chunks(8) {
        let _ = writeln!(
            deck,
            "{}",
            chunk.iter().map(|n| int_field(*n, 10)).collect::<String>()
        );
    }
}

/// `*NODE`: one line per (id, position), all with the translational and
/// rotational constraint codes `constraints` (`[tc, rc]`; `None`: the
/// lines end after z).
pub fn node(deck: &mut String, nodes: &[(u64, [f64; 3])], constraints: Option<[u64; 2]>) {
    node_keyword(deck, constraints.is_some());
    for (id, p) in nodes {
        node_line(deck, *id, *p, constraints);
    }
}

/// The `*NODE` keyword line and its field comment, naming `tc` and `rc`
/// when the lines carry them.
pub fn node_keyword(deck: &mut String, constrained: bool) {
    let codes = if constrained { "      tc      rc" } else { "" };
    let _ = writeln!(
        deck,
        "*NODE\n$    nid               x               y               z{codes}"
    );
}

/// One `*NODE` data line (constraint codes `[tc, rc]`, if any).
pub fn node_line(deck: &mut String, id: u64, p: [f64; 3], constraints: Option<[u64; 2]>) {
    let _ = write!(
        deck,
        "{}{}{}{}",
        int_field(id, 8),
        real_field(p[0], 16),
        real_field(p[1], 16),
        real_field(p[2], 16)
    );
    if let Some([tc, rc]) = constraints {
        let _ = write!(deck, "{}{}", int_field(tc, 8), int_field(rc, 8));
    }
    deck.push('\n');
}

/// `*ELEMENT_MASS`: element `id` of `mass` (deck units, `unit` for the
/// comment) on `node`; one keyword per mass (some pre-processors read one row).
pub fn element_mass(deck: &mut String, id: u64, node: u64, mass: f64, unit: &str) {
    let _ = writeln!(
        deck,
        "*ELEMENT_MASS\n$    eid     nid            mass  ({unit})\n{}{}{}",
        int_field(id, 8),
        int_field(node, 8),
        real_field(mass, 16)
    );
}

/// `*SECTION_DISCRETE` `id`: a translational discrete section.
pub fn discrete_section(deck: &mut String, id: u64, names: FieldNames) {
    let rest = match names {
        FieldNames::All => "        kd        v0        cl        fd       cdl       tdl",
        FieldNames::Written => "",
    };
    let _ = writeln!(
        deck,
        "*SECTION_DISCRETE\n$  secid       dro{rest}\n{}{}",
        int_field(id, 10),
        int_field(0, 10)
    );
}

/// `*PART` `id` titled `title`, of section `section` and material `material`.
pub fn part(deck: &mut String, title: &str, id: u64, section: u64, material: u64) {
    let _ = writeln!(
        deck,
        "*PART\n{title}\n$    pid     secid       mid\n{}{}{}",
        int_field(id, 10),
        int_field(section, 10),
        int_field(material, 10)
    );
}

/// A linear discrete material and its part, both with id `id`:
/// `*MAT_SPRING_ELASTIC` (`K`) or `*MAT_DAMPER_VISCOUS` (`DC`), then `*PART`
/// titled `title` on `section`.
pub fn discrete_part(
    deck: &mut String,
    link: Link,
    value: f64,
    unit: &str,
    id: u64,
    section: u64,
    title: &str,
) {
    let (keyword, field) = match link {
        Link::Spring => ("*MAT_SPRING_ELASTIC", "k"),
        Link::Damper => ("*MAT_DAMPER_VISCOUS", "dc"),
    };
    let _ = writeln!(
        deck,
        "{keyword}\n$    mid{field:>10}  ({unit})\n{}{}",
        int_field(id, 10),
        real_field(value, 10)
    );
    part(deck, title, id, section, id);
}

/// `*MAT_SPRING_GENERAL_NONLINEAR` `id` (LS-DYNA MAT_S06): loading and
/// unloading along the curves `[lcdl, lcdu]`, no hardening.
pub fn nonlinear_spring(deck: &mut String, id: u64, [loading, unloading]: [u64; 2]) {
    let _ = writeln!(
        deck,
        "*MAT_SPRING_GENERAL_NONLINEAR\n$    mid      lcdl      lcdu      beta       tyi       cyi\n{}{}{}{}{}{}",
        int_field(id, 10),
        int_field(loading, 10),
        int_field(unloading, 10),
        real_field(0.0, 10),
        real_field(0.0, 10),
        real_field(0.0, 10)
    );
}

/// The kind of a linear discrete element.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Link {
    /// A spring, `*MAT_SPRING_ELASTIC`.
    Spring,
    /// A viscous damper, `*MAT_DAMPER_VISCOUS`.
    Damper,
}

/// The `*ELEMENT_DISCRETE` keyword line and its field comment.
pub fn element_discrete_header(deck: &mut String, names: FieldNames) {
    let rest = match names {
        FieldNames::All => "      pf          offset",
        FieldNames::Written => "",
    };
    let _ = writeln!(
        deck,
        "*ELEMENT_DISCRETE\n$    eid     pid      n1      n2     vid               s{rest}"
    );
}

/// One `*ELEMENT_DISCRETE` line: element `id` of part `part` between `n1`
/// and `n2` (along the line between them, scale 1).
pub fn element_discrete_line(deck: &mut String, id: u64, part: u64, n1: u64, n2: u64) {
    element_discrete_oriented(deck, id, part, [n1, n2], 0);
}

/// One `*ELEMENT_DISCRETE` line acting along the orientation `vid` (a
/// [`sd_orientation`]; 0: along the current line between the nodes).
pub fn element_discrete_oriented(deck: &mut String, id: u64, part: u64, nodes: [u64; 2], vid: u64) {
    let _ = writeln!(
        deck,
        "{}{}{}{}{}{}",
        int_field(id, 8),
        int_field(part, 8),
        int_field(nodes[0], 8),
        int_field(nodes[1], 8),
        int_field(vid, 8),
        real_field(1.0, 16)
    );
}

/// `*DEFINE_SD_ORIENTATION` `vid` with IOP = 0: discrete elements that
/// name it deflect and push along the fixed unit `vector`, whatever the
/// nodes' current positions. A spring along the line between its nodes
/// turns over once a crush larger than the node spacing makes the nodes
/// pass each other; along a fixed axis its deflection is the relative
/// displacement along the axis, as in the lumped model.
pub fn sd_orientation(deck: &mut String, vid: u64, vector: [f64; 3]) {
    let _ = writeln!(
        deck,
        "*DEFINE_SD_ORIENTATION\n$    vid       iop        xt        yt        zt\n{}{}{}{}{}",
        int_field(vid, 10),
        int_field(0, 10),
        real_field(vector[0], 10),
        real_field(vector[1], 10),
        real_field(vector[2], 10)
    );
}

/// `*SET_NODE_LIST` `id` of `nodes`.
pub fn node_set(deck: &mut String, id: u64, nodes: &[u64]) {
    let _ = writeln!(deck, "*SET_NODE_LIST\n$    sid\n{}", int_field(id, 10));
    id_rows(deck, nodes);
}

/// `*CONSTRAINED_NODAL_RIGID_BODY_SPC` `id` of node set `set`, its centre of
/// mass constrained (CMO = 1) by the translation code `con1` and rotation
/// code `con2` (1 x, 2 y, 3 z, 4 xy, 5 yz, 6 zx, 7 all).
pub fn nodal_rigid_body_spc(deck: &mut String, id: u64, set: u64, con1: u8, con2: u8) {
    let _ = writeln!(
        deck,
        "*CONSTRAINED_NODAL_RIGID_BODY_SPC\n$    pid       cid      nsid\n{}{}{}",
        int_field(id, 10),
        int_field(0, 10),
        int_field(set, 10)
    );
    let _ = writeln!(
        deck,
        "$    cmo      con1      con2\n{}{}{}",
        real_field(1.0, 10),
        real_field(f64::from(con1), 10),
        real_field(f64::from(con2), 10)
    );
}

/// `*CONSTRAINED_NODAL_RIGID_BODY` `id` of node set `set`, its mass and
/// inertia computed from the nodes' masses.
pub fn nodal_rigid_body(deck: &mut String, id: u64, set: u64) {
    let _ = writeln!(
        deck,
        "*CONSTRAINED_NODAL_RIGID_BODY\n$    pid       cid      nsid\n{}{}{}",
        int_field(id, 10),
        int_field(0, 10),
        int_field(set, 10)
    );
}

/// A rigid body given by its mass, inertia and initial velocity rather than
/// by its nodes' masses (deck units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inertia {
    /// Centre of mass.
    pub centre: [f64; 3],
    /// The node at the centre of mass.
    pub node: u64,
    /// Mass.
    pub mass: f64,
    /// Principal moments of inertia about x, y, z (global axes).
    pub moments: [f64; 3],
    /// Initial translational velocity.
    pub velocity: [f64; 3],
}

/// `*CONSTRAINED_NODAL_RIGID_BODY_INERTIA_SPC` `id` of node set `set`
/// (constraint codes as in [`nodal_rigid_body_spc`]).
pub fn nodal_rigid_body_inertia_spc(
    deck: &mut String,
    id: u64,
    set: u64,
    body: &Inertia,
    con: [u8; 2],
) {
    let reals = |values: &[f64]| {
        values
            .iter()
            .map(|v| real_field(*v, 10))
            .collect::<String>()
    };
    let _ = writeln!(
        deck,
        "*CONSTRAINED_NODAL_RIGID_BODY_INERTIA_SPC\n$    pid       cid      nsid     pnode\n{}{}{}{}",
        int_field(id, 10),
        int_field(0, 10),
        int_field(set, 10),
        int_field(body.node, 10)
    );
    let _ = writeln!(
        deck,
        "$    cmo      con1      con2\n{}",
        reals(&[1.0, f64::from(con[0]), f64::from(con[1])])
    );
    let [x, y, z] = body.centre;
    let _ = writeln!(
        deck,
        "$     xc        yc        zc        tm      ircs    nodeid\n{}{}{}",
        reals(&[x, y, z, body.mass]),
        int_field(0, 10),
        int_field(body.node, 10)
    );
    let [ixx, iyy, izz] = body.moments;
    let _ = writeln!(
        deck,
        "$    ixx       ixy       ixz       iyy       iyz       izz\n{}",
        reals(&[ixx, 0.0, 0.0, iyy, 0.0, izz])
    );
    let [vx, vy, vz] = body.velocity;
    let _ = writeln!(
        deck,
        "$    vtx       vty       vtz       vrx       vry       vrz\n{}",
        reals(&[vx, vy, vz, 0.0, 0.0, 0.0])
    );
}

/// `*CONSTRAINED_JOINT_TRANSLATIONAL` between two rigid bodies: `nodes`
/// are three coincident pairs (body A, body B); the first two pairs lie on
/// the sliding axis, the third off it.
pub fn joint_translational(deck: &mut String, nodes: [u64; 6]) {
    let _ = writeln!(
        deck,
        "*CONSTRAINED_JOINT_TRANSLATIONAL\n$     n1        n2        n3        n4        n5        n6"
    );
    id_rows(deck, &nodes);
}

/// `*INITIAL_VELOCITY_NODE`: every node of `nodes` at `velocity`
/// (`units` = length and time symbols for the comment).
pub fn initial_velocity_nodes(
    deck: &mut String,
    nodes: &[u64],
    velocity: [f64; 3],
    units: [&str; 2],
) {
    let _ = writeln!(
        deck,
        "*INITIAL_VELOCITY_NODE\n$    nid        vx        vy        vz  ({}/{})",
        units[0], units[1]
    );
    let components: String = velocity.iter().map(|v| real_field(*v, 10)).collect();
    for node in nodes {
        let _ = writeln!(deck, "{}{components}", int_field(*node, 10));
    }
}

/// `*DEFINE_CURVE` `id` of (abscissa, ordinate) points (deck units), with
/// a `$` comment line `note` after the keyword, if any.
pub fn curve(
    deck: &mut String,
    id: u64,
    note: Option<&str>,
    points: impl Iterator<Item = (f64, f64)>,
) {
    deck.push_str("*DEFINE_CURVE\n");
    if let Some(note) = note {
        let _ = writeln!(deck, "$ {note}");
    }
    let _ = writeln!(
        deck,
        "$   lcid      sidr       sfa       sfo\n{}{}{}{}",
        int_field(id, 10),
        int_field(0, 10),
        real_field(1.0, 10),
        real_field(1.0, 10)
    );
    for (t, f) in points {
        let _ = writeln!(deck, "{}{}", real_field(t, 20), real_field(f, 20));
    }
}

/// `*LOAD_NODE_POINT`: curve `curve` × `scale` on `node` in global
/// direction `dof` (1 x, 2 y, 3 z).
pub fn load_node_point(deck: &mut String, node: u64, dof: usize, curve: u64, scale: f64) {
    let _ = writeln!(
        deck,
        "*LOAD_NODE_POINT\n$    nid       dof      lcid        sf\n{}{}{}{}",
        int_field(node, 10),
        int_field(dof as u64, 10),
        int_field(curve, 10),
        real_field(scale, 10)
    );
}

/// History outputs every `dt` (deck time): `*DATABASE_NODOUT`,
/// `*DATABASE_DEFORC`, `*DATABASE_GLSTAT` and `*DATABASE_HISTORY_NODE` of `nodes`.
pub fn history(deck: &mut String, dt: f64, nodes: &[u64]) {
    for keyword in ["*DATABASE_NODOUT", "*DATABASE_DEFORC", "*DATABASE_GLSTAT"] {
        database(deck, keyword, dt);
    }
    let _ = writeln!(deck, "*DATABASE_HISTORY_NODE\n$   id1       id2 ...");
    id_rows(deck, nodes);
}

/// A `*DATABASE_` output card `keyword` written every `dt` (deck time).
pub fn database(deck: &mut String, keyword: &str, dt: f64) {
    let _ = writeln!(deck, "{keyword}\n$     dt\n{}", real_field(dt, 10));
}

/// `*CONTROL_TERMINATION` at `end` (deck time).
pub fn termination(deck: &mut String, end: f64) {
    let _ = writeln!(
        deck,
        "*CONTROL_TERMINATION\n$ endtim\n{}",
        real_field(end, 10)
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A car name holding a line break or an escape went raw into the deck:
    /// the break ended the comment, leaving the rest as a keyword line.
    #[test]
    fn control_characters_of_a_title_are_escaped() {
        let name = "car\n*END\u{1b}[2J";
        let mut deck = String::new();
        header(&mut deck, name, "test", UnitSystem::Si);
        titled(&mut deck, name);
        assert!(
            !deck.contains('\u{1b}') && !deck.contains("\n*END"),
            "{deck}"
        );
        assert!(
            deck.starts_with("*KEYWORD\n$ car\\u000A*END\\u001B[2J\n"),
            "{deck}"
        );
        assert!(
            deck.ends_with("*TITLE\ncar\\u000A*END\\u001B[2J\n"),
            "{deck}"
        );
    }
}
