//! Rendering: geometry, acceleration, materials, lights, camera, film,
//! image I/O and integrators.
//!
//! The top-level modules are layered, each using only the ones below it
//! (`tests/layers` checks this and that no two modules import each other):
//! `geometry`, `bsdf`, `film`, `media` at the bottom; then `camera`, `image_io`,
//! `metrics`; `texture`; `material`; `light`; `accel`; `scene`;
//! `integrator`; `checkpoint`; and `load`, which builds everything.

pub mod accel;
pub mod bsdf;
pub mod camera;
pub mod checkpoint;
pub mod film;
pub mod geometry;
pub mod image_io;
pub mod integrator;
pub mod light;
pub mod load;
pub mod material;
pub mod media;
pub mod metrics;
pub mod scene;
pub mod session;
pub mod study;
pub mod texture;
