//! File plumbing beneath every layer that writes: a file appears under its name complete or not at
//! all. Below `terrain` and `export` alike, so neither imports the other to write a file.

mod atomic;

pub use atomic::write_atomically;
