"""skyview on xarray: height DataArrays with x/y coordinates and a CRS in, results with the same coordinates out.

The CRS is read from the DataArray's ``crs`` attribute (any string GDAL/PROJ reads), from a
rioxarray-style ``spatial_ref`` coordinate (its ``crs_wkt`` or ``spatial_ref`` attribute), or from
``da.rio.crs`` where rioxarray is installed. Nodata comes from ``nodata`` or ``_FillValue``.
"""
import numpy as np
import xarray as xr

from . import Error
from . import exposure as _exposure
from . import horizon as _horizon
from . import svf as _svf

__all__ = ["georeference", "svf", "horizon", "exposure"]


def _yx(da):
    """The DataArray as (y, x): a leading band dimension of one is dropped (rioxarray.open_rasterio)."""
    if da.ndim == 3 and da.shape[0] == 1:
        da = da.isel({da.dims[0]: 0}, drop=True)
    if da.ndim != 2:
        raise Error(f"the DataArray must be 2-D (y, x), not {da.ndim}-D with dims {da.dims}")
    return da


def _crs(da):
    if "crs" in da.attrs:
        return str(da.attrs["crs"])
    if "spatial_ref" in da.coords:
        attrs = da.coords["spatial_ref"].attrs
        for key in ("crs_wkt", "spatial_ref"):
            if key in attrs:
                return str(attrs[key])
    rio = getattr(da, "rio", None)
    if rio is not None and getattr(rio, "crs", None) is not None:
        return rio.crs.to_wkt()
    return None


def georeference(da):
    """The GDAL transform and CRS of a 2-D DataArray from its regularly spaced cell-centre coordinates."""
    da = _yx(da)
    ydim, xdim = da.dims
    x = np.asarray(da[xdim].values, dtype=np.float64)
    y = np.asarray(da[ydim].values, dtype=np.float64)
    if x.size < 2 or y.size < 2:
        raise Error("the DataArray needs at least 2 cells along x and y to give its cell size")
    dx, dy = x[1] - x[0], y[1] - y[0]
    for name, c, d in ((xdim, x, dx), (ydim, y, dy)):
        if not (np.isfinite(d) and d != 0) or not np.allclose(np.diff(c), d, rtol=1e-6, atol=0):
            raise Error(f"coordinate {name!r} is not regularly spaced: skyview needs a grid of equal cells")
    transform = [x[0] - dx / 2, dx, 0.0, y[0] - dy / 2, 0.0, dy]
    return transform, _crs(da)


def _nodata(da):
    for key in ("nodata", "_FillValue"):
        if key in da.attrs:
            return float(da.attrs[key])
    if "_FillValue" in da.encoding:
        return float(da.encoding["_FillValue"])
    return None


def _coords(da):
    ydim, xdim = da.dims
    return {ydim: da[ydim], xdim: da[xdim]}


def _attrs(da, crs):
    return {"crs": crs} if crs else {}


def svf(da, **options):
    """skyview.svf on a DataArray: a Dataset of its bands (svf, svf_surface, ...) on the same coordinates."""
    da = _yx(da)
    transform, crs = georeference(da)
    options.setdefault("nodata", _nodata(da))
    bands = _svf(da.values, transform=transform, crs=crs, **options)
    variables = {name: xr.DataArray(values, coords=_coords(da), dims=da.dims, attrs={"units": _unit(name)})
                 for name, values in bands.items()}
    return xr.Dataset(variables, attrs=_attrs(da, crs))


def _unit(band):
    return "degree" if band.startswith("openness") else "1"


def horizon(da, **options):
    """skyview.horizon on a DataArray: angles (degrees) with dims (azimuth, y, x), azimuth in degrees from north."""
    da = _yx(da)
    transform, crs = georeference(da)
    options.setdefault("nodata", _nodata(da))
    angles, azimuths = _horizon(da.values, transform=transform, crs=crs, **options)
    coords = {"azimuth": ("azimuth", azimuths, {"units": "degree"}), **_coords(da)}
    attrs = {"units": "degree", "long_name": "horizon elevation angle", **_attrs(da, crs)}
    return xr.DataArray(angles, coords=coords, dims=("azimuth",) + da.dims, name="horizon", attrs=attrs)


def exposure(da, **options):
    """skyview.exposure on a DataArray: a Dataset of its bands (total, direct, ..., svf) on the same coordinates,
    with the run's metadata (site, period, albedo, ...) as the Dataset's attributes. An albedo DataArray is taken
    as its values (it must lie on the same grid)."""
    da = _yx(da)
    transform, crs = georeference(da)
    options.setdefault("nodata", _nodata(da))
    albedo = options.get("albedo")
    if isinstance(albedo, xr.DataArray):
        options["albedo"] = _yx(albedo).values
    result = _exposure(da.values, transform=transform, crs=crs, **options)
    variables = {name: xr.DataArray(values, coords=_coords(da), dims=da.dims,
                                    attrs={"units": "1" if name == "svf" else "kWh m-2"})
                 for name, values in result.bands.items()}
    return xr.Dataset(variables, attrs={**result.metadata, **_attrs(da, crs)})
