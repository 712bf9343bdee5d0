//! Matrix-free conjugate gradients, the one sparse solver both fields need: their energies
//! are sums of squared per-edge residuals, so the operator is applied edge by edge and no
//! matrix is ever assembled (and the summation order, hence the result, is fixed).

/// Solves `A x = b` for a symmetric positive (semi-)definite `A` given as `apply(x, out)`,
/// starting from `x`, for at most `iterations` steps or until the residual drops by `tol`.
pub(crate) fn conjugate_gradient(
    apply: impl Fn(&[f64], &mut [f64]),
    b: &[f64],
    x: &mut [f64],
    iterations: usize,
    tol: f64,
) {
    let n = b.len();
    let mut ax = vec![0.0; n];
    apply(x, &mut ax);
    let mut r: Vec<f64> = b.iter().zip(&ax).map(|(b, a)| b - a).collect();
    let mut p = r.clone();
    let mut rr = dot(&r, &r);
    let b_norm = dot(b, b).sqrt().max(1e-300);
    let mut ap = vec![0.0; n];
    for _ in 0..iterations {
        if rr.sqrt() <= tol * b_norm {
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

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}
