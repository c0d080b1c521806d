//! Human-readable text of DOE results (terminal and reports share it):
//! the coefficient table with standard errors, t, p and 95 % intervals,
//! R², adjusted R², Q² (or why it is undefined), σ and lack of fit.

use bumpsim_core::units::format_number;

/// The summary of one fitted response; `unit` of the response.
pub fn fit_text(response: &str, unit: Option<&str>, f: &crate::regression::Fit) -> String {
    let u = unit.unwrap_or("-");
    let mut text = format!(
        "{response} [{u}]: R² {}, adjusted R² {}, ",
        format_number(f.r2, 4),
        f.r2_adjusted.map_or("-".into(), |v| format_number(v, 4))
    );
    text += &match (f.q2, &f.q2_note) {
        (Some(q2), _) => format!(
            "Q² {} (PRESS {} {u}²)\n",
            format_number(q2, 4),
            format_number(f.press.unwrap_or(0.0), 4)
        ),
        (None, Some(note)) => format!("{note}\n"),
        _ => "Q² undefined\n".into(),
    };
    text += &format!(
        "  {:<12} {:>12} {:>12} {:>9} {:>9} {:>28}\n",
        "term (coded)", "coefficient", "std. error", "t", "p", "95 % interval"
    );
    for j in 0..f.terms.len() {
        let opt = |v: Option<f64>| v.map_or("-".to_string(), |v| format_number(v, 4));
        let ci = f.ci95[j].map_or("-".to_string(), |[a, b]| {
            format!("{} .. {}", format_number(a, 4), format_number(b, 4))
        });
        text += &format!(
            "  {:<12} {:>12} {:>12} {:>9} {:>9} {:>28}\n",
            f.terms[j],
            format_number(f.coefficients[j], 5),
            opt(f.std_errors[j]),
            opt(f.t[j]),
            opt(f.p[j]),
            ci
        );
    }
    if let Some(sd) = f.residual_sd {
        text += &format!(
            "  residual SD {} {u} ({} degrees of freedom)\n",
            format_number(sd, 4),
            f.dof_residual
        );
    }
    if let Some(l) = &f.anova.lack_of_fit {
        text += &format!(
            "  lack of fit: F {} on ({}, {}) df, p {}\n",
            format_number(l.f, 4),
            l.df_lack_of_fit,
            l.df_pure_error,
            format_number(l.p, 3)
        );
    }
    text
}
