//! Ray-scene acceleration: a binned-SAH BVH in pure Rust.

pub mod bench;
pub mod bvh;
#[cfg(feature = "embree")]
pub mod embree;
pub mod mem;
pub use bvh::Bvh;
