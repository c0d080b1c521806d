//! The regression of a whole table: the one code path of `bumpsim doe fit`
//! and of a campaign's collection (crate bumpsim-campaign), so that a
//! campaign's regression equals `doe fit` on its collected table exactly.

use crate::data::{ColumnError, Data};
use crate::model::{ModelFile, Response};
use crate::regression::{Fit, RegressionError, fit, terms};

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
    check(spec)?;
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
        let f = fit(&coded, &observed, &model_terms, &names).map_err(|source| {
            TableFitError::Regression {
                response: response.clone(),
                source,
            }
        })?;
        model
            .responses
            .push(Response::from_fit(response, unit.clone(), &f));
        fits.push(ResponseFit {
            name: response.clone(),
            unit,
            observed,
            fit: f,
        });
    }
    Ok((model, fits))
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
