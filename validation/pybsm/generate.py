#!/usr/bin/python3
"""Build validation/pybsm/reference.json: pyBSM's own numbers for a set of cases radchain is compared with.

Usage:
    /usr/bin/python3 validation/pybsm/generate.py /path/to/pybsm-src [--commit SHA] [--out FILE]

/path/to/pybsm-src is a checkout (or `git archive` export) of github.com/Kitware/pybsm; nothing of pyBSM is copied
into this repository, only the numbers it computes. The script imports pyBSM from <path>/src with two shims, which
are recorded in the output header:

  * numba is not installed here: `numba.njit` is replaced by the identity decorator and `numba.prange` by `range`,
    so pyBSM's kernels run as plain Python (the same arithmetic; numba's fastmath may differ in the last bits).
  * `pybsm/__init__.py` reads its version from installed package metadata; the package module is created by hand
    (version taken from pyproject.toml) so the source tree can be imported without installing it.

pyBSM's MODTRAN 5.2.1 atmosphere database (src/pybsm/atms/*.bin) is stored in Git LFS; a mirror without LFS
objects has 130-byte pointer files instead. When the real .bin files are present they are used. Otherwise the
tables are taken from pyBSM's own test snapshots, which print the loader's output (the float32 values of the .bin,
scaled to W m-2 sr-1 m-1) in full (JSON) or to 9 significant digits (the .ambr repr, enough to recover a float32
exactly). Conditions available that way: (ihaze, altitude m, ground range m) = (1, 1000, 0), (1, 1000, 500),
(1, 2000, 0), (2, 1000, 0) in full; (1, 1000, 100) recovered from the interpolated 5 m snapshot and checked against
the interpolated 300 m snapshot; (1, 9000, 0) only over 0.50-0.66 um and 2.91-3.66 um; and the interpolated
(1, 300, 0) and (1, 25000 -> 20000, 300) tables. A case needing anything else fails loudly.
"""
from __future__ import annotations

import argparse
import datetime
import hashlib
import json
import math
import os
import re
import subprocess
import sys
import types

import numpy as np

ATM_ROWS = 1371
KNOWN_COMMIT = "6a6d23d9168fdd39e4527374632ba5ece42e4519"


# --------------------------------------------------------------------------------------------------------------
# Importing pyBSM from a source tree
# --------------------------------------------------------------------------------------------------------------
def import_pybsm(src: str):
    nb = types.ModuleType("numba")

    def njit(*args, **kwargs):
        if len(args) == 1 and callable(args[0]) and not kwargs:
            return args[0]
        return lambda f: f

    nb.njit = njit
    nb.jit = njit
    nb.prange = range
    sys.modules["numba"] = nb
    pkg_dir = os.path.join(src, "src", "pybsm")
    if not os.path.isdir(pkg_dir):
        sys.exit(f"{pkg_dir}: not a pyBSM source tree (expected src/pybsm)")
    version = "unknown"
    with open(os.path.join(src, "pyproject.toml")) as fh:
        m = re.search(r'^version\s*=\s*"([^"]+)"', fh.read(), re.M)
        if m:
            version = m.group(1)
    pk = types.ModuleType("pybsm")
    pk.__path__ = [pkg_dir]
    pk.__version__ = version
    sys.modules["pybsm"] = pk
    import pybsm.geospatial as geospatial
    import pybsm.metrics.functional as metrics
    import pybsm.noise as noise
    import pybsm.otf.functional as otf
    import pybsm.radiance.functional as radiance
    import pybsm.utils as utils
    from pybsm.simulation import Scenario, Sensor

    return types.SimpleNamespace(geospatial=geospatial, metrics=metrics, noise=noise, otf=otf, radiance=radiance,
                                 utils=utils, Scenario=Scenario, Sensor=Sensor, version=version)


def source_commit(src: str, given: str | None) -> tuple[str, str]:
    if given:
        return given, "given on the command line"
    try:
        out = subprocess.run(["git", "-C", src, "rev-parse", "HEAD"], capture_output=True, text=True, check=True)
        return out.stdout.strip(), "git rev-parse HEAD of the source tree"
    except (OSError, subprocess.CalledProcessError):
        return KNOWN_COMMIT, "not a git work tree: the commit this script was written against (check the file hashes)"


def file_hashes(src: str) -> dict:
    files = ["src/pybsm/metrics/functional.py", "src/pybsm/otf/functional.py", "src/pybsm/radiance/functional.py",
             "src/pybsm/geospatial.py", "src/pybsm/noise.py", "src/pybsm/utils.py", "src/pybsm/simulation/sensor.py",
             "src/pybsm/simulation/scenario.py"]
    out = {}
    for f in files:
        with open(os.path.join(src, f), "rb") as fh:
            out[f] = hashlib.sha256(fh.read()).hexdigest()
    return out


