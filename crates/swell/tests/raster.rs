//! Rasterizer invariants: watertight shared edges, depth order independent of draw order, the fast
//! path against the reference oracle, the binned draw against a serial one (small triangles go
//! through a path of their own), near-plane clipping, back-face culling and thread-count
//! independence.

use std::sync::atomic::{AtomicU32, Ordering};

use glam::{Vec3, Vec4};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use swell::raster::triangle::setup;
use swell::raster::{draw, draw_deferred_with, reference, ClipVertex, Cull, DrawScratch, Framebuffer};
use swell::scene::Camera;

/// Draws `vertices`/`indices` and counts how many times each pixel's shader ran. Triangle `i` is
/// given depth that decreases with `i`, so every covered pixel passes the depth test and the count
/// is the number of triangles covering the pixel centre.
fn coverage_counts(positions: &[Vec4], indices: &[u32], width: u32, height: u32) -> (Vec<u32>, Vec<u32>) {
    let (verts, idx) = depth_ordered(positions, indices);
    let counts: Vec<AtomicU32> = (0..width * height).map(|_| AtomicU32::new(0)).collect();
    let owners: Vec<AtomicU32> = (0..width * height).map(|_| AtomicU32::new(u32::MAX)).collect();
    let mut fb = Framebuffer::new(width, height);
    draw(&mut fb, &verts, &idx, Cull::None, &|f| {
        let i = (f.y * width + f.x) as usize;
        counts[i].fetch_add(1, Ordering::Relaxed);
        owners[i].store(f.primitive, Ordering::Relaxed);
        Vec3::ONE
    });
    (owners.into_iter().map(|a| a.into_inner()).collect(), counts.into_iter().map(|a| a.into_inner()).collect())
}

/// One vertex per triangle corner, triangle `i` at NDC depth `0.9 - 1.5 i / n` (x and y untouched),
/// so later triangles are always nearer.
fn depth_ordered(positions: &[Vec4], indices: &[u32]) -> (Vec<ClipVertex<()>>, Vec<u32>) {
    let n = indices.len() / 3;
    let mut verts = Vec::with_capacity(indices.len());
    for (t, tri) in indices.chunks_exact(3).enumerate() {
        let z = 0.9 - 1.5 * t as f32 / n as f32;
        for &k in tri {
            let p = positions[k as usize];
            verts.push(ClipVertex { position: Vec4::new(p.x, p.y, z * p.w, p.w), varying: () });
        }
    }
    let idx = (0..indices.len() as u32).collect();
    (verts, idx)
}

/// Clip-space position of window point (sx, sy) in pixels, with w = `w`.
fn from_window(sx: f32, sy: f32, w: f32, width: u32, height: u32) -> Vec4 {
    let nx = 2.0 * sx / width as f32 - 1.0;
    let ny = 1.0 - 2.0 * sy / height as f32;
    Vec4::new(nx * w, ny * w, 0.0, w)
}

