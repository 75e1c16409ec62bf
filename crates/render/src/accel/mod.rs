//! Ray-scene acceleration: a binned-SAH BVH in pure Rust.

pub mod bench;
pub mod bvh;
pub mod mem;
pub use bvh::Bvh;