# --------------------------------------------------------------------------------------------------------------
# Atmosphere tables
# --------------------------------------------------------------------------------------------------------------
def _f32(a: np.ndarray) -> np.ndarray:
    """The loader's columns 1-5 are float32 values; round a recovered table back onto them."""
    a = np.array(a, dtype=np.float64)
    a[:, 1:] = a[:, 1:].astype(np.float32).astype(np.float64)
    return a


def _json_table(path: str) -> np.ndarray:
    with open(path) as fh:
        obj = json.load(fh)

    def dec(o):
        t = o["__type__"]
        if t == "ndarray":
            return [dec(x) for x in o["data"]]
        if t == "list":
            return [dec(x) for x in o["items"]]
        if t == "float":
            v = o["value"]
            return float({"NaN": "nan", "Infinity": "inf", "-Infinity": "-inf"}.get(v, v)) if isinstance(v, str) else v
        raise ValueError(t)

    a = np.array(dec(obj), dtype=np.float64)
    assert a.shape == (ATM_ROWS, 6), a.shape
    return a


def _ambr_rows(path: str, block_name: str) -> np.ndarray:
    """Rows of the `atm=array([[...]])` printed at the top of one Metrics snapshot block."""
    with open(path) as fh:
        text = fh.read()
    start = text.index(f"# name: {block_name}\n")
    i = text.index("atm=array(", start)
    j = text.index("]])", i)
    numbers = [float(x) for x in re.findall(r"[-+]?\d\.\d+e[-+]\d+|[-+]?\d+\.\d*(?:e[-+]\d+)?", text[i + 10:j])]
    rows = np.array(numbers, dtype=np.float64).reshape(-1, 6)
    return _f32(rows)


class AtmosphereSource:
    def __init__(self, src: str, pb):
        self.src = src
        self.pb = pb
        self.provenance: dict[str, str] = {}
        self.exact: dict[tuple, np.ndarray] = {}
        self.interp: dict[tuple, np.ndarray] = {}
        atm_dir = os.path.join(src, "src", "pybsm", "atms")
        self.real_database = os.path.getsize(os.path.join(atm_dir, "1.bin")) == ATM_ROWS * 5 * 4
        if self.real_database:
            self.mode = "pyBSM's MODTRAN database (src/pybsm/atms/*.bin, Git LFS objects present)"
            return
        self.mode = ("pyBSM's MODTRAN database is a set of Git LFS pointers in this tree: tables recovered from "
                     "pyBSM's own test snapshots (see provenance)")
        snap = os.path.join(src, "tests", "scenario", "__snapshots__")
        u = os.path.join(snap, "test_utils", "TestUtils.test_load_database_atmosphere")
        s = os.path.join(snap, "test_scenario", "TestScenario.test_atm")
        ambr = os.path.join(src, "tests", "metrics", "__snapshots__", "test_functional.ambr")

        def add(key, path):
            self.exact[key] = _json_table(path)
            self.provenance[str(key)] = os.path.relpath(path, src)

        add((1, 1000.0, 0.0), u + "_no_interp[1-1000.0-0.0].json")
        add((1, 1000.0, 500.0), u + "_no_interp[1-1000.0-500.0].json")
        add((1, 2000.0, 0.0), s + "[test-1-2000.0-0.0-False].json")
        add((2, 1000.0, 0.0), s + "[test-2-1000.0-0.0-False].json")
        # (1, 1000, 100): the 5 m interpolated snapshot is 0.95 atm(0) + 0.05 atm(100) (utils.load_database_atmosphere)
        a5 = _json_table(s + "[test-1-1000.0-5.0-True].json")
        a0 = self.exact[(1, 1000.0, 0.0)]
        a100 = _f32((a5 - 0.95 * a0) / 0.05)
        a100[:, 0] = a0[:, 0]
        # check: the 300 m interpolated snapshot is 0.5 atm(100) + 0.5 atm(500)
        a300 = _json_table(u + "[1-1000.0-300.0].json")
        recon = 0.5 * a100 + 0.5 * self.exact[(1, 1000.0, 500.0)]
        rel = np.max(np.abs(recon[:, 1:] - a300[:, 1:]) / np.maximum(np.abs(a300[:, 1:]), 1e-300))
        if rel > 1e-6:
            sys.exit(f"recovered (1, 1000, 100) table fails the 300 m interpolation check: {rel:.3g}")
        self.exact[(1, 1000.0, 100.0)] = a100
        self.provenance[str((1, 1000.0, 100.0))] = (
            "(test_atm[test-1-1000.0-5.0-True] - 0.95 x no_interp[1-1000.0-0.0]) / 0.05, rounded to float32; "
            f"reproduces test_load_database_atmosphere[1-1000.0-300.0] to {rel:.1e}")
        # (1, 9000, 0): only the in-band rows printed by the niirs5 snapshots (visible and MWIR test sensors)
        vis = _ambr_rows(ambr, "TestFunctional.test_niirs5[sensor1-scenario1-False]")
        mwir = _ambr_rows(ambr, "TestFunctional.test_niirs5[sensor0-scenario0-True]")
        t9 = np.full((ATM_ROWS, 6), np.nan)
        t9[:, 0] = 1e-6 * np.linspace(0.3, 14.0, ATM_ROWS)
        for rows in (vis, mwir):
            for r in rows:
                k = int(round((r[0] * 1e6 - 0.3) / 0.01))
                t9[k, 1:] = r[1:]
        self.exact[(1, 9000.0, 0.0)] = t9
        self.provenance[str((1, 9000.0, 0.0))] = (
            "tests/metrics/__snapshots__/test_functional.ambr, test_niirs5[sensor1-scenario1-False] (0.50-0.66 um) "
            "and [sensor0-scenario0-True] (2.91-3.66 um) atm= rows, 9 significant digits -> float32; NaN elsewhere")
        # interpolated tables as load_database_atmosphere returns them
        self.interp[(1, 300.0, 0.0)] = _json_table(u + "[1-300.0-0.0].json")
        self.provenance["interp " + str((1, 300.0, 0.0))] = os.path.relpath(u + "[1-300.0-0.0].json", src)
        self.interp[(1, 25000.0, 300.0)] = _json_table(u + "[1-25000.0-300.0].json")
        self.provenance["interp " + str((1, 25000.0, 300.0))] = os.path.relpath(u + "[1-25000.0-300.0].json", src)
        self.interp[(1, 1000.0, 300.0)] = a300
        self.provenance["interp " + str((1, 1000.0, 300.0))] = os.path.relpath(u + "[1-1000.0-300.0].json", src)

    def install(self):
        if self.real_database:
            return
        utils = self.pb.utils
        original_interp = utils.load_database_atmosphere

        def no_interp(*, altitude, ground_range, ihaze):
            key = (int(ihaze), float(altitude), float(ground_range))
            if key not in self.exact:
                raise KeyError(f"no atmosphere table for (ihaze, altitude, ground range) = {key} in this tree")
            return self.exact[key].copy()

        def interp(*, altitude, ground_range, ihaze):
            key = (int(ihaze), float(altitude), float(ground_range))
            if key in self.interp:
                return self.interp[key].copy()
            return original_interp(altitude=altitude, ground_range=ground_range, ihaze=ihaze)

        utils.load_database_atmosphere_no_interp = no_interp
        utils.load_database_atmosphere = interp


