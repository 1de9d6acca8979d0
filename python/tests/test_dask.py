"""radchain.dask on a LocalCluster of 2 workers: the merged shards equal the unsharded job (radchain.grid, the command
line's catalogue)."""
import distributed  # python3-distributed (scripts/setup-debian.sh)
import numpy as np
import pandas as pd
import pytest

import radchain
import radchain.dask


@pytest.fixture(scope="module")
def client():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None) as cluster, \
            distributed.Client(cluster) as c:
        yield c


AXES = {"optics.aperture": "15 cm:30 cm:7", "detector.integration_time": "0.5 s:2 s:3"}
RESULTS = ["target.magnitude", "detector.snr"]


@pytest.fixture(scope="module")
def local_grid(cli, sbv, tmp_path_factory):
    """radchain.grid, unsharded (SI columns), and `radchain sweep … --out grid.npy` (display units)."""
    out = tmp_path_factory.mktemp("grid") / "grid.npy"
    cli("sweep", sbv, *[a for k, v in AXES.items() for a in ("--set", f"{k}={v}")],
        "--results", ",".join(RESULTS), "--out", out)
    return radchain.grid(sbv, AXES, results=RESULTS), np.load(out)


@pytest.mark.parametrize("shards, order", [(None, "block"), (3, "round-robin"), (5, "block")])
def test_sweep_equals_unsharded_grid_bit_for_bit(client, sbv, local_grid, shards, order):
    grid, cli_grid = local_grid
    df = radchain.dask.sweep(client, sbv, AXES, results=RESULTS, shards=shards, order=order)
    assert list(df.columns) == list(grid.columns) == ["optics.aperture", "detector.integration_time", *RESULTS]
    assert df.attrs["units"] == grid.attrs["units"]
    assert len(df) == 21 and df.attrs["exit_code"] == 0
    for name in grid.columns:
        assert np.array_equal(df[name].to_numpy(), grid[name].to_numpy()), name
    # the results are the command line's to the last bit (dimensionless: the same numbers in either convention)
    for name in RESULTS:
        assert np.array_equal(df[name].to_numpy(), cli_grid[name]), name
    # point order: the last axis fastest
    assert list(df["detector.integration_time"][:3]) == [0.5, 1.25, 2.0]
    assert df["optics.aperture"].iloc[3] == 0.175


def test_sweep_points_equal_session_run(client, sbv):
    df = radchain.dask.sweep(client, sbv, {"optics.aperture": "20 cm:25 cm:2"}, results="target.magnitude")
    for aperture, magnitude in zip(df["optics.aperture"], df["target.magnitude"]):
        r = radchain.load(sbv, set={"optics.aperture": f"{aperture!r} m"}).run()
        assert magnitude == pytest.approx(r["target.magnitude"], rel=1e-12)


def test_catalogue_equals_local_catalogue(client, source_dir):
    inputs = [str(source_dir / "sensors" / f) for f in ("msx-sbv.toml", "rubin-lsst-r-m5.toml")] + \
             [str(source_dir / "examples")]
    local = radchain.catalogue(inputs)
    for shards, order in ((None, "block"), (3, "round-robin")):
        df = radchain.dask.catalogue(client, inputs, shards=shards, order=order)
        pd.testing.assert_frame_equal(df, local)
        assert df.attrs == local.attrs


def test_catalogue_bad_file_is_an_error_row(client, sbv, tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(open(sbv).read().replace('aperture = "15 cm"', 'aperture = "15 kg"'))
    local = radchain.catalogue([sbv, str(bad)])
    df = radchain.dask.catalogue(client, [sbv, str(bad)], shards=2)
    pd.testing.assert_frame_equal(df, local)
    assert df.attrs["exit_code"] == 2 and df.attrs["errors"] == local.attrs["errors"]
    assert len(df.attrs["errors"]) == 1 and "15 kg" in df.attrs["errors"][0]


def test_bad_axis_raises_input_error_from_the_worker(client, sbv, cli):
    with pytest.raises(radchain.InputError) as error:
        radchain.dask.sweep(client, sbv, {"optics.aperture": "15 kg:30 cm:4"}, shards=2)
    reference = cli("sweep", sbv, "--set", "optics.aperture=15 kg:30 cm:4", check=False)
    assert reference.returncode == 2
    assert str(error.value) == reference.stderr.strip()
