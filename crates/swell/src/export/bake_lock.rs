//! `bake.lock`: a bake directory in use says by whom, so that a second bake of something else
//! cannot mix its frames into it (issue 37).
//!
//! **One lock per shard, one bake per directory.** Shards of one bake run side by side into one
//! directory by design (render farms: N processes on N machines), so the lock cannot be one file
//! per directory. Each process holds the lock of its own shard: `bake.lock` for a whole bake,
//! `bake.I-of-N.lock` for shard I/N. A lock file records its holder (process id, host name, start
//! time, the process's start tick on Linux, shard, command line) and the XXH64 checksum of the
//! `bake.json` it bakes, and is created atomically with that content (written to a temporary
//! file, then hard-linked to its name, which fails if the name exists). A new bake then
//!
//! 1. takes its shard's lock: if another live process holds it, the bake is refused naming that
//!    holder, whatever it bakes (the same shard twice is a mistake: two processes would do the
//!    same work);
//! 2. looks at every other lock in the directory: a live holder baking *another* `bake.json` means
//!    another bake is using the directory, and the new bake is refused (its own lock removed),
//!    naming the holder; holders of the *same* `bake.json` are this bake's other shards, welcome.
//!
//! Two bakes that start at the same moment each see the other's lock in step 2 (each creates its
//! own before looking), so at most one of them goes on, never both.
//!
//! **Stale locks.** A lock is stale when its holder no longer runs: the lock names this host and
//! `/proc/PID` does not exist, is a zombie, or started at another tick than the lock records (the
//! process id was reused). A stale lock (left by a bake killed with SIGKILL, or by a crash) is
//! removed with a note, and the bake goes on. A holder on another host cannot be looked up: its
//! lock is treated as live, except that the same shard of the same bake takes it over with a note
//! (a farm's retry on another machine after a node was lost; should the first still run, both
//! write the same bytes). Where there is no `/proc` (not Linux), every lock is treated as live
//! and the message says to delete it if its holder is gone.
//!
//! The lock is removed when the [`BakeLock`] is dropped: at the end of a bake, after an error, and
//! as a SIGINT unwinds out of the bake. It is advisory: it guards against mistakes and a batch
//! system's duplicates, not against a program that ignores it.

use std::io::Write;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::frame_range::Shard;
use crate::error::{Error, Result};

/// Longest command line a lock records, in characters (the rest is cut, with `…`).
pub const MAX_LOCK_COMMAND_CHARS: usize = 2000;

/// Who holds a bake directory's lock: the content of a lock file, as JSON.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct LockHolder {
    /// Process id of the bake.
    pub pid: u32,
    /// Host name of the machine it runs on (`/proc/sys/kernel/hostname`, else `$HOSTNAME`).
    pub host: String,
    /// When it took the lock, UTC, `YYYY-MM-DDTHH:MM:SSZ`.
    pub started_utc: String,
    /// The process's start time in clock ticks since boot (`/proc/PID/stat`, field 22), on Linux:
    /// a process id reused by another program has another, so the lock is known to be stale.
    pub process_start_ticks: Option<u64>,
    /// The shard it bakes, `I/N` (`0/1` for a whole bake).
    pub shard: String,
    /// Its command line, arguments separated by spaces, at most [`MAX_LOCK_COMMAND_CHARS`].
    pub command: String,
    /// XXH64 (16 hex digits) of the `bake.json` it bakes: equal for the shards of one bake.
    pub bake_json_xxh64: String,
}

impl LockHolder {
    /// This process, baking `shard` of the bake whose `bake.json` has checksum `bake_json_xxh64`.
    fn current(shard: Shard, bake_json_xxh64: &str) -> Self {
        let pid = std::process::id();
        let mut command = std::env::args_os()
            .map(|a| {
                let a = a.to_string_lossy().into_owned();
                if a.is_empty() || a.contains(char::is_whitespace) {
                    format!("'{a}'")
                } else {
                    a
                }
            })
            .collect::<Vec<_>>()
            .join(" ");
        if command.chars().count() > MAX_LOCK_COMMAND_CHARS {
            command = command.chars().take(MAX_LOCK_COMMAND_CHARS).collect::<String>() + "…";
        }
        Self {
            pid,
            host: host_name(),
            started_utc: utc_now(),
            process_start_ticks: process_start_ticks(pid),
            shard: format!("{}/{}", shard.index, shard.count),
            command,
            bake_json_xxh64: bake_json_xxh64.into(),
        }
    }