# --------------------------------------------------------------------------------------------------------------
# Cases
# --------------------------------------------------------------------------------------------------------------
def f(x) -> float:
    return float(x)


BASE_SENSOR = dict(D=275e-3, f=4.0, p_x=0.008e-3, band_um=[0.50, 0.66])  # tests/metrics/test_functional.py


def make_sensor(pb, c: dict):
    kw = dict(name=c["name"], D=c["D"], f=c["f"], p_x=c["p_x"],
              opt_trans_wavelengths=np.array(c["band_um"]) * 1.0e-6)
    for k in ("eta", "int_time", "dark_current", "read_noise", "max_n", "max_well_fill", "bit_depth", "n_tdi", "s_x",
              "s_y", "da_x", "da_y", "pv", "pv_wavelength", "frame_stacks"):
        if k in c:
            kw[k] = c[k]
    if "qe" in c:
        kw["qe"] = np.array(c["qe"])
        kw["qe_wavelengths"] = np.array(c["qe_wavelengths_um"]) * 1e-6
    return pb.Sensor(**kw)


def make_scenario(pb, c: dict):
    kw = dict(name=c["name"], ihaze=c["ihaze"], altitude=c["altitude"], ground_range=c["ground_range"])
    for k in ("aircraft_speed", "ha_wind_speed", "cn2_at_1m"):
        if k in c:
            kw[k] = c[k]
    return pb.Scenario(**kw)


def component_mtfs(pb, sensor, scenario, wavelengths, weights, slant_range, int_time, freqs_cyc_per_rad, axis):
    """common_OTFs evaluated on a 1-row grid at the given frequencies along u (axis 0) or v (axis 1)."""
    fr = np.array([freqs_cyc_per_rad], dtype=np.float64)
    zeros = np.zeros_like(fr)
    uu, vv = (fr, zeros) if axis == 0 else (zeros, fr)
    o = pb.otf.common_OTFs(sensor=sensor, scenario=scenario, uu=uu, vv=vv, mtf_wavelengths=wavelengths,
                           mtf_weights=weights, slant_range=slant_range, int_time=int_time)
    comp = {
        "diffraction": ("common_OTFs.ap_OTF = weighted_by_wavelength(circular_aperture_OTF)", o.ap_OTF),
        "turbulence": ("common_OTFs.turb_OTF = polychromatic_turbulence_OTF (HV profile, wind_speed_turbulence_OTF)",
                       o.turb_OTF),
        "detector": ("common_OTFs.det_OTF = detector_OTF (sinc of w/f)", o.det_OTF),
        "jitter": ("common_OTFs.jit_OTF = jitter_OTF", o.jit_OTF),
        "drift": ("common_OTFs.drft_OTF = drift_OTF (da * int_time * n_tdi)", o.drft_OTF),
        "wavefront": ("common_OTFs.wav_OTF = weighted_by_wavelength(wavefront_OTF)", o.wav_OTF),
        "filter": ("common_OTFs.filter_OTF", o.filter_OTF),
        "system": ("common_OTFs.system_OTF (product)", o.system_OTF),
    }
    return {k: {"function": fn, "values": [f(x) for x in np.abs(np.asarray(v)).ravel()]} for k, (fn, v) in comp.items()}


