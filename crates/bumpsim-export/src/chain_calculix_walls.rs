//! A yielding wall link (second load path, rebound link with an unloading
//! slope) in the CalculiX deck: the chain's elastic-plastic brick behind a
//! one-sided penalty spring, in series through a free node (issue 46).
//!
//! The wall link pushes mass p after its gap g and never pulls; loaded, it
//! follows `F_L(δ)` (δ = x_p − g), and unloads from δ_max at the slope
//! `k_e` ([`solver_unloading`]), keeping the set `δ_max − F_max/k_e`. In
//! the deck:
//!
//! - a brick (as the chain's links, [`crate::chain`]) from the held wall
//!   node to a free node F, with the modulus of `k_b` and the chain's
//!   hardening table (plastic strain `(δ − F_L(δ)/k_e)/L`);
//! - a `SPRINGA` from F to p: zero force up to the gap and in tension,
//!   `k_p (c − g)` at a closing c beyond it (the penalty, `k_p = 2 k_e`);
//! - a point mass on F, `M_F = (k_p + k_b) Δt²` at the deck's increment
//!   Δt (0.1 ms without a step).
//!
//! In series the two make the link: under a force F the pair closes by
//! `g + δ_b(F) + F/k_p`; the brick's plastic strain at F is the chain's,
//! so `δ_b = δ(F) − F/k_e + F/k_b`, and with `1/k_b = 1/k_e − 1/k_p`
//! (`k_b = 2 k_e`) the pair closes by `g + δ(F)`: it loads along the
//! curve, and unloads at `1/(1/k_b + 1/k_p) = k_e`, the brick keeping its
//! plastic strain. Open, the spring carries nothing and the brick sits at
//! its set (F holds no force). A tension beyond the set cannot arise: the
//! spring does not pull.
//!
//! Why the spring is a `SPRINGA` and F has a mass (measured in ccx 2.20,
//! one 1000 kg mass at 10 m/s, a 0.1 m gap, a bilinear link):
//! `springstiff_n2f.f` takes a nonlinear `SPRING2`'s tangent at an
//! elongation it never computes (the table's slope is read at `val`, set
//! only in the `SPRINGA` branch), so a `SPRING2` gap table closed with a
//! zero tangent and Newton cycled between open and closed; a `SPRINGA`
//! gets its slope at its actual elongation. F without a mass (only the
//! brick's 10⁻⁴ kg) cycled at the hardening table's corners (measured
//! with the brick's lateral faces free, before they were tied); with
//! `M_F/(β Δt²) = 4 (k_p + k_b)` (β = 1/4) every increment converges, and
//! F's inertia (`M_F a`, a contact knock of about `v √(M_F k_p)` when F is
//! set moving) stays within 0.02 % of the peak force in that case.
//!
//! The spring runs from F, placed `L + g` (L = [`BRICK_LENGTH`]) behind p
//! along the axis, so it never turns over. Ids: [`BLOCK`].

use super::{Gap, Parts, Span};
use crate::calculix::CalculixOptions;
use crate::chain::{BRICK_LENGTH, CURVE_SPAN, loading_points, solver_unloading};
use crate::inp::{self, real};
use std::fmt::Write;

/// Ids a yielding wall link takes after its block start: the free node F
/// (block + 1) and the brick's nodes (block + 2 … block + 9); elements:
/// the brick block + 1, F's mass block + 2.
pub(super) const BLOCK: u64 = 9;

/// The penalty spring's slope over the link's unloading slope, `k_p/k_e`.
pub(super) const PENALTY: f64 = 2.0;

/// The increment `M_F` is set for when the deck has no step, s.
pub(super) const DEFAULT_INCREMENT: f64 = 1e-4;

/// The free node F of a yielding wall link.
pub(super) fn free_node(gap: Gap) -> u64 {
    gap.block + 1
}

/// The first of its brick's eight nodes.
pub(super) fn brick_nodes(gap: Gap) -> u64 {
    gap.block + 2
}

/// The penalty `k_p`, the brick's `k_b` and F's mass `M_F` (SI) of a link
/// unloading at `k_e` in a deck of increment `dt`.
pub(super) fn series(k_e: f64, dt: f64) -> (f64, f64, f64) {
    let k_p = PENALTY * k_e;
    let k_b = 1.0 / (1.0 / k_e - 1.0 / k_p);
    (k_p, k_b, (k_p + k_b) * dt * dt)
}

impl Parts<'_> {
    /// The deck's fixed increment, s: the barrier run's, the force
    /// analysis's, or [`DEFAULT_INCREMENT`].
    fn increment(&self, options: &CalculixOptions) -> f64 {
        let analysis = options.analysis.as_ref();
        let forced = analysis.map(|a| a.increment.unwrap_or(a.force.step()));
        self.barrier
            .map(|b| b.increment)
            .or(forced)
            .unwrap_or(DEFAULT_INCREMENT)
    }

    /// A yielding wall link: its free node with its mass, its brick
    /// (element block + 1) and the `SPRINGA` `id` from F to the mass.
    pub(super) fn yielding_wall(
        &self,
        deck: &mut String,
        span: &Span,
        gap: Gap,
        id: u64,
        options: &CalculixOptions,
    ) {
        let (layout, units) = (&options.layout, options.layout.units);
        let k_e = solver_unloading(span.link);
        let (k_p, k_b, mass) = series(k_e, self.increment(options));
        let _ = writeln!(
            deck,
            "** {}: {}\n** a brick (k_b {} N/m) from the wall node {} to node {}, a one-sided SPRINGA (k_p {} N/m after {} m) from it to node {}",
            span.label,
            crate::chain::wall_note(span.link),
            real(k_b),
            span.ends[0],
            free_node(gap),
            real(k_p),
            real(gap.gap),
            span.ends[1]
        );
        let behind = BRICK_LENGTH + gap.gap;
        let index = (gap.mass - options.id_offset - 1) as usize;
        let p = layout.node_position(index);
        let axis = layout.axis.vector();
        let at: [f64; 3] = std::array::from_fn(|c| p[c] - behind * axis[c] * units.length());
        inp::node_keyword(deck, &format!("{}_FREE", span.elset));
        inp::node_line(deck, free_node(gap), at);
        let masses = format!("{}_MASS", span.elset);
        let node = free_node(gap);
        inp::mass_element(deck, &masses, gap.block + 2, node, mass * units.mass());
        let brick = Span {
            link: span.link,
            label: span.label.clone(),
            elset: super::brick_elset(span),
            ends: span.ends,
            slot: span.slot,
            at: span.at,
            gap: span.gap,
        };
        let points = loading_points(span.link.curve());
        self.brick(deck, &brick, gap.block + 1, options, &points, k_b);
        inp::element_keyword(deck, "SPRINGA", &span.elset);
        let _ = writeln!(
            deck,
            "{id}, {node}, {}\n*SPRING, ELSET={}, NONLINEAR",
            span.ends[1], span.elset
        );
        // force against elongation (compression negative), ascending
        let far = gap.gap + CURVE_SPAN;
        for (force, elongation) in [
            (-k_p * CURVE_SPAN, -far),
            (0.0, -gap.gap),
            (0.0, CURVE_SPAN),
        ] {
            let (f, e) = (force * units.force(), elongation * units.length());
            let _ = writeln!(deck, "{}, {}", real(f), real(e));
        }
    }
}
