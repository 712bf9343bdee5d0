//! Matrix-free conjugate gradients, the one sparse solver both fields need: their energies
//! are sums of squared per-edge residuals, so the operator is applied edge by edge and no
//! matrix is ever assembled (and the summation order, hence the result, is fixed). Large
//! systems have their vector updates and dot products split into parts
//! ([`crate::parallel`]), summed in a fixed order: the same result on any number of cores.

use crate::parallel;

/// `z = M^-1 r` for a preconditioner `M` (see [`conjugate_gradient`]).
pub(crate) type Preconditioner<'a> = &'a dyn Fn(&[f64], &mut [f64]);

/// Solves `A x = b` for a symmetric positive (semi-)definite `A` given as `apply(x, out)`,
/// starting from `x`, for at most `iterations` steps or until the residual drops by `tol`.
/// `precondition(r, z)`, when given, sets `z = M^-1 r` for a symmetric positive definite `M`
/// close to `A` ([`super::multigrid`]): the steps then no longer grow with the mesh.
/// `keep_going(k)` is asked every [`POLL_EVERY`] steps (`k` done so far); `false` stops early.
pub(crate) fn conjugate_gradient(
    apply: impl Fn(&[f64], &mut [f64]),
    b: &[f64],
    x: &mut [f64],
    iterations: usize,
    tol: f64,
    precondition: Option<Preconditioner<'_>>,
    keep_going: &mut dyn FnMut(usize) -> bool,
) -> usize {
    let n = b.len();
    let mut ax = vec![0.0; n];
    apply(x, &mut ax);
    let mut r: Vec<f64> = b.iter().zip(&ax).map(|(b, a)| b - a).collect();
    let mut z = vec![0.0; n];
    let precondition = |r: &[f64], z: &mut Vec<f64>| match precondition {
        Some(m) => m(r, z),
        None => z.copy_from_slice(r),
    };
    precondition(&r, &mut z);
    let mut p = z.clone();
    let mut rr = parallel::dot(&r, &r);
    let mut rz = parallel::dot(&r, &z);
    let b_norm = parallel::dot(b, b).sqrt().max(1e-300);
    let mut ap = vec![0.0; n];
    for k in 0..iterations {
        if rr.sqrt() <= tol * b_norm || (k % POLL_EVERY == 0 && !keep_going(k)) {
            return k;
        }
        apply(&p, &mut ap);
        let pap = parallel::dot(&p, &ap);
        if pap <= 0.0 || !pap.is_finite() || rz <= 0.0 || !rz.is_finite() {
            return k;
        }
        let alpha = rz / pap;
        let (p_now, ap_now) = (&p, &ap);
        let rr_new = parallel::chunks_mut2(x, &mut r, |range, x, r| {
            let (p, ap) = (&p_now[range.clone()], &ap_now[range]);
            for i in 0..x.len() {
                x[i] += alpha * p[i];
                r[i] -= alpha * ap[i];
            }
            r.iter().map(|r| r * r).sum()
        });
        rr = rr_new;
        precondition(&r, &mut z);
        let rz_new = parallel::dot(&r, &z);
        let beta = rz_new / rz;
        rz = rz_new;
        let z_now = &z;
        parallel::chunks_mut(&mut p, |range, p| {
            for (p, r) in p.iter_mut().zip(&z_now[range]) {
                *p = r + beta * *p;
            }
            0.0
        });
    }
    iterations
}

/// Steps between two polls of `keep_going`.
const POLL_EVERY: usize = 8;
