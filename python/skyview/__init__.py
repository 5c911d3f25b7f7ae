"""skyview on NumPy arrays: horizon angles, sky-view factor, solar exposure, sun positions, sky maps, LAS points.

The functions call the same library as the ``skyview`` command line, with the same option names
(without their dashes: ``--max-error`` is ``max_error``) and the same defaults, and give the same
numbers: ``skyview.svf(z, transform=..., crs=...)`` returns the bands ``skyview svf`` writes.
Computation runs on the library's threads with the GIL released. Failures raise
:class:`skyview.Error` (a ``ValueError``) with the command line's one-line message.

``skyview.xarray`` takes and returns ``xarray`` objects with coordinates; ``skyview.dask`` runs
on ``dask.array`` tiles with a halo from the search radius. See docs/python.md.
"""
import os
from collections import namedtuple

import numpy as np

from . import _skyview
from ._skyview import Error, __version__, horizon, read_las, read_las_header, svf

__all__ = [
    "Error",
    "Exposure",
    "exposure",
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


def sun_position(times, lat, lon, *, elevation=0.0, pressure=None, temperature=None, delta_t=None, delta_ut1=0.0,
                 threads=0):
    """Where the sun is (NREL SPA) at each of `times`, as ``skyview sun --csv`` gives it.

    times: numpy datetime64 values in UTC, of any shape (or one). lat, lon: degrees north and east.
    elevation (m), pressure (mbar, default 1013.25; 0 = no refraction), temperature (deg C, default 15),
    delta_t (TT - UT1 in s; default automatic), delta_ut1 (UT1 - UTC in s): the command line's options;
    threads: at most this many of the library's threads (0: all cores).
    Returns {column: float64 array of the shape of times} with the CSV's columns zenith_deg, azimuth_deg,
    elevation_deg, declination_deg, right_ascension_deg, earth_sun_distance_au, equation_of_time_min, delta_t_s.
    """
    return _skyview._sun_position_unix(
        unix_seconds(times), float(lat), float(lon), float(elevation), pressure, temperature, delta_t, float(delta_ut1),
        threads
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


Exposure = namedtuple("Exposure", ["bands", "metadata"])
Exposure.__doc__ = """Solar exposure of every cell: bands {total, direct, diffuse, reflected, horizontal_total, svf} as
float32 arrays (kWh m-2 over the period; svf 1), and the metadata ``skyview exposure`` writes (SKY_*, SITE_SOURCE,
RASTER_CENTRE_LAT_LON, PERIOD, ALBEDO, ALBEDO_SOURCE, GLOBAL_HORIZONTAL_UNOBSTRUCTED_KWH_M2, the horizon method's)."""


def exposure(z, *, cell_size=None, transform=None, crs=None, nodata=None, z_scale=None, method=None, reads=None,
             skymap=None, sky=None, epw=None, lat=None, lon=None, elevation=None, from_=None, to=None, step=None,
             tz=None, turbidity=None, luminous_efficacy=None, map_size=None, albedo=None, allow_site_mismatch=False,
             horizon_method=None, directions=None, samples=None, far_lines=None, radius=None, rays=None, seed=None,
             edge=None, curvature=None, refraction=None, azimuth_origin=None, azimuths=None, early_exit=True,
             max_error=None, threads=0, progress=None, _tile=None, _height_range=None):
    """Solar exposure of every cell of a height array over a period, as ``skyview exposure`` computes it.

    z, cell_size, transform, crs, nodata, z_scale: as for :func:`svf`. The sky: ``skymap``, a
    :class:`SkyMap` from :func:`skymap` or the path of a map ``skyview skymap`` wrote (its sky, site and
    period); or the sky options sky, epw, lat, lon (default: the raster's centre), elevation, from_, to
    (ISO 8601 text or datetime64 in UTC), step, tz, turbidity, luminous_efficacy and map_size.
    albedo: a number 0 .. 1, an array of the heights' shape, or the path of a raster on the DSM's grid;
    default: the EPW's albedo field, else 0.2. method: fast (default) or exact; reads: area or mipmap.
    horizon_method (--horizon-method) and the other horizon keywords: as for :func:`svf` (sectors from
    grid north by default). progress: a callable taking the fraction done; False or an exception cancels.
    Every keyword is the command line's option of the same name; None keeps its default.
    Returns an :class:`Exposure` (bands, metadata).
    """
    options = dict(cell_size=cell_size, transform=transform, crs=crs, nodata=nodata, z_scale=z_scale, method=method,
                   reads=reads, sky=sky, epw=None if epw is None else str(epw), lat=lat, lon=lon,
                   elevation=elevation, from_=_time_text(from_), to=_time_text(to), step=step, tz=tz,
                   turbidity=turbidity, luminous_efficacy=luminous_efficacy, map_size=map_size,
                   allow_site_mismatch=allow_site_mismatch, horizon_method=horizon_method, directions=directions,
                   samples=samples, far_lines=far_lines, radius=radius, rays=rays, seed=seed, edge=edge,
                   curvature=curvature, refraction=refraction, azimuth_origin=azimuth_origin, azimuths=azimuths,
                   early_exit=early_exit, max_error=max_error, threads=threads, progress=progress, _tile=_tile,
                   _height_range=_height_range)
    if isinstance(skymap, SkyMap):
        options.update(skymap="SkyMap", skymap_direct=skymap.direct, skymap_diffuse=skymap.diffuse,
                       skymap_metadata=dict(skymap.metadata))
    elif skymap is not None:
        options["skymap"] = os.fspath(skymap)
    if albedo is None or isinstance(albedo, (str, os.PathLike)):
        options["albedo_raster"] = None if albedo is None else os.fspath(albedo)
    elif np.ndim(albedo) == 0:
        options["albedo"] = float(albedo)
    else:
        options["albedo_cells"] = np.asarray(albedo, dtype=np.float32)
    bands, metadata = _skyview._exposure(z, options)
    return Exposure(bands, metadata)
