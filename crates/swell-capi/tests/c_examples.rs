//! The C and C++ examples, built with the system's plain `cc` and `c++` against the library cargo
//! just built (installed with `install.sh` and found through pkg-config), run, compared number for
//! number with the Rust library, and run again under valgrind: no errors, no leaks.
//!
//! Without a C compiler the test says so and passes; with `SWELL_REQUIRE_C_TOOLS=1` (CI) a missing
//! `cc`, `c++`, `pkg-config` or `valgrind` is a failure.

use std::path::{Path, PathBuf};
use std::process::Command;

use swell_lib::Water;

fn crate_dir() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Builds `libswell.so` and `libswell.a` with the profile of this test and returns their directory.
///
/// The test binary is target/<dir>/deps/c_examples-<hash>. Cargo does not build a cdylib or
/// staticlib for a package's integration tests (they link to rlibs), so this builds them, with
/// the test's own profile so that everything but the C library itself is already compiled.
fn lib_dir() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let dir = exe.parent().and_then(Path::parent).unwrap().to_path_buf();
    let profile = if dir.ends_with("release") { "release" } else { "test" };
    let root = crate_dir().parent().and_then(Path::parent).unwrap();
    run(Command::new(env!("CARGO")).current_dir(root).args(["build", "-p", "swell-capi", "--profile", profile]));
    dir
}

fn have(tool: &str) -> bool {
    let found = Command::new(tool).arg("--version").output().is_ok_and(|o| o.status.success());
    if !found && std::env::var_os("SWELL_REQUIRE_C_TOOLS").is_some() {
        panic!("{tool} is missing and SWELL_REQUIRE_C_TOOLS is set");
    }
    found
}

