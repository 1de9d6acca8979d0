"""Metamorphic invariants over random draws: transformations of a sensor file that must not change its numbers,
or must change them by a known law. Every draw starts from a bundled file in sensors/ and is seeded
(numpy.random.default_rng), so a failure reproduces; RADCHAIN_DIFFERENTIAL_DRAWS raises the number of draws per
invariant (default 50). A failure prints a small sensor file (TOML text) that shows it and both numbers.

  1. the band that normalises an AB flat-f_nu (or ST flat-f_lambda) point source does not change its electrons
     (relative 1e-6) nor the solved m5 (1e-6 mag);
  2. the same inputs written in other units (lengths m / cm / mm / um, wavelengths nm / um, times s / ms) give
     identical bits in every result;
  3. the sections (and the keys inside them) of a file in another order give identical bits in every result;
  4. the limiting magnitude moves by 2.5 lg k when the exposure is multiplied by k and the detection is
     signal-limited, by 1.25 lg k when it is sky-limited (1e-9 mag);
  5. b x b binning (emva1288) equals the sum of the b^2 native pixels: a point image in an n x n window of b x b
     binned pixels is the n b x n b window of native pixels, and an extended scene's binned pixel carries b^2 times
     the signal and b times the noise (relative 1e-12);
  6. `radchain run --format json`, `radchain sweep` with one point (.npy), `radchain catalogue --format json` and
     Python's radchain.load(...).run() give the same number, to the last bit, for every result requested (the .npy
     holds the report's units, as Python's Value.value; the catalogue prints 6 significant digits, so it is
     checked both to those digits and, literally, to the last bit); and numpy.load reads the .npy.

Run by hand (python/tests/conftest.py):
    PYTHONPATH=<build>/python RADCHAIN_CLI=<build>/radchain RADCHAIN_PLUGIN_PATH=<build>/plugins \
    RADCHAIN_DATA_PATH=spectra /usr/bin/python3 -m pytest -q python/tests/test_metamorphic.py
"""
import json
import math
import os
import struct
import subprocess
import tomllib
import warnings
from decimal import Decimal
from pathlib import Path

import numpy as np
import pytest

import radchain

SOURCE_DIR = Path(os.environ.get("RADCHAIN_SOURCE_DIR", Path(__file__).resolve().parents[2]))
SENSORS = SOURCE_DIR / "sensors"
SPECTRA = SOURCE_DIR / "spectra"
DRAWS = int(os.environ.get("RADCHAIN_DIFFERENTIAL_DRAWS", "50"))
assert DRAWS >= 1, "RADCHAIN_DIFFERENTIAL_DRAWS must be a positive integer"


# --------------------------------------------------------------------------------------------------------------
# A TOML writer for sensor files (tomllib reads them; the standard library has no writer)
# --------------------------------------------------------------------------------------------------------------

def _key(k: str) -> str:
    return k if k and all(c.isalnum() or c in "_-" for c in k) and k.isascii() else json.dumps(k, ensure_ascii=False)


def _value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)  # shortest text that reads back as the same double
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)  # JSON's escapes are TOML basic-string escapes
    if isinstance(v, list):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{_key(k)} = {_value(x)}" for k, x in v.items()) + " }"
    raise TypeError(f"no TOML for {v!r}")


# Tables whose dict values are sub-tables ([criteria.detection]); a dict anywhere else is an inline table
# ([expected] "target.magnitude" = { value = ..., ... }).
_PARENT_TABLES = {"criteria"}


def blocks(doc: dict) -> list:
    """The document as (header, {key: value}) blocks in file order; [[arrays]] one block per entry."""
    out = []
    for name, value in doc.items():
        if isinstance(value, list) and value and all(isinstance(x, dict) for x in value):
            out += [(f"[[{_key(name)}]]", entry) for entry in value]
        elif isinstance(value, dict) and name in _PARENT_TABLES:
            plain = {k: v for k, v in value.items() if not isinstance(v, dict)}
            if plain:
                out.append((f"[{_key(name)}]", plain))
            out += [(f"[{_key(name)}.{_key(k)}]", v) for k, v in value.items() if isinstance(v, dict)]
        elif isinstance(value, dict):
            out.append((f"[{_key(name)}]", value))
        else:
            raise AssertionError(f"top-level key {name} outside a table: not a sensor file layout")
    return out


def dump_blocks(bs: list) -> str:
    lines = []
    for header, table in bs:
        lines.append(header)
        lines += [f"{_key(k)} = {_value(v)}" for k, v in table.items()]
        lines.append("")
    return "\n".join(lines)


def dumps(doc: dict) -> str:
    return dump_blocks(blocks(doc))


def read_doc(name: str) -> dict:
    with open(SENSORS / name, "rb") as f:
        return tomllib.load(f)


def name_for(sensor: str) -> str:
    """The `name` of a text loaded with radchain.loads: relative tables resolve beside the bundled file."""
    return str(SENSORS / sensor)


# --------------------------------------------------------------------------------------------------------------
# Comparing numbers
# --------------------------------------------------------------------------------------------------------------

def bits(x: float) -> bytes:
    return struct.pack("<d", x)


def same_bits(a: float, b: float) -> bool:
    return (math.isnan(a) and math.isnan(b)) or bits(a) == bits(b)


def ulps(a: float, b: float) -> int:
    ia, ib = (np.array([a, b], dtype=np.float64).view(np.int64)).tolist()
    if (ia < 0) != (ib < 0):
        return abs(ia) + abs(ib)
    return abs(ia - ib)


def rel(a: float, b: float) -> float:
    return abs(a - b) / max(abs(a), abs(b), 1e-300)


def numbers_of(result) -> dict:
    """Every number a Result carries, by a stable name: results (value_si), solves, checks, table cells. Names do
    not depend on the order of the file's sections (results and checks by name; solves and tables in their own
    order, which a reordering keeps)."""
    out = {}
    doc = json.loads(result.json())

    def walk(prefix, node):
        if isinstance(node, dict):
            for k, v in node.items():
                if k in ("file", "equation", "note", "source", "message", "stage", "unit", "si_unit", "sensor"):
                    continue
                walk(f"{prefix}.{k}" if prefix else k, v)
        elif isinstance(node, list):
            def label(i, x):  # results by name, solves by unknown, checks by result, criteria by section
                for field in ("name", "unknown", "result", "section"):
                    if isinstance(x, dict) and isinstance(x.get(field), str):
                        return x[field]
                return str(i)
            labels = [label(i, x) for i, x in enumerate(node)]
            if len(set(labels)) < len(labels):
                labels = [str(i) for i in range(len(node))]
            for name, x in zip(labels, node):
                walk(f"{prefix}[{name}]", x)
        elif isinstance(node, bool) or node is None or isinstance(node, str):
            return
        elif isinstance(node, (int, float)):
            out[prefix] = float(node)

    walk("", doc)
    # result.json() prints the shortest text that reads back as the same double; take value_si from the frame too
    df = result.frame()
    for name, value in zip(df["name"], df["value_si"]):
        out[f"frame[{name}]"] = float(value)
    return out


