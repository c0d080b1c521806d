//! CalculiX/Abaqus input deck of an MSD car model, and reading its results
//! back (spec §8; CalculiX CrunchiX User's Manual 2.20).
//!
//! The deck: `*NODE` (node i is m_i, on the axis), `*ELEMENT, TYPE=MASS` with
//! `*MASS`, `TYPE=SPRINGA` with `*SPRING` (k_j) and `TYPE=DASHPOTA` with
//! `*DASHPOT` (c_j) between nodes j and j+1, `*BOUNDARY` on the two
//! directions across the axis, and optional `*INITIAL CONDITIONS,
//! TYPE=VELOCITY`. With a force history it is a complete analysis:
//! `*AMPLITUDE` (the force, time shifted so the first sample is at 0),
//! `*CLOAD` on node 1 along the axis, `*DYNAMIC, DIRECT, ALPHA=0` (trapezoidal
//! rule: no numerical damping, unconditionally stable, second order) with a
//! fixed increment, and `*NODE PRINT` of U to the `.dat` file.
//!
//! A comment line `** bumpsim-deck: units=.. axis=.. start=.. dof=..` records
//! what is needed to map the `.dat` results back to SI model displacements
//! ([`read_results`]).

use crate::ExportError;
use crate::layout::{Axis, Layout, UnitSystem};
use bumpsim_core::model::MsdModel;
use bumpsim_core::series::UniformSeries;
use std::fmt::Write;
use std::path::Path;

/// A transient analysis under a force on m1.
#[derive(Debug, Clone, PartialEq)]
pub struct Analysis {
    /// Force on m1 along the axis, N (SI).
    pub force: UniformSeries,
    /// Fixed time increment, s; default the force's sample interval.
    pub increment: Option<f64>,
    /// Write results every this many increments (at least 1).
    pub output_every: usize,
}

/// Options of the CalculiX export.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CalculixOptions {
    /// Units, axis and node placement.
    pub layout: Layout,
    /// Initial velocity of every mass along the axis, m/s (SI).
    pub initial_velocity: Option<f64>,
    /// The transient analysis; without it the deck holds the model only.
    pub analysis: Option<Analysis>,
    /// Title comment.
    pub title: String,
}

/// Writes the deck text.
pub fn calculix_deck(model: &MsdModel, options: &CalculixOptions) -> Result<String, ExportError> {
    let layout = &options.layout;
    let n = model.dof();
    let mut deck = String::new();
    let start = options.analysis.as_ref().map_or(0.0, |a| a.force.start());
    let [m, l, t, f] = layout.units.symbols();
    let _ = writeln!(
        deck,
        "** {}\n** bumpsim {}: {n}-DOF chain MSD car model (Isaksson 2006, ch. 3.3)",
        options.title,
        env!("CARGO_PKG_VERSION")
    );
    let _ = writeln!(
        deck,
        "** units: mass {m}, length {l}, time {t}, force {f}; node i is mass m_i"
    );
    let _ = writeln!(
        deck,
        "** bumpsim-deck: units={} axis={} start={start:e} dof={n}",
        layout.units, layout.axis
    );
    let _ = writeln!(deck, "*NODE, NSET=NALL");
    for i in 0..n {
        let p = layout.node_position(i);
        let _ = writeln!(
            deck,
            "{}, {}, {}, {}",
            i + 1,
            real(p[0]),
            real(p[1]),
            real(p[2])
        );
    }
    for (i, mass) in model.masses().iter().enumerate() {
        let _ = writeln!(
            deck,
            "*ELEMENT, TYPE=MASS, ELSET=EM{0}\n{0}, {0}\n*MASS, ELSET=EM{0}\n{1}",
            i + 1,
            real(mass * layout.units.mass())
        );
    }
    // springs are elements n + j, dampers 2n + j; a zero damper gets no element
    let links = [
        (
            "SPRINGA",
            "SPRING",
            "EK",
            n,
            model.springs(),
            layout.units.stiffness(),
        ),
        (
            "DASHPOTA",
            "DASHPOT",
            "EC",
            2 * n,
            model.dampers(),
            layout.units.damping(),
        ),
    ];
    for (element, card, set, base, values, factor) in links {
        for (j, value) in values.iter().enumerate().filter(|(_, v)| **v > 0.0) {
            let (id, value) = (base + j + 1, real(value * factor));
            let (a, b) = (j + 1, j + 2);
            let _ = writeln!(
                deck,
                "*ELEMENT, TYPE={element}, ELSET={set}{a}\n{id}, {a}, {b}\n*{card}, ELSET={set}{a}\n\n{value}"
            );
        }
    }
    let _ = writeln!(deck, "*BOUNDARY");
    for dof in layout.axis.other_dofs() {
        let _ = writeln!(deck, "NALL, {dof}, {dof}");
    }
    if let Some(v) = options.initial_velocity {
        let _ = writeln!(
            deck,
            "*INITIAL CONDITIONS, TYPE=VELOCITY\nNALL, {}, {}",
            layout.axis.dof(),
            real(v * layout.axis.sign * layout.units.velocity())
        );
    }
    if let Some(analysis) = &options.analysis {
        transient(&mut deck, analysis, layout)?;
    }
    Ok(deck)
}