#[test]
fn a_closed_fan_covers_every_pixel_of_its_disc_exactly_once() {
    let (width, height) = (101, 97);
    let mut rng = ChaCha8Rng::seed_from_u64(6);
    for case in 0..8 {
        // Sub-pixel centres, including exact pixel centres and corners, where ties are hardest.
        let (cx, cy) = match case {
            0 => (50.5, 48.5),
            1 => (50.0, 48.0),
            _ => (rng.gen_range(40.0..60.0), rng.gen_range(40.0..57.0)),
        };
        let segments = [3, 4, 7, 16, 37, 64, 100, 5][case];
        let radius = 40.0;
        let w = if case % 2 == 0 { 1.0 } else { 2.5 };
        let mut positions = vec![from_window(cx, cy, w, width, height)];
        let phase: f32 = rng.gen_range(0.0..1.0);
        for k in 0..segments {
            let a = std::f32::consts::TAU * (k as f32 + phase) / segments as f32;
            positions.push(from_window(cx + radius * a.cos(), cy + radius * a.sin(), w, width, height));
        }
        let mut indices = Vec::new();
        for k in 0..segments {
            indices.extend_from_slice(&[0, 1 + k, 1 + (k + 1) % segments]);
        }
        let (_, counts) = coverage_counts(&positions, &indices, width, height);
        let inscribed = radius * (std::f32::consts::PI / segments as f32).cos();
        for y in 0..height {
            for x in 0..width {
                let c = counts[(y * width + x) as usize];
                assert!(c <= 1, "case {case}: pixel ({x}, {y}) drawn {c} times");
                let d = ((x as f32 + 0.5 - cx).powi(2) + (y as f32 + 0.5 - cy).powi(2)).sqrt();
                if d < inscribed - 0.5 {
                    assert_eq!(c, 1, "case {case}: pixel ({x}, {y}) inside the disc was missed");
                }
                if d > radius + 0.5 {
                    assert_eq!(c, 0, "case {case}: pixel ({x}, {y}) outside the disc was drawn");
                }
            }
        }
    }
}

#[test]
fn a_grid_with_vertices_on_pixel_centres_has_no_cracks_and_no_overlaps() {
    // Vertices exactly on pixel centres and edges through pixel centres: every tie goes through
    // the top-left rule.
    let (width, height) = (64, 48);
    let (n, step) = (10u32, 5.0f32);
    let mut positions = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            positions.push(from_window(4.5 + step * i as f32, 2.5 + step * j as f32, 1.0, width, height));
        }
    }
    let mut indices = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i;
            let (b, c, d) = (a + 1, a + n + 1, a + n + 2);
            // Alternate the diagonal so both kinds of shared edge are tested.
            if (i + j) % 2 == 0 {
                indices.extend_from_slice(&[a, c, b, b, c, d]);
            } else {
                indices.extend_from_slice(&[a, c, d, a, d, b]);
            }
        }
    }
    let (_, counts) = coverage_counts(&positions, &indices, width, height);
    let (_, ref_counts) = reference::coverage(
        &depth_ordered(&positions, &indices).0.iter().map(|v| v.position).collect::<Vec<_>>(),
        &(0..indices.len() as u32).collect::<Vec<_>>(),
        width,
        height,
    );
    assert_eq!(counts, ref_counts);
    for y in 0..height {
        for x in 0..width {
            let c = counts[(y * width + x) as usize];
            // Top and left boundary centres belong to the grid, bottom and right ones do not.
            let inside = (4..54).contains(&x) && (2..52).contains(&y);
            assert_eq!(c, inside as u32, "pixel ({x}, {y})");
        }
    }
}

/// `n` random triangles with vertices in NDC [-1.3, 1.3]² and w in [0.5, 3].
fn random_triangles(rng: &mut ChaCha8Rng, n: usize, max_size: f32) -> Vec<Vec4> {
    let mut out = Vec::with_capacity(3 * n);
    for _ in 0..n {
        let c = (rng.gen_range(-1.2f32..1.2), rng.gen_range(-1.2f32..1.2));
        let w: f32 = rng.gen_range(0.5..3.0);
        for _ in 0..3 {
            let x = c.0 + rng.gen_range(-max_size..max_size);
            let y = c.1 + rng.gen_range(-max_size..max_size);
            out.push(Vec4::new(x * w, y * w, 0.0, w));
        }
    }
    out
}

#[test]
fn the_fast_rasterizer_agrees_with_the_reference_on_random_triangles() {
    let mut rng = ChaCha8Rng::seed_from_u64(42);
    for (width, height, size) in [(73, 41, 0.3), (128, 96, 0.05), (37, 53, 1.0)] {
        let positions = random_triangles(&mut rng, 300, size);
        let indices: Vec<u32> = (0..positions.len() as u32).collect();
        let (owner, count) = coverage_counts(&positions, &indices, width, height);
        let (verts, idx) = depth_ordered(&positions, &indices);
        let clip: Vec<Vec4> = verts.iter().map(|v| v.position).collect();
        let (ref_owner, ref_count) = reference::coverage(&clip, &idx, width, height);
        assert_eq!(count, ref_count, "{width}x{height}: coverage counts differ");
        assert_eq!(owner, ref_owner, "{width}x{height}: visible triangles differ");
    }
}

