"""A detector prototyped in Python: PyPointCamera reads the light's spectrum in prepare() and
counts it with numpy, the way plugins/detector/emva1288.cpp counts a point image that falls in one pixel (no PSF,
one exposure, no binning, no TDI, no sky):
    S = t η s ∫ P_λ λ/(hc) dλ over [band_min, band_max]            (EMVA 1288 R4.0 eq. 1, Pan 2010 eqs. 6-7)
    n² = S + σ_d0² + 1/(12 K²) + μ_I t                              (EMVA 1288 eqs. 5, 6; σ_q = 1/√12 DN)
with P_λ the focal-plane spectral power per unit signal scale s and the integral the trapezoid of P_λ λ over the
spectrum's nodes in the band (what radchain's band_integral does, spectrum.cpp). The C++ camera and its Python twin
must give the same numbers: forward to 1e-12, the solved limiting magnitude to 1e-10 (the C++ chain inverts in
closed form, the Python one is bracketed), after a spectral parameter changes, and over a sweep."""
import numpy as np
import pytest

import radchain

H_C = 6.62607015e-34 * 299792458.0  # h c, J m (SI 2019 exact values, as radchain/constants.hpp)


@radchain.register_stage
class PyPointCamera(radchain.Stage):
    kind, name = "detector", "py_point_camera"
    summary = "EMVA 1288 camera counting a point image in one pixel (Python twin of emva1288 without a PSF)"
    reference = "EMVA Standard 1288 R4.0 eqs. 1, 5, 6"
    schema = [
        radchain.parameter("band_min", type="quantity", unit="m", required=True, min=0, min_exclusive=True,
                           spectral=True, example="0.4 um", doc="detector band lower limit"),
        radchain.parameter("band_max", type="quantity", unit="m", required=True, min=0, min_exclusive=True,
                           spectral=True, example="0.9 um", doc="detector band upper limit"),
        radchain.parameter("qe", default="1", min=0, max=1, min_exclusive=True, doc="quantum efficiency η"),
        radchain.parameter("integration_time", type="quantity", unit="s", required=True, min=0, min_exclusive=True,
                           example="1 s", doc="exposure t"),
        radchain.parameter("gain", type="quantity", unit="electron-1", required=True, min=0, min_exclusive=True,
                           example="0.5 DN/e-", doc="system gain K"),
        radchain.parameter("read_noise", type="quantity", unit="electron", required=True, min=0, example="3 e-",
                           doc="temporal dark noise σ_d0"),
        radchain.parameter("dark_current", type="quantity", unit="electron/s", default="0 e-/s", min=0,
                           doc="dark current μ_I"),
    ]
    publishes = {"detector.image_electrons": "S = t η s ∫ P λ/(hc) dλ (EMVA eq. 1)",
                 "detector.signal_electrons": "S (the whole image in one pixel)",
                 "detector.noise_electrons": "√(S + σ_d0² + 1/(12K²) + μ_I t) (EMVA eqs. 5, 6)",
                 "detector.snr": "S / n", "detector.integration_time": "input t"}

    def prepare(self, params, light):
        signal = light["signal"]
        if signal is None or signal["form"] != "focal_power":
            raise ValueError("py_point_camera counts a point image: the optics must deliver focal_power")
        w, v = signal["wavelength_m"], signal["value"]
        lo, hi = params["band_min"], params["band_max"]
        if signal["extrapolation"] == "zero":  # nothing outside the table: integrate over the overlap
            lo, hi = max(lo, w[0]), min(hi, w[-1])
        x = np.concatenate(([lo], w[(w > lo) & (w < hi)], [hi]))
        self.photons_per_scale = np.trapz(np.interp(x, w, v) * x, x) / H_C
        self.background = light["background"]

    def evaluate(self, params, inputs):
        t = params["integration_time"]
        s = t * params["qe"] * inputs["light.signal.scale"] * self.photons_per_scale
        noise = np.sqrt(s + params["read_noise"] ** 2 + 1 / (12 * params["gain"] ** 2) + params["dark_current"] * t)
        return {"detector.image_electrons": s, "detector.signal_electrons": s, "detector.noise_electrons": noise,
                "detector.snr": s / noise, "detector.integration_time": t}


