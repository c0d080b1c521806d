//! The chain with nonlinear links ([`bumpsim_core::chain`]) as LS-DYNA and
//! CalculiX decks (issue 46, item 2: "the exports").
//!
//! Masses, dampers, nodes, ids, units, coupling and force history are those
//! of [`crate::lsdyna`] and [`crate::calculix`]; only the springs change.
//! A link with loading curve `F_L(δ)` (δ > 0 in compression) and unloading
//! rule ([`bumpsim_core::link`]) becomes:
//!
//! | link | LS-DYNA | CalculiX | maps |
//! |---|---|---|---|
//! | linear curve, either rule | `*MAT_SPRING_ELASTIC` K = k | `SPRING2`, `*SPRING` k | exactly |
//! | nonlinear curve, elastic | `*MAT_SPRING_NONLINEAR_ELASTIC`, odd `*DEFINE_CURVE` | `SPRING2`, `*SPRING, NONLINEAR` odd table | exactly on the table's points |
//! | nonlinear curve, slope k_u ≥ the curve's steepest rising slope | `*MAT_SPRING_INELASTIC` (LCFD = the curve in the first quadrant, KU = k_u, CTF = 1: compression only) | `C3D8` brick, `*ELASTIC` E, `*PLASTIC` table | exactly in compression |
//! | nonlinear curve, slope k_u below the steepest rising slope | as above | as above, E from the steepest rising slope | approximately |
//!
//! Tables: a bilinear or tabulated curve is written at its corners, then
//! to [`CURVE_SPAN`] along its last slope; a progressive one at
//! [`PROGRESSIVE_POINTS`] points up to δ_lim (chords between them, an
//! error below `(δ_lim/N)² · 3 k3 δ_lim / 4`).
//!
//! **Unloading.** bumpsim unloads from δ_max along `k_e = max(k_u,
//! F_max/δ_max, F_max²/(2 E_L))`. When k_u is at least the curve's steepest
//! rising slope the other two never exceed it (a softening segment lowers
//! F_max, not the slope that reached it) and `k_e = k_u` at every δ_max: a
//! spring with one unloading stiffness (LS-DYNA's KU) or an elastic-plastic
//! continuum with modulus `E = k_u L / A` and hardening curve
//! `σ = F_L(δ)/A` against plastic strain `ε_p = (δ − F_L(δ)/k_u)/L`
//! follows it exactly. Below it, LS-DYNA unloads at the steepest rising slope
//! (the manual: the larger of KU and the curve's largest slope) and so does
//! the brick: stiffer than bumpsim's, so their plastic set is larger.
//! One exception to "exactly": bumpsim keeps a bilinear link elastic until
//! it yields (unloading along k before δ_y, [`bumpsim_core::link`]), while
//! the inelastic spring and the brick with `E` from k_u > k take a set
//! `δ (1 − k/k_u)` from the first compression; a link unloaded before its
//! yield differs by that set (none once it has yielded).
//!
//! **Tension.** bumpsim's unloading line runs on into tension. LS-DYNA's
//! inelastic spring (CTF = 1) carries none; CalculiX's brick (isotropic
//! hardening) yields again at −F_max, where bumpsim stays elastic. Both
//! agree with bumpsim until the link is pulled.
//!
//! **The brick.** CalculiX has no hysteretic spring and expands its truss
//! elements into bricks whose knots fail on yielding, so the link is one
//! `C3D8` of length [`BRICK_LENGTH`] and square section [`BRICK_SIDE`]²
//! beside the axis, small-strain (no NLGEOM), Poisson's ratio 0, its rear
//! face following mass j and its front face mass j+1 along the axis by
//! `*EQUATION`: its axial strain ε is the crush over L. Two lateral faces
//! sit on symmetry supports, the other two follow ε as an incompressible
//! flow does (`u = −ε w/2` across, by `*EQUATION`; left free, these
//! massless nodes made ccx's Newton diverge on softening tables). The
//! strain is then deviatoric, the von Mises stress `σ_eq = σ_axial −
//! σ_lateral`, and the force on the ends (the work of all faces)
//! `F = σ_eq A`, elastic `3 E A/(2L) δ`: so `E = 2 k_E L/(3 A)`, and the
//! `*PLASTIC` table (`σ_eq` against the equivalent plastic strain, here the
//! axial one) is `F/A` against `(δ − F/k_E)/L`, as for a bar in uniaxial
//! stress. A 100 m brick keeps a 1 m crush at 1 % strain.
//!
//! **Front link** ([`Chain::with_front`], the crush zone between the
//! barrier and m1): written between a fixed wall node one spacing ahead of
//! m1 and m1, with the same mapping; bumpsim's front link never pulls,
//! LS-DYNA's inelastic spring neither, the others do.
//!
//! **Wall links** ([`Chain::path`], [`Chain::rebound`]: a link from the
//! barrier into mass p, compressed by `x_p − g` past its gap g, never
//! pulling): each from its own fixed node one spacing ahead of m1 (LS-DYNA
//! ids offset + 3n + 3 and + 4) to mass p, its loading curve shifted by the
//! gap ([`gapped_points`]: `F(δ) = 0` for δ ≤ g, `F_L(δ − g)` beyond). A
//! yielding link with an unloading slope is `*MAT_SPRING_INELASTIC` (CTF =
//! 1), any other `*MAT_SPRING_NONLINEAR_ELASTIC` with zero force in tension:
//! both never pull and map as the chain's links do. In CalculiX an elastic
//! one is a one-sided `SPRING2` table, a yielding one the chain's brick
//! behind a one-sided `SPRINGA` (`crate::chain_calculix`, its `walls`
//! module): both exact as the chain's links are. A gap that makes two
//! written points coincide is refused ([`ExportError::WallGap`]).
//!
//! The CalculiX deck, its barrier run and the link forces read back:
//! [`crate::chain_calculix`].

