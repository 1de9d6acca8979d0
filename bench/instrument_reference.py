#!/usr/bin/env python3
"""What an analyst would otherwise write for the instrument grids bench/instrument_bench.cpp sweeps with radchain,
in vectorised numpy: a survey telescope's depth (the Rubin r-band 5σ depth m5 of sensors/rubin-lsst-r-m5.toml) and
an EO camera's SNR and NIIRS (Sentinel-2A MSI B4, sensors/sentinel-2a-msi-b4.toml).

    /usr/bin/python3 bench/instrument_reference.py                                  # numpy alone
    /usr/bin/python3 bench/instrument_reference.py --check out/release/radchain     # + the corner checks vs radchain
    /usr/bin/python3 bench/instrument_reference.py --bench out/release/radchain_bench  # checks, radchain, ratios

Rubin r m5. The physics, written from the sources the sensor file cites (not from radchain's code):
  * signal: a flat-f_ν AB source, f_ν = 10^(-0.4 (m + 48.6)) erg s-1 cm-2 Hz-1 (Oke & Gunn 1983), through the
    hardware throughput S(λ) and the atmosphere τ(λ)^X (Bouguer-Lambert-Beer from the X = 1 table), counted as
    photons: C(X) = A ∫ f_ν S τ^X / (h λ) dλ electrons per second at m = 0 (trapezoid rule on the tables' grid);
  * sky: m_sky AB mag/arcsec² at the pupil (not extinguished), over a pixel of (p/f)² sr;
  * PSF: a Gaussian of FWHM θ X^0.6 (Kolmogorov seeing, Roddier 1981) sampled by the pixels, centred on one:
    n_eff = 1/Σ f_ij² (King 1983; SMTN-002 uses 2.266 FWHM²/p², its large-PSF limit);
  * noise: σ² = S + n_eff (sky t + dark t + read² + 1/(12 K²)) (EMVA 1288 eqs. 5, 6 with quantisation), and
    SNR = 5 solved in closed form: S = (T² + √(T⁴ + 4 T² B))/2, m5 = −2.5 lg(S / (C t)).
Grids: airmass 1..2 × exposure 5..60 s × sky 19..22 mag/arcsec² and seeing 0.5..1.5" × exposure × sky, 100 each.

Sentinel-2A MSI B4. Which physics: the file's plugins (earth_orbit, sun, none, reflectance_ground, telescope,
emva1288, giqe); the formulas from the sources they and the file cite:
  * geometry: a circular orbit at h = 786 km over a sphere of R = 6371.0 km (IUGG mean radius, rounded; the
    platform's default), the line of sight rolled φ across track: slant range ρ = (R+h) cos φ − √(R² − (R+h)² sin² φ),
    view zenith at the ground sin η = (R+h) sin φ / R (Wertz & Larson, SMAD 3rd ed. (1999) §5.2, eqs. 5-17..5-27);
    along-track GSD ρ p/f' (neighbouring lines lie perpendicular to the look plane; SMAD §5.2);
  * integration time: the file gives none, so the pushbroom's line time t = GSD_along / v (square samples,
    Schowengerdt, Remote Sensing 3rd ed. (2007) §3.3), v = √(GM/(R+h)) R/(R+h) the sub-satellite point's speed
    over a non-rotating Earth (WGS 84 GM = 3.986004418e14 m³ s⁻²) — at the look's along-track GSD, as
    docs/eo-imagers.md and docs/validation.md state it (the ground under a rolled look moves at v cos λ, λ = η − φ
    the Earth central angle: one line per ground line there would be 1/cos λ longer, +1.03e-3 at 20°; not done
    here, to check the same convention);
  * signal: a Lambertian top-of-atmosphere reflectance ρ under the Sun at zenith θ_s, L_λ = ρ E_λ cos θ_s / π
    (Schott, The Image Chain Approach 2nd ed. (2007) §4.1; no atmosphere), E_λ the ASTM E-490-00a AM0 table at 1 AU;
    focal-plane irradiance E'_λ = π L_λ τ / (4 N²), N = f'/D, unobscured (Kolobrodov 1996 eq. 5); electrons of one
    pixel S = η t p² ∫ E'_λ λ/(hc) dλ over the 650-680 nm box band (EMVA 1288 R4.0 eq. 1), by the trapezoid rule
    on the E-490 nodes with the band edges interpolated in (the table's own piecewise-linear spectrum);
  * noise: σ² = S + σ_d² + 1/(12 K²) (EMVA 1288 eqs. 5, 6: shot, read, quantisation; the file gives no dark
    current, DSNU or PRNU), detector.snr = S/σ;
  * NIIRS: GIQE-5 (NGA, General Image Quality Equation v5.0 (2015); pyBSM's metrics.functional.giqe5)
      NIIRS = 9.57 − 3.32 lg GSD_W + 3.32 (1 − exp(−1.9/SNR)) lg RER − 2 (lg RER)⁴ − 1.8/SNR,
    GSD_W = GSD_NP / sin(elevation)^¼ in inches (NGA eq. 5), GSD_NP = ρ p/f', elevation = 90° − η at the target;
    RER = (RER_cs RER_as²)^⅓ (NGA eq. 7); SNR = the criterion's own 142 (the B4 requirement at L_ref, as the file
    gives it; not detector.snr). GIQE-5 has no overshoot (H) or noise-gain term (GIQE-4's, Leachtenauer et al.
    1997): H is not computed;
  * MTF budget (across = along track here: the integration is the line time, so no smear, and no TDI):
    diffraction of the unobscured pupil at the criterion's 665 nm, (2/π)(acos s − s √(1 − s²)), s = λ N ν
    (Goodman, Fourier Optics 3rd ed. (2005) ch. 6), times the pixel aperture |sinc(p ν)| (Holst 2008 ch. 10); the
    modulus, as IBSM eq. 3-57 and pyBSM (giqe_edge_terms on np.abs(system OTF)) take it (the edge's own transform
    is the signed OTF: rer(..., signed=True), RER +0.012 to +0.050 over these apertures);
  * edge: ER(x) = ½ + (1/π) ∫₀^ν_c MTF(ν) sin(2πνx)/ν dν (Leachtenauer 1997 §2; Fiete, Modeling the Imaging Chain
    of Digital Cameras (2010) §12.3), x in samples, so RER = ER(½) − ER(−½) = (2/π) ∫₀^c MTF(u) sin(πu)/u du with
    u in cycles/sample and c = p/(λN) the cut-off; composite Simpson on 1000 panels (1000 → 4000 panels moves RER
    by < 1e-8: the check prints it).
The RER depends on the aperture alone (N = f'/D), GSD_W on the roll alone, the SNR is a product of a factor per
axis: so, as a numpy user would, the edge response is integrated once per distinct aperture (100 × 1001 MTF nodes)
and broadcast over the roll, and S is one outer product over roll × sun × reflectance.
Grids (bench/instrument_bench.cpp, axes in its order, the outer first): detector.snr over roll 0..20° × solar zenith
20..70° × reflectance 0.02..0.6, 100 each (10⁶); NIIRS over aperture 10..20 cm × roll 0..20°, 100 each (10⁴).
"""
import argparse
import json
import math
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import timeit
import tomllib

