//! Ray-scene acceleration: a binned-SAH BVH in pure Rust.

pub mod bvh;
pub use bvh::Bvh;