    /// The holder in words, for messages: `process 123 on host h, started T, shard 0/1: swell bake ...`.
    pub fn describe(&self) -> String {
        format!(
            "process {} on host {}, started {}, shard {}: `{}`",
            self.pid, self.host, self.started_utc, self.shard, self.command
        )
    }
}

/// The lock file name of `shard`: `bake.lock` for a whole bake, `bake.I-of-N.lock` for a shard.
pub fn lock_name(shard: Shard) -> String {
    if shard.count == 1 {
        "bake.lock".into()
    } else {
        format!("bake.{}-of-{}.lock", shard.index, shard.count)
    }
}

/// Whether `name` is a lock file's name ([`lock_name`] of some shard).
fn is_lock_name(name: &str) -> bool {
    name == "bake.lock"
        || name.strip_prefix("bake.").and_then(|r| r.strip_suffix(".lock")).is_some_and(|r| {
            r.split_once("-of-")
                .is_some_and(|(i, n)| [i, n].iter().all(|d| !d.is_empty() && d.bytes().all(|c| c.is_ascii_digit())))
        })
}

/// Whether a lock's holder still runs, as far as this machine can tell.
#[derive(Clone, Debug, PartialEq, Eq)]
enum Liveness {
    /// It runs on this host.
    Running,
    /// It does not run any more; why, in words.
    Gone(String),
    /// It cannot be looked up from here; why, in words.
    Unknown(String),
}

fn liveness(h: &LockHolder) -> Liveness {
    let here = host_name();
    if h.host != here {
        return Liveness::Unknown(format!(
            "it runs on host {}, not this one ({here}), and swell cannot look up another host's processes",
            h.host
        ));
    }
    if !Path::new("/proc/self/stat").exists() {
        return Liveness::Unknown("this system has no /proc to look its process up in".into());
    }
    match (process_start_ticks(h.pid), h.process_start_ticks) {
        (None, _) => Liveness::Gone(format!("process {} no longer runs", h.pid)),
        (Some(now), Some(then)) if now != then => {
            Liveness::Gone(format!("process {} is another program now (the id was reused)", h.pid))
        }
        _ => Liveness::Running,
    }
}

/// The lock a bake holds on its directory and shard; dropping it removes the lock file (if it is
/// still this holder's: a lock taken over from here by another host is left to that host).
#[derive(Debug)]
pub struct BakeLock {
    path: PathBuf,
    holder: LockHolder,
}

impl BakeLock {
    /// Takes the lock of `shard` in `dir` (which must exist) for the bake whose `bake.json` has
    /// checksum `bake_json_xxh64`, as the module documentation describes. Stale locks removed and
    /// locks taken over are described in `notes`. Refusals are [`Error::Invalid`] for `--out`,
    /// naming the lock file and its holder; nothing but this process's own lock (removed again on
    /// a refusal) is ever written.
    pub fn acquire(dir: &Path, shard: Shard, bake_json_xxh64: &str, notes: &mut Vec<String>) -> Result<Self> {
        let me = LockHolder::current(shard, bake_json_xxh64);
        let path = dir.join(lock_name(shard));
        let mut tries = 0;
        loop {
            tries += 1;
            if tries > 10 {
                return Err(Error::invalid(
                    "--out",
                    format!("{}: other processes keep taking and removing this lock; try again", path.display()),
                ));
            }
            match create_exclusive(&path, &me) {
                Ok(()) => break,
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {}
                Err(e) => return Err(Error::io(&path, e)),
            }
            let held = match read_holder(&path)? {
                None => continue, // released meanwhile
                Some(Err(why)) => return Err(unreadable_lock(dir, &path, &why)),
                Some(Ok(h)) => h,
            };
            match liveness(&held) {
                Liveness::Gone(why) => {
                    if remove_if_still(&path, &held)? {
                        notes.push(format!("removed the stale lock {} of {} ({why})", path.display(), held.describe()));
                    }
                }
                Liveness::Running => return Err(in_use(dir, &path, &held, &me, None)),
                Liveness::Unknown(why) => {
                    if held.bake_json_xxh64 != me.bake_json_xxh64 || held.shard != me.shard {
                        return Err(in_use(dir, &path, &held, &me, Some(&why)));
                    }
                    if remove_if_still(&path, &held)? {
                        notes.push(format!(
                            "took over the lock {} of {}: {why}; it baked this same shard of this same bake, so \
                             should it still run, both write the same bytes",
                            path.display(),
                            held.describe()
                        ));
                    }
                }
            }
        }
        let lock = Self { path, holder: me };
        // Every other lock: the shards of this bake are welcome, another bake is not.
        let own = lock_name(shard);
        let entries = std::fs::read_dir(dir).map_err(|e| Error::io(dir, e))?;
        let mut others: Vec<PathBuf> = entries
            .filter_map(|e| e.ok())
            .filter(|e| e.file_name().to_str().is_some_and(|n| n != own && is_lock_name(n)))
            .map(|e| e.path())
            .collect();
        others.sort();
        for other in others {
            let held = match read_holder(&other)? {
                None => continue,
                Some(Err(why)) => return Err(unreadable_lock(dir, &other, &why)),
                Some(Ok(h)) => h,
            };
            if held.bake_json_xxh64 == lock.holder.bake_json_xxh64 {
                continue;
            }
            match liveness(&held) {
                Liveness::Gone(why) => {
                    if remove_if_still(&other, &held)? {
                        notes.push(format!(
                            "removed the stale lock {} of {} ({why})",
                            other.display(),
                            held.describe()
                        ));
                    }
                }
                Liveness::Running => return Err(in_use(dir, &other, &held, &lock.holder, None)),
                Liveness::Unknown(why) => return Err(in_use(dir, &other, &held, &lock.holder, Some(&why))),
            }
        }
        Ok(lock)
    }

