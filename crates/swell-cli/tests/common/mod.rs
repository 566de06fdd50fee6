//! What the CLI test files share: running the real binary and reading what it wrote.

// Each test file uses its own subset.
#![allow(dead_code)]

use std::collections::BTreeMap;
use std::path::Path;
use std::process::{Command, Output};

/// The binary under test.
pub const SWELL: &str = env!("CARGO_BIN_EXE_swell");

/// Runs `swell` with `args` to completion.
pub fn swell(args: &[&str]) -> Output {
    Command::new(SWELL).args(args).output().unwrap()
}

/// A run's standard error as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Every visible file of `dir` (temporaries of killed runs start with a dot) and its bytes.
pub fn files(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap())
        .filter(|e| !e.file_name().to_string_lossy().starts_with('.'))
        .map(|e| (e.file_name().to_string_lossy().into_owned(), std::fs::read(e.path()).unwrap()))
        .collect()
}
