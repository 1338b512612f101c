//! EG (Evolving Guide) subdivision reference, assembled straight from spec
//! `docs/math/eg.md` §1–§7, independent of the kernel: the degree raising `R`
//! (c-net → d-net, §3), the limit-point formulas (3) and (4) (§4), and the
//! dense `(12n+1)²` subdivision matrix `A_n` (§5–§7) with its spectrum.
//!
//! Indexing. c-net (`6n+1`): sector `s` node `(x, y)` in the order
//! `(1,0) (2,0) (1,1) (2,1) (1,2) (2,2)` at `6s + k`, the center `e` last.
//! d-net (`12n+1`): sector `s` node `d_ij` (`i = 0..3`, `j = 0..2`) at
//! `12s + i + 4j` (the paper's order `00 10 20 30 01 11 …`), `c0` last.

use nalgebra::{Complex, DMatrix, DVector};

/// One EG rule table (docs/math/eg.md §7): the integer weights (÷10⁵) of the inner new
/// nodes, one row of 12 per sector offset `r`, columns `00 10 20 30 01 11 21
/// 31 02 12 22 32`. `a11`, `a22`: rows `r = 0..=⌊n/2⌋`; `a21`: `r = 0..n`;
/// `a31`, `a32`: `r = 0..=⌊(n+1)/2⌋`.
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    /// `A_11`.
    pub a11: Vec<[i64; 12]>,
    /// `A_22`.
    pub a22: Vec<[i64; 12]>,
    /// `A_21`.
    pub a21: Vec<[i64; 12]>,
    /// `A_31`.
    pub a31: Vec<[i64; 12]>,
    /// `A_32`.
    pub a32: Vec<[i64; 12]>,
}

/// The spec's table for `n = 3` (§7).
pub fn table3() -> Table {
    Table {
        a11: vec![
            [
                -1, -13, -37, 42, -13, 1671, 10243, 2049, -37, 10243, 50096, 5073,
            ],
            [0, 0, 38, 35, -4, 20, -169, -859, -77, -272, -1886, -2793],
        ],
        a22: vec![
            [0, 6, -49, -96, 6, -87, 2309, 1776, -49, 2309, 15760, 6979],
            [0, 0, 87, 57, -11, 39, -330, -1928, -58, -793, -3253, -5925],
        ],
        a21: vec![
            [0, -10, 2, 1, -5, 153, 8101, 7372, -173, 2036, 32183, 20229],
            [0, 3, 46, -11, -7, -3, 98, -966, -118, 328, 1736, -2329],
            [0, -8, -3, -128, 0, 16, -709, 307, 55, -198, -2703, 4434],
        ],
        a31: vec![
            [0, -3, 0, 76, 16, -125, 3642, 9873, 79, -370, 4902, 23927],
            [0, 16, 79, 79, -3, -125, -370, -1761, 0, 3642, 4902, -6789],
            [
                0, -7, 113, 79, -7, 80, -1088, -1761, 113, -1088, -6828, -6789,
            ],
        ],
        a32: vec![
            [0, -3, -30, 63, 9, -28, 792, 2658, 14, -402, 341, 7126],
            [0, 9, 14, 44, -3, -28, -402, -1866, -30, 792, 341, -6175],
            [0, -4, 63, 44, -4, 62, -1112, -1866, 63, -1112, -6536, -6175],
        ],
    }
}