def differing(a: dict, b: dict) -> list:
    rows = []
    for k in sorted(set(a) | set(b)):
        if k not in a or k not in b:
            rows.append((k, a.get(k), b.get(k)))
        elif not same_bits(a[k], b[k]):
            rows.append((k, a[k], b[k]))
    return rows


def describe_rows(rows, limit=8) -> str:
    text = []
    for k, x, y in rows[:limit]:
        if x is None or y is None:
            text.append(f"  {k}: {x!r} vs {y!r} (only in one)")
        else:
            text.append(f"  {k}: {x!r} vs {y!r} ({ulps(x, y)} ulp)")
    if len(rows) > limit:
        text.append(f"  ... and {len(rows) - limit} more")
    return "\n".join(text)


def quiet_run(session):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return session.run()


def quiet_evaluate(session):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return session.evaluate()


def quiet_set(session, key, value):
    with warnings.catch_warnings():  # "a [[solve]] overwrites ...": the forward evaluation uses the value set
        warnings.simplefilter("ignore")
        session.set(key, value, si=True)


def loads(text: str, sensor: str):
    return radchain.loads(text, name=name_for(sensor))


# --------------------------------------------------------------------------------------------------------------
# 1. The normalising band does not change a flat source
# --------------------------------------------------------------------------------------------------------------

# Bandpass tables (dimensionless throughput or response) in spectra/, far UV to near IR.
BANDS = [
    "johnson_cousins_B_bessell1990.csv", "johnson_cousins_V_bessell1990.csv", "johnson_cousins_R_bessell1990.csv",
    "johnson_cousins_I_bessell1990.csv", "johnson_V_mann_vonbraun_2015.csv", "johnson_V_stsci_cdbs_johnson_v_004.csv",
    "lsst_hardware_u_throughputs1.9.csv", "lsst_hardware_g_throughputs1.9.csv", "lsst_hardware_r_throughputs1.9.csv",
    "lsst_hardware_i_throughputs1.9.csv", "lsst_hardware_z_throughputs1.9.csv", "lsst_hardware_y_throughputs1.9.csv",
    "lsst_filter_r_throughputs1.9.csv", "sdss_g_doi2010.csv", "sdss_r_doi2010.csv", "sdss_i_doi2010.csv",
    "gaia_dr3_G.csv", "gaia_dr3_BP.csv", "gaia_dr3_RP.csv", "tess_response_v2.0.csv",
    "swift_uvot_b_throughput.csv", "swift_uvot_v_throughput.csv", "swift_uvot_u_throughput.csv",
    "galex_nuv_throughput.csv", "roman_wfi_sca01_f062_throughput.csv", "roman_wfi_sca01_f158_throughput.csv",
]
# Detector set-ups the flat source is seen through: the six Rubin files (emva1288, site atmosphere, sky, PSF
# photometry) and the MSX SBV's ccd_frame with its target replaced by a point_source.
FLAT_SETUPS = [f"rubin-lsst-{b}-m5.toml" for b in "ugrizy"] + ["msx-sbv.toml"]


def flat_source_doc(sensor: str, system: str, band: str) -> dict:
    doc = read_doc(sensor)
    doc["target"] = {"plugin": "point_source", "system": system, "band": band,
                     "sed_shape": "flat_f_nu" if system == "ab" else "flat_f_lambda", "magnitude": 20}
    doc.pop("expected", None)
    doc.pop("table", None)
    doc.pop("uncertainty", None)
    for solve in doc.get("solve", []):
        if solve.get("unknown") == "target.magnitude":
            solve["bracket"] = [-10, 40]
    return doc


@pytest.mark.parametrize("system", ["ab", "st"])
def test_normalising_band_does_not_change_a_flat_source(system):
    """A source flat in f_nu (AB) or f_lambda (ST) of magnitude m has the same f_nu (f_lambda) everywhere: the band
    its magnitude is quoted in cannot change what the detector counts. Catches an SED built only over the
    normalising band's table (Johnson B vs the LSST r curve moved the Rubin r m5 from 24.50 to 21.80)."""
    rng = np.random.default_rng(20261101 if system == "ab" else 20261102)
    failures = []
    for draw in range(DRAWS):
        sensor = FLAT_SETUPS[rng.integers(len(FLAT_SETUPS))]
        band_a, band_b = (BANDS[i] for i in rng.choice(len(BANDS), size=2, replace=False))
        magnitude = float(np.round(rng.uniform(14.0, 26.0), 3))
        values = {}
        for band in (band_a, band_b):
            text = dumps(flat_source_doc(sensor, system, band))
            s = loads(text, sensor)
            quiet_set(s, "target.magnitude", magnitude)
            electrons = quiet_evaluate(s)["detector.signal_electrons"]
            solved = quiet_run(s)
            values[band] = (electrons, solved["target.magnitude"], all(x.converged for x in solved.solves), text)
        (ea, ma, converged_a, text_a), (eb, mb, converged_b, _) = values[band_a], values[band_b]
        bad = [] if converged_a and converged_b else [f"the m5 solve did not converge ({band_a}: {converged_a}, "
                                                      f"{band_b}: {converged_b})"]
        if not rel(ea, eb) <= 1e-6:
            bad.append(f"detector.signal_electrons at m = {magnitude}: {ea!r} ({band_a}) vs {eb!r} ({band_b}), "
                       f"relative {rel(ea, eb):.3g} > 1e-6")
        if not abs(ma - mb) <= 1e-6:
            bad.append(f"solved target.magnitude: {ma!r} ({band_a}) vs {mb!r} ({band_b}), |delta| "
                       f"{abs(ma - mb):.3g} mag > 1e-6")
        if bad:
            failures.append((draw, sensor, band_a, band_b, bad, text_a))
    if failures:
        draw, sensor, band_a, band_b, bad, text_a = failures[0]
        pytest.fail(
            f"{len(failures)} of {DRAWS} draws: the normalising band changes a flat-{'f_nu AB' if system == 'ab' else 'f_lambda ST'}"
            f" source.\nFirst: draw {draw}, {sensor}, band {band_a} vs {band_b}:\n  " + "\n  ".join(bad) +
            f"\nSensor file (with band = \"{band_a}\"; replace it by \"{band_b}\"), --no-solve at the magnitude above:\n"
            f"{text_a}")


