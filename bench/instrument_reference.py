#!/usr/bin/env python3
"""What an analyst would otherwise write for a survey telescope's depth grid: the Rubin r-band 5σ depth m5 of
sensors/rubin-lsst-r-m5.toml in vectorised numpy, over the grids bench/instrument_bench.cpp sweeps with radchain.

    /usr/bin/python3 bench/instrument_reference.py                                  # numpy alone
    /usr/bin/python3 bench/instrument_reference.py --bench out/release/radchain_bench  # and radchain: ratios

The physics, written from the sources the sensor file cites (not from radchain's code):
  * signal: a flat-f_ν AB source, f_ν = 10^(-0.4 (m + 48.6)) erg s-1 cm-2 Hz-1 (Oke & Gunn 1983), through the
    hardware throughput S(λ) and the atmosphere τ(λ)^X (Bouguer-Lambert-Beer from the X = 1 table), counted as
    photons: C(X) = A ∫ f_ν S τ^X / (h λ) dλ electrons per second at m = 0 (trapezoid rule on the tables' grid);
  * sky: m_sky AB mag/arcsec² at the pupil (not extinguished), over a pixel of (p/f)² sr;
  * PSF: a Gaussian of FWHM θ X^0.6 (Kolmogorov seeing, Roddier 1981) sampled by the pixels, centred on one:
    n_eff = 1/Σ f_ij² (King 1983; SMTN-002 uses 2.266 FWHM²/p², its large-PSF limit);
  * noise: σ² = S + n_eff (sky t + dark t + read² + 1/(12 K²)) (EMVA 1288 eqs. 5, 6 with quantisation), and
    SNR = 5 solved in closed form: S = (T² + √(T⁴ + 4 T² B))/2, m5 = −2.5 lg(S / (C t)).
Grids: airmass 1..2 × exposure 5..60 s × sky 19..22 mag/arcsec² and seeing 0.5..1.5" × exposure × sky, 100 each.
"""
import argparse
import json
import math
import os
import pathlib
import statistics
import subprocess
import sys
import timeit
import tomllib

import numpy as np
from scipy.special import erf

ROOT = pathlib.Path(__file__).resolve().parent.parent
SPECTRA = ROOT / "spectra"
H = 6.62607015e-34           # J s (exact, SI 2019)
F_NU_AB0 = 10 ** (-0.4 * 48.6) * 1e-3  # W m-2 Hz-1 of AB magnitude 0 (3630.8 Jy)
ARCSEC = math.pi / 648000.0


def load(name):
    """spectra/*.csv: '#' provenance lines, a header, then wavelength_nm,value rows. (m, value)."""
    rows = [line for line in (SPECTRA / name).read_text().splitlines() if line and not line.startswith("#")][1:]
    data = np.array([[float(x) for x in row.split(",")[:2]] for row in rows])
    return data[:, 0] * 1e-9, data[:, 1]


def quantity(text, unit, factor=1.0):
    """'6.423 m' -> 6.423 (the sensor file's few units, written out)."""
    number, written = text.split(None, 1)
    assert written == unit, (text, unit)
    return float(number) * factor


class Rubin:
    def __init__(self):
        sensor = tomllib.loads((ROOT / "sensors" / "rubin-lsst-r-m5.toml").read_text())
        optics, detector, atmosphere = sensor["optics"], sensor["detector"], sensor["atmosphere"]
        self.aperture = quantity(optics["aperture"], "m")
        focal = quantity(optics["focal_length"], "m")
        pitch = quantity(detector["pixel_pitch"], "um", 1e-6)
        self.pixel_rad = pitch / focal
        self.read = quantity(detector["read_noise"], "e-")
        self.dark = quantity(detector["dark_current"], "e-/s")
        self.gain = quantity(detector["gain"], "DN/e-")
        self.seeing = quantity(atmosphere["seeing"], "arcsec", ARCSEC)
        self.time = quantity(detector["integration_time"], "s")
        self.sky = float(atmosphere["sky_brightness"])
        self.threshold = float(sensor["criteria"]["detection"]["threshold"])
        wl, self.hardware = load(detector["qe_curve"])
        wl_atm, atm = load(atmosphere["transmittance_table"])
        assert np.array_equal(wl, wl_atm), "the two tables share their grid"
        self.wavelength, self.atmosphere = wl, atm
        self.area = math.pi * self.aperture**2 / 4

    def zero_point_rates(self, airmass):
        """C(X): electrons per second of an AB magnitude 0 source, one per airmass (a spectral integral each)."""
        weight = F_NU_AB0 * self.hardware / (H * self.wavelength)
        return self.area * np.trapz(weight * self.atmosphere ** np.asarray(airmass)[:, None], self.wavelength, axis=1)

    def sky_rates(self, sky_mag):
        """Sky electrons per second per pixel, one per sky brightness (AB mag/arcsec², at the pupil)."""
        per_arcsec2 = self.area * np.trapz(F_NU_AB0 * self.hardware / (H * self.wavelength), self.wavelength)
        pixel_arcsec2 = (self.pixel_rad / ARCSEC) ** 2
        return per_arcsec2 * pixel_arcsec2 * 10 ** (-0.4 * np.asarray(sky_mag))

    def n_eff(self, fwhm_rad):
        """1/Σ f_ij² of a pixel-sampled Gaussian centred on a pixel (separable), one per FWHM, vectorised."""
        sigma = np.asarray(fwhm_rad)[:, None] / self.pixel_rad / (2 * math.sqrt(2 * math.log(2)))
        half = int(math.ceil(8 * sigma.max())) + 1
        edges = np.arange(-half, half + 2) - 0.5
        cdf = 0.5 * erf(edges[None, :] / (math.sqrt(2) * sigma))
        column = np.diff(cdf, axis=1)
        return 1.0 / (column**2).sum(axis=1) ** 2

    def m5(self, rate, neff, sky_rate, time):
        """The SNR = T closed form, broadcast over whatever the arguments' shapes are."""
        floor = self.read**2 + 1.0 / (12 * self.gain**2)
        background = neff * ((sky_rate + self.dark) * time + floor)
        t2 = self.threshold**2
        signal = 0.5 * (t2 + np.sqrt(t2 * t2 + 4 * t2 * background))
        return -2.5 * np.log10(signal / (rate * time))

    def airmass_grid(self, n=100):
        airmass, time, sky = np.linspace(1, 2, n), np.linspace(5, 60, n), np.linspace(19, 22, n)
        rate = self.zero_point_rates(airmass)[:, None, None]
        neff = self.n_eff(self.seeing * airmass**0.6)[:, None, None]
        return self.m5(rate, neff, self.sky_rates(sky)[None, None, :], time[None, :, None])

    def seeing_grid(self, n=100):
        seeing, time, sky = np.linspace(0.5, 1.5, n) * ARCSEC, np.linspace(5, 60, n), np.linspace(19, 22, n)
        rate = self.zero_point_rates([1.0])[0]
        neff = self.n_eff(seeing)[:, None, None]
        return self.m5(rate, neff, self.sky_rates(sky)[None, None, :], time[None, :, None])

    def nominal(self):
        rate = self.zero_point_rates([1.0])[0]
        return float(self.m5(rate, self.n_eff([self.seeing])[0], self.sky_rates(self.sky), self.time))


