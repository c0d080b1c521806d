//! The model orders (numbers of masses) to identify, as written on a
//! command line or in a study: one number (`3`), an inclusive range
//! (`1..5`) or a list (`1,2,3`), each from 1 to
//! [`MAX_DOF`](crate::estimate::MAX_DOF).
//!
//! ```
//! use bumpsim_ident::dofs::DofList;
//! let dofs: DofList = "2..4".parse().unwrap();
//! assert_eq!(dofs.0, vec![2, 3, 4]);
//! assert_eq!("1,3".parse::<DofList>().unwrap().0, vec![1, 3]);
//! assert!("0".parse::<DofList>().is_err() && "4..2".parse::<DofList>().is_err());
//! assert!("1..1000000000000".parse::<DofList>().is_err()); // above MAX_DOF
//! ```

use std::str::FromStr;

/// Model orders to identify, in the order given.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DofList(pub Vec<usize>);

/// A text that is not a DOF number, range or list.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "'{0}': expected a number (3), a range (1..5) or a list (1,2,3) of numbers from 1 to {max}",
    max = crate::estimate::MAX_DOF
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
        if list.is_empty() {
            return Err(DofListError(text.into()));
        }
        Ok(DofList(list))
    }
}