import numpy as np
from scipy.special import erf

ROOT = pathlib.Path(__file__).resolve().parent.parent
SPECTRA = ROOT / "spectra"
H = 6.62607015e-34           # J s (exact, SI 2019)
C = 299792458.0              # m/s (exact)
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


class Sentinel2:
    """Sentinel-2A MSI B4: detector.snr and the GIQE-5 NIIRS (physics and sources: the module's docstring)."""
    EARTH_RADIUS = 6371.0e3       # m: IUGG mean radius, rounded (earth_orbit's default; the file gives none)
    EARTH_GM = 3.986004418e14     # m³ s⁻²: WGS 84
    # GIQE-5 (NGA 2015): A0..A5
    A0, A1, A2, A3, A4, A5 = 9.57, -3.32, 3.32, -1.9, -2.0, -1.8
    INCH = 0.0254                 # m, exact
    PANELS = 1000                 # Simpson panels of the edge integral, to the cut-off

    def __init__(self):
        sensor = tomllib.loads((ROOT / "sensors" / "sentinel-2a-msi-b4.toml").read_text())
        optics, detector, iq = sensor["optics"], sensor["detector"], sensor["criteria"]["iq"]
        assert sensor["source"] == {"plugin": "sun"}, "the sun's defaults: the E-490 table at 1 AU"
        assert sensor["atmosphere"]["plugin"] == "none" and sensor["optics"].get("obscuration", 0) == 0
        assert "integration_time" not in detector, "the line time is the integration time"
        self.altitude = quantity(sensor["platform"]["altitude"], "km", 1e3)
        self.aperture = quantity(optics["aperture"], "mm", 1e-3)
        self.focal = quantity(optics["focal_length"], "mm", 1e-3)
        self.tau = float(optics["transmittance"])
        self.pitch = quantity(detector["pixel_pitch"], "um", 1e-6)
        self.qe = float(detector["qe"])
        self.read = quantity(detector["read_noise"], "e-")
        self.gain = quantity(detector["gain"], "DN/e-")
        self.wavelength = quantity(iq["wavelength"], "nm", 1e-9)
        self.giqe_snr = float(iq["snr"])
        self.reflectance = float(sensor["target"]["reflectance"])
        self.solar_zenith = math.radians(quantity(sensor["target"]["solar_zenith"], "deg"))
        lo, hi = quantity(detector["band_min"], "um", 1e-6), quantity(detector["band_max"], "um", 1e-6)
        # ASTM E-490-00a at 1 AU, W m-2 nm-1 in the table: the band's photon radiance per unit reflectance at cos θ_s = 1,
        # ∫ E_λ/π λ/(hc) dλ over [lo, hi], trapezoid on the table's nodes with the band edges interpolated in.
        name = "am0_astm_e490_00a.csv"
        header = [line for line in (SPECTRA / name).read_text().splitlines() if line and not line.startswith("#")][0]
        assert header.endswith("W_m-2_nm-1"), header
        wl, irradiance = load(name)
        nodes = np.concatenate([[lo], wl[(wl > lo) & (wl < hi)], [hi]])
        values = np.interp(nodes, wl, irradiance * 1e9) / math.pi * nodes / (H * C)
        self.photon_radiance = float(np.sum(0.5 * (values[1:] + values[:-1]) * np.diff(nodes)))
        self.quant_floor = self.read**2 + 1.0 / (12 * self.gain**2)
        r, s = self.EARTH_RADIUS, self.EARTH_RADIUS + self.altitude
        self.ground_speed = math.sqrt(self.EARTH_GM / s) * r / s

    def slant_range(self, roll):
        """ρ(θ) of a look θ off nadir (SMAD §5.2), as (s² − R²)/(s cos θ + √(R² − s² sin² θ)) for precision at nadir."""
        r, s = self.EARTH_RADIUS, self.EARTH_RADIUS + self.altitude
        return (s * s - r * r) / (s * np.cos(roll) + np.sqrt(r * r - (s * np.sin(roll)) ** 2))

    def view_zenith(self, roll):
        return np.arcsin((self.EARTH_RADIUS + self.altitude) * np.sin(roll) / self.EARTH_RADIUS)

    def electrons_per_reflectance(self, roll):
        """S / (ρ cos θ_s) per roll: η t p² π τ/(4N²) ∫ E/π λ/(hc) dλ with t = ρ_slant (p/f') / v, the line time."""
        n = self.focal / self.aperture
        line_time = self.slant_range(np.asarray(roll)) * (self.pitch / self.focal) / self.ground_speed
        return self.qe * line_time * self.pitch**2 * math.pi * self.tau / (4 * n * n) * self.photon_radiance

    def snr(self, signal):
        return signal / np.sqrt(signal + self.quant_floor)

    def snr_grid(self, n=100):
        """detector.snr over roll × solar zenith × reflectance (bench order), n each."""
        roll, sun, rho = np.radians(np.linspace(0, 20, n)), np.radians(np.linspace(20, 70, n)), np.linspace(0.02, 0.6, n)
        signal = self.electrons_per_reflectance(roll)[:, None, None] * np.cos(sun)[None, :, None] * rho[None, None, :]
        return self.snr(signal)

    def rer(self, aperture, panels=PANELS, signed=False):
        """RER = (2/π) ∫₀^c MTF(u) sin(πu)/u du, one per aperture, vectorised: Simpson on `panels` panels of [0, c].
        signed=True integrates the OTF (the pixel's signed sinc) instead of the MTF |OTF|, to compare conventions."""
        cutoff = (self.pitch * np.asarray(aperture, dtype=float) / (self.wavelength * self.focal))[:, None]  # p/(λN)
        s = np.linspace(0.0, 1.0, panels + 1)[None, :]       # ν/ν_c
        u = cutoff * s                                         # cycles per sample
        diffraction = 2 / math.pi * (np.arccos(s) - s * np.sqrt(1 - s * s))
        safe = np.where(u == 0, 1.0, u)
        sin_over_u = np.where(u == 0, math.pi, np.sin(math.pi * u) / safe)  # → π at u = 0
        pixel = sin_over_u / math.pi                                        # sinc(u), 1 at u = 0
        integrand = diffraction * (pixel if signed else np.abs(pixel)) * sin_over_u
        weights = np.ones(panels + 1)
        weights[1:-1:2], weights[2:-1:2] = 4, 2
        return (integrand @ weights) * cutoff[:, 0] / (3 * panels) * 2 / math.pi

    def weighted_gsd(self, roll):
        """GIQE-5's GSD_W = ρ p/f' / sin(90° − η)^¼ (NGA eq. 5), metres."""
        roll = np.asarray(roll)
        return self.slant_range(roll) * self.pitch / self.focal / np.sin(math.pi / 2 - self.view_zenith(roll)) ** 0.25

    def niirs(self, gsd_w, rer, snr):
        lg_rer = np.log10(rer)
        return (self.A0 + self.A1 * np.log10(gsd_w / self.INCH) + self.A2 * (1 - np.exp(self.A3 / snr)) * lg_rer
                + self.A4 * lg_rer**4 + self.A5 / snr)

    def niirs_grid(self, n=100, panels=PANELS):
        """NIIRS over aperture × roll (bench order), n each: the RER once per aperture, GSD_W once per roll."""
        aperture, roll = np.linspace(0.10, 0.20, n), np.radians(np.linspace(0, 20, n))
        rer = self.rer(aperture, panels)  # across = along track: the weighted RER (RER_cs RER_as²)^⅓ is RER itself
        return self.niirs(self.weighted_gsd(roll)[None, :], rer[:, None], self.giqe_snr)

    def nominal(self):
        """(detector.snr, NIIRS) at the file's values: nadir, ρ = 0.3 under a 30° Sun, D = 150 mm."""
        signal = self.electrons_per_reflectance(0.0) * math.cos(self.solar_zenith) * self.reflectance
        niirs = self.niirs(self.weighted_gsd(0.0), self.rer([self.aperture])[0], self.giqe_snr)
        return float(self.snr(signal)), float(niirs)


