//! Rendering: geometry, acceleration, materials, lights, camera, film,
//! image I/O and integrators.

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
pub mod metrics;
pub mod scene;
pub mod session;
pub mod texture;
