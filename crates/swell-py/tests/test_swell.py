"""pytest suite of the swell Python package (issue 19).

Comparisons with the command line need the `swell` binary: set SWELL_BIN to it (.ci/run does), or
build it at target/release/swell. Without it those tests skip, unless SWELL_REQUIRE_CLI is set.
"""

import json
import os
import struct
import subprocess
import threading
import time
import zlib
from pathlib import Path

import numpy as np
import pytest

import swell

ROOT = Path(__file__).resolve().parents[3]
PRESETS = ROOT / "crates" / "swell" / "presets"


def preset(name, **replace):
    text = (PRESETS / f"{name}.toml").read_text()
    for old, new in replace.items():
        assert old in text, old
        text = text.replace(old, new)
    return text


OCEAN = preset("ocean", **{"cells = [400, 400]": "cells = [48, 48]", "width = 1280\nheight = 720": "width = 160\nheight = 90"})
SEA = preset("sea", **{"cells = [256, 256]": "cells = [32, 32]"})
ONLY_WATER = "[water]\nmodel = 'sines'\nsize = [20.0, 10.0]\ncells = [8, 4]\n[[water.waves]]\namplitude = 0.3\nwavelength = 7.0\nspeed = 2.0\ndirection = [1.0, 0.5]\n"
CAMERA = "version = 1\n[camera]\neye = [0.0, 10.0, 30.0]\ntarget = [0.0, 0.0, 0.0]\n"


def cli():
    path = os.environ.get("SWELL_BIN") or str(ROOT / "target" / "release" / "swell")
    if not Path(path).is_file():
        if os.environ.get("SWELL_REQUIRE_CLI"):
            pytest.fail(f"the swell binary {path} is missing and SWELL_REQUIRE_CLI is set")
        pytest.skip("no swell binary (set SWELL_BIN)")
    return path


def run_cli(*args, ok=True):
    p = subprocess.run([cli(), *args], capture_output=True, text=True)
    if ok:
        assert p.returncode == 0, p.stderr
    return p