use crate::ExportError;
use crate::cards;
use crate::layout::{Layout, UnitSystem};
use crate::lsdyna::LsDynaOptions;
use bumpsim_core::chain::{Chain, WallPath};
use bumpsim_core::link::{Curve, Link, Unloading};
use bumpsim_core::model::MsdModel;
use std::fmt::Write;

/// How far the written curves reach, m (beyond any car's crush).
pub const CURVE_SPAN: f64 = 10.0;

/// Points of a progressive curve up to its limit deformation.
pub const PROGRESSIVE_POINTS: usize = 40;

/// Length of a CalculiX link brick, m.
pub const BRICK_LENGTH: f64 = 100.0;

/// Side of a CalculiX link brick's square section, m.
pub const BRICK_SIDE: f64 = 1.0;

/// The loading curve as (δ m, F N) points from (0, 0) to [`CURVE_SPAN`]
/// (or further along the last slope to the last table point).
pub fn loading_points(curve: &Curve) -> Vec<(f64, f64)> {
    let mut d: Vec<f64> = match curve {
        Curve::Linear { .. } => vec![0.0],
        Curve::Bilinear {
            stiffness,
            yield_force,
            ..
        } => vec![0.0, yield_force / stiffness],
        Curve::Progressive { limit, .. } => (0..=PROGRESSIVE_POINTS)
            .map(|i| limit * i as f64 / PROGRESSIVE_POINTS as f64)
            .collect(),
        Curve::Table { points } => points.iter().map(|p| p[0]).collect(),
    };
    if d.last().is_some_and(|&last| last < CURVE_SPAN) {
        d.push(CURVE_SPAN);
    }
    d.into_iter().map(|d| (d, curve.force(d))).collect()
}

/// The stiffness a solver unloads at, N/m: the larger of k_u and the
/// curve's steepest rising slope ([`Curve::steepest_rise`]: a softening
/// segment, however steep, asks no stiffer unloading of the solvers'
/// plasticity).
pub fn solver_unloading(link: &Link) -> f64 {
    match link.unloading() {
        Unloading::Slope(k) => k.max(link.curve().steepest_rise()),
        Unloading::Elastic => link.curve().steepest_slope(),
    }
}

/// How a link is written, and whether the solvers follow bumpsim exactly.
#[derive(Debug, Clone, PartialEq)]
pub struct LinkMapping {
    /// LS-DYNA material keyword.
    pub lsdyna: &'static str,
    /// CalculiX element and card.
    pub calculix: &'static str,
    /// Whether the decks follow bumpsim's link exactly (in compression).
    pub exact: bool,
    /// One line for the deck header.
    pub note: String,
}

