//! The error type users see: every message names what was wrong, its value and what would be valid.

use std::fmt::Display;
use std::path::PathBuf;

/// Everything that can go wrong in swell that is the caller's to fix.
///
/// Internal invariants are `debug_assert!`s, not variants: an `Error` always means bad input or a
/// failing environment (disk, permissions).
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A parameter outside its valid range, e.g. `water.waves[2].steepness = 1.7 is outside [0, 1]`.
    #[error("{key} = {value} is outside {range}")]
    OutOfRange {
        /// Key path of the parameter, as written in a scene file (`water.waves[2].steepness`).
        key: String,
        /// The offending value, formatted.
        value: String,
        /// The valid range, formatted (`[0, 1]`, `> 0`).
        range: String,
    },
    /// A parameter that is wrong for a reason other than its range.
    #[error("{key}: {message}")]
    Invalid {
        /// Key path of the parameter.
        key: String,
        /// What is wrong and what would be right.
        message: String,
    },
    /// A scene or data file that could not be parsed.
    #[error("{path}: {message}")]
    Parse {
        /// Where the text came from (a file path or `preset NAME`).
        path: String,
        /// The parser's message, with the key path where known.
        message: String,
    },
    /// A preset name that does not exist.
    #[error("unknown preset `{name}`; available presets: {available}")]
    UnknownPreset {
        /// The name asked for.
        name: String,
        /// Comma-separated list of valid names.
        available: String,
    },
    /// A file that could not be read or written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file concerned.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// An image that could not be encoded or decoded.
    #[error("{}: {message}", path.display())]
    Image {
        /// The file concerned.
        path: PathBuf,
        /// The codec's message.
        message: String,
    },
    /// An [`Error::OutOfRange`] or [`Error::Invalid`] found in a named source (a scene file, a
    /// preset): the source first, as parse errors have it.
    #[error("{source_name}: {error}")]
    InSource {
        /// The file path, or `preset NAME`.
        source_name: String,
        /// The error, naming the key, value and valid range.
        error: Box<Error>,
    },
    /// A simulation that left its stable range (e.g. a spring mesh blowing up).
    #[error("simulation unstable: {0}")]
    Unstable(String),
}

/// `Result` with swell's [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;

impl Error {
    /// Builds an [`Error::OutOfRange`] for `key = value` outside `range`.
    pub fn out_of_range(key: impl Into<String>, value: impl Display, range: impl Into<String>) -> Self {
        Error::OutOfRange { key: key.into(), value: value.to_string(), range: range.into() }
    }

    /// Builds an [`Error::Invalid`].
    pub fn invalid(key: impl Into<String>, message: impl Into<String>) -> Self {
        Error::Invalid { key: key.into(), message: message.into() }
    }

    /// Builds an [`Error::Io`] for `path`.
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Error::Io { path: path.into(), source }
    }

    /// This error as found in `source_name` (a file path or `preset NAME`): key errors get the
    /// source in front, as parse errors have; errors that already name a file are kept.
    pub fn in_source(self, source_name: &str) -> Self {
        match self {
            Error::OutOfRange { .. } | Error::Invalid { .. } => {
                Error::InSource { source_name: source_name.into(), error: Box::new(self) }
            }
            other => other,
        }
    }

    /// The error without the source [`Error::in_source`] added.
    pub fn without_source(&self) -> &Error {
        match self {
            Error::InSource { error, .. } => error,
            other => other,
        }
    }
}

/// A number as people read it in a message: as typed for everyday sizes, in scientific notation
/// for huge or tiny ones (`1e300`, not its 301 digits).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Human<T>(pub T);

macro_rules! human_display {
    ($t:ty) => {
        impl Display for Human<$t> {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                let x = self.0;
                if x.is_finite() && x != 0.0 && (x.abs() >= 1e9 || x.abs() < 1e-6) {
                    write!(f, "{x:e}")
                } else {
                    write!(f, "{x}")
                }
            }
        }
    };
}
human_display!(f32);
human_display!(f64);

/// Checks `lo <= value <= hi` (and that `value` is finite), naming `key` in the error.
pub fn check_range(key: &str, value: f32, lo: f32, hi: f32) -> Result<()> {
    if value.is_finite() && value >= lo && value <= hi {
        Ok(())
    } else {
        Err(Error::out_of_range(key, value, format!("[{lo}, {hi}]")))
    }
}

/// Checks `value > 0` and finite, naming `key` in the error.
pub fn check_positive(key: &str, value: f32) -> Result<()> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(Error::out_of_range(key, Human(value), "(0, inf)"))
    }
}

/// Checks `value >= 0` and finite, naming `key` in the error.
pub fn check_non_negative(key: &str, value: f32) -> Result<()> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(Error::out_of_range(key, Human(value), "[0, inf)"))
    }
}

/// Checks that a seed fits a TOML integer, [0, i64::MAX], naming `key`: scene files store seeds,
/// and a larger one could not be saved.
pub fn check_seed(key: &str, seed: u64) -> Result<()> {
    if seed <= i64::MAX as u64 {
        Ok(())
    } else {
        Err(Error::out_of_range(key, seed, format!("[0, {}]", i64::MAX)))
    }
}

/// Checks an integer count `lo <= value <= hi`, naming `key` in the error.
pub fn check_count(key: &str, value: u32, lo: u32, hi: u32) -> Result<()> {
    if (lo..=hi).contains(&value) {
        Ok(())
    } else {
        Err(Error::out_of_range(key, value, format!("[{lo}, {hi}]")))
    }
}

/// Checks that every component of a vector is finite, naming `key` in the error.
pub fn check_finite_vec(key: &str, v: &[f32]) -> Result<()> {
    if v.iter().all(|c| c.is_finite()) {
        Ok(())
    } else {
        Err(Error::invalid(key, format!("{v:?} must have finite components")))
    }
}

/// Checks that a horizontal direction (x, z) is finite and non-zero (it is normalised on use),
/// naming `key` in the error.
pub fn check_direction(key: &str, d: glam::Vec2) -> Result<()> {
    let len = d.length();
    if len.is_finite() && len > 1e-6 {
        Ok(())
    } else {
        Err(Error::invalid(key, format!("{:?} must be a finite, non-zero (x, z) vector", d.to_array())))
    }
}