def _table_range_nm(name: str):
    rows = [line for line in (SPECTRA / name).read_text().splitlines() if line.strip() and not line.startswith("#")]
    wavelengths = [float(line.split(",")[0]) for line in rows[1:]]
    return min(wavelengths), max(wavelengths)


def test_the_band_check_sees_a_flat_sed_cut_to_the_band(tmp_path):
    """The power of the check above: the known bug (a flat-f_nu SED built only over the normalising band's table)
    emulated with `sed` tables that are flat in f_nu over each band's range only. Normalised in Johnson B, such a
    source has no light in most of the Rubin r band: m5 24.50 (LSST r) against ~21.8 (Johnson B), which the check's
    1e-6 mag tolerance must flag. (Passing here says the comparison can fail; the check above is the invariant.)"""
    f_nu = 10 ** (-0.4 * 48.60) * 1e-3  # W m-2 Hz-1 of AB magnitude 0
    m5 = {}
    for band in ("johnson_cousins_B_bessell1990.csv", "lsst_hardware_r_throughputs1.9.csv"):
        lo, hi = _table_range_nm(band)
        grid = np.geomspace(lo, hi, 4001)
        # 0 beyond the band's range, as the bug counted it, down to 0 at the table's ends (a table ending above 0
        # inside the detector's band is refused)
        rows = [(100.0, 0.0), (lo * (1 - 1e-9), 0.0)] + [(float(x), f_nu * 299792458.0 / (x * 1e-9) ** 2 * 1e-9)
                                                          for x in grid] + [(hi * (1 + 1e-9), 0.0), (3000.0, 0.0)]
        csv = tmp_path / f"flat_fnu_over_{band}"
        csv.write_text("# flat f_nu over one band's table only (the emulated bug)\nwavelength_nm,flux_density_W_m-2_nm-1\n"
                       + "".join(f"{x!r},{y!r}\n" for x, y in rows))
        doc = flat_source_doc("rubin-lsst-r-m5.toml", "ab", band)
        del doc["target"]["sed_shape"]
        doc["target"]["sed"] = str(csv)
        m5[band] = quiet_run(loads(dumps(doc), "rubin-lsst-r-m5.toml"))["target.magnitude"]
    b, r = m5.values()
    assert abs(r - 24.50) < 0.05 and abs(b - r) > 1.0, m5
    print(f"emulated bug: m5 {m5}")


# --------------------------------------------------------------------------------------------------------------
# 2. Inputs written in other units
# --------------------------------------------------------------------------------------------------------------

# (unit, its size in the SI unit as an exact decimal)
LENGTH_UNITS = [("m", Decimal(1)), ("cm", Decimal("0.01")), ("mm", Decimal("0.001")), ("um", Decimal("0.000001"))]
WAVELENGTH_UNITS = [("nm", Decimal("1e-9")), ("um", Decimal("1e-6"))]
TIME_UNITS = [("s", Decimal(1)), ("ms", Decimal("0.001"))]
FAMILIES = {"length": LENGTH_UNITS, "wavelength": WAVELENGTH_UNITS, "time": TIME_UNITS}
UNIT_KEYS = [  # (section, key, family)
    ("optics", "aperture", "length"), ("optics", "focal_length", "length"), ("optics", "psf_wavelength", "wavelength"),
    ("detector", "pixel_pitch", "length"), ("detector", "band_min", "wavelength"),
    ("detector", "band_max", "wavelength"), ("detector", "integration_time", "time"),
    ("platform", "altitude", "length"), ("criteria.iq", "wavelength", "wavelength"),
]
UNIT_FILES = ["msx-sbv.toml", "rubin-lsst-r-m5.toml", "rubin-lsst-g-m5.toml", "sentinel-2a-msi-b4.toml",
              "sentinel-2a-msi-b8.toml", "landsat-8-oli-b2.toml", "pleiades-1a-hiri-pan.toml", "worldview-2-pan.toml",
              "seahawk-hawkeye-b4.toml", "kolobrodov-1996-ccd151-computed.toml", "pan2010-auxiliary-sensor.toml"]


def _section(doc, dotted):
    node = doc
    for part in dotted.split("."):
        node = node.get(part) if isinstance(node, dict) else None
        if node is None:
            return None
    return node


# every unit the bundled files write these quantities in, with its size in the SI unit (exact decimals)
_UNIT_SIZES = {"m": Decimal(1), "cm": Decimal("0.01"), "mm": Decimal("0.001"), "um": Decimal("1e-6"),
               "nm": Decimal("1e-9"), "km": Decimal(1000), "s": Decimal(1), "ms": Decimal("0.001"),
               "us": Decimal("1e-6")}


def _si_of(text: str):
    number, unit = text.split(None, 1)
    size = _UNIT_SIZES.get(unit.strip())
    return None if size is None else Decimal(number) * size


def _written(si: Decimal, unit: str, size: Decimal) -> str:
    """si (an exact decimal, in the SI unit) written exactly in `unit` (no rounding: a decimal shift)."""
    v = (si / size).normalize()
    text = format(v, "f")
    return f"{text} {unit}"


def unit_slots(doc):
    """The (section, key, family, SI value) of the file's quantities that can be rewritten."""
    slots = []
    for section, key, family in UNIT_KEYS:
        table = _section(doc, section)
        if isinstance(table, dict) and isinstance(table.get(key), str):
            si = _si_of(table[key])
            if si is not None and si > 0:
                slots.append((section, key, family, si))
    return slots


def _with_units(doc, values: dict) -> dict:
    """A copy of doc with values[(section, key)] = text."""
    out = json.loads(json.dumps(doc))
    for (section, key), text in values.items():
        _section(out, section)[key] = text
    return out


def _draw_decimal(rng, si: Decimal, narrow=False) -> Decimal:
    """A random value within a factor ~1.3 of si (narrow: si itself), with 1 to 6 significant digits (narrow: 4
    to 7)."""
    digits = int(rng.integers(4, 8)) if narrow else int(rng.integers(1, 7))
    x = float(si) * (1.0 if narrow else math.exp(rng.uniform(-0.25, 0.25)))
    exponent = math.floor(math.log10(x)) - digits + 1
    mantissa = max(1, round(x / 10.0 ** exponent))
    return (Decimal(mantissa) * Decimal(10) ** exponent).normalize()


def _si_inputs(session, slots) -> dict:
    return {f"{section}.{key}": session.get(f"{section}.{key}") for section, key, _, _ in slots}