def nyquist_fractions():
    return [0.25, 0.5, 0.75, 1.0, 1.5]


def run_niirs_case(pb, c: dict) -> dict:
    sensor = make_sensor(pb, c)
    scenario = make_scenario(pb, c)
    interp = c.get("interp", False)
    m5 = pb.metrics.niirs5(sensor=sensor, scenario=scenario, interp=interp)
    sensor3 = make_sensor(pb, c)
    scenario3 = make_scenario(pb, c)
    m3 = pb.metrics.niirs(sensor=sensor3, scenario=scenario3, interp=interp)
    snr = m5.snr
    ifov = sensor.p_x / sensor.f
    nyq = 0.5 / ifov  # cycles/rad
    freqs = [x * nyq for x in nyquist_fractions()]
    comps_u = component_mtfs(pb, make_sensor(pb, c), make_scenario(pb, c), m5.mtf_wavelengths, m5.mtf_weights,
                             m5.slant_range, snr.int_time, freqs, 0)
    band = m5.atm  # cropped in-band table (columns: wavelength, TRANS, PTH THRML, SURF EMIS, SOL SCAT, GRND RFLT)
    # reflectance dimension: total_radiance + signal_rate at a few reflectances, the same optics/QE resampling as
    # photon_detector_SNR, electrons over the (well-fill scaled) integration time
    refl = {}
    for rho in c.get("reflectances", [0.05, 0.15, 0.3, 0.6]):
        L = pb.radiance.total_radiance(atm=band, reflectance=rho, temperature=282.0)
        rate, _, _ = pb.radiance.signal_rate(wavelengths=band[:, 0], target_radiance=L, optical_transmission=snr.opt_trans,
                                             D=sensor.D, f=sensor.f, w_x=sensor.w_x, w_y=sensor.w_y, qe=snr.qe,
                                             other_irradiance=snr.other_irradiance, dark_current=sensor.dark_current)
        refl[f"{rho}"] = {
            "function": "radiance.total_radiance(temperature=282) + radiance.signal_rate, x int_time x n_tdi",
            "electrons": f(rate * snr.int_time * sensor.n_tdi),
            "band_mean_radiance_W_m2_sr_um": f(np.trapz(L, band[:, 0]) / (band[-1, 0] - band[0, 0]) * 1e-6),
        }
    out = {
        "kind": "niirs",
        "inputs": {k: v for k, v in c.items() if k not in ("doc",)},
        "doc": c.get("doc", ""),
        "atmosphere": {
            "key": [c["ihaze"], c["altitude"], c["ground_range"]],
            "interp": interp,
            "in_band_table": {
                "columns": ["wavelength_m", "TRANS", "PTH_THRML", "SURF_EMIS", "SOL_SCAT", "GRND_RFLT(rho=0.15)"],
                "units": "radiance columns W m-2 sr-1 m-1",
                "rows": [[f(x) for x in r] for r in band],
            },
        },
        "outputs": {
            "slant_range_m": {"function": "geospatial.curved_earth_slant_range (r_earth 6378.164 km)",
                              "value": f(m5.slant_range)},
            "elev_angle_rad": {"function": "pi/2 - geospatial.nadir_angle (angle at the sensor)",
                               "value": f(m5.elev_angle)},
            "ifov_rad": {"function": "p_x / f", "value": f(ifov)},
            "gsd_m": {"function": "niirs5: gsd_x = ifov_x * slant_range", "value": f(m5.gsd_x)},
            "gsd_w_m": {"function": "giqe5: gsd / sin(elev_angle)**0.25", "value": f(m5.gsd_w)},
            "gsd_gp_m": {"function": "giqe4: gsd_gm / sin(elev_angle)**0.5", "value": f(m3.gsd_gp)},
            "int_time_s": {"function": "photon_detector_SNR: int_time x check_well_fill scale", "value": f(snr.int_time)},
            "well_fraction": {"function": "photon_detector_SNR.well_fraction", "value": f(snr.well_fraction)},
            "target_electrons": {"function": "photon_detector_SNR.tgt_n (rho 0.15, giqe_radiance)", "value": f(snr.tgt_n)},
            "background_electrons": {"function": "photon_detector_SNR.bkg_n (rho 0.07, giqe_radiance)",
                                     "value": f(snr.bkg_n)},
            "contrast_electrons": {"function": "photon_detector_SNR.contrast_signal", "value": f(snr.contrast_signal)},
            "total_noise_electrons": {"function": "photon_detector_SNR.total_noise", "value": f(snr.total_noise)},
            "quantization_noise_electrons": {"function": "noise.quantization_noise(max_n, bit_depth)",
                                             "value": f(snr.quantization_noise)},
            "dark_current_noise_electrons": {"function": "photon_detector_SNR.dark_current_noise (reported, not added)",
                                             "value": f(snr.dark_current_noise)},
            "path_noise_electrons": {"function": "niirs5: path_noise", "value": f(snr.path_noise)},
            "scene_noise_electrons": {"function": "niirs5: scene_noise", "value": f(snr.scene_noise)},
            "snr": {"function": "photon_detector_SNR.snr = contrast / total_noise", "value": f(snr.snr)},
            "cutoff_frequency_cyc_per_rad": {"function": "niirs5: D / min(mtf_wavelengths)",
                                             "value": f(m5.cutoff_frequency)},
            "df_cyc_per_rad": {"function": "niirs5: grid step (101 points over +-cutoff)", "value": f(m5.df)},
            "r0_band_m": {"function": "polychromatic_turbulence_OTF r0_band", "value": f(np.ravel(m5.otf.r0_band)[0])},
            "mtf_wavelengths_m": {"function": "niirs5: in-band wavelengths with signal weight > 0",
                                  "value": [f(x) for x in m5.mtf_wavelengths]},
            "mtf_weights": {"function": "photon_detector_SNR.weights (target e-/s/m per wavelength)",
                            "value": [f(x) for x in m5.mtf_weights]},
            "mtf_frequencies": {"function": "fractions of Nyquist 0.5/ifov, u axis (x)",
                                "nyquist_fraction": nyquist_fractions(),
                                "cycles_per_rad": [f(x) for x in freqs],
                                "cycles_per_m_focal_plane": [f(x / sensor.f) for x in freqs]},
            "mtf_u": comps_u,
            "rer_0": {"function": "giqe5_RER (slice_otf ang 0, relative_edge_response)", "value": f(m5.rer_0)},
            "rer_90": {"function": "giqe5_RER (slice_otf ang pi/2)", "value": f(m5.rer_90)},
            "rer_giqe5": {"function": "giqe5: (max * min**2)**(1/3)", "value": f(m5.rer)},
            "niirs_giqe5": {"function": "metrics.functional.niirs5 -> giqe5", "value": f(m5.niirs)},
            "rer_gm": {"function": "giqe_edge_terms: sqrt(rer_0 rer_90)", "value": f(m3.rer_gm)},
            "eho_gm": {"function": "giqe_edge_terms: sqrt(eho_0 eho_90) (edge_height_overshoot)", "value": f(m3.eho_gm)},
            "noise_gain": {"function": "noise.noise_gain(filter_kernel)", "value": f(m3.ng)},
            "niirs_giqe3": {"function": "metrics.functional.niirs -> giqe3", "value": f(m3.niirs)},
            "niirs_giqe4": {"function": "metrics.functional.niirs -> giqe4", "value": f(m3.niirs_4)},
            "electrons_at_reflectance": refl,
        },
    }
    return out


