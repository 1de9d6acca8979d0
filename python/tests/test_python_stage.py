"""A stage written in Python (radchain.Stage, register_stage) in a chain: the Python twin of the C++ criterion
snr_threshold (threshold form, plugins/criterion/snr_threshold.cpp: margin = SNR/T − 1, Pan 2010 eq. 10) gives the
C++ numbers: forward bit for bit, solved to 1e-12 (the C++ criterion inverts in closed form, the Python one is
bracketed by TOMS 748), swept to 1e-12."""
import numpy as np
import pytest

import radchain


@radchain.register_stage
class PySnrThreshold(radchain.Stage):
    kind, name = "criterion", "py_snr_threshold"
    summary = "detection when SNR >= T (Python twin of snr_threshold, threshold form)"
    reference = "Pan et al. 2010 eq. (10)"
    schema = [radchain.parameter("threshold", default="5", min=0, min_exclusive=True, doc="SNR threshold T")]
    publishes = {"criteria.*.threshold": "input T", "criteria.*.margin": "SNR/T - 1 (Pan 2010 eq. 10)"}
    needs = ["detector.snr"]

    def evaluate(self, params, inputs):
        t = params["threshold"]
        return {"criteria.*.threshold": t, "criteria.*.margin": inputs["detector.snr"] / t - 1.0}


@pytest.fixture(scope="module")
def twins(sbv):
    text = open(sbv).read()
    assert text.count('plugin = "snr_threshold"') == 1
    python_text = text.replace('plugin = "snr_threshold"', 'plugin = "py_snr_threshold"')
    return radchain.loads(text, name=sbv), radchain.loads(python_text, name=sbv)


SHARED = ["target.magnitude", "detector.snr", "detector.signal_electrons", "criteria.detection.margin",
          "criteria.detection.threshold"]


def test_forward_bit_for_bit(twins):
    cpp, py = (s.evaluate() for s in twins)
    for name in SHARED:
        assert py[name] == cpp[name], name
    assert py.record("criteria.detection.margin").stage == "py_snr_threshold"
    assert py["criteria.detection.margin"] == py["detector.snr"] / 5.0 - 1.0


def test_solved_limiting_magnitude_to_1e12(twins):
    cpp, py = (s.run() for s in twins)
    assert py.solves[0].converged and py.passed == cpp.passed
    assert py["target.magnitude"] == pytest.approx(cpp["target.magnitude"], rel=1e-12)
    assert py["criteria.detection.margin"] == pytest.approx(0.0, abs=1e-12)
    assert py["detector.snr"] == pytest.approx(5.0, rel=1e-12)


def test_parameter_set_and_sweep_to_1e12(twins):
    cpp, py = twins
    for s in twins:
        s.set("criteria.detection.threshold", 7.0)
    assert py.run()["target.magnitude"] == pytest.approx(cpp.run()["target.magnitude"], rel=1e-12)
    apertures = np.linspace(0.10, 0.30, 9)
    a = cpp.sweep({"optics.aperture": apertures}, results=["target.magnitude"])
    b = py.sweep({"optics.aperture": apertures}, results=["target.magnitude"])
    assert b["ok"].all()
    np.testing.assert_allclose(b["target.magnitude"], a["target.magnitude"], rtol=1e-12, atol=0)
    for s in twins:
        s.set("criteria.detection.threshold", 5.0)


def test_schema_is_checked_like_a_plugin(sbv):
    text = open(sbv).read().replace('plugin = "snr_threshold"', 'plugin = "py_snr_threshold"')
    with pytest.raises(radchain.InputError) as error:
        radchain.loads(text, set={"criteria.detection.threshold": "-1"}, name=sbv)
    assert error.value.subject == "threshold" or "threshold" in str(error.value)
    assert "> 0" in str(error.value)


def test_contract_errors(sbv):
    class NotATerm(radchain.Stage):
        kind, name = "criterion", "py_not_a_term"
        publishes = {"criteria.*.marginal": ""}
    with pytest.raises(ValueError, match="not a vocabulary term"):
        radchain.register_stage(NotATerm)

    class Shadow(PySnrThreshold):
        name = "snr_threshold"
    with pytest.raises(ValueError, match="a plugin library has that name"):
        radchain.register_stage(Shadow)

    @radchain.register_stage
    class Forgetful(PySnrThreshold):
        name = "py_forgetful"

        def evaluate(self, params, inputs):
            return {"criteria.*.threshold": params["threshold"]}
    text = open(sbv).read().replace('plugin = "snr_threshold"', 'plugin = "py_forgetful"')
    with pytest.raises(RuntimeError, match='evaluate\\(\\) returned no "criteria.\\*.margin"'):
        radchain.loads(text, name=sbv).evaluate()
