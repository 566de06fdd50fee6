#!/usr/bin/env python3
"""Renders an OBJ mesh with OpenGL exactly as `swell render --obj` defines the image, for comparison.

Same inputs as swell's comparison mode: the OBJ (v, vn, f), the camera JSON
`{"eye","target","up","fov_y_deg","near","far","width","height"}` and the light JSON
`{"dir","color","ambient","base_color","background"}`; colour = base * (ambient + color * max(0, N.L)),
L = -dir, no gamma, into an RGBA8 framebuffer object, depth test on, no culling. `flat` lights each
triangle with its geometric normal (taken from the screen-space derivatives of the position, as a
GL program does without duplicating vertices), `gouraud` each vertex with its normal.

With Mesa's llvmpipe (the default when no GPU is present: `moderngl` makes a surfaceless EGL
context) this is "a general OpenGL implementation on the CPU". `--repeat N` prints
`{"median_ms": ..., "renderer": ...}` over N frames, each timed from clear to `glFinish`
(file loading and the read-back excluded, as swell's `--repeat` excludes them).

    gl_render.py --obj M.obj --camera C.json [--light L.json] --shading flat|gouraud --out F.png [--repeat N]
"""
import argparse
import json
import statistics
import sys
import time

import moderngl
import numpy as np
from PIL import Image

VERTEX = """
#version 330
uniform mat4 clip_from_world;
uniform vec3 to_light, color, ambient, base_color;
in vec3 in_position;
in vec3 in_normal;
out vec3 v_world;
out vec3 v_color;
void main() {
    v_world = in_position;
    v_color = base_color * (ambient + color * max(0.0, dot(normalize(in_normal), to_light)));
    gl_Position = clip_from_world * vec4(in_position, 1.0);
}
"""

FRAGMENT = """
#version 330
uniform int flat_shading;
uniform vec3 to_light, color, ambient, base_color;
in vec3 v_world;
in vec3 v_color;
out vec4 frag;
void main() {
    if (flat_shading == 1) {
        // Front faces (counter-clockwise on screen) get the normal that points at the viewer,
        // which is the winding-order normal (b - a) x (c - a) swell uses.
        vec3 n = normalize(cross(dFdx(v_world), dFdy(v_world)));
        if (!gl_FrontFacing) n = -n;
        frag = vec4(base_color * (ambient + color * max(0.0, dot(n, to_light))), 1.0);
    } else {
        frag = vec4(v_color, 1.0);
    }
}
"""


def read_obj(path):
    positions, normals, vertex_of = [], [], {}
    out_pos, out_nrm, indices = [], [], []
    with open(path) as f:
        for line in f:
            tag, _, rest = line.partition(" ")
            if tag == "v":
                positions.append([float(x) for x in rest.split()[:3]])
            elif tag == "vn":
                normals.append([float(x) for x in rest.split()[:3]])
            elif tag == "f":
                face = []
                for corner in rest.split():
                    key = corner
                    if key not in vertex_of:
                        parts = corner.split("/")
                        vi = int(parts[0]) - 1
                        ni = int(parts[2]) - 1 if len(parts) > 2 and parts[2] else vi
                        vertex_of[key] = len(out_pos)
                        out_pos.append(positions[vi])
                        out_nrm.append(normals[ni] if normals else [0.0, 1.0, 0.0])
                    face.append(vertex_of[key])
                for i in range(1, len(face) - 1):  # fan, as swell's reader splits polygons
                    indices += [face[0], face[i], face[i + 1]]
    return (np.array(out_pos, dtype="f4"), np.array(out_nrm, dtype="f4"), np.array(indices, dtype="u4"))


def look_at_rh(eye, target, up):
    f = target - eye
    f /= np.linalg.norm(f)
    s = np.cross(f, up)
    s /= np.linalg.norm(s)
    u = np.cross(s, f)
    m = np.identity(4)
    m[0, :3], m[1, :3], m[2, :3] = s, u, -f
    m[:3, 3] = [-s @ eye, -u @ eye, f @ eye]
    return m


def perspective_rh_gl(fov_y, aspect, near, far):
    t = 1.0 / np.tan(fov_y / 2)
    m = np.zeros((4, 4))
    m[0, 0], m[1, 1] = t / aspect, t
    m[2, 2], m[2, 3] = (far + near) / (near - far), 2 * far * near / (near - far)
    m[3, 2] = -1.0
    return m


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--obj", required=True)
    ap.add_argument("--camera", required=True)
    ap.add_argument("--light")
    ap.add_argument("--shading", choices=["flat", "gouraud"], default="flat")
    ap.add_argument("--out", required=True)
    ap.add_argument("--repeat", type=int)
    a = ap.parse_args()

    cam = json.load(open(a.camera))
    light = {"dir": [-0.4, -1.0, -0.6], "color": [0.8] * 3, "ambient": [0.2] * 3, "base_color": [0.8] * 3,
             "background": [0.0] * 3}
    if a.light:
        light.update(json.load(open(a.light)))
    w, h = int(cam["width"]), int(cam["height"])
    eye, target = np.array(cam["eye"], float), np.array(cam["target"], float)
    up = np.array(cam.get("up", [0, 1, 0]), float)
    proj = perspective_rh_gl(np.radians(cam.get("fov_y_deg", 45.0)), w / h, cam.get("near", 0.1), cam.get("far", 5000.0))
    clip_from_world = proj @ look_at_rh(eye, target, up)

    pos, nrm, idx = read_obj(a.obj)
    ctx = moderngl.create_standalone_context(backend="egl")
    prog = ctx.program(vertex_shader=VERTEX, fragment_shader=FRAGMENT)
    prog["clip_from_world"].write(clip_from_world.T.astype("f4").tobytes())  # column-major
    d = np.array(light["dir"], float)
    prog["to_light"].value = tuple(-d / np.linalg.norm(d))
    for key in ["color", "ambient", "base_color"]:
        prog[key].value = tuple(light[key][:3])
    prog["flat_shading"].value = 1 if a.shading == "flat" else 0
    vao = ctx.vertex_array(
        prog,
        [(ctx.buffer(pos.tobytes()), "3f", "in_position"), (ctx.buffer(nrm.tobytes()), "3f", "in_normal")],
        index_buffer=ctx.buffer(idx.tobytes()),
        index_element_size=4,
    )
    fbo = ctx.framebuffer(color_attachments=[ctx.renderbuffer((w, h), 4)], depth_attachment=ctx.depth_renderbuffer((w, h)))
    fbo.use()
    ctx.enable(moderngl.DEPTH_TEST)
    bg = tuple(light["background"][:3]) + (1.0,)

    def frame():
        fbo.clear(*bg, depth=1.0)
        vao.render(moderngl.TRIANGLES)
        ctx.finish()

    frame()  # warm-up: shader compilation and buffer upload happen on first use
    if a.repeat:
        times = []
        for _ in range(a.repeat):
            t0 = time.perf_counter()
            frame()
            times.append((time.perf_counter() - t0) * 1e3)
        print(json.dumps({"median_ms": statistics.median(times), "renderer": ctx.info["GL_RENDERER"],
                          "triangles": len(idx) // 3, "width": w, "height": h}))
    rgba = np.frombuffer(fbo.read(components=4), dtype=np.uint8).reshape(h, w, 4)[::-1]  # GL rows go up
    Image.fromarray(rgba, "RGBA").save(a.out)


if __name__ == "__main__":
    sys.exit(main())
