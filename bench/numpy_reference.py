#!/usr/bin/env python3
"""What a user would otherwise write: the MSX SBV limiting magnitude (Pan 2010, sensors/msx-sbv.toml) in
vectorised numpy, doing the same spectral work as radchain's spectral phase (E-490 AM0 table with CIE 1924 V(λ):
illuminance and total; the photon integral over the detector band) and closing with Pan's eq. (11).

    /usr/bin/python3 bench/numpy_reference.py          # Debian: apt-get install python3-numpy
    /usr/bin/python3 bench/numpy_reference.py --bench out/release/radchain_bench   # and radchain, ratios printed

Prints the limiting magnitude (radchain: 15.5565) and the median times of
  * one limiting magnitude including the spectral integration (files already loaded; with the illuminance and
    total radchain also reports, and without them), and
  * 1e6 vectorised evaluations over the aperture (closed form, no root finding), and
  * 1e6 limiting magnitudes over a 100 × 100 × 100 grid of aperture × QE × exposure (the closed form broadcast), and
    the same grid factored by hand (a logarithm per axis value, one broadcast sum: radchain's factored sweep).
"""
import pathlib
import statistics
import timeit

import numpy as np

SPECTRA = pathlib.Path(__file__).resolve().parent.parent / "spectra"
H = 6.62607015e-34  # J s (exact, SI 2019)
C = 299792458.0     # m/s (exact)


def load(name, value_factor):
    """spectra/*.csv: '#' provenance lines, a header wavelength_nm,<quantity>_<unit>, then rows. SI out."""
    rows = [line for line in (SPECTRA / name).read_text().splitlines() if line and not line.startswith("#")][1:]
    data = np.array([[float(x) for x in row.split(",")] for row in rows])
    return data[:, 0] * 1e-9, data[:, 1] * value_factor


def band_integral(lo, hi, *spectra, weight=None):
    """∫ Π s_i(λ) w(λ) dλ by the trapezoid rule on the union of the grids (radchain's band_integral)."""
    for w, _ in spectra:  # zero outside a table
        lo, hi = max(lo, w[0]), min(hi, w[-1])
    nodes = np.union1d(np.concatenate([w[(w > lo) & (w < hi)] for w, _ in spectra]), [lo, hi])
    f = np.ones_like(nodes)
    for w, v in spectra:
        f *= np.interp(nodes, w, v, left=0.0, right=0.0)
    if weight is not None:
        f *= weight(nodes)
    return np.trapz(f, nodes)


SUN = load("am0_astm_e490_00a.csv", 1e9)       # W m-2 nm-1 -> W m-2 m-1
V = load("cie_1924_photopic_V_1nm.csv", 1.0)

# sensors/msx-sbv.toml (Pan 2010 Table 1)
M_SUN, APERTURE, TRANSMITTANCE, QE, TIME = -26.73, 0.15, 0.56, 0.27, 0.625
FULL_WELL, ADC_BITS, DARK_RATE, READ_NOISE, THRESHOLD = 1e5, 12, 18.0, 6.0, 5.0
BAND = (0.3e-6, 0.9e-6)


def noise_floor():
    quantisation = FULL_WELL / (2**ADC_BITS * np.sqrt(12.0))  # Pan 2010 §3.2 as printed
    return DARK_RATE * TIME + READ_NOISE**2 + quantisation


def signal_at_threshold():
    t2 = THRESHOLD**2  # Pan 2010 eq. (11)
    return 0.5 * (t2 + np.sqrt(t2 * t2 + 4 * t2 * noise_floor()))


def limiting_magnitude(aperture=APERTURE):
    """One limiting magnitude, spectral integration included."""
    lo, hi = max(SUN[0][0], V[0][0]), min(SUN[0][-1], V[0][-1])
    illuminance = 683.0 * band_integral(lo, hi, SUN, V)  # what the sun stage reports
    total = band_integral(SUN[0][0], SUN[0][-1], SUN)
    efficacy = illuminance / total
    photons = band_integral(*BAND, SUN, weight=lambda l: l / (H * C))  # photons s-1 m-2 per unit ratio
    electrons_per_ratio = TIME * QE * TRANSMITTANCE * np.pi * aperture**2 / 4 * photons
    return M_SUN - 2.5 * np.log10(signal_at_threshold() / electrons_per_ratio), efficacy


