//! bumpsim-campaign: campaigns at cluster scale (spec §10, issue 17): a
//! design of experiments whose points are FE runs, dispatched to a local
//! process pool or a Slurm job array, collected into the design table and
//! regressed with the code of `bumpsim doe fit`, surviving failed,
//! timed-out, pre-empted and lost tasks and a restarted controller.
//!
//! - [`spec`]: the campaign file (design, template, derived quantities,
//!   solver, responses, regression, executor);
//! - [`expr`]: the derived quantities' arithmetic;
//! - [`template`]: `{{name}}` deck templates and LS-DYNA `*PARAMETER` includes;
//! - [`init`]: the campaign folder (point folders, task script, state);
//! - [`task`]: the task script and the exit marker it leaves;
//! - [`state`]: the state of every point, kept in an append-only journal
//!   ([`journal`]: its framing) compacted into snapshots;
//! - [`lock`]: the controller lock;
//! - [`executor`]: local process pool and Slurm job arrays;
//! - [`run`], [`controller`]: the controller loop with retries, requeues and resume;
//! - [`repair`]: a state rebuilt from the point folders;
//! - [`status`]: points per status, as text or JSON;
//! - [`response`]: a `[[response]]` (reader, file, quantity, statistic);
//! - [`readers`]: responses from CalculiX `.dat`, CSV and LS-DYNA `glstat`;
//! - [`identify`]: per-point identification from a study template;
//! - [`collect`]: the collected table and its regression.
//!
//! A two-factor campaign whose "solver" is `true` and whose response is a
//! CSV the template itself writes (run locally, collected and fitted):
//!
//! ```
//! use bumpsim_campaign::{collect, init, run};
//! let dir = std::env::temp_dir().join(format!("bumpsim-doc-campaign-{}", std::process::id()));
//! std::fs::create_dir_all(&dir).unwrap();
//! std::fs::write(dir.join("out.tmpl"), "time [s],y [m]\n0,0\n1,{{y}}\n").unwrap();
//! std::fs::write(dir.join("c.toml"), r#"
//! name = "doc"
//! derived = { y = "2 * a + b" }
//! [design]
//! kind = "full"
//! factors = [{ name = "a", low = 1, high = 2 }, { name = "b", low = 0, high = 1 }]
//! centre = 1
//! [template]
//! file = "out.tmpl"
//! deck = "out.csv"
//! [solver]
//! command = ["true"]
//! [[response]]
//! name = "y_max"
//! reader = "csv"
//! file = "out.csv"
//! quantity = "y"
//! unit = "m"
//! "#).unwrap();
//! let campaign = dir.join("campaign");
//! assert_eq!(init::init(&dir.join("c.toml"), &campaign).unwrap().points, 5);
//! let summary = run::run(&campaign, &run::RunOptions::default()).unwrap();
//! assert_eq!((summary.done, summary.failed.len()), (5, 0));
//! let collected = collect::collect(&campaign).unwrap();
//! assert_eq!(collected.rows, 5);
//! assert!(campaign.join("results/report/index.html").exists());
//! std::fs::remove_dir_all(&dir).unwrap();
//! ```

pub mod collect;
pub mod controller;
pub mod error;
pub mod executor;
pub mod expr;
pub mod identify;
pub mod init;
pub mod journal;
pub mod lock;
pub mod readers;
pub mod repair;
pub mod response;
pub mod run;
pub mod spec;
pub mod staging;
pub mod state;
pub mod status;
pub mod task;
pub mod template;

pub use error::{CampaignError, Result};

/// The types most campaigns need (the facade globs it).
pub mod prelude {
    pub use crate::error::CampaignError;
    pub use crate::spec::Spec as CampaignSpec;
}
