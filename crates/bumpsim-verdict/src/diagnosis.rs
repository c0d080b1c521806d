//! Why no bumper passes (issue 45 item 8): when the target search finds no
//! passing bumper at any stiffness, the criterion and test that rule out
//! every candidate, and whether the bumper could change it at all.
//!
//! The energy budget of that test on the car's own bumper: the impact's
//! kinetic energy `E` (the verdict's energies), what the car's bumper took,
//! and what the crash boxes store up to their usable stroke `s` before
//! they block, `Σ ½ k₁ s²` over the sides (k₁ each side's first link,
//! elastic here). What neither takes goes through the blocks into the
//! rails, whatever the bumper: then the load path behind the bumper, not
//! the bumper, has to change.

use crate::error::VerdictError;
use crate::verdict::{Setup, judge};

/// The energy stored by both crash boxes up to the usable stroke, J.
fn crash_box_capacity(setup: &Setup, test: &crate::protocol::Test) -> f64 {
    let Some(end) = setup.end(test.end) else {
        return 0.0;
    };
    let stroke = end.limits.crash_box_stroke;
    [end.car.left(), end.car.right()]
        .iter()
        .filter_map(|c| c.springs.first())
        .map(|k| 0.5 * k * stroke * stroke)
        .sum()
}

/// The explanation when no stiffness row of the target search passes:
/// `failing` holds each row's failing criterion ("name (test)") at its
/// middle force level, None for a row where something passes (then the
/// answer is None). The criterion and test failing at every row, the
/// test's energy budget and what would have to change.
pub fn nothing_passes(
    setup: &Setup,
    rows: &[Option<&str>],
) -> Result<Option<String>, VerdictError> {
    if rows.is_empty() || rows.iter().any(Option::is_none) {
        return Ok(None);
    }
    let failing: Vec<&str> = rows.iter().flatten().copied().collect();
    let Some(&first) = failing.first() else {
        return Ok(None);
    };
    let every = failing.iter().all(|f| *f == first);
    let Some(test) = setup
        .tests
        .iter()
        .find(|t| first.ends_with(&format!("({})", t.name)))
    else {
        return Ok(None);
    };
    let criterion = first.trim_end_matches(&format!(" ({})", test.name));
    let v = judge(setup, test)?;
    let Some(e) = v.energies else {
        return Ok(None);
    };
    let boxes = crash_box_capacity(setup, test);
    let mut out = format!(
        "no bumper in the range passes: {criterion} in {} fails {} ({} stiffnesses). On the car's own bumper {} brings {:.2} kJ; the bumper took {:.2} kJ and the crash boxes store {:.2} kJ up to their usable stroke before they block",
        test.name,
        match every {
            true => "at every stiffness (each row's middle force level)",
            false => "at most stiffnesses (each row's middle force level)",
        },
        rows.len(),
        test.name,
        e.initial / 1e3,
        e.bumper / 1e3,
        boxes / 1e3,
    );
    out += &match criterion {
        "rail force" | "crash-box stroke" => format!(
            ": what they cannot take goes through the blocked crash boxes into the rails. This is the car's load path, not the bumper: give the crash boxes more stroke or a crushing force level (damageability.crash_box_stroke, the [left]/[right] first springs), let the rails take more (damageability.rail_yield), or size the bumper for the other tests (--protocol without {}).",
            test.name
        ),
        "bumper stroke" => format!(
            ": more bumper depth (damageability.bumper_stroke) is what would have to change, or leave {} out (--protocol).",
            test.name
        ),
        c if c.starts_with("clearance") => format!(
            ": the front's travel passes the gap at every bumper; more gap behind the bumper ({c} in the car file) or a stiffer load path behind it would have to change, or leave {} out (--protocol).",
            test.name
        ),
        _ => format!(
            ": check the limit in the car file, or leave {} out (--protocol).",
            test.name
        ),
    };
    Ok(Some(out))
}
