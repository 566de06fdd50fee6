"""Files that are FIFOs (issue 37, class 2): one that no process writes to is refused at once,
naming it, instead of blocking the interpreter in open(2) where even Ctrl-C cannot reach it; one
with a writer is read as a file. FIFOs are made with os.mkfifo in a temporary directory that
pytest removes with them."""

import os
import re
import threading
import time

import numpy as np
import pytest

import swell

pytestmark = pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="FIFOs are POSIX")

SEA = (
    "version = 1\n[camera]\neye = [0.0, 6.0, 14.0]\ntarget = [0.0, 0.0, 0.0]\n[render]\nwidth = 16\n"
    "height = 9\n[water]\nmodel = 'sines'\ncells = [8, 8]\n[[water.waves]]\namplitude = 0.3\n"
    "wavelength = 8.0\nspeed = 3.0\ndirection = [1.0, 0.0]\n"
)

NO_WRITER = "is a FIFO or pipe that no process writes to"

# Longest a refusal may take: it takes milliseconds; a blocked open would take forever.
PROMPTLY_S = 30.0


def promptly(call):
    """What `call()` returns or raises, on a daemon thread, so that a hang fails the test (and
    does not keep the interpreter from exiting) instead of blocking the run."""
    outcome = {}

    def target():
        try:
            outcome["value"] = call()
        except BaseException as e:  # handed to the test thread
            outcome["error"] = e

    thread = threading.Thread(target=target, daemon=True)
    thread.start()
    thread.join(PROMPTLY_S)
    assert not thread.is_alive(), f"blocked for over {PROMPTLY_S} s on a FIFO"
    if "error" in outcome:
        raise outcome["error"]
    return outcome["value"]


@pytest.fixture
def fifo(tmp_path):
    path = tmp_path / "scene.toml"
    os.mkfifo(path)
    yield path
    path.unlink()


def test_a_scene_fifo_without_a_writer_raises_at_once(fifo):
    with pytest.raises(OSError, match=f"^{re.escape(str(fifo))}: {NO_WRITER}"):
        promptly(lambda: swell.Water.from_file(fifo))
    with pytest.raises(OSError, match=NO_WRITER):
        promptly(lambda: swell.Water.from_file(str(fifo)))


def test_a_heightmap_or_texture_fifo_without_a_writer_raises_at_once(fifo):
    heightmap = f"{SEA}[terrain]\ngenerator = 'heightmap'\npath = '{fifo}'\nheight_scale = 2.0\n"
    with pytest.raises(ValueError, match=f"^terrain\\.path: {re.escape(str(fifo))}: {NO_WRITER}"):
        promptly(lambda: swell.render(heightmap))
    texture = f"{SEA}[water.material]\ntexture = '{fifo}'\n"
    with pytest.raises(ValueError, match=f"^water\\.material\\.texture: {re.escape(str(fifo))}: {NO_WRITER}"):
        promptly(lambda: swell.render(texture))


def test_a_scene_fifo_with_a_writer_loads_as_the_file_does(fifo, tmp_path):
    regular = tmp_path / "regular.toml"
    regular.write_text(SEA)
    expected = swell.Water.from_file(regular).displace(1.0)[0]
    # The writer has the FIFO open before swell reads it (as a shell's <(...) has): opening
    # read-write never waits (Linux) and lets the write-only open find a reader; once the
    # read-write descriptor is closed, the writer is the only one.
    rw = os.open(fifo, os.O_RDWR)
    writer = os.open(fifo, os.O_WRONLY)
    os.close(rw)

    def feed():
        data, deadline = SEA.encode(), time.monotonic() + PROMPTLY_S
        while data:
            # Until swell has opened the FIFO a write fails (EPIPE) and writes nothing: retry.
            try:
                data = data[os.write(writer, data) :]
            except BrokenPipeError:
                assert time.monotonic() < deadline, "swell never opened the FIFO"
                time.sleep(0.005)
        os.close(writer)

    feeder = threading.Thread(target=feed, daemon=True)
    feeder.start()
    water = promptly(lambda: swell.Water.from_file(fifo))
    feeder.join(PROMPTLY_S)
    np.testing.assert_array_equal(water.displace(1.0)[0], expected)
