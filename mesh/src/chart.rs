//! Provenance: where a face of the analysed (possibly refined) mesh lies in
//! the input mesh, and how a patch is re-expressed in the input face's own
//! parameter square.
//!
//! Every face has a parameter square `(s, t) ∈ [0, 1]²`: its first vertex at
//! (0,0), its second at (1,0), its last at (0,1). A face made by the refinement
//! step is the sub-quad of an input face at one of its corners `k`: its
//! vertices are the corner's vertex point, the edge point of edge `k→k+1`, the
//! face point and the edge point of edge `k−1→k`. For an input quad, that
//! sub-quad is the quadrant of the quad's square at corner `k`; for any other
//! input polygon, positions are given in the sub-quad's own square and the
//! corner `k` is reported (OpenSubdiv's PatchParam does the same for
//! irregular faces).

/// An axis-aligned affine map `(s, t) ↦ origin + s·du + t·dv` where `du` and
/// `dv` are multiples of the coordinate axes (a rotation by a multiple of 90°
/// or a flip, and a scale): squares map to squares, rectangles to rectangles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Affine {
    /// Image of (0,0).
    pub origin: [f64; 2],
    /// Image of (1,0) minus the origin.
    pub du: [f64; 2],
    /// Image of (0,1) minus the origin.
    pub dv: [f64; 2],
}

impl Affine {
    /// The identity.
    pub const IDENTITY: Affine = Affine {
        origin: [0.0, 0.0],
        du: [1.0, 0.0],
        dv: [0.0, 1.0],
    };

    /// The image of `(s, t)`.
    pub fn apply(&self, s: f64, t: f64) -> [f64; 2] {
        [
            self.origin[0] + s * self.du[0] + t * self.dv[0],
            self.origin[1] + s * self.du[1] + t * self.dv[1],
        ]
    }

    /// `self ∘ inner`: first `inner`, then `self`.
    pub fn compose(&self, inner: &Affine) -> Affine {
        let o = self.apply(inner.origin[0], inner.origin[1]);
        let lin = |d: [f64; 2]| {
            [
                d[0] * self.du[0] + d[1] * self.dv[0],
                d[0] * self.du[1] + d[1] * self.dv[1],
            ]
        };
        Affine {
            origin: o,
            du: lin(inner.du),
            dv: lin(inner.dv),
        }
    }

    /// The map of the unit square onto itself that puts the square's corner
    /// `k` (0: (0,0), 1: (1,0), 2: (1,1), 3: (0,1), counter-clockwise) at
    /// (0,0), the next corner at (1,0) and the previous at (0,1): a rotation by
    /// `k·90°`. Re-expresses coordinates in a frame that starts at corner `k`
    /// into the frame that starts at corner 0.
    pub fn rotation(k: usize) -> Affine {
        match k % 4 {
            0 => Affine::IDENTITY,
            1 => Affine {
                origin: [1.0, 0.0],
                du: [0.0, 1.0],
                dv: [-1.0, 0.0],
            },
            2 => Affine {
                origin: [1.0, 1.0],
                du: [-1.0, 0.0],
                dv: [0.0, -1.0],
            },
            _ => Affine {
                origin: [0.0, 1.0],
                du: [0.0, -1.0],
                dv: [1.0, 0.0],
            },
        }
    }

    /// The quadrant of the unit square at corner `k`, in the frame of corner
    /// `k` (a refined sub-quad's own square) → the square's own coordinates.
    pub fn quadrant(k: usize) -> Affine {
        let r = Affine::rotation(k);
        Affine {
            origin: r.origin,
            du: [r.du[0] * 0.5, r.du[1] * 0.5],
            dv: [r.dv[0] * 0.5, r.dv[1] * 0.5],
        }
    }

    /// Whether the map exchanges the axes (`du` along the second axis).
    pub fn swaps(&self) -> bool {
        self.du[0] == 0.0
    }

    /// Image of the rectangle `[u0, u1] × [v0, v1]` as `[u0', u1', v0', v1']`
    /// with `u0' ≤ u1'`, `v0' ≤ v1'`.
    pub fn rect(&self, r: [f64; 4]) -> [f64; 4] {
        let a = self.apply(r[0], r[2]);
        let b = self.apply(r[1], r[3]);
        [
            a[0].min(b[0]),
            a[0].max(b[0]),
            a[1].min(b[1]),
            a[1].max(b[1]),
        ]
    }

