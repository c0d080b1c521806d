//! CalculiX/Abaqus input deck of an MSD car model, and reading its results
//! back (spec §8; CalculiX CrunchiX User's Manual 2.20).
//!
//! The deck: `*NODE` (node offset + i is m_i, on the axis), `*ELEMENT,
//! TYPE=MASS` with `*MASS`, `TYPE=SPRING2` with `*SPRING` (k_j, between
//! the axis's degree of freedom of both nodes: F = k_j (u_{j+1} − u_j)
//! whatever the crush, where a `SPRINGA` along the line between its nodes
//! turns over once they cross) and `TYPE=DASHPOTA` with `*DASHPOT` (c_j)
//! between nodes j and j+1, `*BOUNDARY`
//! on the two directions across the axis, and optional `*INITIAL
//! CONDITIONS, TYPE=VELOCITY`. With a force history it is a complete
//! analysis: `*AMPLITUDE` (the force, time shifted so the first sample is at
//! 0), `*CLOAD` on m1 along the axis, `*DYNAMIC, DIRECT, ALPHA=0`
//! (trapezoidal rule: no numerical damping, unconditionally stable, second
//! order) with a fixed increment, and `*NODE PRINT` of U to the `.dat` file.
//!
//! **Include-safe.** Node and element ids are `id_offset + k`; every set and
//! the amplitude carry a name prefix (default `BUMPSIM_`: `BUMPSIM_NALL`,
//! `BUMPSIM_EM1`, `BUMPSIM_FORCE`), and constraints and initial conditions
//! act on the car's own set only, so the deck can be `*INCLUDE`d in a model
//! with its own `Nall` set and low node ids (issue 16; tested in `ccx`).
//!
//! **Coupling.** With attachment nodes, each follows m1 along the axis by a
//! two-term `*EQUATION` (the axial part of LS-DYNA's nodal rigid body; the
//! user's model supports the attachment nodes across the axis).
//!
//! A comment line `** bumpsim-deck: units=.. axis=.. start=.. dof=..` records
//! what is needed to map the `.dat` results back to SI model displacements
//! ([`read_results`]).

use crate::ExportError;
use crate::cards::Link;
use crate::inp::{self, Print, real};
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
#[derive(Debug, Clone, PartialEq)]
pub struct CalculixOptions {
    /// Units, axis and node placement.
    pub layout: Layout,
    /// Initial velocity of every mass along the axis, m/s (SI).
    pub initial_velocity: Option<f64>,
    /// The transient analysis; without it the deck holds the model only.
    pub analysis: Option<Analysis>,
    /// Title comment.
    pub title: String,
    /// Added to every node and element id.
    pub id_offset: u64,
    /// Prefix of every set and amplitude name (letters, digits, `_`).
    pub prefix: String,
    /// The user's bumper attachment node ids, tied to m1 along the axis.
    pub attach: Vec<u64>,
}

impl Default for CalculixOptions {
    fn default() -> Self {
        CalculixOptions {
            layout: Layout::default(),
            initial_velocity: None,
            analysis: None,
            title: String::new(),
            id_offset: 0,
            prefix: DEFAULT_PREFIX.to_string(),
            attach: Vec::new(),
        }
    }
}

/// The default prefix of set and amplitude names.
pub const DEFAULT_PREFIX: &str = "BUMPSIM_";

/// Largest node or element id CalculiX reads (a 32-bit integer).
pub const MAX_CALCULIX_ID: u64 = 2_147_483_647;

/// Checks a set-name prefix: letters, digits and `_`, not first a digit, at most 40.
pub fn check_prefix(prefix: &str) -> Result<(), ExportError> {
    if !prefix
        .chars()
        .all(|c| c.is_ascii_alphanumeric() || c == '_')
        || prefix.starts_with(|c: char| c.is_ascii_digit())
        || prefix.len() > 40
    {
        return Err(ExportError::Prefix {
            prefix: prefix.to_string(),
        });
    }
    Ok(())
}