def median_seconds(statement, number=1, repeat=7):
    return statistics.median(timeit.repeat(statement, number=number, repeat=repeat)) / number


def radchain_env(binary):
    return dict(os.environ, RADCHAIN_PLUGIN_PATH=str(pathlib.Path(binary).resolve().parent / "plugins"),
                RADCHAIN_DATA_PATH=str(SPECTRA))


def radchain_medians(bench):
    """Runs the instrument benchmarks once each (their grids take seconds); (ms, label, points) per benchmark."""
    run = subprocess.run([str(bench), "--benchmark_filter=Rubin|Sentinel2", "--benchmark_repetitions=3",
                          "--benchmark_report_aggregates_only=true", "--benchmark_format=json"],
                         capture_output=True, text=True, env=radchain_env(bench), check=True)
    out = {}
    for b in json.loads(run.stdout)["benchmarks"]:
        if b.get("aggregate_name") == "median":
            out[b["run_name"].split("/")[0]] = (b["real_time"], b.get("label", ""), b.get("points"))
    return out


def cli_sweep(cli, sensor, axes, results):
    """`radchain sweep` of a small grid on one core, as .npy (full precision): {result: array shaped by the axes, the
    first outermost}."""
    with tempfile.TemporaryDirectory() as scratch:
        grid = pathlib.Path(scratch) / "grid.npy"
        command = [str(cli), "sweep", str(ROOT / "sensors" / sensor), "--results", ",".join(results),
                   "--out", str(grid), "--threads", "1"]
        for key, steps in axes:
            command += ["--set", f"{key}={steps}"]
        subprocess.run(command, capture_output=True, text=True, env=radchain_env(cli), check=True)
        table = np.load(grid)
    shape = tuple(int(steps.rsplit(":", 1)[1]) for _, steps in axes)
    return {name: table[name].reshape(shape) for name in results}


