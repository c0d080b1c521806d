//! The regression of a whole table: the one code path of `bumpsim doe fit`
//! and of a campaign's collection (crate bumpsim-campaign), so that a
//! campaign's regression equals `doe fit` on its collected table exactly.
//! Responses given standard errors ([`StandardErrors`], a column of the
//! table per response) are fitted by [`crate::weighted`].

use crate::data::{ColumnError, Data};
use crate::model::{ModelFile, Response};
use crate::regression::{Fit, RegressionError, Term, fit, terms};
use crate::weighted::{Weighting, fit_weighted};
use std::str::FromStr;

/// What to fit: factor and response columns, optional levels, model terms.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TableFitSpec {
    /// Factor columns.
    pub factors: Vec<String>,
    /// Response columns.
    pub responses: Vec<String>,
    /// Low levels (default: the data's minimum).
    pub low: Vec<f64>,
    /// High levels (default: the data's maximum).
    pub high: Vec<f64>,
    /// Two-factor interactions.
    pub interactions: bool,
    /// Squares.
    pub squares: bool,
}

/// One response's fit with what a report needs.
#[derive(Debug, Clone)]
pub struct ResponseFit {
    /// Response name.
    pub name: String,
    /// Unit from the table's header.
    pub unit: Option<String>,
    /// Observed values.
    pub observed: Vec<f64>,
    /// The fit.
    pub fit: Fit,
    /// How the runs were weighted, for a response with standard errors.
    pub weighting: Option<Weighting>,
}

impl ResponseFit {
    /// The fit's summary as `doe fit` prints it: weighted (naming the
    /// column of `se` that holds this response's standard errors) or plain.
    pub fn summary(&self, se: &[StandardErrors]) -> String {
        let (name, unit) = (self.name.as_str(), self.unit.as_deref());
        let column = se.iter().find(|s| s.response == self.name);
        match (&self.weighting, column) {
            (Some(w), Some(c)) => crate::text::weighted_text(name, unit, &self.fit, w, &c.column),
            _ => crate::text::fit_text(name, unit, &self.fit),
        }
    }
}

/// A response's standard errors: the table column that holds them.
/// Written `RESPONSE=COLUMN`, or `RESPONSE` alone for the column
/// `RESPONSE.se` (the convention of `doe collect`'s columns).
///
/// ```
/// use bumpsim_doe::table_fit::StandardErrors;
/// let a: StandardErrors = "k1".parse().unwrap();
/// let b: StandardErrors = "k1=k1_se".parse().unwrap();
/// assert_eq!((a.column.as_str(), b.column.as_str()), ("k1.se", "k1_se"));
/// assert!("=k1.se".parse::<StandardErrors>().is_err());
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct StandardErrors {
    /// The response.
    pub response: String,
    /// The column of its standard errors (same unit).
    pub column: String,
}

impl FromStr for StandardErrors {
    type Err = TableFitError;

    fn from_str(spec: &str) -> Result<StandardErrors, TableFitError> {
        let (response, column) = match spec.split_once('=') {
            Some((r, c)) => (r.trim().to_string(), c.trim().to_string()),
            None => (spec.trim().to_string(), format!("{}.se", spec.trim())),
        };
        if response.is_empty() || column.is_empty() {
            return Err(TableFitError::Spec(format!(
                "standard errors '{spec}': expected RESPONSE=COLUMN or RESPONSE (for the column RESPONSE.se)"
            )));
        }
        Ok(StandardErrors { response, column })
    }
}

/// Why a table cannot be fitted.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum TableFitError {
    /// Factors or responses named twice or both, or levels that do not
    /// match the factors.
    #[error("{0}")]
    Spec(String),
    /// A column is missing or a factor range is invalid.
    #[error(transparent)]
    Column(#[from] ColumnError),
    /// The regression of one response failed.
    #[error("response '{response}': {source}")]
    Regression {
        /// The response.
        response: String,
        /// The cause.
        source: RegressionError,
    },
    /// The weighted regression of one response failed (a bad standard
    /// error names its row).
    #[error("response '{response}' with standard errors '{column}': {source}")]
    Weighted {
        /// The response.
        response: String,
        /// The column of its standard errors.
        column: String,
        /// The cause.
        source: RegressionError,
    },
}

/// Fits every response of `spec` on `data`: the model file and the fits.
///
/// ```
/// use bumpsim_doe::data::Data;
/// use bumpsim_doe::table_fit::{TableFitSpec, fit_table};
/// let data = Data::parse("t [mm],y [kN]\n2,10\n4,14\n3,12.1\n", std::path::Path::new("d.csv")).unwrap();
/// let spec = TableFitSpec { factors: vec!["t".into()], responses: vec!["y".into()], ..Default::default() };
/// let (model, fits) = fit_table(&data, &spec).unwrap();
/// assert_eq!(model.responses[0].unit.as_deref(), Some("kN"));
/// assert!((fits[0].fit.coefficients[1] - 2.0).abs() < 1e-9);
/// ```
pub fn fit_table(
    data: &Data,
    spec: &TableFitSpec,
) -> Result<(ModelFile, Vec<ResponseFit>), TableFitError> {
    fit_table_weighted(data, spec, &[])
}

