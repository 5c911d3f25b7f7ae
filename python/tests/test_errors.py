"""What skyview refuses, and that it says so as the command line does."""
import numpy as np
import pytest

import skyview
from conftest import run


def flat(rows=20, cols=20):
    return np.zeros((rows, cols), np.float32)


def test_error_is_a_value_error():
    assert issubclass(skyview.Error, ValueError)


@pytest.mark.parametrize(
    "z, message",
    [
        (np.zeros((3, 4, 5)), "2-D"),
        (np.zeros(7), "2-D"),
        (np.zeros((4, 4), bool), "real numbers"),
        (np.zeros((4, 4), complex), "real numbers"),
        (np.array([["a", "b"], ["c", "d"]]), "real numbers"),
        (np.zeros((0, 5)), "empty"),
        (np.zeros((1, 1)), "single cell"),
        (np.full((4, 4), np.nan), "only nodata"),
        (np.array([[0.0, np.inf], [0.0, 0.0]]), "infinite"),
        ([[0.0, 1.0], [2.0, 3.0]], "NumPy array"),
    ],
)
def test_arrays_that_hold_no_heights_are_refused(z, message):
    with pytest.raises(skyview.Error, match=message):
        skyview.svf(z, cell_size=1.0)


@pytest.mark.parametrize("cell_size", [float("nan"), float("inf"), 0.0, -1.0])
def test_cell_sizes_must_be_positive_and_finite(cell_size):
    with pytest.raises(skyview.Error, match="cell_size"):
        skyview.svf(flat(), cell_size=cell_size)


def test_the_cells_size_must_be_said_once():
    with pytest.raises(skyview.Error, match="cell_size"):
        skyview.svf(flat())
    with pytest.raises(skyview.Error, match="not both"):
        skyview.svf(flat(), cell_size=1.0, transform=[0, 1, 0, 0, 0, -1])
    with pytest.raises(skyview.Error, match="6 numbers"):
        skyview.svf(flat(), transform=[0, 1, 0, 0])
    with pytest.raises(skyview.Error, match="non-finite"):
        skyview.svf(flat(), transform=[0, float("nan"), 0, 0, 0, -1])
    with pytest.raises(skyview.Error, match="not a CRS"):
        skyview.svf(flat(), transform=[0, 1, 0, 0, 0, -1], crs="EPSG:nonsense")


def test_degrees_without_a_crs_are_refused():
    with pytest.raises(skyview.Error, match="degrees"):
        skyview.svf(flat(), transform=[23.7, 1e-5, 0, 37.9, 0, -1e-5])


def test_option_errors_carry_the_command_lines_message(skyview_exe, tmp_path):
    from osgeo import gdal

    gdal.UseExceptions()
    dsm = tmp_path / "flat.tif"
    ds = gdal.GetDriverByName("GTiff").Create(str(dsm), 20, 20, 1, gdal.GDT_Float32)
    ds.SetGeoTransform([0, 1, 0, 0, 0, -1])
    ds = None
    for flags, kwargs in [
        (["--rays", "64"], {"rays": 64}),
        (["--method", "nonsense"], {"method": "nonsense"}),
        (["--max-error", "0.02", "--directions", "64"], {"max_error": 0.02, "directions": 64}),
        (["--edge", "nodata"], {"edge": "nodata"}),
        (["--products", "svf,sky"], {"products": "svf,sky"}),
    ]:
        code, err = run(skyview_exe, "svf", dsm, tmp_path / "out.tif", "-q", *flags)
        assert code != 0, err
        with pytest.raises(skyview.Error) as raised:
            skyview.svf(flat(), cell_size=1.0, **kwargs)
        assert str(raised.value) in err, (flags, err)


def test_option_values_checked_before_the_library():
    with pytest.raises(skyview.Error, match="far_lines"):
        skyview.svf(flat(), cell_size=1.0, far_lines=3)
    with pytest.raises(skyview.Error, match="edge"):
        skyview.svf(flat(), cell_size=1.0, edge="closed")
    with pytest.raises(skyview.Error, match="radius"):
        skyview.svf(flat(), cell_size=1.0, radius=-5)
    with pytest.raises(TypeError):
        skyview.svf(flat(), cell_size=1.0, no_such_option=1)


def test_nodata_value_and_nan_are_nodata():
    z = flat()
    z[3, 4] = -9999
    z[5, 6] = np.nan
    bands = skyview.svf(z, cell_size=1.0, nodata=-9999, products="svf")
    assert np.isnan(bands["svf"][3, 4]) and np.isnan(bands["svf"][5, 6])
    assert np.isnan(bands["svf"]).sum() == 2
    assert bands["svf"][10, 10] == pytest.approx(1.0)