def check_against_cli(rubin, cli):
    """radchain's m5 on a 3 × 3 × 3 corner of the airmass grid against this file's: the same physics?"""
    radchain = cli_sweep(cli, "rubin-lsst-r-m5.toml",
                         [("atmosphere.airmass", "1:2:3"), ("detector.integration_time", "5 s:60 s:3"),
                          ("atmosphere.sky_brightness", "19:22:3")], ["target.magnitude"])["target.magnitude"]
    return float(np.abs(radchain - rubin.airmass_grid(3)).max())


def check_sentinel2_against_cli(sentinel, cli):
    """radchain's detector.snr on a 3 × 3 × 3 corner grid and NIIRS (and RER) on a 3 × 3 one against this file's:
    (max relative ΔSNR, max |ΔNIIRS|, max |ΔRER|). The corners are the bench grids' ends and middles."""
    snr = cli_sweep(cli, "sentinel-2a-msi-b4.toml",
                    [("platform.roll", "0 deg:20 deg:3"), ("target.solar_zenith", "20 deg:70 deg:3"),
                     ("target.reflectance", "0.02:0.6:3")], ["detector.snr"])["detector.snr"]
    iq = cli_sweep(cli, "sentinel-2a-msi-b4.toml", [("optics.aperture", "10 cm:20 cm:3"), ("platform.roll", "0 deg:20 deg:3")],
                   ["criteria.iq.niirs", "criteria.iq.rer"])
    rer = sentinel.rer(np.linspace(0.10, 0.20, 3))
    return (float(np.abs(snr / sentinel.snr_grid(3) - 1).max()),
            float(np.abs(iq["criteria.iq.niirs"] - sentinel.niirs_grid(3)).max()),
            float(np.abs(iq["criteria.iq.rer"] - rer[:, None]).max()))


