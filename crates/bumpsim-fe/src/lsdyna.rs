//! The same coupled model as an LS-DYNA keyword deck, for users who have
//! that solver (issue 16; LS-DYNA Keyword User's Manual vol. I and II).
//!
//! Geometry as the CalculiX deck ([`crate::deck`]): the car's +x axis, m1
//! at the origin, crash boxes from x = 0 to x = −L_box at the snapped ±y_c,
//! the beam across at x = −L_box. Cards:
//!
//! - beam and crash boxes: 2-node Belytschko–Schwer resultant beams
//!   (`*SECTION_BEAM`, ELFORM = 2) with the box section's area, second
//!   moments, torsion constant J = 2 t (d−t)² (h−t)² / (d + h − 2t) and the
//!   area as shear area; orientation by a third node (local s along the
//!   section's depth);
//! - materials: `*MAT_ELASTIC`, or `*MAT_RESULTANT_PLASTICITY` (initial
//!   yield stress, hardening slope of the first segment) when a yield curve
//!   is given;
//! - the car: `bumpsim export lsdyna`'s include, its nodal rigid body tying
//!   the crash boxes' rear nodes to m1 (ids from 1000 above the bumper's);
//! - striker: `*RIGIDWALL_PLANAR` on the beam nodes (barrier), or
//!   `*RIGIDWALL_PLANAR_MOVING` with the pendulum's mass and speed;
//! - the beam held out of plane (`*BOUNDARY_SPC_SET`: z, rx, ry), initial
//!   velocity of bumper and car (barrier), `*CONTROL_TERMINATION`, and
//!   `RWFORC`, `GLSTAT`, `MATSUM`, `NODOUT`, `DEFORC` and d3plot outputs.

use crate::FeError;
use crate::bumper::{BoxSection, BumperMesh, Material};
use bumpsim_core::model::MsdModel;
use bumpsim_export::cards;
use bumpsim_export::layout::{Layout, UnitSystem, int_field, real_field};
use bumpsim_export::lsdyna::{LsDynaOptions, lsdyna_include};
use bumpsim_impact::impact::Scenario;

/// Settings of the LS-DYNA deck.
#[derive(Debug, Clone, PartialEq)]
pub struct LsDynaRun {
    /// Deck units.
    pub units: UnitSystem,
    /// Termination time, s.
    pub duration: f64,
    /// Output interval of the histories, s.
    pub output_interval: f64,
}

struct Writer<'a> {
    deck: String,
    u: UnitSystem,
    mesh: &'a BumperMesh,
}

fn i8(v: u64) -> String {
    int_field(v, 8)
}
fn i10(v: u64) -> String {
    int_field(v, 10)
}
fn r10(v: f64) -> String {
    real_field(v, 10)
}

impl Writer<'_> {
    fn stress(&self) -> f64 {
        self.u.force() / (self.u.length() * self.u.length())
    }

    fn line(&mut self, text: &str) {
        self.deck.push_str(text);
        self.deck.push('\n');
    }

    fn node(&mut self, id: u64, p: [f64; 3]) {
        let l = self.u.length();
        cards::node_line(&mut self.deck, id, p.map(|c| c * l), None);
    }

    fn section(&mut self, id: u64, s: &BoxSection) {
        let (d, h, t) = (s.depth, s.height, s.wall);
        let about_t = (h * d.powi(3) - (h - 2.0 * t) * (d - 2.0 * t).powi(3)) / 12.0;
        let about_s = (d * h.powi(3) - (d - 2.0 * t) * (h - 2.0 * t).powi(3)) / 12.0;
        let torsion = 2.0 * t * (d - t).powi(2) * (h - t).powi(2) / (d + h - 2.0 * t);
        let (l2, l4) = (self.u.length().powi(2), self.u.length().powi(4));
        self.line("*SECTION_BEAM\n$  secid    elform      shrf   qr/irid       cst");
        let card = format!("{}{}{}{}{}", i10(id), i10(2), r10(1.0), r10(2.0), r10(0.0));
        self.line(&card);
        self.line("$      a       iss       itt         j        sa");
        let area = s.area() * l2;
        let card = format!(
            "{}{}{}{}{}",
            r10(area),
            r10(about_s * l4),
            r10(about_t * l4),
            r10(torsion * l4),
            r10(area)
        );
        self.line(&card);
    }

    fn material(&mut self, id: u64, m: &Material) {
        let rho = m.density * self.u.mass() / self.u.length().powi(3);
        let (e, nu) = (m.youngs_modulus * self.stress(), m.poisson);
        let card = format!("{}{}{}{}", i10(id), r10(rho), r10(e), r10(nu));
        match m.yield_curve.as_slice() {
            [] => {
                self.line("*MAT_ELASTIC\n$    mid        ro         e        pr");
                self.line(&card);
            }
            points => {
                let hardening = match points {
                    [a, b, ..] => (b[0] - a[0]) / (b[1] - a[1]),
                    _ => 0.0,
                };
                self.line("*MAT_RESULTANT_PLASTICITY\n$    mid        ro         e        pr      sigy      etan");
                let card = format!(
                    "{card}{}{}",
                    r10(points[0][0] * self.stress()),
                    r10(hardening * self.stress())
                );
                self.line(&card);
            }
        }
    }

    fn part(&mut self, id: u64, title: &str) {
        cards::part(&mut self.deck, title, id, id, id);
    }
}

