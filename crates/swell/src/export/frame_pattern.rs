//! File names numbered by frame: a printf-style pattern such as `frames/sea_%04d.png`, the form
//! video tools (ffmpeg, Blender, Nuke) read image sequences in.

use std::path::{Path, PathBuf};

use crate::error::{Error, Result};

/// Widest zero padding `%0Nd` accepts: frame numbers have at most 7 digits
/// ([`MAX_FRAME`](super::MAX_FRAME)), and two more leave room for tools that expect 9.
pub const MAX_PATTERN_WIDTH: usize = 9;

/// What a frame pattern may hold, for error messages.
const VALID: &str =
    "valid: one %d or %0Nd (N in [1, 9]) in the file name, %% for a literal %, e.g. frames/sea_%04d.png";

/// A path with one frame-number directive in its file name: `%d` (the number as is) or `%0Nd`
/// (zero-padded to at least N digits, N in [1, [`MAX_PATTERN_WIDTH`]]), plus `%%` for a literal
/// `%`, as printf and ffmpeg read it. Frame k's file is [`path`](Self::path)`(k)`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FramePattern {
    /// The directory the files go to (`.` when the pattern names none).
    dir: PathBuf,
    /// The file name before the directive, `%%` already turned into `%`.
    prefix: String,
    /// Minimum digits of the frame number, zero-padded; 0 for `%d`.
    width: usize,
    /// The file name after the directive, `%%` already turned into `%`.
    suffix: String,
}

impl FramePattern {
    /// Whether `path` asks for a frame pattern: its file name holds a `%`. (Only then is it parsed
    /// as one; a name without `%` is one file.)
    pub fn is_pattern(path: &Path) -> bool {
        path.file_name().is_some_and(|n| n.to_string_lossy().contains('%'))
    }