def test_units_do_not_change_the_bits():
    """The same quantities written in m / cm / mm / um, nm / um, s / ms: every number of the run is the same double.
    A unit conversion is the number times udunits' factor (0.01 for cm): both the decimal text and the factor are
    rounded in binary, so "15.037 cm" need not read back as the double nearest 0.15037 m. The failure message
    separates such inputs (Session.get differs) from results that differ although every input is the same."""
    rng = np.random.default_rng(20261103)
    conversion_failures, result_failures = [], []
    skipped = 0
    unit_tally = {}  # unit: [inputs read, inputs not read as the double nearest their exact decimal value]
    for draw in range(DRAWS):
        sensor = UNIT_FILES[rng.integers(len(UNIT_FILES))]
        doc = read_doc(sensor)
        slots = unit_slots(doc)
        assert slots, sensor
        drawn = {(section, key): _draw_decimal(rng, si) for section, key, _, si in slots}
        if ("detector", "band_min") in drawn and ("detector", "band_max") in drawn:
            # inside the file's band (a QE table may end at its edges), band_min < band_max
            lo_si = next(si for s_, k_, _, si in slots if (s_, k_) == ("detector", "band_min"))
            hi_si = next(si for s_, k_, _, si in slots if (s_, k_) == ("detector", "band_max"))
            lo, hi = sorted(_draw_decimal(rng, lo_si + (hi_si - lo_si) * Decimal(float(x)), narrow=True)
                            for x in rng.uniform(0.0, 1.0, size=2))
            if not lo < hi:
                lo, hi = lo_si, hi_si
            drawn[("detector", "band_min")], drawn[("detector", "band_max")] = max(lo, lo_si), min(hi, hi_si)
        si_text = {(s, k): _written(drawn[(s, k)], FAMILIES[f][0][0], FAMILIES[f][0][1]) for s, k, f, _ in slots}
        other_text = {}
        for s, k, f, _ in slots:
            unit, size = FAMILIES[f][int(rng.integers(len(FAMILIES[f])))]
            other_text[(s, k)] = _written(drawn[(s, k)], unit, size)
        base_doc, other_doc = _with_units(doc, si_text), _with_units(doc, other_text)
        try:  # a drawn value the file's chain refuses (out of range, past a table): draw again
            a = loads(dumps(base_doc), sensor)
            ra = quiet_run(a)
        except radchain.InputError:
            skipped += 1
            continue
        b = loads(dumps(other_doc), sensor)  # the same values in other units: must load where the SI text does
        rb = quiet_run(b)
        rows = differing(numbers_of(ra), numbers_of(rb))
        if not rows:
            continue
        inputs_a, inputs_b = _si_inputs(a, slots), _si_inputs(b, slots)
        inexact = {k: (inputs_a[k], inputs_b[k]) for k in inputs_a if not same_bits(inputs_a[k], inputs_b[k])}
        for s_, k_, _, _ in slots:  # which text read as the double nearest the exact decimal
            exact = float(drawn[(s_, k_)])
            for text, value in ((si_text[(s_, k_)], inputs_a[f"{s_}.{k_}"]), (other_text[(s_, k_)], inputs_b[f"{s_}.{k_}"])):
                unit = text.split()[1]
                tally = unit_tally.setdefault(unit, [0, 0])
                tally[0] += 1
                tally[1] += 0 if same_bits(value, exact) else 1
        # The smallest file that shows it: one key in another unit.
        minimal = None
        for s, k, f, _ in slots:
            if other_text[(s, k)].split()[1] == si_text[(s, k)].split()[1]:
                continue
            one = dict(si_text)
            one[(s, k)] = other_text[(s, k)]
            one_session = loads(dumps(_with_units(doc, one)), sensor)
            one_rows = differing(numbers_of(ra), numbers_of(quiet_run(one_session)))
            if one_rows:
                minimal = (s, k, si_text[(s, k)], other_text[(s, k)], one_rows, dumps(_with_units(doc, one)))
                break
        (conversion_failures if inexact else result_failures).append((draw, sensor, rows, inexact, minimal))
    assert skipped <= DRAWS // 5, f"{skipped} of {DRAWS} draws refused: the draws are too wide"
    if conversion_failures or result_failures:
        parts = [f"{len(conversion_failures) + len(result_failures)} of {DRAWS} draws give other bits in another unit "
                 f"({len(conversion_failures)} with an input already read as another double, "
                 f"{len(result_failures)} with every input the same double).",
                 "Inputs of the differing draws not read as the double nearest their decimal value, by unit: " +
                 ", ".join(f"{u} {bad}/{n}" for u, (n, bad) in sorted(unit_tally.items())) +
                 " (the number times udunits' factor, both rounded)"]
        for title, failures in (("Inputs read differently", conversion_failures),
                                ("Same inputs, other results", result_failures)):
            if not failures:
                continue
            draw, sensor, rows, inexact, minimal = failures[0]
            parts.append(f"{title}, first: draw {draw}, {sensor}")
            for k, (x, y) in inexact.items():
                parts.append(f"  input {k}: {x!r} vs {y!r} ({ulps(x, y)} ulp)")
            parts.append(f"  {len(rows)} numbers differ:\n" + describe_rows(rows))
            if minimal:
                s, k, ta, tb, one_rows, text = minimal
                parts.append(f"  minimal: only [{s}] {k} = \"{ta}\" written \"{tb}\" ({len(one_rows)} numbers differ):\n"
                             + describe_rows(one_rows, 4) + f"\n  sensor file (with \"{tb}\"):\n{text}")
        pytest.fail("\n".join(parts))


# --------------------------------------------------------------------------------------------------------------
# 3. Reordered sections
# --------------------------------------------------------------------------------------------------------------

ALL_SENSORS = sorted(p.name for p in SENSORS.glob("*.toml"))


def shuffled_blocks(bs, rng, keys=True):
    """The blocks in a random order that keeps the entries of each [[array]] in their order (the order of the
    [[solve]] and [[table]] entries is meaningful), each block's keys shuffled too when `keys`."""
    order = list(rng.permutation(len(bs)))
    # restore the relative order of each array's entries
    for header in {h for h, _ in bs if h.startswith("[[")}:
        positions = [i for i, j in enumerate(order) if bs[j][0] == header]
        entries = sorted(order[i] for i in positions)
        for i, j in zip(positions, entries):
            order[i] = j
    out = []
    for j in order:
        header, table = bs[j]
        items = list(table.items())
        if keys:
            items = [items[i] for i in rng.permutation(len(items))]
        out.append((header, dict(items)))
    return out


