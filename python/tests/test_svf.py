"""skyview.svf and skyview.horizon: the command line's bands on the sample DSMs, and analytic cases."""
import math

import numpy as np
import pytest

import skyview
from conftest import crop, read_heights, read_raster


def assert_bands_equal(python_bands, cli_bands):
    assert list(python_bands) == list(cli_bands), "the same bands in the same order"
    for name, values in python_bands.items():
        assert values.dtype == np.float32
        # Float32 precision: the same library and options give the same bits, but GeoTIFF's float predictor
        # and the stored nodata leave nothing to round; allow one unit in the last place.
        np.testing.assert_allclose(values, cli_bands[name], rtol=2e-7, atol=1e-7, equal_nan=True, err_msg=name)


@pytest.mark.parametrize(
    "sample, window, options",
    [
        ("city_athens/DSM.tif", (120, 100, 140, 150), {}),
        ("city_goteborg/DSM_KRbig.tif", (90, 80, 60, 70), {"method": "march", "radius": 60, "directions": 32}),
        ("terrain/TM1_564_146_nodata.tif", (100, 90, 0, 0), {"products": "svf,openness_negative", "max_error": 0.05}),
        ("city_athens/DSM.tif", (70, 60, 0, 0), {"method": "sampled", "samples": 8, "seed": 3, "radius": 30}),
    ],
)
def test_svf_equals_the_command_lines_geotiff(sample_data, cli, tmp_path, sample, window, options):
    dsm = crop(sample_data / sample, tmp_path / "dsm.tif", *window)
    flags = [str(a) for key, value in options.items() for a in ("--" + key.replace("_", "-"), value)]
    cli("svf", dsm, tmp_path / "svf.tif", "-q", *flags)
    expected, _, _ = read_raster(tmp_path / "svf.tif")
    z, nodata, transform, crs = read_heights(dsm)
    got = skyview.svf(z, transform=transform, crs=crs, nodata=nodata, **options)
    assert_bands_equal(got, expected)


def test_geographic_raster_gives_the_command_lines_true_distances(sample_data, cli, tmp_path):
    dsm = crop(sample_data / "city_athens/DSM.tif", tmp_path / "dsm4326.tif", 90, 90, 150, 150, dstSRS="EPSG:4326")
    cli("svf", dsm, tmp_path / "svf.tif", "-q", "--products", "svf,sky_visibility")
    expected, _, _ = read_raster(tmp_path / "svf.tif")
    z, nodata, transform, crs = read_heights(dsm)
    assert abs(transform[1]) < 1e-3, "cells in degrees"
    got = skyview.svf(z, transform=transform, crs=crs, nodata=nodata, products=["svf", "sky_visibility"])
    assert_bands_equal(got, expected)
    # The same raster taken as metres would be a different city: the CRS is what makes it right.
    assert np.nanmean(got["svf"]) > 0.3


def test_horizon_equals_the_command_lines_bands(sample_data, cli, tmp_path):
    dsm = crop(sample_data / "city_athens/DSM.tif", tmp_path / "dsm.tif", 80, 70, 200, 200)
    cli("horizon", dsm, tmp_path / "h.tif", "-q", "--directions", "8", "--radius", "20", "--edge", "nodata")
    expected, _, _ = read_raster(tmp_path / "h.tif")
    z, nodata, transform, crs = read_heights(dsm)
    angles, azimuths = skyview.horizon(z, transform=transform, crs=crs, nodata=nodata, directions=8, radius=20,
                                       edge="nodata")
    assert angles.shape == (8, 70, 80) and angles.dtype == np.float32
    assert [f"horizon_azimuth_{a:.10g}" for a in azimuths] == list(expected)
    for k, name in enumerate(expected):
        np.testing.assert_allclose(angles[k], expected[name], rtol=2e-7, atol=1e-6, equal_nan=True, err_msg=name)
    assert np.isnan(angles[:, 0, 0]).all() and not np.isnan(angles[:, 35, 40]).any(), "edge nodata where it leaves"