/// [`fit_table`] with standard errors for some responses: those are fitted
/// by [`crate::weighted::fit_weighted`] with the column's values.
///
/// ```
/// use bumpsim_doe::data::Data;
/// use bumpsim_doe::table_fit::{TableFitSpec, fit_table_weighted};
/// let text = "t [mm],y [kN],y.se [kN]\n2,10,0.5\n4,14,0.5\n3,12.1,1\n3,11.8,0.5\n";
/// let data = Data::parse(text, std::path::Path::new("d.csv")).unwrap();
/// let spec = TableFitSpec { factors: vec!["t".into()], responses: vec!["y".into()], ..Default::default() };
/// let se = ["y".parse().unwrap()];
/// let (model, fits) = fit_table_weighted(&data, &spec, &se).unwrap();
/// assert_eq!(model.responses[0].weighted.as_ref().unwrap().column, "y.se");
/// assert_eq!(fits[0].weighting.as_ref().unwrap().method, "REML");
/// ```
pub fn fit_table_weighted(
    data: &Data,
    spec: &TableFitSpec,
    standard_errors: &[StandardErrors],
) -> Result<(ModelFile, Vec<ResponseFit>), TableFitError> {
    check(spec)?;
    check_standard_errors(spec, standard_errors)?;
    let (factors, coded) = data.coded(&spec.factors, &spec.low, &spec.high)?;
    let names: Vec<String> = factors.iter().map(|f| f.name.clone()).collect();
    let model_terms = terms(factors.len(), spec.interactions, spec.squares);
    let mut model = ModelFile {
        factors,
        responses: Vec::new(),
    };
    let mut fits = Vec::new();
    for response in &spec.responses {
        let observed = data.values(response)?;
        let unit = data.unit(response);
        let se = standard_errors.iter().find(|s| &s.response == response);
        let table = Table {
            coded: &coded,
            terms: &model_terms,
            names: &names,
        };
        let (entry, fitted) = table.fit(data, response, &observed, unit.clone(), se)?;
        model.responses.push(entry);
        fits.push(ResponseFit {
            name: response.clone(),
            unit,
            observed,
            fit: fitted.0,
            weighting: fitted.1,
        });
    }
    Ok((model, fits))
}

/// The coded table and model every response is fitted on.
struct Table<'a> {
    coded: &'a [Vec<f64>],
    terms: &'a [Term],
    names: &'a [String],
}

impl Table<'_> {
    /// One response: its model file entry, fit and weighting.
    fn fit(
        &self,
        data: &Data,
        response: &str,
        observed: &[f64],
        unit: Option<String>,
        se: Option<&StandardErrors>,
    ) -> Result<(Response, (Fit, Option<Weighting>)), TableFitError> {
        let Some(se) = se else {
            let f = fit(self.coded, observed, self.terms, self.names).map_err(|source| {
                TableFitError::Regression {
                    response: response.into(),
                    source,
                }
            })?;
            return Ok((Response::from_fit(response, unit, &f), (f, None)));
        };
        let values = data.values(&se.column)?;
        let weighted = fit_weighted(self.coded, observed, &values, self.terms, self.names)
            .map_err(|source| TableFitError::Weighted {
                response: response.into(),
                column: se.column.clone(),
                source,
            })?;
        let entry = Response::from_weighted(response, unit, &weighted, &se.column);
        Ok((entry, (weighted.fit, Some(weighted.weighting))))
    }
}

/// Refuses standard errors for a response that is not fitted, given twice,
/// or in a column that is a factor or a response.
fn check_standard_errors(
    spec: &TableFitSpec,
    standard_errors: &[StandardErrors],
) -> Result<(), TableFitError> {
    let bad = |why: String| Err(TableFitError::Spec(why));
    for (i, s) in standard_errors.iter().enumerate() {
        let (r, c) = (&s.response, &s.column);
        if !spec.responses.contains(r) {
            return bad(format!(
                "standard errors for '{r}' (column '{c}'): '{r}' is not a fitted response ({})",
                spec.responses.join(", ")
            ));
        }
        if standard_errors[..i].iter().any(|t| &t.response == r) {
            return bad(format!("standard errors for '{r}' are given twice"));
        }
        if spec.factors.contains(c) || spec.responses.contains(c) {
            return bad(format!(
                "standard errors of '{r}' in column '{c}': '{c}' is a factor or a response"
            ));
        }
    }
    Ok(())
}

/// Refuses a spec whose values would be ignored or mixed up: a factor or
/// response named twice, a column both factor and response, and low or
/// high levels that are not one per factor.
fn check(spec: &TableFitSpec) -> Result<(), TableFitError> {
    let bad = |why: String| Err(TableFitError::Spec(why));
    for (what, names) in [("factor", &spec.factors), ("response", &spec.responses)] {
        if let Some(i) = (0..names.len()).find(|&i| names[..i].contains(&names[i])) {
            return bad(format!("{what} '{}' is given twice", names[i]));
        }
    }
    if let Some(both) = spec.factors.iter().find(|f| spec.responses.contains(f)) {
        return bad(format!("'{both}' is given as a factor and as a response"));
    }
    for (what, levels) in [("low", &spec.low), ("high", &spec.high)] {
        if !levels.is_empty() && levels.len() != spec.factors.len() {
            return bad(format!(
                "{} {what} levels for {} factors: give one per factor, or none (the data's extremes)",
                levels.len(),
                spec.factors.len()
            ));
        }
    }
    Ok(())
}
