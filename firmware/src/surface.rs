//! Link-time panic check of the kernel's public API.
//!
//! The workloads call the kernel with the fixed sample data, and LTO may fold
//! away checks that only those inputs make dead. Here every public
//! refinement and evaluation entry point is called with arguments hidden
//! behind [`black_box`], so the optimiser knows nothing about them, from a
//! branch it cannot prove dead (`black_box(false)`): it is linked, never run.
//! With the release panic handler (see `main.rs`), any panic path left in
//! these calls makes the link fail.

use core::hint::black_box;

/// Links the API surface of the enabled schemes. Never executes it.
#[inline(never)]
pub fn link() {
    if black_box(false) {
        // Both scalar types: the firmware computes in f32, the WASM module
        // and hosts in f64; the generic code is instantiated per type.
        #[cfg(feature = "c2ps")]
        {
            c2ps::all::<f32>();
            c2ps::all::<f64>();
        }
        #[cfg(feature = "eg")]
        {
            eg::all::<f32>();
            eg::all::<f64>();
        }
        #[cfg(feature = "c2ps-stream")]
        {
            stream::all::<f32>();
            stream::all::<f64>();
        }
        common::all::<f32>();
        common::all::<f64>();
    }
}

/// Shared pieces: Bézier patches, the B-spline conversion, the root ring.
mod common {
    use super::black_box;
    use capdiv::bezier::bspline_to_bezier_cubic;
    use capdiv::trig::{primitive_root, RootsOfUnity};
    use capdiv::{BicubicPatch, BiquarticPatch, Point3, Real};

    #[inline(never)]
    pub fn all<R: Real>() {
        let p = black_box(Point3::<R>::ZERO);
        let (u, v) = black_box((R::ratio(1, 2), R::ratio(1, 2)));
        let cubic = BicubicPatch {
            points: bspline_to_bezier_cubic(&black_box([[p; 4]; 4])),
        };
        let _ = black_box(cubic.evaluate(u, v));
        let _ = black_box(cubic.position(u, v));
        let _ = black_box(cubic.normal(u, v));
        let quartic = BiquarticPatch {
            points: black_box([[p; 5]; 5]),
        };
        let _ = black_box(quartic.evaluate(u, v).map(|e| e.normal()));
        let _ = black_box(primitive_root(black_box(12)));
        let mut empty = RootsOfUnity::<R, 96>::empty();
        let _ = black_box(empty.reset(black_box(12)));
        if let Ok(mut ring) = RootsOfUnity::<R, 96>::new(black_box(6)) {
            let _ = black_box(ring.get(black_box(7)));
            let _ = black_box(ring.double());
        }
        let _ = black_box(p.norm() + p.dot(p) + p.max_abs_diff(p));
        let _ = black_box(p.cross(p).cast::<f64>());
    }
}

#[cfg(feature = "c2ps")]
mod c2ps {
    use super::black_box;
    use capdiv::{FirstStep, OuterRegion, PolarNet, PoleJet, Real};

    /// Small enough that this never-run code costs no stack to speak of.
    type Net<R> = PolarNet<R, 24>;

    #[inline(never)]
    pub fn all<R: Real>() {
        let pole = black_box([R::ZERO; 3]);
        let store = [[R::ZERO; 3]; 21];
        let pts: &[[R; 3]] = black_box(&store);
        let len = black_box(3);
        let links: [&[[R; 3]]; 7] = black_box([pts; 7]).map(|l| l.get(..len).unwrap_or(l));
        let links: &[&[[R; 3]]] = black_box(&links);
        let flat_store = [R::ZERO; 63];
        let flat: &[R] = black_box(&flat_store);
        for mut net in [
            Net::<R>::new(pole, links),
            Net::<R>::from_flat(pole, black_box(3), flat),
        ]
        .into_iter()
        .flatten()
        {
            let _ = black_box(net.step(black_box(FirstStep::Plain)));
            let _ = black_box(net.rts_step());
            let _ = black_box(net.link(black_box(2)));
            let _ = black_box(net.ring_patch(black_box(1)));
            for patch in net.ring_patches() {
                black_box(patch);
            }
            let jet = PoleJet::of(&net);
            let _ = black_box((jet.limit(), jet.geometry()));
            black_box((net.valence(), net.level(), net.pole(), net.ring_len()));
        }
        // In-place construction (statics): reset, then refine and read out.
        let mut net = Net::<R>::empty();
        let _ = black_box(net.reset(pole, links));
        let _ = black_box(net.reset_flat(pole, black_box(3), flat));
        let _ = black_box(net.step(black_box(FirstStep::Uniform)));
        let _ = black_box(PoleJet::of(&net).geometry());
        if let Ok(region) = OuterRegion::new(pole, links) {
            let _ = black_box(region.patch(black_box(4)));
            for patch in region.patches() {
                black_box(patch);
            }
        }
    }
}

#[cfg(feature = "eg")]
mod eg {
    use super::black_box;
    use capdiv::eg::{lambda_catmull_clark, CNet, DNet, EgSubdivision, InnerNode, RuleTable};
    use capdiv::Real;

