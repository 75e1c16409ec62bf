//! Helpers shared by the integration tests of lumis-render.

pub mod chi2;
