//! Matrix-free conjugate gradients, the one sparse solver both fields need: their energies
//! are sums of squared per-edge residuals, so the operator is applied edge by edge and no
//! matrix is ever assembled (and the summation order, hence the result, is fixed).

/// Solves `A x = b` for a symmetric positive (semi-)definite `A` given as `apply(x, out)`,
/// starting from `x`, for at most `iterations` steps or until the residual drops by `tol`.
/// `keep_going(k)` is asked every [`POLL_EVERY`] steps (`k` done so far); `false` stops early.
pub(crate) fn conjugate_gradient(
    apply: impl Fn(&[f64], &mut [f64]),
    b: &[f64],
    x: &mut [f64],
    iterations: usize,
    tol: f64,
    keep_going: &mut dyn FnMut(usize) -> bool,
) {
    let n = b.len();
    let mut ax = vec![0.0; n];
    apply(x, &mut ax);
    let mut r: Vec<f64> = b.iter().zip(&ax).map(|(b, a)| b - a).collect();
    let mut p = r.clone();
    let mut rr = dot(&r, &r);
    let b_norm = dot(b, b).sqrt().max(1e-300);
    let mut ap = vec![0.0; n];
    for k in 0..iterations {
        if rr.sqrt() <= tol * b_norm || (k % POLL_EVERY == 0 && !keep_going(k)) {
            break;
        }
        apply(&p, &mut ap);
        let pap = dot(&p, &ap);
        if pap <= 0.0 || !pap.is_finite() {
            break;
        }
        let alpha = rr / pap;
        for i in 0..n {
            x[i] += alpha * p[i];
            r[i] -= alpha * ap[i];
        }
        let rr_new = dot(&r, &r);
        let beta = rr_new / rr;
        rr = rr_new;
        for i in 0..n {
            p[i] = r[i] + beta * p[i];
        }
    }
}

/// Steps between two polls of `keep_going`.
const POLL_EVERY: usize = 8;

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}
