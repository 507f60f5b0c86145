//! A sampled state, at which the real and interval rings evaluate: every symbol's
//! components, after the assumptions, and the unit normal, as floating-point numbers.

use crate::algebra::Tensor;
use rustc_hash::FxHashMap as HashMap;

/// One random state: every symbol's components (after the assumptions) and a normal.
#[derive(Clone, Debug)]
pub struct State {
    pub symbols: HashMap<String, Tensor<f64>>,
    pub n: Vec<f64>,
}