#[test]
fn depth_order_does_not_depend_on_draw_order() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let (width, height) = (96, 64);
    let positions = random_triangles(&mut rng, 400, 0.4);
    // Each triangle flat at its own depth, so no two triangles tie at any pixel.
    let mut verts = Vec::new();
    for (t, tri) in positions.chunks_exact(3).enumerate() {
        let z = -0.95 + 1.9 * ((t * 7919) % 400) as f32 / 400.0;
        let color = Vec3::new(rng.gen(), rng.gen(), rng.gen());
        for p in tri {
            verts.push(ClipVertex { position: Vec4::new(p.x, p.y, z * p.w, p.w), varying: color });
        }
    }
    let forward: Vec<u32> = (0..verts.len() as u32).collect();
    let backward: Vec<u32> = forward.chunks_exact(3).rev().flatten().copied().collect();
    let render = |idx: &[u32]| {
        let mut fb = Framebuffer::new(width, height);
        draw(&mut fb, &verts, idx, Cull::None, &|f| f.varying);
        fb
    };
    let (a, b) = (render(&forward), render(&backward));
    assert_eq!(a.depth, b.depth);
    assert_eq!(a.color, b.color);
    assert!(a.depth.iter().filter(|&&d| d < 1.0).count() > (width * height / 2) as usize);
}

#[test]
fn triangles_crossing_the_near_plane_are_clipped_and_interpolated_in_perspective() {
    // Eye at the origin looking down -Z at a floor y = -1 that runs from behind the eye (z = 30)
    // to z = -60: the near plane cuts both of its triangles.
    let camera = Camera {
        eye: Vec3::ZERO,
        target: Vec3::new(0.0, -0.2, -1.0),
        up: Vec3::Y,
        fov_y_deg: 70.0,
        near: 0.1,
        far: 1000.0,
    };
    let (width, height) = (120, 80);
    let clip_from_world = camera.clip_from_world(width as f32 / height as f32);
    let corners = [
        Vec3::new(-20.0, -1.0, 30.0),
        Vec3::new(20.0, -1.0, 30.0),
        Vec3::new(20.0, -1.0, -60.0),
        Vec3::new(-20.0, -1.0, -60.0),
    ];
    let verts: Vec<ClipVertex<Vec3>> =
        corners.iter().map(|&p| ClipVertex { position: clip_from_world * p.extend(1.0), varying: p }).collect();
    let mut fb = Framebuffer::new(width, height);
    draw(&mut fb, &verts, &[0, 1, 2, 0, 2, 3], Cull::None, &|f| f.varying);
    let forward = (camera.target - camera.eye).normalize();
    let right = forward.cross(Vec3::Y).normalize();
    let up = right.cross(forward);
    let tan_half = (0.5 * camera.fov_y_deg.to_radians()).tan();
    let aspect = width as f32 / height as f32;
    // Where the ray through window point (sx, sy) meets the floor inside its bounds, if it does.
    let hit = |sx: f32, sy: f32| -> Option<Vec3> {
        let nx = 2.0 * sx / width as f32 - 1.0;
        let ny = 1.0 - 2.0 * sy / height as f32;
        let d = forward + right * (nx * tan_half * aspect) + up * (ny * tan_half);
        if d.y >= 0.0 {
            return None;
        }
        let p = d * (-1.0 / d.y);
        (p.x.abs() < 20.0 && p.z > -60.0).then_some(p)
    };
    let mut covered = 0;
    for y in 0..height {
        for x in 0..width {
            let i = (y * width + x) as usize;
            let corners =
                [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)].map(|(dx, dy)| hit(x as f32 + dx, y as f32 + dy));
            let centre = hit(x as f32 + 0.5, y as f32 + 0.5);
            if corners.iter().all(Option::is_some) {
                let expected = centre.unwrap();
                let got = fb.color[i];
                assert!(fb.depth[i] >= 0.0 && fb.depth[i] < 1.0);
                assert!(
                    (got - expected).length() < 2e-3 * expected.length().max(1.0),
                    "pixel ({x}, {y}): interpolated {got}, ray hits {expected}"
                );
                covered += 1;
            } else if corners.iter().all(Option::is_none) {
                assert_eq!(fb.depth[i], 1.0, "pixel ({x}, {y}) sees no floor but was drawn");
            }
        }
    }
    assert!(covered > (width * height / 3) as usize, "only {covered} pixels see the floor");
}

