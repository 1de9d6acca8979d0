"""Session.sweep against `radchain sweep` and against single runs at the same values."""
import csv
import io
import math
import threading
import time
import warnings

import numpy as np
import pytest

import radchain


def cli_csv(cli, *args):
    rows = list(csv.reader(io.StringIO(cli("sweep", *args, "--format", "csv").stdout)))
    return rows[0], np.array([[float(x) for x in row] for row in rows[1:]])


def close(a, b, rel):
    return abs(a - b) <= rel * max(abs(a), abs(b))


def test_sweep_equals_cli_sweep(cli, sbv):
    # `--set optics.aperture=15 cm:30 cm:16`: value i = 15 + 15 i/15 cm (SweepAxis::value), in SI
    cm = 15 + (30 - 15) * np.arange(16) / 15
    apertures = cm * 0.01
    out = radchain.load(sbv).sweep({"optics.aperture": apertures}, results=["target.magnitude", "detector.snr"])
    header, ref = cli_csv(cli, sbv, "--set", "optics.aperture=15 cm:30 cm:16", "--results",
                          "target.magnitude,detector.snr")
    assert header == ["optics.aperture_cm", "target.magnitude", "detector.snr"]
    assert list(out) == ["optics.aperture", "target.magnitude", "detector.snr", "ok"]
    assert out["ok"].all() and out["target.magnitude"].shape == (16,)
    np.testing.assert_allclose(out["optics.aperture"] * 100, ref[:, 0], rtol=1e-12)
    # the CLI prints 10 significant digits
    np.testing.assert_allclose(out["target.magnitude"], ref[:, 1], rtol=6e-10, atol=0)
    np.testing.assert_allclose(out["detector.snr"], ref[:, 2], rtol=6e-10, atol=0)
    assert np.all(np.diff(out["target.magnitude"]) > 0)  # fainter limits with bigger pupils


def test_sweep_point_equals_run_at_that_value(cli, sbv):
    apertures = np.array([0.1, 0.17, 0.2, 0.333, 0.5])
    out = radchain.load(sbv).sweep({"optics.aperture": apertures})
    ref = cli.json("run", sbv, "--set", "optics.aperture=0.2 m", "--format", "json")
    assert close(out["target.magnitude"][2], ref["solves"][0]["value_si"], 1e-12)
    assert radchain.load(sbv).sweep({"optics.aperture": [0.2]}, results="detector.snr")["detector.snr"].shape == (1,)
    for i, d in enumerate(apertures):
        s = radchain.load(sbv)
        s.set("optics.aperture", float(d), si=True)
        r = s.run()
        # lanes solve by Dekker's method, run() by TOMS 748: both within 2^-47 of the root (docs/architecture.md)
        assert close(out["target.magnitude"][i], r["target.magnitude"], 1e-12), d
        for name in r:
            if math.isnan(r[name]):
                assert math.isnan(out[name][i]), name
            else:
                assert close(out[name][i], r[name], 1e-10) or abs(out[name][i] - r[name]) < 1e-12, (name, d)


def test_forward_sweep_equals_evaluate(sbv):
    magnitudes = np.linspace(12, 18, 13)
    times = np.array([0.5, 2.0])
    out = radchain.load(sbv).sweep({"target.magnitude": magnitudes[:, None], "detector.integration_time": times[None, :]},
                                   results=["detector.snr", "criteria.detection.margin"], solve=False)
    assert out["detector.snr"].shape == (13, 2)
    assert np.array_equal(out["target.magnitude"], np.broadcast_to(magnitudes[:, None], (13, 2)))
    for i in (0, 6, 12):
        for j in (0, 1):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # setting a solved unknown warns; evaluate() uses it
                s = radchain.load(sbv, set={"target.magnitude": float(magnitudes[i]),
                                            "detector.integration_time": float(times[j])}, si=True)
            r = s.evaluate()
            assert close(out["detector.snr"][i, j], r["detector.snr"], 1e-13)
            assert close(out["criteria.detection.margin"][i, j], r["criteria.detection.margin"], 1e-12)
    # SNR rises with the integration time and falls with the magnitude
    assert np.all(out["detector.snr"][:, 1] > out["detector.snr"][:, 0])
    assert np.all(np.diff(out["detector.snr"][:, 0]) < 0)