/// The mapping of `link`.
pub fn mapping(link: &Link) -> LinkMapping {
    let curve = link.curve();
    let (lsdyna, calculix) = match (curve, link.unloading()) {
        (Curve::Linear { .. }, _) => ("*MAT_SPRING_ELASTIC", "SPRING2 *SPRING"),
        (_, Unloading::Elastic) => (
            "*MAT_SPRING_NONLINEAR_ELASTIC",
            "SPRING2 *SPRING, NONLINEAR",
        ),
        (_, Unloading::Slope(_)) => ("*MAT_SPRING_INELASTIC", "C3D8 *ELASTIC, *PLASTIC"),
    };
    let (exact, note) = match (curve, link.unloading()) {
        (Curve::Linear { .. }, _) => (true, "linear: exact".to_string()),
        (Curve::Progressive { .. }, Unloading::Elastic) => (
            true,
            format!(
                "elastic along the curve: exact at {PROGRESSIVE_POINTS} points, chords between"
            ),
        ),
        (_, Unloading::Elastic) => (true, "elastic along the curve: exact".to_string()),
        (_, Unloading::Slope(k)) if k >= curve.steepest_rise() => (
            true,
            format!(
                "unloading slope {k:e} N/m: exact in compression (tension: see docs/export.md)"
            ),
        ),
        (_, Unloading::Slope(k)) => (
            false,
            format!(
                "APPROXIMATE: unloads at the curve's steepest rising slope {:e} N/m, bumpsim at max({k:e} N/m, secant, energy term)",
                curve.steepest_rise()
            ),
        ),
    };
    LinkMapping {
        lsdyna,
        calculix,
        exact,
        note,
    }
}

/// The linear chain the decks share (masses, dampers, and each link's
/// initial slope, for the layout, ids and unit checks).
pub(crate) fn skeleton(chain: &Chain) -> MsdModel {
    let springs = chain
        .links()
        .iter()
        .map(|l| l.curve().initial_slope())
        .collect();
    MsdModel::new(chain.masses().to_vec(), chain.dampers().to_vec(), springs)
        .expect("a valid chain is a valid linear chain")
}

/// Checks that every curve point stays finite in the deck's units, and
/// that a wall link's curve, shifted by its gap, keeps its points apart
/// once written (a gap so large that `gap + δ` rounds to the gap would
/// fold the curve onto a vertical step).
pub(crate) fn check_curves(chain: &Chain, units: UnitSystem) -> Result<(), ExportError> {
    let front = chain
        .front()
        .map(|f| ("the front link".to_string(), f, None));
    let links = chain.links().iter().enumerate();
    let links = links.map(|(j, l)| (format!("link {}", j + 1), l, None));
    let walls = wall_links(chain)
        .into_iter()
        .map(|(_, label, w)| (format!("the {label}"), &w.link, Some(w.gap)));
    for (what, link, gap) in links.chain(front).chain(walls) {
        let points = match gap {
            None => loading_points(link.curve()),
            Some(gap) => gapped_points(link.curve(), gap),
        };
        let fine = points
            .iter()
            .all(|(d, f)| (d * units.length()).is_finite() && (f * units.force()).is_finite())
            && (solver_unloading(link) * units.stiffness()).is_finite();
        if !fine {
            return Err(ExportError::Overflow {
                what: format!("{what} (its loading curve to {CURVE_SPAN} m)"),
                units: units.to_string(),
            });
        }
        if let Some(gap) = gap {
            apart(&points, units).map_err(|at| ExportError::WallGap {
                what: what.clone(),
                gap,
                at,
            })?;
        }
    }
    Ok(())
}

/// Checks that the points' deformations, in the deck's units and written
/// to 13 significant digits ([`crate::inp::real`], the coarser of the two
/// decks), strictly increase; the first deformation (m) that does not.
fn apart(points: &[(f64, f64)], units: UnitSystem) -> Result<(), f64> {
    let written = |d: f64| {
        crate::inp::real(d * units.length())
            .parse::<f64>()
            .unwrap_or(f64::NAN)
    };
    for pair in points.windows(2) {
        let rising = written(pair[1].0).partial_cmp(&written(pair[0].0));
        if rising != Some(std::cmp::Ordering::Greater) {
            return Err(pair[1].0);
        }
    }
    Ok(())
}