/// The spec's table for `n = 5` (§7; A21 row 4, column 01 is −59).
pub fn table5() -> Table {
    Table {
        a11: vec![
            [
                -129, 221, 50, -28, 221, 2629, 6368, 2877, 50, 6368, 61638, 6916,
            ],
            [-26, 68, -27, 2, 36, -65, -111, -16, 2, -177, -10, -388],
            [28, -41, -27, 21, -57, -73, 278, -17, 4, 306, -692, -676],
        ],
        a22: vec![
            [
                -491, 973, 57, -205, 973, -322, -4931, 1147, 57, -4931, 41825, 11869,
            ],
            [
                -74, 217, -103, 27, 68, -164, -225, -200, 76, -94, 2039, -3059,
            ],
            [
                165, -264, -112, 114, -332, -210, 1422, -150, 34, 1591, -5064, -3801,
            ],
        ],
        a21: vec![
            [
                -256, 482, 14, -132, 582, -379, 5085, 5035, 70, -3009, 48736, 23656,
            ],
            [
                -143, 317, -74, -16, 243, -143, -857, -44, -67, 434, 5702, -564,
            ],
            [
                89, -140, -48, 53, -195, -107, 773, -48, 67, 874, -2602, -1630,
            ],
            [
                57, -96, -42, 35, -83, -172, 625, -107, -74, 552, -1421, -2015,
            ],
            [
                49, -135, 104, -135, -59, -88, 456, 957, -37, 538, -1701, 3402,
            ],
        ],
        a31: vec![
            [
                -269, 492, -13, -197, 541, -115, -84, 9355, -192, -1203, 16754, 43563,
            ],
            [
                -269, 541, -192, -10, 492, -115, -1203, -313, -13, -84, 16754, 641,
            ],
            [
                103, -154, -54, 62, -243, -113, 944, -117, 118, 951, -2635, -2601,
            ],
            [
                79, -125, -80, 62, -125, -219, 800, -117, -80, 800, -2081, -2601,
            ],
        ],
        a32: vec![
            [
                -433, 772, -48, -208, 910, -235, -3106, 1327, -264, -2342, 12285, 25197,
            ],
            [
                -433, 910, -264, -41, 772, -235, -2342, -207, -48, -3106, 12285, -542,
            ],
            [
                220, -354, -73, 125, -509, -69, 1859, -299, 263, 1600, -6314, -5478,
            ],
            [
                169, -285, -124, 125, -285, -260, 1544, -299, -124, 1544, -5418, -5478,
            ],
        ],
    }
}

/// The built-in table for `n`, if the spec has one (n = 3, 5).
pub fn builtin_table(n: usize) -> Option<Table> {
    match n {
        3 => Some(table3()),
        5 => Some(table5()),
        _ => None,
    }
}

/// Column of `d_ij` within a sector row of a table, `i + 4j`.
fn col(i: usize, j: usize) -> usize {
    i + 4 * j
}

/// The weight `a_ij^{r,hk}` (integer, ×10⁵) for any `r` (mod n), filling the
/// unlisted rows by the symmetries of §6. `hk` ∈ {11, 21, 12, 22, 31, 32}.
pub fn weight(t: &Table, n: usize, hk: (usize, usize), r: isize, i: usize, j: usize) -> i64 {
    let m = |r: isize| r.rem_euclid(n as isize) as usize;
    let listed =
        |rows: &Vec<[i64; 12]>, r: usize, i: usize, j: usize| rows.get(r).map(|row| row[col(i, j)]);
    // Rows of the tables for hk ∈ {11, 22, 21} (12 via the 12 ↔ 21 symmetry).
    let diag_like = |hk: (usize, usize), r: isize, i: usize, j: usize| -> i64 {
        let rows = match hk {
            (1, 1) => &t.a11,
            (2, 2) => &t.a22,
            (2, 1) => &t.a21,
            _ => unreachable!(),
        };
        if let Some(w) = listed(rows, m(r), i, j) {
            return w;
        }
        // a_ij^{r,hk} = a_ji^{−r,kh} (i, j ≤ 2); a_3j^{r,hk} = a_3j^{−r−1,kh}; here kh = hk.
        let w = if i == 3 {
            listed(rows, m(-r - 1), i, j)
        } else {
            listed(rows, m(-r), j, i)
        };
        w.expect("the symmetric row is listed")
    };
    match hk {
        (1, 1) | (2, 2) | (2, 1) => diag_like(hk, r, i, j),
        (1, 2) => {
            if i == 3 {
                diag_like((2, 1), -r - 1, i, j)
            } else {
                diag_like((2, 1), -r, j, i)
            }
        }
        (3, k) => {
            let rows = if k == 1 { &t.a31 } else { &t.a32 };
            if let Some(w) = listed(rows, m(r), i, j) {
                return w;
            }
            // a_ij^{r,3k} = a_ji^{1−r,3k} (i, j ≤ 2); a_3j^{r,3k} = a_3j^{−r,3k}.
            let w = if i == 3 {
                listed(rows, m(-r), i, j)
            } else {
                listed(rows, m(1 - r), j, i)
            };
            w.expect("the symmetric row is listed")
        }
        _ => panic!("no EG rule for node {hk:?}"),
    }
}

/// A d-node position in doubled c-units `(X, Y) = (2x, 2y)` of sector `s`,
/// re-expressed in the sector that owns it (`X ≥ 0`, `Y ≥ 1`, §2); returns
/// `(sector, i, j)` with `i = 3 − X`, `j = 3 − Y`.
pub fn d_owner(n: usize, s: isize, x2: i64, y2: i64) -> (usize, usize, usize) {
    let (mut s, mut x, mut y) = (s, x2, y2);
    loop {
        if y <= 0 {
            (s, x, y) = (s - 1, -y, x);
        } else if x < 0 {
            (s, x, y) = (s + 1, y, -x);
        } else {
            break;
        }
    }
    assert!(
        x <= 3 && y <= 3,
        "d-node ({x}, {y}) outside the 12 of a sector"
    );
    (
        s.rem_euclid(n as isize) as usize,
        (3 - x) as usize,
        (3 - y) as usize,
    )
}

