"""skyview.exposure: the command line's bands and metadata on a sample DSM, an open plane, and errors."""
import numpy as np
import pytest

import skyview
from conftest import crop, read_heights, read_raster, run

PERIOD = ["--from", "2024-06-21T03:00Z", "--to", "2024-06-21T19:00Z", "--step", "1h"]
KEYWORDS = dict(from_="2024-06-21T03:00Z", to="2024-06-21T19:00Z", step="1h")


def raster_metadata(path):
    from osgeo import gdal

    gdal.UseExceptions()
    return gdal.Open(str(path)).GetMetadata()


def assert_bands_equal(got, expected):
    assert list(got) == list(expected) == ["total", "direct", "diffuse", "reflected", "horizontal_total", "svf"]
    for name, values in got.items():
        assert values.dtype == np.float32
        np.testing.assert_allclose(values, expected[name], rtol=2e-7, atol=1e-7, equal_nan=True, err_msg=name)


@pytest.mark.parametrize("method", ["fast", "exact"])
def test_exposure_equals_the_command_lines_geotiff(sample_data, cli, tmp_path, method):
    dsm = crop(sample_data / "city_athens/DSM.tif", tmp_path / "dsm.tif", 50, 40, 180, 160)
    horizon = ["--directions", "16", "--radius", "40"]
    cli("exposure", dsm, tmp_path / "e.tif", "-q", "--method", method, "--map-size", "64", *PERIOD, *horizon)
    expected, _, _ = read_raster(tmp_path / "e.tif")
    z, nodata, transform, crs = read_heights(dsm)
    got = skyview.exposure(z, transform=transform, crs=crs, nodata=nodata, method=method, map_size=64,
                           directions=16, radius=40, **KEYWORDS)
    assert_bands_equal(got.bands, expected)
    written = raster_metadata(tmp_path / "e.tif")
    for key in ("PERIOD", "SITE_SOURCE", "RASTER_CENTRE_LAT_LON", "SKY_LATITUDE", "SKY_ELEVATION", "ALBEDO",
                "ALBEDO_SOURCE", "GLOBAL_HORIZONTAL_UNOBSTRUCTED_KWH_M2", "EXPOSURE_METHOD", "EXPOSURE_MAP_SIZE"):
        assert got.metadata[key] == written[key], key
    assert got.metadata["SITE_SOURCE"] == "the raster's centre"
    assert np.nanmean(got.bands["total"]) > 1.0  # kWh m-2 over a June day in Athens


def test_a_skymap_from_python_equals_the_command_lines_map_file(sample_data, cli, tmp_path):
    dsm = crop(sample_data / "city_athens/DSM.tif", tmp_path / "dsm.tif", 40, 30, 200, 200)
    z, nodata, transform, crs = read_heights(dsm)
    site = dict(lat=37.97, lon=23.73)
    sky = skyview.skymap(size=48, **site, **KEYWORDS)
    cli("skymap", tmp_path / "sky.tif", "--no-preview", "-q", "--lat", "37.97", "--lon", "23.73", "--size", "48",
        *PERIOD)
    for method in ("fast", "exact"):
        out = tmp_path / f"e_{method}.tif"
        cli("exposure", dsm, out, "-q", "--skymap", tmp_path / "sky.tif", "--method", method, "--radius", "30",
            "--albedo", "0.3")
        expected, _, _ = read_raster(out)
        from_object = skyview.exposure(z, transform=transform, crs=crs, nodata=nodata, skymap=sky, method=method,
                                       radius=30, albedo=0.3)
        assert_bands_equal(from_object.bands, expected)
        from_file = skyview.exposure(z, transform=transform, crs=crs, nodata=nodata, skymap=tmp_path / "sky.tif",
                                     method=method, radius=30, albedo=0.3)
        assert_bands_equal(from_file.bands, expected)
        assert from_file.metadata["SKYMAP"] == str(tmp_path / "sky.tif")


