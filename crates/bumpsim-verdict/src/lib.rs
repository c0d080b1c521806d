//! bumpsim-verdict: will it pass? A car's bumper in the low-speed
//! protocols, judged against its damageability limits with margins, and
//! the bumper that would pass (issue 36).
//!
//! - [`protocol`]: 49 CFR 581, CMVSS 215, UN R42, the RCAR bumper and
//!   structural tests and the IIHS tests, each with its figures, source and
//!   what could not be checked;
//! - [`limits`]: the car's clearances and limits (`[damageability]` of the
//!   planar car file);
//! - [`criteria`]: each criterion's value, limit and margin;
//! - [`line`](mod@line): the same criteria for a car along a line (the chain with
//!   nonlinear links), from its model's 1-D runs;
//! - [`pulse`]: peak and 3 ms clip deceleration, delta-V, OLC, ASI
//!   (EN 1317-1:2010 or 1998), to a defined contact end;
//! - [`verdict`](mod@verdict): every test run and judged;
//! - [`requirements`]: what each protocol requires, and whether the
//!   model judges it, a proxy stands in, or the engineer must check it;
//! - [`sequence`]: a protocol's impacts in order on one car, each from
//!   the damage the earlier ones left (issue 45);
//! - [`probability`]: the verdict propagated over the car's uncertainty:
//!   each criterion's probability of passing (issue 39);
//! - [`sensitivity`]: which uncertain parameters drive each criterion:
//!   Sobol' first-order and total indices with bootstrap intervals
//!   (issue 39);
//! - [`uncertainty`]: the car's uncertainty, from an identification's
//!   JSON or relative spreads;
//! - [`target`]: the region of bumper characteristics that passes every
//!   criterion with a margin, its binding criteria and corridor;
//! - [`diagnosis`]: why no bumper passes, when none does;
//! - [`text`]: the tables with units.
//!
//! ```
//! use bumpsim_core::model::MsdModel;
//! use bumpsim_impact::bumper::Bumper;
//! use bumpsim_planar::car::{Layout, PlanarCar};
//! use bumpsim_verdict::prelude::*;
//! let chain = MsdModel::new(vec![16.0, 1300.0], vec![4e3], vec![6e6]).unwrap();
//! let bumper = Bumper::three_part(3e6, 200e3, 2e7).unwrap();
//! let car = PlanarCar::symmetric(&chain, &bumper, &Layout::default()).unwrap();
//! let limits = Damageability::parse(
//!     "[damageability]\nrail_yield = 300e3\ncrash_box_stroke = 0.05\n\
//!      [[damageability.clearance]]\nname = \"radiator\"\ngap = 0.08\nfrom = \"beam\"\n",
//!     "car.toml".as_ref(),
//! )?;
//! let tests = bumpsim_verdict::protocol::select(&["part581-barrier-front"])?;
//! let v = verdict(&Setup::new(vec![CarEnd::new(car, limits)?], tests, 0.0)?)?;
//! assert!(v.passed());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod criteria;
pub mod diagnosis;
pub mod error;
pub mod limits;
pub mod line;
pub mod probability;
pub mod protocol;
pub mod pulse;
pub mod requirements;
pub mod sensitivity;
pub mod sequence;
pub mod target;
pub mod text;
pub mod uncertainty;
pub mod verdict;

pub use error::VerdictError;
pub use verdict::{Setup, Verdict, verdict};

/// The types most verdicts need (the facade globs it).
pub mod prelude {
    pub use crate::criteria::{Criterion, Outcome};
    pub use crate::error::VerdictError;
    pub use crate::limits::{Damageability, End};
    pub use crate::probability::Sampling;
    pub use crate::protocol::{Protocol, Test};
    pub use crate::target::{Region, TargetOptions};
    pub use crate::uncertainty::{Propagation, Uncertainty};
    pub use crate::verdict::{CarEnd, Setup, TestVerdict, Verdict, verdict};
}
