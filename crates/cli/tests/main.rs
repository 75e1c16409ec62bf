//! The `lumis` binary's integration tests as one test binary: the files
//! beside this one are its modules (one per subject; `common` is their
//! helper module), compiled and linked once, their tests sharing the
//! harness's threads.

mod common;

mod cli;
mod parts;
mod resume;
mod session;
mod stdout;
mod study;
mod study_external;
mod tev;
