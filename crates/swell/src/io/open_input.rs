//! Opening the files swell reads (scene files, heightmaps and their sidecars, water and foam
//! textures, `--obj` meshes, `--camera` and `--light` files) so that none can hang a run (issue 37).
//!
//! A plain `open` of a FIFO (named pipe) blocks until some process opens it for writing, which
//! may be never: the CLI, a C program and a Python interpreter (where Ctrl-C cannot interrupt a
//! system call made without the GIL) would hang for good. On unix, [`open_input`] opens with
//! `O_NONBLOCK`, which returns at once whether or not a writer exists, then clears `O_NONBLOCK`
//! so that reads behave as usual: a read of a FIFO or pipe with a writer waits for its data
//! (`--scene <(...)`, `/dev/stdin`), and a read of one with no writer returns end of file at
//! once (POSIX), which [`read_input`] and [`open_seekable`] report as such. A writer must
//! therefore have the FIFO open by the time it is read, as `<(...)` and a writer started first
//! do; one that opens it only later finds no reader.

use std::fs::File;
use std::io::{BufRead, BufReader, Cursor, Read, Seek, SeekFrom};
use std::path::Path;

use crate::error::{Error, Result};

/// Most bytes read into memory from an input that cannot seek (a FIFO, a pipe, a device) before
/// decoding it as an image: 256 MiB. Image decoders seek, so such an input is read whole first;
/// a regular file is decoded as it is read and is not bound by this. The largest heightmap
/// (`MAX_HEIGHTMAP_BYTES`, 64 MiB decoded) fits with room for a PNG that does not compress;
/// `/dev/zero` given as an image is refused after this many bytes instead of filling memory.
pub const MAX_PIPED_BYTES: u64 = 256 << 20;

/// Opens `path` for reading without ever blocking, even on a FIFO that no process writes to
/// (see the module documentation), and refuses a directory ("is a directory, not a file").
/// Errors name `path`.
pub fn open_input(path: &Path) -> Result<File> {
    let file = open_without_waiting(path).map_err(|e| Error::io(path, e))?;
    let meta = file.metadata().map_err(|e| Error::io(path, e))?;
    if meta.is_dir() {
        return Err(Error::io(
            path,
            std::io::Error::new(std::io::ErrorKind::IsADirectory, "is a directory, not a file"),
        ));
    }
    Ok(file)
}

/// Reads the whole of `path` ([`open_input`]), but at most `max_bytes` + 1 bytes: a result longer
/// than `max_bytes` means the input is over the caller's limit, which the caller refuses naming
/// that limit, so `/dev/zero` cannot exhaust memory. A FIFO or pipe that gives no bytes at all
/// (no writer had it open, or the writer sent nothing) is an error saying so, not an empty file
/// that a parser would then call malformed.
pub fn read_input(path: &Path, max_bytes: u64) -> Result<Vec<u8>> {
    read_open(open_input(path)?, path, max_bytes)
}

/// An input an image decoder may seek in: the file itself when `path` is a regular file, else its
/// bytes read into memory (see [`open_seekable`]).
#[derive(Debug)]
pub enum SeekableInput {
    /// A regular file, read through a buffer as the decoder goes.
    File(BufReader<File>),
    /// The whole of a FIFO, pipe or device, read before decoding.
    Memory(Cursor<Vec<u8>>),
}

/// Opens `path` ([`open_input`]) for a decoder that seeks: a regular file as it is, anything else
/// (a FIFO or pipe with a writer, `/dev/stdin`, a device) read whole into memory, refused past
/// [`MAX_PIPED_BYTES`]. A FIFO or pipe with no data is refused as in [`read_input`].
pub fn open_seekable(path: &Path) -> Result<SeekableInput> {
    let file = open_input(path)?;
    let regular = file.metadata().map_err(|e| Error::io(path, e))?.is_file();
    if regular {
        return Ok(SeekableInput::File(BufReader::new(file)));
    }
    let bytes = read_open(file, path, MAX_PIPED_BYTES)?;
    if bytes.len() as u64 > MAX_PIPED_BYTES {
        return Err(Error::Parse {
            path: path.display().to_string(),
            message: format!(
                "over the limit of {MAX_PIPED_BYTES} bytes read from a pipe, FIFO or device \
                 (MAX_PIPED_BYTES); give a regular file"
            ),
        });
    }
    Ok(SeekableInput::Memory(Cursor::new(bytes)))
}

