"""skyview on NumPy arrays: horizon angles, sky-view factor, sun positions, sky maps and LAS points.

The functions call the same library as the ``skyview`` command line, with the same option names
(without their dashes: ``--max-error`` is ``max_error``) and the same defaults, and give the same
numbers: ``skyview.svf(z, transform=..., crs=...)`` returns the bands ``skyview svf`` writes.
Computation runs on the library's threads with the GIL released. Failures raise
:class:`skyview.Error` (a ``ValueError``) with the command line's one-line message.

``skyview.xarray`` takes and returns ``xarray`` objects with coordinates; ``skyview.dask`` runs
on ``dask.array`` tiles with a halo from the search radius. See docs/python.md.
"""
from collections import namedtuple

import numpy as np

from . import _skyview
from ._skyview import Error, __version__, horizon, read_las, read_las_header, svf

__all__ = [
    "Error",
    "SkyMap",
    "horizon",
    "read_las",
    "read_las_header",
    "skymap",
    "sun_position",
    "svf",
    "unix_seconds",
]

def unix_seconds(times):
    """UTC instants (numpy datetime64, or ISO 8601 text without an offset) as float seconds since 1970; NaT gives NaN."""
    a = np.asarray(times)
    if a.dtype.kind != "M":
        try:
            a = a.astype("datetime64[us]")
        except (TypeError, ValueError) as e:
            raise Error(f"times must be numpy datetime64 values in UTC (or ISO 8601 text without an offset): {e}") from None
    micro = a.astype("datetime64[us]").astype(np.int64)
    seconds = (micro // 1_000_000).astype(np.float64) + (micro % 1_000_000) / 1e6
    return np.where(np.isnat(a), np.nan, seconds)


def sun_position(times, lat, lon, *, elevation=0.0, pressure=None, temperature=None, delta_t=None, delta_ut1=0.0):
    """Where the sun is (NREL SPA) at each of `times`, as ``skyview sun --csv`` gives it.

    times: numpy datetime64 values in UTC, of any shape (or one). lat, lon: degrees north and east.
    elevation (m), pressure (mbar, default 1013.25; 0 = no refraction), temperature (deg C, default 15),
    delta_t (TT - UT1 in s; default automatic), delta_ut1 (UT1 - UTC in s): the command line's options.
    Returns {column: float64 array of the shape of times} with the CSV's columns zenith_deg, azimuth_deg,
    elevation_deg, declination_deg, right_ascension_deg, earth_sun_distance_au, equation_of_time_min, delta_t_s.
    """
    return _skyview._sun_position_unix(
        unix_seconds(times), float(lat), float(lon), float(elevation), pressure, temperature, delta_t, float(delta_ut1)
    )


SkyMap = namedtuple("SkyMap", ["direct", "diffuse", "metadata"])
SkyMap.__doc__ = """A sky's directional exposure map: direct and diffuse (float32, Wh m-2 sr-1; rows from the zenith
down to the horizon, columns by azimuth clockwise from north), and the metadata ``skyview skymap`` records."""


def _time_text(t):
    if t is None or isinstance(t, str):
        return t
    return str(np.datetime_as_string(np.datetime64(t, "s"), unit="s")) + "Z"


def skymap(from_=None, to=None, *, lat=None, lon=None, elevation=None, step=None, tz=None, sky=None, turbidity=None,
           albedo=None, luminous_efficacy=None, epw=None, size=None, threads=0):
    """The directional exposure map of the sky over a period, as ``skyview skymap`` writes it.

    from_, to: the period (to excluded): ISO 8601 text with an offset or zone (or ``tz``), or numpy
    datetime64 in UTC. Every keyword is the command line's option of the same name (--from is from_);
    None keeps its default (Preetham sky, turbidity 2.5, 30 min steps, 512 x 512 cells).
    Returns a :class:`SkyMap`.
    """
    bands, metadata = _skyview._skymap(
        _time_text(from_), _time_text(to), lat, lon, elevation, step, tz, sky, turbidity, albedo, luminous_efficacy,
        None if epw is None else str(epw), size, threads
    )
    return SkyMap(bands["direct"], bands["diffuse"], metadata)
