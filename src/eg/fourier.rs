//! [`FourierRule`]: an EG step (docs/math/eg.md §5, §6) with rule (7) factored
//! through the discrete Fourier transform over the sectors — the same linear
//! map as the dense sum of the `step` module, in about half the operations.
//!
//! Rule (7) is a cyclic correlation over the sectors: per inner node `o = hk`
//! and node `i = ij`, `y_s = Σ_r a^r x_{s+r}` with `x = d − c0`, `y = d̃ − c0`
//! and `a^r = a_ij^{r,hk}`. With `θ = 2π/n`, `X_f = Σ_s x_s e^{−iθfs}` and
//! `Â_f = Σ_r a^r e^{iθfr} = C_f + i S_f`, it is `Y_f = Â_f X_f`, and since
//! everything is real only `f = 0..=⌊n/2⌋` are needed:
//!
//! - `Xc_f = Σ_s x_s cos θfs`, `Xs_f = Σ_s x_s sin θfs` (pairs `s`, `n − s`
//!   share one product);
//! - `U_f = Σ_i C_f Xc_f + S_f Xs_f`, `V_f = Σ_i C_f Xs_f − S_f Xc_f`;
//! - `y_s = U_0 + Σ_{0<f<n/2} (U_f cos θfs + V_f sin θfs) + [n even] U_{n/2} (−1)^s`,
//!
//! with `C_f`, `S_f` scaled by `1/n` (`f = 0`, `n/2`) or `2/n` (between) when
//! the rule is built. Per step that is `12·(n + …)` point operations for the
//! transforms and `72·(2n − 1)` (odd n) for the products, against `72n²` for
//! the dense sum: 666 → ~520 point terms at n = 3, 1,830 → ~1,000 at n = 5
//! (`benches/eg_vs_cc.rs`; docs/benchmarks.md, "EG against Catmull-Clark").
//!
//! The outer nodes (§5) are convex combinations of 9 old nodes, with the
//! three sectors a stencil reads picked once per sector and the stencils
//! unrolled into constants.
//!
//! Memory: the `72n` transformed weights live in the rule, in arrays sized
//! for [`MAX_VALENCE`] (864 scalars, and 72 roots: 3,840 B for `f32`,
//! 7,584 B for `f64`), built once per table and shared by every cap of that
//! valence; the dense [`EgSubdivision::step`] needs none, so small firmware
//! keeps using it.
//!
//! [`EgSubdivision::step`]: super::EgSubdivision::step

use super::layout::{Term, REGULAR};
use super::net::{DNet, DSector};
use super::rule::{InnerNode, RuleTable, WEIGHT_SCALE};
use super::tables::Row;
use super::MAX_VALENCE;
use crate::error::Error;
use crate::point::Point3;
use crate::real::Real;
use crate::trig::RootsOfUnity;

/// Frequencies `0..=⌊n/2⌋` for every valence up to [`MAX_VALENCE`].
const FREQS: usize = MAX_VALENCE / 2 + 1;

/// The six outer new nodes `i' + 4j'` (`i' = 0` or `j' = 0`) and their §5
/// stencils (regular index `I = i' + 2`, `J = j' + 2`).
const OUTER: [usize; 6] = [0, 1, 2, 3, 4, 8];

const fn outer_terms() -> [[Term; 9]; 6] {
    let mut t = [REGULAR[0][0]; 6];
    let mut k = 0;
    while k < 6 {
        let node = OUTER[k];
        t[k] = REGULAR[node % 4 + 2][node / 4 + 2];
        // The outer stencils read sectors s − 1 ..= s + 1, never the center,
        // with 9 nonzero weights each.
        let mut j = 0;
        while j < 9 {
            let term = t[k][j];
            assert!(term.ds >= -1 && term.ds <= 1 && term.node < 12 && term.w != 0);
            j += 1;
        }
        k += 1;
    }
    t
}