impl Read for SeekableInput {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        match self {
            SeekableInput::File(f) => f.read(buf),
            SeekableInput::Memory(m) => m.read(buf),
        }
    }
}

impl BufRead for SeekableInput {
    fn fill_buf(&mut self) -> std::io::Result<&[u8]> {
        match self {
            SeekableInput::File(f) => f.fill_buf(),
            SeekableInput::Memory(m) => m.fill_buf(),
        }
    }

    fn consume(&mut self, amount: usize) {
        match self {
            SeekableInput::File(f) => f.consume(amount),
            SeekableInput::Memory(m) => m.consume(amount),
        }
    }
}

impl Seek for SeekableInput {
    fn seek(&mut self, pos: SeekFrom) -> std::io::Result<u64> {
        match self {
            SeekableInput::File(f) => f.seek(pos),
            SeekableInput::Memory(m) => m.seek(pos),
        }
    }
}

/// At most `max_bytes` + 1 bytes of the open `file`, refusing a FIFO or pipe that gave none.
fn read_open(file: File, path: &Path, max_bytes: u64) -> Result<Vec<u8>> {
    let mut bytes = Vec::new();
    (&file).take(max_bytes.saturating_add(1)).read_to_end(&mut bytes).map_err(|e| Error::io(path, e))?;
    if bytes.is_empty() && is_fifo(&file) {
        return Err(Error::io(
            path,
            std::io::Error::new(
                std::io::ErrorKind::UnexpectedEof,
                "is a FIFO or pipe that no process writes to (or whose writer sent nothing): \
                 nothing to read; start the writer first, or give a regular file",
            ),
        ));
    }
    Ok(bytes)
}

/// Whether `file` is a FIFO or pipe (named or not): only those end at once when no one writes.
#[cfg(unix)]
fn is_fifo(file: &File) -> bool {
    use std::os::unix::fs::FileTypeExt;
    file.metadata().is_ok_and(|m| m.file_type().is_fifo())
}

#[cfg(not(unix))]
fn is_fifo(_file: &File) -> bool {
    false
}

/// `open(path, O_RDONLY | O_NONBLOCK)`, then `O_NONBLOCK` cleared: the open cannot wait for a
/// FIFO's writer, the reads after it are the usual blocking ones.
#[cfg(unix)]
fn open_without_waiting(path: &Path) -> std::io::Result<File> {
    use std::os::fd::AsRawFd;
    use std::os::unix::fs::OpenOptionsExt;
    let file = std::fs::OpenOptions::new().read(true).custom_flags(libc::O_NONBLOCK).open(path)?;
    let fd = file.as_raw_fd();
    // SAFETY: `fd` is the open descriptor `file` owns for the whole of both calls; F_GETFL and
    // F_SETFL read and set its status flags and touch no memory of ours.
    let flags = unsafe { libc::fcntl(fd, libc::F_GETFL) };
    if flags < 0 || unsafe { libc::fcntl(fd, libc::F_SETFL, flags & !libc::O_NONBLOCK) } < 0 {
        return Err(std::io::Error::last_os_error());
    }
    Ok(file)
}

/// Elsewhere there are no FIFOs that block an open: the plain open.
#[cfg(not(unix))]
fn open_without_waiting(path: &Path) -> std::io::Result<File> {
    File::open(path)
}

// The tests make temporary directories with tempfile, which comes with `render`.
#[cfg(all(test, unix, feature = "render"))]
mod tests {
    use super::*;
    use std::io::Write;
    use std::time::{Duration, Instant};

