//! XXH64, the 64-bit xxHash checksum, streamed: what a bake records per file so that `--resume`
//! can tell a complete frame from a damaged one.
//!
//! Why XXH64 and not a CRC or FNV-1a: it reads 32 bytes per step in four independent lanes, so
//! hashing a frame is a small fraction of baking it (a 7 MB frame in well under a millisecond in
//! an optimised build), and it is a published algorithm with a standard tool, so anyone can check a
//! bake by hand: `xxhsum -H1 disp_0042.exr` (Debian's `xxhash` package) prints the checksum
//! `check_0042.json` records. Seed 0, digest printed as 16 lowercase hex digits (big-endian, as
//! `xxhsum` prints it). It detects damage (truncation, zeroed blocks, flipped bits), not tampering.

use std::io::Read;
use std::path::Path;

use crate::error::{Error, Result};

const P1: u64 = 0x9E37_79B1_85EB_CA87;
const P2: u64 = 0xC2B2_AE3D_27D4_EB4F;
const P3: u64 = 0x1656_67B1_9E37_79F9;
const P4: u64 = 0x85EB_CA77_C2B2_AE63;
const P5: u64 = 0x27D4_EB2F_1656_67C5;

/// An XXH64 checksum being computed over bytes given in any number of pieces: the digest depends
/// only on the concatenated bytes, never on how they were split.
#[derive(Clone, Debug)]
pub struct Xxh64 {
    /// The four lane accumulators, used once 32 bytes have been seen.
    lanes: [u64; 4],
    /// Bytes of an unfinished 32-byte stripe.
    pending: [u8; 32],
    /// How many bytes of `pending` are filled, in [0, 32).
    pending_len: usize,
    /// Bytes seen so far.
    total: u64,
}

impl Default for Xxh64 {
    fn default() -> Self {
        Self::new()
    }
}

fn round(acc: u64, input: u64) -> u64 {
    acc.wrapping_add(input.wrapping_mul(P2)).rotate_left(31).wrapping_mul(P1)
}

fn merge_round(acc: u64, lane: u64) -> u64 {
    (acc ^ round(0, lane)).wrapping_mul(P1).wrapping_add(P4)
}

fn u64_at(b: &[u8], at: usize) -> u64 {
    u64::from_le_bytes(b[at..at + 8].try_into().expect("8 bytes"))
}

impl Xxh64 {
    /// A checksum over no bytes yet, seed 0.
    pub fn new() -> Self {
        Self { lanes: [P1.wrapping_add(P2), P2, 0, 0u64.wrapping_sub(P1)], pending: [0; 32], pending_len: 0, total: 0 }
    }

    fn stripe(&mut self, s: &[u8]) {
        for (k, lane) in self.lanes.iter_mut().enumerate() {
            *lane = round(*lane, u64_at(s, 8 * k));
        }
    }

    /// Adds `bytes` to what is checksummed.
    pub fn update(&mut self, mut bytes: &[u8]) {
        self.total += bytes.len() as u64;
        if self.pending_len > 0 {
            let take = (32 - self.pending_len).min(bytes.len());
            self.pending[self.pending_len..self.pending_len + take].copy_from_slice(&bytes[..take]);
            self.pending_len += take;
            bytes = &bytes[take..];
            if self.pending_len < 32 {
                return;
            }
            let stripe = self.pending;
            self.stripe(&stripe);
            self.pending_len = 0;
        }
        let mut chunks = bytes.chunks_exact(32);
        for s in &mut chunks {
            self.stripe(s);
        }
        let rest = chunks.remainder();
        self.pending[..rest.len()].copy_from_slice(rest);
        self.pending_len = rest.len();
    }