def median_seconds(statement, number=1, repeat=7):
    return statistics.median(timeit.repeat(statement, number=number, repeat=repeat)) / number


def radchain_medians(bench):
    """Runs the instrument benchmarks once each (their grids take seconds); ms per benchmark."""
    env = dict(os.environ, RADCHAIN_PLUGIN_PATH=str(pathlib.Path(bench).resolve().parent / "plugins"),
               RADCHAIN_DATA_PATH=str(SPECTRA))
    run = subprocess.run([str(bench), "--benchmark_filter=Rubin|Sentinel2", "--benchmark_repetitions=3",
                          "--benchmark_report_aggregates_only=true", "--benchmark_format=json"],
                         capture_output=True, text=True, env=env, check=True)
    out = {}
    for b in json.loads(run.stdout)["benchmarks"]:
        if b.get("aggregate_name") == "median":
            out[b["run_name"].split("/")[0]] = (b["real_time"], b.get("label", ""))
    return out


def check_against_cli(rubin, cli):
    """radchain's m5 on a 3 × 3 × 3 corner of the airmass grid against this file's: the same physics?"""
    env = dict(os.environ, RADCHAIN_PLUGIN_PATH=str(pathlib.Path(cli).resolve().parent / "plugins"),
               RADCHAIN_DATA_PATH=str(SPECTRA))
    run = subprocess.run([str(cli), "sweep", str(ROOT / "sensors" / "rubin-lsst-r-m5.toml"),
                          "--set", "atmosphere.airmass=1:2:3", "--set", "detector.integration_time=5 s:60 s:3",
                          "--set", "atmosphere.sky_brightness=19:22:3", "--results", "target.magnitude", "--format", "csv"],
                         capture_output=True, text=True, env=env, check=True)
    rows = [line.split(",") for line in run.stdout.splitlines() if line and line[0].isdigit()]
    radchain = np.array([float(r[-1]) for r in rows]).reshape(3, 3, 3)
    numpy = rubin.airmass_grid(3)
    return float(np.abs(radchain - numpy).max())


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bench", help="radchain_bench to run straight after, printing the ratios")
    args = parser.parse_args()
    rubin = Rubin()
    print(f"Rubin r m5 at X = 1, 30 s, 21.2 mag/arcsec², 0.83\": {rubin.nominal():.4f} (numpy)")
    numpy_ms = {
        "BM_RubinM5_AirmassExposureSky_OneCore": 1e3 * median_seconds(rubin.airmass_grid),
        "BM_RubinM5_SeeingExposureSky_OneCore": 1e3 * median_seconds(rubin.seeing_grid),
    }
    for name, ms in numpy_ms.items():
        print(f"numpy {name[3:]}: {ms:.1f} ms for 10^6 points (median of 7)")
    if not args.bench:
        return
    cli = pathlib.Path(args.bench).resolve().parent / "radchain"
    print(f"radchain vs numpy on a 3x3x3 airmass corner grid: max |Δm5| = {check_against_cli(rubin, cli):.2e} mag")
    medians = radchain_medians(args.bench)
    print("grid (10^6 points unless said) | radchain, 1 core (ms) | numpy (ms) | numpy / radchain | radchain's method")
    for name, (ms, label) in medians.items():
        reference = numpy_ms.get(name)
        ratio = f"{reference / ms:.2f}" if reference else "-"
        print(f"{name[3:]} | {ms:.1f} | {reference:.1f} | {ratio} | {label}" if reference
              else f"{name[3:]} | {ms:.1f} | - | - | {label}")


if __name__ == "__main__":
    sys.exit(main())