/// The LS-DYNA include of `chain` (see [`crate::lsdyna`] for the rest).
///
/// ```
/// use bumpsim_core::chain::Chain;
/// use bumpsim_core::link::{Curve, Link, Unloading};
/// use bumpsim_export::chain::lsdyna_chain_include;
/// let link = Link::new(Curve::bilinear(1e6, 5e4, 0.1).unwrap(), Unloading::Slope(2e6)).unwrap();
/// let chain = Chain::new(vec![2.0, 900.0], vec![0.0], vec![link]).unwrap();
/// let deck = lsdyna_chain_include(&chain, &Default::default()).unwrap();
/// assert!(deck.contains("*MAT_SPRING_INELASTIC"));
/// ```
pub fn lsdyna_chain_include(chain: &Chain, options: &LsDynaOptions) -> Result<String, ExportError> {
    check_curves(chain, options.layout.units)?;
    let units = options.layout.units;
    let cards = |deck: &mut String, j: usize, id: u64, section: u64| {
        let label = format!("link {}", j + 1);
        let title = format!("link {} between m{} and m{}", j + 1, j + 1, j + 2);
        lsdyna_link(deck, &chain.links()[j], units, id, section, &label, &title);
    };
    let deck = crate::lsdyna::include(&skeleton(chain), Some(&cards), options)?;
    lsdyna_walls(deck, chain, options)
}

/// A link from the barrier's fixed node into a mass: the front link (on m1,
/// no gap) or a wall link ([`Chain::path`], [`Chain::rebound`]).
struct WallSpring<'a> {
    /// Node, section, material, curve, part and element id.
    id: u64,
    link: &'a Link,
    /// The mass it pushes, 0-based.
    mass: usize,
    /// Its gap, m: `None` for the front link (written as a chain link).
    gap: Option<f64>,
    label: &'static str,
}

/// The chain's springs on the barrier, with ids offset + 3n + 2 (front),
/// + 3 (second load path) and + 4 (rebound link).
fn wall_springs<'a>(chain: &'a Chain, options: &LsDynaOptions) -> Vec<WallSpring<'a>> {
    let first = options.id_offset + 3 * chain.dof() as u64 + 2;
    let front = chain.front().map(|link| WallSpring {
        id: first,
        link,
        mass: 0,
        gap: None,
        label: "front link",
    });
    let walls = wall_links(chain)
        .into_iter()
        .map(|(slot, label, wall)| WallSpring {
            id: first + slot,
            link: &wall.link,
            mass: wall.mass,
            gap: Some(wall.gap),
            label,
        });
    front.into_iter().chain(walls).collect()
}

/// The wall springs written before `*END`, each from its own fixed node
/// (the barrier) one spacing ahead of m1: node, section, material, curve,
/// part and element all with the spring's id.
fn lsdyna_walls(
    deck: String,
    chain: &Chain,
    options: &LsDynaOptions,
) -> Result<String, ExportError> {
    let springs = wall_springs(chain, options);
    let Some(last) = springs.last().map(|s| s.id) else {
        return Ok(deck);
    };
    let limit = crate::lsdyna::MAX_ID;
    if last > limit {
        return Err(ExportError::IdRange {
            offset: options.id_offset,
            last,
            limit,
        });
    }
    if let Some(id) = springs
        .iter()
        .map(|s| s.id)
        .find(|id| options.attach.contains(id))
    {
        return Err(ExportError::IdClash {
            node: id,
            first: id,
            last: id,
        });
    }
    let mut deck = deck
        .strip_suffix("*END\n")
        .map(str::to_string)
        .unwrap_or(deck);
    for spring in &springs {
        lsdyna_wall(&mut deck, spring, options);
    }
    deck.push_str("*END\n");
    Ok(deck)
}