fn check_names(model: &MsdModel, options: &CalculixOptions, extra: u64) -> Result<(), ExportError> {
    check_prefix(&options.prefix)?;
    let last = options
        .id_offset
        .saturating_add(3 * model.dof() as u64)
        .saturating_add(extra);
    if last > MAX_CALCULIX_ID {
        return Err(ExportError::IdRange {
            offset: options.id_offset,
            last,
            limit: MAX_CALCULIX_ID,
        });
    }
    let first = options.id_offset + 1;
    crate::check_attach(
        &options.attach,
        first..=first + model.dof() as u64 - 1,
        MAX_CALCULIX_ID,
    )
}

/// The user's attachment nodes follow m1 along the axis: one two-term
/// `*EQUATION` each (u_a − u_m1 = 0 in the axis direction).
fn coupling(deck: &mut String, options: &CalculixOptions) {
    if options.attach.is_empty() {
        return;
    }
    let (dof, m1) = (options.layout.axis.dof(), options.id_offset + 1);
    let _ = writeln!(
        deck,
        "** coupling: the attachment nodes follow m1 (node {m1}) along the axis\n*EQUATION"
    );
    for node in &options.attach {
        let _ = writeln!(deck, "2\n{node}, {dof}, 1.0, {m1}, {dof}, -1.0");
    }
}

/// Writes the deck text.
pub fn calculix_deck(model: &MsdModel, options: &CalculixOptions) -> Result<String, ExportError> {
    deck(model, None, options)
}

/// What a deck of nonlinear links adds to the linear chain's (the chain's
/// CalculiX module implements it): extra ids, its springs, a front link,
/// supports, ties and its own run.
pub(crate) trait Extra {
    /// Ids beyond the linear deck's.
    fn extra_ids(&self) -> u64;
    /// Spring `j` as element `id` in the set `elset`.
    fn spring(&self, deck: &mut String, j: usize, elset: &str, id: u64, options: &CalculixOptions);
    /// Cards after the springs (a front link).
    fn front(&self, deck: &mut String, options: &CalculixOptions);
    /// Supports beyond the mass nodes' cross directions.
    fn held(&self, model: &MsdModel, options: &CalculixOptions) -> Vec<(String, usize, usize)>;
    /// Equations after the coupling.
    fn ties(&self, deck: &mut String, options: &CalculixOptions);
    /// The step, when there is no force analysis.
    fn run(
        &self,
        deck: &mut String,
        model: &MsdModel,
        options: &CalculixOptions,
    ) -> Result<(), ExportError>;
}

