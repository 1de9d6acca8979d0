#!/usr/bin/env python3
"""A catalogue of 1,000 sensor files, radchain against what a Python user would otherwise write —
a loop of tomllib + numpy over the same files, measured in the same run.

    /usr/bin/python3 bench/catalogue_python.py [path/to/radchain]     # default out/release/radchain

The files are 1,000 copies of sensors/msx-sbv.toml with apertures from 10 to 40 cm (so that no two files are
alike). Per file the Python loop parses the TOML (tomllib), converts the quantities it needs to SI, does the
spectral work radchain's spectral phase does for it (E-490 × V(λ) illuminance and total; the photon integral over
the detector band, spectra loaded once and cached as radchain caches them), solves the limiting magnitude in
closed form (Pan 2010 eq. 11: numpy_reference.py) and checks it against the file's [expected] value: the numbers
radchain's catalogue prints for the file. radchain runs `radchain catalogue DIR --format csv --out FILE` (all
cores, process start-up and plugin loading included). Prints the medians of 5 runs and the ratio.
"""
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time
import tomllib

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import numpy_reference as ref  # noqa: E402  (the SBV chain in numpy: spectra, band integrals, eq. 11)

ROOT = pathlib.Path(__file__).resolve().parent.parent
UNITS = {"cm": 1e-2, "mm": 1e-3, "m": 1.0, "um": 1e-6, "nm": 1e-9, "s": 1.0, "ms": 1e-3, "e-": 1.0, "e-/s": 1.0}


def si(value):
    """'15 cm' -> 0.15; a bare number stays as it is."""
    if isinstance(value, (int, float)):
        return float(value)
    number, unit = value.split(None, 1)
    return float(number) * UNITS[unit]


def evaluate(path):
    """One file: what `radchain catalogue` reports for it (the limiting magnitude and its check)."""
    with open(path, "rb") as f:
        s = tomllib.load(f)
    optics, detector = s["optics"], s["detector"]
    aperture, transmittance = si(optics["aperture"]), si(optics["transmittance"])
    qe, time_s = si(detector["qe"]), si(detector["integration_time"])
    band = (si(detector["band_min"]), si(detector["band_max"]))
    lo, hi = max(ref.SUN[0][0], ref.V[0][0]), min(ref.SUN[0][-1], ref.V[0][-1])
    illuminance = 683.0 * ref.band_integral(lo, hi, ref.SUN, ref.V)
    total = ref.band_integral(ref.SUN[0][0], ref.SUN[0][-1], ref.SUN)
    photons = ref.band_integral(*band, ref.SUN, weight=lambda l: l / (ref.H * ref.C))
    full_well, bits = si(detector["full_well"]), detector["adc_bits"]
    floor = si(detector["dark_current"]) * time_s + si(detector["read_noise"]) ** 2 + full_well / (2**bits * np.sqrt(12.0))
    t2 = float(s["criteria"]["detection"]["threshold"]) ** 2
    signal = 0.5 * (t2 + np.sqrt(t2 * t2 + 4 * t2 * floor))
    electrons_per_ratio = time_s * qe * transmittance * np.pi * aperture**2 / 4 * photons
    magnitude = s["source"]["visual_magnitude"] - 2.5 * np.log10(signal / electrons_per_ratio)
    expected = s["expected"]["target.magnitude"]
    return magnitude, illuminance / total, abs(magnitude - expected["value"]) <= expected["tolerance"]


def main():
    radchain = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ROOT / "out/release/radchain")
    text = (ROOT / "sensors/msx-sbv.toml").read_text()
    with tempfile.TemporaryDirectory() as folder:
        folder = pathlib.Path(folder)
        for i, d in enumerate(np.linspace(10, 40, 1000)):
            (folder / f"sensor-{i:04d}.toml").write_text(text.replace('aperture = "15 cm"', f'aperture = "{d:.6f} cm"'))
        files = sorted(folder.glob("*.toml"))
        out = folder / "catalogue.csv"
        python_s, radchain_s = [], []
        for _ in range(5):  # alternating, so that the machine's load hits both alike
            start = time.perf_counter()
            rows = [evaluate(f) for f in files]
            python_s.append(time.perf_counter() - start)
            start = time.perf_counter()
            subprocess.run([str(radchain), "catalogue", str(folder), "--format", "csv", "--out", str(out)], check=False,
                           stdout=subprocess.DEVNULL)
            radchain_s.append(time.perf_counter() - start)
        # The same numbers: radchain's computed magnitudes (printed to 6 digits) against the loop's.
        computed = [float(line.split(",")[2]) for line in out.read_text().splitlines()[1:] if ",target.magnitude," in line]
        worst = max(abs(a - b[0]) for a, b in zip(computed, rows))
        print(f"{len(files)} files; largest |radchain - python| limiting magnitude: {worst:.2e}")
        p, r = statistics.median(python_s), statistics.median(radchain_s)
        print(f"python tomllib + numpy loop: {p * 1e3:.0f} ms (median of 5)")
        print(f"radchain catalogue:          {r * 1e3:.0f} ms (median of 5, process included)")
        print(f"ratio python / radchain:     {p / r:.2f}")


if __name__ == "__main__":
    main()
