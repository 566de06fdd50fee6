//! Atomic file output: a file appears under its final name complete, or not at all.

use std::io::{BufWriter, Write};
use std::path::Path;

use crate::error::{Error, Result};

/// Writes `path` by calling `write` on a temporary file in the same directory, then renaming it
/// over `path`. If `write` fails, or the process dies, no file exists under `path` (an existing one
/// is left untouched) and the temporary file is removed.
pub fn write_atomically(path: &Path, write: impl FnOnce(&mut dyn Write) -> Result<()>) -> Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let tmp = tempfile::Builder::new()
        .prefix(".swell-")
        .suffix(".tmp")
        .tempfile_in(dir)
        .map_err(|e| Error::io(path, without_temp_path(e)))?;
    {
        let mut out = BufWriter::new(tmp.as_file());
        write(&mut out)?;
        out.flush().map_err(|e| Error::io(path, e))?;
    }
    // tempfile creates 0600 files; outputs are ordinary documents, readable like any other.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let perms = std::fs::Permissions::from_mode(0o644);
        tmp.as_file().set_permissions(perms).map_err(|e| Error::io(path, e))?;
    }
    tmp.as_file().sync_all().map_err(|e| Error::io(path, e))?;
    tmp.persist(path).map_err(|e| Error::io(path, e.error))?;
    Ok(())
}

/// tempfile's error without its " at path .swell-XXXX.tmp": the user asked for the output, which
/// the message names instead. The OS's own words stay ("No such file or directory (os error 2)").
fn without_temp_path(e: std::io::Error) -> std::io::Error {
    let text = e.to_string();
    let text = text.split(" at path ").next().unwrap_or(&text).to_string();
    std::io::Error::new(e.kind(), text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_failed_write_leaves_nothing_behind() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.bin");
        let r = write_atomically(&path, |w| {
            w.write_all(b"partial").unwrap();
            Err(Error::invalid("test", "fails half way"))
        });
        assert!(r.is_err());
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
        write_atomically(&path, |w| w.write_all(b"whole").map_err(|e| Error::io("x", e))).unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"whole");
    }

    #[test]
    fn a_missing_directory_is_an_error_naming_the_file() {
        let e = write_atomically(Path::new("/nonexistent-dir/x.png"), |_| Ok(())).unwrap_err();
        assert!(e.to_string().starts_with("/nonexistent-dir/x.png"), "{e}");
        assert!(!e.to_string().contains(".swell-"), "the temporary file is not the user's: {e}");
        assert!(e.to_string().contains("No such file or directory"), "the OS's words stay: {e}");
    }
}
