//! The study's error: a message, made from any error on the way (files,
//! images, sessions) with the context it happened in.

use std::fmt;

#[derive(Debug)]
pub struct StudyError(pub String);

pub type Result<T> = std::result::Result<T, StudyError>;

impl fmt::Display for StudyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for StudyError {}

macro_rules! from_display {
    ($($t:ty),*) => {$(
        impl From<$t> for StudyError {
            fn from(e: $t) -> Self {
                StudyError(e.to_string())
            }
        }
    )*};
}
from_display!(
    std::io::Error,
    String,
    crate::image_io::ImageError,
    crate::session::SessionError,
    serde_json::Error
);

/// `.with_context(|| "while doing x")` on any result whose error displays.
pub trait Context<T> {
    fn with_context<F: FnOnce() -> String>(self, f: F) -> Result<T>;
}

impl<T, E: fmt::Display> Context<T> for std::result::Result<T, E> {
    fn with_context<F: FnOnce() -> String>(self, f: F) -> Result<T> {
        self.map_err(|e| StudyError(format!("{}: {e}", f())))
    }
}

/// Returns early with a formatted [`StudyError`].
macro_rules! bail {
    ($($t:tt)*) => {
        return Err($crate::study::error::StudyError(format!($($t)*)))
    };
}
pub(crate) use bail;