/// A c-net point `(x, y)` of sector `s` as a c-net index (§1): re-expressed
/// until owned (`x ≥ 1`, `y ≥ 0`); `(0, 0)` is the center `e` (index `6n`).
pub fn c_index(n: usize, s: isize, x: i64, y: i64) -> usize {
    if x == 0 && y == 0 {
        return 6 * n;
    }
    let (mut s, mut x, mut y) = (s, x, y);
    loop {
        if y < 0 {
            (s, x, y) = (s - 1, -y, x);
        } else if x <= 0 {
            (s, x, y) = (s + 1, y, -x);
        } else {
            break;
        }
    }
    let k = match (x, y) {
        (1, 0) => 0,
        (2, 0) => 1,
        (1, 1) => 2,
        (2, 1) => 3,
        (1, 2) => 4,
        (2, 2) => 5,
        _ => panic!("c-node ({x}, {y}) outside the 6 of a sector"),
    };
    6 * s.rem_euclid(n as isize) as usize + k
}

/// Index of `d_ij` of sector `s` in the d-net vector.
pub fn d_index(s: usize, i: usize, j: usize) -> usize {
    12 * s + col(i, j)
}

/// Degree raising `R` (§3), `12n × (6n+1)`: per direction, a d-node at
/// `u = k + ½` takes `(c_k + c_{k+1})/2`, at `u = k` takes
/// `(c_{k−1} + 10 c_k + c_{k+1})/12`; tensor product.
pub fn degree_raising(n: usize) -> DMatrix<f64> {
    // Univariate stencil at doubled coordinate U: list of (c coordinate, weight).
    let stencil = |u2: i64| -> Vec<(i64, f64)> {
        if u2 % 2 != 0 {
            let k = (u2 - 1) / 2;
            vec![(k, 0.5), (k + 1, 0.5)]
        } else {
            let k = u2 / 2;
            vec![(k - 1, 1.0 / 12.0), (k, 10.0 / 12.0), (k + 1, 1.0 / 12.0)]
        }
    };
    let mut r = DMatrix::zeros(12 * n, 6 * n + 1);
    for s in 0..n {
        for j in 0..3 {
            for i in 0..4 {
                let (x2, y2) = (3 - i as i64, 3 - j as i64);
                for (cx, wx) in stencil(x2) {
                    for &(cy, wy) in &stencil(y2) {
                        r[(d_index(s, i, j), c_index(n, s as isize, cx, cy))] += wx * wy;
                    }
                }
            }
        }
    }
    r
}

/// Weights of the c-net formula (3) for `c0`, a row over the `6n+1` c-nodes.
pub fn c0_from_cnet_weights(n: usize) -> DVector<f64> {
    let nf = n as f64;
    let (we, w10, w11) = if n == 3 {
        (11.0 / 32.0, 1.0 / 6.0, 5.0 / 96.0)
    } else {
        (
            nf / (nf + 5.0),
            4.0 / (nf * (nf + 5.0)),
            1.0 / (nf * (nf + 5.0)),
        )
    };
    let mut w = DVector::zeros(6 * n + 1);
    w[6 * n] = we;
    for s in 0..n {
        w[c_index(n, s as isize, 1, 0)] += w10;
        w[c_index(n, s as isize, 1, 1)] += w11;
    }
    w
}

