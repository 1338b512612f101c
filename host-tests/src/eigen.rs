//! Eigenvalues of a general real square matrix: nalgebra's Householder
//! Hessenberg reduction, then the Francis double-shift QR iteration with
//! exceptional shifts (EISPACK `hqr`, as in Numerical Recipes §11.6).
//!
//! Why not `nalgebra::Schur`: its QR iteration has no exceptional shifts and a
//! purely relative deflation test, and on the RTS matrices (exact zero
//! eigenvalues in Jordan blocks) it does not converge — `Schur::try_new` with
//! 20000 iterations fails for n = 5, 6, 12, 16, 33, 64 (measured with nalgebra
//! 0.35), and `complex_eigenvalues` loops forever.

use nalgebra::{Complex, DMatrix};

/// All eigenvalues of `a` (square), sorted by decreasing modulus.
/// `None` if the QR iteration does not converge (200 iterations per eigenvalue).
pub fn eigenvalues(a: &DMatrix<f64>) -> Option<Vec<Complex<f64>>> {
    let n = a.nrows();
    assert_eq!(n, a.ncols(), "square matrix expected");
    if n == 0 {
        return Some(Vec::new());
    }
    let h = nalgebra::linalg::Hessenberg::new(a.clone()).unpack_h();
    // Rarely (RTS, n = 56) the iteration stalls on a cluster of exact zero
    // eigenvalues; the spectrum of `H + σI` is that of `H` moved by σ, and the
    // move changes the iteration's path, so a few diagonal shifts are tried.
    for sigma in [0.0, 0.3, -0.2, 0.7] {
        // 1-based copy, as in the published algorithm.
        let mut m = vec![vec![0.0f64; n + 1]; n + 1];
        for i in 0..n {
            for j in 0..n {
                // Entries below the subdiagonal are zero up to round-off; drop them.
                m[i + 1][j + 1] = if i > j + 1 { 0.0 } else { h[(i, j)] };
            }
            m[i + 1][i + 1] += sigma;
        }
        if let Some((wr, wi)) = hqr(&mut m, n) {
            let mut ev: Vec<Complex<f64>> = (1..=n)
                .map(|i| Complex::new(wr[i] - sigma, wi[i]))
                .collect();
            ev.sort_by(|x, y| y.norm().total_cmp(&x.norm()));
            return Some(ev);
        }
    }
    None
}

fn sign(a: f64, b: f64) -> f64 {
    if b >= 0.0 {
        a.abs()
    } else {
        -a.abs()
    }
}

