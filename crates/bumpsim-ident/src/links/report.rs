//! The text of an identification with yielding links: fit per case, the
//! parameter table of the shared engine, the plastic sets with intervals.

use super::LinkIdentification;
use bumpsim_core::units::{Dimension, format_quantity};

/// The identification as text (every number with its unit).
pub fn text(found: &LinkIdentification) -> String {
    let mut out = format!(
        "chain with yielding links, {} masses: objective {:.6e}\n",
        found.layout.dof, found.objective
    );
    for (case, fit) in &found.fits {
        out += &format!("  fit {case}: {fit:.2} %\n");
    }
    for (case, fit) in &found.force_fits {
        out += &format!("  fit {case} wall force: {fit:.2} %\n");
    }
    for (case, [force, output]) in found.fits.iter().map(|f| &f.0).zip(&found.scales) {
        out += &format!(
            "  channel scales {case}: wall force {}, output {output:.3e} (SI)\n",
            format_quantity(*force, Dimension::Force)
        );
    }
    if !found.moved.is_empty() {
        out += &format!(
            "  priors: {}\n",
            bumpsim_estimate::prior::text(&found.moved, &|_, v| format_quantity(
                v,
                Dimension::Mass
            ))
        );
    }
    let u = &found.uncertainty;
    let parameters = &found.parameters;
    for (i, parameter) in parameters.iter().enumerate() {
        let interval = match u.ci95[i] {
            Some([a, b]) => format!("[{}, {}]", parameter.format(a), parameter.format(b)),
            None if u.fixed[i] => "fixed".to_string(),
            None if u.at_bound[i] => "at a bound".to_string(),
            None => "no interval".to_string(),
        };
        out += &format!(
            "  {:<4} {:>14}  95 % {interval}\n",
            parameter.name,
            parameter.format(found.theta[i])
        );
    }
    for set in &found.plastic_sets {
        let length = |v: f64| format_quantity(v, Dimension::Length);
        let interval = set.ci95.map_or("no interval".into(), |[a, b]| {
            format!("[{}, {}]", length(a), length(b))
        });
        let link = match set.link {
            0 => "the front crush zone".to_string(),
            j if found.path.is_some() && j == found.layout.dof => {
                "the second load path".to_string()
            }
            j if found.rebound.is_some()
                && j == found.layout.dof + usize::from(found.path.is_some()) =>
            {
                "the rebound link".to_string()
            }
            j => format!("link {j}"),
        };
        out += &format!(
            "  plastic set of {link} after {}: {}  95 % {interval}\n",
            set.case,
            length(set.value)
        );
    }
    out
}
