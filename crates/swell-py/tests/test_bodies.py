"""Floating bodies from Python (issue 34): ``swell.World`` floats the same bodies the same way as
the Rust library and the C API, obeys Archimedes, and does not depend on the frame rate.

``bodies_reference.json`` holds poses written by the Rust test
``added_bodies_and_thrust_are_the_library_s_and_the_python_reference``
(crates/swell-capi/src/tests.rs), which checks that the C API and the library's ``World`` give
them bit for bit; here Python must give them bit for bit too.
"""

import json
import math
from pathlib import Path

import numpy as np
import pytest

import swell

REFERENCE = json.loads((Path(__file__).resolve().parent / "bodies_reference.json").read_text())


def still_water(*bodies, amplitude=0.005):
    """Nearly still fresh water (a 5 mm swell) over a 40 m patch, with the given [[body]] tables."""
    return (
        "version = 1\n[water]\nmodel = 'sines'\nsize = [40.0, 40.0]\ncells = [8, 8]\ndensity = 1000.0\n"
        f"[[water.waves]]\namplitude = {amplitude}\nwavelength = 15.0\nspeed = 4.8\ndirection = [1.0, 0.0]\n"
        + "".join(bodies)
    )


def plank(name, density, y=1.0, x=0.0):
    """A 2 x 0.5 x 2 m box: flat enough to float level at any density (a cube of pine would roll
    onto an edge, as real ones do)."""
    return (
        f"[[body]]\nname = '{name}'\nshape = 'box'\nsize = [2.0, 0.5, 2.0]\ndensity = {density}\n"
        f"position = [{x}, {y}, 0.0]\n"
    )


def test_poses_are_the_rust_library_s_bit_for_bit():
    ref = REFERENCE
    world = swell.World.from_toml(ref["scene"])
    records = iter(ref["records"])
    for frame in range(ref["last_frame"] + 1):
        t = frame / 60.0
        world.advance(t)
        assert world.time == t
        if frame % ref["record_every"] == 0:
            r = next(records)
            assert (r["frame"], r["t"]) == (frame, t)
            positions, rotations = world.positions, world.rotations
            assert positions.dtype == np.float64 and positions.shape == (len(world), 3)
            assert rotations.dtype == np.float64 and rotations.shape == (len(world), 4)
            np.testing.assert_array_equal(positions, np.array(r["positions"]), err_msg=f"t = {t}")
            np.testing.assert_array_equal(rotations, np.array(r["rotations"]), err_msg=f"t = {t}")
        if frame == ref["add_frame"]:
            assert world.add_body(ref["add_toml"]) == 3
            assert world.add_body(**ref["add_keys"]) == 4
        if frame == ref["thrust_frame"]:
            world.set_thrust(ref["thrust_body"], ref["thrust"])
    assert next(records, None) is None
    assert world.names == ref["names"]


def test_straight_to_t_and_in_60_fps_steps_give_identical_poses():
    text = REFERENCE["scene"]
    straight = swell.World.from_toml(text)
    straight.advance(3.0)
    stepped = swell.World.from_toml(text)
    for frame in range(181):
        stepped.advance(frame / 60.0)
    np.testing.assert_array_equal(straight.positions, stepped.positions)
    np.testing.assert_array_equal(straight.rotations, stepped.rotations)
    # Asked for an earlier time, the world replays from t = 0: the poses of a fresh world.
    stepped.advance(1.25)
    fresh = swell.World.from_toml(text)
    fresh.advance(1.25)
    np.testing.assert_array_equal(stepped.positions, fresh.positions)
    np.testing.assert_array_equal(stepped.rotations, fresh.rotations)
    # And the bodies did move in between: the comparisons above are not of poses at rest.
    assert np.abs(fresh.positions - straight.positions).max() > 0.1


def test_planks_float_as_archimedes_says():
    # Planks half a metre thick dropped from 1 m onto nearly still fresh water: pine (500 kg/m³)
    # floats half under, its centre at the water line; a 250 kg/m³ one a quarter under, its centre
    # 0.125 m up; stone (3000 kg/m³) sinks (no ground below).
    world = swell.World.from_toml(
        still_water(plank("pine", 500.0), plank("light", 250.0, x=5.0), plank("stone", 3000.0, x=-5.0))
    )
    world.advance(6.0)
    # Two seconds more at 60 fps (two heave periods): on average where Archimedes puts them, still
    # bobbing by centimetres (the water's radiation damping is not modelled), level.
    heights, levels = [], []
    for frame in range(361, 481):
        world.advance(frame / 60.0)
        heights.append(world.positions[:, 1])
        levels.append(np.abs(world.rotations[:2, 3]))
    heights = np.array(heights)
    assert abs(heights[:, 0].mean()) < 0.005, heights[:, 0].mean()
    assert abs(heights[:, 1].mean() - 0.125) < 0.005, heights[:, 1].mean()
    assert np.abs(heights[:, :2] - [0.0, 0.125]).max() < 0.06, heights[:, :2]
    assert heights[:, 2].max() < -20.0, heights[:, 2]
    assert np.min(levels) > 0.999, np.min(levels)
    assert np.allclose(np.linalg.norm(world.rotations, axis=1), 1.0, atol=1e-12)


