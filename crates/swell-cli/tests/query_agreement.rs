//! issue 19: the library's query API ([`swell::Water`], which the C and Python bindings wrap)
//! gives the numbers the CLI writes: `swell bake`'s displacement, normal and foam maps, `swell
//! export`'s mesh, `swell render`'s pixels and `swell stats`'s JSON, for the same scene and time.

use std::process::Command;

use glam::{Vec2, Vec3};
use swell::Water;

mod common;
use common::{read_exr_rgb, read_exr_y};

const SWELL: &str = env!("CARGO_BIN_EXE_swell");

fn swell(args: &[&str]) -> String {
    let out = Command::new(SWELL).args(args).output().unwrap();
    assert!(out.status.success(), "swell {args:?}: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap()
}

/// The ocean preset on a 48-cell grid (bilinear sampling of the 256² field, foam on).
fn ocean_text() -> String {
    let text = include_str!("../../swell/presets/ocean.toml").replace("cells = [400, 400]", "cells = [48, 48]");
    assert!(text.contains("cells = [48, 48]"));
    text.replace("width = 1280\nheight = 720", "width = 160\nheight = 90")
}

#[test]
fn bake_maps_and_the_exported_mesh_are_the_query_api_s_numbers() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("ocean.toml");
    std::fs::write(&scene, ocean_text()).unwrap();
    let scene = scene.to_str().unwrap();
    let bake = dir.path().join("bake");
    swell(&["bake", "--scene", scene, "--frames", "3..3", "--fps", "24", "--quiet", "--out", bake.to_str().unwrap()]);
    let obj = dir.path().join("ocean.obj");
    swell(&["export", "--scene", scene, "--time", "0.125", "--out", obj.to_str().unwrap()]);

    let mut water = Water::from_toml(&ocean_text(), "t").unwrap();
    // Asked out of order first: the answers must not depend on it.
    let n = water.vertex_count();
    let (mut p, mut q, mut foam) = (vec![Vec3::ZERO; n], vec![Vec3::ZERO; n], vec![0.0; n]);
    water.displace(7.0, &mut p, &mut q).unwrap();
    let t = 3.0 / 24.0;
    water.displace(t, &mut p, &mut q).unwrap();
    assert!(water.foam(t, &mut foam).unwrap());

    let grid = *water.grid();
    let disp: Vec<Vec3> = (0..n)
        .map(|k| {
            let r = grid.rest_position(k % grid.verts_x(), k / grid.verts_x());
            p[k] - Vec3::new(r.x, 0.0, r.y)
        })
        .collect();
    assert_eq!(read_exr_rgb(&bake.join("disp_0003.exr")), disp);
    assert_eq!(read_exr_rgb(&bake.join("normal_0003.exr")), q);
    assert_eq!(read_exr_y(&bake.join("foam_0003.exr")), foam);

    // OBJ writes f32 with Rust's shortest round-trip formatting: exact.
    let text = std::fs::read_to_string(&obj).unwrap();
    let parse = |prefix: &str| -> Vec<Vec3> {
        text.lines()
            .skip_while(|l| *l != "o water")
            .take_while(|l| !l.starts_with("o ") || *l == "o water")
            .filter_map(|l| l.strip_prefix(prefix))
            .map(|l| {
                let v: Vec<f32> = l.split_whitespace().map(|s| s.parse().unwrap()).collect();
                Vec3::new(v[0], v[1], v[2])
            })
            .collect()
    };
    assert_eq!(parse("v "), p);
    assert_eq!(parse("vn "), q);

    // A floating object at a vertex sits at the vertex's height (to the inversion's tolerance).
    let pts: Vec<Vec2> = p.iter().step_by(53).map(|v| Vec2::new(v.x, v.z)).collect();
    let mut h = vec![0.0; pts.len()];
    water.heights_at(t, &pts, &mut h).unwrap();
    for (k, v) in p.iter().step_by(53).enumerate() {
        assert!((h[k] - v.y).abs() < 2e-3, "point {k}: {} vs {}", h[k], v.y);
    }
}

#[test]
fn stats_json_is_the_library_s() {
    let out = swell(&["stats", "--preset", "ocean", "--time", "1.5"]);
    let stats = swell::world::sea_stats(&swell::scene::preset("ocean").unwrap(), 1.5).unwrap();
    assert_eq!(out.trim_end(), serde_json::to_string_pretty(&stats).unwrap());
}
