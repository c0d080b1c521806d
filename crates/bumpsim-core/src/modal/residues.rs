//! Residues of one output and their exact derivatives with respect to the
//! log parameters, for [`super::ModalForm`] (the formulas are the module's:
//! `∂λ_i = F_ii`, `∂r_i = (c'V)_i β_i + γ_i (U b')_i
//! + Σ_(j≠i) (γ_j F_ji β_i + γ_i F_ij β_j)/(λ_i − λ_j)` with `F = U ∂A V`,
//! `γ = cV`, `β = Ub`).

use super::C;
use super::eigen::Decomposition;
use crate::model::{MsdModel, ParameterKind, parameter_kind};
use crate::state_space::relative_inverse_mass;

/// The output mass within the chain: masses, total, and `w` with
/// `x_o = x_cm + wᵀu`.
pub(super) struct Chain {
    pub masses: Vec<f64>,
    pub total: f64,
    output: usize,
    /// `w_l` per link (see the module).
    w: Vec<f64>,
}

impl Chain {
    pub fn new(model: &MsdModel, output: usize) -> Chain {
        let masses = model.masses().to_vec();
        let total: f64 = masses.iter().sum();
        let mut chain = Chain {
            masses,
            total,
            output,
            w: Vec::new(),
        };
        chain.w = (0..chain.masses.len() - 1)
            .map(|l| chain.weight(l, None))
            .collect();
        chain
    }

    /// `w_l`, or with `Some(i)` its derivative `∂w_l/∂ln m_i`. Behind the
    /// output the masses behind link l count (+), before it those in front
    /// of it (−).
    fn weight(&self, l: usize, by: Option<usize>) -> f64 {
        let behind = l >= self.output;
        let counts = |j: usize| if behind { j > l } else { j <= l };
        let sign = if behind { 1.0 } else { -1.0 };
        let (m, total) = (&self.masses, self.total);
        let sum: f64 = (0..m.len()).filter(|&j| counts(j)).map(|j| m[j]).sum();
        match by {
            None => sign * sum / total,
            Some(i) => {
                let own = f64::from(u8::from(counts(i)));
                sign * m[i] * (own / total - sum / (total * total))
            }
        }
    }
}

/// The residues of one output and what their derivatives need.
pub(super) struct Modes {
    pub decomposition: Decomposition,
    /// `r_i = γ_i β_i` per eigenvalue.
    pub residue: Vec<C>,
    /// `γ = c V`.
    gamma: Vec<C>,
    /// `β = U b`.
    beta: Vec<C>,
    /// `1/(λ_i − λ_j)` for each representative i and every j (0 on i = j).
    differences: Vec<Vec<C>>,
}

impl Modes {
    pub fn new(decomposition: Decomposition, chain: &Chain) -> Modes {
        let d = &decomposition;
        let gamma = observed(d, &chain.w);
        // b = [0; e_0 / m_0]: U b is column L of U over m_0
        let beta: Vec<C> = (0..d.size())
            .map(|i| d.u(i, d.links) / chain.masses[0])
            .collect();
        let residue = gamma.iter().zip(&beta).map(|(g, b)| g * b).collect();
        let differences = (0..d.representatives())
            .map(|i| {
                let li = d.lambda[i];
                d.lambda
                    .iter()
                    .enumerate()
                    .map(|(j, lj)| if i == j { C::ZERO } else { (li - lj).inv() })
                    .collect()
            })
            .collect();
        Modes {
            decomposition,
            residue,
            gamma,
            beta,
            differences,
        }
    }

    /// Per representative i, `(∂r_i/∂p, r_i ∂λ_i/∂p)` for log parameter `p`,
    /// and the rigid coefficient `∂(1/M)/∂p` of `ρ`.
    pub fn derivatives(&self, model: &MsdModel, chain: &Chain, p: usize) -> (f64, Vec<(C, C)>) {
        let d = &self.decomposition;
        let (size, links) = (d.size(), d.links);
        let (a, l) = rank_one(model, p);
        // F = U (a ℓᵀ) V = α βᵀ
        let alpha: Vec<C> = (0..size)
            .map(|i| (links..size).map(|r| d.u(i, r) * a[r]).sum())
            .collect();
        let along: Vec<C> = (0..size)
            .map(|j| (0..size).map(|r| d.v(r, j) * l[r]).sum())
            .collect();
        let (kind, number) = parameter_kind(model.dof(), p);
        let mass = (kind == ParameterKind::Mass).then_some(number - 1);
        let observed = match mass {
            Some(i) => observed(
                d,
                &(0..links)
                    .map(|l| chain.weight(l, Some(i)))
                    .collect::<Vec<_>>(),
            ),
            None => vec![C::ZERO; size],
        };
        // b = e_0/m_0 depends on m_0 only: U b' = −U b
        let input = if mass == Some(0) { -1.0 } else { 0.0 };
        let rigid = mass.map_or(0.0, |i| -chain.masses[i] / (chain.total * chain.total));
        let (gamma, beta) = (&self.gamma, &self.beta);
        let terms = (0..d.representatives())
            .map(|i| {
                let inv = &self.differences[i];
                let s1: C = (0..size).map(|j| gamma[j] * alpha[j] * inv[j]).sum();
                let s2: C = (0..size).map(|j| along[j] * beta[j] * inv[j]).sum();
                let dlambda = alpha[i] * along[i];
                let dresidue = observed[i] * beta[i]
                    + gamma[i] * beta[i] * input
                    + along[i] * beta[i] * s1
                    + gamma[i] * alpha[i] * s2;
                (dresidue, self.residue[i] * dlambda)
            })
            .collect();
        (rigid, terms)
    }
}

/// `γ = c V` for `c = [x; 0]` (a displacement functional `x` per link).
fn observed(d: &Decomposition, x: &[f64]) -> Vec<C> {
    (0..d.size())
        .map(|j| (0..d.links).map(|l| d.v(l, j) * x[l]).sum())
        .collect()
}

/// `∂A/∂ln θ_p = a ℓᵀ` of the relative system: rank one. A mass:
/// `∂R/∂ln m_i = −q_i q_iᵀ/m_i` (q_i the i-th column of the difference
/// matrix) in both velocity-row blocks; a damper or spring: column j of
/// `−θ_j R` in the velocity or position columns.
fn rank_one(model: &MsdModel, p: usize) -> (Vec<f64>, Vec<f64>) {
    let (m, c, k) = (model.masses(), model.dampers(), model.springs());
    let links = m.len() - 1;
    let (mut a, mut l) = (vec![0.0; 2 * links], vec![0.0; 2 * links]);
    let mut column = |j: usize, by: f64| {
        for r in 0..links {
            a[links + r] = -by * relative_inverse_mass(m, r, j);
        }
    };
    let (kind, number) = parameter_kind(model.dof(), p);
    match (kind, number - 1) {
        (ParameterKind::Mass, i) => {
            // q_i: +1 at link i, −1 at link i − 1
            let q = |r: usize| f64::from(u8::from(r == i)) - f64::from(u8::from(r + 1 == i));
            for r in 0..links {
                a[links + r] = q(r) / m[i];
                l[r] = k[r] * q(r);
                l[links + r] = c[r] * q(r);
            }
        }
        (ParameterKind::Damper, j) => {
            column(j, c[j]);
            l[links + j] = 1.0;
        }
        (ParameterKind::Spring, j) => {
            column(j, k[j]);
            l[j] = 1.0;
        }
    }
    (a, l)
}
