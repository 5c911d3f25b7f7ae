"""skyview on dask arrays: tiles with a halo of the search radius, so that a cluster computes a city.

Each tile is computed with ``dask.array.map_overlap`` on the tile and a halo of the cells within
``radius`` metres (the library's own ``halo_cells``), placed in the whole raster (its ground frame,
edges, direction set and seeds), so every cell gets the value the single call
:func:`skyview.svf` gives it. An unlimited radius (the sweep's default) would need the whole raster
in every tile, and ``max_error`` chooses its own radius: both are refused here. Each tile's heights
are stored relative to the whole raster's base height (one pass over the heights finds it), so the
results are bit-identical to the single call's.
"""
import numpy as np
import dask.array as da

from . import Error, _skyview
from . import exposure as _exposure
from . import horizon as _horizon
from . import svf as _svf

__all__ = ["halo", "svf", "horizon", "exposure"]

_NO_RADIUS = (
    "skyview.dask needs radius= (metres): the halo each tile carries is the search radius, and an unlimited "
    "radius (the sweep's default) would put the whole raster in every tile; use skyview.svf on one machine instead"
)


def halo(shape, radius, *, cell_size=None, transform=None, crs=None):
    """Cells of halo a tile of a raster of `shape` (rows, cols) needs for a search radius of `radius` metres."""
    if radius is None:
        raise Error(_NO_RADIUS)
    rows, cols = (int(n) for n in shape)
    return _skyview._halo_cells(rows, cols, float(radius), cell_size, transform, crs)


def _padded_origin(block_info, depth):
    """Where a block of the overlapped array starts in the raster: the block's own start less its halo."""
    info = block_info[0]
    starts = []
    for (start, _), index in zip(info["array-location"], info["chunk-location"]):
        # map_overlap (boundary 'none') grows each chunk by `depth` on each side facing another
        # chunk: block i of the grown array starts 2 * depth * i past block i's start less depth.
        starts.append(start - 2 * depth * index)
    return starts


def _check(z, options):
    if not isinstance(z, da.Array):
        z = da.asarray(z)
    if z.ndim != 2:
        raise Error(f"z must be a 2-D array of heights (rows, cols), not {z.ndim}-D")
    if options.get("radius") is None:
        raise Error(_NO_RADIUS)
    if options.get("max_error") is not None:
        raise Error("skyview.dask takes no max_error: it chooses the radius, which sets each tile's halo; give "
                    "method, directions and radius")
    if "cell_size" not in options and "transform" not in options:
        raise Error("give cell_size (metres) or transform (with crs) to say how large the cells are")
    return z


def _height_range(z, nodata):
    """The lowest and highest valid heights of the whole array (one pass over it, now): each tile's heights are
    stored relative to the raster's base height, their midpoint, so that tiles hold the single call's floats."""
    valid = z.astype(np.float64)
    if nodata is not None:
        valid = da.where(valid == nodata, np.nan, valid)
    lo, hi = da.compute(da.nanmin(valid), da.nanmax(valid))
    if not (np.isfinite(lo) and np.isfinite(hi)):
        return None  # nothing valid (or infinite): the tiles' own calls say what is wrong
    return float(lo), float(hi)


def _all_nodata(block, nodata):
    invalid = np.isnan(block) if block.dtype.kind == "f" else np.zeros(block.shape, bool)
    if nodata is not None:
        invalid |= block == nodata
    return bool(invalid.all())


def _banded_tile(block, block_info, options, bands, depth_, compute):
    """A tile's bands as one record array: NaN for a tile of nodata, else compute(block, tile origin)."""
    out = np.empty(block.shape, np.dtype([(name, "<f4") for name in bands]))
    if block_info is None or _all_nodata(block, options.get("nodata")):
        for name in bands:
            out[name] = np.nan
        return out
    values = compute(_padded_origin(block_info, depth_))
    for name in bands:
        out[name] = values[name]
    return out


def _svf_tile(block, block_info=None, *, options, bands, depth_, full, heights):
    """One tile of svf(): the block and its halo, placed in the raster; its bands as one record array."""
    return _banded_tile(
        block, block_info, options, bands, depth_,
        lambda origin: _svf(block, _tile=(origin[1], origin[0]) + full, _height_range=heights, **options))


def _horizon_tile(block, block_info=None, *, options, directions, depth_, full, heights):
    """One tile of horizon(): its angles as records of `directions` floats, (rows, cols, directions)."""
    record = np.dtype([("angles", "<f4", (directions,))])
    out = np.empty(block.shape, record)
    if block_info is None or _all_nodata(block, options.get("nodata")):
        out["angles"] = np.nan
        return out
    row0, col0 = _padded_origin(block_info, depth_)
    angles, _ = _horizon(block, _tile=(col0, row0) + full, _height_range=heights, **options)
    out["angles"] = np.moveaxis(angles, 0, -1)
    return out


