//! Every tolerance of the numeric routes, in one place: the relative tolerances that
//! judge a sampled relation, the steps of finite differences and of the adversarial
//! search, the clearances a quadrature must reach. None of them can make a proof (every
//! proof is exact and checked by the kernel); each can only decide a sampled verdict or
//! ask for a second, exact look at a counterexample.

/// Samples whose singular expression is below this in magnitude are excluded.
pub const SINGULAR_EPS: f64 = 1e-8;

/// Rounding allowed at the ends of a declared range (relative).
pub const RANGE_TOL: f64 = 1e-12;

/// Relative tolerance of a float comparison: |l − r| ≤ TOL · (1 + |l| + |r|). Inputs
/// are O(1), expressions have a few hundred operations at most, so rounding stays
/// near 1e-14; a wrong statement differs by O(1e-2) or more at a random point.
pub const TOL: f64 = 1e-9;

/// Relative agreement required between the exact values of a counterexample and the
/// interpreter's `f64` values at the same point.
pub const REVERIFY_AGREEMENT: f64 = 1e-9;

/// Beyond this magnitude of an interval argument, `sin`, `cos` and `tan` are enclosed by
/// their whole range (the position of the extrema is not computed there); at a single
/// number libm's value is used whatever its size.
pub const TRIG_REDUCTION: f64 = 1e6;

/// A violation found by the search counts only with a relative margin above this: the
/// search maximises the residual, so it can climb onto rounding noise (near a singular
/// set, cancellation of large terms) just above the sampling tolerance; a genuine
/// violation stands far above it.
pub const SEARCH_CONFIRM: f64 = 1e-6;

/// Initial step, as a fraction of each coordinate's range.
pub const FIRST_STEP: f64 = 0.25;

/// The search from one start ends when the step falls below this fraction.
pub const LAST_STEP: f64 = 1e-9;

/// How far a state near a counterexample moves each free coordinate, as a fraction of its
/// range (at most; the fraction is random).
pub const NEARBY_STEP: f64 = 1e-6;

/// Relative agreement required between an exact value and the interpreter's.
pub const SCALAR_AGREEMENT: f64 = 1e-9;

/// Relative step of central differences.
pub const FD_STEP: f64 = 1e-6;

/// Relative tolerance between num-dual and central differences.
pub const FD_TOL: f64 = 1e-6;

/// Relative step of the second difference that confirms a negative Hessian eigenvalue:
/// its truncation error is O(step²) and its rounding error O(ε/step²) ≈ 1e-10.
pub const SECOND_DIFFERENCE_STEP: f64 = 1e-3;

/// The second difference must be below −this·(1 + max|λ|) to confirm a negative
/// eigenvalue (well above its rounding error).
pub const SECOND_DIFFERENCE_TOL: f64 = 1e-7;

/// A violation caused by adaptive averages counts only beyond this multiple of their
/// error estimate; between one and this multiple the state is unresolved.
pub const QUADRATURE_CLEAR: f64 = 10.0;

/// The largest relative error estimate of the averages a `holds` may rest on.
pub const QUADRATURE_MAX: f64 = 1e-5;

/// Step of the central differences. The five-point stencil is exact for polynomials of
/// degree ≤ 4 in the step and has truncation error h⁴/30 · |f⁽⁵⁾| otherwise; rounding
/// adds about ε/h per level of nesting.
pub const TAYLOR_STEP: f64 = 1e-3;

/// Relative agreement required between an exact value involving derivatives and the
/// difference quotients' value: the stencil's error at [`TAYLOR_STEP`], nested up to three
/// derivatives deep (ε/h³ ≈ 2e-7), with a margin.
pub const TAYLOR_AGREEMENT: f64 = 1e-5;

/// The factor between an average's error estimate (or its tolerance times ∫|f|,
/// whichever is larger) and the bound a decision uses: at kinks the 15- and 7-point
/// rules err alike, and on the sphere the true error of ⟨|a·n|⟩ was seen 2.5 times
/// above both.
pub const QUADRATURE_SAFETY: f64 = 10.0;

/// Step of the differences in ε and along the coordinates of α. The five-point
/// stencil is exact for polynomials of degree ≤ 4, so for the usual densities
/// (quadratic in the field) the ε-difference has no truncation error at any step, and
/// a step ten times the interpreter's keeps the rounding of the nested differences
/// (each level multiplies it by about 1.5/h) well below the agreement required.
pub const VARIATION_STEP: f64 = 1e-2;
