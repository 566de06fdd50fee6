#!/usr/bin/env python3
"""Turns a swell 16-bit heightmap (PNG + `.toml` sidecar) into a Wavefront OBJ with `v`, `vn`, `f`.

Two triangles per cell, counter-clockwise seen from +Y (the winding swell's own grids use), vertex
normals from central differences of the heights. The same file then feeds `swell render --obj` and
`gl_render.py`, so the two renderers draw exactly the same triangles.

    heightmap_to_obj.py terrain.png terrain.obj
"""
import sys
import tomllib

import numpy as np
from PIL import Image


def main(png_path, obj_path):
    with open(png_path + ".toml", "rb") as f:
        side = tomllib.load(f)
    grey = np.asarray(Image.open(png_path), dtype=np.float64)
    rows, cols = grey.shape
    heights = side["height_offset"] + side["height_scale"] * grey / 65535.0
    ex, ez = side["extent"]
    # The grid is centred on the origin, row index along +Z, column index along +X.
    xs = (np.arange(cols) / (cols - 1) - 0.5) * ex
    zs = (np.arange(rows) / (rows - 1) - 0.5) * ez
    dx, dz = ex / (cols - 1), ez / (rows - 1)
    gx = np.gradient(heights, dx, axis=1)
    gz = np.gradient(heights, dz, axis=0)
    normals = np.dstack([-gx, np.ones_like(heights), -gz])
    normals /= np.linalg.norm(normals, axis=2, keepdims=True)
    with open(obj_path, "w") as out:
        out.write(f"# {png_path}: {cols} x {rows} heightmap, {2 * (cols - 1) * (rows - 1)} triangles\n")
        for r in range(rows):
            out.write("".join(f"v {xs[c]:.5f} {heights[r, c]:.5f} {zs[r]:.5f}\n" for c in range(cols)))
        for r in range(rows):
            out.write("".join(f"vn {n[0]:.6f} {n[1]:.6f} {n[2]:.6f}\n" for n in normals[r]))
        for r in range(rows - 1):
            lines = []
            for c in range(cols - 1):
                a = r * cols + c + 1  # OBJ indices start at 1
                b, d, e = a + 1, a + cols, a + cols + 1
                # Seen from +Y with +Z toward the viewer's bottom: (a, d, b) and (b, d, e) are CCW.
                lines.append(f"f {a}//{a} {d}//{d} {b}//{b}\nf {b}//{b} {d}//{d} {e}//{e}\n")
            out.write("".join(lines))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: heightmap_to_obj.py HEIGHTMAP.png OUT.obj")
    main(sys.argv[1], sys.argv[2])
