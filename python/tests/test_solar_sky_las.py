"""skyview.sun_position against `skyview sun --csv`, skyview.skymap against `skyview skymap`, skyview.read_las."""
import csv
import io
import pathlib
import subprocess

import numpy as np
import pytest

import skyview
from conftest import REPO, read_raster


def sun_csv(exe, *args):
    out = subprocess.run([exe, "sun", "--csv", *args], capture_output=True, text=True, check=True).stdout
    return list(csv.DictReader(io.StringIO(out)))


def test_sun_positions_equal_the_command_lines_csv(skyview_exe):
    site = ["--lat", "39.742476", "--lon", "-105.1786", "--elevation", "1830.14", "--pressure", "820",
            "--temperature", "11"]
    rows = sun_csv(skyview_exe, *site, "--from", "2024-06-21T00:00Z", "--to", "2024-06-22T00:00Z", "--step", "30m")
    times = np.array([r["time_utc"].rstrip("Z") for r in rows], dtype="datetime64[s]")
    got = skyview.sun_position(times, 39.742476, -105.1786, elevation=1830.14, pressure=820, temperature=11)
    assert len(rows) == 49
    for column in ("zenith_deg", "azimuth_deg", "elevation_deg", "declination_deg", "right_ascension_deg",
                   "earth_sun_distance_au", "equation_of_time_min", "delta_t_s"):
        expected = np.array([float(r[column]) for r in rows])
        decimals = len(rows[0][column].split(".")[1])
        np.testing.assert_allclose(got[column], expected, atol=0.51 * 10.0 ** -decimals, rtol=0, err_msg=column)


def test_spa_test_case_and_shapes():
    # Reda & Andreas (2008) Table A4.1: 2003-10-17 12:30:30 -07:00, zenith 50.11162, azimuth 194.34024.
    t = np.datetime64("2003-10-17T19:30:30")
    got = skyview.sun_position(t, 39.742476, -105.1786, elevation=1830.14, pressure=820, temperature=11, delta_t=67)
    assert float(got["zenith_deg"]) == pytest.approx(50.11162, abs=1e-5)
    assert float(got["azimuth_deg"]) == pytest.approx(194.34024, abs=1e-5)
    grid = np.array([["2024-01-01T12:00", "NaT"], ["2024-07-01T12:00", "2024-07-01T00:00"]], dtype="datetime64[m]")
    many = skyview.sun_position(grid, 0.0, 0.0)
    assert many["zenith_deg"].shape == (2, 2)
    assert np.isnan(many["zenith_deg"][0, 1]) and not np.isnan(many["zenith_deg"][1, 1])


def test_sun_errors():
    with pytest.raises(skyview.Error, match="lat"):
        skyview.sun_position(np.datetime64("2024-01-01"), 91, 0)
    with pytest.raises(skyview.Error, match="datetime64"):
        skyview.sun_position(["yesterday"], 0, 0)


def test_skymap_equals_the_command_lines_bands(cli, tmp_path):
    args = ["--lat", "30", "--lon", "10", "--from", "2023-06-21T04:00Z", "--to", "2023-06-21T20:00Z", "--step", "1h",
            "--size", "32"]
    cli("skymap", tmp_path / "sky.tif", "--no-preview", "-q", *args)
    expected, _, _ = read_raster(tmp_path / "sky.tif")
    got = skyview.skymap("2023-06-21T04:00Z", np.datetime64("2023-06-21T20:00"), lat=30, lon=10, step="1h", size=32)
    assert got.direct.shape == (32, 32)
    np.testing.assert_allclose(got.direct, expected["direct"], rtol=2e-7)
    np.testing.assert_allclose(got.diffuse, expected["diffuse"], rtol=2e-7)
    assert got.metadata["SKY"] == "preetham"
    with pytest.raises(skyview.Error):
        skyview.skymap("2023-06-21T04:00Z", None, lat=30, lon=10)


def test_read_las_gives_every_point_of_the_header():
    path = REPO / "sample_dems" / "district.las"
    header = skyview.read_las_header(path.as_posix())
    points = skyview.read_las(path.as_posix())
    assert points.dtype.names == ("x", "y", "z", "intensity", "return_number", "number_of_returns", "classification")
    assert len(points) == header["point_count"] > 1000
    for i, axis in enumerate("xyz"):
        # The header's bounds as its writer rounded them (to 0.01 here).
        assert points[axis].min() == pytest.approx(header["min"][i], abs=0.01)
        assert points[axis].max() == pytest.approx(header["max"][i], abs=0.01)
    assert set(np.unique(points["classification"])) <= set(range(32))


def test_read_las_samples_and_errors(sample_data, tmp_path):
    points = skyview.read_las(str(sample_data / "las" / "simple.las"))
    assert len(points) == 1065  # laspy's simple.las
    with pytest.raises(skyview.Error, match="LAZ|laz"):
        skyview.read_las(str(sample_data / "las" / "simple.laz"))
    (tmp_path / "bad.las").write_bytes(b"LASF" + bytes(40))
    with pytest.raises(skyview.Error):
        skyview.read_las(str(tmp_path / "bad.las"))
