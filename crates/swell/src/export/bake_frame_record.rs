//! `check_NNNN.json`: the record that frame NNNN of a bake is complete, and its verification on
//! `--resume` (issue 37).
//!
//! A bake writes a frame's maps (each atomically), reads each back for its size and XXH64
//! checksum ([`super::bake_checksum`]), and only then writes the record, atomically, naming every
//! file with its size and checksum and the checksum of the `bake.json` it belongs to. The record is
//! thus the frame's last word: a frame without one was cut short, and a frame whose files do not
//! match theirs has been damaged since (an empty or truncated file, a file copied in from another
//! bake, a disk error). `--resume` bakes every such frame again instead of counting it as done,
//! and a record from another bake (its `bake.json` checksum differs) counts as no record.
//!
//! The record holds nothing but what the frame's bytes determine, so every way of making a bake
//! (sequential, sharded, resumed) writes the same record, byte for byte.

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::bake_checksum::{file_checksum, hex};
use super::write_atomically;
use crate::error::{Error, Result};

/// The record of one complete frame, stored as `check_{frame:04}.json` in the bake directory.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub(crate) struct FrameRecord {
    /// The frame number.
    pub frame: u32,
    /// XXH64 (16 hex digits) of the bytes of the `bake.json` the frame was baked under.
    pub bake_json_xxh64: String,
    /// Every map file of the frame, in the order of `bake.json`'s maps, EXR then PNG.
    pub files: Vec<FileRecord>,
}

/// One file of a frame as it was written.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub(crate) struct FileRecord {
    /// File name within the bake directory, e.g. `disp_0042.exr`.
    pub name: String,
    /// Size in bytes.
    pub bytes: u64,
    /// XXH64 of the file's bytes, 16 hex digits (what `xxhsum -H1 FILE` prints).
    pub xxh64: String,
}

/// The file name of frame `frame`'s record, with at least four digits like the maps.
pub(crate) fn record_name(frame: u32) -> String {
    format!("check_{frame:04}.json")
}

/// Whether `name` is a record file's name (`check_` then at least four digits, `.json`).
pub(crate) fn is_record_name(name: &str) -> bool {
    name.strip_prefix("check_")
        .and_then(|r| r.strip_suffix(".json"))
        .is_some_and(|d| d.len() >= 4 && d.bytes().all(|c| c.is_ascii_digit()))
}

/// Size and checksum of the file `dir/name`, as its record states them.
pub(crate) fn file_record(dir: &Path, name: &str) -> Result<FileRecord> {
    let (bytes, digest) = file_checksum(&dir.join(name))?;
    Ok(FileRecord { name: name.to_string(), bytes, xxh64: hex(digest) })
}

/// Writes `record` to `dir`, atomically; the text is a pure function of the record.
pub(crate) fn write_record(dir: &Path, record: &FrameRecord) -> Result<()> {
    let path = dir.join(record_name(record.frame));
    let mut text = serde_json::to_vec_pretty(record).expect("a record always serialises");
    text.push(b'\n');
    write_atomically(&path, |out| out.write_all(&text).map_err(|e| Error::io(&path, e)))
}

/// Checks that frame `frame` of the bake in `dir` (whose `bake.json` has checksum
/// `bake_json_xxh64`) is complete: its record exists, belongs to this bake, lists exactly `names`
/// (the frame's files, in order), and every file has the recorded size and checksum. `Err` holds
/// the first reason it is not, in words naming the file, for the user.
pub(crate) fn verify_frame(dir: &Path, frame: u32, names: &[String], bake_json_xxh64: &str) -> Result<(), String> {
    let record_path = dir.join(record_name(frame));
    let text = match std::fs::read(&record_path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Err(format!("{} is missing (the frame was cut short)", record_name(frame)))
        }
        Err(e) => return Err(format!("{} cannot be read: {e}", record_name(frame))),
    };
    let record: FrameRecord =
        serde_json::from_slice(&text).map_err(|e| format!("{} is not a frame record ({e})", record_name(frame)))?;
    if record.frame != frame {
        return Err(format!("{} is the record of frame {}, not {frame}", record_name(frame), record.frame));
    }
    if record.bake_json_xxh64 != bake_json_xxh64 {
        return Err(format!("{} belongs to another bake", record_name(frame)));
    }
    let recorded: Vec<&str> = record.files.iter().map(|f| f.name.as_str()).collect();
    if recorded != names.iter().map(String::as_str).collect::<Vec<_>>() {
        return Err(format!("{} lists other files ({})", record_name(frame), recorded.join(", ")));
    }
    for want in &record.files {
        let path = dir.join(&want.name);
        // The size first: a missing, empty or truncated file is found without reading it.
        let size = match std::fs::metadata(&path) {
            Ok(m) => m.len(),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Err(format!("{} is missing", want.name)),
            Err(e) => return Err(format!("{} cannot be read: {e}", want.name)),
        };
        if size != want.bytes {
            return Err(format!("{} is {size} bytes, its record says {}", want.name, want.bytes));
        }
        let got = file_record(dir, &want.name).map_err(|e| e.to_string())?;
        if got != *want {
            return Err(format!("{}'s checksum is {}, its record says {}", want.name, got.xxh64, want.xxh64));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn records_verify_their_frame_and_name_what_is_wrong() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        std::fs::write(d.join("disp_0007.exr"), b"displacement").unwrap();
        std::fs::write(d.join("normal_0007.exr"), b"normals").unwrap();
        let names = vec!["disp_0007.exr".to_string(), "normal_0007.exr".to_string()];
        let record = FrameRecord {
            frame: 7,
            bake_json_xxh64: "00000000000000aa".into(),
            files: names.iter().map(|n| file_record(d, n).unwrap()).collect(),
        };
        assert!(verify_frame(d, 7, &names, "00000000000000aa").unwrap_err().contains("check_0007.json is missing"));
        write_record(d, &record).unwrap();
        assert!(d.join("check_0007.json").is_file());
        assert_eq!(verify_frame(d, 7, &names, "00000000000000aa"), Ok(()));
        // Another bake's record, or one for other files, is not this frame's.
        assert!(verify_frame(d, 7, &names, "00000000000000bb").unwrap_err().contains("another bake"));
        assert!(verify_frame(d, 7, &names[..1], "00000000000000aa").unwrap_err().contains("lists other files"));
        // Emptied, truncated, changed in place, removed: each is named.
        let check = |what: &str| verify_frame(d, 7, &names, "00000000000000aa").unwrap_err().contains(what);
        std::fs::write(d.join("normal_0007.exr"), b"").unwrap();
        assert!(check("normal_0007.exr is 0 bytes, its record says 7"));
        std::fs::write(d.join("normal_0007.exr"), b"normalZ").unwrap();
        assert!(check("normal_0007.exr's checksum is"));
        std::fs::remove_file(d.join("normal_0007.exr")).unwrap();
        assert!(check("normal_0007.exr is missing"));
        std::fs::write(d.join("check_0007.json"), b"{\"frame\": 7").unwrap();
        assert!(check("check_0007.json is not a frame record"));
    }

    #[test]
    fn record_names_have_at_least_four_digits() {
        assert_eq!(record_name(3), "check_0003.json");
        assert_eq!(record_name(12345), "check_12345.json");
        assert!(is_record_name("check_0003.json") && is_record_name("check_12345.json"));
        assert!(!is_record_name("check_003.json") && !is_record_name("check_00a3.json") && !is_record_name("x.json"));
    }
}
