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
        # Bit-identical: each tile's heights are stored relative to the whole raster's base height.
        np.testing.assert_array_equal(computed[name], single[name], err_msg=name)


def test_dask_horizon_equals_the_single_call(client):
    import dask.array as da
    import skyview.dask as sdask

    z = city()
    angles, azimuths = sdask.horizon(da.from_array(z, chunks=(45, 55)), cell_size=1.0, radius=15, directions=8)
    single, single_azimuths = skyview.horizon(z, cell_size=1.0, radius=15, directions=8)
    np.testing.assert_array_equal(azimuths, single_azimuths)
    np.testing.assert_array_equal(client.compute(angles, sync=True), single)


def test_dask_refuses_what_has_no_halo():
    import dask.array as da
    import skyview.dask as sdask

    z = da.from_array(city(), chunks=40)
    with pytest.raises(skyview.Error, match="radius"):
        sdask.svf(z, cell_size=1.0)
    with pytest.raises(skyview.Error, match="max_error"):
        sdask.svf(z, cell_size=1.0, radius=20, max_error=0.05)


SKY = dict(lat=37.9, lon=21.0, from_="2024-06-21T03:00Z", to="2024-06-21T19:00Z", step="2h")


def test_xarray_exposure_keeps_coordinates_and_metadata():
    xr = pytest.importorskip("xarray")
    import skyview.xarray as sxr

    z = city(40, 50)
    x = TRANSFORM[0] + 0.5 + np.arange(z.shape[1])
    y = TRANSFORM[3] - 0.5 - np.arange(z.shape[0])
    da = xr.DataArray(z, coords={"y": y, "x": x}, dims=("y", "x"), attrs={"crs": CRS})
    albedo = xr.full_like(da, 0.3)
    ds = sxr.exposure(da, directions=8, radius=20, map_size=32, albedo=albedo, **SKY)
    single = skyview.exposure(z, transform=TRANSFORM, crs=CRS, directions=8, radius=20, map_size=32,
                              albedo=np.full(z.shape, 0.3), **SKY)
    assert list(ds.data_vars) == list(single.bands)
    for name, values in single.bands.items():
        np.testing.assert_array_equal(ds[name].values, values)
    assert ds["total"].attrs["units"] == "kWh m-2" and ds.attrs["PERIOD"] == single.metadata["PERIOD"]
    np.testing.assert_array_equal(ds["svf"].y, y)


def test_dask_exposure_with_an_albedo_array_equals_the_single_call(client):
    import dask.array as da
    import skyview.dask as sdask

    z = city()
    sky = skyview.skymap(size=32, **SKY)
    albedo = np.random.default_rng(2).uniform(0.1, 0.4, z.shape)
    options = dict(transform=TRANSFORM, crs=CRS, radius=15.0, directions=8, skymap=sky)
    single = skyview.exposure(z, albedo=albedo, **options)
    tiles = sdask.exposure(da.from_array(z, chunks=(45, 55)), albedo=da.from_array(albedo, chunks=30), **options)
    computed = client.compute(tiles, sync=True)
    assert list(computed) == list(single.bands)
    for name, values in single.bands.items():
        np.testing.assert_array_equal(computed[name], values, err_msg=name)
    with pytest.raises(skyview.Error, match="needs skymap="):
        sdask.exposure(da.from_array(z, chunks=45), radius=15.0, cell_size=1.0, **SKY)


def test_dask_on_worker_processes_equals_the_single_call():
    distributed = pytest.importorskip("distributed")
    import dask.array as da
    import skyview.dask as sdask

    z = city(60, 70)
    options = dict(transform=TRANSFORM, crs=CRS, radius=12.0, directions=8)
    single = skyview.svf(z, **options)
    try:
        cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0")
    except Exception as e:  # a sandbox that forbids spawning processes or opening sockets
        pytest.skip(f"no LocalCluster of worker processes here: {type(e).__name__}: {e}")
    with cluster, distributed.Client(cluster) as client:
        computed = client.compute(sdask.svf(da.from_array(z, chunks=(30, 35)), **options), sync=True)
    for name in single:
        np.testing.assert_array_equal(computed[name], single[name], err_msg=name)