def run_mtf_case(pb, c: dict) -> dict:
    """Geometry + MTF + RER + GIQE from pyBSM's functions with a monochromatic MTF and no turbulence (cn2 = 0), so
    that the inputs are the ones radchain's giqe criterion takes; SNR given."""
    sensor = make_sensor(pb, dict(c, band_um=[c["wavelength_um"], c["wavelength_um"]]))
    scenario = make_scenario(pb, dict(c, ihaze=1, cn2_at_1m=0.0))
    h, g = c["altitude"], c["ground_range"]
    slant = pb.geospatial.curved_earth_slant_range(h_target=0.0, h_sensor=h, ground_range=g)
    nadir = pb.geospatial.nadir_angle(h_target=0.0, h_sensor=h, slant_range=slant) if g > 0 else 0.0
    elev = math.pi / 2 - nadir
    ifov = sensor.p_x / sensor.f
    gsd = pb.geospatial.ground_sample_distance(ifov=ifov, slant_range=slant)
    lam = np.array([c["wavelength_um"] * 1e-6])
    w = np.array([1.0])
    int_time = c.get("int_time", 1.0)
    # the niirs5 frequency grid
    cutoff = sensor.D / lam.min()
    u_rng = np.linspace(-1.0, 1.0, 101) * cutoff
    v_rng = np.linspace(1.0, -1.0, 101) * cutoff
    uu, vv = np.meshgrid(u_rng, v_rng)
    df = u_rng[1] - u_rng[0]
    o = pb.otf.common_OTFs(sensor=sensor, scenario=scenario, uu=uu, vv=vv, mtf_wavelengths=lam, mtf_weights=w,
                           slant_range=slant, int_time=int_time)
    rer_0, rer_90 = pb.metrics.giqe5_RER(mtf=np.abs(o.system_OTF), df=df, ifov_x=ifov, ifov_y=ifov)
    snr = c["snr"]
    niirs5, gsd_w, rer5 = pb.metrics.giqe5(rer_1=rer_0, rer_2=rer_90, gsd=gsd, snr=snr, elev_angle=elev)
    rer_gm, eho_gm = pb.metrics.giqe_edge_terms(mtf=np.abs(o.system_OTF), df=df, ifov_x=ifov, ifov_y=ifov)
    niirs4, gsd_gp = pb.metrics.giqe4(rer=rer_gm, gsd=gsd, eho=eho_gm, ng=1.0, snr=snr, elev_angle=elev)
    niirs3 = pb.metrics.giqe3(rer=rer_gm, gsd=gsd, eho=eho_gm, ng=1.0, snr=snr)
    nyq = 0.5 / ifov
    freqs = [x * nyq for x in nyquist_fractions()]
    comps_u = component_mtfs(pb, sensor, scenario, lam, w, slant, int_time, freqs, 0)
    comps_v = component_mtfs(pb, sensor, scenario, lam, w, slant, int_time, freqs, 1)
    # the 1-D slice giqe5_RER integrates (u axis), for reference
    u_slice = pb.otf.slice_otf(otf=np.abs(o.system_OTF), ang=0)
    return {
        "kind": "mtf_geometry",
        "inputs": {k: v for k, v in c.items() if k not in ("doc",)},
        "doc": c.get("doc", ""),
        "outputs": {
            "slant_range_m": {"function": "geospatial.curved_earth_slant_range (r_earth 6378.164 km)", "value": f(slant)},
            "nadir_angle_rad": {"function": "geospatial.nadir_angle (at the sensor)", "value": f(nadir)},
            "elev_angle_rad": {"function": "pi/2 - geospatial.nadir_angle", "value": f(elev)},
            "ifov_rad": {"function": "p_x / f", "value": f(ifov)},
            "gsd_m": {"function": "geospatial.ground_sample_distance = ifov * slant_range", "value": f(gsd)},
            "gsd_w_m": {"function": "giqe5: gsd / sin(elev)**0.25", "value": f(gsd_w)},
            "gsd_gp_m": {"function": "giqe4: gsd / sin(elev)**0.5", "value": f(gsd_gp)},
            "cutoff_frequency_cyc_per_rad": {"function": "D / lambda", "value": f(cutoff)},
            "df_cyc_per_rad": {"function": "niirs5 grid step", "value": f(df)},
            "mtf_frequencies": {"function": "fractions of Nyquist 0.5/ifov", "nyquist_fraction": nyquist_fractions(),
                                "cycles_per_rad": [f(x) for x in freqs],
                                "cycles_per_m_focal_plane": [f(x / sensor.f) for x in freqs]},
            "mtf_u": comps_u,
            "mtf_v": comps_v,
            "rer_slice_u": {"function": "otf.slice_otf(abs(system_OTF), 0): the samples relative_edge_response "
                                        "integrates (df apart, from 0)",
                            "values": [f(x) for x in u_slice]},
            "rer_0": {"function": "metrics.giqe5_RER", "value": f(rer_0)},
            "rer_90": {"function": "metrics.giqe5_RER", "value": f(rer_90)},
            "rer_giqe5": {"function": "metrics.giqe5 weighted RER", "value": f(rer5)},
            "niirs_giqe5": {"function": "metrics.giqe5", "value": f(niirs5)},
            "rer_gm": {"function": "metrics.giqe_edge_terms", "value": f(rer_gm)},
            "eho_gm": {"function": "metrics.giqe_edge_terms", "value": f(eho_gm)},
            "niirs_giqe4": {"function": "metrics.giqe4 (ng = 1)", "value": f(niirs4)},
            "niirs_giqe3": {"function": "metrics.giqe3 (ng = 1)", "value": f(niirs3)},
        },
    }


