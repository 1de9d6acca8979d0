"""Python gets the command line's limits and cannot be turned against itself: a sweep larger than 10^8 points must be
asked for (allow_large, as --allow-large), a stage that calls back into its own Session is refused instead of waiting
for ever, a sweep uses the values it checked even if the caller's array changes under it, and a table that numpy could
not read back (a result listed twice) is refused."""
import threading

import numpy as np
import pytest

import radchain


def test_a_sweep_larger_than_1e8_points_must_be_asked_for(sbv):
    session = radchain.load(sbv)
    apertures = np.broadcast_to(np.linspace(0.15, 0.3, 10001)[:, None], (10001, 10000))  # no memory behind it
    times = np.broadcast_to(np.linspace(0.1, 2.0, 10000)[None, :], (10001, 10000))
    with pytest.raises(radchain.InputError, match="allow_large=True"):
        session.sweep({"optics.aperture": apertures, "detector.integration_time": times})
    with pytest.raises(radchain.InputError, match="more than 1e\\+10 points"):
        session.sweep({"optics.aperture": np.broadcast_to(0.2, (100001, 100001))}, allow_large=True)
    with pytest.raises(radchain.InputError, match="--allow-large"):
        radchain.grid(sbv, {"optics.aperture": "15 cm:30 cm:1000", "detector.qe": "0.2:0.8:1000",
                            "detector.integration_time": "0.1 s:2 s:101"})


calls_back = {}


@radchain.register_stage
class CallsBackIntoItsSession(radchain.Stage):
    kind, name = "criterion", "py_calls_back"
    summary = "reads its own session from inside the chain (refused)"
    reference = "test"
    schema = [radchain.parameter("threshold", default="5", min=0, min_exclusive=True, doc="SNR threshold T")]
    publishes = {"criteria.*.margin": "SNR/T - 1"}
    needs = ["detector.snr"]

    def evaluate(self, params, inputs):
        session = calls_back.get("session")
        if session is not None:
            session["detector.snr"]  # re-entry: the session is busy with the call that runs this stage
        return {"criteria.*.margin": inputs["detector.snr"] / params["threshold"] - 1.0}


def test_a_stage_calling_back_into_its_own_session_is_refused(sbv):
    text = open(sbv).read().replace('plugin = "snr_threshold"', 'plugin = "py_calls_back"')
    session = radchain.loads(text, name=sbv)
    calls_back["session"] = session
    outcome = {}

    def run():
        try:
            session.run()
        except Exception as error:  # noqa: BLE001 (the error is the result)
            outcome["error"] = error

    worker = threading.Thread(target=run, daemon=True)
    worker.start()
    worker.join(60)
    calls_back.clear()
    assert not worker.is_alive(), "the session waited for itself"
    assert "called back into its own session" in str(outcome.get("error")), outcome


changing = {}


@radchain.register_stage
class ChangesTheCallersArray(radchain.Stage):
    kind, name = "criterion", "py_changes_array"
    summary = "overwrites the caller's sweep values while the sweep runs"
    reference = "test"
    schema = [radchain.parameter("threshold", default="5", min=0, min_exclusive=True, doc="SNR threshold T")]
    publishes = {"criteria.*.margin": "SNR/T - 1"}
    needs = ["detector.snr"]

    def evaluate(self, params, inputs):
        values = changing.get("values")
        if values is not None:
            values[:] = -1.0  # an aperture no check would pass
        return {"criteria.*.margin": inputs["detector.snr"] / params["threshold"] - 1.0}


def test_a_sweep_uses_the_values_it_checked(sbv):
    text = open(sbv).read().replace('plugin = "snr_threshold"', 'plugin = "py_changes_array"')
    session = radchain.loads(text, name=sbv)
    apertures = np.linspace(0.15, 0.3, 64)
    asked = ["detector.snr", "criteria.detection.margin"]  # (the margin: the stage runs at every point)
    expected = session.sweep({"optics.aperture": apertures.copy()}, results=asked, solve=False)
    changing["values"] = apertures
    got = session.sweep({"optics.aperture": apertures}, results=asked, solve=False)
    changing.clear()
    assert np.all(apertures == -1.0)  # the stage did change the caller's array
    for name in asked:
        np.testing.assert_array_equal(got[name], expected[name])


def test_a_result_listed_twice_is_refused_not_written_as_an_unreadable_table(sbv):
    # (two columns of one name make an .npy that numpy.load refuses)
    with pytest.raises(radchain.InputError, match="listed twice"):
        radchain.grid(sbv, {"optics.aperture": "15 cm:30 cm:3"}, results=["detector.snr", "detector.snr"])


def test_names_are_strings_without_nul_not_coerced(sbv):
    # A NUL cut the name on the C++ side (a KeyError named 'target.magnitude', a --set refused as another key); a
    # number or bytes was str()-ed into a name nobody wrote.
    s = radchain.load(sbv)
    s.run()
    with pytest.raises(ValueError, match="NUL"):
        s["target.magnitude\0junk"]
    with pytest.raises(ValueError, match="NUL"):
        s.set("optics.aperture\0x", "15 cm")
    with pytest.raises(ValueError, match="NUL"):
        s.set("optics.aperture", "15 cm\0 junk")
    with pytest.raises(TypeError, match="a parameter key is a str"):
        s.set(3, "15 cm")
    with pytest.raises(TypeError, match="a result name is a str"):
        s[b"target.magnitude"]
    with pytest.raises(ValueError, match="NUL"):
        s.sweep({"optics.aperture": [0.1, 0.2]}, results=["target.magnitude\0zz"])
    with pytest.raises(TypeError, match="a parameter key is a str"):
        radchain.load(sbv, set={1.5: "15 cm"})
    with pytest.raises(ValueError, match="NUL"):
        radchain.load(sbv + "\0.bak")
    with pytest.raises(ValueError, match="NUL"):
        radchain.catalogue([sbv], results=["detector.snr\0"])
    # The names as given still work.
    assert s["target.magnitude"] == pytest.approx(15.5565, abs=1e-4)


def test_a_mistyped_result_name_suggests_the_nearest(sbv):
    s = radchain.load(sbv)
    r = s.run()
    with pytest.raises(KeyError, match=r"target.magnitud: no such result \(did you mean 'target.magnitude'\?\)"):
        r["target.magnitud"]
    with pytest.raises(KeyError, match="did you mean"):
        r.record("detector.snrr")
    with pytest.raises(KeyError, match=r'detector.snrr: no such result \(did you mean "detector.snr"\?\)'):
        s["detector.snrr"]
