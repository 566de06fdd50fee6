"""Measured seas from Python: a directional spectrum E(f, θ) as wavespectra holds it, turned into
the scene text of an FFT ocean (``Water.from_spectrum``), and ``Water.stats`` as an xarray
Dataset.

wavespectra's conventions are swell's defaults: ``efth`` in m²/Hz/deg, ``freq`` in Hz, ``dir`` in
degrees the waves come from (nautical: 0 = from north, which is −Z in swell; 90 = from east, +X).
Other units are read from the coordinates' ``units`` attributes (``rad/s``, ``rad``) or given as
``freq_unit=`` / ``dir_unit=``; ``spectrum_direction="going-to"`` names the other direction
convention. The library checks every value (negative or NaN energy, repeated directions...) and
its error names the field: ``water.spectrum_table[0].efth[3][7] = -1 is outside [0, ...]``.
"""

import json
import math
import os

import numpy as np

#: Units a frequency coordinate may carry, by the axis name swell's scene uses.
_FREQ_UNITS = {"hz": "freq_hz", "s-1": "freq_hz", "1/s": "freq_hz", "rad/s": "freq_rad_s", "rad s-1": "freq_rad_s"}
#: Units a direction coordinate may carry.
_DIR_UNITS = {
    "deg": "dir_deg",
    "degree": "dir_deg",
    "degrees": "dir_deg",
    "degree_north": "dir_deg",
    "degree_true": "dir_deg",
    "rad": "dir_rad",
    "radian": "dir_rad",
    "radians": "dir_rad",
}


def read_spectrum(path):
    """The ``efth`` variable of a netCDF file as wavespectra writes it (``to_netcdf``), as an
    xarray DataArray (needs xarray and a netCDF backend: netCDF4, h5netcdf or scipy)."""
    import xarray as xr

    with xr.open_dataset(os.fspath(path)) as ds:
        if "efth" not in ds:
            raise ValueError(f"{os.fspath(path)}: no variable efth (wavespectra's name for E(f, θ))")
        return ds["efth"].load()


def _toml_value(key, v):
    """``v`` as a TOML value; ``key`` is named in the error for a type TOML cannot hold."""
    if isinstance(v, np.generic):
        v = v.item()
    if isinstance(v, np.ndarray):
        v = v.tolist()
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, (str, os.PathLike)):
        return json.dumps(os.fspath(v))
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(key, x) for x in v) + "]"
    raise TypeError(f"water.{key}: a {type(v).__name__} cannot be a scene value (numbers, strings, lists, bools)")


def _axis_name(coord, given, table, what, default):
    """The scene's axis name for a coordinate: ``given`` if set, else its ``units`` attribute."""
    unit = given if given is not None else getattr(coord, "attrs", {}).get("units", None)
    if unit is None:
        return default
    name = table.get(str(unit).strip().lower())
    if name is None:
        raise ValueError(f"{what}: units {unit!r} are not known; valid: {', '.join(sorted(table))}")
    return name


