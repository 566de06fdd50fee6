"""Type stubs of the compiled module (see swell/__init__.py for the overview)."""

from os import PathLike
from typing import Any, Callable, Dict, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

_Coord = Union[float, npt.ArrayLike]

class Cancelled(Exception):
    """A long call stopped because the progress callback returned False; asking again continues
    from where it stopped."""

class Water:
    """The water of a scene, built and ready to answer queries about any time ``t`` (s).

    Queries at one time share one evaluation of the model's state; answers depend only on the
    scene and ``t``. Calls on one object from several threads are serialised by a lock inside it.
    """

    @staticmethod
    def from_toml(text: str) -> "Water":
        """Builds the water of a scene's TOML text. Raises ValueError with the CLI's message."""
    @staticmethod
    def from_spectrum(efth: Any, freq: Optional[npt.ArrayLike] = None, dir: Optional[npt.ArrayLike] = None, **keys: Any) -> "Water":
        """The FFT ocean of a tabulated directional spectrum: a wavespectra/xarray DataArray
        ``efth(freq, dir)`` (m²/Hz/deg, Hz, degrees coming from; units read from the coordinates),
        a list of them (summed), a netCDF path, or a numpy array with ``freq`` and ``dir``;
        ``freq_unit=``/``dir_unit=`` for numpy coordinates in other units; any other ``[water]``
        key as a keyword (``grid``, ``patch_size``, ``cascades``, ``seed``, ``depth``, ``size``,
        ``cells``, ``spectrum_direction``)."""
    def stats(self, t: float = 0.0) -> Any:
        """The sea state of this water's spectral sea at ``t`` (s) as ``swell stats`` prints it:
        an xarray Dataset (hs, tp, dpm, dspr along ``source`` = expected/realised) when xarray is
        installed, else a dict."""
    @staticmethod
    def from_file(path: Union[str, "PathLike[str]"]) -> "Water":
        """Reads a scene file (relative heightmap paths are relative to it) and builds its water."""
    @property
    def rows(self) -> int:
        """Vertices of the grid along +Z (``cells_z + 1``)."""
    @property
    def cols(self) -> int:
        """Vertices of the grid along +X (``cells_x + 1``)."""
    def displace(
        self, t: float, out: Optional[Tuple[npt.NDArray[np.float32], npt.NDArray[np.float32]]] = None
    ) -> Tuple[npt.NDArray[np.float32], npt.NDArray[np.float32]]:
        """Displaced world positions (m) and unit normals of the grid at time ``t`` (s), each a
        float32 array of shape ``(rows, cols, 3)``; ``[j, i]`` is the vertex of row j (+Z),
        column i (+X). With ``out=(positions, normals)`` (writable C-contiguous float32 arrays of
        that shape) they are filled and returned: no allocation per call."""
    def set_progress(self, callback: Optional[Callable[[float], Optional[bool]]]) -> None:
        """Sets (None removes) the callable told the fraction done of long calls (a spring mesh
        asked far ahead) about every 10-50 ms; returning False stops the call with
        ``Cancelled``. Ctrl-C stops long calls within a second either way."""
    def foam(self, t: float) -> Optional[npt.NDArray[np.float32]]:
        """Foam coverage in [0, 1] per vertex, float32 ``(rows, cols)``, or None without foam."""
    def height_at(self, x: _Coord, z: _Coord, t: float) -> Any:
        """Heights (m) of the surface above world (x, z) (m) at time ``t`` (s): float64 with the
        broadcast shape of ``x`` and ``z`` (a float for two scalars)."""
    def normal_at(self, x: _Coord, z: _Coord, t: float) -> npt.NDArray[np.float64]:
        """Unit normals above world (x, z) at time ``t``: float64, broadcast shape + ``(3,)``."""
    def has_water(self, x: _Coord, z: _Coord) -> Any:
        """Whether there is water above world (x, z): bool, broadcast shape (a bool for two
        scalars). False off a finite patch, where ``height_at`` answers NaN; True everywhere for
        a sea over the whole plane."""

def render(text: str, t: float = 0.0, width: Optional[int] = None, height: Optional[int] = None) -> npt.NDArray[np.uint8]:
    """Renders a scene's TOML text at time ``t`` (s) as ``swell render --time t`` does: a
    ``(height, width, 3)`` uint8 sRGB array, top row first. ``width``/``height`` override
    ``[render]``'s, each in [1, 16384]."""

def stats(text: str, t: float = 0.0) -> Dict[str, Any]:
    """The sea state of a spectral scene (``model = "fft"``) at time ``t``, as ``swell stats``
    prints it: hs_realised_m, hs_expected_m, peak_period_s, foam_coverage, grid, ..."""
