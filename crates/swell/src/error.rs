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
    /// A long call stopped because its caller asked it to ([`crate::Water::set_watch`]): nothing
    /// is wrong, and the same call asked again continues from where this one stopped.
    #[error("cancelled: {0}")]
    Cancelled(String),
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

/// Longest line of a message [`printable`] passes, in characters (escapes counted as written).
pub const MAX_MESSAGE_LINE_CHARS: usize = 400;
/// Most lines of a message [`printable`] passes.
pub const MAX_MESSAGE_LINES: usize = 40;

/// `message` made safe to print in a terminal, store as C's last error or raise in Python (issue
/// 37): a message echoes user text (keys, values, file names, the scene line a parser quotes), and
/// that text may hold escape sequences that retitle or clear the terminal, NUL bytes that end a C
/// string early, bidirectional overrides that show text in another order than it is, or a
/// 100,000-character key. Control characters other than newline and tab, and the bidi embedding,
/// override and isolate marks (U+202A-U+202E, U+2066-U+2069, U+200E, U+200F, U+061C), are written
/// as `\u{..}`; a line longer than [`MAX_MESSAGE_LINE_CHARS`] is cut there with its total length
/// stated, and lines past [`MAX_MESSAGE_LINES`] are counted, not printed. The CLI, the C ABI and
/// the Python package print every [`Error`] through this, so all three show the same text.
pub fn printable(message: &str) -> String {
    let mut out = String::with_capacity(message.len().min(MAX_MESSAGE_LINE_CHARS * 2));
    let total_lines = message.split('\n').count();
    for (k, line) in message.split('\n').take(MAX_MESSAGE_LINES).enumerate() {
        if k > 0 {
            out.push('\n');
        }
        let mut written = 0;
        for (count, c) in line.chars().enumerate() {
            let escaped = needs_escape(c).then(|| format!("\\u{{{:x}}}", c as u32));
            let width = escaped.as_ref().map_or(1, |e| e.len());
            if written + width > MAX_MESSAGE_LINE_CHARS {
                let rest = line.chars().skip(count).count();
                out.push_str(&format!("... ({} characters in all)", count + rest));
                break;
            }
            written += width;
            match escaped {
                Some(e) => out.push_str(&e),
                None => out.push(c),
            }
        }
    }
    if total_lines > MAX_MESSAGE_LINES {
        out.push_str(&format!("\n... ({} more lines)", total_lines - MAX_MESSAGE_LINES));
    }
    out
}

/// Whether [`printable`] writes `c` as an escape: control characters but newline and tab, and the
/// marks that reorder text (Unicode's bidi controls).
fn needs_escape(c: char) -> bool {
    (c.is_control() && c != '\n' && c != '\t')
        || matches!(c, '\u{200E}' | '\u{200F}' | '\u{061C}' | '\u{202A}'..='\u{202E}' | '\u{2066}'..='\u{2069}')
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn printable_escapes_terminal_controls_nul_and_bidi_marks_and_keeps_lines() {
        let hostile = "water.\u{1b}]0;pwned\u{7}\u{1b}[2J\0key\u{202E}gnp.exe\r: bad\n\tsecond line";
        let p = printable(hostile);
        assert_eq!(p, "water.\\u{1b}]0;pwned\\u{7}\\u{1b}[2J\\u{0}key\\u{202e}gnp.exe\\u{d}: bad\n\tsecond line");
        assert!(!p.chars().any(needs_escape));
        // Plain messages pass unchanged.
        let plain = "scene.toml: water.cells[0] = 0 is outside [1, 4096]";
        assert_eq!(printable(plain), plain);
    }

    #[test]
    fn printable_cuts_long_lines_and_many_lines_and_states_the_totals() {
        let key = "k".repeat(100_000);
        let p = printable(&format!("unknown key `{key}`"));
        assert!(p.len() < MAX_MESSAGE_LINE_CHARS + 40, "{} bytes", p.len());
        assert!(p.ends_with("... (100014 characters in all)"), "{}", &p[p.len() - 40..]);
        // Escapes count at their written width, so a line of escapes is cut as short.
        let p = printable(&"\u{1b}".repeat(10_000));
        assert!(p.len() <= MAX_MESSAGE_LINE_CHARS + 40);
        assert!(p.ends_with("(10000 characters in all)"));
        let p = printable(&"line\n".repeat(100));
        assert_eq!(p.lines().count(), MAX_MESSAGE_LINES + 1);
        assert!(p.ends_with("... (61 more lines)"), "{p}");
    }
}