def test_an_open_plane_gets_the_skys_global_horizontal():
    z = np.zeros((12, 14))
    sky = skyview.skymap(lat=45.0, lon=7.0, size=64, **KEYWORDS)
    with pytest.warns(UserWarning, match="z has no CRS: the sky map's site \\(45, 7\\) cannot be checked"):
        got = skyview.exposure(z, cell_size=2.0, skymap=sky, directions=8)
    global_horizontal = float(sky.metadata["GLOBAL_HORIZONTAL_WH_M2"]) / 1000
    assert global_horizontal > 5.0
    np.testing.assert_allclose(got.bands["horizontal_total"], global_horizontal, rtol=2e-3)
    np.testing.assert_allclose(got.bands["svf"], 1.0, rtol=1e-6)
    np.testing.assert_allclose(got.bands["reflected"], 0.0, atol=1e-6)
    # The same sky made from its options at the given site, with an albedo per cell.
    albedo = np.full(z.shape, 0.25)
    albedo[0, 0] = np.nan
    with pytest.warns(UserWarning, match="1 cells have no albedo"):
        made = skyview.exposure(z, cell_size=2.0, lat=45.0, lon=7.0, map_size=64, directions=8, albedo=albedo,
                                **KEYWORDS)
    np.testing.assert_array_equal(made.bands["horizontal_total"][1:], got.bands["horizontal_total"][1:])
    assert np.isnan(made.bands["total"][0, 0]) and made.metadata["ALBEDO"] == "per cell"
    assert made.metadata["SITE_SOURCE"] == "--lat/--lon"


@pytest.mark.parametrize(
    "flags, keywords",
    [
        (["--method", "slow"], dict(method="slow")),
        (["--method", "exact", "--reads", "mipmap"], dict(method="exact", reads="mipmap")),
        (["--albedo", "1.5"], dict(albedo=1.5)),
        (["--map-size", "8"], dict(map_size=8)),
        (["--max-error", "0.05"], dict(max_error=0.05)),
        (["--sky", "perez-epw"], dict(sky="perez-epw")),
        (["--from", "2024-12-21T20:00Z", "--to", "2024-12-21T23:00Z", "--lat", "60", "--lon", "10",
          "--allow-site-mismatch"],
         dict(from_="2024-12-21T20:00Z", to="2024-12-21T23:00Z", lat=60, lon=10, allow_site_mismatch=True)),
        (["--lat", "10", "--lon", "10"], dict(lat=10, lon=10)),
    ],
)
def test_bad_inputs_raise_the_command_lines_message(skyview_exe, tmp_path, flags, keywords):
    z = np.zeros((10, 12))
    z[4:6, 4:6] = 8
    transform = [500000.0, 1.0, 0.0, 4200000.0, 0.0, -1.0]
    from osgeo import gdal, osr

    gdal.UseExceptions()
    ds = gdal.GetDriverByName("GTiff").Create(str(tmp_path / "dsm.tif"), 12, 10, 1, gdal.GDT_Float32)
    ds.SetGeoTransform(transform)
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(32634)
    ds.SetProjection(srs.ExportToWkt())
    ds.GetRasterBand(1).WriteArray(z)
    ds = None
    options = dict(KEYWORDS)
    options.update(keywords)
    cli_flags = list(PERIOD) if "from_" not in keywords else []
    code, err = run(skyview_exe, "exposure", tmp_path / "dsm.tif", tmp_path / "e.tif", "-q", *cli_flags, *flags)
    with pytest.raises(skyview.Error) as raised:
        skyview.exposure(z, transform=transform, crs="EPSG:32634", **options)
    assert code != 0 and str(raised.value) in err, (flags, err, str(raised.value))


def test_a_raster_without_crs_needs_a_site():
    with pytest.raises(skyview.Error, match="z has no CRS to place the sun: give --lat and --lon"):
        skyview.exposure(np.zeros((8, 8)), cell_size=1.0, **KEYWORDS)
    sky = skyview.skymap(lat=45.0, lon=7.0, size=32, **KEYWORDS)
    with pytest.raises(skyview.Error, match="--lat applies only to runs without --skymap"):
        skyview.exposure(np.zeros((8, 8)), cell_size=1.0, skymap=sky, lat=45.0)
    with pytest.raises(skyview.Error, match="albedo array is 3 x 3 cells"):
        skyview.exposure(np.zeros((8, 8)), cell_size=1.0, skymap=sky, albedo=np.zeros((3, 3)))
