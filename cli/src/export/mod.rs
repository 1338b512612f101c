//! Exchange formats of a whole surface (`capdiv surface --format …`):
//! [`gltf`] for the web and real-time viewers (the welded tessellation),
//! [`step`] for CAD (the exact patches as a B-rep of B-spline faces).

pub mod gltf;
pub mod step;