    /// Parses `path` as a frame pattern; `key` names the option in errors, which quote the value
    /// and say what is valid. Refused: no directive or more than one, any directive other than
    /// `%d`, `%0Nd` and `%%`, a directive in the directory part (the directory must exist before
    /// the first frame is written), and a name that is not UTF-8.
    pub fn parse(key: &str, path: &Path) -> Result<Self> {
        let shown = path.display();
        let bad = |what: String| Error::invalid(key, format!("`{shown}`: {what}; {VALID}"));
        let name = path
            .file_name()
            .ok_or_else(|| bad("names no file".into()))?
            .to_str()
            .ok_or_else(|| bad("the file name is not UTF-8".into()))?;
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => PathBuf::from("."),
        };
        if dir.to_string_lossy().contains('%') {
            return Err(bad("a % in the directory part: the frame number goes in the file name".into()));
        }
        let mut prefix = String::new();
        let mut suffix = String::new();
        let mut width = None;
        let mut chars = name.char_indices().peekable();
        while let Some((at, c)) = chars.next() {
            let text = if width.is_none() { &mut prefix } else { &mut suffix };
            if c != '%' {
                text.push(c);
                continue;
            }
            // The directive runs to the first letter or `%` after the `%` sign.
            let rest = &name[at + 1..];
            let len = rest.find(|ch: char| ch.is_ascii_alphabetic() || ch == '%').map_or(rest.len(), |i| i + 1);
            let directive = &rest[..len];
            for _ in 0..len {
                chars.next();
            }
            if directive == "%" {
                text.push('%');
                continue;
            }
            let Some(digits) = directive.strip_suffix('d') else {
                let what = if directive.is_empty() {
                    "a % at the end of the file name".to_string()
                } else {
                    format!("`%{directive}` is not a frame-number directive")
                };
                return Err(bad(what));
            };
            let w = match digits {
                "" => 0,
                _ if digits.starts_with('0') && digits.len() > 1 && digits.bytes().all(|b| b.is_ascii_digit()) => {
                    match digits[1..].parse::<usize>() {
                        Ok(n) if (1..=MAX_PATTERN_WIDTH).contains(&n) => n,
                        _ => {
                            return Err(bad(format!("`%{directive}` pads to outside [1, {MAX_PATTERN_WIDTH}] digits")))
                        }
                    }
                }
                _ => {
                    return Err(bad(format!(
                        "`%{directive}` is not a frame-number directive (pad with zeros, not spaces: %0Nd)"
                    )))
                }
            };
            if width.is_some() {
                return Err(bad("two frame-number directives: give exactly one".into()));
            }
            width = Some(w);
        }
        let Some(width) = width else {
            return Err(bad("no frame-number directive (only %%)".into()));
        };
        Ok(Self { dir, prefix, width, suffix })
    }

    /// The directory the frames are written to (`.` when the pattern names none).
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The file of frame `frame`: the directory, then the file name with the directive replaced by
    /// the frame number, zero-padded to the directive's width.
    pub fn path(&self, frame: u32) -> PathBuf {
        let name = format!("{}{:0width$}{}", self.prefix, frame, self.suffix, width = self.width);
        if self.dir == Path::new(".") {
            PathBuf::from(name)
        } else {
            self.dir.join(name)
        }
    }

    /// The file name's extension after expansion (`png` for `sea_%04d.png`), lower case.
    pub fn extension(&self) -> Option<String> {
        Path::new(&self.path(0)).extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(s: &str) -> Result<FramePattern> {
        FramePattern::parse("--out", Path::new(s))
    }

    fn message(s: &str) -> String {
        parse(s).expect_err(s).to_string()
    }

    #[test]
    fn expands_the_frame_number_zero_padded() {
        let p = parse("frames/sea_%04d.png").unwrap();
        assert_eq!(p.path(7), Path::new("frames/sea_0007.png"));
        assert_eq!(p.path(48), Path::new("frames/sea_0048.png"));
        assert_eq!(p.path(123_456), Path::new("frames/sea_123456.png"), "padding never truncates");
        assert_eq!(p.dir(), Path::new("frames"));
        assert_eq!(p.extension().as_deref(), Some("png"));
        let p = parse("x%d.png").unwrap();
        assert_eq!(p.path(0), Path::new("x0.png"));
        assert_eq!(p.path(95), Path::new("x95.png"));
        assert_eq!(p.dir(), Path::new("."));
        assert_eq!(parse("%09d.PNG").unwrap().path(3), Path::new("000000003.PNG"));
        assert!(parse("%1d.png").is_err(), "space padding is refused");
    }

    #[test]
    fn double_percent_is_a_literal_percent() {
        let p = parse("out/100%%_%03d.png").unwrap();
        assert_eq!(p.path(5), Path::new("out/100%_005.png"));
        let p = parse("f_%02d_%%.png").unwrap();
        assert_eq!(p.path(5), Path::new("f_05_%.png"));
    }

    #[test]
    fn bad_patterns_are_refused_with_the_reason_and_what_is_valid() {
        for (s, why) in [
            ("a_%d_%d.png", "two frame-number directives"),
            ("a_%04d%d.png", "two frame-number directives"),
            ("a_%s.png", "`%s` is not a frame-number directive"),
            ("a_%4d.png", "pad with zeros"),
            ("a_%00d.png", "outside [1, 9]"),
            ("a_%010d.png", "outside [1, 9]"),
            ("a_%0xd.png", "`%0x` is not"),
            ("a_100%%.png", "no frame-number directive"),
            ("a_%", "a % at the end"),
            ("f%d/a_%d.png", "directory part"),
        ] {
            let m = message(s);
            assert!(m.starts_with("--out: "), "{s}: {m}");
            assert!(m.contains(s), "{s}: the message quotes the value: {m}");
            assert!(m.contains(why), "{s}: {m}");
            assert!(m.contains("valid: one %d or %0Nd"), "{s}: {m}");
        }
    }

    #[test]
    fn only_names_with_a_percent_are_patterns() {
        assert!(FramePattern::is_pattern(Path::new("a/b_%04d.png")));
        assert!(!FramePattern::is_pattern(Path::new("a%d/b.png")), "the directory is not the name");
        assert!(!FramePattern::is_pattern(Path::new("sea.png")));
    }
}
