//! The model orders (numbers of masses) to identify, as written on a
//! command line or in a study: one number (`3`), an inclusive range
//! (`1..5`) or a list (`1,2,3`), each from 1 to
//! [`MAX_DOF`](crate::estimate::MAX_DOF); and the DOF table (the
//! thesis's table 1) identified over them, each model continued from the
//! last one identified ([`Sweep`], [`table`]; issue 19).
//!
//! ```
//! use bumpsim_ident::dofs::DofList;
//! let dofs: DofList = "2..4".parse().unwrap();
//! assert_eq!(dofs.0, vec![2, 3, 4]);
//! assert_eq!("1,3".parse::<DofList>().unwrap().0, vec![1, 3]);
//! assert!("0".parse::<DofList>().is_err() && "4..2".parse::<DofList>().is_err());
//! assert!("1..1000000000000".parse::<DofList>().is_err()); // above MAX_DOF
//! assert!("2,2".parse::<DofList>().is_err()); // each order once
//! ```

use crate::case::LoadCase;
use crate::estimate::{IdentError, Identification, Settings, identify};
use bumpsim_core::model::MsdModel;
use std::str::FromStr;

/// Model orders to identify, in the order given.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DofList(pub Vec<usize>);

/// A text that is not a DOF number, range or list.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "'{0}': expected a number (3), a range (1..5) or a list (1,2,3) of different numbers from 1 to {max} ({reason})",
    max = crate::estimate::MAX_DOF,
    reason = crate::settings::MAX_DOF_REASON
)]
pub struct DofListError(pub String);

impl FromStr for DofList {
    type Err = DofListError;

    fn from_str(text: &str) -> Result<DofList, DofListError> {
        let number = |s: &str| match s.trim().parse::<usize>() {
            Ok(n) if (1..=crate::estimate::MAX_DOF).contains(&n) => Ok(n),
            _ => Err(DofListError(text.into())),
        };
        let list: Vec<usize> = match text.split_once("..") {
            Some((a, b)) => (number(a)?..=number(b)?).collect(),
            None => text.split(',').map(number).collect::<Result<_, _>>()?,
        };
        if list.is_empty() || repeated(&list).is_some() {
            return Err(DofListError(text.into()));
        }
        Ok(DofList(list))
    }
}

/// The first DOF that `list` gives a second time, if any (a study's list
/// and `--dof` are checked alike).
pub(crate) fn repeated(list: &[usize]) -> Option<usize> {
    (1..list.len())
        .find(|&i| list[..i].contains(&list[i]))
        .map(|i| list[i])
}

/// A DOF table in the making: it remembers the last model identified, so
/// that the next order starts from it ([`Settings::continue_from`]: each
/// mass split in turn). A failed order leaves the memory as it was.
/// Cross-validated, it also predicts each load case left out
/// ([`crate::crossval`]) for the table's recommendation
/// ([`crate::choice`]).
#[derive(Debug, Clone, Default)]
pub struct Sweep {
    last: Option<MsdModel>,
    cross_validated: bool,
}

impl Sweep {
    /// A sweep that has identified nothing yet.
    pub fn new() -> Sweep {
        Sweep::default()
    }

    /// The same sweep, cross-validating each order when `yes`.
    pub fn cross_validated(self, yes: bool) -> Sweep {
        Sweep {
            cross_validated: yes,
            ..self
        }
    }

    /// Identifies `settings.dof` masses from `cases` ([`identify`]),
    /// continued from the last model this sweep identified.
    pub fn identify(
        &mut self,
        cases: &[LoadCase],
        mut settings: Settings,
        observer: &dyn bumpsim_estimate::observer::Observer,
    ) -> Result<Identification, IdentError> {
        if let Some(last) = &self.last {
            settings.continue_from(last);
        }
        let mut result = identify(cases, &settings, observer)?;
        self.last = Some(result.model.clone());
        if self.cross_validated {
            result.cross_validation = crate::crossval::cross_validate(cases, &settings, &result);
        }
        Ok(result)
    }
}

/// The DOF table over `dofs` in order: `setup(dof)` gives an order's cases
/// and settings; each order is continued from the last one identified and
/// cross-validated (with two or more cases).
///
/// ```
/// use bumpsim_core::model::MsdModel;
/// use bumpsim_ident::{LoadCase, Settings, dofs::table};
/// let truth = MsdModel::new(vec![30.0, 900.0], vec![3e3], vec![6e5]).unwrap();
/// let force: Vec<f64> = (0..300).map(|k| 2e4 * (k as f64 * 5e-4 * 50.0).sin().max(0.0)).collect();
/// let mut case = LoadCase {
///     name: "flat".into(), start: 0.0, step: 5e-4, force, measured: vec![], output_dof: 1,
///     initial_velocity: 0.0, window: (0, 299), compare: Default::default(),
/// };
/// case.measured = case.simulate(&truth).unwrap();
/// let cases = vec![case];
/// let rows = table(&[1, 2], &|dof| (cases.clone(), Settings::new(dof, 4)));
/// let two = rows[1].as_ref().unwrap();
/// assert!(two.objective < rows[0].as_ref().unwrap().objective);
/// assert!(two.cases[0].fit_percent > 99.9);
/// ```
pub fn table(
    dofs: &[usize],
    setup: &dyn Fn(usize) -> (Vec<LoadCase>, Settings),
) -> Vec<Result<Identification, IdentError>> {
    let mut sweep = Sweep::new().cross_validated(true);
    dofs.iter()
        .map(|&dof| {
            let (cases, settings) = setup(dof);
            sweep.identify(&cases, settings, &|| {})
        })
        .collect()
}