def test_spectral_parameter_sweeps_point_by_point(sbv):
    band_max = np.array([0.7e-6, 0.8e-6, 0.9e-6])
    out = radchain.load(sbv).sweep({"detector.band_max": band_max}, results=["target.magnitude"])
    for i, b in enumerate(band_max):
        r = radchain.load(sbv, set={"detector.band_max": float(b)}, si=True).run()
        assert out["target.magnitude"][i] == r["target.magnitude"]  # the same scalar solver: bit for bit


def test_thread_count_does_not_change_results(sbv):
    apertures = np.linspace(0.1, 0.4, 20001)
    s = radchain.load(sbv)
    everything = s.sweep({"optics.aperture": apertures}, results=["target.magnitude", "detector.snr"])
    try:
        radchain.set_threads(1)
        one = radchain.load(sbv).sweep({"optics.aperture": apertures}, results=["target.magnitude", "detector.snr"])
    finally:
        radchain.set_threads(0)
    for k in everything:
        assert np.array_equal(everything[k], one[k]), k


def test_sweep_frame(sbv):
    df = radchain.load(sbv).sweep({"optics.aperture": [0.15, 0.2]}, results=["target.magnitude"], frame=True)
    assert list(df.columns) == ["optics.aperture", "target.magnitude", "ok"]
    assert df.attrs["units"] == {"optics.aperture": "m", "target.magnitude": "1"}  # parameters and results
    assert df["target.magnitude"][0] == pytest.approx(15.5565, abs=1e-4)  # README: 15.5565 vs 15.55 printed


def test_failed_solve_is_nan_and_warns(sbv):
    # a 0.5 mm pupil reaches SNR 5 only for stars brighter than magnitude 5, outside the bracket [5, 25]
    with pytest.warns(RuntimeWarning, match="point 0 .*target.magnitude"):
        out = radchain.load(sbv).sweep({"optics.aperture": [0.0005, 0.15]}, results=["target.magnitude"])
    assert not out["ok"][0] and math.isnan(out["target.magnitude"][0])
    assert out["ok"][1] and not math.isnan(out["target.magnitude"][1])


def test_sweep_errors(sbv):
    s = radchain.load(sbv)
    with pytest.raises(radchain.InputError) as caught:
        s.sweep({"optics.aperture": [0.1, -0.2]})
    assert caught.value.subject == "optics.aperture[1] = -0.20000000000000001"
    with pytest.raises(radchain.InputError, match="a \\[\\[solve\\]\\] determines target.magnitude"):
        s.sweep({"target.magnitude": [14, 15]})
    with pytest.raises(radchain.InputError, match="did you mean \"detector.snr\""):
        s.sweep({"optics.aperture": [0.1]}, results=["detector.snrr"])
    with pytest.raises(radchain.InputError, match="no numeric parameter"):
        s.sweep({"optics.aperturee": [0.1]})
    with pytest.raises(ValueError):
        s.sweep({"optics.aperture": [0.1, 0.2], "detector.qe": [0.1, 0.2, 0.3]})  # shapes do not broadcast


def test_sweep_releases_the_gil(sbv):
    """Another Python thread runs while a sweep computes (the sweep holds no GIL while C++ works)."""
    s = radchain.load(sbv)
    apertures = np.linspace(0.15, 0.30, 2_000_000)
    s.sweep({"optics.aperture": apertures[:100]}, results=["target.magnitude"])  # worker chains built
    done = threading.Event()
    seconds = []

    def work():
        start = time.perf_counter()
        s.sweep({"optics.aperture": apertures}, results=["target.magnitude"])
        seconds.append(time.perf_counter() - start)
        done.set()

    ticks = 0
    worker = threading.Thread(target=work)
    worker.start()
    while not done.is_set():
        time.sleep(0.001)  # wakes only if it can take the GIL back
        ticks += 1
    worker.join()
    # unloaded, about one tick per 1-2 ms of the sweep (a busy machine: fewer); with the GIL held through it, one
    # or two ticks in all
    assert ticks > max(5, seconds[0] * 20), (ticks, seconds)


def test_several_solves_sweep_point_by_point(source_dir):
    """Kolobrodov's camera solves f' and D (two [[solve]]s: no lanes): each point equals run() there, bit for bit."""
    f = str(source_dir / "sensors" / "kolobrodov-1996-ccd151-computed.toml")
    s = radchain.load(f)
    assert s.solved == ["optics.focal_length", "optics.aperture"]
    altitudes = np.array([300e3, 400e3, 600e3])
    out = s.sweep({"platform.altitude": altitudes}, results=s.solved)
    for i, h in enumerate(altitudes):
        r = radchain.load(f, set={"platform.altitude": float(h)}, si=True).run()
        for unknown in s.solved:
            assert out[unknown][i] == r[unknown], (unknown, h)
    # f' scales with the altitude at a fixed GSD
    assert out["optics.focal_length"][2] / out["optics.focal_length"][0] == pytest.approx(2.0, rel=1e-12)


