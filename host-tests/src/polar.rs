//! A polar configuration (docs/math/c2ps.md §1): the pole `q00` and links
//! `links[i-1]` = link `i`, each a closed ring of `n` points, index `j` mod `n`.

use crate::vec3::P3;

/// A polar configuration of valence `n = links[0].len()`.
#[derive(Clone, Debug, PartialEq)]
pub struct Polar {
    /// The polar vertex `q00` (the 0-link).
    pub pole: P3,
    /// `links[i-1][j]` = `q[i][j]`, link `i = 1, 2, …`.
    pub links: Vec<Vec<P3>>,
}

impl Polar {
    /// A configuration from its pole and links (not validated: the reference
    /// is only ever given well-formed data).
    pub fn new(pole: P3, links: Vec<Vec<P3>>) -> Self {
        Polar { pole, links }
    }

    /// The valence `n`.
    pub fn valence(&self) -> usize {
        self.links[0].len()
    }

    /// Link `i` (1-based); link 0 is the pole repeated, as in the paper.
    pub fn q(&self, i: usize, j: usize) -> P3 {
        if i == 0 {
            self.pole
        } else {
            let l = &self.links[i - 1];
            l[j % l.len()]
        }
    }

    /// All points: the pole, then every link.
    pub fn points(&self) -> impl Iterator<Item = P3> + '_ {
        std::iter::once(self.pole).chain(self.links.iter().flatten().copied())
    }

    /// Largest absolute coordinate: the scale round-off is measured against.
    pub fn max_abs(&self) -> f64 {
        self.points()
            .flat_map(|p| p.into_iter())
            .fold(0.0, |m, c| m.max(c.abs()))
    }

    /// Bounding-box size: the longest side of the axis-aligned bounding box.
    pub fn bbox_size(&self) -> f64 {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for p in self.points() {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max)
    }

    /// The image under `x ↦ M x + t`.
    pub fn affine(&self, m: &[[f64; 3]; 3], t: &P3) -> Polar {
        let f = |p: P3| -> P3 {
            let mut o = *t;
            for (r, row) in m.iter().enumerate() {
                o[r] += row[0] * p[0] + row[1] * p[1] + row[2] * p[2];
            }
            o
        };
        Polar {
            pole: f(self.pole),
            links: self
                .links
                .iter()
                .map(|l| l.iter().map(|&p| f(p)).collect())
                .collect(),
        }
    }
}