def canyon(width, height, rows=201, cols=41):
    """A street canyon along north of `width` m between walls `height` m high, 1 m cells: walls at |east| >= width/2."""
    east = np.arange(cols) - cols // 2
    z = np.where(np.abs(east) >= width / 2, height, 0.0)
    return np.tile(z, (rows, 1))


def test_canyon_floor_sees_the_formulas_sky():
    W, H, n = 10.0, 20.0, 64
    z = canyon(W, H)
    bands = skyview.svf(z, cell_size=1.0, directions=n, curvature="off")
    centre = bands["svf"][100, 20]
    # Each sector k (centred on 360 k / n from grid north) sees the wall at (W/2) / |sin phi| metres.
    phi = 2 * math.pi * np.arange(n) / n
    h = np.arctan(H * np.abs(np.sin(phi)) / (W / 2))
    assert centre == pytest.approx(1 - np.mean(np.sin(h) ** 2), abs=1e-4)
    assert centre == pytest.approx(math.cos(math.atan(2 * H / W)), abs=2e-3), "the continuous canyon"
    assert bands["sky_visibility"][100, 20] == pytest.approx(1 - np.mean(np.sin(h)), abs=1e-4)
    assert bands["svf_surface"][100, 20] == pytest.approx(centre, abs=1e-6), "a flat floor"


def test_pit_centre_sees_a_ring_of_sky():
    R, D = 30.0, 10.0
    y, x = np.mgrid[-50:51, -50:51]
    z = np.where(np.hypot(x, y) < R, -D, 0.0).astype(np.float32)
    bands = skyview.svf(z, cell_size=1.0, directions=32, curvature="off")
    angles, azimuths = skyview.horizon(z, cell_size=1.0, directions=32, curvature="off")
    rim = math.atan(D / R)
    # The rim is a cell's width from a circle: within a degree and a half of atan(D / R) all round.
    np.testing.assert_allclose(angles[:, 50, 50], math.degrees(rim), atol=1.5)
    assert bands["svf"][50, 50] == pytest.approx(math.cos(rim) ** 2, abs=0.01)
    assert bands["openness_positive"][50, 50] == pytest.approx(90 - math.degrees(rim), abs=1.5)
    assert list(azimuths) == [360 * k / 32 for k in range(32)], "sectors from true north by default"


def test_cell_size_means_metres_and_scales_the_pit():
    y, x = np.mgrid[-30:31, -30:31]
    z = np.where(np.hypot(x, y) < 20, -10.0, 0.0)
    one = skyview.svf(z, cell_size=1.0, products="svf")["svf"][30, 30]
    two = skyview.svf(z, cell_size=2.0, products="svf")["svf"][30, 30]
    assert two > one + 0.05, "twice as wide, the same depth: more sky"


def test_defaults_are_the_command_lines(sample_data, cli, tmp_path):
    dsm = crop(sample_data / "city_athens/DSM.tif", tmp_path / "dsm.tif", 50, 40, 10, 10)
    cli("svf", dsm, tmp_path / "svf.tif", "-q")
    bands, _, _ = read_raster(tmp_path / "svf.tif")
    z, nodata, transform, crs = read_heights(dsm)
    got = skyview.svf(z, transform=transform, crs=crs, nodata=nodata)
    assert list(got) == ["svf", "svf_surface", "sky_visibility", "openness_positive", "openness_negative"]
    assert_bands_equal(got, bands)


def test_the_library_runs_outside_the_gil():
    import threading

    z = canyon(10, 20, rows=301, cols=301)
    results = []
    threads = [threading.Thread(target=lambda: results.append(skyview.svf(z, cell_size=1.0, products="svf")))
               for _ in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    np.testing.assert_array_equal(results[0]["svf"], results[1]["svf"])
