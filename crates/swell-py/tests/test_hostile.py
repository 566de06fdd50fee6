"""Hostile input through the Python package (issue 37): queries that must not answer garbage with
calm water, and messages that must not echo control characters or overlong text."""

import datetime

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
        (np.array([datetime.datetime(2026, 1, 1)], dtype="datetime64[s]"), "<M8[s]"),
        (np.array([True, False]), "bool"),
        ("3.0", "<U3"),
    ],
)
def test_non_real_coordinates_raise_type_error_naming_the_dtype(water, bad, dtype):
    with pytest.raises(TypeError, match=rf"^x: dtype {dtype} is not a real number type"):
        water.height_at(bad, 0.0, 0.0)
    with pytest.raises(TypeError, match=r"^z: dtype"):
        water.normal_at(0.0, bad, 0.0)


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
