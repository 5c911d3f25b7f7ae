"""progress=callable(fraction) on svf, horizon and exposure: called as the run goes, and able to cancel it."""
import numpy as np
import pytest

import skyview

SKY = dict(lat=45.0, lon=7.0, from_="2024-06-21T03:00Z", to="2024-06-21T19:00Z", step="2h", map_size=32)


def hills(rows=60, cols=70):
    y, x = np.mgrid[0:rows, 0:cols]
    return 10 * np.sin(x / 7.0) * np.cos(y / 5.0)


CALLS = {
    "svf": lambda z, **kw: skyview.svf(z, cell_size=1.0, directions=8, **kw),
    "horizon": lambda z, **kw: skyview.horizon(z, cell_size=1.0, directions=8, method="march", radius=20, **kw),
    "exposure": lambda z, **kw: skyview.exposure(z, cell_size=1.0, directions=8, **SKY, **kw),
}


@pytest.mark.parametrize("name", list(CALLS))
def test_progress_goes_from_0_to_1_and_the_result_is_unchanged(name):
    z = hills()
    fractions = []
    got = CALLS[name](z, progress=fractions.append)
    assert fractions[0] == 0.0 and fractions[-1] == 1.0
    assert fractions == sorted(fractions) and all(0.0 <= f <= 1.0 for f in fractions)
    plain = CALLS[name](z)
    first = got if name == "horizon" else (got if name == "svf" else got.bands)
    again = plain if name == "horizon" else (plain if name == "svf" else plain.bands)
    if name == "horizon":
        np.testing.assert_array_equal(first[0], again[0])
    else:
        for band in first:
            np.testing.assert_array_equal(first[band], again[band])


@pytest.mark.parametrize("name", list(CALLS))
def test_false_cancels_with_an_error_and_an_exception_is_raised_as_it_is(name):
    z = hills()
    seen = []

    def stop(fraction):
        seen.append(fraction)
        return False

    with pytest.raises(skyview.Error, match="^cancelled$"):
        CALLS[name](z, progress=stop)
    assert seen == [0.0], "no call after the run was cancelled"

    class Stop(Exception):
        pass

    def fail(fraction):
        raise Stop(f"at {fraction}")

    with pytest.raises(Stop, match="at 0.0"):
        CALLS[name](z, progress=fail)
    # The library is left as it was: the next call runs to the end.
    assert CALLS[name](z, progress=lambda f: None) is not None


def test_cancelling_part_way_stops_the_engine():
    # A sweep over many directions of a larger raster: cancelled at the first report after the start,
    # the run ends before its last direction (fractions seen stay below 1).
    z = hills(400, 400)
    seen = []

    def stop_after_start(fraction):
        seen.append(fraction)
        return len(seen) < 2  # go on at the start, stop at the first report after it

    with pytest.raises(skyview.Error, match="cancelled"):
        skyview.svf(z, cell_size=1.0, directions=2048, progress=stop_after_start)
    assert len(seen) == 2 and seen[-1] < 1.0


def test_progress_must_be_callable():
    with pytest.raises(skyview.Error, match="progress must be a callable"):
        skyview.svf(hills(), cell_size=1.0, progress=3)