def niirs_cases() -> list[dict]:
    b = dict(BASE_SENSOR)
    cases = [
        dict(b, name="A1-test-sensor-9km-nadir", ihaze=1, altitude=9000.0, ground_range=0.0,
             doc="pyBSM tests/metrics/test_functional.py test_niirs5/test_niirs sensor1 (docs/examples/pybsm_example.py "
                 "camera): D 275 mm, f 4 m, p 8 um, 0.50-0.66 um, all other Sensor/Scenario defaults"),
        dict(b, name="A2-test-sensor-1km-nadir", ihaze=1, altitude=1000.0, ground_range=0.0,
             doc="the test sensor at 1 km"),
        dict(b, name="A3-test-sensor-1km-gr500", ihaze=1, altitude=1000.0, ground_range=500.0,
             doc="1 km altitude, 500 m ground range (26.6 deg off nadir)"),
        dict(b, name="A4-test-sensor-1km-gr100", ihaze=1, altitude=1000.0, ground_range=100.0,
             doc="1 km altitude, 100 m ground range"),
        dict(b, name="A5-test-sensor-2km-nadir", ihaze=1, altitude=2000.0, ground_range=0.0,
             doc="2 km altitude"),
        dict(b, name="A6-test-sensor-1km-ihaze2", ihaze=2, altitude=1000.0, ground_range=0.0,
             doc="rural 5 km visibility (ihaze 2) instead of 23 km"),
        dict(b, name="A7-test-sensor-300m-interp", ihaze=1, altitude=300.0, ground_range=0.0, interp=True,
             doc="300 m altitude, atmosphere interpolated between the 225 m and 500 m tables"),
        dict(b, name="A8-test-sensor-25km-gr300-interp", ihaze=1, altitude=25000.0, ground_range=300.0, interp=True,
             doc="25 km altitude (the interpolating loader clamps to the 20 km tables), 300 m ground range"),
        dict(name="A9-small-aperture-detector-1km", D=0.10, f=1.0, p_x=5e-6, band_um=[0.45, 0.70], ihaze=1,
             altitude=1000.0, ground_range=500.0, eta=0.3, int_time=2e-3, dark_current=2000.0, read_noise=25.0,
             max_n=40000, bit_depth=12, qe=[0.55, 0.65, 0.60, 0.45], qe_wavelengths_um=[0.45, 0.55, 0.62, 0.70],
             s_x=5e-6, s_y=5e-6, da_x=1e-4, da_y=0.0,
             doc="a small obscured camera with a real detector: QE curve, read and dark noise, 12-bit ADC, 40k e- well, "
                 "jitter and drift"),
        dict(name="A10-large-aperture-2km-tdi", D=0.5, f=5.0, p_x=10e-6, band_um=[0.50, 0.66], ihaze=1,
             altitude=2000.0, ground_range=0.0, eta=0.2, int_time=1e-4, n_tdi=16, read_noise=50.0, max_n=200000,
             bit_depth=14, pv=(2 * math.pi * 0.05) ** 2, pv_wavelength=0.633e-6,
             doc="a 0.5 m aperture with 16 TDI stages and 0.05 waves rms wavefront error (pv at 633 nm)"),
        dict(b, name="A11-test-sensor-1km-no-turbulence", ihaze=1, altitude=1000.0, ground_range=0.0, cn2_at_1m=0.0,
             int_time=1e-3, read_noise=10.0, max_n=50000, bit_depth=12,
             doc="turbulence off (cn2_at_1m = 0), 1 ms integration, 10 e- read noise, 50k e- well, 12 bits"),
        dict(b, name="A12-test-sensor-1km-gr500-moving", ihaze=1, altitude=1000.0, ground_range=500.0,
             aircraft_speed=100.0, int_time=5e-3, read_noise=10.0, max_n=50000, bit_depth=12,
             doc="aircraft speed 100 m/s: the short/long-exposure turbulence weight exp(-v t / r0) < 1"),
        dict(name="A13-mwir-9km-nadir", D=275e-3, f=4.0, p_x=0.008e-3, band_um=[2.91, 3.66], ihaze=1,
             altitude=9000.0, ground_range=0.0,
             doc="pyBSM test_niirs5/test_niirs sensor0 (MWIR 2.91-3.66 um, emissive GIQE targets 282/280 K); interp=False "
                 "here (the snapshot's interp=True reads the same 9 km node)"),
    ]
    return cases


