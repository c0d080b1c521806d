//! CalculiX/Abaqus input-deck cards shared by every deck bumpsim writes
//! (the MSD chain of [`crate::calculix`], the planar car of bumpsim-planar
//! and the coupled bumper of bumpsim-fe): free format, comma-separated, reals
//! always with a decimal point ([`real`]). Sources: CalculiX CrunchiX User's
//! Manual 2.20.
//!
//! Every writer appends complete cards (keyword line, data lines) to a
//! `String`; values are in the deck's units.
//!
//! ```
//! use bumpsim_export::inp;
//! let mut deck = String::new();
//! inp::node_keyword(&mut deck, "CAR");
//! inp::node_line(&mut deck, 7, [0.0, 0.5, 0.0]);
//! inp::mass_element(&mut deck, "CAR_M7", 7, 7, 12.5);
//! assert!(deck.starts_with("*NODE, NSET=CAR\n7, 0.000000000000e0, 5.000000000000e-1"));
//! ```

use crate::cards::Link;
use std::fmt::Write;

/// A real as CalculiX reads it: always with a decimal point (`5e5` is misread), 13 digits.
pub fn real(value: f64) -> String {
    format!("{:.12e}", value + 0.0)
}

/// The `*NODE` keyword line of the node set `nset`.
pub fn node_keyword(deck: &mut String, nset: &str) {
    let _ = writeln!(deck, "*NODE, NSET={nset}");
}

/// One `*NODE` data line: id, x, y, z.
pub fn node_line(deck: &mut String, id: u64, p: [f64; 3]) {
    let _ = writeln!(deck, "{id}, {}, {}, {}", real(p[0]), real(p[1]), real(p[2]));
}

/// The `*ELEMENT` keyword line of elements of `kind` (`MASS`, `SPRINGA`,
/// `B32R`, …) in the element set `elset`.
pub fn element_keyword(deck: &mut String, kind: &str, elset: &str) {
    let _ = writeln!(deck, "*ELEMENT, TYPE={kind}, ELSET={elset}");
}

/// A point mass: `*ELEMENT, TYPE=MASS` `element` on `node` in the element
/// set `elset`, and its `*MASS` `mass`.
pub fn mass_element(deck: &mut String, elset: &str, element: u64, node: u64, mass: f64) {
    element_keyword(deck, "MASS", elset);
    let _ = writeln!(
        deck,
        "{element}, {node}\n*MASS, ELSET={elset}\n{}",
        real(mass)
    );
}

/// A linear axial link: `*ELEMENT, TYPE=SPRINGA` with `*SPRING` (stiffness
/// `value`) or `TYPE=DASHPOTA` with `*DASHPOT` (damping `value`), element
/// `element` between `nodes` in the element set `elset`.
pub fn link_element(
    deck: &mut String,
    link: Link,
    elset: &str,
    element: u64,
    nodes: [u64; 2],
    value: f64,
) {
    let (kind, card) = match link {
        Link::Spring => ("SPRINGA", "SPRING"),
        Link::Damper => ("DASHPOTA", "DASHPOT"),
    };
    let [a, b] = nodes;
    element_keyword(deck, kind, elset);
    let _ = writeln!(
        deck,
        "{element}, {a}, {b}\n*{card}, ELSET={elset}\n\n{}",
        real(value)
    );
}

/// A link along one global direction: `*ELEMENT, TYPE=SPRING2` with
/// `*SPRING` (stiffness `value`, acting between degree of freedom `dof` of
/// both nodes) or `TYPE=DASHPOTA` with `*DASHPOT` (damping `value`),
/// element `element` between `nodes` in the element set `elset`.
///
/// A `SPRINGA` acts along the current line between its nodes: once its
/// nodes cross (a crush beyond their distance) its force turns over. A
/// `SPRING2` between the same degree of freedom of both nodes,
/// F = k (u_b − u_a), keeps its direction whatever the crush. (A
/// `DASHPOTA`'s force, c (v_b − v_a)·e e, is unchanged when e flips, and
/// CalculiX has no fixed-direction dashpot.) For the 1-D chain, whose
/// masses move along the axis only.
///
/// ```
/// use bumpsim_export::{cards::Link, inp};
/// let mut deck = String::new();
/// inp::axial_link_element(&mut deck, Link::Spring, "EK1", 4, [1, 2], 1, 5e5);
/// assert_eq!(deck, "*ELEMENT, TYPE=SPRING2, ELSET=EK1\n4, 1, 2\n*SPRING, ELSET=EK1\n1, 1\n5.000000000000e5\n");
/// ```
pub fn axial_link_element(
    deck: &mut String,
    link: Link,
    elset: &str,
    element: u64,
    nodes: [u64; 2],
    dof: usize,
    value: f64,
) {
    match link {
        Link::Spring => {
            let [a, b] = nodes;
            element_keyword(deck, "SPRING2", elset);
            let _ = writeln!(
                deck,
                "{element}, {a}, {b}\n*SPRING, ELSET={elset}\n{dof}, {dof}\n{}",
                real(value)
            );
        }
        Link::Damper => link_element(deck, link, elset, element, nodes, value),
    }
}

/// `*INITIAL CONDITIONS, TYPE=VELOCITY`: one line per (node set or node,
/// degree of freedom, velocity).
pub fn initial_velocity(deck: &mut String, rows: &[(&str, usize, f64)]) {
    deck.push_str("*INITIAL CONDITIONS, TYPE=VELOCITY\n");
    for (set, dof, v) in rows {
        let _ = writeln!(deck, "{set}, {dof}, {}", real(*v));
    }
}

/// `*BOUNDARY`: one line per (node set or node, first, last degree of
/// freedom held).
pub fn boundary(deck: &mut String, rows: &[(String, usize, usize)]) {
    deck.push_str("*BOUNDARY\n");
    for (set, first, last) in rows {
        let _ = writeln!(deck, "{set}, {first}, {last}");
    }
}

/// When a `*NODE PRINT` or `*EL PRINT` writes to the `.dat` file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Print {
    /// CalculiX's default: every increment, each node or element.
    Default,
    /// Every this many increments, each node or element.
    Every(usize),
    /// Only the set's totals.
    Totals,
}

impl Print {
    fn parameter(self) -> String {
        match self {
            Print::Default => String::new(),
            Print::Every(n) => format!(", FREQUENCY={n}"),
            Print::Totals => ", TOTALS=ONLY".into(),
        }
    }
}

/// `*NODE PRINT` of `outputs` (`U`, `U, V`, `RF`) of the node set `nset`.
pub fn node_print(deck: &mut String, nset: &str, print: Print, outputs: &str) {
    let _ = writeln!(
        deck,
        "*NODE PRINT, NSET={nset}{}\n{outputs}",
        print.parameter()
    );
}

/// `*EL PRINT` of `outputs` (`ELSE`, `ELKE`) of the element set `elset`.
pub fn element_print(deck: &mut String, elset: &str, print: Print, outputs: &str) {
    let _ = writeln!(
        deck,
        "*EL PRINT, ELSET={elset}{}\n{outputs}",
        print.parameter()
    );
}