def test_reordered_sections_give_the_same_bits():
    """Every bundled file with its sections (and the keys inside each) in a random order: every number of the run
    (results, solves, checks, tables) is the same double as the file's own."""
    rng = np.random.default_rng(20261104)
    reference = {}
    failures = []
    for draw in range(DRAWS):
        sensor = ALL_SENSORS[draw % len(ALL_SENSORS)] if draw < len(ALL_SENSORS) else ALL_SENSORS[rng.integers(len(ALL_SENSORS))]
        if sensor not in reference:
            reference[sensor] = numbers_of(quiet_run(radchain.load(str(SENSORS / sensor))))
        bs = blocks(read_doc(sensor))
        reordered = shuffled_blocks(bs, rng)
        text = dump_blocks(reordered)
        rows = differing(reference[sensor], numbers_of(quiet_run(loads(text, sensor))))
        if rows:
            # smaller: the file as written by dump_blocks in its own order, then one block moved to the end
            own = dump_blocks(bs)
            own_rows = differing(reference[sensor], numbers_of(quiet_run(loads(own, sensor))))
            minimal = (own, own_rows, "the file rewritten in its own order (no reordering)") if own_rows else None
            if minimal is None:
                for i in range(len(bs)):
                    moved = bs[:i] + bs[i + 1:] + [bs[i]]
                    moved_rows = differing(reference[sensor], numbers_of(quiet_run(loads(dump_blocks(moved), sensor))))
                    if moved_rows:
                        minimal = (dump_blocks(moved), moved_rows, f"only {bs[i][0]} moved to the end")
                        break
            failures.append((draw, sensor, rows, text, minimal))
    if failures:
        draw, sensor, rows, text, minimal = failures[0]
        message = (f"{len(failures)} of {DRAWS} reordered files differ from their original. First: draw {draw}, "
                   f"{sensor}, {len(rows)} numbers differ (original vs reordered):\n" + describe_rows(rows))
        if minimal:
            message += f"\nMinimal: {minimal[2]}:\n" + describe_rows(minimal[1], 4) + "\n" + minimal[0]
        else:
            message += "\nReordered file:\n" + text
        pytest.fail(message)


# --------------------------------------------------------------------------------------------------------------
# 4. Limiting magnitude against exposure
# --------------------------------------------------------------------------------------------------------------

def _signal_limited_doc(rng):
    """A chain whose only noise is the target's shot noise: no sky, no dark current, no read noise, a quantisation
    step of 2^-32 e- (its variance < 1e-18 e-^2 against S = T^2 >= 9 e-)."""
    kind = ["rubin", "msx"][int(rng.integers(2))]
    threshold = float(np.round(rng.uniform(3.0, 10.0), 4))
    time = float(np.round(10 ** rng.uniform(-1.0, 2.0), 6))
    if kind == "rubin":
        sensor = f"rubin-lsst-{'ugrizy'[rng.integers(6)]}-m5.toml"
        doc = read_doc(sensor)
        doc["atmosphere"].pop("sky_brightness", None)  # no sky
        doc["detector"].update({"read_noise": "0 e-", "dark_current": "0 e-/s", "gain": "1e9 DN/e-", "adc_bits": 32,
                                "integration_time": f"{time} s"})
        doc["optics"]["aperture"] = f"{float(np.round(10 ** rng.uniform(-1, 1), 5))} m"
    else:
        sensor = "msx-sbv.toml"
        doc = read_doc(sensor)
        doc["detector"].update({"read_noise": "0 e-", "dark_current": "0 e-/s", "full_well": "1 e-", "adc_bits": 32,
                                "quantisation": "emva", "integration_time": f"{time} s"})
        doc["optics"]["aperture"] = f"{float(np.round(10 ** rng.uniform(0.5, 2), 4))} cm"
    doc["criteria"]["detection"]["threshold"] = threshold
    doc["solve"][0]["bracket"] = [-30, 40]
    for key in ("expected", "table", "uncertainty"):
        doc.pop(key, None)
    return sensor, doc, time


def _sky_limited_doc(rng):
    """The MSX SBV's ccd_frame under a sky of -10 V mag/arcsec^2 in 1 cm pixels behind a short focal length: the
    background B per window is > 1e22 e-, so S = T^2/2 (1 + sqrt(1 + 4B/T^2)) is T sqrt(B) to 1e-10 and the
    limiting magnitude moves as 1.25 lg k; no read noise, no dark current, a negligible quantisation step."""
    sensor = "msx-sbv.toml"
    doc = read_doc(sensor)
    time = float(np.round(10 ** rng.uniform(1.0, 3.0), 4))
    doc["detector"].update({"read_noise": "0 e-", "dark_current": "0 e-/s", "full_well": "1 e-", "adc_bits": 32,
                            "quantisation": "emva", "integration_time": f"{time} s", "pixel_pitch": "1 cm",
                            "sky_brightness": -10})
    doc["optics"]["focal_length"] = f"{float(np.round(10 ** rng.uniform(-2.0, -1.5), 5))} m"
    doc["optics"]["aperture"] = f"{float(np.round(10 ** rng.uniform(1.0, 2.0), 4))} cm"
    doc["criteria"]["detection"]["threshold"] = float(np.round(rng.uniform(3.0, 10.0), 4))
    doc["solve"][0]["bracket"] = [-30, 40]
    for key in ("expected", "table", "uncertainty"):
        doc.pop(key, None)
    return sensor, doc, time