def _one_table(efth, freq, dir, freq_unit, dir_unit, index):
    """The ``[[water.spectrum_table]]`` text of one spectrum."""
    where = f"spectrum {index}" if index is not None else "efth"
    if isinstance(efth, (str, os.PathLike)):
        efth = read_spectrum(efth)
    if hasattr(efth, "dims") and hasattr(efth, "coords"):
        if freq is not None or dir is not None:
            raise TypeError(f"{where}: a DataArray carries its own freq and dir; do not pass them")
        missing = [d for d in ("freq", "dir") if d not in efth.dims]
        if missing:
            raise ValueError(f"{where}: a DataArray efth(freq, dir) is needed; it has dims {tuple(efth.dims)}")
        extra = {d: n for d, n in efth.sizes.items() if d not in ("freq", "dir")}
        wide = {d: n for d, n in extra.items() if n != 1}
        if wide:
            d = next(iter(wide))
            raise ValueError(f"{where}: one sea at a time: select one {d} (efth.isel({d}=0)); sizes {wide}")
        efth = efth.squeeze(drop=True).transpose("freq", "dir")
        freq_name = _axis_name(efth["freq"], freq_unit, _FREQ_UNITS, f"{where}: freq", "freq_hz")
        dir_name = _axis_name(efth["dir"], dir_unit, _DIR_UNITS, f"{where}: dir", "dir_deg")
        freq, dir, values = efth["freq"].values, efth["dir"].values, efth.values
    else:
        if freq is None or dir is None:
            raise TypeError(f"{where}: a numpy efth needs freq= and dir= (its coordinates)")
        freq_name = _axis_name(None, freq_unit, _FREQ_UNITS, f"{where}: freq", "freq_hz")
        dir_name = _axis_name(None, dir_unit, _DIR_UNITS, f"{where}: dir", "dir_deg")
        values = efth
    freq = np.asarray(freq, dtype=np.float64).ravel()
    dir = np.asarray(dir, dtype=np.float64).ravel()
    values = np.asarray(values, dtype=np.float64)
    if values.shape != (freq.size, dir.size):
        raise ValueError(
            f"{where}: efth has shape {values.shape}; expected (len(freq), len(dir)) = ({freq.size}, {dir.size})"
        )
    # wavespectra's files list directions in any order; the scene wants them increasing.
    fi, di = np.argsort(freq, kind="stable"), np.argsort(dir, kind="stable")
    freq, dir, values = freq[fi], dir[di], values[np.ix_(fi, di)]
    rows = ",\n  ".join(_toml_value("efth", r) for r in values.tolist())
    return (
        "\n[[water.spectrum_table]]\n"
        f"{freq_name} = {_toml_value(freq_name, freq.tolist())}\n"
        f"{dir_name} = {_toml_value(dir_name, dir.tolist())}\n"
        f"efth = [\n  {rows},\n]\n"
    )


def scene_text(efth, freq=None, dir=None, freq_unit=None, dir_unit=None, **keys):
    """The scene text of an FFT ocean whose spectrum is ``efth`` (see ``Water.from_spectrum``);
    ``keys`` are other ``[water]`` keys (``grid=256``, ``patch_size=1000.0``, ``size=[200, 200]``,
    ``spectrum_direction="going-to"``, ...)."""
    for fixed in ("model", "spectrum", "spectrum_table", "spectrum_file"):
        if fixed in keys:
            raise TypeError(f"from_spectrum sets water.{fixed} itself; do not pass it")
    many = isinstance(efth, (list, tuple))
    if many and (freq is not None or dir is not None):
        raise TypeError("a list of spectra carries its coordinates (DataArrays or paths); do not pass freq or dir")
    items = list(efth) if many else [efth]
    if not items:
        raise ValueError("efth: an empty list of spectra")
    water = ['model = "fft"', 'spectrum = "table"']
    water += [f"{k} = {_toml_value(k, v)}" for k, v in keys.items()]
    tables = [
        _one_table(e, freq, dir, freq_unit, dir_unit, i if many else None) for i, e in enumerate(items)
    ]
    return "[water]\n" + "\n".join(water) + "\n" + "".join(tables)


#: The sea-state parameters of ``Water.stats``, wavespectra's names, with swell's JSON keys.
_STATS = {
    "hs": ("hs_expected_m", "hs_realised_m", "m", "significant wave height Hm0"),
    "tp": ("tp_expected_s", "tp_realised_s", "s", "smooth peak period"),
    "dpm": ("dpm_expected_deg", "dpm_realised_deg", "degree", "mean direction at the peak, coming from"),
    "dspr": ("dspr_expected_deg", "dspr_realised_deg", "degree", "directional spread"),
}


def stats_result(d):
    """``swell stats``'s dict as an xarray Dataset (variables hs, tp, dpm, dspr along the
    coordinate ``source`` = ["expected", "realised"], the other values as attributes) when xarray
    is installed; else the dict unchanged."""
    try:
        import xarray as xr
    except ImportError:
        return d
    nan = float("nan")
    data = {
        name: (("source",), [nan if d[a] is None else d[a] for a in (e, r)], {"units": u, "long_name": ln})
        for name, (e, r, u, ln) in _STATS.items()
    }
    used = {k for e, r, _, _ in _STATS.values() for k in (e, r)}
    attrs = {k: (json.dumps(v) if isinstance(v, (list, dict)) else v) for k, v in d.items() if k not in used}
    return xr.Dataset(data, coords={"source": ["expected", "realised"]}, attrs=attrs)