/// The deck of `model`, with the nonlinear links and run of `chain` when given.
pub(crate) fn deck(
    model: &MsdModel,
    chain: Option<&dyn Extra>,
    options: &CalculixOptions,
) -> Result<String, ExportError> {
    check_names(model, options, chain.map_or(0, |c| c.extra_ids()))?;
    let analysis = options.analysis.as_ref();
    let increment = analysis
        .and_then(|a| a.increment)
        .map(|dt| ("the increment", dt));
    crate::check_finite(
        model,
        &options.layout,
        options.initial_velocity,
        analysis.map(|a| &a.force),
        increment.as_slice(),
    )?;
    let layout = &options.layout;
    let n = model.dof();
    let (offset, set) = (options.id_offset, &options.prefix);
    let mut deck = String::new();
    let start = options.analysis.as_ref().map_or(0.0, |a| a.force.start());
    let [m, l, t, f] = layout.units.symbols();
    let what = match chain {
        None => "MSD car model (Isaksson 2006, ch. 3.3)",
        Some(_) => "car model with nonlinear links",
    };
    let _ = writeln!(
        deck,
        "** {}\n** bumpsim {}: {n}-DOF chain {what}",
        bumpsim_core::names::printable(&options.title),
        env!("CARGO_PKG_VERSION")
    );
    let _ = writeln!(
        deck,
        "** units: mass {m}, length {l}, time {t}, force {f}; node {} + i is mass m_i",
        offset
    );
    let _ = writeln!(
        deck,
        "** bumpsim-deck: units={} axis={} start={start:e} dof={n} offset={offset} prefix={set}",
        layout.units, layout.axis
    );
    let all = format!("{set}NALL");
    inp::node_keyword(&mut deck, &all);
    for i in 0..n {
        inp::node_line(&mut deck, offset + i as u64 + 1, layout.node_position(i));
    }
    for (i, mass) in model.masses().iter().enumerate() {
        let (elset, id) = (format!("{set}EM{}", i + 1), offset + i as u64 + 1);
        inp::mass_element(&mut deck, &elset, id, id, mass * layout.units.mass());
    }
    links(&mut deck, model, chain, options);
    if let Some(chain) = chain {
        chain.front(&mut deck, options);
    }
    let mut held: Vec<_> = layout
        .axis
        .other_dofs()
        .map(|dof| (all.clone(), dof, dof))
        .into();
    if let Some(chain) = chain {
        held.extend(chain.held(model, options));
    }
    inp::boundary(&mut deck, &held);
    coupling(&mut deck, options);
    if let Some(chain) = chain {
        chain.ties(&mut deck, options);
    }
    if let Some(v) = options.initial_velocity {
        let v = v * layout.axis.sign * layout.units.velocity();
        inp::initial_velocity(&mut deck, &[(&all, layout.axis.dof(), v)]);
    }
    if let Some(analysis) = &options.analysis {
        transient(&mut deck, analysis, options)?;
    } else if let Some(chain) = chain {
        chain.run(&mut deck, model, options)?;
    }
    Ok(deck)
}

/// Springs are elements offset + n + j, dampers offset + 2n + j; a zero damper gets no element.
fn links(
    deck: &mut String,
    model: &MsdModel,
    chain: Option<&dyn Extra>,
    options: &CalculixOptions,
) {
    let (n, units, set) = (model.dof() as u64, options.layout.units, &options.prefix);
    let links = [
        (Link::Spring, "EK", n, model.springs(), units.stiffness()),
        (Link::Damper, "EC", 2 * n, model.dampers(), units.damping()),
    ];
    for (link, kind, base, values, factor) in links {
        for (j, value) in values.iter().enumerate().filter(|(_, v)| **v > 0.0) {
            let node = |k: usize| options.id_offset + k as u64;
            let id = options.id_offset + base + j as u64 + 1;
            let elset = format!("{set}{kind}{}", j + 1);
            let nodes = [node(j + 1), node(j + 2)];
            if let (Link::Spring, Some(chain)) = (link, chain) {
                chain.spring(deck, j, &elset, id, options);
                continue;
            }
            let dof = options.layout.axis.dof();
            inp::axial_link_element(deck, link, &elset, id, nodes, dof, value * factor);
        }
    }
}

fn transient(
    deck: &mut String,
    analysis: &Analysis,
    options: &CalculixOptions,
) -> Result<(), ExportError> {
    let (layout, set) = (&options.layout, &options.prefix);
    let force = &analysis.force;
    let increment = analysis.increment.unwrap_or(force.step());
    if analysis.output_every == 0 {
        return Err(ExportError::OutputInterval);
    }
    if force.len() < 2 {
        return Err(ExportError::ForceSamples {
            samples: force.len(),
        });
    }
    let units = layout.units;
    let points = (0..force.len()).map(|k| {
        (
            (force.time(k) - force.start()) * units.time(),
            force.values()[k] * units.force(),
        )
    });
    amplitude(deck, &format!("{set}FORCE"), points);
    let duration = force.end() - force.start();
    dynamic_step(deck, increment, duration, units)?;
    let _ = writeln!(
        deck,
        "*CLOAD, AMPLITUDE={set}FORCE\n{}, {}, {:.1}",
        options.id_offset + 1,
        layout.axis.dof(),
        layout.axis.sign
    );
    let every = Print::Every(analysis.output_every);
    inp::node_print(deck, &format!("{set}NALL"), every, "U");
    deck.push_str("*END STEP\n");
    Ok(())
}