def test_a_body_dropped_into_a_running_world_and_a_thrust():
    world = swell.World.from_toml(still_water(plank("pine", 500.0, y=0.0)))
    world.advance(2.0)
    k = world.add_body(shape="sphere", size=np.array([0.3]), density=np.float32(300.0), position=(3, 2, 0))
    assert (k, world.names, len(world)) == (1, ["pine", "body1"], 2)
    # Held at its initial pose until the next body step, then falling.
    np.testing.assert_array_equal(world.positions[1], [3.0, 2.0, 0.0])
    np.testing.assert_array_equal(world.rotations[1], [0.0, 0.0, 0.0, 1.0])
    world.advance(2.25)
    assert world.positions[1, 1] < 2.0 - 0.1
    world.advance(6.0)
    # A 300 kg/m³ ball floats 30 % under: its centre above the water line.
    assert 0.0 < world.positions[1, 1] < 0.3, world.positions
    assert world.index("body1") == 1

    pushed = swell.World.from_toml(still_water(plank("pine", 500.0, y=0.0)))
    pushed.set_thrust("pine", [200.0, 0.0, 0.0])
    np.testing.assert_array_equal(pushed.thrusts, [[200.0, 0.0, 0.0]])
    pushed.advance(6.0)
    # 200 N against the water's drag: the crate has gone metres east, the other stayed.
    assert pushed.positions[0, 0] > world.positions[0, 0] + 1.0, (pushed.positions, world.positions)
    pushed.set_thrust(0, np.zeros(3))
    np.testing.assert_array_equal(pushed.thrusts, [[0.0, 0.0, 0.0]])


def test_a_mesh_body_from_a_scene_file_finds_its_obj_beside_the_file(tmp_path, monkeypatch):
    # The plank as a closed mesh, counter-clockwise seen from outside.
    v = [(x, y, z) for x in (-1.0, 1.0) for y in (-0.25, 0.25) for z in (-1.0, 1.0)]
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    obj = "".join(f"v {x} {y} {z}\n" for x, y, z in v)
    obj += "".join(f"f {a + 1} {b + 1} {c + 1}\nf {a + 1} {c + 1} {d + 1}\n" for a, b, c, d in quads)
    (tmp_path / "hulls").mkdir()
    (tmp_path / "hulls" / "plank.obj").write_text(obj)
    scene = tmp_path / "scene.toml"
    scene.write_text(still_water("[[body]]\nname = 'hull'\nshape = 'mesh'\npath = 'hulls/plank.obj'\nposition = [0.0, 1.0, 0.0]\n"))
    world = swell.World.from_file(scene)
    world.advance(8.0)
    # As the pine plank (500 kg/m³ by default): half under, its centre near the water line.
    assert abs(world.positions[0, 1]) < 0.06, world.positions
    # Added from Python, a relative path is relative to the working directory.
    monkeypatch.chdir(tmp_path)
    assert world.add_body(shape="mesh", path=Path("hulls/plank.obj"), position=[5.0, 1.0, 0.0], density=250.0) == 1
    world.advance(16.0)
    assert world.names == ["hull", "body1"]
    assert abs(world.positions[1, 1] - 0.125) < 0.06, world.positions


def test_a_world_without_bodies_has_empty_poses_and_takes_a_body_at_its_time():
    world = swell.World.from_toml(still_water())
    world.advance(3.0)
    assert len(world) == 0 and world.names == []
    assert world.positions.shape == (0, 3) and world.rotations.shape == (0, 4)
    assert repr(world) == "<swell.World 0 floating bodies, at t = 3 s>"
    # Dropped at t = 3 s, not at t = 0: held at its initial pose until the next step after 3 s.
    world.add_body(plank("pine", 500.0, y=2.0))
    np.testing.assert_array_equal(world.positions, [[0.0, 2.0, 0.0]])
    world.advance(3.2)
    # About g t² / 2 = 0.2 m fallen in 0.2 s, not three seconds' worth.
    assert 1.7 < world.positions[0, 1] < 1.85, world.positions