fn run(cmd: &mut Command) -> String {
    let out = cmd.output().unwrap_or_else(|e| panic!("{cmd:?}: {e}"));
    assert!(
        out.status.success(),
        "{cmd:?} failed ({}):\nstdout:\n{}\nstderr:\n{}",
        out.status,
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// The scene text of examples/ocean.c: its `SCENE` string literal, unescaped.
fn example_scene() -> String {
    example_literal("ocean.c", "SCENE")
}

/// The string literal `static const char *NAME = "..." "...";` of the example `file`, one literal
/// per line, unescaped.
fn example_literal(file: &str, name: &str) -> String {
    let src = std::fs::read_to_string(crate_dir().join("examples").join(file)).unwrap();
    let start = src.find(&format!("static const char *{name} =")).unwrap_or_else(|| panic!("{file} defines {name}"));
    let mut text = String::new();
    for line in src[start..].lines().skip(1).map(str::trim) {
        let literal = line.trim_end_matches(';');
        let inner = literal.strip_prefix('"').and_then(|l| l.strip_suffix('"')).expect("one literal per line");
        text.push_str(&inner.replace("\\n", "\n"));
        if line.ends_with(';') {
            break;
        }
    }
    text
}

/// Installs the library into a temporary prefix with install.sh and returns pkg-config's flags.
fn install(prefix: &Path, lib_dir: &Path, static_link: bool) -> Vec<String> {
    run(Command::new("sh").arg(crate_dir().join("install.sh")).arg(prefix).arg(lib_dir));
    let mut cmd = Command::new("pkg-config");
    cmd.env("PKG_CONFIG_PATH", prefix.join("lib/pkgconfig")).args(["--cflags", "--libs", "swell"]);
    if static_link {
        cmd.arg("--static");
    }
    run(&mut cmd).split_whitespace().map(String::from).collect()
}

fn valgrind(program: &Path, ld_path: &Path) -> String {
    let out = Command::new("valgrind")
        .args([
            "--leak-check=full",
            "--show-leak-kinds=definite,indirect,possible",
            "--errors-for-leak-kinds=definite,indirect,possible",
            "--error-exitcode=1",
        ])
        .arg(format!("--suppressions={}", crate_dir().join("tests/valgrind.supp").display()))
        .arg(program)
        .env("LD_LIBRARY_PATH", ld_path)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "valgrind found errors in {}:\n{stderr}", program.display());
    assert!(stderr.contains("ERROR SUMMARY: 0 errors"), "{stderr}");
    stderr
}

/// Numbers after `key` on a line of the examples' output.
fn numbers_after(line: &str, key: &str, count: usize) -> Vec<f32> {
    let rest = &line[line.find(key).unwrap_or_else(|| panic!("no `{key}` in {line}")) + key.len()..];
    rest.split_whitespace().take(count).map(|s| s.parse().unwrap()).collect()
}

#[test]
fn the_c_and_cpp_examples_agree_with_the_library_and_pass_valgrind() {
    if !(have("cc") && have("c++") && have("pkg-config")) {
        eprintln!("skipped: cc, c++ or pkg-config not found");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let prefix = dir.path().join("prefix");
    let lib_dir = lib_dir();
    let examples = crate_dir().join("examples");

    // C against the shared library, C++ against the static one.
    let shared = install(&prefix, &lib_dir, false);
    let c_exe = dir.path().join("ocean_c");
    run(Command::new("cc")
        .args(["-std=c99", "-Wall", "-Wextra", "-Werror"])
        .arg(examples.join("ocean.c"))
        .args(&shared)
        .arg("-o")
        .arg(&c_exe));
    let static_flags = install(&prefix, &lib_dir, true);
    let cpp_exe = dir.path().join("ocean_cpp");
    let libs: Vec<&String> = static_flags.iter().filter(|f| *f != "-lswell").collect();
    run(Command::new("c++")
        .args(["-std=c++17", "-Wall", "-Wextra", "-Werror"])
        .arg(examples.join("ocean.cpp"))
        .arg(prefix.join("lib/libswell.a"))
        .args(&libs)
        .arg("-o")
        .arg(&cpp_exe));
    let ld = prefix.join("lib");
    let c_out = run(Command::new(&c_exe).env("LD_LIBRARY_PATH", &ld));
    let cpp_out = run(&mut Command::new(&cpp_exe));

    // The same numbers as the Rust library, bit for bit (printed with 9 significant digits).
    let mut water = Water::from_toml(&example_scene(), "example").unwrap();
    let n = water.vertex_count();
    let (mut p, mut q) = (vec![glam::Vec3::ZERO; n], vec![glam::Vec3::ZERO; n]);
    let c_frames: Vec<&str> = c_out.lines().filter(|l| l.starts_with("t ")).collect();
    let cpp_frames: Vec<&str> = cpp_out.lines().filter(|l| l.starts_with("t ")).collect();
    assert_eq!((c_frames.len(), cpp_frames.len()), (3, 3), "{c_out}\n{cpp_out}");
    for (c, cpp) in c_frames.iter().zip(&cpp_frames) {
        let t = f64::from(numbers_after(c, "t ", 1)[0]);
        let t = (t * 24.0).round() / 24.0;
        water.displace(t, &mut p, &mut q).unwrap();
        let pts = [glam::Vec2::new(3.0, -4.0), glam::Vec2::new(10.0, 7.5), glam::Vec2::new(-20.0, 12.25)];
        let mut h = [0.0; 3];
        water.heights_at(t, &pts, &mut h).unwrap();
        assert_eq!(numbers_after(c, "buoy ", 3), h.to_vec(), "{c}");
        assert_eq!(numbers_after(c, "vertex0 ", 3), p[0].to_array().to_vec(), "{c}");
        assert_eq!(numbers_after(cpp, "buoy ", 1), vec![h[0]], "{cpp}");
        assert_eq!(numbers_after(cpp, "vertex0 ", 3), p[0].to_array().to_vec(), "{cpp}");
        assert!(c.contains("foam 1"), "the example's ocean has foam: {c}");
    }
    // Double precision far out: the buoy 10^6 m east as at home, and as the library says.
    let mut far = [0.0f64; 2];
    let pts = [glam::DVec2::new(3.0, -4.0), glam::DVec2::new(3.0 + 64.0 * 15625.0, -4.0)];
    water.heights_at_f64(1.0, &pts, &mut far).unwrap();
    // The models answer in f32, widened: 9 significant digits give it back exactly.
    let c_far = numbers_after(&c_out, "far buoy ", 2);
    assert_eq!(c_far, far.map(|h| h as f32).to_vec(), "{c_out}");
    assert!((c_far[1] - c_far[0]).abs() < 1e-4, "{c_out}");
    // Errors reach C as codes with the CLI's messages.
    assert!(
        c_out.contains(
            "short buffer -> 2: positions_len: 3266; must be 3267 (3 floats per vertex x 33 rows x 33 columns)"
        ),
        "{c_out}"
    );
    assert!(c_out.contains("bad scene -> 3: toml: water.grid = 100 is outside powers of two in [16, 2048]"), "{c_out}");
    assert!(cpp_out.contains("bad scene: toml: water.grid = 100 is outside powers of two in [16, 2048]"), "{cpp_out}");
    // The render is the same frame in both.
    let render = |s: &str| s.lines().find(|l| l.starts_with("rendered")).map(String::from);
    assert_eq!(render(&c_out), render(&cpp_out));
    assert!(render(&c_out).unwrap().starts_with("rendered 96x54"));

    if !have("valgrind") {
        eprintln!("valgrind not found: the examples ran, but not under valgrind");
        return;
    }
    for exe in [&c_exe, &cpp_exe] {
        let report = valgrind(exe, &ld);
        eprintln!(
            "valgrind {}: {}",
            exe.display(),
            report.lines().filter(|l| l.contains("SUMMARY")).collect::<Vec<_>>().join(" | ")
        );
    }
}

/// examples/bodies.c, built with `cc` against the shared library, floats the same bodies as the
/// Rust library's `World` given the same scene, the same drop of a barrel (its `BARREL` snippet)
/// and a ball (the parameters bodies.c passes), and the same thrust at the same frames: every
/// printed pose equal bit for bit (printed with 17 significant digits); then under valgrind.
#[test]
fn the_bodies_example_floats_the_library_s_bodies_and_passes_valgrind() {
    if !(have("cc") && have("pkg-config")) {
        eprintln!("skipped: cc or pkg-config not found");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let prefix = dir.path().join("prefix");
    let lib_dir = lib_dir();
    let flags = install(&prefix, &lib_dir, false);
    let exe = dir.path().join("bodies_c");
    run(Command::new("cc")
        .args(["-std=c99", "-Wall", "-Wextra", "-Werror"])
        .arg(crate_dir().join("examples/bodies.c"))
        .args(&flags)
        .arg("-o")
        .arg(&exe));
    let ld = prefix.join("lib");
    let out = run(Command::new(&exe).env("LD_LIBRARY_PATH", &ld));

    // The library, step for step as bodies.c goes: 24 fps for 4 s, the barrel and the ball dropped
    // after frame 24, the crate pushed from frame 48.
    let scene = swell_lib::scene::Scene::from_toml(&example_literal("bodies.c", "SCENE"), "bodies.c").unwrap();
    let mut world = swell_lib::world::World::new(scene).unwrap();
    let mut expected = Vec::new();
    for frame in 0..=96 {
        let t = f64::from(frame) / 24.0;
        world.advance(t).unwrap();
        if frame % 12 == 0 {
            for (b, p) in world.bodies.bodies().iter().zip(world.body_poses()) {
                let (q, r) = (p.position, p.rotation);
                expected.push((t, b.name.clone(), [q.x, q.y, q.z, r.x, r.y, r.z, r.w]));
            }
        }
        if frame == 24 {
            let barrel = example_literal("bodies.c", "BARREL");
            let spec = swell_lib::scene::Scene::from_toml(&barrel, "barrel").unwrap().bodies.remove(0);
            assert_eq!(world.add_body(spec).unwrap(), 1);
            let shape = swell_lib::body::BodyShape::Sphere;
            let mut ball = swell_lib::body::BodySpec::new(shape, &[0.25], glam::Vec3::new(2.0, 1.5, 1.0));
            (ball.name, ball.density) = ("ball".into(), Some(300.0));
            assert_eq!(world.add_body(ball).unwrap(), 2);
        }
        if frame == 48 {
            world.bodies.bodies_mut()[0].thrust = glam::DVec3::new(400.0, 0.0, 0.0);
        }
    }
    let printed: Vec<(f64, String, Vec<f64>)> = out
        .lines()
        .filter(|l| l.starts_with("t "))
        .map(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            assert_eq!(w.len(), 10, "{l}");
            (w[1].parse().unwrap(), w[2].to_string(), w[3..].iter().map(|v| v.parse().unwrap()).collect())
        })
        .collect();
    // 3 frames with the crate alone, 6 with three bodies.
    assert_eq!(printed.len(), 3 + 6 * 3, "{out}");
    for ((t, name, pose), (et, ename, epose)) in printed.iter().zip(&expected) {
        assert_eq!((t, name, &pose[..]), (et, ename, &epose[..]), "{out}");
    }
    // Afloat at the end, every one: near the water at rest, neither sunk nor flung away.
    for (_, name, pose) in &printed[printed.len() - 3..] {
        assert!(pose[1].abs() < 0.8, "{name}: {pose:?}");
    }
    assert!(out.contains("added barrel 1 ball 2"), "{out}");
    assert!(
        out.contains("nan time -> 2: t = NaN is outside [0, 1e7] seconds (floating bodies start at t = 0)"),
        "{out}"
    );
    assert!(out.contains("short buffer -> 2: positions_len: 8; must be 9 (3 doubles per body x 3 bodies)"), "{out}");
    assert!(out.contains("bad body -> 3: toml: body[3].size: [1.0, 0.5] has 2 values; shape box takes"), "{out}");
    assert!(out.contains("bad index -> 2: index: 3; must be below 3 (the scene's bodies)"), "{out}");

    if !have("valgrind") {
        eprintln!("valgrind not found: the bodies example ran, but not under valgrind");
        return;
    }
    let report = valgrind(&exe, &ld);
    eprintln!(
        "valgrind bodies_c: {}",
        report.lines().filter(|l| l.contains("SUMMARY")).collect::<Vec<_>>().join(" | ")
    );
}
