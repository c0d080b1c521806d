//! The documents of an impact that every front end writes (`bumpsim impact
//! --json`, Python's `Impact.to_json`): one serialisable type, so the JSON
//! is assembled once, here, and both front ends write the same bytes.
//!
//! ```
//! use bumpsim_core::model::MsdModel;
//! use bumpsim_impact::bumper::Bumper;
//! use bumpsim_impact::document::ImpactSummary;
//! use bumpsim_impact::impact::{Options, Scenario, simulate};
//! let car = MsdModel::new(vec![1000.0], vec![], vec![]).unwrap();
//! let bumper = Bumper::three_part(1e6, 1e9, 1e6).unwrap();
//! let scenario = Scenario::Barrier { speed: 2.0 };
//! let r = simulate(&car, &bumper, scenario, &Options::default()).unwrap();
//! let doc = ImpactSummary::of(scenario, &r);
//! assert_eq!(doc.peak_force, r.peak_force);
//! assert!(doc.warnings.is_empty());
//! ```

use crate::impact::{EnergyBalance, ImpactResult, Scenario};
use serde::Serialize;

/// `bumpsim impact --json` of a 1-D car: the scenario, the peaks and the
/// energy balance (SI), and the result's own warnings; the histories go to
/// the CSV.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ImpactSummary {
    /// What hit what.
    pub scenario: Scenario,
    /// Largest bumper force, N.
    pub peak_force: f64,
    /// Largest compression, m.
    pub max_compression: f64,
    /// Permanent compression, m.
    pub remaining_compression: f64,
    /// Contact end, s.
    pub contact_time: f64,
    /// Energy the bumper absorbed, J.
    pub absorbed_energy: f64,
    /// The energy balance, J.
    pub energy: EnergyBalance,
    /// Integration step, s.
    pub step: f64,
    /// The result's checks ([`ImpactResult::warnings`]).
    pub warnings: Vec<String>,
}

impl ImpactSummary {
    /// The summary of `result` of `scenario`.
    pub fn of(scenario: Scenario, result: &ImpactResult) -> ImpactSummary {
        ImpactSummary {
            scenario,
            peak_force: result.peak_force,
            max_compression: result.max_compression,
            remaining_compression: result.remaining_compression,
            contact_time: result.contact_time,
            absorbed_energy: result.absorbed_energy,
            energy: result.energy,
            step: result.step,
            warnings: result.warnings(),
        }
    }
}