/// Node ids of the written bumper.
struct Nodes {
    beam: Vec<u64>,
    boxes: [Vec<u64>; 2],
    orientation: [u64; 2],
}

fn nodes(w: &mut Writer) -> Nodes {
    let (mesh, x) = (w.mesh, -w.mesh.crash_boxes.length);
    cards::node_keyword(&mut w.deck, false);
    let ys = mesh.beam_node_y();
    let beam: Vec<u64> = (1..=ys.len() as u64).collect();
    for (&id, &y) in beam.iter().zip(&ys) {
        w.node(id, [x, y, 0.0]);
    }
    let mut next = beam.len() as u64;
    let per_box = 2 * mesh.crash_boxes.elements;
    let boxes = mesh.crash_box_nodes().map(|index| {
        let y = ys[index];
        let mut chain = vec![beam[index]];
        for j in 1..=per_box {
            next += 1;
            w.node(
                next,
                [
                    x + mesh.crash_boxes.length * j as f64 / per_box as f64,
                    y,
                    0.0,
                ],
            );
            chain.push(next);
        }
        chain
    });
    // beam: local s along x (the section's depth); boxes: local s along y
    let orientation = [next + 1, next + 2];
    w.node(orientation[0], [x + 1.0, 0.0, 0.0]);
    w.node(orientation[1], [x / 2.0, 10.0 * mesh.beam.width, 0.0]);
    Nodes {
        beam,
        boxes,
        orientation,
    }
}

fn elements(w: &mut Writer, n: &Nodes) {
    w.line("*ELEMENT_BEAM\n$    eid     pid      n1      n2      n3");
    let mut id = 0;
    let mut beam = |w: &mut Writer, pid: u64, a: u64, b: u64, o: u64| {
        id += 1;
        let row = format!("{}{}{}{}{}", i8(id), i8(pid), i8(a), i8(b), i8(o));
        w.line(&row);
    };
    for pair in n.beam.windows(2) {
        beam(w, 1, pair[0], pair[1], n.orientation[0]);
    }
    for chain in &n.boxes {
        for pair in chain.windows(2) {
            beam(w, 2, pair[0], pair[1], n.orientation[1]);
        }
    }
}