/// A real as CalculiX reads it: always with a decimal point (`5e5` is misread), 13 digits.
fn real(value: f64) -> String {
    format!("{:.12e}", value + 0.0)
}

fn transient(deck: &mut String, analysis: &Analysis, layout: &Layout) -> Result<(), ExportError> {
    let force = &analysis.force;
    let increment = analysis.increment.unwrap_or(force.step());
    if !(increment.is_finite() && increment > 0.0) {
        return Err(ExportError::Increment { increment });
    }
    if analysis.output_every == 0 {
        return Err(ExportError::OutputInterval);
    }
    if force.len() < 2 {
        return Err(ExportError::ForceSamples {
            samples: force.len(),
        });
    }
    let units = layout.units;
    let _ = writeln!(deck, "*AMPLITUDE, NAME=FORCE");
    let pairs: Vec<String> = (0..force.len())
        .map(|k| {
            format!(
                "{}, {}",
                real((force.time(k) - force.start()) * units.time()),
                real(force.values()[k] * units.force())
            )
        })
        .collect();
    for chunk in pairs.chunks(2) {
        let _ = writeln!(deck, "{}", chunk.join(", "));
    }
    let duration = (force.end() - force.start()) * units.time();
    let dt = increment * units.time();
    let increments = (duration / dt).ceil() as u64 + 10;
    let _ = writeln!(
        deck,
        "*STEP, INC={increments}\n*DYNAMIC, DIRECT, ALPHA=0.0\n{}, {}",
        real(dt),
        real(duration)
    );
    let _ = writeln!(
        deck,
        "*CLOAD, AMPLITUDE=FORCE\n1, {}, {:.1}",
        layout.axis.dof(),
        layout.axis.sign
    );
    let _ = writeln!(
        deck,
        "*NODE PRINT, NSET=NALL, FREQUENCY={}\nU\n*END STEP",
        analysis.output_every
    );
    Ok(())
}

/// Displacements read back from a CalculiX run, SI, along the model axis.
#[derive(Debug, Clone, PartialEq)]
pub struct Results {
    /// Times, s (the force's time base: the deck's shift is undone).
    pub time: Vec<f64>,
    /// x_i per mass (outer) and time (inner), m, positive along the model +x.
    pub displacement: Vec<Vec<f64>>,
}

/// Reads the `.dat` results of a deck written by [`calculix_deck`]: the deck's
/// `bumpsim-deck` line gives units, axis, time shift and DOF; the `.dat` file
/// beside it (same stem) gives the displacements.
pub fn read_results(deck_path: &Path) -> Result<Results, ExportError> {
    let deck = read(deck_path)?;
    let meta = DeckMeta::parse(&deck).ok_or_else(|| ExportError::Dat {
        path: deck_path.into(),
        line: 0,
        reason: "no '** bumpsim-deck:' line: not a deck written by bumpsim export calculix".into(),
    })?;
    if meta.dof == 0 || meta.dof > MAX_DECK_DOF || !meta.start.is_finite() {
        return Err(ExportError::Dat {
            path: deck_path.into(),
            line: 0,
            reason: format!(
                "'** bumpsim-deck:' line: dof = {} (expected 1 to {MAX_DECK_DOF}), start = {} s (expected finite)",
                meta.dof, meta.start
            ),
        });
    }
    let dat_path = deck_path.with_extension("dat");
    let dat = read(&dat_path)?;
    parse_dat(&dat, &dat_path, &meta)
}

