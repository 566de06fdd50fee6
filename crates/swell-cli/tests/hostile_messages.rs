//! Issue 37, class 4: messages echo user text (keys, values, file names, the scene line the parser
//! quotes) escaped and cut, so a hostile scene cannot retitle or clear the terminal, hide text
//! behind bidi overrides, or flood it.

mod common;

use common::{stderr, swell};

/// Bytes that act on a terminal, or reorder what it shows.
fn has_raw_controls(s: &str) -> bool {
    s.chars().any(|c| (c.is_control() && c != '\n' && c != '\t') || ('\u{202a}'..='\u{202e}').contains(&c))
}

#[test]
fn a_key_with_escape_sequences_and_bidi_marks_is_printed_escaped() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("hostile.toml");
    std::fs::write(&scene, "version = 1\n[water]\nmodel = 'sines'\n\"w\u{1b}]0;pwned\u{7}\u{1b}[2J\u{202e}x\" = 1\n")
        .unwrap();
    let out =
        swell(&["render", "--scene", scene.to_str().unwrap(), "--out", dir.path().join("x.png").to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let err = stderr(&out);
    assert!(!has_raw_controls(&err), "{err:?}");
    assert!(err.contains("\\u{1b}]0;pwned\\u{7}"), "{err}");
    assert!(!dir.path().join("x.png").exists());
}

#[test]
fn a_100000_character_key_is_cut_with_its_length_stated() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("long.toml");
    std::fs::write(&scene, format!("version = 1\n[water]\nmodel = 'sines'\n{} = 1\n", "k".repeat(100_000))).unwrap();
    let out =
        swell(&["render", "--scene", scene.to_str().unwrap(), "--out", dir.path().join("x.png").to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let err = stderr(&out);
    assert!(err.len() < 4000, "{} bytes", err.len());
    assert!(err.contains("characters in all)"), "{err}");
}

#[test]
fn a_file_name_with_control_characters_is_printed_escaped() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("no\u{1b}[2Jsuch\r.toml");
    let out =
        swell(&["render", "--scene", missing.to_str().unwrap(), "--out", dir.path().join("x.png").to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let err = stderr(&out);
    assert!(!has_raw_controls(&err), "{err:?}");
    assert!(err.contains("no\\u{1b}[2Jsuch\\u{d}.toml"), "{err}");
}