/// `*AMPLITUDE, NAME=name` of (time, value) points in deck units, two to a line.
pub fn amplitude(deck: &mut String, name: &str, points: impl Iterator<Item = (f64, f64)>) {
    let _ = writeln!(deck, "*AMPLITUDE, NAME={name}");
    let pairs: Vec<String> = points
        .map(|(t, v)| format!("{}, {}", real(t), real(v)))
        .collect();
    for chunk in pairs.chunks(2) {
        let _ = writeln!(deck, "{}", chunk.join(", "));
    }
}

/// `*STEP` and `*DYNAMIC, DIRECT, ALPHA=0.0` (trapezoidal rule) with a fixed
/// `increment` over `duration` (both s, SI; written in `units`); refuses
/// an increment beyond the duration or below [`crate::MIN_INTERVAL`], and
/// more increments than CalculiX's 32-bit `INC` holds.
pub fn dynamic_step(
    deck: &mut String,
    increment: f64,
    duration: f64,
    units: UnitSystem,
) -> Result<(), ExportError> {
    crate::check_interval("increment", increment, Some(duration), f64::INFINITY)?;
    let (dt, length) = (increment * units.time(), duration * units.time());
    // `as u64` saturated and `+ 10` overflowed (a panic in debug, INC=9 in
    // release) for --increment 1e-300; INC is a 32-bit integer in CalculiX
    let count = (length / dt).ceil() + 10.0;
    if count.is_nan() || count > MAX_CALCULIX_ID as f64 {
        return Err(ExportError::Increments {
            increment,
            count,
            duration,
            limit: MAX_CALCULIX_ID,
        });
    }
    let _ = writeln!(
        deck,
        "*STEP, INC={}\n*DYNAMIC, DIRECT, ALPHA=0.0\n{}, {}",
        count as u64,
        real(dt),
        real(length)
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
    let results = parse_dat(&dat, &dat_path, &meta)?;
    check_complete(&dat, &dat_path, analysis_end(&deck), &results, &meta)?;
    Ok(results)
}

/// The end of the deck's analysis and its increment, both in deck time
/// units, for a deck that runs one with fixed increments, as
/// [`calculix_deck`] writes (`*DYNAMIC, DIRECT` and the line after it:
/// increment, period).
fn analysis_end(deck: &str) -> Option<(f64, f64)> {
    let mut lines = deck.lines();
    lines.find(|l| {
        let l = l.trim_start().to_ascii_uppercase();
        l.starts_with("*DYNAMIC") && l.contains("DIRECT")
    })?;
    let mut numbers = lines
        .next()?
        .split(',')
        .map(|w| w.trim().parse::<f64>().ok());
    let (increment, period) = (numbers.next()??, numbers.next()??);
    Some((period, increment))
}

/// Refuses a `.dat` that a run cut short or a copy cut off: one that ends
/// mid-line, or whose last print is not the end of the deck's analysis
/// (CalculiX prints the last increment of a step whatever the print
/// frequency; the `.dat` gives times to 7 digits).
fn check_complete(
    dat: &str,
    path: &Path,
    end: Option<(f64, f64)>,
    results: &Results,
    meta: &DeckMeta,
) -> Result<(), ExportError> {
    let error = |line: usize, reason: String| ExportError::Dat {
        path: path.into(),
        line,
        reason,
    };
    if !dat.ends_with('\n') {
        return Err(error(
            dat.lines().count(),
            "the file ends mid-line: the run was cut short or the file cut off".into(),
        ));
    }
    let last = results
        .time
        .last()
        .map_or(0.0, |t| (t - meta.start) * meta.units.time());
    match end {
        Some((period, increment)) if last < period - (0.5 * increment).max(1e-6 * period) => {
            Err(error(
                0,
                format!(
                    "the results end at t = {} s but the deck's analysis runs to {} s: the run stopped early or the file was cut off",
                    last / meta.units.time() + meta.start,
                    period / meta.units.time() + meta.start
                ),
            ))
        }
        _ => Ok(()),
    }
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
    /// Node id offset (0 in decks written before it existed).
    offset: u64,
    /// Set name prefix ("" in decks written before it existed).
    prefix: String,
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
            offset: value("offset").map_or(Some(0), |v| v.parse().ok())?,
            prefix: value("prefix").unwrap_or("").to_string(),
        })
    }
}

