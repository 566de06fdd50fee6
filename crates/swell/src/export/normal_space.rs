//! The space a baked normal map is expressed in: world, or tangent space of the flat patch with
//! OpenGL's or DirectX's green convention.
//!
//! **Tangent space of a displaced grid.** The reference frame is the *undisplaced, flat* grid the
//! maps are pixels of, whose frame is the same at every pixel: tangent T = +X (map u, columns),
//! normal N = +Y (up), bitangent B along the map's v. A tangent-space normal map applied to a flat
//! plane laid out as the bake's grid (u along +X, image top towards −Z) therefore reproduces the
//! world normal of the displaced surface, which is what an engine that displaces a flat plane with
//! the displacement map and shades it with the normal map needs.
//!
//! The two green conventions differ only in which way B points:
//!
//! | space | R | G | B | B vector | handedness |
//! |---|---|---|---|---|---|
//! | `world` | n.x | n.y | n.z | — | — |
//! | `tangent-gl` (OpenGL: Blender, Unity, Godot, glTF) | n.x | −n.z | n.y | −Z: green points to the image's top | T × B = N |
//! | `tangent-dx` (DirectX: Unreal, 3ds Max) | n.x | n.z | n.y | +Z: green points to the image's bottom | T × B = −N |
//!
//! Row 0 of a map is its top and rows run along +Z, so "up" in the image is −Z in the world; glTF's
//! `TEXCOORD_0` has v along +Z (top-left origin), and an engine with a bottom-left origin (OpenGL,
//! Blender) sees v' = 1 − v growing towards −Z: `tangent-gl`'s B = dP/dv'. The maps hold floats in
//! [−1, 1] (EXR) or `(n + 1) / 2` of full scale (PNG) in every space.

use glam::Vec3;

crate::closed_set! {
    /// The space of a baked normal map; see the module documentation for the exact frames. The
    /// names are those of the command line and `bake.json`.
    #[derive(Default)]
    pub enum NormalSpace: "a normal space" {
        /// The unit normal in swell's world axes (x, y, z), +Y up. The default.
        #[default]
        World = "world",
        /// Tangent space of the flat patch, OpenGL convention: (n.x, −n.z, n.y).
        TangentGl = "tangent-gl",
        /// Tangent space of the flat patch, DirectX convention: (n.x, n.z, n.y).
        TangentDx = "tangent-dx",
    }
}

impl NormalSpace {
    /// The world unit normal `n` expressed in this space (a permutation with one sign: exact).
    #[inline]
    pub fn from_world(self, n: Vec3) -> Vec3 {
        match self {
            NormalSpace::World => n,
            NormalSpace::TangentGl => Vec3::new(n.x, -n.z, n.y),
            NormalSpace::TangentDx => Vec3::new(n.x, n.z, n.y),
        }
    }

    /// What the normal map's R, G, B hold, in words (for `bake.json`).
    pub fn channels(self) -> &'static str {
        match self {
            NormalSpace::World => "R, G, B = unit normal x, y, z in world axes (+Y up)",
            NormalSpace::TangentGl => {
                "R, G, B = unit normal in tangent space of the flat patch, OpenGL convention: \
                 R = n.x (T = +X), G = -n.z (B = -Z, towards the image's top), B = n.y (N = +Y)"
            }
            NormalSpace::TangentDx => {
                "R, G, B = unit normal in tangent space of the flat patch, DirectX convention: \
                 R = n.x (T = +X), G = n.z (B = +Z, towards the image's bottom), B = n.y (N = +Y)"
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_bad_names_list_the_valid_ones() {
        for &m in NormalSpace::ALL {
            assert_eq!(NormalSpace::parse("--normal-space", m.name()).unwrap(), m);
            let json = serde_json::to_string(&m).unwrap();
            assert_eq!(json, format!("\"{}\"", m.name()));
        }
        let e = NormalSpace::parse("--normal-space", "tangent").unwrap_err().to_string();
        assert!(
            e.contains("--normal-space") && e.contains("`tangent`") && e.contains("world, tangent-gl, tangent-dx"),
            "{e}"
        );
    }

    #[test]
    fn flat_water_points_along_blue_and_tilts_map_to_the_conventions() {
        let up = Vec3::Y;
        for m in [NormalSpace::TangentGl, NormalSpace::TangentDx] {
            assert_eq!(m.from_world(up), Vec3::Z, "{m:?}");
        }
        // A surface rising towards +X leans its normal towards -X: red goes negative in all spaces.
        let n = Vec3::new(-0.6, 0.8, 0.0);
        assert_eq!(NormalSpace::TangentGl.from_world(n), Vec3::new(-0.6, 0.0, 0.8));
        // A surface rising towards -Z (the image's top) leans towards +Z: OpenGL green (up) goes
        // negative, DirectX green (down) positive.
        let n = Vec3::new(0.0, 0.8, 0.6);
        assert_eq!(NormalSpace::TangentGl.from_world(n).y, -0.6);
        assert_eq!(NormalSpace::TangentDx.from_world(n).y, 0.6);
        // The OpenGL frame is right-handed: T x B = N.
        let (t, b, nn) = (Vec3::X, Vec3::NEG_Z, Vec3::Y);
        assert_eq!(t.cross(b), nn);
        // Each space reads back to the world normal through its frame.
        let n = Vec3::new(0.3, 0.9, -0.3).normalize();
        let gl = NormalSpace::TangentGl.from_world(n);
        assert!((t * gl.x + b * gl.y + nn * gl.z - n).length() < 1e-7);
        let dx = NormalSpace::TangentDx.from_world(n);
        assert!((t * dx.x + Vec3::Z * dx.y + nn * dx.z - n).length() < 1e-7);
    }
}
