"""skyview.xarray keeps coordinates and CRS; skyview.dask on a LocalCluster equals the single call."""
import numpy as np
import pytest

import skyview


def city(rows=90, cols=110, seed=5):
    """Blocks of buildings 5-30 m high on streets, 1 m cells, a few nodata cells."""
    rng = np.random.default_rng(seed)
    z = np.zeros((rows, cols))
    for _ in range(40):
        r, c = rng.integers(0, rows - 8), rng.integers(0, cols - 8)
        z[r:r + rng.integers(3, 9), c:c + rng.integers(3, 9)] = rng.uniform(5, 30)
    z[40:42, 50:53] = np.nan
    return z


TRANSFORM = [500000.0, 1.0, 0.0, 4200000.0, 0.0, -1.0]
CRS = "EPSG:32634"


def test_xarray_in_and_out():
    xr = pytest.importorskip("xarray")
    import skyview.xarray as sxr

    z = city()
    x = TRANSFORM[0] + 0.5 + np.arange(z.shape[1])
    y = TRANSFORM[3] - 0.5 - np.arange(z.shape[0])
    da = xr.DataArray(z, coords={"y": y, "x": x}, dims=("y", "x"), attrs={"crs": CRS})
    ds = sxr.svf(da, directions=8)
    expected = skyview.svf(z, transform=TRANSFORM, crs=CRS, directions=8)
    assert list(ds.data_vars) == list(expected)
    for name in expected:
        np.testing.assert_array_equal(ds[name].values, expected[name])
    np.testing.assert_array_equal(ds["svf"].x, x)
    assert ds.attrs["crs"] == CRS and ds["openness_positive"].attrs["units"] == "degree"
    # rioxarray's layout: a band dimension of one, the CRS on a spatial_ref coordinate.
    rio = da.expand_dims(band=[1]).assign_coords(spatial_ref=((), 0, {"crs_wkt": CRS}))
    rio.attrs = {}
    h = sxr.horizon(rio, directions=4, radius=20)
    angles, azimuths = skyview.horizon(z, transform=TRANSFORM, crs=CRS, directions=4, radius=20)
    assert h.dims == ("azimuth", "y", "x")
    np.testing.assert_array_equal(h.values, angles)
    np.testing.assert_array_equal(h.azimuth, azimuths)
    with pytest.raises(skyview.Error, match="regularly spaced"):
        sxr.svf(da.isel(x=[0, 1, 3, 4]))


@pytest.fixture(scope="module")
def client():
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None) as c:
        with distributed.Client(c) as client:
            yield client


@pytest.mark.parametrize("method, radius", [("sweep", 25.0), ("march", 18.0), ("sampled", 20.0)])
def test_dask_on_a_local_cluster_equals_the_single_call(client, method, radius):
    import dask.array as da
    import skyview.dask as sdask

    z = city()
    options = dict(transform=TRANSFORM, crs=CRS, method=method, radius=radius, directions=16)
    single = skyview.svf(z, **options)
    tiles = sdask.svf(da.from_array(z, chunks=(45, 55)), **options)
    assert list(tiles) == list(single)
    assert tiles["svf"].numblocks == (2, 2)
    assert sdask.halo(z.shape, radius, transform=TRANSFORM, crs=CRS) >= radius
    computed = client.compute(tiles, sync=True)
    for name in single:
        # Float32 precision: each tile's heights are stored relative to its own base height.
        np.testing.assert_allclose(computed[name], single[name], rtol=2.5e-7, atol=2e-6, equal_nan=True, err_msg=name)


def test_dask_horizon_equals_the_single_call(client):
    import dask.array as da
    import skyview.dask as sdask

    z = city()
    angles, azimuths = sdask.horizon(da.from_array(z, chunks=(45, 55)), cell_size=1.0, radius=15, directions=8)
    single, single_azimuths = skyview.horizon(z, cell_size=1.0, radius=15, directions=8)
    np.testing.assert_array_equal(azimuths, single_azimuths)
    np.testing.assert_allclose(client.compute(angles, sync=True), single, atol=2e-4, equal_nan=True)


def test_dask_refuses_what_has_no_halo():
    import dask.array as da
    import skyview.dask as sdask

    z = da.from_array(city(), chunks=40)
    with pytest.raises(skyview.Error, match="radius"):
        sdask.svf(z, cell_size=1.0)
    with pytest.raises(skyview.Error, match="max_error"):
        sdask.svf(z, cell_size=1.0, radius=20, max_error=0.05)