    /// The lock file.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// This process as the lock records it.
    pub fn holder(&self) -> &LockHolder {
        &self.holder
    }
}

impl Drop for BakeLock {
    fn drop(&mut self) {
        // Only our own: a lock taken over by another host's retry is that process's now.
        if let Ok(Some(Ok(h))) = read_holder(&self.path) {
            if h == self.holder {
                let _ = std::fs::remove_file(&self.path);
            }
        }
    }
}

/// The refusal of `me` for a directory in use by `held` (its lock at `lock`); `unknown` says why
/// its liveness cannot be checked from here.
fn in_use(dir: &Path, lock: &Path, held: &LockHolder, me: &LockHolder, unknown: Option<&str>) -> Error {
    let what = if held.bake_json_xxh64 == me.bake_json_xxh64 {
        "this same bake (the same bake.json) of this shard"
    } else {
        "another bake (another bake.json)"
    };
    let advice = match unknown {
        None => format!(
            "wait for it to end, or bake into another directory (if that process is not a bake into {}, delete {})",
            dir.display(),
            lock.display()
        ),
        Some(why) => format!(
            "{why}, so it may still run; if it does not, delete {}, or bake into another directory",
            lock.display()
        ),
    };
    Error::invalid(
        "--out",
        format!("{} is in use by {what}: {} is held by {}; {advice}", dir.display(), lock.display(), held.describe()),
    )
}

fn unreadable_lock(dir: &Path, lock: &Path, why: &str) -> Error {
    Error::invalid(
        "--out",
        format!(
            "{} is not a lock swell can read ({why}); if no bake is running into {}, delete it",
            lock.display(),
            dir.display()
        ),
    )
}

/// Creates `path` holding `holder`, failing with `AlreadyExists` if it exists. The content is
/// written to a temporary file first and hard-linked to `path`, so a lock never exists without
/// its holder (a crash cannot leave an empty lock); where hard links are not supported, the file
/// is created exclusively and then written.
fn create_exclusive(path: &Path, holder: &LockHolder) -> std::io::Result<()> {
    let dir = path.parent().unwrap_or(Path::new("."));
    let mut text = serde_json::to_vec_pretty(holder).expect("a lock holder always serialises");
    text.push(b'\n');
    let tmp = tempfile::Builder::new().prefix(".swell-").suffix(".tmp").tempfile_in(dir)?;
    tmp.as_file().write_all(&text)?;
    tmp.as_file().sync_all()?;
    match std::fs::hard_link(tmp.path(), path) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => Err(e),
        Err(_) => {
            let mut f = std::fs::OpenOptions::new().write(true).create_new(true).open(path)?;
            f.write_all(&text)?;
            f.sync_all()
        }
    }
}

/// The holder recorded in the lock at `path`: `None` if there is no such file, `Some(Err(why))`
/// if it is not a lock swell wrote.
fn read_holder(path: &Path) -> Result<Option<std::result::Result<LockHolder, String>>> {
    match std::fs::read(path) {
        Ok(bytes) if bytes.is_empty() => Ok(Some(Err("it is empty".into()))),
        Ok(bytes) => Ok(Some(serde_json::from_slice(&bytes).map_err(|e| format!("not a bake lock: {e}")))),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
        Err(e) => Err(Error::io(path, e)),
    }
}