    /// The checksum of every byte given so far.
    pub fn digest(&self) -> u64 {
        let [v1, v2, v3, v4] = self.lanes;
        let mut h = if self.total >= 32 {
            let h = v1.rotate_left(1).wrapping_add(v2.rotate_left(7)).wrapping_add(v3.rotate_left(12));
            let h = h.wrapping_add(v4.rotate_left(18));
            [v1, v2, v3, v4].into_iter().fold(h, merge_round)
        } else {
            P5
        };
        h = h.wrapping_add(self.total);
        let mut rest = &self.pending[..self.pending_len];
        while rest.len() >= 8 {
            h ^= round(0, u64_at(rest, 0));
            h = h.rotate_left(27).wrapping_mul(P1).wrapping_add(P4);
            rest = &rest[8..];
        }
        if rest.len() >= 4 {
            let k = u64::from(u32::from_le_bytes(rest[..4].try_into().expect("4 bytes")));
            h ^= k.wrapping_mul(P1);
            h = h.rotate_left(23).wrapping_mul(P2).wrapping_add(P3);
            rest = &rest[4..];
        }
        for &b in rest {
            h ^= u64::from(b).wrapping_mul(P5);
            h = h.rotate_left(11).wrapping_mul(P1);
        }
        h ^= h >> 33;
        h = h.wrapping_mul(P2);
        h ^= h >> 29;
        h = h.wrapping_mul(P3);
        h ^ (h >> 32)
    }
}

/// The XXH64 checksum of `bytes`.
pub fn xxh64(bytes: &[u8]) -> u64 {
    let mut h = Xxh64::new();
    h.update(bytes);
    h.digest()
}

/// The size in bytes and the XXH64 checksum of the file at `path`, read in 1 MiB pieces (a frame's
/// map is never held twice in memory). Errors name the file.
pub fn file_checksum(path: &Path) -> Result<(u64, u64)> {
    let mut file = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
    let mut h = Xxh64::new();
    let mut buf = vec![0u8; 1 << 20];
    loop {
        match file.read(&mut buf) {
            Ok(0) => break,
            Ok(n) => h.update(&buf[..n]),
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(Error::io(path, e)),
        }
    }
    Ok((h.total, h.digest()))
}

/// A checksum as `bake.json`'s neighbours write it: 16 lowercase hex digits, as `xxhsum` prints it.
pub fn hex(digest: u64) -> String {
    format!("{digest:016x}")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Digests printed by `xxhsum -H1` (xxHash 0.8.1, Debian's `xxhash` package) for the same bytes.
    #[test]
    fn digests_are_those_of_the_reference_tool() {
        assert_eq!(hex(xxh64(b"")), "ef46db3751d8e999");
        assert_eq!(hex(xxh64(b"a")), "d24ec4f1a98c6e5b");
        assert_eq!(hex(xxh64(b"abc")), "44bc2cf5ad770999");
        assert_eq!(hex(xxh64(&[0u8; 100])), "17bb1103c92c502f");
        assert_eq!(hex(xxh64(&pattern())), "b260521730b6d8d9");
        let long: Vec<u8> = (0..3_000_000u32).map(|k| (k % 251) as u8).collect();
        assert_eq!(hex(xxh64(&long)), "c121b1d5ab7da7ef");
    }

    /// 1000 bytes that are not a short period: `(k * 2654435761 mod 2^32) >> 13`, low byte.
    fn pattern() -> Vec<u8> {
        (0..1000u32).map(|k| (k.wrapping_mul(2_654_435_761) >> 13) as u8).collect()
    }

    #[test]
    fn the_digest_does_not_depend_on_how_the_bytes_are_split() {
        let bytes = pattern();
        let whole = xxh64(&bytes);
        for split in [1, 3, 7, 31, 32, 33, 64, 999] {
            let mut h = Xxh64::new();
            for piece in bytes.chunks(split) {
                h.update(piece);
            }
            assert_eq!(h.digest(), whole, "pieces of {split}");
        }
        // Every length from 0 to 70 goes through each tail path; one changed byte changes the digest.
        for len in 0..70 {
            let mut other = bytes[..len].to_vec();
            if len > 0 {
                other[len / 2] ^= 1;
                assert_ne!(xxh64(&other), xxh64(&bytes[..len]), "length {len}");
            }
        }
    }

    #[test]
    fn a_file_checksum_is_its_size_and_digest() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("f.bin");
        let bytes: Vec<u8> = (0..3_000_000u32).map(|k| (k % 251) as u8).collect();
        std::fs::write(&path, &bytes).unwrap();
        assert_eq!(file_checksum(&path).unwrap(), (bytes.len() as u64, xxh64(&bytes)));
        let e = file_checksum(&dir.path().join("missing.bin")).unwrap_err().to_string();
        assert!(e.contains("missing.bin"), "{e}");
    }
}