    /// A FIFO at `dir/name`, made with mkfifo(3).
    fn fifo(dir: &Path, name: &str) -> std::path::PathBuf {
        let path = dir.join(name);
        let c = std::ffi::CString::new(path.as_os_str().as_encoded_bytes()).unwrap();
        // SAFETY: `c` is a NUL-terminated path that outlives the call.
        assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0, "mkfifo {}", path.display());
        path
    }

    /// Runs `f` on another thread and fails the test if it has not returned within 10 s (a hang
    /// would otherwise block the test run for good).
    fn promptly<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || tx.send(f()).ok());
        rx.recv_timeout(Duration::from_secs(10)).expect("blocked on a FIFO for over 10 s")
    }

    #[test]
    fn a_fifo_without_a_writer_is_refused_at_once_naming_it() {
        let dir = tempfile::tempdir().unwrap();
        let path = fifo(dir.path(), "scene.toml");
        let start = Instant::now();
        let p = path.clone();
        let e = promptly(move || read_input(&p, 100).unwrap_err().to_string());
        assert!(e.starts_with(&format!("{}: is a FIFO or pipe that no process writes to", path.display())), "{e}");
        let p = path.clone();
        let e = promptly(move || open_seekable(&p).unwrap_err().to_string());
        assert!(e.contains("nothing to read"), "{e}");
        assert!(start.elapsed() < Duration::from_secs(5));
        // Opening alone succeeds: only reading tells there is nothing.
        let p = path.clone();
        assert!(promptly(move || open_input(&p).is_ok()));
    }

    #[test]
    fn a_fifo_with_a_writer_is_read_as_usual_and_can_seek_from_memory() {
        let dir = tempfile::tempdir().unwrap();
        let path = fifo(dir.path(), "data");
        // A writer opened first, as `<(...)` has it: opening read-write never waits (Linux), and
        // makes the write-only open below find a reader; the writer then outlives the read-write
        // descriptor, so the reader sees its data and then end of file.
        let rw = std::fs::OpenOptions::new().read(true).write(true).open(&path).unwrap();
        let mut w = std::fs::OpenOptions::new().write(true).open(&path).unwrap();
        drop(rw);
        let p = path.clone();
        let reader = std::thread::spawn(move || read_input(&p, 100));
        // Writing before the reader has opened fails with EPIPE and writes nothing: retry.
        let deadline = Instant::now() + Duration::from_secs(10);
        while let Err(e) = w.write_all(b"version = 1\n") {
            assert_eq!(e.kind(), std::io::ErrorKind::BrokenPipe);
            assert!(Instant::now() < deadline, "no reader opened the FIFO");
            std::thread::sleep(Duration::from_millis(5));
        }
        drop(w);
        assert_eq!(reader.join().unwrap().unwrap(), b"version = 1\n");
    }

    #[test]
    fn a_device_that_cannot_seek_is_read_into_memory_within_the_limit() {
        let mut input = open_seekable(Path::new("/dev/null")).unwrap();
        assert!(matches!(input, SeekableInput::Memory(_)));
        let mut all = Vec::new();
        input.read_to_end(&mut all).unwrap();
        assert!(all.is_empty());
        assert_eq!(input.seek(SeekFrom::Start(0)).unwrap(), 0);
    }

    #[test]
    fn limits_directories_and_regular_files() {
        let dir = tempfile::tempdir().unwrap();
        let e = read_input(dir.path(), 10).unwrap_err().to_string();
        assert_eq!(e, format!("{}: is a directory, not a file", dir.path().display()));
        let path = dir.path().join("f.txt");
        std::fs::write(&path, b"0123456789abc").unwrap();
        assert_eq!(read_input(&path, 100).unwrap(), b"0123456789abc");
        // One byte past the limit, no more, tells the caller it is over.
        assert_eq!(read_input(&path, 4).unwrap(), b"01234");
        assert!(matches!(open_seekable(&path).unwrap(), SeekableInput::File(_)));
        // An empty regular file is empty, not an error: the parser says what it lacks.
        std::fs::write(&path, b"").unwrap();
        assert_eq!(read_input(&path, 4).unwrap(), b"");
        let e = read_input(&dir.path().join("missing"), 4).unwrap_err();
        assert!(matches!(&e, Error::Io { source, .. } if source.kind() == std::io::ErrorKind::NotFound), "{e}");
    }
}