    /// Re-indexes a `K×K` control grid `p[i][j]` (`i` along `s`, `j` along `t`)
    /// so that `i` runs along the image's first axis and `j` along its second,
    /// both increasing.
    pub fn orient<T: Copy, const K: usize>(&self, p: &[[T; K]; K]) -> [[T; K]; K] {
        let mut out = *p;
        let swap = self.swaps();
        // Direction of s and t in the image: which axis and which sign.
        let (s_neg, t_neg) = if swap {
            (self.du[1] < 0.0, self.dv[0] < 0.0)
        } else {
            (self.du[0] < 0.0, self.dv[1] < 0.0)
        };
        for (i, row) in p.iter().enumerate() {
            for (j, x) in row.iter().enumerate() {
                let a = if s_neg { K - 1 - i } else { i };
                let b = if t_neg { K - 1 - j } else { j };
                if swap {
                    out[b][a] = *x;
                } else {
                    out[a][b] = *x;
                }
            }
        }
        out
    }
}

/// Where a face of the analysed mesh lies in the input mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceChart {
    /// The input face.
    pub face: u32,
    /// For a sub-quad of an input face that is not a quad, the input corner it
    /// sits at; `None` for positions in the input face's own square.
    pub corner: Option<u8>,
    /// From this face's own square to the input face's square (or the
    /// corner's sub-square).
    pub map: Affine,
}

impl FaceChart {
    /// An input face itself.
    pub fn input(face: u32) -> Self {
        FaceChart {
            face,
            corner: None,
            map: Affine::IDENTITY,
        }
    }

    /// The chart of the sub-quad at corner `k` of a face with `n` corners
    /// and this chart (a Catmull-Clark child): the quadrant of this square,
    /// or, for an input face that is not a quad, its corner's own square.
    pub fn child(&self, k: usize, n: usize) -> Self {
        if n == 4 || self.corner.is_some() {
            FaceChart {
                face: self.face,
                corner: self.corner,
                map: self.map.compose(&Affine::quadrant(k)),
            }
        } else {
            FaceChart {
                face: self.face,
                corner: Some(k as u8),
                map: Affine::IDENTITY,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quadrants_put_corners_where_the_chart_doc_says() {
        // Sub-quad at corner k: (0,0) at corner k, (1,0) at the midpoint of
        // edge k→k+1, (0,1) at the midpoint of edge k−1→k, (1,1) the centre.
        let corners = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        for k in 0..4 {
            let q = Affine::quadrant(k);
            let c = corners[k];
            let n = corners[(k + 1) % 4];
            let p = corners[(k + 3) % 4];
            let mid = |a: [f64; 2], b: [f64; 2]| [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
            assert_eq!(q.apply(0.0, 0.0), c);
            assert_eq!(q.apply(1.0, 0.0), mid(c, n));
            assert_eq!(q.apply(0.0, 1.0), mid(c, p));
            assert_eq!(q.apply(1.0, 1.0), [0.5, 0.5]);
        }
    }

    #[test]
    fn orient_follows_the_map() {
        // A grid whose entry is its own (s, t) corner index; after orienting,
        // entry [i][j] must be the preimage of image position (i, j).
        let mut g = [[(0usize, 0usize); 2]; 2];
        for (i, row) in g.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                *x = (i, j);
            }
        }
        for k in 0..4 {
            let m = Affine::rotation(k);
            let o = m.orient(&g);
            for (i, row) in o.iter().enumerate() {
                for (j, &(s, t)) in row.iter().enumerate() {
                    assert_eq!(m.apply(s as f64, t as f64), [i as f64, j as f64], "k={k}");
                }
            }
        }
    }

    #[test]
    fn compose_applies_inner_first() {
        let a = Affine::quadrant(1);
        let b = Affine::quadrant(2);
        let c = a.compose(&b);
        for (s, t) in [(0.0, 0.0), (1.0, 0.0), (0.3, 0.7)] {
            let inner = b.apply(s, t);
            assert_eq!(c.apply(s, t), a.apply(inner[0], inner[1]));
        }
    }
}
