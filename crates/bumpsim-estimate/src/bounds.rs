//! Bounds and fixed values of a model's parameters (SI, in the model's
//! parameter order). The search works in log parameters `p = ln θ`, so
//! every bound is positive (an upper bound may be infinite) and a fixed
//! value is held where it is, not estimated.
//!
//! ```
//! use bumpsim_estimate::bounds::Bounds;
//! let mut b = Bounds::uniform(3, 1.0);
//! b.fixed[1] = Some(5.0);
//! assert_eq!(b.free(), vec![0, 2]);
//! let (lower, upper) = b.log_free();
//! assert_eq!(lower, vec![0.0, 0.0]);
//! assert!(upper.iter().all(|u| u.is_infinite()));
//! ```

/// Bounds and fixed values per parameter, SI.
#[derive(Debug, Clone, PartialEq)]
pub struct Bounds {
    /// Lower bounds (> 0).
    pub lower: Vec<f64>,
    /// Upper bounds (may be infinite).
    pub upper: Vec<f64>,
    /// Fixed values (not estimated).
    pub fixed: Vec<Option<f64>>,
}

impl Bounds {
    /// `count` parameters in `[lower, ∞)`, none fixed.
    pub fn uniform(count: usize, lower: f64) -> Bounds {
        Bounds {
            lower: vec![lower; count],
            upper: vec![f64::INFINITY; count],
            fixed: vec![None; count],
        }
    }

    /// Each parameter within a factor `reach` of its value in `theta`.
    pub fn around(theta: &[f64], reach: f64) -> Bounds {
        Bounds {
            lower: theta.iter().map(|t| t / reach).collect(),
            upper: theta.iter().map(|t| t * reach).collect(),
            fixed: vec![None; theta.len()],
        }
    }

    /// Indices of the parameters not fixed.
    pub fn free(&self) -> Vec<usize> {
        (0..self.fixed.len())
            .filter(|&i| self.fixed[i].is_none())
            .collect()
    }

    /// The bounds of the free parameters in log: `(ln lower, ln upper)`.
    pub fn log_free(&self) -> (Vec<f64>, Vec<f64>) {
        let free = self.free();
        let log = |v: &[f64]| free.iter().map(|&i| v[i].ln()).collect();
        (log(&self.lower), log(&self.upper))
    }
}