/// One wall spring's cards.
fn lsdyna_wall(deck: &mut String, spring: &WallSpring, options: &LsDynaOptions) {
    let layout = &options.layout;
    let ahead = Layout {
        origin: std::array::from_fn(|c| {
            layout.origin[c] - layout.spacing * layout.axis.vector()[c]
        }),
        ..*layout
    };
    let (id, m) = (spring.id, spring.mass + 1);
    let [_, l, _, _] = layout.units.symbols();
    match spring.gap {
        None => {
            let _ = writeln!(deck, "$ front link: the barrier's fixed node {id} to m1");
        }
        Some(gap) => {
            let gap = crate::layout::real_field(gap * layout.units.length(), 10);
            let _ = writeln!(
                deck,
                "$ {}: the barrier's fixed node {id} to m{m}, touching after a gap of {} {l}",
                spring.label,
                gap.trim()
            );
        }
    }
    cards::node(deck, &[(id, ahead.node_position(0))], Some([7, 7]));
    cards::discrete_section(deck, id, cards::FieldNames::Written);
    let title = format!("{} between the barrier and m{m}", spring.label);
    match spring.gap {
        None => lsdyna_link(
            deck,
            spring.link,
            layout.units,
            id,
            id,
            spring.label,
            &title,
        ),
        Some(gap) => lsdyna_gapped(deck, spring, gap, layout.units, &title),
    }
    cards::sd_orientation(deck, id, layout.axis.vector());
    cards::element_discrete_header(deck, cards::FieldNames::Written);
    let node = options.id_offset + spring.mass as u64 + 1;
    cards::element_discrete_oriented(deck, id, id, [id, node], id);
}

/// A wall link's material, curve and part (all id `spring.id`): its
/// loading curve shifted by the gap ([`gapped_points`]), zero before it.
///
/// Why a shifted curve and not the element's `OFFSET`: the curve carries
/// the gap where the parser and a reader see it, the same in both decks,
/// and needs no convention for the offset's sign under `CTF`. A yielding
/// link with an unloading slope is `*MAT_SPRING_INELASTIC` (CTF = 1:
/// compression only, so it never pulls): its curve is a yield bound in the
/// first quadrant, 0 up to the gap, and its elastic trial at KU ≥ every
/// slope of the curve follows the curve past it and unloads at KU down to
/// zero force. Any other link (linear, or elastic along its curve) is
/// `*MAT_SPRING_NONLINEAR_ELASTIC` on one curve against elongation, the
/// shifted curve in compression (negative: the mass moves towards the
/// barrier node, against the axis) and zero in tension: it never pulls
/// either. Both follow bumpsim's wall link exactly where its chain link
/// does ([`mapping`]).
fn lsdyna_gapped(deck: &mut String, spring: &WallSpring, gap: f64, units: UnitSystem, title: &str) {
    let (link, id, label) = (spring.link, spring.id, spring.label);
    let [_, l, _, f] = units.symbols();
    let points = gapped_points(link.curve(), gap);
    let scaled = |(d, force): (f64, f64)| (d * units.length(), force * units.force());
    match (link.curve(), link.unloading()) {
        (Curve::Linear { .. }, _) | (_, Unloading::Elastic) => {
            let _ = writeln!(
                deck,
                "$ {label}: {}\n*MAT_SPRING_NONLINEAR_ELASTIC\n$    mid       lcd       lcr\n{}{}{}",
                wall_note(link),
                crate::layout::int_field(id, 10),
                crate::layout::int_field(id, 10),
                crate::layout::int_field(0, 10)
            );
            let mut rows: Vec<(f64, f64)> = points.iter().rev().map(|&(d, f)| (-d, -f)).collect();
            rows.push((CURVE_SPAN, 0.0));
            let note = format!(
                "curve of the {label}: force ({f}) against elongation ({l}), zero in tension and before the gap"
            );
            cards::curve(deck, id, Some(&note), rows.into_iter().map(scaled));
        }
        (_, Unloading::Slope(k)) => {
            let _ = writeln!(
                deck,
                "$ {label}: {}\n*MAT_SPRING_INELASTIC\n$    mid      lcfd        ku       ctf  (ku {f}/{l})\n{}{}{}{}",
                wall_note(link),
                crate::layout::int_field(id, 10),
                crate::layout::int_field(id, 10),
                crate::layout::real_field(k * units.stiffness(), 10),
                crate::layout::real_field(1.0, 10)
            );
            let note = format!(
                "loading curve of the {label}: force ({f}) against crush ({l}), zero before the gap"
            );
            cards::curve(deck, id, Some(&note), points.into_iter().map(scaled));
        }
    }
    cards::part(deck, title, id, id, id);
}

