//! Which frames a bake or an export covers: an inclusive range `A..B`, optionally one shard of it.

use crate::error::{Error, Result};

/// Largest frame number: keeps file names at most 7 digits and `frame / fps` exact in `f64`.
pub const MAX_FRAME: u32 = 9_999_999;

/// Most shards a range can be split into.
pub const MAX_SHARDS: u32 = 100_000;

/// Frames `first..=last`; frame `k` shows time `k / fps` seconds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameRange {
    /// First frame, in [0, [`MAX_FRAME`]].
    pub first: u32,
    /// Last frame (included), in [`first`](Self::first), [`MAX_FRAME`]].
    pub last: u32,
}

impl FrameRange {
    /// Frames `first..=last`, checked; `key` names the option in errors.
    pub fn new(key: &str, first: u32, last: u32) -> Result<Self> {
        if last > MAX_FRAME {
            return Err(Error::out_of_range(key, format!("{first}..{last}"), format!("frames [0, {MAX_FRAME}]")));
        }
        if last < first {
            return Err(Error::invalid(
                key,
                format!("{first}..{last} ends before it starts: B must be >= A (A..B includes both, so {first}..{first} is one frame)"),
            ));
        }
        Ok(Self { first, last })
    }

    /// Parses a frame list as every subcommand's `--frames` takes it: `A..B` (whole frame numbers,
    /// both included) or a count `N` (frames `0..N-1`, N >= 1); `key` names the option in errors.
    pub fn parse(key: &str, s: &str) -> Result<Self> {
        let bad = || {
            Error::invalid(
                key,
                format!(
                    "`{s}` is not a frame count N (frames 0 to N-1) or a range A..B of whole frame numbers \
                     0 <= A <= B, both included (e.g. 48 or 0..47)"
                ),
            )
        };
        let number = |t: &str| -> Result<u32> {
            let t = t.trim();
            if t.is_empty() || !t.bytes().all(|c| c.is_ascii_digit()) {
                return Err(bad());
            }
            // More digits than u32 holds is still a frame number, only too large.
            t.parse::<u32>().map_err(|_| Error::out_of_range(key, s, format!("frames [0, {MAX_FRAME}]")))
        };
        match s.trim().split_once("..") {
            Some((a, b)) => Self::new(key, number(a)?, number(b)?),
            None => match number(s)? {
                0 => Err(Error::invalid(key, "0 frames: give a count N >= 1, or a range A..B")),
                n => Self::new(key, 0, n - 1),
            },
        }
    }

    /// Number of frames (at least 1).
    pub fn len(&self) -> u32 {
        self.last - self.first + 1
    }

    /// Always false: a range holds at least one frame.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The frames in increasing order.
    pub fn iter(&self) -> impl Iterator<Item = u32> {
        self.first..=self.last
    }
}

/// Shard `index` of `count`: the frames `first + index`, `first + index + count`, ... of a range.
///
/// The shards `0/N` to `N-1/N` partition any range, whatever machine or order they run in.
/// `--shard auto` takes `index` and `count` from a batch system's array-job variables
/// (`resolve_shard` in `array_job.rs`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// Which shard, in [0, `count`).
    pub index: u32,
    /// How many shards, in [1, [`MAX_SHARDS`]].
    pub count: u32,
}

impl Shard {
    /// The whole range as one shard.
    pub const WHOLE: Shard = Shard { index: 0, count: 1 };

    /// Parses `I/N` with 0 <= I < N; `key` names the option in errors.
    pub fn parse(key: &str, s: &str) -> Result<Self> {
        let bad = || Error::invalid(key, format!("`{s}` is not I/N with whole numbers 0 <= I < N (e.g. 0/4)"));
        let (i, n) = s.trim().split_once('/').ok_or_else(bad)?;
        let index: u32 = i.trim().parse().map_err(|_| bad())?;
        let count: u32 = n.trim().parse().map_err(|_| bad())?;
        if !(1..=MAX_SHARDS).contains(&count) {
            return Err(Error::out_of_range(format!("{key} count"), count, format!("[1, {MAX_SHARDS}]")));
        }
        if index >= count {
            return Err(Error::out_of_range(
                format!("{key} index"),
                index,
                format!("[0, {}] (shards are numbered from 0)", count - 1),
            ));
        }
        Ok(Self { index, count })
    }

    /// This shard's frames of `range`, in increasing order.
    pub fn frames(&self, range: FrameRange) -> impl Iterator<Item = u32> {
        range.iter().skip(self.index as usize).step_by(self.count as usize)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_are_inclusive_and_refuse_garbage() {
        let r = FrameRange::parse("--frames", "3..5").unwrap();
        assert_eq!(r.iter().collect::<Vec<_>>(), [3, 4, 5]);
        assert_eq!(FrameRange::parse("--frames", "0..0").unwrap().len(), 1);
        // A count N is frames 0 to N-1: the same meaning in render, export and bake.
        assert_eq!(FrameRange::parse("--frames", "48").unwrap(), FrameRange::new("f", 0, 47).unwrap());
        assert!(FrameRange::parse("--frames", "0").unwrap_err().to_string().contains("0 frames"));
        for bad in ["", "5x", "a..b", "-1..4", "1..-4", "1...4", "1..4x", " .. ", "-3", "2.5"] {
            let e = FrameRange::parse("--frames", bad).unwrap_err().to_string();
            assert!(e.starts_with("--frames: `") && e.contains("A..B"), "{bad}: {e}");
        }
        let e = FrameRange::parse("--frames", "9..2").unwrap_err().to_string();
        assert!(e.contains("ends before it starts"), "{e}");
        let e = FrameRange::parse("--frames", "0..99999999999").unwrap_err().to_string();
        assert!(e.contains("outside"), "{e}");
    }

    #[test]
    fn shards_partition_the_range() {
        let r = FrameRange::new("f", 7, 30).unwrap();
        let mut all: Vec<u32> =
            (0..5).flat_map(|i| Shard { index: i, count: 5 }.frames(r).collect::<Vec<_>>()).collect();
        all.sort();
        assert_eq!(all, r.iter().collect::<Vec<_>>());
        assert_eq!(Shard::parse("--shard", "2/3").unwrap().frames(r).take(2).collect::<Vec<_>>(), [9, 12]);
        for bad in ["3/3", "1/0", "x/2", "1", "-1/2"] {
            assert!(Shard::parse("--shard", bad).is_err(), "{bad}");
        }
    }
}
