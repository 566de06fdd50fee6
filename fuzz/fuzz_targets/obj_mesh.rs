//! OBJ reader: any text either reads into a mesh whose every index is in range, whose positions
//! are finite and whose normals are finite unit vectors, or is refused with an error. Never a
//! panic, and never an allocation past the OBJ limits (libFuzzer's -rss_limit_mb catches that).
#![no_main]

use libfuzzer_sys::fuzz_target;
use swell::mesh::parse_obj;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    if let Ok(mesh) = parse_obj(text, "fuzz.obj") {
        assert_eq!(mesh.indices.len() % 3, 0);
        assert_eq!(mesh.positions.len(), mesh.normals.len());
        assert!(mesh.indices.iter().all(|&i| (i as usize) < mesh.positions.len()));
        assert!(mesh.positions.iter().all(|p| p.is_finite()));
        assert!(mesh.normals.iter().all(|n| n.is_finite() && (n.length() - 1.0).abs() < 1e-3), "{:?}", mesh.normals);
    }
});