/// Weights of the d-net formula (4) for `c0`, a row over the `12n` d-nodes:
/// `e_ij / γ_n`, the same in every sector.
pub fn c0_from_dnet_weights(n: usize) -> DVector<f64> {
    let nf = n as f64;
    let mut e = [[0.0f64; 3]; 4]; // e[i][j]
    let gamma;
    if n == 3 {
        gamma = 93120.0;
        let (e00, e20, e22, e32) = (11.0, -73.0, 10643.0, 19062.0);
        e[0][0] = e00;
        e[1][0] = -6.0 * e00;
        e[0][1] = -6.0 * e00;
        e[1][1] = 36.0 * e00;
        e[2][0] = e20;
        e[0][2] = e20;
        e[2][1] = -6.0 * e20;
        e[1][2] = -6.0 * e20;
        e[2][2] = e22;
        e[3][0] = e[1][0];
        e[3][1] = e[1][1];
        e[3][2] = e32;
    } else {
        gamma = 178480.0 * nf * (nf + 5.0);
        let e00 = 2587.0 * nf - 8377.0;
        let e20 = 19339.0 * nf - 53929.0;
        let e30 = 336.0 * (153.0 * nf - 448.0);
        e[0][0] = e00;
        e[1][0] = -6.0 * e00;
        e[0][1] = -6.0 * e00;
        e[1][1] = 36.0 * e00;
        e[2][0] = e20;
        e[0][2] = e20;
        e[2][1] = -6.0 * e20;
        e[1][2] = -6.0 * e20;
        e[2][2] = 157051.0 * nf + 50279.0;
        e[3][0] = e30;
        e[3][1] = -6.0 * e30;
        e[3][2] = 48.0 * (8483.0 * nf - 5008.0);
    }
    let mut w = DVector::zeros(12 * n);
    for s in 0..n {
        for (i, ei) in e.iter().enumerate() {
            for (j, &eij) in ei.iter().enumerate() {
                w[d_index(s, i, j)] = eij / gamma;
            }
        }
    }
    w
}

/// Univariate regular bi-4 rule (§5): new regular index `I` → (old index, weight).
pub fn regular_rule(big_i: usize) -> Vec<(usize, f64)> {
    let shift = 2 * (big_i / 4);
    let w: &[(usize, f64)] = match big_i % 4 {
        0 => &[(0, 9.0), (1, 6.0), (2, 1.0)],
        1 => &[(0, 3.0), (1, 10.0), (2, 3.0)],
        2 => &[(0, 1.0), (1, 6.0), (2, 9.0)],
        _ => &[(1, 2.0), (2, 12.0), (3, 2.0)], // (1, 6, 1)/8 = (2, 12, 2)/16
    };
    w.iter().map(|&(k, v)| (k + shift, v / 16.0)).collect()
}

/// The EG subdivision matrix `A_n` (§5–§7), `(12n+1)²`, rows = new
/// `(d̃, c0)`, columns = old `(d, c0)`. `table`: the rule table for `n`
/// (`None`: the built-in one for n = 3, 5). `None` when there is no table.
pub fn matrix(n: usize, table: Option<&Table>) -> Option<DMatrix<f64>> {
    let builtin;
    let t = match table {
        Some(t) => t,
        None => {
            builtin = builtin_table(n)?;
            &builtin
        }
    };
    let dim = 12 * n + 1;
    let mut a = DMatrix::zeros(dim, dim);
    a[(12 * n, 12 * n)] = 1.0; // c0 is kept.
    for s in 0..n {
        for jn in 0..3 {
            for in_ in 0..4 {
                let row = d_index(s, in_, jn);
                if in_ == 0 || jn == 0 {
                    // §5: regular rule, new d̃_{i'j'} is regular (i'+2, j'+2).
                    for (k, wk) in regular_rule(in_ + 2) {
                        for &(l, wl) in &regular_rule(jn + 2) {
                            let (x2, y2) = (3 - k as i64, 3 - l as i64);
                            let (so, io, jo) = d_owner(n, s as isize, x2, y2);
                            a[(row, d_index(so, io, jo))] += wk * wl;
                        }
                    }
                } else {
                    // §6: EG rule, weights ÷ 10⁵, a0 = 1 − Σ a on c0.
                    let mut sum = 0.0;
                    for r in 0..n {
                        for j in 0..3 {
                            for i in 0..4 {
                                let w = weight(t, n, (in_, jn), r as isize, i, j) as f64 / 1e5;
                                a[(row, d_index((s + r) % n, i, j))] += w;
                                sum += w;
                            }
                        }
                    }
                    a[(row, 12 * n)] += 1.0 - sum;
                }
            }
        }
    }
    Some(a)
}

/// Eigenvalues of `A_n`, sorted by decreasing modulus (general real matrix:
/// Hessenberg + Francis QR, [`crate::eigen::eigenvalues`]).
pub fn eigenvalues(a: &DMatrix<f64>) -> Vec<Complex<f64>> {
    crate::eigen::eigenvalues(a).expect("QR iteration converges")
}

/// Catmull-Clark's subdominant eigenvalue
/// `λ_CC(n) = (5 + c(1/n) + cos(π/n) √(2(9 + c(1/n)))) / 16`, `c(t) = cos 2πt`.
pub fn lambda_cc(n: usize) -> f64 {
    let c = (std::f64::consts::TAU / n as f64).cos();
    (5.0 + c + (std::f64::consts::PI / n as f64).cos() * (2.0 * (9.0 + c)).sqrt()) / 16.0
}
