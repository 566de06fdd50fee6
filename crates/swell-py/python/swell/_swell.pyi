"""Type stubs of the compiled module (see swell/__init__.py for the overview)."""

from os import PathLike
from typing import Any, Callable, Dict, List, Optional, Tuple, Union

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

class World:
    """A scene built and stepped in time: its water and its floating bodies (``[[body]]``), which
    ride the water the scene draws, stepped at a fixed 120 Hz whatever times are asked.

    ``advance(t)`` moves it to ``t`` (s); ``positions`` and ``rotations`` are then the bodies'
    poses at ``t``. Calls on one object from several threads are serialised by a lock inside it.
    """

    @staticmethod
    def from_toml(text: str) -> "World":
        """Builds a scene's TOML text at t = 0 (relative paths relative to the working directory).
        Raises ValueError with the CLI's message."""
    @staticmethod
    def from_file(path: Union[str, "PathLike[str]"]) -> "World":
        """Reads a scene file (relative mesh and heightmap paths are relative to it) and builds it."""
    def __len__(self) -> int:
        """How many floating bodies the world has, added ones included."""
    @property
    def names(self) -> List[str]:
        """The bodies' names in body order (an unnamed ``[[body]]`` is ``body<index>``)."""
    def index(self, name: str) -> int:
        """The index of the body named ``name``; KeyError if none is."""
    @property
    def time(self) -> float:
        """The time (s) the world was last moved to: that of ``positions`` and ``rotations``."""
    def advance(self, t: float) -> None:
        """Moves the world to ``t`` (s, in [0, 1e7]): bodies step at 120 Hz up to ``t`` on the water
        at each step's time; poses do not depend on the frame rate. A ``t`` before the world's time
        replays from t = 0 (thrusts as they are now). ValueError for a bad ``t`` or a body that
        left the finite numbers."""
    @property
    def positions(self) -> npt.NDArray[np.float64]:
        """Every body's centre of mass at ``time``, world metres: float64 ``(len, 3)``."""
    @property
    def rotations(self) -> npt.NDArray[np.float64]:
        """Every body's rotation (body frame to world) at ``time``, unit quaternions (x, y, z, w):
        float64 ``(len, 4)``."""
    def add_body(self, toml: Optional[str] = None, **keys: Any) -> int:
        """Adds a floating body from the text of one ``[[body]]`` table (header included) or from
        its keys as keywords (``shape="box", size=[1.0, 0.5, 2.0], position=[0.0, 2.0, 0.0]``);
        returns its index. Held still until the next body step after ``time``, then free.
        ValueError naming the key as ``body[k]``; TypeError for a value no key takes."""
    def set_thrust(self, body: Union[int, str], force: npt.ArrayLike) -> None:
        """Sets the force (N, world x, y, z) applied at ``body``'s centre of mass from the next
        step on, ``body`` its index or name; (0, 0, 0) removes it."""
    @property
    def thrusts(self) -> npt.NDArray[np.float64]:
        """The thrusts set, N, world axes: float64 ``(len, 3)``."""

def render(text: str, t: float = 0.0, width: Optional[int] = None, height: Optional[int] = None) -> npt.NDArray[np.uint8]:
    """Renders a scene's TOML text at time ``t`` (s) as ``swell render --time t`` does: a
    ``(height, width, 3)`` uint8 sRGB array, top row first. ``width``/``height`` override
    ``[render]``'s, each in [1, 16384]."""

def stats(text: str, t: float = 0.0) -> Dict[str, Any]:
    """The sea state of a spectral scene (``model = "fft"``) at time ``t``, as ``swell stats``
    prints it: hs_realised_m, hs_expected_m, peak_period_s, foam_coverage, grid, ..."""
