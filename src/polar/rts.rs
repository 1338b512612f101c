//! One RTS step (spec C2PS.md §3): the C²PS rules with the valence kept, no
//! periodic refinement (`q̃ = q`) and `τ = j/n`. In place, O(n).

use super::fourier::Fourier;
use super::index::{add_mod, at, put};
use super::net::PolarNet;
use crate::point::Point3;
use crate::real::Real;
use heapless::VecView;

impl<R: Real, const CAP: usize> PolarNet<R, CAP> {
    /// One RTS step. Valence and level are unchanged; the links held grow as
    /// for C²PS (old links up to `K` give new links up to `2K−1`, at most 5).
    pub fn rts_step(&mut self) {
        if self.held < 2 {
            return; // an empty net: nothing to refine
        }
        let new_held = self.held_after_step();
        let n = self.valence();
        let [l1, l2, l3, l4, l5] = &mut self.links;
        for (slot, l) in [&mut *l1, &mut *l2, &mut *l3, &mut *l4, &mut *l5]
            .into_iter()
            .enumerate()
        {
            if slot < new_held {
                // Cannot fail: n <= CAP already holds for link 1.
                let _ = l.resize(n, Point3::ZERO);
            }
        }
        rts_in_place(
            &mut self.pole,
            [
                l1.as_mut_view(),
                l2.as_mut_view(),
                l3.as_mut_view(),
                l4.as_mut_view(),
                l5.as_mut_view(),
            ],
            self.held,
            self.roots.as_slice(),
        );
        self.held = new_held;
    }
}

fn rts_in_place<R: Real>(
    pole: &mut Point3<R>,
    links: [&mut VecView<Point3<R>>; 5],
    held: usize,
    roots: &[[R; 2]],
) {
    let [l1, l2, l3, l4, l5] = links;
    let n = l1.len();
    let f = Fourier::of(l1, roots, 1);
    let q00 = *pole;
    let has3 = held >= 3 && l3.len() == n && l4.len() == n && l5.len() == n;
    if l2.len() != n || l3.len() != n {
        return;
    }
    let half = R::ratio(1, 2);
    let z = Point3::ZERO;
    let no_root = [R::ZERO; 2];
    for j in 0..n {
        let (q1, q2, q3) = (
            at(l1, j, z),
            at(l2, j, z),
            if has3 { at(l3, j, z) } else { z },
        );
        let h1 = f.h1(at(roots, j, no_root));
        // (2j) mod n, for j < n.
        let h2 = f.h2(at(roots, add_mod(j, j, n), no_root));
        if has3 {
            put(l5, j, (q2 + q3) * half);
            put(l4, j, (q1 + q2 * R::from_f64(6.0) + q3) * R::ratio(1, 8));
        }
        put(l3, j, (q1 + q2) * half);
        put(
            l2,
            j,
            q1 * R::ratio(11, 12) + q2 * R::ratio(1, 12) - h1 * R::ratio(1, 6),
        );
        put(l1, j, (q00 + f.a) * half + h1 + h2 * half);
    }
    *pole = q00 * R::ratio(3, 4) + f.a * R::ratio(1, 4);
}