def mtf_cases() -> list[dict]:
    return [
        dict(name="B1-ikonos-like-681km-nadir", altitude=681e3, ground_range=0.0, D=0.70, f=10.0, p_x=12e-6,
             wavelength_um=0.675, snr=50.0, doc="sensors/ikonos-2-pan.toml's camera, monochromatic 675 nm"),
        dict(name="B2-ikonos-like-681km-gr350km", altitude=681e3, ground_range=350e3, D=0.70, f=10.0, p_x=12e-6,
             wavelength_um=0.675, snr=50.0, doc="the same 350 km down range (about 26.5 deg off nadir at the sensor)"),
        dict(name="B3-500km-obscured-jitter", altitude=500e3, ground_range=150e3, D=0.30, f=3.6, p_x=8e-6, eta=0.35,
             s_x=0.5e-6, s_y=0.5e-6, wavelength_um=0.60, snr=30.0,
             doc="500 km, 0.35 central obscuration, 0.5 urad rms jitter"),
        dict(name="B4-test-sensor-9km-nadir-mono", altitude=9000.0, ground_range=0.0, D=275e-3, f=4.0, p_x=8e-6,
             wavelength_um=0.58, snr=50.0, doc="pyBSM's test camera at 9 km, monochromatic 580 nm, no turbulence"),
        dict(name="B5-test-sensor-9km-gr20km-drift", altitude=9000.0, ground_range=20e3, D=275e-3, f=4.0, p_x=8e-6,
             wavelength_um=0.58, snr=20.0, int_time=1e-3, da_x=1e-3, da_y=0.0,
             doc="20 km down range, a 1 mrad/s drift along x over 1 ms (0.5 pixel)"),
        dict(name="B6-wavefront-500km", altitude=500e3, ground_range=0.0, D=0.5, f=5.0, p_x=10e-6, eta=0.2,
             pv=(2 * math.pi * 0.07) ** 2, pv_wavelength=0.6e-6, wavelength_um=0.60, snr=100.0,
             doc="0.07 waves rms wavefront error at 600 nm (pyBSM's Goodman phase-screen wavefront_OTF, L = D)"),
        dict(name="B7-20km-gr150km-grazing", altitude=20e3, ground_range=150e3, D=0.35, f=2.8, p_x=7e-6,
             wavelength_um=0.55, snr=15.0, doc="20 km altitude at 150 km ground range (low elevation)"),
    ]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("pybsm_src")
    ap.add_argument("--commit")
    ap.add_argument("--out", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "reference.json"))
    args = ap.parse_args()
    src = os.path.abspath(args.pybsm_src)
    pb = import_pybsm(src)
    commit, commit_how = source_commit(src, args.commit)
    atm = AtmosphereSource(src, pb)
    atm.install()

    # self-check against pyBSM's own snapshot of test_niirs5 / test_niirs (sensor1, 9 km)
    base = niirs_cases()[0]
    m5 = pb.metrics.niirs5(sensor=make_sensor(pb, base), scenario=make_scenario(pb, base), interp=False)
    m3 = pb.metrics.niirs(sensor=make_sensor(pb, base), scenario=make_scenario(pb, base), interp=False)
    snapshot = {"niirs5.niirs": 10.05230879223981, "niirs5.rer": 0.544879982245952, "snr": 758.4695956880196,
                "niirs.niirs": 10.048636441352345, "niirs.niirs_4": 9.36816615042465}
    ours = {"niirs5.niirs": m5.niirs, "niirs5.rer": m5.rer, "snr": m5.snr.snr, "niirs.niirs": m3.niirs,
            "niirs.niirs_4": m3.niirs_4}
    self_check = {k: {"snapshot": v, "here": f(ours[k]), "relative_delta": f(abs(ours[k] / v - 1))}
                  for k, v in snapshot.items()}
    worst = max(x["relative_delta"] for x in self_check.values())
    if worst > 1e-9:
        sys.exit(f"this run does not reproduce pyBSM's own test snapshot: {self_check}")

    cases = []
    for c in niirs_cases():
        cases.append(dict(run_niirs_case(pb, c), name=c["name"]))
    for c in mtf_cases():
        cases.append(dict(run_mtf_case(pb, c), name=c["name"]))

    header = {
        "peer": "pyBSM (Python Based Sensor Model), AFRL / Kitware",
        "repo": "https://github.com/Kitware/pybsm",
        "commit": commit,
        "commit_source": commit_how,
        "pybsm_version": pb.version,
        "source_sha256": file_hashes(src),
        "python": sys.version.split()[0],
        "numpy": np.__version__,
        "scipy": __import__("scipy").__version__,
        "date": datetime.date.today().isoformat(),
        "generator": "validation/pybsm/generate.py",
        "shims": ["numba absent: njit = identity, prange = range (plain Python kernels)",
                  "pybsm/__init__.py bypassed (it reads installed metadata); version from pyproject.toml"],
        "atmosphere": atm.mode,
        "atmosphere_provenance": atm.provenance,
        "self_check": {"against": "tests/metrics/__snapshots__/test_functional.ambr test_niirs5/test_niirs "
                                  "[sensor1-scenario1-False]", "values": self_check, "worst_relative_delta": worst},
        "units": "SI: m, rad, s, electrons; frequencies in cycles/rad (object space) unless named otherwise",
        "notes": [
            "kind 'niirs': pybsm.metrics.functional.niirs5 and niirs (GIQE-5, GIQE-3, GIQE-4) end to end, "
            "atmosphere from the MODTRAN tables; the in-band table is stored with the case.",
            "kind 'mtf_geometry': pyBSM's geometry, common_OTFs (one wavelength, weight 1, cn2_at_1m = 0), "
            "giqe5_RER / giqe_edge_terms on niirs5's 101x101 grid, giqe5 / giqe4 / giqe3 at a given SNR.",
            "mtf_u / mtf_v: each component at the listed frequencies along one axis (u = x, v = y); polychromatic "
            "components are the signal-weighted means pyBSM uses.",
        ],
    }
    with open(args.out, "w") as fh:
        json.dump({"header": header, "cases": cases}, fh, indent=1)
        fh.write("\n")
    print(f"wrote {args.out}: {len(cases)} cases; self-check worst {worst:.2e}")


if __name__ == "__main__":
    main()
