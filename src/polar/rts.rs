//! One RTS step (docs/math/c2ps.md §3): the C²PS rules with the valence kept, no
//! periodic refinement (`q̃ = q`) and `τ = j/n`. In place, O(n).

use super::fourier::Fourier;
use super::index::{add_mod, at, put};
use super::net::{capacity, link_count_after_step, link_of, split_links, Head};
use super::step::step_fits;
use crate::error::Error;
use crate::point::Point3;
use crate::real::Real;

/// One RTS step of a net (`PolarNetInner::rts_step`), over its storage's
/// slices: compiled once per scalar type, whatever the storage.
pub(crate) fn rts_step<R: Real>(
    head: &mut Head<R>,
    (links, roots): (&mut [Point3<R>], &mut [[R; 2]]),
) -> Result<(), Error> {
    if head.link_count < 2 {
        return Ok(()); // an empty net: nothing to refine
    }
    let n = head.valence;
    let cap = capacity(links.len(), roots.len());
    step_fits(
        head.pole,
        [1, 2, 3].map(|i| link_of(links, cap, head, i).unwrap_or(&[])),
        n,
    )?;
    let new_link_count = link_count_after_step(head.link_count);
    rts_in_place(
        &mut head.pole,
        split_links(links, cap, n, new_link_count),
        n,
        head.link_count,
        roots.get(..n).unwrap_or_default(),
    );
    head.link_count = new_link_count;
    Ok(())
}

/// The step over plain slices. On entry `links[k][..n]` holds
/// link `k+1` for `k < link_count`, and every link that will be written
/// (`k < 2·link_count − 1`, at most 5) has room for `n` points (more is left alone).
fn rts_in_place<R: Real>(
    pole: &mut Point3<R>,
    links: [&mut [Point3<R>]; 5],
    n: usize,
    link_count: usize,
    roots: &[[R; 2]],
) {
    let [l1, l2, l3, l4, l5] = links;
    let f = Fourier::of(l1.get(..n).unwrap_or(&[]), roots, 1);
    let q00 = *pole;
    let has3 = link_count >= 3 && l3.len() >= n && l4.len() >= n && l5.len() >= n;
    if l1.len() < n || l2.len() < n || l3.len() < n {
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
