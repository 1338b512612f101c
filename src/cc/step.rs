//! One Catmull-Clark step of a cap's c-net (Catmull & Clark 1978).
//!
//! Rules, on the quad net around the center (every node but the center has
//! valence 4):
//! - face point: the average of the face's 4 corners;
//! - edge point: the average of the edge's 2 ends and its 2 faces' points;
//! - vertex point of a vertex of valence `k`:
//!   `(k−2)/k · v + 1/k² Σ edge neighbours + 1/k² Σ face points`
//!   (the paper's `Q/k + 2R/k + (k−3)S/k`); `k = n` at the center, 4 elsewhere.
//!
//! In the new grid (half the spacing) node `(X, Y)` of a sector is the
//! vertex point of old `(X/2, Y/2)` (both even), an edge point (one odd) or a
//! face point (both odd). A step computes, per sector, the new extended ring
//! `X ∈ 1..=3`, `Y ∈ 0..=3` ([`super::cap`]): every stencil reads only old
//! nodes with `x, y ≤ 2` (the old c-net), in sectors `s − 1 ..= s + 1`.

use super::cap::{node_of, CcCap, EXT_SECTOR};
use crate::error::Error;
use crate::point::Point3;
use crate::polar::index::put;
use crate::real::Real;

/// The old c-net, read in the frame of sector `s`.
struct Old<'a, R> {
    net: &'a [Point3<R>],
    e: Point3<R>,
    n: usize,
    s: usize,
}

impl<R: Real> Old<'_, R> {
    /// Old node `(x, y)` (the §1 change of frame included); `x, y ≤ 2` by
    /// construction of every stencil, so the fallback is never taken.
    #[inline]
    fn p(&self, x: i32, y: i32) -> Point3<R> {
        node_of(self.net, self.e, self.n, self.s, x, y, 2).unwrap_or(self.e)
    }

    /// Face point of the old face `[a, a+1] × [b, b+1]`.
    #[inline]
    fn face(&self, a: i32, b: i32) -> Point3<R> {
        (self.p(a, b) + self.p(a + 1, b) + self.p(a + 1, b + 1) + self.p(a, b + 1)) * R::ratio(1, 4)
    }

    /// New node `(x, y)` (new-grid units, `x ≥ 1`, `(x, y) ≠ (0, 0)`).
    fn new_node(&self, x: i32, y: i32) -> Point3<R> {
        let (a, b) = (x >> 1, y >> 1);
        match (x & 1, y & 1) {
            // Vertex point of old (a, b), valence 4: ½ v + (Σ 4 edge
            // neighbours + Σ 4 face points) / 16.
            (0, 0) => {
                let sum = self.p(a + 1, b)
                    + self.p(a, b + 1)
                    + self.p(a - 1, b)
                    + self.p(a, b - 1)
                    + self.face(a, b)
                    + self.face(a - 1, b)
                    + self.face(a - 1, b - 1)
                    + self.face(a, b - 1);
                self.p(a, b) * R::ratio(1, 2) + sum * R::ratio(1, 16)
            }
            // Edge point of the old edge (a, b)–(a+1, b): faces below and above.
            (1, 0) => {
                (self.p(a, b) + self.p(a + 1, b) + self.face(a, b - 1) + self.face(a, b))
                    * R::ratio(1, 4)
            }
            // Edge point of the old edge (a, b)–(a, b+1): faces left and right.
            (0, _) => {
                (self.p(a, b) + self.p(a, b + 1) + self.face(a - 1, b) + self.face(a, b))
                    * R::ratio(1, 4)
            }
            // Face point of the old face [a, a+1] × [b, b+1].
            _ => self.face(a, b),
        }
    }
}

impl<R: Real> CcCap<'_, R> {
    /// One Catmull-Clark step: the new extended ring of every sector (face,
    /// edge and vertex points of the old c-net, see the module doc) and the
    /// new center, by the vertex rule of valence `n`:
    /// `(n−2)/n e + 1/n² Σ_s (1,0)_s + 1/n² Σ_s f_s`, `f_s` the point of the
    /// face `[0,1]²` of sector `s`.
    ///
    /// The new net is written into the half of the storage the current one
    /// does not use, then adopted. [`Error::NonFinite`] if a coordinate
    /// overflows: the center, the current net and the level (the whole
    /// observable state) are then unchanged.
    pub fn step(&mut self) -> Result<(), Error> {
        let n = self.n;
        let len = n.saturating_mul(EXT_SECTOR);
        // `new` checked the storage length; the error only spares a panic path.
        let short = Error::CapacityExceeded {
            needed: Self::storage_len(n),
            capacity: self.storage.len(),
        };
        let (first, second) = self.storage.split_at_mut_checked(len).ok_or(short)?;
        let (cur, next): (&[Point3<R>], &mut [Point3<R>]) = if self.flip {
            (second, first)
        } else {
            (first, second)
        };
        let e = self.center;
        let mut center_sum = Point3::ZERO;
        let mut finite = true;
        for s in 0..n {
            let old = Old { net: cur, e, n, s };
            for y in 0..4 {
                for x in 1..4 {
                    let q = old.new_node(x, y);
                    finite &= q.is_finite();
                    put(next, s * EXT_SECTOR + (x as usize - 1) + 3 * y as usize, q);
                }
            }
            center_sum += old.p(1, 0) + old.face(0, 0);
        }
        let nf = n as f64;
        let center = e * R::from_f64((nf - 2.0) / nf) + center_sum * R::from_f64(1.0 / (nf * nf));
        if !finite || !center.is_finite() {
            return Err(Error::NonFinite);
        }
        self.center = center;
        self.flip = !self.flip;
        self.level = self.level.saturating_add(1);
        Ok(())
    }
}