def _directions_first(records):
    return np.moveaxis(records["angles"], -1, 0)


def _exposure_tile(block, albedo=None, block_info=None, *, options, depth_, full, heights):
    """One tile of exposure(): the block (and its albedo cells) with its halo; its bands as one record array."""
    if albedo is not None:
        options = dict(options, albedo=albedo)
    return _banded_tile(
        block, block_info, options, _skyview._exposure_band_names(), depth_,
        lambda origin: _exposure(block, _tile=(origin[1], origin[0]) + full, _height_range=heights, **options).bands)


# The tiles' functions are module-level (pickled by reference, not by value: the module's builtin
# functions cannot be pickled for the workers) and take their settings as keywords.
def svf(z, **options):
    """skyview.svf over a dask array of heights: {band name: dask array}, equal to the single call.

    Keywords as for :func:`skyview.svf`; radius is required. Nothing is computed until the arrays are.
    """
    z = _check(z, options)
    depth = halo(z.shape, options["radius"], cell_size=options.get("cell_size"),
                 transform=options.get("transform"), crs=options.get("crs"))
    bands = _skyview._svf_band_names(options.get("products"), options.get("method"), options.get("rays"))
    record = np.dtype([(name, "<f4") for name in bands])
    full = (int(z.shape[1]), int(z.shape[0]))
    records = da.map_overlap(_svf_tile, z, depth=depth, boundary="none", dtype=record,
                             meta=np.empty((0, 0), record), options=options, bands=bands, depth_=depth, full=full,
                             heights=_height_range(z, options.get("nodata")))
    return {name: records[name] for name in bands}


def horizon(z, **options):
    """skyview.horizon over a dask array: (angles as a dask array (directions, rows, cols), azimuths).

    Keywords as for :func:`skyview.horizon`; radius is required.
    """
    z = _check(z, options)
    depth = halo(z.shape, options["radius"], cell_size=options.get("cell_size"),
                 transform=options.get("transform"), crs=options.get("crs"))
    full = (int(z.shape[1]), int(z.shape[0]))
    # The azimuths from a tile of the raster's first 2 x 2 cells, placed in it: the direction set is
    # the whole raster's.
    first = np.asarray(z[:2, :2].compute(), dtype=np.float64)
    if _all_nodata(first, options.get("nodata")):
        first = np.zeros((2, 2))
    _, azimuths = _horizon(first, _tile=(0, 0) + full, **dict(options, edge=None))
    n = len(azimuths)
    record = np.dtype([("angles", "<f4", (n,))])
    records = da.map_overlap(_horizon_tile, z, depth=depth, boundary="none", dtype=record,
                             meta=np.empty((0, 0), record), options=options, directions=n, depth_=depth, full=full,
                             heights=_height_range(z, options.get("nodata")))
    angles = records.map_blocks(_directions_first, dtype=np.float32, new_axis=0, chunks=((n,),) + records.chunks)
    return angles, azimuths


def exposure(z, **options):
    """skyview.exposure over a dask array: {band name: dask array}, equal to the single call with the same sky.

    Keywords as for :func:`skyview.exposure`; radius and skymap (a :class:`skyview.SkyMap` or a map file) are
    required: the sky is made once, not in every tile. albedo may be a number or an array of z's shape (NumPy
    or dask), which is cut into the same tiles. The run's metadata are those of the single call.
    """
    z = _check(z, options)
    if options.get("skymap") is None:
        raise Error("skyview.dask.exposure needs skymap= (skyview.skymap(...) or a map file): the sky is made once "
                    "for the whole raster, not in every tile")
    depth = halo(z.shape, options["radius"], cell_size=options.get("cell_size"),
                 transform=options.get("transform"), crs=options.get("crs"))
    full = (int(z.shape[1]), int(z.shape[0]))
    bands = _skyview._exposure_band_names()
    record = np.dtype([(name, "<f4") for name in bands])
    arrays = [z]
    albedo = options.get("albedo")
    if albedo is not None and not isinstance(albedo, str) and np.ndim(albedo) > 0:
        albedo = da.asarray(albedo)
        if albedo.shape != z.shape:
            raise Error(f"the albedo array is {albedo.shape[0]} x {albedo.shape[1]} cells (rows x columns) where the "
                        f"heights are {z.shape[0]} x {z.shape[1]}")
        arrays.append(albedo.rechunk(z.chunks))
        options = {k: v for k, v in options.items() if k != "albedo"}
    records = da.map_overlap(_exposure_tile, *arrays, depth=depth, boundary="none", dtype=record,
                             meta=np.empty((0, 0), record), options=options, depth_=depth, full=full,
                             heights=_height_range(z, options.get("nodata")), align_arrays=False)
    return {name: records[name] for name in bands}
