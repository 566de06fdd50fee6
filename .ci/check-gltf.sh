#!/usr/bin/env bash
# Exports the sea preset (and the floating bodies' example) as .glb and .gltf (+ .bin) and runs the Khronos glTF-Validator on them.
# Needs node + npm (the npm registry, or its cache) and a built `swell`:
#   bash .ci/check-gltf.sh [path/to/swell]        (default: target/release/swell)
set -euo pipefail
swell=${1:-target/release/swell}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
(cd "$work" && npm install --silent --no-audit --no-fund gltf-validator >/dev/null)
"$swell" export --preset sea --time 2.5 --out "$work/sea.glb"
"$swell" export --preset sea --time 2.5 --out "$work/sea.gltf"
"$swell" export --preset sea --frames 0..1 --out "$work/seq.glb"
# issue 34: floating bodies in each frame and their motion as a node animation (flotsam_bodies.glb).
"$swell" export --scene "$(dirname "$0")/../docs/examples/floating/flotsam.toml" --frames 0..3 --out "$work/flotsam.glb"
GLTF_VALIDATOR_DIR="$work" node "$(dirname "$0")/validate-gltf.mjs" "$work"/*.glb "$work/sea.gltf"
