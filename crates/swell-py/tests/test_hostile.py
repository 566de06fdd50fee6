"""Hostile input through the Python package (issue 37): queries that must not answer garbage with
calm water, and messages that must not echo control characters or overlong text."""

import datetime
import re

import numpy as np
import pytest

import swell

ONLY_WATER = "[water]\nmodel = 'sines'\nsize = [20.0, 10.0]\ncells = [8, 4]\n[[water.waves]]\namplitude = 0.3\nwavelength = 7.0\nspeed = 2.0\ndirection = [1.0, 0.5]\n"


@pytest.fixture
def water():
    return swell.Water.from_toml(ONLY_WATER)


@pytest.mark.parametrize("bad", [float("nan"), float("inf"), -float("inf")])
def test_a_non_finite_scalar_point_is_refused(water, bad):
    for query in (water.height_at, water.normal_at):
        with pytest.raises(ValueError, match=r"^x = (NaN|inf|-inf) is outside finite world metres$"):
            query(bad, 0.0, 0.0)
        with pytest.raises(ValueError, match=r"^z = "):
            query(0.0, bad, 0.0)


def test_the_first_bad_index_of_an_array_is_named(water):
    z = np.zeros((3, 4))
    z[1, 2] = np.nan
    z[2, 0] = np.inf
    with pytest.raises(ValueError, match=r"^z\[1, 2\] = NaN is outside finite world metres$"):
        water.height_at(np.zeros((3, 4)), z, 1.0)
    x = np.array([0.0, 1.0, -np.inf])
    with pytest.raises(ValueError, match=r"^x\[2\] = -inf "):
        water.normal_at(x, 0.0, 1.0)


@pytest.mark.parametrize(
    "bad, dtype",
    [
        (None, "object"),
        (np.array([1 + 2j]), "complex128"),
        (np.array(["1.0"]), "<U3"),
        (np.array([datetime.datetime(2026, 1, 1)], dtype="datetime64[s]"), "datetime64[s]"),
        (np.array([True, False]), "bool"),
        ("3.0", "<U3"),
    ],
)
def test_non_real_coordinates_raise_type_error_naming_the_dtype(water, bad, dtype):
    with pytest.raises(TypeError, match=rf"^x: dtype {re.escape(dtype)} is not a real number type"):
        water.height_at(bad, 0.0, 0.0)
    with pytest.raises(TypeError, match=r"^z: dtype"):
        water.normal_at(0.0, bad, 0.0)


def test_coordinates_past_the_models_arithmetic_are_refused(water):
    with pytest.raises(ValueError, match=r"^x\[1\] = 2e196 is outside world metres within 1e9 of the origin"):
        water.height_at(np.array([0.0, 2.0e196]), 0.0, 0.0)
    with pytest.raises(ValueError, match=r"^z = -1.5e9 is outside"):
        water.normal_at(0.0, -1.5e9, 0.0)


def test_integer_and_float_arrays_of_any_layout_are_still_taken(water):
    base = np.arange(12, dtype=np.float64).reshape(3, 4)
    expected = water.height_at(base, base.T.copy().T, 0.5)
    for x in (base.astype(np.int32), base.astype(np.uint16), base.astype(np.float32), np.asfortranarray(base), base[:, ::1]):
        np.testing.assert_array_equal(water.height_at(x, base, 0.5), expected)
    # A strided view and a list of ints.
    np.testing.assert_array_equal(water.height_at(base[::2, ::2], base[::2, ::2], 0.5), expected[::2, ::2])
    assert water.height_at([0, 1], [2, 3], 0.5).shape == (2,)


def test_messages_escape_control_and_bidi_characters_and_are_cut():
    hostile_key = "w\x1b]0;pwned\x07\x1b[2J\u202e"
    with pytest.raises(ValueError) as e:
        swell.Water.from_toml(f'[water]\nmodel = "sines"\n"{hostile_key}" = 1\n')
    text = str(e.value)
    assert "\x1b" not in text and "\x07" not in text and "\u202e" not in text, text
    assert "\\u{1b}" in text, text
    long_key = "k" * 100_000
    with pytest.raises(ValueError) as e:
        swell.Water.from_toml(f"[water]\nmodel = 'sines'\n{long_key} = 1\n")
    text = str(e.value)
    assert len(text) < 4000, len(text)
    assert "characters in all)" in text, text


def springs(lattice=128):
    """The springs preset's model with a small grid: 0.4 s steps on a lattice x lattice mesh."""
    return swell.Water.from_toml(
        f"[water]\nmodel = 'springs'\nsize = [20.0, 20.0]\ncells = [8, 8]\nlattice = [{lattice}, {lattice}]\n"
    )


