//! lumis-render's integration tests as one test binary: the files beside
//! this one are its modules (one per subject; `common` is their helper
//! module). One binary is compiled and linked once, and its tests share the
//! harness's threads, where a binary per file ran each file's tests apart
//! (a long test left the other core idle). Apart: `limits.rs` (it installs
//! a counting global allocator), `embree.rs` (feature `embree`) and
//! `layers/` (the module structure), each its own `[[test]]` in Cargo.toml.

mod common;

mod alpha;
mod bdpt;
mod bsdf_chi2;
mod bsdf_energy;
mod bsdf_layered;
mod bvh;
mod coated_integrators;
mod cornell_tungsten;
mod default_scene;
mod determinism;
mod env_light;
mod film_splat;
mod furnace;
mod fuzz_corpus;
mod inputs;
mod instancing;
mod integrator_options;
mod light_chi2;
mod lighttracer;
mod materials_coated;
mod materials_microfacet;
mod media;
mod media_loading;
mod media_photon;
mod merge;
mod mis_weights;
mod parts;
mod pbrt_images;
mod pbrt_v3;
mod phase_chi2;
mod photon_consistency;
mod photon_emission;
mod photon_map;
mod photon_order;
mod photon_progressive;
mod resume;
mod scene_errors;
mod session;
mod shapes;
mod shared_scenes;
mod spectra;
mod splats;
mod textured_emitter;
mod textures_load;
mod textures_procedural;
mod transmission;
mod vcm;
mod water_scene;
