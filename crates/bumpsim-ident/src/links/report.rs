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
    let u = &found.uncertainty;
    let parameters = found.layout.parameters();
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
        out += &format!(
            "  plastic set of link {} after {}: {}  95 % {interval}\n",
            set.link,
            set.case,
            length(set.value)
        );
    }
    out
}
