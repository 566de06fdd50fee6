#!/usr/bin/env bash
# swell's rasterizer against Mesa's llvmpipe on paper 001's largest case: a 513 x 513 diamond-square
# heightmap (524,288 triangles) at 800 x 800, flat and Gouraud, 1 and 2 threads. Prints one JSON line
# per run and the image agreement; leaves the images in $OUT. See tools/llvmpipe/README.md.
set -euo pipefail
cd "$(dirname "$0")/../.."
OUT=${OUT:-target/llvmpipe}
REPEAT=${REPEAT:-20}
mkdir -p "$OUT"
cargo build --release -q -p swell-cli
SWELL=target/release/swell
T=tools/llvmpipe

$SWELL terrain --generator diamond-square --size 513 --seed 1 --extent 200 --out "$OUT/terrain.png" >/dev/null
python3 $T/heightmap_to_obj.py "$OUT/terrain.png" "$OUT/terrain.obj"
cat > "$OUT/camera.json" <<JSON
{"eye": [0, 160, 190], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y_deg": 45, "near": 1, "far": 1000,
 "width": 800, "height": 800}
JSON
cat > "$OUT/light.json" <<JSON
{"dir": [-0.4, -1.0, -0.6], "color": [0.8, 0.8, 0.8], "ambient": [0.2, 0.2, 0.2],
 "base_color": [0.8, 0.8, 0.8], "background": [0, 0, 0]}
JSON

for shading in flat gouraud; do
  for threads in 1 2; do
    common=(--obj "$OUT/terrain.obj" --camera "$OUT/camera.json" --light "$OUT/light.json" --shading $shading)
    s=$($SWELL render "${common[@]}" --threads $threads --repeat "$REPEAT" --out "$OUT/swell-$shading.png")
    g=$(LP_NUM_THREADS=$threads python3 $T/gl_render.py "${common[@]}" --repeat "$REPEAT" --out "$OUT/gl-$shading.png")
    echo "{\"shading\": \"$shading\", \"threads\": $threads, \"swell\": $s, \"llvmpipe\": $g}"
  done
  echo "{\"shading\": \"$shading\", \"agreement\": $(python3 $T/compare_images.py "$OUT/swell-$shading.png" "$OUT/gl-$shading.png")}"
done