/// The header note of a wall link: the chain link's, its tension rule
/// replaced (a wall link never pulls, nor do its springs).
pub(crate) fn wall_note(link: &Link) -> String {
    let m = mapping(link);
    match (m.exact, link.curve(), link.unloading()) {
        (false, _, _) => m.note,
        (true, Curve::Progressive { .. }, Unloading::Elastic) => format!(
            "along the curve after the gap: exact at {PROGRESSIVE_POINTS} points, chords between; never pulls"
        ),
        (true, _, _) => "after the gap: exact in compression; never pulls".to_string(),
    }
}

/// The chain's wall links besides the front link, with their id slots
/// after the front link's (1, 2) and labels: [`Chain::path`] and
/// [`Chain::rebound`].
pub fn wall_links(chain: &Chain) -> Vec<(u64, &'static str, &WallPath)> {
    let path = chain.path().map(|w| (1, "second load path", w));
    let rebound = chain.rebound().map(|w| (2, "rebound link", w));
    path.into_iter().chain(rebound).collect()
}

/// A wall link's loading curve shifted by its gap `gap` (m): (0, 0), then
/// (gap, 0) when the gap is positive, then each point of
/// [`loading_points`] past the first moved on by the gap.
pub fn gapped_points(curve: &Curve, gap: f64) -> Vec<(f64, f64)> {
    let points = loading_points(curve);
    let mut out = vec![(0.0, 0.0)];
    if gap > 0.0 {
        out.push((gap, 0.0));
    }
    out.extend(points.iter().skip(1).map(|&(d, f)| (gap + d, f)));
    out
}

/// Writes a link's material (id `id`), curve (id `id`) and part titled `title`.
fn lsdyna_link(
    deck: &mut String,
    link: &Link,
    units: UnitSystem,
    id: u64,
    section: u64,
    label: &str,
    title: &str,
) {
    let m = mapping(link);
    let _ = writeln!(deck, "$ {label}: {}", m.note);
    let [_, l, _, f] = units.symbols();
    let points = loading_points(link.curve());
    match (link.curve(), link.unloading()) {
        (Curve::Linear { stiffness }, _) => {
            let unit = format!("{f}/{l}");
            let k = stiffness * units.stiffness();
            cards::discrete_part(deck, cards::Link::Spring, k, &unit, id, section, title);
            return;
        }
        (_, Unloading::Elastic) => {
            let _ = writeln!(
                deck,
                "*MAT_SPRING_NONLINEAR_ELASTIC\n$    mid       lcd       lcr\n{}{}{}",
                crate::layout::int_field(id, 10),
                crate::layout::int_field(id, 10),
                crate::layout::int_field(0, 10)
            );
            let mut rows: Vec<(f64, f64)> = points.iter().rev().map(|&(d, f)| (-d, -f)).collect();
            rows.extend(points.iter().skip(1).copied());
            let rows = rows
                .into_iter()
                .map(|(d, f)| (d * units.length(), f * units.force()));
            let note = format!("curve of {label}: force ({f}) against elongation ({l}), odd");
            cards::curve(deck, id, Some(&note), rows);
        }
        (_, Unloading::Slope(k)) => {
            let _ = writeln!(
                deck,
                "*MAT_SPRING_INELASTIC\n$    mid      lcfd        ku       ctf  (ku {f}/{l})\n{}{}{}{}",
                crate::layout::int_field(id, 10),
                crate::layout::int_field(id, 10),
                crate::layout::real_field(k * units.stiffness(), 10),
                crate::layout::real_field(1.0, 10)
            );
            // the manual: in the first quadrant whichever way the spring acts
            let rows = points
                .iter()
                .map(|&(d, f)| (d * units.length(), f * units.force()));
            let note = format!(
                "loading curve of {label}: force ({f}) against crush ({l}), first quadrant"
            );
            cards::curve(deck, id, Some(&note), rows);
        }
    }
    cards::part(deck, title, id, section, id);
}