@pytest.mark.parametrize("regime", ["signal-limited", "sky-limited"])
def test_limiting_magnitude_against_exposure(regime):
    """t -> k t moves the limiting magnitude by 2.5 lg k when the target's own shot noise is the only noise (S = T^2
    whatever t: the flux limit goes as 1/t) and by 1.25 lg k when the sky dominates (S = T sqrt(B), B ∝ t: the flux
    limit goes as 1/sqrt(t)). Tolerance 1e-9 mag. Signal-limited: the Rubin files (emva1288, site without sky) and
    the MSX SBV (ccd_frame). Sky-limited: ccd_frame only, since 1.25 lg k holds to 1e-9 mag only for B > ~1e21 e-,
    which the site's sky (>= 10 AB mag/arcsec^2) cannot reach through any plausible emva1288 pixel; the draw checks
    that the exact S = T^2/2 (1 + sqrt(1 + 4B/T^2)) is within 1e-10 mag of the asymptote."""
    rng = np.random.default_rng(20261105 if regime == "signal-limited" else 20261106)
    slope = 2.5 if regime == "signal-limited" else 1.25
    failures = []
    for draw in range(DRAWS):
        sensor, doc, time = (_signal_limited_doc if regime == "signal-limited" else _sky_limited_doc)(rng)
        k = float(10 ** rng.uniform(-1.5, 1.5))
        s = loads(dumps(doc), sensor)
        r1 = quiet_run(s)
        m1 = r1["target.magnitude"]
        quiet_set(s, "detector.integration_time", time * k)
        r2 = quiet_run(s)
        m2 = r2["target.magnitude"]
        assert r1.passed or all(x.converged for x in r1.solves), (sensor, r1.solves)
        expected = slope * math.log10(k)
        if regime == "signal-limited":  # the draw is in the regime: n^2 = S to 1e-12
            for r in (r1, r2):
                noise, signal = r["detector.noise_electrons"], r["detector.signal_electrons"]
                assert abs(noise * noise - signal) <= 1e-12 * signal, (draw, sensor, noise, signal)
        if regime == "sky-limited":
            # the model's own answer, S = T^2/2 (1 + sqrt(1 + 4B/T^2)): its distance from the asymptote must be
            # far below the tolerance, or the draw does not test the law
            t_ = doc["criteria"]["detection"]["threshold"]
            b1, b2 = r1["detector.background_electrons"], r2["detector.background_electrons"]
            s_of = lambda b: t_ * t_ / 2 * (1 + math.sqrt(1 + 4 * b / (t_ * t_)))
            exact = 2.5 * math.log10(k * s_of(b1) / s_of(b2))  # m = -2.5 lg(S / t) + const
            assert abs(exact - expected) < 1e-10, f"draw {draw}: the sky is not large enough ({b1:.3g} e-)"
        if not abs((m2 - m1) - expected) <= 1e-9:
            failures.append((draw, sensor, time, k, m1, m2, expected, dumps(doc)))
    if failures:
        draw, sensor, time, k, m1, m2, expected, text = failures[0]
        pytest.fail(f"{len(failures)} of {DRAWS} draws ({regime}): m(k t) - m(t) != {slope} lg k to 1e-9 mag. First: "
                    f"draw {draw} from {sensor}, t = {time} s, k = {k!r}: m(t) = {m1!r}, m(k t) = {m2!r}, moved "
                    f"{m2 - m1!r}, expected {expected!r} (off by {(m2 - m1) - expected:.3g} mag)\n"
                    f"Sensor file (then detector.integration_time = {time * k!r} s):\n{text}")


# --------------------------------------------------------------------------------------------------------------
# 5. Binning
# --------------------------------------------------------------------------------------------------------------

BIN_POINT_RESULTS = ["detector.signal_electrons", "detector.noise_electrons", "detector.snr",
                     "detector.background_electrons", "detector.dark_electrons", "detector.read_noise",
                     "detector.peak_pixel_fill", "detector.ensquared_energy"]  # (window_pixel_count counts binned pixels)


def _binned_point_doc(rng, prnu: bool):
    sensor = f"rubin-lsst-{'ugrizy'[rng.integers(6)]}-m5.toml"
    doc = read_doc(sensor)
    det = doc["detector"]
    det["photometry"] = "window"
    det.update({
        "read_noise": f"{float(np.round(rng.uniform(0, 10), 3))} e-",
        "dark_current": f"{float(np.round(rng.uniform(0, 2), 3))} e-/s",
        "dsnu": f"{float(np.round(rng.uniform(0, 3), 3))} e-",
        "prnu": float(np.round(rng.uniform(0.001, 0.02), 4)) if prnu else 0,
        "exposures": int(rng.integers(1, 5)),
        "gain": f"{float(np.round(rng.uniform(0.2, 4), 3))} DN/e-",
        "integration_time": f"{float(np.round(10 ** rng.uniform(0, 2.5), 3))} s",
    })
    doc["atmosphere"]["seeing"] = f"{float(np.round(rng.uniform(0.4, 2.0), 3))} arcsec"
    for key in ("expected", "table", "uncertainty"):
        doc.pop(key, None)
    doc["solve"][0]["bracket"] = [10, 35]
    return sensor, doc


def _binned_pair(doc, b, n):
    binned, native = json.loads(json.dumps(doc)), json.loads(json.dumps(doc))
    binned["detector"].update({"binning": b, "window_pixels": n})
    native["detector"].update({"binning": 1, "window_pixels": n * b})
    return binned, native


@pytest.mark.parametrize("prnu", [False, True], ids=["no-prnu", "prnu"])
def test_binning_a_point_image_is_the_window_of_native_pixels(prnu):
    """emva1288 b x b binning, a point image in an n x n window of binned pixels = the same point image in an
    n b x n b window of native pixels: the same electrons, noise (read, dark, DSNU per native pixel; PRNU of the
    native pixels), SNR and m5 (relative 1e-12). Only the window photometry is a sum of pixels (PSF-weighted
    photometry weights binned pixels by another PSF sampling: not a sum)."""
    rng = np.random.default_rng(20261107 if not prnu else 20261108)
    failures = []
    for draw in range(DRAWS):
        sensor, doc = _binned_point_doc(rng, prnu)
        b, n = int(rng.integers(2, 5)), int(rng.integers(1, 4))
        magnitude = float(np.round(rng.uniform(18, 25), 3))
        binned_doc, native_doc = _binned_pair(doc, b, n)
        rows = []
        sessions = [loads(dumps(d), sensor) for d in (binned_doc, native_doc)]
        forward = []
        for s in sessions:
            quiet_set(s, "target.magnitude", magnitude)
            forward.append(quiet_evaluate(s))
        for name in BIN_POINT_RESULTS:
            x, y = forward[0][name], forward[1][name]
            if not rel(x, y) <= 1e-12:
                rows.append((name, x, y))
        m5 = [quiet_run(s)["target.magnitude"] for s in sessions]
        if not abs(m5[0] - m5[1]) <= 1e-10:
            rows.append(("target.magnitude (solved)", m5[0], m5[1]))
        if rows:
            failures.append((draw, sensor, b, n, magnitude, rows, dumps(binned_doc)))
    if failures:
        draw, sensor, b, n, magnitude, rows, text = failures[0]
        pytest.fail(f"{len(failures)} of {DRAWS} draws: {b}x{b} binning with a {n}x{n} window differs from a "
                    f"{n * b}x{n * b} window of native pixels. First: draw {draw} ({sensor}), at m = {magnitude} "
                    f"(binned vs native):\n" + "\n".join(f"  {k}: {x!r} vs {y!r} (relative {rel(x, y):.3g})"
                                                         for k, x, y in rows) +
                    f"\nSensor file (binned; the native one has binning = 1, window_pixels = {n * b}):\n{text}")