/// Writes the LS-DYNA deck of the coupled model.
pub fn lsdyna_deck(
    mesh: &BumperMesh,
    car: &MsdModel,
    scenario: Scenario,
    run: &LsDynaRun,
) -> Result<String, FeError> {
    mesh.validate()?;
    crate::run::check_scenario(scenario)?;
    crate::run::check_run(run.duration, run.output_interval, "output interval")?;
    let mut w = Writer {
        deck: String::new(),
        u: run.units,
        mesh,
    };
    let title = format!(
        "bumpsim {}: {} coupled to a {}-DOF MSD car",
        env!("CARGO_PKG_VERSION"),
        mesh.name.as_deref().unwrap_or("parametric bumper"),
        car.dof()
    );
    cards::titled(&mut w.deck, &title);
    cards::units_comment(&mut w.deck, run.units);
    let n = nodes(&mut w);
    w.section(1, &mesh.beam.section);
    w.section(2, &mesh.crash_boxes.section);
    w.material(1, &mesh.beam.material);
    w.material(2, &mesh.crash_boxes.material);
    w.part(1, "bumper beam");
    w.part(2, "crash boxes");
    elements(&mut w, &n);
    let everything: Vec<u64> = n
        .beam
        .iter()
        .chain(n.boxes.iter().flat_map(|c| c[1..].iter()))
        .copied()
        .collect();
    cards::node_set(&mut w.deck, 1, &n.beam);
    cards::node_set(&mut w.deck, 2, &everything);
    w.line("*BOUNDARY_SPC_SET\n$   nsid       cid      dofx      dofy      dofz     dofrx     dofry     dofrz");
    let spc = format!(
        "{}{}{}{}{}{}{}{}",
        i10(1),
        i10(0),
        i10(0),
        i10(0),
        i10(1),
        i10(1),
        i10(1),
        i10(0)
    );
    w.line(&spc);
    striker(&mut w, scenario);
    let offset = n.orientation[1].max(everything.len() as u64) + 1000;
    car_include(&mut w, car, scenario, run, &n, offset)?;
    let time = run.units.time();
    cards::termination(&mut w.deck, run.duration * time);
    for keyword in ["*DATABASE_RWFORC", "*DATABASE_MATSUM"] {
        cards::database(&mut w.deck, keyword, run.output_interval * time);
    }
    cards::database(
        &mut w.deck,
        "*DATABASE_BINARY_D3PLOT",
        run.duration * time / 50.0,
    );
    w.line("*END");
    Ok(w.deck)
}

fn striker(w: &mut Writer, scenario: Scenario) {
    let x = -w.mesh.crash_boxes.length * w.u.length();
    let head = x + w.u.length();
    let geometry = format!(
        "{}{}{}{}{}{}{}",
        r10(x),
        r10(0.0),
        r10(0.0),
        r10(head),
        r10(0.0),
        r10(0.0),
        r10(0.0)
    );
    let name = match scenario {
        Scenario::Barrier { .. } => "*RIGIDWALL_PLANAR",
        Scenario::Impactor { .. } => "*RIGIDWALL_PLANAR_MOVING",
    };
    w.line(&format!(
        "{name}\n$   nsid    nsidex     boxid\n{}{}{}",
        i10(1),
        i10(0),
        i10(0)
    ));
    w.line("$     xt        yt        zt        xh        yh        zh      fric");
    w.line(&geometry);
    if let Scenario::Impactor { mass, speed } = scenario {
        w.line("$   mass        v0");
        let card = format!("{}{}", r10(mass * w.u.mass()), r10(speed * w.u.velocity()));
        w.line(&card);
    }
    if let Scenario::Barrier { speed } = scenario {
        let set = format!("{}{}{}", i10(2), i10(0), i10(0));
        w.line(&format!(
            "*INITIAL_VELOCITY\n$   nsid    nsidex     boxid\n{set}"
        ));
        w.line("$     vx        vy        vz");
        let card = format!("{}{}{}", r10(-speed * w.u.velocity()), r10(0.0), r10(0.0));
        w.line(&card);
    }
}

fn car_include(
    w: &mut Writer,
    car: &MsdModel,
    scenario: Scenario,
    run: &LsDynaRun,
    n: &Nodes,
    offset: u64,
) -> Result<(), FeError> {
    let options = LsDynaOptions {
        layout: Layout {
            units: run.units,
            ..Layout::default()
        },
        id_offset: offset,
        attach: n.boxes.iter().filter_map(|c| c.last().copied()).collect(),
        initial_velocity: match scenario {
            Scenario::Barrier { speed } => Some(-speed),
            Scenario::Impactor { .. } => None,
        },
        title: "the MSD car".into(),
        output_interval: Some(run.output_interval),
        ..Default::default()
    };
    let include = lsdyna_include(car, &options)?;
    for line in include.lines().filter(|l| *l != "*KEYWORD" && *l != "*END") {
        w.line(line);
    }
    Ok(())
}
