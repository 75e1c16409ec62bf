//! lumis-scene's integration tests as one test binary (compiled and linked
//! once): the files beside this one are its modules.

mod directives;
mod errors;
mod no_panic;
mod shared_scenes;
mod upgrade;