EXTENDED_FILES = ["sentinel-2a-msi-b4.toml"]  # the bundled emva1288 file with an extended scene
# name: the power of b it scales with (sum of b^2 independent native pixels)
BIN_EXTENDED_SCALING = {"detector.signal_electrons": 2, "detector.noise_electrons": 1, "detector.snr": 1,
                        "detector.reference_signal_electrons": 2, "detector.snr_at_reference": 1,
                        "detector.noise_equivalent_radiance": -1, "detector.saturation_radiance": 0,
                        "detector.peak_pixel_fill": 0, "detector.scene_radiance": 0}


def test_binning_an_extended_scene_sums_native_pixels():
    """emva1288 on an extended scene: a b x b binned pixel sums b^2 native pixels with independent noise (shot,
    dark, read, DSNU, PRNU): signal x b^2, noise x b, SNR x b, NEdL / b; radiances and the native fill unchanged
    (relative 1e-12). Random DSNU, PRNU, co-adds, TDI stages, dark current and read noise."""
    rng = np.random.default_rng(20261109)
    failures = []
    for draw in range(DRAWS):
        sensor = EXTENDED_FILES[rng.integers(len(EXTENDED_FILES))]
        doc = read_doc(sensor)
        if doc["detector"].get("plugin") != "emva1288":
            pytest.fail(f"{sensor}: expected an emva1288 detector")
        doc["detector"].update({
            "read_noise": f"{float(np.round(rng.uniform(0, 50), 3))} e-",
            "dark_current": f"{float(np.round(rng.uniform(0, 500), 3))} e-/s",
            "dsnu": f"{float(np.round(rng.uniform(0, 5), 3))} e-",
            "prnu": float(np.round(rng.uniform(0, 0.02), 4)),
            "exposures": int(rng.integers(1, 5)),
            "tdi_stages": int(rng.integers(1, 9)),
            "integration_time": f"{float(np.round(10 ** rng.uniform(-0.5, 1), 4))} ms",
            "pixel_pitch": f"{float(np.round(rng.uniform(4, 15), 3))} um",
        })
        doc["target"]["reflectance"] = float(np.round(rng.uniform(0.02, 0.9), 4))
        for key in ("expected", "table", "uncertainty"):
            doc.pop(key, None)
        b = int(rng.integers(2, 6))
        binned = json.loads(json.dumps(doc))
        binned["detector"]["binning"] = b
        doc["detector"]["binning"] = 1
        r1, rb = (quiet_evaluate(loads(dumps(d), sensor)) for d in (doc, binned))
        rows = []
        for name, power in BIN_EXTENDED_SCALING.items():
            expected, got = r1[name] * b ** power, rb[name]
            if not rel(expected, got) <= 1e-12:
                rows.append((name, power, r1[name], got, expected))
        if rows:
            failures.append((draw, sensor, b, rows, dumps(binned)))
    if failures:
        draw, sensor, b, rows, text = failures[0]
        pytest.fail(f"{len(failures)} of {DRAWS} draws: {b}x{b} binning of an extended scene is not the sum of "
                    f"{b * b} native pixels. First: draw {draw} ({sensor}):\n" +
                    "\n".join(f"  {k}: binning 1 {x!r} -> binning {b} {y!r}, expected x b^{p} = {e!r} "
                              f"(relative {rel(e, y):.3g})" for k, p, x, y, e in rows) +
                    f"\nSensor file (binned; set binning = 1 for the other):\n{text}")


# --------------------------------------------------------------------------------------------------------------
# 6. Command line and Python
# --------------------------------------------------------------------------------------------------------------

def _cli_env():
    env = dict(os.environ)
    env.setdefault("RADCHAIN_DATA_PATH", str(SPECTRA))
    return env


def _cli(cli_path, *args):
    done = subprocess.run([cli_path, *map(str, args)], capture_output=True, text=True, env=_cli_env())
    if done.returncode not in (0, 1):
        raise AssertionError(f"radchain {' '.join(map(str, args))} exited {done.returncode}: {done.stderr}")
    return done


# Numeric keys that every draw can perturb (the first present is used), with a factor range.
PERTURB = [("optics", "aperture"), ("detector", "integration_time"), ("optics", "transmittance"),
           ("detector", "qe"), ("target", "reflectance")]


def _perturbed(doc, rng):
    """(key, its new TOML value text) of one input of doc moved by a random factor (written in the file); not a
    [[solve]] unknown (a sweep may not step one)."""
    solved = {solve.get("unknown") for solve in doc.get("solve", [])}
    for section, key in PERTURB:
        table = doc.get(section, {})
        if key not in table or f"{section}.{key}" in solved:
            continue
        value = table[key]
        factor = math.exp(rng.uniform(-0.2, 0.2))
        if isinstance(value, str):
            number, unit = value.split(None, 1)
            new = float(np.round(float(number) * factor, int(rng.integers(2, 9))))
            table[key] = f"{new!r} {unit}"
            return f"{section}.{key}", table[key]
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            new = float(np.round(min(float(value) * factor, 1.0) if key in ("transmittance", "qe", "reflectance")
                                 else float(value) * factor, int(rng.integers(2, 9))))
            table[key] = new
            return f"{section}.{key}", repr(new)
    return None, None


@pytest.fixture(scope="module")
def cli_path():
    path = os.environ.get("RADCHAIN_CLI")
    if not path or not Path(path).is_file():
        pytest.fail("RADCHAIN_CLI must name the radchain executable built with the module")
    return path


def read_npy(path):
    """(column names, rows) of a .npy table as `radchain sweep --out` writes it (a structured array of '<f8'),
    read from its header directly: numpy.load refuses a header with a repeated field name (see
    test_sweep_npy_loads_with_numpy)."""
    import ast
    data = Path(path).read_bytes()
    assert data[:6] == b"\x93NUMPY", path
    major = data[6]
    length_bytes = 2 if major == 1 else 4
    header_length = int.from_bytes(data[8:8 + length_bytes], "little")
    start = 8 + length_bytes
    header = ast.literal_eval(data[start:start + header_length].decode("latin-1"))
    names = [name for name, kind in header["descr"]]
    assert all(kind == "<f8" for _, kind in header["descr"]), header
    values = np.frombuffer(data[start + header_length:], dtype="<f8").reshape(-1, len(names))
    return names, values


def column_name(record) -> str:
    """A result's column in a sweep table: its name, and its display unit after '_' when it has one."""
    return record.name if record.unit in ("", "1") else f"{record.name}_{record.unit.replace(' ', '_')}"