#[test]
fn back_face_culling_skips_clockwise_triangles_only() {
    let ccw = [Vec4::new(-0.5, -0.5, 0.0, 1.0), Vec4::new(0.5, -0.5, 0.0, 1.0), Vec4::new(0.0, 0.5, 0.0, 1.0)];
    let verts: Vec<ClipVertex<()>> = ccw.iter().map(|&p| ClipVertex { position: p, varying: () }).collect();
    let drawn = |idx: &[u32], cull| {
        let mut fb = Framebuffer::new(16, 16);
        draw(&mut fb, &verts, idx, cull, &|_| Vec3::ONE);
        fb.depth.iter().filter(|&&d| d < 1.0).count()
    };
    let front = drawn(&[0, 1, 2], Cull::Back);
    assert!(front > 0);
    assert_eq!(drawn(&[0, 2, 1], Cull::Back), 0);
    assert_eq!(drawn(&[0, 2, 1], Cull::None), front);
}

/// `positions` at random NDC depths in [-0.9, 0.9], each with a random colour to interpolate.
fn with_random_depths_and_colors(rng: &mut ChaCha8Rng, positions: &[Vec4]) -> Vec<ClipVertex<Vec3>> {
    positions
        .iter()
        .map(|&p| {
            let z = rng.gen_range(-0.9f32..0.9);
            ClipVertex {
                position: Vec4::new(p.x, p.y, z * p.w, p.w),
                varying: Vec3::new(rng.gen(), rng.gen(), rng.gen()),
            }
        })
        .collect()
}

#[test]
fn the_image_is_bit_identical_on_one_two_and_three_threads() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let (width, height) = (157, 131);
    let positions = random_triangles(&mut rng, 2000, 0.3);
    let verts = with_random_depths_and_colors(&mut rng, &positions);
    let indices: Vec<u32> = (0..verts.len() as u32).collect();
    let render = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| {
            let mut fb = Framebuffer::new(width, height);
            draw(&mut fb, &verts, &indices, Cull::None, &|f| f.varying);
            fb
        })
    };
    let one = render(1);
    for n in [2, 3] {
        let other = render(n);
        assert!(
            one.color
                .iter()
                .zip(&other.color)
                .all(|(a, b)| a.to_array().map(f32::to_bits) == b.to_array().map(f32::to_bits)),
            "{n} threads differ"
        );
        assert!(one.depth.iter().zip(&other.depth).all(|(a, b)| a.to_bits() == b.to_bits()));
    }
}