/// The §5 stencils of [`OUTER`], checked at compile time.
const OUTER_TERMS: [[Term; 9]; 6] = outer_terms();

/// Rule (7) of one [`RuleTable`] in the Fourier basis over the sectors (see
/// the module documentation), for [`EgSubdivision::step_fourier`]. Build it
/// once per table and valence; it borrows nothing but the table.
///
/// [`EgSubdivision::step_fourier`]: super::EgSubdivision::step_fourier
#[derive(Clone, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct FourierRule<'t, R> {
    table: RuleTable<'t>,
    valence: usize,
    /// `cos[f][o][i] = w_f Σ_r a_i^{r,o} cos θfr` (`o` in [`InnerNode::ALL`]
    /// order, `i` the node index `i + 4j`), `w_f` = `1/n` or `2/n`.
    cos: [[[R; 12]; 6]; FREQS],
    /// `sin[f][o][i] = w_f Σ_r a_i^{r,o} sin θfr` for `0 < f < n/2`.
    sin: [[[R; 12]; 6]; FREQS],
    /// `(cos, sin) θfs` for `f, s ≤ n/2`.
    roots: [[[R; 2]; FREQS]; FREQS],
}

impl<'t, R: Real> FourierRule<'t, R> {
    /// The transformed rule of `table` (a table [`RuleTable::new`] accepted,
    /// or [`RuleTable::builtin`]). Errors: [`Error::TableShape`] when a row is
    /// missing; the valence errors of the roots of unity (none for `3..=10`).
    pub fn new(table: &RuleTable<'t>) -> Result<Self, Error> {
        Self::from_rows(table, table.valence(), |node, r| table.row(node, r))
    }

    /// The transformed rule of valence `n` whose expanded rows (§6) `row`
    /// gives; `table` is kept for the dense fallback.
    fn from_rows(
        table: &RuleTable<'t>,
        n: usize,
        row: impl Fn(InnerNode, usize) -> Option<Row>,
    ) -> Result<Self, Error> {
        let ring = RootsOfUnity::<R, MAX_VALENCE>::new(n)?;
        let mut rule = FourierRule {
            table: *table,
            valence: n,
            cos: [[[R::ZERO; 12]; 6]; FREQS],
            sin: [[[R::ZERO; 12]; 6]; FREQS],
            roots: [[[R::ZERO; 2]; FREQS]; FREQS],
        };
        let half = n / 2;
        for (f, row) in rule.roots.iter_mut().enumerate().take(half + 1) {
            for (s, root) in row.iter_mut().enumerate().take(half + 1) {
                *root = ring.get(f * s);
            }
        }
        for (o, node) in InnerNode::ALL.into_iter().enumerate() {
            for r in 0..n {
                let row = row(node, r)
                    .ok_or(Error::TableShape)?
                    .map(|a| R::ratio(a, WEIGHT_SCALE));
                for f in 0..=half {
                    let [c, s] = ring.get(f * r);
                    for (w, a) in rule.cos_mut(f, o)?.iter_mut().zip(row) {
                        *w += a * c;
                    }
                    if 2 * f != n && f != 0 {
                        for (w, a) in rule.sin_mut(f, o)?.iter_mut().zip(row) {
                            *w += a * s;
                        }
                    }
                }
            }
        }
        for f in 0..=half {
            let scale = if f == 0 || 2 * f == n {
                R::ratio(1, n as i32)
            } else {
                R::ratio(2, n as i32)
            };
            for o in 0..6 {
                for w in rule.cos_mut(f, o)?.iter_mut() {
                    *w *= scale;
                }
                for w in rule.sin_mut(f, o)?.iter_mut() {
                    *w *= scale;
                }
            }
        }
        Ok(rule)
    }