def test_bad_inputs_raise_naming_the_argument_or_key():
    world = swell.World.from_toml(REFERENCE["scene"])
    world.advance(1.0)
    before = (world.positions.copy(), world.rotations.copy())
    for t in (math.nan, math.inf, -0.5, 2e7):
        with pytest.raises(ValueError, match=r"^t = .* is outside \[0, 1e7\] seconds \(floating bodies start at t = 0\)$"):
            world.advance(t)
    # A refused call changed nothing.
    assert world.time == 1.0
    np.testing.assert_array_equal(world.positions, before[0])
    with pytest.raises(ValueError, match=r"^add_body: body\[3\]\.size: \[1\.0, 0\.5\] has 2 values"):
        world.add_body(shape="box", size=[1.0, 0.5])
    with pytest.raises(ValueError, match=r"^add_body: body\[3\]\.density = 0 is outside \[10, 20000\]$"):
        world.add_body(shape="box", size=[1.0, 1.0, 1.0], density=0)
    with pytest.raises(ValueError, match=r"^add_body: body\[3\]\.name: \"crate\" names an earlier body too"):
        world.add_body(name="crate", shape="sphere", size=[0.5])
    with pytest.raises(ValueError, match=r"^add_body: body\[3\]\.spin: unknown field `spin`"):
        world.add_body(shape="sphere", size=[0.5], spin=3)
    with pytest.raises(ValueError, match=r"^toml: body\[3\]\.shape: unknown variant `boat`"):
        world.add_body("[[body]]\nshape = 'boat'\nsize = [1.0]\n")
    with pytest.raises(ValueError, match=r"^toml: TOML parse error at line 3"):
        world.add_body("[[body]]\nshape = 'sphere'\nsize = [0.5\n")
    with pytest.raises(ValueError, match=r"^toml: holds 2 \[\[body\]\] tables; give exactly one"):
        world.add_body("[[body]]\nshape = 'sphere'\nsize = [0.5]\n" * 2)
    with pytest.raises(ValueError, match=r"^toml: holds 1 \[\[body\]\] table and other sections"):
        world.add_body("[[body]]\nshape = 'sphere'\nsize = [0.5]\n[render]\nwidth = 64\n")
    with pytest.raises(TypeError, match=r"^color: a value of type object is not one a \[\[body\]\] key takes"):
        world.add_body(shape="sphere", size=[0.5], color=object())
    with pytest.raises(TypeError, match="^add_body: give either the TOML text"):
        world.add_body()
    with pytest.raises(TypeError, match="^add_body: give either the TOML text"):
        world.add_body("[[body]]\nshape = 'sphere'\nsize = [0.5]\n", name="both")
    assert len(world) == 3, "nothing refused was added"
    with pytest.raises(KeyError, match="raft"):
        world.set_thrust("raft", [1.0, 0.0, 0.0])
    with pytest.raises(KeyError, match="raft"):
        world.index("raft")
    with pytest.raises(IndexError, match=r"^body: 3 is outside \[0, 3\) \(the world's bodies\)$"):
        world.set_thrust(3, [1.0, 0.0, 0.0])
    with pytest.raises(TypeError, match="^body: a float is not a body's index or name$"):
        world.set_thrust(1.0, [1.0, 0.0, 0.0])
    with pytest.raises(ValueError, match=r"^force: 2 values; must be 3"):
        world.set_thrust(0, [1.0, 0.0])
    with pytest.raises(ValueError, match=r"^force\[2\] = (NaN|inf) is outside finite newtons$"):
        world.set_thrust(0, [1.0, 0.0, math.nan])
    with pytest.raises(TypeError, match="^force: a str is not three numbers$"):
        world.set_thrust(0, "abc")
    np.testing.assert_array_equal(world.thrusts, np.zeros((3, 3)))
    with pytest.raises(ValueError, match=r"^toml: body\[1\]\.mass = -1 is outside"):
        swell.World.from_toml(REFERENCE["scene"].replace("mass = 40.0", "mass = -1.0"))


def test_a_body_thrown_out_of_the_finite_numbers_raises_instead_of_giving_nan():
    world = swell.World.from_toml(REFERENCE["scene"])
    world.set_thrust("buoy", [0.0, -1e300, 0.0])
    with pytest.raises(ValueError, match='"buoy" left the finite numbers'):
        world.advance(2.0)
    # The poses are still those of the last good time, finite.
    assert world.time == 0.0
    assert np.isfinite(world.positions).all() and np.isfinite(world.rotations).all()
    world.set_thrust("buoy", [0.0, 0.0, 0.0])
    world.advance(2.0)
    fresh = swell.World.from_toml(REFERENCE["scene"])
    fresh.advance(2.0)
    np.testing.assert_array_equal(world.positions, fresh.positions)