/// Most masses a deck read back may declare (a guard against a corrupt
/// `dof=` on the deck's `bumpsim-deck` line).
pub const MAX_DECK_DOF: usize = 10_000;

fn read(path: &Path) -> Result<String, ExportError> {
    std::fs::read_to_string(path).map_err(|e| ExportError::Dat {
        path: path.into(),
        line: 0,
        reason: format!("cannot read: {e}"),
    })
}

struct DeckMeta {
    units: UnitSystem,
    axis: Axis,
    start: f64,
    dof: usize,
}

impl DeckMeta {
    fn parse(deck: &str) -> Option<DeckMeta> {
        let line = deck
            .lines()
            .find_map(|l| l.strip_prefix("** bumpsim-deck:"))?;
        let value = |key: &str| {
            line.split_whitespace()
                .find_map(|w| w.strip_prefix(key)?.strip_prefix('='))
        };
        Some(DeckMeta {
            units: value("units")?.parse().ok()?,
            axis: value("axis")?.parse().ok()?,
            start: value("start")?.parse().ok()?,
            dof: value("dof")?.parse().ok()?,
        })
    }
}

fn parse_dat(text: &str, path: &Path, meta: &DeckMeta) -> Result<Results, ExportError> {
    let error = |line: usize, reason: String| ExportError::Dat {
        path: path.into(),
        line,
        reason,
    };
    let mut results = Results {
        time: Vec::new(),
        displacement: vec![Vec::new(); meta.dof],
    };
    let mut counts = vec![0usize; meta.dof];
    for (index, line) in text.lines().enumerate() {
        let words: Vec<&str> = line.split_whitespace().collect();
        if line.contains("displacements") {
            let time: f64 = words
                .last()
                .and_then(|w| w.parse().ok())
                .filter(|t: &f64| t.is_finite())
                .ok_or_else(|| error(index + 1, "block header without a finite time".into()))?;
            let time = time / meta.units.time() + meta.start;
            if counts.iter().any(|&c| c != results.time.len()) {
                return Err(error(
                    index + 1,
                    "the previous displacement block does not list every mass node once (truncated?)".into(),
                ));
            }
            if results.time.last().is_some_and(|&last| time <= last) {
                return Err(error(
                    index + 1,
                    format!("block time {time} s does not increase (a duplicate block?)"),
                ));
            }
            results.time.push(time);
        } else if words.len() == 4 {
            let numbers: Option<Vec<f64>> = words.iter().map(|w| w.parse().ok()).collect();
            let numbers = numbers.ok_or_else(|| {
                error(
                    index + 1,
                    format!(
                        "expected a node and three displacements, found '{}'",
                        line.trim()
                    ),
                )
            })?;
            if let Some(v) = numbers.iter().find(|v| !v.is_finite()) {
                return Err(error(
                    index + 1,
                    format!("value {v}: expected finite numbers"),
                ));
            }
            let node = numbers[0] as usize;
            if node == 0 || node > meta.dof || results.time.is_empty() {
                return Err(error(
                    index + 1,
                    format!(
                        "node {node} is not a mass node 1..{} of a displacement block",
                        meta.dof
                    ),
                ));
            }
            if counts[node - 1] == results.time.len() {
                return Err(error(
                    index + 1,
                    format!("node {node} appears twice in one displacement block"),
                ));
            }
            let along = numbers[meta.axis.component + 1] * meta.axis.sign / meta.units.length();
            results.displacement[node - 1].push(along);
            counts[node - 1] += 1;
        }
    }
    if results.time.is_empty() || counts.iter().any(|&c| c != results.time.len()) {
        return Err(error(
            0,
            format!(
                "expected every node in each of the {} displacement blocks (a truncated run?)",
                results.time.len()
            ),
        ));
    }
    Ok(results)
}