def test_ctrl_c_stops_a_long_sweep(sbv):
    # Ctrl-C in a notebook: the sweep checks Python's signals between blocks of 2^18 points, so a KeyboardInterrupt
    # raised early stops it within a block, not after all of its 2e7 solved points; the session stays usable.
    import _thread

    s = radchain.load(sbv)
    apertures = np.linspace(0.1, 0.4, 20_000_000)
    started = time.perf_counter()
    s.sweep({"optics.aperture": apertures[:2_000_000]}, results=["target.magnitude"])
    tenth = time.perf_counter() - started  # a tenth of the whole sweep
    timer = threading.Timer(tenth / 2, _thread.interrupt_main)
    started = time.perf_counter()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        s.sweep({"optics.aperture": apertures}, results=["target.magnitude"])
    interrupted_after = time.perf_counter() - started
    timer.cancel()
    # stopped ~ a block after the interrupt (≈ 0.65 tenth), not after the whole sweep (≈ 10 tenths)
    assert interrupted_after < 4 * tenth, (interrupted_after, tenth)
    small = s.sweep({"optics.aperture": apertures[:1000]}, results=["target.magnitude"])
    assert small["ok"].all()


def test_grid_is_factored_and_agrees_with_the_per_point_sweep(cli, sbv):
    axes = {"optics.aperture": "15 cm:30 cm:40", "detector.integration_time": "0.1 s:2 s:40"}
    df = radchain.grid(sbv, axes, results="target.magnitude")
    # columns in SI under their bare names, as Session.sweep's; their units in attrs
    assert list(df) == ["optics.aperture", "detector.integration_time", "target.magnitude"]
    assert df.attrs["units"] == {"optics.aperture": "m", "detector.integration_time": "s", "target.magnitude": "1"}
    assert len(df) == 1600 and df.attrs["exit_code"] == 0
    assert df.attrs["method"].startswith("closed form factored over the grid: the noise floor varies with "
                                         "detector.integration_time;"), df.attrs["method"]
    # the same points through Session.sweep (lanes, each solved on its own)
    d = df["optics.aperture"].to_numpy()
    t = df["detector.integration_time"].to_numpy()
    per_point = radchain.load(sbv).sweep({"optics.aperture": d, "detector.integration_time": t}, results="target.magnitude")
    np.testing.assert_allclose(df["target.magnitude"], per_point["target.magnitude"], rtol=1e-10, atol=0)
    # and the CLI's CSV of the same sweep, to its 10 digits
    header, ref = cli_csv(cli, sbv, "--set", "optics.aperture=15 cm:30 cm:40", "--set", "detector.integration_time=0.1 s:2 s:40",
                          "--results", "target.magnitude")
    np.testing.assert_allclose(df["target.magnitude"], ref[:, 2], rtol=6e-10, atol=0)  # the CSV's 10 digits
    np.testing.assert_allclose(df["optics.aperture"], ref[:, 0] * 0.01, rtol=6e-10, atol=0)  # the CSV in cm, 10 digits
    dimmer = radchain.grid(sbv, axes, results="target.magnitude", set={"optics.transmittance": "0.5"})
    assert dimmer.attrs["method"].startswith("closed form factored"), dimmer.attrs["method"]
    # S ∝ τ and the SBV's floor does not depend on it: every limit 2.5 lg(0.56/0.5) brighter
    np.testing.assert_allclose(df["target.magnitude"] - dimmer["target.magnitude"], 2.5 * np.log10(0.56 / 0.5), atol=1e-10)
    more = radchain.grid(sbv, axes, results=["target.magnitude", "detector.snr"])
    assert more.attrs["method"] == "per point: a result other than the solved target.magnitude is read (detector.snr)"
    np.testing.assert_allclose(more["target.magnitude"], df["target.magnitude"], rtol=1e-10, atol=0)
    # per point, grid and Session.sweep are one engine at the same SI values: the same bits
    same = radchain.load(sbv).sweep({"optics.aperture": d, "detector.integration_time": t},
                                    results=["target.magnitude", "detector.snr"], frame=True)
    assert list(same.columns[:-1]) == list(more.columns)
    assert same.attrs["units"] == more.attrs["units"]
    for name in more.columns:
        assert np.array_equal(same[name].to_numpy(), more[name].to_numpy()), name