/// Removes the lock at `path` if it still records `held`: it is first renamed away (only one
/// process can move a given file), then checked; a lock that changed meanwhile (another process
/// took it) is put back. Returns whether `held`'s lock was removed.
fn remove_if_still(path: &Path, held: &LockHolder) -> Result<bool> {
    let dir = path.parent().unwrap_or(Path::new("."));
    let aside = dir.join(format!(
        ".swell-stale-{}-{}.tmp",
        std::process::id(),
        std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_nanos())
    ));
    match std::fs::rename(path, &aside) {
        Ok(()) => {}
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(false),
        Err(e) => return Err(Error::io(path, e)),
    }
    let same = matches!(read_holder(&aside), Ok(Some(Ok(ref h))) if h == held);
    if !same {
        // Someone else's fresh lock: back under its name, unless a third took the name meanwhile.
        let _ = std::fs::hard_link(&aside, path);
    }
    std::fs::remove_file(&aside).map_err(|e| Error::io(&aside, e))?;
    Ok(same)
}

/// This machine's host name: `/proc/sys/kernel/hostname`, else `$HOSTNAME` or `$COMPUTERNAME`,
/// else `unknown`.
fn host_name() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .ok()
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
        .or_else(|| std::env::var("HOSTNAME").ok().filter(|s| !s.is_empty()))
        .or_else(|| std::env::var("COMPUTERNAME").ok().filter(|s| !s.is_empty()))
        .unwrap_or_else(|| "unknown".into())
}

/// The start time (clock ticks since boot, field 22 of `/proc/PID/stat`) of process `pid`, if it
/// exists and is not a zombie (a killed process its parent has not reaped yet).
fn process_start_ticks(pid: u32) -> Option<u64> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    // `pid (comm) state ...`: comm may hold spaces and parentheses, so split after the last ')'.
    let rest = &stat[stat.rfind(')')? + 1..];
    let fields: Vec<&str> = rest.split_whitespace().collect();
    if matches!(fields.first(), Some(&"Z") | Some(&"X") | Some(&"x")) {
        return None;
    }
    // Fields 3 (state) onwards: field 22 is the 20th.
    fields.get(19)?.parse().ok()
}

/// Now, UTC, as `YYYY-MM-DDTHH:MM:SSZ`.
fn utc_now() -> String {
    let secs = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_secs());
    utc_text(secs)
}

