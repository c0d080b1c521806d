//! The warning of an unloading slope the rule replaced (issue 46 item 2):
//! a link that unloads at a slope k_u from its largest compression δ_max
//! past its elastic limit unloads at
//!
//! ```text
//! k_e = max(k_u, F_max/δ_max, F_max²/(2 E_L))
//! ```
//!
//! ([`bumpsim_core::link`]: the secant keeps the plastic set
//! `δ_p = δ_max − F_max/k_e` non-negative, the last term the dissipated
//! work). A k_u far below the secant (`unloading = "1e-300 N/mm"`) then
//! runs with a set of 0 mm: the impact says so, naming the link, both
//! slopes and the compression.

use super::Crush;
use bumpsim_core::chain::Chain;
use bumpsim_core::link::Link;
use bumpsim_core::units::{Dimension, format_quantity};

/// One warning per link (the front link first) whose given unloading
/// slope the rule replaced at its largest compression in `crush`.
pub(super) fn replaced(chain: &Chain, crush: &Crush) -> Vec<String> {
    let front = chain
        .front()
        .zip(crush.front)
        .map(|(link, (reached, _))| ("front link".to_string(), link, reached));
    let between = chain
        .links()
        .iter()
        .zip(&crush.response.reached)
        .enumerate()
        .map(|(j, (link, reached))| (format!("link {}", j + 1), link, *reached));
    front
        .into_iter()
        .chain(between)
        .filter_map(|(name, link, reached)| warning(&name, link, reached))
        .collect()
}

fn warning(name: &str, link: &Link, reached: f64) -> Option<String> {
    let (given, used) = link.replaced_unloading(reached)?;
    let slope = |k: f64| format_quantity(k, Dimension::Stiffness);
    Some(format!(
        "{name}: unloading = {} is below the rule k_e = max(k_u, F_max/δ_max, F_max²/(2 E_L)) at its largest compression {}: it unloads at {} instead (docs/formats.md, nonlinear links)",
        slope(given),
        format_quantity(reached, Dimension::Length),
        slope(used)
    ))
}