    #[inline(never)]
    pub fn all<R: Real>() {
        let center = black_box([R::ZERO; 3]);
        let node_store = [[R::ZERO; 3]; 120];
        let nodes: &[[R; 3]] = black_box(&node_store);
        let len = black_box(18);
        let nodes = nodes.get(..len).unwrap_or(nodes);
        let c0 = black_box(Some([R::ZERO; 3]));
        if let Ok(c) = CNet::new(center, nodes) {
            let _ = black_box((c.limit(), c.regular_cap(), c.sector(black_box(1))));
            let d = c.to_dnet();
            let _ = black_box((d.fitted_limit(), d.node(black_box(1), 2, 1)));
            let _ = black_box(d.refined(None));
            let _ = black_box(CNet::from_sectors(
                center,
                black_box(&[[[R::ZERO; 3]; 6]; 3]),
            ));
        }
        if let Ok(d) = DNet::new(nodes, c0) {
            let table = RuleTable::builtin(black_box(3));
            let _ = black_box(d.refined(table.as_ref()));
            let _ = black_box(DNet::from_sectors(black_box(&[[[R::ZERO; 3]; 12]; 3]), c0));
            if let Some(t) = table {
                let node = black_box(InnerNode::ALL[1]);
                let _ = black_box((t.row(node, black_box(2)), t.c0_weight(node)));
                let user = RuleTable::new(
                    black_box(3),
                    t.listed(InnerNode::D11),
                    t.listed(InnerNode::D22),
                    t.listed(InnerNode::D21),
                    t.listed(InnerNode::D31),
                    t.listed(InnerNode::D32),
                );
                if let Ok(user) = user {
                    if let Ok(mut sub) = EgSubdivision::new(&d, Some(user)) {
                        let _ = black_box(sub.step());
                        let _ = black_box(sub.ring_patch(black_box(2)));
                    }
                }
            }
            if let Ok(mut sub) = EgSubdivision::new(&d, None) {
                let _ = black_box(sub.step());
                let _ = black_box(sub.ring_patch(black_box(2)));
                for patch in sub.ring_patches() {
                    black_box(patch);
                }
                black_box((sub.limit(), sub.level(), sub.net(), sub.previous()));
            }
        }
        let flat_store = [R::ZERO; 360];
        let flat: &[R] = black_box(&flat_store);
        let flat = flat.get(..black_box(54)).unwrap_or(flat);
        let _ = black_box(CNet::from_flat(center, flat).map(|c| c.limit()));
        if let Ok(d) = DNet::from_flat(flat, c0) {
            if let Ok(sub) = EgSubdivision::new(&d, None) {
                let _ = black_box(sub.ring_patch_domain(black_box(1)));
            }
        }
        // In-place construction (statics): every reset path, then a step.
        let mut cnet = CNet::<R>::empty();
        let _ = black_box(cnet.reset(center, nodes));
        let _ = black_box(cnet.reset_flat(center, flat));
        let _ = black_box(cnet.reset_sectors(center, black_box(&[[[R::ZERO; 3]; 6]; 3])));
        let mut dnet = DNet::<R>::empty();
        dnet.reset_from_cnet(&cnet);
        let _ = black_box(dnet.reset(nodes, c0));
        let _ = black_box(dnet.reset_flat(flat, c0));
        let _ = black_box(dnet.reset_sectors(black_box(&[[[R::ZERO; 3]; 12]; 3]), c0));
        let mut sub = EgSubdivision::<R>::empty();
        let _ = black_box(sub.reset(&cnet, None));
        let _ = black_box(sub.reset(&dnet, None));
        if let Some(t) = RuleTable::builtin(black_box(5)) {
            let _ = black_box(sub.reset(&dnet, Some(t)));
            let _ = black_box(sub.reset(&cnet, Some(t)));
        }
        let _ = black_box(sub.step());
        black_box(lambda_catmull_clark(black_box(7)));
    }
}

#[cfg(feature = "c2ps-stream")]
mod stream {
    use super::black_box;
    use capdiv::{FirstStep, PolarStream, Real, StreamOptions};

    #[inline(never)]
    pub fn all<R: Real>() {
        let pole = black_box([R::ZERO; 3]);
        let store = [[R::ZERO; 3]; 21];
        let pts: &[[R; 3]] = black_box(&store);
        let links: [&[[R; 3]]; 3] = black_box([pts, pts, pts]);
        let mut state = PolarStream::<R, 4>::empty();
        let opts = StreamOptions::depth(black_box(3))
            .first(black_box(FirstStep::Plain))
            .only(black_box(1), black_box(Some(1)));
        if let Ok(mut sweep) = state.sweep(pole, &links, opts) {
            let _ = black_box(sweep.jet());
            let _ = black_box(sweep.valence(black_box(2)));
            let _ = black_box(sweep.len());
            let _ = black_box(sweep.next().map(|p| p.ring_index()));
        }
        let _ = black_box(
            state.run(pole, &links, black_box(StreamOptions::depth(2)), |p| {
                black_box(p);
            }),
        );
    }
}
