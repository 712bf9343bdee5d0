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
    // z = M^-1 r and r . z. Without a preconditioner z is r itself and r . z is r . r,
    // summed in the same parts and order as the update's own sum of squares `rr`: neither a
    // copy nor a second dot product is made (the iterates are the same bit for bit), and
    // `z` stays empty.
    let mut z = vec![0.0; if precondition.is_some() { n } else { 0 }];
    let precondition_dot = |r: &[f64], rr: f64, z: &mut [f64]| match precondition {
        Some(m) => {
            m(r, z);
            parallel::dot(r, z)
        }
        None => rr,
    };
    let mut rr = parallel::dot(&r, &r);
    let mut rz = precondition_dot(&r, rr, &mut z);
    let mut p = if precondition.is_some() {
        z.clone()
    } else {
        r.clone()
    };
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
        let rz_new = precondition_dot(&r, rr, &mut z);
        let beta = rz_new / rz;
        rz = rz_new;
        let z_now: &[f64] = if precondition.is_some() { &z } else { &r };
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A symmetric positive definite operator over `n` unknowns: a weighted path Laplacian
    /// plus a small diagonal, large enough that the vector loops are split into parts.
    fn path_operator(n: usize) -> impl Fn(&[f64], &mut [f64]) {
        move |x: &[f64], out: &mut [f64]| {
            for i in 0..n {
                out[i] = 1e-3 * (1.0 + (i % 7) as f64) * x[i];
            }
            for i in 1..n {
                let w = 1.0 + (i % 5) as f64 * 0.25;
                let d = w * (x[i] - x[i - 1]);
                out[i] += d;
                out[i - 1] -= d;
            }
        }
    }

    #[test]
    fn solves_a_small_system() {
        let n = 50;
        let apply = path_operator(n);
        let b: Vec<f64> = (0..n).map(|i| ((i * 37) % 11) as f64 - 5.0).collect();
        let mut x = vec![0.0; n];
        conjugate_gradient(&apply, &b, &mut x, 10 * n, 1e-12, None, &mut |_| true);
        let mut ax = vec![0.0; n];
        apply(&x, &mut ax);
        let residual: f64 = ax.iter().zip(&b).map(|(a, b)| (a - b).powi(2)).sum();
        assert!(residual.sqrt() < 1e-8, "residual {residual}");
    }

    /// Without a preconditioner the solver reuses `r` for `z` and `r . r` for `r . z`; the
    /// iterates must be those of the identity preconditioner bit for bit (the remesher's
    /// lattices depend on them), on a system split into parts too.
    #[test]
    fn no_preconditioner_is_the_identity_bit_for_bit() {
        for n in [100, 3 * parallel::MIN_PART + 11] {
            let apply = path_operator(n);
            let b: Vec<f64> = (0..n).map(|i| ((i * 37) % 11) as f64 - 5.0).collect();
            let identity = |r: &[f64], z: &mut [f64]| z.copy_from_slice(r);
            let (mut plain, mut with) = (vec![0.0; n], vec![0.0; n]);
            let a = conjugate_gradient(&apply, &b, &mut plain, 40, 1e-14, None, &mut |_| true);
            let c = conjugate_gradient(
                &apply,
                &b,
                &mut with,
                40,
                1e-14,
                Some(&identity),
                &mut |_| true,
            );
            assert_eq!(a, c);
            assert!(
                plain
                    .iter()
                    .zip(&with)
                    .all(|(p, w)| p.to_bits() == w.to_bits())
            );
            assert!(plain.iter().any(|&p| p != 0.0));
        }
    }
}
