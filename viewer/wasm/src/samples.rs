//! The meshes the viewer offers, all from [`capdiv_mesh::samples`] (the same
//! generators as `capdiv demo` and the coverage example).

use capdiv_mesh::{samples, MeshInput};

/// A sample: identifier (as in the page's selector), one line about it, and
/// its generator.
pub struct Sample {
    /// Identifier.
    pub name: &'static str,
    /// What it shows.
    pub about: &'static str,
    /// Builds the mesh.
    pub build: fn() -> MeshInput,
}

/// Every sample, in the page's order (the first is shown on load).
pub const SAMPLES: &[Sample] = &[
    Sample {
        name: "mushroom",
        about: "surface of revolution, C²PS poles of valence 12 at the cap and the foot",
        build: samples::mushroom,
    },
    Sample {
        name: "globe",
        about: "unit sphere as a latitude-longitude grid, two C²PS poles of valence 8",
        build: || samples::globe(8, 9),
    },
    Sample {
        name: "hand",
        about: "palm, fingers and thumb: polar finger tips (n = 8), wrist pole n = 26, EG n = 5 junctions",
        build: samples::hand,
    },
    Sample {
        name: "rounded-cube",
        about: "cube of 3×3 grids bulged towards a sphere: eight EG caps of valence 3",
        build: || samples::rounded_cube(3),
    },
    Sample {
        name: "cube",
        about: "the plain cube: valence-3 neighbours, refined once before the caps",
        build: samples::cube,
    },
    Sample {
        name: "two-beam-corner",
        about: "L-shaped corner of two square beams: valence 5 inside, valence 3 outside",
        build: samples::two_beam_corner,
    },
    Sample {
        name: "torus",
        about: "regular quad torus: uniform bicubic B-spline patches only",
        build: || samples::torus(8, 6),
    },
    Sample {
        name: "pole-disk",
        about: "open bumpy disk around one C²PS pole of valence 6",
        build: || samples::pole_disk(6, 4),
    },
    Sample {
        name: "extraordinary-disk-5",
        about: "open bumpy disk around one EG cap of valence 5",
        build: || samples::extraordinary_disk(5, 3),
    },
    Sample {
        name: "extraordinary-disk-7",
        about: "open bumpy disk around one valence-7 point (Catmull-Clark cap: EG has no rule)",
        build: || samples::extraordinary_disk(7, 3),
    },
    Sample {
        name: "triangle-and-pentagon",
        about: "a triangle and a pentagon among quads: refined before analysis",
        build: samples::triangle_and_pentagon_mesh,
    },
];

/// The sample called `name`.
pub fn by_name(name: &str) -> Option<&'static Sample> {
    SAMPLES.iter().find(|s| s.name == name)
}