def run_checks(rubin, sentinel, cli):
    print(f"radchain vs numpy on a 3x3x3 airmass corner grid: max |Δm5| = {check_against_cli(rubin, cli):.2e} mag")
    snr, niirs, rer = check_sentinel2_against_cli(sentinel, cli)
    print(f"radchain vs numpy, Sentinel-2A B4 detector.snr on a 3x3x3 roll x sun x reflectance corner grid: "
          f"max |ΔSNR|/SNR = {snr:.2e}")
    print(f"radchain vs numpy, Sentinel-2A B4 NIIRS on a 3x3 aperture x roll corner grid: max |ΔNIIRS| = {niirs:.2e} "
          f"(max |ΔRER| = {rer:.2e})")
    apertures = np.linspace(0.10, 0.20, 100)
    converged = float(np.abs(sentinel.rer(apertures, 4 * Sentinel2.PANELS) - sentinel.rer(apertures)).max())
    print(f"numpy's edge integral, {Sentinel2.PANELS} -> {4 * Sentinel2.PANELS} Simpson panels: max |ΔRER| = "
          f"{converged:.1e} over the 100 apertures")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bench", help="radchain_bench to run straight after, printing the ratios (and the corner "
                                        "checks against the radchain beside it)")
    parser.add_argument("--check", help="radchain executable: the corner checks only, no benchmarks")
    parser.add_argument("--repeat", type=int, default=7, help="numpy timings: median of this many runs (default 7)")
    args = parser.parse_args()
    rubin, sentinel = Rubin(), Sentinel2()
    print(f"Rubin r m5 at X = 1, 30 s, 21.2 mag/arcsec², 0.83\": {rubin.nominal():.4f} (numpy)")
    snr, niirs = sentinel.nominal()
    print(f"Sentinel-2A B4 at nadir, reflectance 0.3, 30° Sun, D = 150 mm: detector.snr {snr:.4f}, NIIRS {niirs:.4f} (numpy)")
    numpy_ms = {
        "BM_RubinM5_AirmassExposureSky_OneCore": 1e3 * median_seconds(rubin.airmass_grid, repeat=args.repeat),
        "BM_RubinM5_SeeingExposureSky_OneCore": 1e3 * median_seconds(rubin.seeing_grid, repeat=args.repeat),
        "BM_Sentinel2Snr_ReflectanceSunRoll_OneCore": 1e3 * median_seconds(sentinel.snr_grid, repeat=args.repeat),
        "BM_Sentinel2Niirs_ApertureRoll_OneCore": 1e3 * median_seconds(sentinel.niirs_grid, repeat=args.repeat),
    }
    points = {"BM_Sentinel2Niirs_ApertureRoll_OneCore": "10^4"}
    for name, ms in numpy_ms.items():
        print(f"numpy {name[3:]}: {ms:.1f} ms for {points.get(name, '10^6')} points (median of {args.repeat})")
    if args.check:
        run_checks(rubin, sentinel, args.check)
    if not args.bench:
        return
    if not args.check:
        run_checks(rubin, sentinel, pathlib.Path(args.bench).resolve().parent / "radchain")
    medians = radchain_medians(args.bench)
    print("grid (points) | radchain, 1 core (ms) | numpy (ms) | numpy / radchain | radchain's method")
    for name, (ms, label, count) in medians.items():
        size = f"{count:.0f}" if count else "?"
        reference = numpy_ms.get(name)
        print(f"{name[3:]} ({size}) | {ms:.1f} | {reference:.1f} | {reference / ms:.2f} | {label}" if reference
              else f"{name[3:]} ({size}) | {ms:.1f} | - | - | {label}")


if __name__ == "__main__":
    sys.exit(main())