/// The draw (forward and deferred) against a serial renderer built from the public setup and
/// scan, bit for bit, colours and depths: every triangle in submission order, depth-tested, its
/// varying interpolated perspective-correctly. The mesh mixes what the draw bins differently:
/// triangles of a pixel or two (set up 16 at a time and binned as fragments, some straddling
/// two bands), larger ones (binned as records), overlapping at random depths, and a few that
/// cross the viewport's edges.
#[test]
fn the_binned_draw_matches_a_serial_one_with_small_and_large_triangles() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let (width, height) = (157u32, 131u32);
    let mut positions = random_triangles(&mut rng, 12000, 0.015);
    positions.extend(random_triangles(&mut rng, 300, 0.1));
    positions.extend(random_triangles(&mut rng, 40, 0.5));
    let verts = with_random_depths_and_colors(&mut rng, &positions);
    // Shuffled corners, so triangles of both windings.
    let mut indices: Vec<u32> = (0..verts.len() as u32).collect();
    for t in indices.chunks_exact_mut(3) {
        if rng.gen::<bool>() {
            t.swap(1, 2);
        }
    }
    let mut expected = Framebuffer::new(width, height);
    for (p, t) in indices.chunks_exact(3).enumerate() {
        let tri = [verts[t[0] as usize], verts[t[1] as usize], verts[t[2] as usize]];
        // Every vertex is in front of the eye and inside the guard band: no clipping.
        if let Some(s) = setup(&tri, p as u32, width, height, false) {
            s.scan((0, height - 1), |c| {
                let (i, z) = ((c.y * width + c.x) as usize, s.depth(c.linear));
                if z < expected.depth[i] {
                    expected.depth[i] = z;
                    expected.color[i] = s.interpolate(s.perspective_weights(c.linear));
                }
            });
        }
    }
    let bits = |fb: &Framebuffer| -> Vec<[u32; 4]> {
        fb.color
            .iter()
            .zip(&fb.depth)
            .map(|(c, d)| [c.x.to_bits(), c.y.to_bits(), c.z.to_bits(), d.to_bits()])
            .collect()
    };
    let mut forward = Framebuffer::new(width, height);
    draw(&mut forward, &verts, &indices, Cull::None, &|f| f.varying);
    let mut deferred = Framebuffer::new(width, height);
    draw_deferred_with(&mut DrawScratch::default(), &mut deferred, &verts, &indices, Cull::None, &|v, out| {
        out.copy_from_slice(v)
    });
    let covered = expected.depth.iter().filter(|&&d| d < 1.0).count();
    assert!(covered > (width * height / 3) as usize, "the mesh covers {covered} pixels");
    assert!(bits(&forward) == bits(&expected), "the forward draw differs from the serial one");
    assert!(bits(&deferred) == bits(&expected), "the deferred draw differs from the serial one");
}

/// A vertex with a w so small that 1/w overflows (below about 3e-39) is inside every clip plane
/// but has no window position: its triangles are dropped, in debug builds without an arithmetic
/// overflow, whatever path their size would take, and the rest of the draw is unaffected.
#[test]
fn a_vertex_whose_inverse_w_overflows_drops_its_triangles() {
    let (width, height) = (64u32, 64u32);
    let v = |x: f32, y: f32, w: f32| ClipVertex { position: Vec4::new(x, y, 0.0, w), varying: () };
    let verts = [
        // Small next to the overflowing vertex, large, and one ordinary triangle.
        v(0.0, -2.0, 1.0),
        v(1e-40, -1e-40, 1e-40),
        v(-2.0, -2.0, 1.0),
        v(-0.5, -0.5, 1.0),
        v(0.5, -0.5, 1.0),
        v(1e-40, 5e-41, 1e-40),
        v(-0.5, 0.2, 1.0),
        v(-0.4, 0.2, 1.0),
        v(-0.5, 0.3, 1.0),
    ];
    let indices: Vec<u32> = (0..verts.len() as u32).collect();
    for cull in [Cull::None, Cull::Back] {
        let mut fb = Framebuffer::new(width, height);
        let drawn = AtomicU32::new(0);
        draw(&mut fb, &verts, &indices, cull, &|f| {
            assert_eq!(f.primitive, 2, "only the ordinary triangle draws");
            drawn.fetch_add(1, Ordering::Relaxed);
            Vec3::ONE
        });
        // The ordinary triangle faces the viewer (counter-clockwise), so it draws either way.
        assert!(drawn.into_inner() > 0, "{cull:?}");
        assert!(fb.color.iter().all(|c| c.is_finite()));
    }
}