@pytest.fixture(scope="module")
def front_ends(cli_path, tmp_path_factory):
    """DRAWS bundled files, one input of each moved by a random factor (in the file), through the four front ends:
    Python's radchain.load(path).run(), `radchain run --format json`, a one-point `radchain sweep --out x.npy` over
    the moved input (at its value in the file), and one `radchain catalogue --format json --results <every result>`
    of all the draws' files."""
    rng = np.random.default_rng(20261110)
    folder = tmp_path_factory.mktemp("front-ends")
    draws = []
    for draw in range(DRAWS):
        sensor = ALL_SENSORS[draw] if draw < len(ALL_SENSORS) else ALL_SENSORS[rng.integers(len(ALL_SENSORS))]
        doc = read_doc(sensor)
        key, text = _perturbed(doc, rng)
        for drop in ("table", "uncertainty"):
            doc.pop(drop, None)
        path = folder / f"draw{draw:03d}-{sensor}"
        path.write_text(dumps(doc))
        python = quiet_run(radchain.load(str(path)))
        records = {name: python.record(name) for name in python.frame()["name"]}
        run = json.loads(_cli(cli_path, "run", path, "--format", "json").stdout)
        npy = None
        if key is not None:
            npy_path = folder / f"draw{draw:03d}.npy"
            _cli(cli_path, "sweep", path, "--set", f"{key}={text}:{text}:1", "--out", npy_path, "--threads", 1)
            npy = npy_path
        draws.append(dict(draw=draw, sensor=sensor, path=path, key=key, text=text, records=records, run=run,
                          npy=npy))
    # one catalogue of every draw's file, with every result of any of them requested ("not computed by this
    # sensor": a null cell)
    requested = sorted({name for d in draws for name in d["records"]})
    catalogue = json.loads(_cli(cli_path, "catalogue", *[d["path"] for d in draws], "--format", "json",
                                "--results", ",".join(requested)).stdout)
    for d in draws:
        d["catalogue"] = [row for row in catalogue["rows"] if row["sensor"] == d["path"].stem]
    return draws


def _report(failures, what):
    d, rows = failures[0]
    return (f"{len(failures)} of {DRAWS} draws: {what}. First: draw {d['draw']} from {d['sensor']} "
            f"({d['key']} = {d['text']}):\n" + describe_rows(rows) + f"\nSensor file:\n{Path(d['path']).read_text()}")


def test_python_equals_run_json(front_ends):
    """Every result, in SI (value_si) and in the report's unit (value): the same double."""
    failures = []
    for d in front_ends:
        py = {}
        for name, r in d["records"].items():
            py[f"{name} (SI)"], py[f"{name} [{r.unit}]"] = float(r.value_si), float(r.value)
        cli = {}
        for r in d["run"]["results"]:
            cli[f"{r['name']} (SI)"] = math.nan if r["value_si"] is None else float(r["value_si"])
            cli[f"{r['name']} [{r['unit']}]"] = math.nan if r["value"] is None else float(r["value"])
        rows = differing(py, cli)
        if rows:
            failures.append((d, rows))
    if failures:
        pytest.fail(_report(failures, "radchain.load(...).run() (left) differs from `radchain run --format json` "
                                      "(right)"))


def test_python_equals_sweep_npy(front_ends):
    """A one-point sweep over the moved input, at its value in the file: every result column (the report's unit,
    as the .npy holds it) is the double Python's record shows."""
    failures, checked = [], 0
    for d in front_ends:
        if d["npy"] is None:
            continue
        checked += 1
        names, values = read_npy(d["npy"])
        assert values.shape[0] == 1, (d["npy"], values.shape)
        # the axis column first, then the results; a swept input that is also a result has one column, the axis's
        # (the axis column is the input as written in its unit, not the result's display value: not compared)
        columns = {name: float(values[0, i]) for i, name in enumerate(names) if i >= 1}
        rows = []
        for name, r in d["records"].items():
            if column_name(r) == names[0]:
                continue
            got = columns.get(column_name(r))
            if got is None or not same_bits(float(r.value), got):
                rows.append((f"{name} [{r.unit}]", float(r.value), got))
        if rows:
            failures.append((d, rows))
    assert checked >= min(DRAWS, len(ALL_SENSORS)) // 2, checked
    if failures:
        pytest.fail(_report(failures, "radchain.load(...).run() (left) differs from the one-point "
                                      "`radchain sweep --out x.npy` (right)"))


def test_sweep_npy_loads_with_numpy(front_ends):
    """README: `--out grid.npy` is numpy.load()-able. A sweep over an input that the chain also publishes as a result
    (optics.aperture, detector.integration_time, ...) writes its column twice under one name."""
    failures = []
    for d in front_ends:
        if d["npy"] is None:
            continue
        try:
            np.load(d["npy"])
        except ValueError as error:
            names, _ = read_npy(d["npy"])
            repeated = sorted({n for n in names if names.count(n) > 1})
            failures.append((d, error, repeated))
    if failures:
        d, error, repeated = failures[0]
        pytest.fail(f"{len(failures)} of {len([d for d in front_ends if d['npy']])} one-point sweeps write a .npy that "
                    f"numpy.load refuses ({error}): repeated columns {repeated}. First: draw {d['draw']}, "
                    f"`radchain sweep {d['path'].name} --set \"{d['key']}={d['text']}:{d['text']}:1\" --out x.npy`")


def _catalogue_rows(d):
    """(result, Python's value in the report's unit, the catalogue's cell) of the catalogue's rows in the report's
    unit (a solved unknown or an [expected] result is shown once more in the unit of its [expected] entry: left out)."""
    records = d["records"]
    rows = [(row["result"], float(records[row["result"]].value), row["computed"]) for row in d["catalogue"]
            if row["result"] in records and row["computed"] is not None
            and row["unit"] == ("" if records[row["result"]].unit == "1" else records[row["result"]].unit)]
    assert {name for name, _, _ in rows} == set(records), sorted(set(records) - {name for name, _, _ in rows})
    return rows


def test_catalogue_json_equals_python_to_the_last_bit(front_ends):
    """The catalogue's JSON carries each requested result to the last bit (its text table shows 6 digits)."""
    failures = []
    for d in front_ends:
        rows = [(name, py, float(cell)) for name, py, cell in _catalogue_rows(d) if not same_bits(py, float(cell))]
        if rows:
            failures.append((d, rows))
    if failures:
        pytest.fail(_report(failures, "Python's value in the report's unit (left) differs from `radchain catalogue "
                                      "--format json` `computed` (right)"))
