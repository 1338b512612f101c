//! Exchange formats of a whole surface (`capdiv surface --format …`):
//! [`gltf`] for the web and real-time viewers (the welded tessellation).

pub mod gltf;