/// `secs` after 1970-01-01T00:00:00Z as `YYYY-MM-DDTHH:MM:SSZ` (the proleptic Gregorian calendar:
/// days to civil date after Howard Hinnant's `civil_from_days`).
fn utc_text(secs: u64) -> String {
    let days = (secs / 86_400) as i64;
    let rem = secs % 86_400;
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!("{year:04}-{month:02}-{day:02}T{:02}:{:02}:{:02}Z", rem / 3600, rem / 60 % 60, rem % 60)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn whole() -> Shard {
        Shard::WHOLE
    }

    #[test]
    fn utc_dates_are_civil_dates() {
        assert_eq!(utc_text(0), "1970-01-01T00:00:00Z");
        assert_eq!(utc_text(951_782_400), "2000-02-29T00:00:00Z");
        assert_eq!(utc_text(1_700_000_000), "2023-11-14T22:13:20Z");
        assert_eq!(utc_text(4_102_444_799), "2099-12-31T23:59:59Z");
    }

    #[test]
    fn lock_names_are_per_shard() {
        assert_eq!(lock_name(whole()), "bake.lock");
        assert_eq!(lock_name(Shard { index: 3, count: 16 }), "bake.3-of-16.lock");
        assert!(is_lock_name("bake.lock") && is_lock_name("bake.3-of-16.lock"));
        assert!(!is_lock_name("bake.json") && !is_lock_name("bake.x-of-2.lock") && !is_lock_name("bake.-of-2.lock"));
    }

    #[test]
    fn this_process_is_running_and_a_dead_one_is_gone() {
        let me = LockHolder::current(whole(), "00");
        assert_eq!(liveness(&me), Liveness::Running);
        assert!(me.process_start_ticks.is_some());
        // A child that has exited and been reaped.
        let mut child = std::process::Command::new("true").spawn().unwrap();
        let pid = child.id();
        child.wait().unwrap();
        let dead = LockHolder { pid, ..me.clone() };
        assert!(matches!(liveness(&dead), Liveness::Gone(_)), "{:?}", liveness(&dead));
        // Our own id with another start tick: the id was reused.
        let reused = LockHolder { process_start_ticks: Some(me.process_start_ticks.unwrap() + 1), ..me.clone() };
        assert!(matches!(liveness(&reused), Liveness::Gone(w) if w.contains("reused")));
        let elsewhere = LockHolder { host: "another-host.example".into(), ..me };
        assert!(matches!(liveness(&elsewhere), Liveness::Unknown(w) if w.contains("another-host.example")));
    }

    #[test]
    fn a_held_lock_refuses_a_second_taker_and_drop_releases_it() {
        let dir = tempfile::tempdir().unwrap();
        let mut notes = vec![];
        let lock = BakeLock::acquire(dir.path(), whole(), "aa", &mut notes).unwrap();
        assert!(dir.path().join("bake.lock").is_file() && notes.is_empty());
        let before = std::fs::read(lock.path()).unwrap();
        // Held by this (running) process: the same shard is refused, whatever the bake.
        for hash in ["aa", "bb"] {
            let e = BakeLock::acquire(dir.path(), whole(), hash, &mut notes).unwrap_err().to_string();
            assert!(e.contains("is in use") && e.contains(&format!("process {}", std::process::id())), "{e}");
        }
        // Another shard of the same bake is welcome; of another bake, refused (and leaves nothing).
        let shard = Shard { index: 1, count: 2 };
        let other = BakeLock::acquire(dir.path(), shard, "aa", &mut notes).unwrap();
        drop(other);
        let e = BakeLock::acquire(dir.path(), shard, "bb", &mut notes).unwrap_err().to_string();
        assert!(e.contains("bake.lock is held by"), "{e}");
        let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
        assert_eq!(names, ["bake.lock"], "a refused taker leaves nothing");
        assert_eq!(std::fs::read(lock.path()).unwrap(), before);
        drop(lock);
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0, "dropping the lock removes it");
    }

    #[test]
    fn stale_locks_are_removed_with_a_note_and_foreign_ones_refuse_or_are_taken_over() {
        let dir = tempfile::tempdir().unwrap();
        let mut child = std::process::Command::new("true").spawn().unwrap();
        let dead_pid = child.id();
        child.wait().unwrap();
        let me = LockHolder::current(whole(), "aa");
        let write = |name: &str, h: &LockHolder| std::fs::write(dir.path().join(name), serde_json::to_vec(h).unwrap());
        // A dead holder of another bake, in this shard and in another.
        let dead = LockHolder { pid: dead_pid, bake_json_xxh64: "bb".into(), ..me.clone() };
        write("bake.lock", &dead).unwrap();
        write("bake.0-of-2.lock", &dead).unwrap();
        let mut notes = vec![];
        let lock = BakeLock::acquire(dir.path(), whole(), "aa", &mut notes).unwrap();
        assert_eq!(notes.len(), 2, "{notes:?}");
        assert!(notes.iter().all(|n| n.contains("stale") && n.contains("no longer runs")), "{notes:?}");
        assert_eq!(lock.holder().pid, std::process::id());
        assert!(!dir.path().join("bake.0-of-2.lock").exists());
        drop(lock);
        // A holder on another host: another bake is refused, naming the host; the same shard of
        // the same bake takes the lock over.
        let remote = LockHolder { host: "farm-node-7".into(), pid: 1, ..me.clone() };
        write("bake.lock", &LockHolder { bake_json_xxh64: "bb".into(), ..remote.clone() }).unwrap();
        let e = BakeLock::acquire(dir.path(), whole(), "aa", &mut notes).unwrap_err().to_string();
        assert!(e.contains("host farm-node-7") && e.contains("delete"), "{e}");
        write("bake.lock", &remote).unwrap();
        notes.clear();
        let lock = BakeLock::acquire(dir.path(), whole(), "aa", &mut notes).unwrap();
        assert!(notes[0].contains("took over"), "{notes:?}");
        drop(lock);
        // Garbage under a lock's name is not silently replaced.
        std::fs::write(dir.path().join("bake.lock"), b"").unwrap();
        let e = BakeLock::acquire(dir.path(), whole(), "aa", &mut notes).unwrap_err().to_string();
        assert!(e.contains("is not a lock swell can read (it is empty)"), "{e}");
    }
}