PHOTONS = band_integral(*BAND, SUN, weight=lambda l: l / (H * C))


def vectorised(apertures):
    """The limiting magnitude at many apertures: the spectral integral done once, then closed-form arithmetic."""
    electrons_per_ratio = TIME * QE * TRANSMITTANCE * np.pi * apertures**2 / 4 * PHOTONS
    return M_SUN - 2.5 * np.log10(signal_at_threshold() / electrons_per_ratio)


def vectorised_grid(apertures, qes, times):
    """The headline grid: aperture × QE × exposure, the closed form broadcast over the three axes (the
    dark electrons grow with the exposure, so the signal at threshold does too)."""
    d, qe, t = apertures[:, None, None], qes[None, :, None], times[None, None, :]
    t2 = THRESHOLD**2
    floor = DARK_RATE * t + READ_NOISE**2 + FULL_WELL / (2**ADC_BITS * np.sqrt(12.0))
    required = 0.5 * (t2 + np.sqrt(t2 * t2 + 4 * t2 * floor))
    electrons_per_ratio = t * qe * TRANSMITTANCE * np.pi * d**2 / 4 * PHOTONS
    return M_SUN - 2.5 * np.log10(required / electrons_per_ratio)


def vectorised_grid_factored(apertures, qes, times):
    """The same grid as an expert would factor it by hand: the closed form on the exposure axis alone (the noise floor
    depends on t only), the aperture's and the QE's powers as logarithms on their own axes, then one broadcast sum:
    what radchain's factored sweep (radchain/batch/factored_grid.hpp) finds from the chain."""
    t2 = THRESHOLD**2
    floor = DARK_RATE * times + READ_NOISE**2 + FULL_WELL / (2**ADC_BITS * np.sqrt(12.0))
    required = 0.5 * (t2 + np.sqrt(t2 * t2 + 4 * t2 * floor))
    per_time = M_SUN - 2.5 * np.log10(required / (times * TRANSMITTANCE * np.pi / 4 * PHOTONS))
    outer = 5.0 * np.log10(apertures)[:, None] + 2.5 * np.log10(qes)[None, :]
    return outer[:, :, None] + per_time[None, None, :]


def limiting_magnitude_lean(aperture=APERTURE):
    """The same without the sun's illuminance and total: only the integral the magnitude needs."""
    photons = band_integral(*BAND, SUN, weight=lambda l: l / (H * C))
    electrons_per_ratio = TIME * QE * TRANSMITTANCE * np.pi * aperture**2 / 4 * photons
    return M_SUN - 2.5 * np.log10(signal_at_threshold() / electrons_per_ratio)


def median_seconds(statement, number, repeat=7):
    return statistics.median(t / number for t in timeit.repeat(statement, number=number, repeat=repeat))


def radchain_medians(bench):
    """Medians (ms) of the radchain benchmarks that the numpy lines compare with, run now (one core each)."""
    import json
    import os
    import subprocess
    build = pathlib.Path(bench).resolve().parent
    env = dict(os.environ, RADCHAIN_PLUGIN_PATH=str(build / "plugins"), RADCHAIN_DATA_PATH=str(SPECTRA))
    run = subprocess.run([str(bench), "--benchmark_filter=HandWritten|MillionSolves_Lanes_OneCore|GridSolves|"
                          "SbvLimitingMagnitudeWithSpectralPhase$|MillionForwardEvaluations_LanesEssential_OneCore",
                          "--benchmark_repetitions=5", "--benchmark_report_aggregates_only=true",
                          "--benchmark_format=json"], capture_output=True, text=True, env=env, check=True)
    scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}
    return {b["run_name"].split("/")[0]: b["real_time"] * scale[b["time_unit"]]
            for b in json.loads(run.stdout)["benchmarks"] if b.get("aggregate_name") == "median"}


