//! Property tests over combinations of command-line flags (issue 22): whatever flags a user puts
//! together, good or bad, `swell` either does the job (exit 0, the output complete) or refuses
//! with `error: ` and a message naming a flag or key, exit code 1 or 2, and no output file. It never
//! panics, never dies on a signal and never leaves a half-written or temporary file.

use std::path::Path;
use std::process::Command;

use proptest::prelude::*;

const SWELL: &str = env!("CARGO_BIN_EXE_swell");

/// One flag of `render` with a value from a small pool of good and bad values.
fn render_flag() -> impl Strategy<Value = Vec<String>> {
    let v = |flag: &'static str, values: &'static [&'static str]| {
        proptest::sample::select(values).prop_map(move |x| vec![flag.to_string(), x.to_string()])
    };
    prop_oneof![
        v("--time", &["0", "2.5", "-3", "1e300", "nan", "1e7", "x"]),
        v("--frames", &["2", "1..3", "0", "3..1", "0..x", "-1", "99999"]),
        v("--fps", &["24", "50", "60", "0", "1e9", "-1"]),
        v("--shading", &["flat", "phong", "blinn-phong", "nope"]),
        v("--supersample", &["1", "2", "9", "0"]),
        v("--threads", &["1", "2", "0", "999999"]),
        v("--size", &["16x9", "24x24", "0x5", "5", "99999x2"]),
        v("--camera", &["/nonexistent.json"]),
        v("--light", &["/nonexistent.json"]),
        v("--repeat", &["2", "0"]),
        Just(vec!["--wireframe".to_string()]),
        Just(vec!["--normals".to_string()]),
        v("--preset", &["sea", "pool", "ocean", "springs", "nope"]),
    ]
}

fn visible_files(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn any_render_command_line_succeeds_whole_or_fails_cleanly(
        flags in proptest::collection::vec(render_flag(), 0..5),
        gif in any::<bool>(),
    ) {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join(if gif { "out.gif" } else { "out.png" });
        let mut args: Vec<String> = vec!["render".into()];
        // A preset unless one was drawn (two would be clap's error, also fine); small images.
        if !flags.iter().any(|f| f[0] == "--preset") {
            args.extend(["--preset".into(), "sea".into()]);
        }
        if !flags.iter().any(|f| f[0] == "--size") {
            args.extend(["--size".into(), "16x9".into()]);
        }
        for f in &flags {
            args.extend(f.iter().cloned());
        }
        args.extend(["--out".into(), out.to_str().unwrap().into()]);
        let o = Command::new(SWELL).args(&args).output().unwrap();
        let stderr = String::from_utf8_lossy(&o.stderr);
        let code = o.status.code();
        prop_assert!(code.is_some(), "{args:?}: killed by a signal\n{stderr}");
        prop_assert!(!stderr.contains("panicked"), "{args:?}: panicked\n{stderr}");
        let files = visible_files(dir.path());
        if o.status.success() {
            prop_assert_eq!(&files, &vec![out.file_name().unwrap().to_string_lossy().into_owned()], "{:?}", args);
            prop_assert!(std::fs::metadata(&out).unwrap().len() > 0);
        } else {
            prop_assert!(matches!(code, Some(1) | Some(2)), "{args:?}: exit {code:?}\n{stderr}");
            prop_assert!(stderr.starts_with("error: "), "{args:?}: {stderr}");
            prop_assert!(files.is_empty(), "{args:?}: left {files:?}\n{stderr}");
        }
    }
}