SENSOR = """
[sensor]
name = "a point camera, in C++ and in Python"
[source]
plugin = "sun"
[atmosphere]
plugin = "none"
[target]
plugin = "point_source"
system = "vega"
band = "johnson_cousins_V_bessell1990.csv"
magnitude = 12
[optics]
plugin = "telescope"
aperture = "20 cm"
transmittance = 0.8
focal_length = "1 m"
[detector]
plugin = "{plugin}"
band_min = "0.4 um"
band_max = "0.9 um"
qe = 0.6
integration_time = "1 s"
gain = "0.5 DN/e-"
read_noise = "3 e-"
dark_current = "2 e-/s"
{extra}
[criteria.detection]
plugin = "snr_threshold"
threshold = 5
[[solve]]
unknown = "target.magnitude"
criterion = "detection"
bracket = [5, 25]
"""
CPP_ONLY = 'full_well = "20000 e-"\nadc_bits = 16\npixel_pitch = "5 um"'  # emva1288's required keys
SHARED = ["detector.image_electrons", "detector.signal_electrons", "detector.noise_electrons", "detector.snr"]


@pytest.fixture()
def twins(source_dir):
    name = str(source_dir / "sensors" / "twin.toml")  # data files resolve as for the bundled sensors
    return (radchain.loads(SENSOR.format(plugin="emva1288", extra=CPP_ONLY), name=name),
            radchain.loads(SENSOR.format(plugin="py_point_camera", extra=""), name=name))


def test_forward_numbers_agree(twins):
    cpp, py = (s.evaluate() for s in twins)
    for n in SHARED:
        assert py[n] == pytest.approx(cpp[n], rel=1e-12), n
    assert py.record("detector.snr").stage == "py_point_camera"
    assert 1e3 < py["detector.signal_electrons"] < 1e6  # a 12th-magnitude star in 1 s on 20 cm: a real count


def test_solved_limiting_magnitude_agrees(twins):
    cpp, py = (s.run() for s in twins)
    assert cpp.solves[0].converged and py.solves[0].converged
    assert py["target.magnitude"] == pytest.approx(cpp["target.magnitude"], rel=1e-10)
    assert py["detector.snr"] == pytest.approx(5.0, rel=1e-9)


def test_spectral_parameter_reruns_prepare(twins):
    for s in twins:
        s.set("detector.band_max", 0.7e-6, si=True)
    cpp, py = (s.evaluate() for s in twins)
    assert py["detector.image_electrons"] == pytest.approx(cpp["detector.image_electrons"], rel=1e-12)
    narrow, = {cpp["detector.image_electrons"]}
    for s in twins:
        s.set("detector.band_max", 0.9e-6, si=True)
    assert twins[1].evaluate()["detector.image_electrons"] > narrow  # the wider band counts more: prepare re-ran


def test_sweep_agrees(twins):
    exposures = np.geomspace(0.1, 100, 7)
    cpp, py = (s.sweep({"detector.integration_time": exposures}, results=["target.magnitude"]) for s in twins)
    np.testing.assert_allclose(py["target.magnitude"], cpp["target.magnitude"], rtol=1e-10)
    assert np.all(np.diff(py["target.magnitude"]) > 0)  # longer exposures reach fainter


@radchain.register_stage
class PyProbeCamera(PyPointCamera):
    """PyPointCamera that keeps the light its prepare() was given."""
    name = "py_probe_camera"
    seen = {}

    def prepare(self, params, light):
        PyProbeCamera.seen = light
        super().prepare(params, light)


def test_prepare_sees_the_light_per_unit_scale(source_dir):
    radchain.loads(SENSOR.format(plugin="py_probe_camera", extra=""), name=str(source_dir / "sensors" / "twin.toml")).evaluate()
    light = PyProbeCamera.seen
    assert light["signal"]["form"] == "focal_power" and light["signal"]["unit"] == "W m-1"
    assert isinstance(light["signal"]["wavelength_m"], np.ndarray)
    assert light["signal"]["wavelength_m"].shape == light["signal"]["value"].shape
    assert light["background"] is None and light["path_radiance"] is None  # no sky, no atmosphere