fn parse_dat(text: &str, path: &Path, meta: &DeckMeta) -> Result<Results, ExportError> {
    let error = |line: usize, reason: String| ExportError::Dat {
        path: path.into(),
        line,
        reason,
    };
    // only the blocks of the car's own set: a main deck may print others
    let blocks = crate::dat::parse(text, path)?;
    let set = format!("{}NALL", meta.prefix);
    let blocks = crate::dat::history(&blocks, "displacements", &set).unwrap_or(&[]);
    let mut results = Results {
        time: Vec::with_capacity(blocks.len()),
        displacement: vec![Vec::with_capacity(blocks.len()); meta.dof],
    };
    for block in blocks {
        let time = block.time / meta.units.time() + meta.start;
        let first = block.rows.first().map_or(0, |r| r.line);
        if results.time.last().is_some_and(|&last| time <= last) {
            return Err(error(
                first,
                format!("block time {time} s does not increase (a duplicate block?)"),
            ));
        }
        results.time.push(time);
        for row in &block.rows {
            let node = row
                .id
                .map_or(0, |id| id.saturating_sub(meta.offset) as usize);
            if node == 0 || node > meta.dof || row.values.len() != 3 {
                return Err(error(
                    row.line,
                    format!(
                        "row {:?}: not a mass node {}..{} with three displacements",
                        row.id,
                        meta.offset + 1,
                        meta.offset + meta.dof as u64
                    ),
                ));
            }
            let history = &mut results.displacement[node - 1];
            if history.len() == results.time.len() {
                return Err(error(
                    row.line,
                    format!(
                        "node {} appears twice in one displacement block",
                        meta.offset + node as u64
                    ),
                ));
            }
            history.push(row.values[meta.axis.component] * meta.axis.sign / meta.units.length());
        }
        if results
            .displacement
            .iter()
            .any(|h| h.len() != results.time.len())
        {
            return Err(error(
                first,
                "the displacement block does not list every mass node once (truncated?)".into(),
            ));
        }
    }
    if results.time.is_empty() {
        return Err(error(
            0,
            format!("no displacement blocks for set {set} (a truncated run?)"),
        ));
    }
    Ok(results)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A car name's line break went raw into the `**` title comment.
    #[test]
    fn the_title_comment_escapes_control_characters() {
        let model = MsdModel::new(vec![1.8, 74.8], vec![1.0e5], vec![4.75e5]).unwrap();
        let options = CalculixOptions {
            title: "car\n*STEP\u{7}".into(),
            ..Default::default()
        };
        let deck = calculix_deck(&model, &options).unwrap();
        assert!(deck.starts_with("** car\\u000A*STEP\\u0007\n"), "{deck}");
        assert!(!deck.contains('\u{7}'));
    }

    #[test]
    fn results_come_from_the_cars_own_set_with_the_offset_undone() {
        let meta = DeckMeta {
            units: UnitSystem::Si,
            axis: Axis::default(),
            start: 0.0,
            dof: 2,
            offset: 1000,
            prefix: "BUMPSIM_".into(),
        };
        let block = |set: &str, t: &str, nodes: [(u64, f64); 2]| {
            let rows: String = nodes
                .iter()
                .map(|(n, u)| format!("  {n}  {u:e}  0.0  0.0\n"))
                .collect();
            format!(" displacements (vx,vy,vz) for set {set} and time  {t}\n\n{rows}\n")
        };
        let dat = block("NALL", "1e-3", [(1, 9.0), (2, 9.0)])
            + &block("BUMPSIM_NALL", "1e-3", [(1001, 0.5), (1002, 0.25)]);
        let r = parse_dat(&dat, Path::new("x.dat"), &meta).unwrap();
        assert_eq!(r.time.len(), 1);
        assert_eq!(r.displacement, vec![vec![0.5], vec![0.25]]);
        let foreign = block("BUMPSIM_NALL", "1e-3", [(1, 0.5), (2, 0.25)]);
        let e = parse_dat(&foreign, Path::new("x.dat"), &meta).unwrap_err();
        assert!(e.to_string().contains("not a mass node 1001..1002"), "{e}");
    }

    /// A `.dat` cut anywhere (mid-line, or after a whole block) returned
    /// the times before the cut with exit 0; now it is the whole run or an
    /// error.
    #[test]
    fn a_cut_dat_is_refused_wherever_it_is_cut() {
        let dir = std::env::temp_dir().join(format!("bumpsim-cut-dat-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let deck = "** bumpsim-deck: units=si axis=+x start=0e0 dof=2 offset=0 prefix=BUMPSIM_\n*STEP, INC=14\n*DYNAMIC, DIRECT, ALPHA=0.0\n1.0e-4, 4.0e-4\n*NODE PRINT, NSET=BUMPSIM_NALL, FREQUENCY=1\nU\n*END STEP\n";
        std::fs::write(dir.join("car.inp"), deck).unwrap();
        let dat: String = (1..=4)
            .map(|k| {
                format!(
                    "\n displacements (vx,vy,vz) for set BUMPSIM_NALL and time  {k}.000000E-04\n\n         1  {k}.250000E-03  0.000000E+00  0.000000E+00\n         2  {k}.125000E-04  0.000000E+00  0.000000E+00\n"
                )
            })
            .collect();
        std::fs::write(dir.join("car.dat"), &dat).unwrap();
        let whole = read_results(&dir.join("car.inp")).unwrap();
        assert_eq!(whole.time.len(), 4);
        for cut in 1..dat.len() {
            std::fs::write(dir.join("car.dat"), &dat[..cut]).unwrap();
            if let Ok(r) = read_results(&dir.join("car.inp")) {
                assert_eq!(r, whole, "cut after {cut} bytes read as a whole run");
            }
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn names_and_ids_calculix_cannot_read_are_refused() {
        let model = MsdModel::new(vec![1.0, 2.0], vec![1.0], vec![1.0]).unwrap();
        for prefix in ["BAD NAME", "1ST_", "A,B"] {
            let options = CalculixOptions {
                prefix: prefix.into(),
                ..Default::default()
            };
            assert!(matches!(
                calculix_deck(&model, &options),
                Err(ExportError::Prefix { .. })
            ));
        }
        // an increment of 1e-300 s panicked on `u64::MAX + 10`; now it is
        // below the shortest, and over a 100 s force 1e-8 s overflows INC
        let short = UniformSeries::new(0.0, 1e-3, vec![0.0, 1.0, 0.0]).unwrap();
        let long = UniformSeries::new(0.0, 50.0, vec![0.0, 1.0, 0.0]).unwrap();
        for (force, increment) in [(&short, 1e-300), (&short, 1e-13), (&long, 1e-8)] {
            let options = CalculixOptions {
                analysis: Some(Analysis {
                    force: force.clone(),
                    increment: Some(increment),
                    output_every: 1,
                }),
                ..Default::default()
            };
            let err = calculix_deck(&model, &options).unwrap_err();
            let count = matches!(err, ExportError::Increments { .. });
            assert_eq!(count, increment > 1e-9, "{err}");
            assert!(
                count || matches!(err, ExportError::Increment { .. }),
                "{err}"
            );
        }
        for id_offset in [u64::MAX, MAX_CALCULIX_ID - 1] {
            let options = CalculixOptions {
                id_offset,
                ..Default::default()
            };
            let err = calculix_deck(&model, &options).unwrap_err();
            assert!(matches!(err, ExportError::IdRange { .. }), "{err}");
            // the CalculiX bound was reported as LS-DYNA's "8-column limit"
            let text = err.to_string();
            assert!(
                text.contains("CalculiX 32-bit id limit 2147483647"),
                "{text}"
            );
        }
    }
}
