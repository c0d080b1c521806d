//! When [`super::simulate`] repeats a run at half the safety factor
//! ([`super::Settings::refine`]): a run that diverged or whose energy
//! balance misses [`super::ENERGY_TOLERANCE`] is repeated; the finer run
//! replaces it after a divergence whatever it gives, after a finished run
//! only when its balance closes better.

use super::ENERGY_TOLERANCE;
use crate::car::PlanarError;
use crate::result::PlanarResult;

/// Whether a run is worth repeating finer: it diverged, or its energy
/// balance misses [`ENERGY_TOLERANCE`].
pub(super) fn open(run: &Result<PlanarResult, PlanarError>) -> bool {
    match run {
        Ok(r) => r.energy.max_relative_error > ENERGY_TOLERANCE,
        Err(e) => matches!(e, PlanarError::Diverged { .. }),
    }
}

/// Whether the finer `run` replaces `best`: any outcome after a divergence
/// (a refusal over [`MAX_STEPS`](super::MAX_STEPS) names the car's stiffness too), a balance
/// that closes better after a finished run.
pub(super) fn better(
    run: &Result<PlanarResult, PlanarError>,
    best: &Result<PlanarResult, PlanarError>,
) -> bool {
    match (run, best) {
        (_, Err(_)) => true,
        (Ok(r), Ok(b)) => r.energy.max_relative_error < b.energy.max_relative_error,
        (Err(_), Ok(_)) => false,
    }
}
