"""Fixtures of the skyview Python suite: the command line to compare with, and the sample data."""
import os
import pathlib
import shutil
import subprocess

import numpy as np
import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def skyview_exe():
    """The `skyview` executable built beside the module (ctest sets SKYVIEW_EXE), else on PATH."""
    exe = os.environ.get("SKYVIEW_EXE") or shutil.which("skyview")
    if not exe or not os.path.exists(exe):
        pytest.skip("the skyview executable is not built (set SKYVIEW_EXE)")
    return exe


@pytest.fixture(scope="session")
def sample_data():
    """The real sample rasters in ../shared/sample_data (never committed); tests skip where absent."""
    shared = pathlib.Path(os.environ.get("SKYVIEW_SHARED_DIR", REPO.parent / "shared"))
    folder = shared / "sample_data"
    if not folder.is_dir():
        pytest.skip(f"sample data not found in {folder}")
    return folder


def run(exe, *args):
    """Runs `skyview ARGS -q`; returns (exit code, stderr)."""
    done = subprocess.run([exe, *map(str, args)], capture_output=True, text=True)
    return done.returncode, done.stderr


@pytest.fixture
def cli(skyview_exe):
    """cli(*args): runs the command line, failing the test on a non-zero exit."""

    def call(*args):
        code, err = run(skyview_exe, *args)
        assert code == 0, err
        return err

    return call


def read_raster(path):
    """(bands {description: float32 array with NaN for nodata}, heights of band 1, transform, crs WKT) via GDAL."""
    from osgeo import gdal

    gdal.UseExceptions()
    ds = gdal.Open(str(path))
    bands = {}
    for i in range(1, ds.RasterCount + 1):
        b = ds.GetRasterBand(i)
        a = b.ReadAsArray().astype(np.float32)
        nodata = b.GetNoDataValue()
        if nodata is not None and not np.isnan(nodata):
            a[a == np.float32(nodata)] = np.nan
        bands[b.GetDescription() or str(i)] = a
    return bands, ds.GetGeoTransform(), ds.GetProjection()


def read_heights(path):
    """Band 1 as stored (float64), its nodata value, the transform and the CRS: what skyview.svf takes."""
    from osgeo import gdal

    gdal.UseExceptions()
    ds = gdal.Open(str(path))
    band = ds.GetRasterBand(1)
    return band.ReadAsArray().astype(np.float64), band.GetNoDataValue(), list(ds.GetGeoTransform()), ds.GetProjection()


def crop(source, target, cols, rows, col0=0, row0=0, **warp):
    """A window of `source` as a GeoTIFF (and warped where `warp` names a dstSRS)."""
    from osgeo import gdal

    gdal.UseExceptions()
    if warp:
        tmp = str(target) + ".window.tif"
        gdal.Translate(tmp, str(source), srcWin=[col0, row0, cols, rows])
        gdal.Warp(str(target), tmp, **warp)
    else:
        gdal.Translate(str(target), str(source), srcWin=[col0, row0, cols, rows])
    return target