def test_a_progress_callback_sees_long_calls_and_can_stop_them():
    water, plain = springs(), springs()
    seen = []

    def progress(fraction):
        seen.append(fraction)
        return len(seen) < 3

    water.set_progress(progress)
    with pytest.raises(swell.Cancelled, match="^cancelled: stopped at the caller's request"):
        water.height_at(1.0, 2.0, 400.0)
    assert len(seen) == 3 and seen[0] == 0.0 and seen[0] < seen[1] < seen[2] < 1.0, seen
    # An exception raised by the callback stops the call and is raised as it is.
    water.set_progress(lambda f: 1 / 0)
    with pytest.raises(ZeroDivisionError):
        water.height_at(1.0, 2.0, 800.0)
    # Without a callback the stopped call finishes where it was, to the uninterrupted answer.
    water.set_progress(None)
    assert water.height_at(1.0, 2.0, 400.0) == plain.height_at(1.0, 2.0, 400.0)
    with pytest.raises(TypeError, match="^callback: a int is not callable"):
        water.set_progress(3)


def test_ctrl_c_stops_a_long_call_within_a_second():
    import _thread
    import threading
    import time

    # A million steps on a 257² lattice: minutes of work, released GIL.
    water = springs(256)
    timer = threading.Timer(0.3, _thread.interrupt_main)
    start = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            water.height_at(0.0, 0.0, 3.0e5)
    finally:
        timer.cancel()
    assert time.monotonic() - start < 0.3 + 1.0


def test_displace_fills_out_arrays_without_allocating():
    water = springs(16)
    p, n = water.displace(2.0)
    out = (np.full_like(p, 7.0), np.full_like(n, 7.0))
    got = water.displace(2.0, out=out)
    assert got[0] is out[0] and got[1] is out[1]
    np.testing.assert_array_equal(out[0], p)
    np.testing.assert_array_equal(out[1], n)
    with pytest.raises(ValueError, match=r"^out\[0\]: shape \(2, 2, 3\); must be"):
        water.displace(2.0, out=(np.zeros((2, 2, 3), np.float32), out[1]))
    with pytest.raises(TypeError, match=r"^out\[1\]: must be a float32 numpy array"):
        water.displace(2.0, out=(out[0], np.zeros(p.shape, np.float64)))
    with pytest.raises(ValueError, match=r"^out\[0\]: must be C-contiguous"):
        water.displace(2.0, out=(np.asfortranarray(out[0]), out[1]))
    readonly = out[1].copy()
    readonly.flags.writeable = False
    with pytest.raises(ValueError, match=r"^out\[1\]: must be writable"):
        water.displace(2.0, out=(out[0], readonly))
    with pytest.raises(ValueError, match="two different arrays"):
        water.displace(2.0, out=(out[0], out[0]))


def test_points_off_a_finite_patch_answer_nan_and_has_water_says_why():
    # The patch is 20 m x 10 m about the origin: (30, 0) is off it. A query there must not answer
    # the model's formula extended past the pool's edge as if there were water.
    pool = swell.Water.from_toml(ONLY_WATER.replace("[water]\n", "[water]\nextent = 'patch'\n"))
    x = np.array([0.0, 9.0, 30.0, -11.0])
    z = np.array([0.0, 4.0, 0.0, 0.0])
    assert pool.has_water(x, z).tolist() == [True, True, False, False]
    assert pool.has_water(0.0, 0.0) is True and pool.has_water(30.0, 0.0) is False
    h = pool.height_at(x, z, 1.0)
    assert np.isfinite(h[:2]).all() and np.isnan(h[2:]).all()
    n = pool.normal_at(x, z, 1.0)
    assert np.isfinite(n[:2]).all() and np.isnan(n[2:]).all()
    # A sea over the whole plane has water everywhere, and answers everywhere.
    sea = swell.Water.from_toml(ONLY_WATER.replace("[water]\n", "[water]\nextent = 'unbounded'\n"))
    assert sea.has_water(x, z).all()
    assert np.isfinite(sea.height_at(x, z, 1.0)).all()


def test_coordinates_far_from_the_origin_keep_their_precision():
    # An FFT ocean repeats every patch_size (64 m): 15,625 patches out (10^6 m) the buoy floats as
    # at home, where float32 coordinates would move in 6 cm steps.
    ocean = swell.Water.from_toml(
        "[water]\nmodel = 'fft'\ngrid = 32\npatch_size = 64.0\ncascades = 1\nsize = [64.0, 64.0]\ncells = [16, 16]\n"
    )
    x = np.array([3.3, 10.25, -0.01])
    z = np.array([-7.1, 40.0, 63.99])
    near = ocean.height_at(x, z, 2.5)
    far = ocean.height_at(x + 1.0e6, z, 2.5)
    assert np.abs(near).min() > 1e-3
    np.testing.assert_allclose(far, near, atol=1e-4)
    np.testing.assert_allclose(ocean.normal_at(x + 1.0e6, z, 2.5), ocean.normal_at(x, z, 2.5), atol=1e-3)
