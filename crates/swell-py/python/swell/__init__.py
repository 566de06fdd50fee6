"""swell: water surfaces simulated and rendered on the CPU, from Python.

One scene, written in swell's TOML scene format (docs/scene-format.md; only ``[water]`` is
required for the water queries), answers for any time ``t`` in seconds:

* ``Water.displace(t, out=None)``: the displaced grid's positions and normals, float32
  ``(rows, cols, 3)``, into caller's arrays with ``out=``;
* ``Water.foam(t)``: foam coverage per vertex, or None for models without foam;
* ``Water.height_at(x, z, t)`` and ``Water.normal_at(x, z, t)``: the surface above world points,
  numpy broadcasting, computed in parallel with the GIL released;
* ``render(text, t)``: the frame ``swell render`` draws, as a ``(height, width, 3)`` uint8 array;
* ``stats(text, t)``: the sea state ``swell stats`` prints, as a dict;
* ``Water.from_spectrum(efth, ...)``: the FFT ocean of a measured or modelled directional
  spectrum E(f, θ), a wavespectra/xarray DataArray (or numpy arrays with their coordinates, or a
  netCDF file as wavespectra writes it: ``read_spectrum(path)``), and ``Water.stats(t)``: Hs, Tp,
  Dpm and Dspr of the input and of the realised sea with wavespectra's definitions, an xarray
  Dataset when xarray is installed (an optional dependency), else a dict;
* ``World.from_toml(text)``: a scene's floating bodies (``[[body]]``) riding its water (issue 34):
  ``advance(t)``, then ``positions`` float64 ``(n, 3)`` and ``rotations`` float64 ``(n, 4)``
  (quaternions x, y, z, w), ``names``, ``add_body(...)`` and ``set_thrust(body, force)``; the
  same poses as the Rust library and the C API for the same scene and time.

Conventions: SI units (metres, seconds), right-handed, +Y up, water at rest at y = 0. Answers
depend only on the scene and ``t``, never on earlier calls. Bad input raises ``ValueError`` with
the message the ``swell`` command line prints after ``error:``; unreadable files raise ``OSError``;
non-finite coordinates raise ``ValueError`` and non-numeric ones ``TypeError``. Long calls (a
spring mesh asked far ahead) stop on Ctrl-C within a second, and ``Water.set_progress`` is told
their progress and may stop them (``Cancelled``).
"""

from ._spectrum import read_spectrum
from ._swell import Cancelled, Water, World, __version__, render, stats

__all__ = ["Cancelled", "Water", "World", "read_spectrum", "render", "stats", "__version__"]
