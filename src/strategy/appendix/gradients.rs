//! `yield-gradients`: Q and F at the state, exact against num-dual and central
//! differences of an independently written F_2.

use super::*;

/// The exact gradient evaluated at `f_r`, as (Q_11, Q_22, Q_12, Q_21, F_13, F_23).
pub(super) fn exact_gradient_at(p: &Params, g: &tangent::YieldGradient, f_r: f64) -> [f64; 6] {
    let at = |x: &RatFunc| x.eval_f64(&|v| if v == p.f_r { f_r } else { f64::NAN });
    [
        at(&g.q[0]),
        at(&g.q[1]),
        at(&g.q[2]),
        at(&g.q[3]),
        at(&g.f[0]),
        at(&g.f[1]),
    ]
}

/// The largest differences (exact vs num-dual, num-dual vs central differences) over
/// the states of the check; `exact` gives the closed form for a shear sign.
pub fn gradient_residuals(
    p: &Params,
    exact: &dyn Fn(ShearSign) -> Result<tangent::YieldGradient, String>,
) -> Result<(f64, f64, usize), String> {
    let (mut worst_exact, mut worst_fd, mut n) = (0.0f64, 0.0f64, 0);
    for shear in [ShearSign::Positive, ShearSign::Negative] {
        let g = exact(shear)?;
        for f_r in [0.05, 0.3, 0.5, 1.0, 2.0, 3.0] {
            for sigma in [-1.0, -2.5] {
                for r_g in [1.0, 0.4] {
                    let x = tangent::state_components(sigma, f_r, shear);
                    let dual = tangent::yield_gradient_dual(x, f_r, r_g);
                    let closed = exact_gradient_at(p, &g, f_r);
                    for k in 0..6 {
                        worst_exact = worst_exact.max((dual[k] - closed[k]).abs());
                        let (mut xp, mut xm) = (x, x);
                        xp[k] += FD_STEP;
                        xm[k] -= FD_STEP;
                        let fd = (tangent::rolling_yield(&xp, f_r, r_g)
                            - tangent::rolling_yield(&xm, f_r, r_g))
                            / (2.0 * FD_STEP);
                        // μ-derivatives: F₂ is not differentiable across μ = 0 only when
                        // q = r = 0, which the state avoids (τ ≠ 0).
                        worst_fd = worst_fd.max((fd - dual[k]).abs());
                        n += 1;
                    }
                }
            }
        }
    }
    Ok((worst_exact, worst_fd, n))
}

pub(super) fn yield_gradients(p: &Params) -> Result<Outcome, String> {
    let (worst_exact, worst_fd, n) =
        gradient_residuals(p, &|s| tangent::yield_gradient_exact(p, s))?;
    let g = tangent::yield_gradient_exact(p, ShearSign::Positive)?;
    let shown: Vec<String> = g.q.iter().chain(&g.f).map(|x| p.display(x)).collect();
    let holds = worst_exact <= ROUTE_TOL && worst_fd <= FD_TOL;
    let detail = format!(
        "exact at the state (τ > 0): (Q_11, Q_22, Q_12, Q_21) = ({}), (F_1, F_2) = ({}); τ < 0 flips Q_12, Q_21; \
         num-dual at {n} component checks (f_r 0.05–3, σ = −1, −2.5, R_g = 1, 0.4, both signs of τ): \
         largest |exact − num-dual| {worst_exact:.1e} (tolerance {ROUTE_TOL:.0e}), largest |num-dual − central difference| \
         {worst_fd:.1e} (step {FD_STEP:.0e}, tolerance {FD_TOL:.0e})",
        shown[..4].join(", "),
        shown[4..].join(", ")
    );
    // Compared at sampled parameter points in f64: sampled evidence, not a proof.
    let outcome = if holds {
        Outcome::holds_sampled(Method::Symbolic, n)
    } else {
        Outcome::fails(Method::Symbolic, Strength::Sampled, n)
    };
    Ok(outcome.with_finding(Finding::Appendix { text: detail }))
}