/// Eigenvalues of the upper Hessenberg matrix `a[1..=n][1..=n]` (destroyed).
#[allow(clippy::many_single_char_names, clippy::needless_range_loop)]
fn hqr(a: &mut [Vec<f64>], n: usize) -> Option<(Vec<f64>, Vec<f64>)> {
    const MAX_ITS: usize = 200;
    let mut wr = vec![0.0; n + 1];
    let mut wi = vec![0.0; n + 1];
    let mut anorm = 0.0;
    for i in 1..=n {
        for j in (i.max(2) - 1)..=n {
            anorm += a[i][j].abs();
        }
    }
    let mut nn = n as isize;
    let mut t = 0.0;
    while nn >= 1 {
        let mut its = 0;
        loop {
            let nu = nn as usize;
            let mut l = nu;
            while l >= 2 {
                let mut s = a[l - 1][l - 1].abs() + a[l][l].abs();
                if s == 0.0 {
                    s = anorm;
                }
                if a[l][l - 1].abs() + s == s {
                    a[l][l - 1] = 0.0;
                    break;
                }
                l -= 1;
            }
            let mut x = a[nu][nu];
            if l == nu {
                wr[nu] = x + t;
                wi[nu] = 0.0;
                nn -= 1;
            } else {
                let mut y = a[nu - 1][nu - 1];
                let mut w = a[nu][nu - 1] * a[nu - 1][nu];
                if l == nu - 1 {
                    let p = 0.5 * (y - x);
                    let q = p * p + w;
                    let mut z = q.abs().sqrt();
                    x += t;
                    if q >= 0.0 {
                        z = p + sign(z, p);
                        wr[nu - 1] = x + z;
                        wr[nu] = x + z;
                        if z != 0.0 {
                            wr[nu] = x - w / z;
                        }
                        wi[nu - 1] = 0.0;
                        wi[nu] = 0.0;
                    } else {
                        wr[nu - 1] = x + p;
                        wr[nu] = x + p;
                        wi[nu - 1] = -z;
                        wi[nu] = z;
                    }
                    nn -= 2;
                } else {
                    if its == MAX_ITS {
                        return None;
                    }
                    if its % 10 == 0 && its > 0 {
                        // Exceptional shift.
                        t += x;
                        for i in 1..=nu {
                            a[i][i] -= x;
                        }
                        let s = a[nu][nu - 1].abs() + a[nu - 1][nu - 2].abs();
                        x = 0.75 * s;
                        y = x;
                        w = -0.4375 * s * s;
                    }
                    its += 1;
                    let (mut p, mut q, mut r, mut z);
                    let mut m = nu - 2;
                    loop {
                        z = a[m][m];
                        r = x - z;
                        let s0 = y - z;
                        p = (r * s0 - w) / a[m + 1][m] + a[m][m + 1];
                        q = a[m + 1][m + 1] - z - r - s0;
                        r = a[m + 2][m + 1];
                        let s = p.abs() + q.abs() + r.abs();
                        p /= s;
                        q /= s;
                        r /= s;
                        if m == l {
                            break;
                        }
                        let u = a[m][m - 1].abs() * (q.abs() + r.abs());
                        let v = p.abs() * (a[m - 1][m - 1].abs() + z.abs() + a[m + 1][m + 1].abs());
                        if u + v == v {
                            break;
                        }
                        m -= 1;
                    }
                    for i in (m + 2)..=nu {
                        a[i][i - 2] = 0.0;
                        if i != m + 2 {
                            a[i][i - 3] = 0.0;
                        }
                    }
                    let mut k = m;
                    while k < nu {
                        if k != m {
                            p = a[k][k - 1];
                            q = a[k + 1][k - 1];
                            r = 0.0;
                            if k != nu - 1 {
                                r = a[k + 2][k - 1];
                            }
                            x = p.abs() + q.abs() + r.abs();
                            if x != 0.0 {
                                p /= x;
                                q /= x;
                                r /= x;
                            }
                        }
                        let s = sign((p * p + q * q + r * r).sqrt(), p);
                        if s != 0.0 {
                            if k == m {
                                if l != m {
                                    a[k][k - 1] = -a[k][k - 1];
                                }
                            } else {
                                a[k][k - 1] = -s * x;
                            }
                            p += s;
                            x = p / s;
                            y = q / s;
                            z = r / s;
                            q /= p;
                            r /= p;
                            for j in k..=nu {
                                let mut pp = a[k][j] + q * a[k + 1][j];
                                if k != nu - 1 {
                                    pp += r * a[k + 2][j];
                                    a[k + 2][j] -= pp * z;
                                }
                                a[k + 1][j] -= pp * y;
                                a[k][j] -= pp * x;
                            }
                            let mmin = nu.min(k + 3);
                            for i in l..=mmin {
                                let mut pp = x * a[i][k] + y * a[i][k + 1];
                                if k != nu - 1 {
                                    pp += z * a[i][k + 2];
                                    a[i][k + 2] -= pp * r;
                                }
                                a[i][k + 1] -= pp * q;
                                a[i][k] -= pp;
                            }
                        }
                        k += 1;
                    }
                }
            }
            if nn < 1 || l as isize >= nn - 1 {
                break;
            }
        }
    }
    Some((wr, wi))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Symmetric matrices: agree with nalgebra's symmetric eigensolver.
    /// A companion matrix: the roots of its polynomial, including a complex pair.
    #[test]
    fn eigenvalues_of_known_matrices() {
        let n = 12;
        let s = DMatrix::from_fn(n, n, |i, j| (((i * 7 + j * 7 + i * j) % 13) as f64) - 6.0);
        let mut expect: Vec<f64> = s
            .clone()
            .symmetric_eigen()
            .eigenvalues
            .iter()
            .copied()
            .collect();
        expect.sort_by(|a, b| b.abs().total_cmp(&a.abs()));
        let got = eigenvalues(&s).unwrap();
        for (g, e) in got.iter().zip(&expect) {
            assert!((g.re - e).abs() < 1e-10 && g.im.abs() < 1e-10, "{g} vs {e}");
        }
        // (x − 3)(x − 2)(x² + 1) = x⁴ − 5x³ + 7x² − 5x + 6.
        let c = DMatrix::from_row_slice(
            4,
            4,
            &[
                5.0, -7.0, 5.0, -6.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0,
            ],
        );
        let got = eigenvalues(&c).unwrap();
        let want = [Complex::new(3.0, 0.0), Complex::new(2.0, 0.0)];
        assert!((got[0] - want[0]).norm() < 1e-12 && (got[1] - want[1]).norm() < 1e-12);
        assert!((got[2].re.abs() + (got[2].im.abs() - 1.0).abs()) < 1e-12);
        assert!((got[3] - got[2].conj()).norm() < 1e-12);
    }
}