if __name__ == "__main__":
    import argparse
    parser = argparse.ArgumentParser(description="numpy's closed form of the SBV limiting magnitude, timed")
    parser.add_argument("--bench", help="radchain_bench to run straight after, printing the ratios")
    arguments = parser.parse_args()
    magnitude, _ = limiting_magnitude()
    print(f"limiting magnitude (SBV, 15 cm): {magnitude:.6g}   (radchain: 15.5565)")
    one = median_seconds(limiting_magnitude, number=2000)
    print(f"one limiting magnitude with spectral integration: {one * 1e6:.1f} us (median of 7)")
    lean = median_seconds(limiting_magnitude_lean, number=2000)
    print(f"  the same, only the detector's photon integral: {lean * 1e6:.1f} us (median of 7)")
    apertures = np.linspace(0.15, 0.30, 1_000_000)
    aperture = many = median_seconds(lambda: vectorised(apertures), number=10)
    print(f"1e6 vectorised evaluations over the aperture: {many * 1e3:.1f} ms (median of 7)")
    grid = (np.linspace(0.15, 0.30, 100), np.linspace(0.2, 0.8, 100), np.linspace(0.1, 2.0, 100))
    print(f"grid point 123456 (aperture × QE × exposure): {vectorised_grid(*grid).ravel()[123456]:.10g}")
    many = median_seconds(lambda: vectorised_grid(*grid), number=10)
    print(f"1e6 limiting magnitudes over the 100 × 100 × 100 grid: {many * 1e3:.1f} ms (median of 7)")
    print(f"  factored by hand, point 123456: {vectorised_grid_factored(*grid).ravel()[123456]:.10g}")
    factored = median_seconds(lambda: vectorised_grid_factored(*grid), number=10)
    print(f"  the same factored by hand (logs per axis, one broadcast sum): {factored * 1e3:.1f} ms (median of 7)")
    print(f"numpy {np.__version__}")
    if arguments.bench:
        medians = radchain_medians(arguments.bench)
        aperture, closed, hand = aperture * 1e3, many * 1e3, factored * 1e3
        rows = [("10^6 over the aperture: lanes", "BM_MillionSolves_Lanes_OneCore", "BM_MillionLimitingMagnitudes_HandWrittenLoop", aperture),
                ("10^6 grid: lanes", "BM_MillionGridSolves_Lanes_OneCore", "BM_MillionGridLimitingMagnitudes_HandWrittenLoop", closed),
                ("10^6 grid: factored", "BM_MillionGridSolves_Factored_OneCore", "BM_MillionGridLimitingMagnitudes_HandWrittenLoop", closed)]
        print("radchain (median of 5, ms) | C++ hand loop | ratio to it | numpy closed form | numpy / radchain")
        for label, name, loop, reference in rows:
            r, h = medians[name], medians[loop]
            print(f"{label}: {r:.2f} | {h:.2f} | {r / h:.2f}x | {reference:.2f} | {reference / r:.2f}")
        r = medians["BM_MillionGridSolves_Factored_OneCore"]
        print(f"10^6 grid, factored: numpy factored by hand {hand:.2f} ms, numpy / radchain {hand / r:.2f} "
              f"(radchain writes each sweep row, 4 columns; numpy the magnitudes alone)")
        cold = medians["BM_SbvLimitingMagnitudeWithSpectralPhase"] * 1e3
        print(f"one cold solve, every spectral integral included: {cold:.2f} us (target <= 3 us); numpy's "
              f"{one * 1e6:.1f} us, numpy / radchain {one * 1e6 / cold:.0f}")
        forward = medians["BM_MillionForwardEvaluations_LanesEssential_OneCore"]
        print(f"10^6 forward evaluations: {forward:.2f} ms (target <= 10 ms)")