    /// The table this rule was built from (the one a step applies).
    #[inline]
    pub fn table(&self) -> &RuleTable<'t> {
        &self.table
    }

    /// The valence.
    #[inline]
    pub fn valence(&self) -> usize {
        self.valence
    }

    fn cos_mut(&mut self, f: usize, o: usize) -> Result<&mut [R; 12], Error> {
        self.cos
            .get_mut(f)
            .and_then(|c| c.get_mut(o))
            .ok_or(Error::OutOfDomain)
    }

    fn sin_mut(&mut self, f: usize, o: usize) -> Result<&mut [R; 12], Error> {
        self.sin
            .get_mut(f)
            .and_then(|c| c.get_mut(o))
            .ok_or(Error::OutOfDomain)
    }

    /// One step from `old` into `out` (resized to `old`'s valence, `c0`
    /// copied). [`Error::TableShape`] when the valences differ, before
    /// anything is written. No overflow check: the caller's
    /// (`cannot_overflow`, as for the dense step).
    pub(crate) fn step_into(&self, old: &DNet<R>, out: &mut DNet<R>) -> Result<(), Error> {
        let n = old.valence();
        if n != self.valence() || !(3..=MAX_VALENCE).contains(&n) {
            return Err(Error::TableShape);
        }
        let c0 = old.c0;
        out.c0 = c0;
        out.sectors.clear();
        for _ in 0..n {
            out.sectors
                .push([c0; 12])
                .map_err(|_| Error::ValenceUnsupported { valence: n })?;
        }
        self.outer_nodes(&old.sectors, &mut out.sectors);
        self.inner_nodes(&old.sectors, c0, &mut out.sectors);
        Ok(())
    }

    /// The outer nodes of every sector: `Σ w d` over the §5 stencil (weights
    /// `w/256 ≥ 0`, exact in binary, summing to 1: a convex combination, as
    /// accurate as the dense step's `c0 + Σ w (d − c0)`, 9 × 3 subtractions
    /// cheaper).
    fn outer_nodes(&self, old: &[DSector<R>], out: &mut [DSector<R>]) {
        let n = old.len();
        for (s, new) in out.iter_mut().enumerate() {
            let prev = if s == 0 { n - 1 } else { s - 1 };
            let next = if s + 1 == n { 0 } else { s + 1 };
            let (Some(a), Some(b), Some(c)) = (old.get(prev), old.get(s), old.get(next)) else {
                return;
            };
            let around = [a, b, c];
            // Constant stencils: the loops unroll, the taps fold into
            // addresses and the weights `w/256` into constants.
            for (&k, terms) in OUTER.iter().zip(&OUTER_TERMS) {
                let mut acc = Point3::ZERO;
                for t in terms {
                    let sec = around.get(usize::from(t.ds.wrapping_add(1) as u8));
                    if let Some(p) = sec.and_then(|sec| sec.get(usize::from(t.node))) {
                        acc += *p * R::ratio(i32::from(t.w), 256);
                    }
                }
                if let Some(q) = new.get_mut(k) {
                    *q = acc;
                }
            }
        }
    }

    /// The inner nodes of every sector by rule (7) through the transform.
    fn inner_nodes(&self, old: &[DSector<R>], c0: Point3<R>, out: &mut [DSector<R>]) {
        let n = old.len();
        let half = n / 2;
        // Pairs (s, n − s) for 0 < s < n/2; for even n, s = n/2 alone.
        let pairs = (n - 1) / 2;
        let x = |s: usize, i: usize| -> Point3<R> {
            old.get(s)
                .and_then(|sec| sec.get(i))
                .map_or(Point3::ZERO, |d| *d - c0)
        };
        // Forward transform of each node index i: xc[f][i], xs[f][i].
        let mut xc = [[Point3::ZERO; 12]; FREQS];
        let mut xs = [[Point3::ZERO; 12]; FREQS];
        for i in 0..12 {
            let x0 = x(0, i);
            let mut p = [Point3::ZERO; FREQS];
            let mut m = [Point3::ZERO; FREQS];
            for s in 1..=pairs {
                let (a, b) = (x(s, i), x(n - s, i));
                if let (Some(ps), Some(ms)) = (p.get_mut(s), m.get_mut(s)) {
                    *ps = a + b;
                    *ms = a - b;
                }
            }
            let mid = if n.is_multiple_of(2) {
                x(half, i)
            } else {
                Point3::ZERO
            };
            for (f, roots) in self.roots.iter().enumerate().take(half + 1) {
                let mut c = x0;
                let mut sn = Point3::ZERO;
                for s in 1..=pairs {
                    if let (Some(ps), Some(ms), Some(&[cs, ss])) =
                        (p.get(s), m.get(s), roots.get(s))
                    {
                        c += *ps * cs;
                        sn += *ms * ss;
                    }
                }
                if n.is_multiple_of(2) {
                    if f % 2 == 0 {
                        c += mid;
                    } else {
                        c = c - mid;
                    }
                }
                if let (Some(cf), Some(sf)) = (xc.get_mut(f), xs.get_mut(f)) {
                    if let (Some(ci), Some(si)) = (cf.get_mut(i), sf.get_mut(i)) {
                        *ci = c;
                        *si = sn;
                    }
                }
            }
        }
        // Products and inverse transform, one inner node at a time.
        for (o, node) in InnerNode::ALL.into_iter().enumerate() {
            let mut u = [Point3::ZERO; FREQS];
            let mut v = [Point3::ZERO; FREQS];
            for f in 0..=half {
                let (Some(cw), Some(sw), Some(c), Some(sx)) = (
                    self.cos.get(f).and_then(|w| w.get(o)),
                    self.sin.get(f).and_then(|w| w.get(o)),
                    xc.get(f),
                    xs.get(f),
                ) else {
                    continue;
                };
                let mut uf = Point3::ZERO;
                let mut vf = Point3::ZERO;
                if f == 0 || 2 * f == n {
                    for (w, p) in cw.iter().zip(c) {
                        uf += *p * *w;
                    }
                } else {
                    for (((wc, ws), pc), ps) in cw.iter().zip(sw).zip(c).zip(sx) {
                        uf += *pc * *wc + *ps * *ws;
                        vf += *ps * *wc - *pc * *ws;
                    }
                }
                if let (Some(uo), Some(vo)) = (u.get_mut(f), v.get_mut(f)) {
                    *uo = uf;
                    *vo = vf;
                }
            }
            let k = node.index();
            let mut put = |s: usize, y: Point3<R>| {
                if let Some(q) = out.get_mut(s).and_then(|sec| sec.get_mut(k)) {
                    *q = c0 + y;
                }
            };
            for s in 0..=half {
                let mut a = Point3::ZERO;
                let mut b = Point3::ZERO;
                for (f, (uf, vf)) in u.iter().zip(&v).enumerate().take(half + 1) {
                    let Some(&[cs, ss]) = self.roots.get(f).and_then(|r| r.get(s)) else {
                        continue;
                    };
                    a += *uf * cs;
                    if f != 0 && 2 * f != n {
                        b += *vf * ss;
                    }
                }
                if s == 0 || 2 * s == n {
                    // sin θfs = 0 here.
                    put(s, a);
                } else {
                    put(s, a + b);
                    put(n - s, a - b);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::step::{step_into, Rule};
    use super::*;

    fn next(seed: &mut u64) -> f64 {
        *seed ^= *seed << 13;
        *seed ^= *seed >> 7;
        *seed ^= *seed << 17;
        (*seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }

    fn net(n: usize, seed: &mut u64) -> DNet<f64> {
        let mut sectors = heapless::Vec::new();
        for _ in 0..n {
            let sec = core::array::from_fn(|_| {
                Point3([next(seed) * 5.0, next(seed) * 5.0, next(seed) * 5.0])
            });
            let _ = sectors.push(sec);
        }
        DNet {
            c0: Point3([next(seed), next(seed), next(seed)]),
            sectors,
        }
    }

    /// Every valence 3..=10 (even ones included, which no built-in table
    /// has): the transform path equals the literal rule (7) sum
    /// `c0 + Σ_r Σ_i a_i^{r,o}/10⁵ (d_i^{s+r} − c0)` for arbitrary integer
    /// rows. Tolerance: |a| < 10⁵ over 12n terms of |d − c0| ≤ 12, so the
    /// sums stay below ~1.5·10³; the transform adds a few roundings of that
    /// size per term (≤ 2·10⁻¹³ with 10× margin): 1e-11.
    #[test]
    fn transform_equals_the_literal_sum_for_every_valence() {
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let table = RuleTable::builtin(3).unwrap();
        let cases = if cfg!(miri) { 1 } else { 8 };
        for n in 3..=MAX_VALENCE {
            for _ in 0..cases {
                let mut rows = [[[0i32; 12]; MAX_VALENCE]; 6];
                for w in rows.iter_mut().flatten().flatten() {
                    *w = (next(&mut seed) * 99_999.0) as i32;
                }
                let row = |node: InnerNode, r: usize| {
                    let o = InnerNode::ALL.iter().position(|&x| x == node)?;
                    rows.get(o)?.get(r).copied()
                };
                let rule = FourierRule::<f64>::from_rows(&table, n, row).unwrap();
                let old = net(n, &mut seed);
                let mut out = old.clone();
                rule.step_into(&old, &mut out).unwrap();
                for (o, node) in InnerNode::ALL.into_iter().enumerate() {
                    for s in 0..n {
                        let mut want = Point3::ZERO;
                        for (r, row) in rows[o].iter().enumerate().take(n) {
                            let src = &old.sectors[(s + r) % n];
                            for (d, a) in src.iter().zip(row) {
                                want += (*d - old.c0) * (f64::from(*a) / 1e5);
                            }
                        }
                        let got = out.sectors[s][node.index()] - old.c0;
                        assert!(
                            got.max_abs_diff(want) < 1e-11,
                            "n={n} s={s} {node:?}: {:e}",
                            got.max_abs_diff(want)
                        );
                    }
                }
            }
        }
    }

    /// With the built-in tables the step equals the dense one within 4e-15
    /// of the net's size (the dense sums' rounding and the transform's, each
    /// ~61 terms of weight ≤ 0.6; the outer nodes' 9 terms far less).
    #[test]
    fn step_equals_the_dense_step() {
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        for n in [3, 5] {
            let table = RuleTable::builtin(n).unwrap();
            let rule = FourierRule::<f64>::new(&table).unwrap();
            for _ in 0..if cfg!(miri) { 1 } else { 20 } {
                let old = net(n, &mut seed);
                let (mut fast, mut dense) = (old.clone(), old.clone());
                rule.step_into(&old, &mut fast).unwrap();
                step_into(&old, Rule::Eg(&table), &mut dense).unwrap();
                for (a, b) in fast.sectors.iter().zip(&dense.sectors) {
                    for k in OUTER {
                        assert!(a[k].max_abs_diff(b[k]) < 4e-15 * 5.0);
                    }
                    for node in InnerNode::ALL {
                        let k = node.index();
                        assert!(
                            a[k].max_abs_diff(b[k]) < 4e-15 * 5.0,
                            "{:e}",
                            a[k].max_abs_diff(b[k])
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn refuses_another_valence() {
        let rule = FourierRule::<f32>::new(&RuleTable::builtin(5).unwrap()).unwrap();
        let mut seed = 1u64;
        let old = net(3, &mut seed);
        let old = DNet {
            c0: Point3(old.c0.0.map(|c| c as f32)),
            sectors: old
                .sectors
                .iter()
                .map(|s| s.map(|p| Point3(p.0.map(|c| c as f32))))
                .collect(),
        };
        let mut out = old.clone();
        assert_eq!(rule.step_into(&old, &mut out), Err(Error::TableShape));
        assert_eq!(out, old);
    }
}