def read_png_rgba(path):
    """A minimal decoder for the 8-bit RGBA, non-interlaced PNGs swell writes."""
    data = Path(path).read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat, width, height = 8, b"", 0, 0
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos : pos + 4])
        kind, body = data[pos + 4 : pos + 8], data[pos + 8 : pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, color, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert (depth, color, interlace) == (8, 6, 0)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = np.frombuffer(zlib.decompress(idat), dtype=np.uint8).reshape(height, 1 + 4 * width)
    out = np.zeros((height, 4 * width), dtype=np.int32)
    for y in range(height):  # PNG's filters are defined row by row
        f, line = raw[y, 0], raw[y, 1:].astype(np.int32)
        prev = out[y - 1] if y else np.zeros(4 * width, dtype=np.int32)
        if f == 0:
            out[y] = line
        elif f == 1:
            row = line.copy()
            for x in range(4, 4 * width):
                row[x] = (row[x] + row[x - 4]) & 255
            out[y] = row
        elif f == 2:
            out[y] = (line + prev) & 255
        else:
            row = line.copy()
            for x in range(4 * width):
                a = row[x - 4] if x >= 4 else 0
                b, c = prev[x], (prev[x - 4] if x >= 4 else 0)
                if f == 3:
                    row[x] = (row[x] + (a + b) // 2) & 255
                else:
                    p = a + b - c
                    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                    pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                    row[x] = (row[x] + pred) & 255
            out[y] = row
    return out.astype(np.uint8).reshape(height, width, 4)


def test_version_is_the_crate_version():
    cargo = (ROOT / "Cargo.toml").read_text()
    assert f'version = "{swell.__version__}"' in cargo


def test_displace_gives_float32_grids_of_rows_by_cols():
    w = swell.Water.from_toml(SEA)
    pos, nrm = w.displace(1.5)
    assert pos.shape == nrm.shape == (w.rows, w.cols, 3) == (33, 33, 3)
    assert pos.dtype == nrm.dtype == np.float32
    assert np.allclose(np.linalg.norm(nrm, axis=2), 1.0, atol=1e-5)
    # Row j runs along +Z, column i along +X: 200 m over 32 cells is 6.25 m between rest points.
    assert abs(np.mean(pos[:, 1:, 0] - pos[:, :-1, 0]) - 6.25) < 0.1
    assert abs(np.mean(pos[1:, :, 2] - pos[:-1, :, 2]) - 6.25) < 0.1


def test_only_water_is_required():
    try:
        w = swell.Water.from_toml(ONLY_WATER)
    except ValueError as e:  # before Scene::from_toml gave version and camera defaults
        pytest.skip(f"this build still needs version and [camera]: {e}")
    assert (w.rows, w.cols) == (5, 9)


def test_positions_equal_the_cli_export_of_that_time(tmp_path):
    scene = tmp_path / "ocean.toml"
    scene.write_text(OCEAN)
    obj = tmp_path / "ocean.obj"
    run_cli("export", "--scene", str(scene), "--time", "0.625", "--out", str(obj))
    v, vn, inside = [], [], False
    for line in obj.read_text().splitlines():
        if line.startswith("o "):
            inside = line == "o water"
        elif inside and line.startswith("v "):
            v.append([float(s) for s in line.split()[1:]])
        elif inside and line.startswith("vn "):
            vn.append([float(s) for s in line.split()[1:]])
    w = swell.Water.from_file(scene)
    w.displace(3.0)  # another time first: answers do not depend on history
    pos, nrm = w.displace(0.625)
    assert np.array_equal(pos.reshape(-1, 3), np.array(v, dtype=np.float32))
    assert np.array_equal(nrm.reshape(-1, 3), np.array(vn, dtype=np.float32))


def test_heights_broadcast_and_match_the_mesh():
    w = swell.Water.from_toml(OCEAN)
    pos, _ = w.displace(2.0)
    x, z = pos[..., 0], pos[..., 2]
    h = w.height_at(x, z, 2.0)
    assert h.shape == x.shape and h.dtype == np.float64
    assert np.max(np.abs(h - pos[..., 1])) < 2e-3
    grid = w.height_at(np.array([[1.0], [2.0]]), np.array([0.0, 5.0, 9.0]), 2.0)
    assert grid.shape == (2, 3)
    assert grid[1, 2] == w.height_at(2.0, 9.0, 2.0)
    one = w.height_at(1.0, 2.0, 2.0)
    assert isinstance(one, float)
    n = w.normal_at([1.0, 2.0], 3.0, 2.0)
    assert n.shape == (2, 3) and np.allclose(np.linalg.norm(n, axis=1), 1.0)


def test_answers_do_not_depend_on_the_order_of_calls():
    # Within the 32 m lattice: off it there is no water and the answer is NaN.
    pts = np.linspace(-15, 15, 101)
    fresh = swell.Water.from_toml(preset("springs"))
    expected = fresh.height_at(pts, pts * 0.5, 4.0)
    used = swell.Water.from_toml(preset("springs"))
    for t in (9.0, 1.0, 4.0, 0.0):
        used.height_at(pts, pts, t)
        used.displace(t)
    assert np.isfinite(expected).all() and np.abs(expected).max() > 0
    assert np.array_equal(used.height_at(pts, pts * 0.5, 4.0), expected)


def test_foam_only_where_the_model_has_it():
    f = swell.Water.from_toml(OCEAN).foam(2.0)
    assert f.shape == (49, 49) and f.dtype == np.float32
    assert f.min() >= 0.0 and f.max() <= 1.0
    assert swell.Water.from_toml(SEA).foam(2.0) is None


def test_render_gives_the_cli_png_pixels(tmp_path):
    img = swell.render(OCEAN, t=1.25, width=96, height=54)
    assert img.shape == (54, 96, 3) and img.dtype == np.uint8
    scene = tmp_path / "ocean.toml"
    scene.write_text(OCEAN)
    png = tmp_path / "ocean.png"
    run_cli("render", "--scene", str(scene), "--time", "1.25", "--size", "96x54", "--out", str(png))
    assert np.array_equal(read_png_rgba(png)[..., :3], img)
    assert swell.render(OCEAN).shape == (90, 160, 3)


def test_stats_are_the_cli_s(tmp_path):
    ours = swell.stats(OCEAN, t=1.5)
    assert ours["hs_realised_m"] > 0 and ours["surface_cells"] == [48, 48]
    scene = tmp_path / "ocean.toml"
    scene.write_text(OCEAN)
    theirs = json.loads(run_cli("stats", "--scene", str(scene), "--time", "1.5").stdout)
    assert ours == theirs


STEEP = CAMERA + "[water]\nmodel = 'gerstner'\n[[water.waves]]\namplitude = 1.0\nwavelength = 10.0\nspeed = 3.0\ndirection = [1.0, 0.0]\nsteepness = 1.7\n"


def test_bad_input_raises_value_error_with_the_cli_message(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(STEEP)
    message = run_cli("render", "--scene", str(bad), "--out", str(tmp_path / "x.png"), ok=False).stderr.strip()
    assert message == f"error: {bad}: water.waves[0].steepness = 1.7 is outside [0, 1]"
    with pytest.raises(ValueError) as e:
        swell.Water.from_file(bad)
    assert "error: " + str(e.value) == message
    # Scene text has no file name: its errors name it `toml`, where the CLI names the file.
    for call in (lambda: swell.Water.from_toml(STEEP), lambda: swell.render(STEEP), lambda: swell.stats(STEEP)):
        with pytest.raises(ValueError) as e:
            call()
        assert "error: " + str(e.value) == message.replace(str(bad), "toml")
    w = swell.Water.from_toml(SEA)
    with pytest.raises(ValueError, match=r"^t = NaN is outside finite seconds$"):
        w.displace(float("nan"))
    with pytest.raises(ValueError, match=r"^t = inf is outside finite seconds$"):
        w.height_at(0.0, 0.0, float("inf"))
    with pytest.raises(ValueError, match=r"^width = 0 is outside \[1, 16384\]$"):
        swell.render(SEA, width=0)
    with pytest.raises(ValueError, match="swell stats needs a spectral sea"):
        swell.stats(SEA)
    with pytest.raises(ValueError, match="TOML parse error"):
        swell.Water.from_toml("[water\n")
    with pytest.raises(ValueError, match="shape mismatch"):
        w.height_at(np.zeros(3), np.zeros(4), 0.0)
    with pytest.raises(OSError):
        swell.Water.from_file(tmp_path / "missing.toml")
    with pytest.raises(TypeError):
        w.displace("soon")


def test_the_gil_is_released_during_queries():
    w = swell.Water.from_toml(OCEAN)
    x = np.random.default_rng(1).uniform(-500, 500, 2_000_000)
    done, ticks = threading.Event(), 0

    def work():
        w.height_at(x, x[::-1], 3.0)
        done.set()

    thread = threading.Thread(target=work)
    start = time.perf_counter()
    thread.start()
    while not done.is_set():
        ticks += 1
        time.sleep(0.001)
    thread.join()
    elapsed = time.perf_counter() - start
    # With the GIL held for the whole call this loop could not run while it lasted (a tick or two).
    assert elapsed > 0.05 and ticks > 20, (ticks, elapsed)
