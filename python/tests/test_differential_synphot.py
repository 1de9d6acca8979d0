"""Differential tests: radchain's photometry against synphot (Debian's python3-synphot 1.1.1, used as a library).

Many random configurations, drawn with numpy.random.default_rng([family seed, draw index]) so that any draw can
be regenerated alone (a failure prints the family's seed and the draw). RADCHAIN_DIFFERENTIAL_DRAWS sets the draws
per family: 200 by default (~20 s of CPU for the file), and for the long run
    RADCHAIN_DIFFERENTIAL_DRAWS=100000 <the environment of python/CMakeLists.txt> /usr/bin/python3 -m pytest -q \
        python/tests/test_differential_synphot.py
(~0.12 s of CPU per draw of all four families, synphot's interpolation most of it: about 3.5 h on one core; add -s
to see each family's worst delta when it passes). Families:
  1. zero points: target.zero_point_photon_rate (photons s-1 m-2 of magnitude 0) in AB, ST and Vega through
     bundled and random box / top-hat / Gaussian bandpasses;
  2. count rates: detector.signal_electrons of a point source of random magnitude, SED flat in f_nu, flat in
     f_lambda, Vega, a random table or a Planck curve (blackbody_lamp), normalised in band A (any system) and
     observed through the detector's qe_curve between band_min and band_max;
  3. magnitudes both ways: m -> radchain's target.band_photon_rate -> synphot's effstim magnitude, and synphot's
     electrons for m -> radchain's solve of target.magnitude at the SNR those electrons give;
  4. sky: detector.sky_electrons_per_pixel of the site's sky (flat f_nu of m AB mag/arcsec², or the dark-sky table
     scaled to m in a sky_band, or the table's own magnitude) vs synphot × the pixel's solid angle.

What is compared is the same integral on both sides (radchain: photon counting, Bessell & Murphy 2012 eq. A1, the
trapezoid on the union of the tables' grids). synphot is given the wavelengths to integrate on explicitly:
  * a tabulated spectrum times a tabulated band: the union of both tables' nodes inside the band, with the tabulated
    f_lambda interpolated linearly IN ENERGY UNITS onto that grid before synphot sees it. synphot stores a table
    in photlam and interpolates f_lambda·λ, which differs from radchain's interpolated f_lambda times λ by ~1e-7;
    the union grid's trapezoid differs from the exact integral of the two piecewise-linear functions by ~1e-6.
    With the same grid and the same interpolant both compute the same sum: tolerance 1e-9 (rounding, unit factors).
  * an analytic spectrum (AB's flat f_nu, ST's / the SED's flat f_lambda, the site's flat sky): a dense geometric
    grid (20,001 points) merged with the band's nodes, i.e. the exact integral of the piecewise-linear band times the
    analytic spectrum (checked against the closed form: < 1e-9). radchain samples them on log grids (2,000 points
    per factor e; the sky 20,001 points over 0.1-30 µm) and integrates by the trapezoid on the union of the grids:
    tolerance 1e-5 with bundled tables, 1e-4 with random ones (TOL_ANALYTIC, TOL_ANALYTIC_STEEP below say why).
  * a Planck SED (blackbody_lamp): radchain samples it at every integer nm from 100 to 2,500 nm
    (physics::planck_grid_m); synphot's BlackBody1D is sampled at the same nodes and handled as a table.
  * synphot's Empirical1D extrapolates a bandpass whose ends are not 0 at its end values; every table here is built
    with fill_value=0 (0 outside the table, as radchain's zero extrapolation).
The integrals are synphot's (SourceSpectrum * SpectralElement).integrate(wavelengths=..., 'trapezoid'), the
count rate's trapezoid: Observation.countrate sums bins whose edges lie half a bin beyond the waveset's ends,
which adds half a bin of the end values wherever the band does not end at 0 (a band cut at band_min/band_max).
"""
import math
import os
import zlib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pytest

import radchain

import astropy.units as u  # python3-astropy, python3-synphot: scripts/setup-debian.sh installs both
from synphot import SourceSpectrum, SpectralElement, Observation, units as syn_units
from synphot.models import ConstFlux1D, Empirical1D, BlackBody1D

SOURCE_DIR = Path(os.environ.get("RADCHAIN_SOURCE_DIR", Path(__file__).resolve().parents[2]))
SPECTRA = SOURCE_DIR / "spectra"
DRAWS = int(float(os.environ.get("RADCHAIN_DIFFERENTIAL_DRAWS", "200")))
POOL = 1024    # random tables per role and family (class Synthetic)
DENSE = 20001  # points of the dense grid for analytic spectra

# Tolerances (relative unless said otherwise):
TOL_SAME_GRID = 1e-9  # the same tables on the same union grid: only rounding and unit factors differ
TOL_ANALYTIC = 1e-5   # an analytic spectrum (flat f_nu / f_lambda): synphot's integral is exact to < 1e-9; radchain
#                       samples it on a log grid (2000 points per factor e) and integrates by its convention, the
#                       trapezoid on the union of the grids, which errs where a band's edge is narrower than that grid's
#                       step: 5e-7 in 200 draws of bundled tables, 4.9e-6 in a 3000-draw run (flat f_lambda through a
#                       coarse 1.0-1.7 um TESS response), so 1e-5
TOL_MAG = 1.0857 * TOL_ANALYTIC  # magnitudes: 2.5/ln 10 × the relative tolerance of the rate behind them
# A random table with a steep edge narrower than the analytic spectrum's grid step (0.76 nm at 1.5 µm): radchain's
# trapezoid on the union of the grids (its documented convention, synphot's too) misses the segment's curvature
# term 2 T' (f λ)', which grows as the segment's width squared: up to 3e-5 in 1000 draws of 2-60-node tables.
# Bundled tables keep TOL_ANALYTIC; a synthetic one with an analytic spectrum gets this.
TOL_ANALYTIC_STEEP = 1e-4

PHOTON_RATE = u.photon / (u.s * u.cm ** 2)  # what integrate() of photlam × throughput over Å gives
ARCSEC_PER_RAD = 648000.0 / math.pi

# Bundled bandpasses (dimensionless tables whose column reads as no unit): magnitudes' bands and detector curves.
FILTER_TABLES = [
    "johnson_cousins_B_bessell1990.csv", "johnson_cousins_V_bessell1990.csv", "johnson_cousins_R_bessell1990.csv",
    "johnson_cousins_I_bessell1990.csv", "johnson_V_mann_vonbraun_2015.csv", "johnson_V_stsci_cdbs_johnson_v_004.csv",
    "lsst_hardware_u_throughputs1.9.csv", "lsst_hardware_g_throughputs1.9.csv", "lsst_hardware_r_throughputs1.9.csv",
    "lsst_hardware_i_throughputs1.9.csv", "lsst_hardware_z_throughputs1.9.csv", "lsst_hardware_y_throughputs1.9.csv",
    "lsst_filter_r_throughputs1.9.csv", "sdss_g_doi2010.csv", "sdss_r_doi2010.csv", "sdss_i_doi2010.csv",
    "gaia_dr3_G.csv", "gaia_dr3_BP.csv", "gaia_dr3_RP.csv", "galex_fuv_throughput.csv", "galex_nuv_throughput.csv",
    "swift_uvot_v_throughput.csv", "swift_uvot_b_throughput.csv", "swift_uvot_u_throughput.csv",
    "swift_uvot_uvw1_throughput.csv", "roman_wfi_sca01_f062_throughput.csv", "roman_wfi_sca01_f158_throughput.csv",
    "tess_response_v2.0.csv", "cie_1924_photopic_V_1nm.csv",
]
QE_TABLES = [
    "ccd_back_illuminated_hamamatsu_S10420-01_qe.csv", "ccd_back_illuminated_lsst_e2v_qe.csv",
    "cmos_sony_imx428_mono_qe.csv", "ccd_front_illuminated_fairchild_relative.csv", "lsst_detector_throughputs1.9.csv",
]
VEGA_FILE = "vega_alpha_lyr_stis_002.csv"
SKY_TABLE = "lsst_darksky_throughputs1.9.csv"  # W m-2 nm-1 arcsec-2, 300-1200 nm


# ---------------------------------------------------------------------------------------------------------------
# Tables: the CSV format of spectra/ (framework/core/src/spectrum_csv.cpp): '#' provenance lines, a header
# wavelength_<unit>,<quantity>_<unit>, two comma-separated numbers per row, strictly increasing wavelengths.

@dataclass
class Table:
    name: str             # the file name a sensor file gives (bundled: found in RADCHAIN_DATA_PATH; else beside it)
    nm: np.ndarray        # wavelengths, nm
    value: np.ndarray     # dimensionless, or W m-2 nm-1 (SEDs), or W m-2 nm-1 arcsec-2 (the sky)
    text: str = ""        # the CSV text of a table written by the test (for failure reports)

    @property
    def lo(self):
        return float(self.nm[0])

    @property
    def hi(self):
        return float(self.nm[-1])


def read_table(path: Path) -> Table:
    rows = [line for line in path.read_text().splitlines() if not line.lstrip().startswith("#")]
    header = rows[0].split(",")
    assert header[0].strip() == "wavelength_nm", (path, header)
    data = np.array([[float(x) for x in r.split(",")] for r in rows[1:]])
    return Table(path.name, data[:, 0].copy(), data[:, 1].copy())


_BUNDLED: dict = {}


def bundled(name: str) -> Table:
    if name not in _BUNDLED:
        _BUNDLED[name] = read_table(SPECTRA / name)
    return _BUNDLED[name]


def write_table(folder: Path, name: str, nm, value, column="response") -> Table:
    nm = np.asarray(nm, float)
    value = np.asarray(value, float)
    assert np.all(np.diff(nm) > 0)
    lines = ["# synthetic table written by python/tests/test_differential_synphot.py (random draw)",
             f"wavelength_nm,{column}"]
    lines += [f"{w!r},{v!r}" for w, v in zip(nm.tolist(), value.tolist())]
    text = "\n".join(lines) + "\n"
    (folder / name).write_text(text)
    return Table(name, nm, value, text)


def random_band(rng, folder: Path, name: str, lo_limit=120.0, hi_limit=2400.0, shapes=("box", "tophat", "gauss"),
                min_width=3.0, max_width=800.0) -> Table:
    """A random bandpass table: a box (non-zero at its ends), a top-hat with ramps to 0, or a Gaussian; 2 to 60 nodes
    (coarse tables make the trapezoid at their nodes differ from the exact integral)."""
    shape = shapes[rng.integers(len(shapes))]
    width = float(np.exp(rng.uniform(np.log(min_width), np.log(max_width))))
    width = min(width, 0.9 * (hi_limit - lo_limit))
    lo = float(rng.uniform(lo_limit, hi_limit - width))
    hi = lo + width
    amplitude = float(rng.uniform(0.05, 1.0))
    n = int(rng.integers(2, 61))
    if shape == "gauss":
        n = max(n, 5)
        nm = np.linspace(lo, hi, n)
        centre, sigma = 0.5 * (lo + hi) + rng.uniform(-0.1, 0.1) * width, width / rng.uniform(4.0, 9.0)
        value = amplitude * np.exp(-0.5 * ((nm - centre) / sigma) ** 2)
    else:
        inner = np.sort(rng.uniform(lo, hi, max(n - 2, 0)))
        nm = np.concatenate([[lo], inner, [hi]])
        nm = np.round(nm, 4)
        nm = nm[np.concatenate([[True], np.diff(nm) > 1e-3])]
        if nm.size < 2:
            nm = np.array([round(lo, 4), round(hi, 4)])
        value = amplitude * (1.0 + 0.3 * rng.uniform(-1.0, 1.0, nm.size)) if rng.random() < 0.5 else \
            np.full(nm.size, amplitude)
        if shape == "tophat" and nm.size > 2:  # ramps from 0 over the first and last intervals
            value[0] = value[-1] = 0.0
    return write_table(folder, name, nm, value)


class Synthetic:
    """The random tables of one family: POOL per role (a band, a QE curve, an SED), table j of a role generated from
    default_rng([family seed, crc32(role), j]) and written once as <role>_<j>.csv. radchain keeps every table file it
    reads for the life of the process (cached_spectrum_csv), so a long run must not write a new file per draw."""

    def __init__(self, folder: Path, seed: int):
        self.folder, self.seed, self.tables = folder, seed, {}

    def get(self, draw_rng, role: str, maker) -> Table:
        j = int(draw_rng.integers(POOL))
        if (role, j) not in self.tables:
            rng = np.random.default_rng([self.seed, zlib.crc32(role.encode()), j])
            self.tables[role, j] = maker(rng, self.folder, f"{role}_{j}.csv")
        return self.tables[role, j]

    def band(self, draw_rng, role: str, within=(100.0, 2500.0)) -> Table:
        lo, hi = max(within[0], 120.0), min(within[1], 2400.0)
        return self.get(draw_rng, role, lambda rng, folder, name: random_band(rng, folder, name, lo, hi))


def pick_band(rng, synthetic: Synthetic, role: str, synthetic_fraction=0.5, within=(100.0, 2500.0)) -> Table:
    if rng.random() < synthetic_fraction:
        return synthetic.band(rng, role, within)
    choices = [f for f in FILTER_TABLES if bundled(f).lo >= within[0] and bundled(f).hi <= within[1]]
    return bundled(choices[rng.integers(len(choices))])


# ---------------------------------------------------------------------------------------------------------------
# synphot side.

def grid_union(lo, hi, *node_sets, dense=False):
    """Sorted union of the nodes inside [lo, hi], the limits included; plus a dense geometric grid if asked."""
    parts = [np.array([lo, hi], float)]
    for nodes in node_sets:
        nodes = np.asarray(nodes, float)
        parts.append(nodes[(nodes > lo) & (nodes < hi)])
    if dense:
        parts.append(np.geomspace(lo, hi, DENSE)[1:-1])
    return np.unique(np.concatenate(parts))


def syn_band(table: Table) -> SpectralElement:
    return SpectralElement(Empirical1D, points=table.nm * 10.0, lookup_table=table.value, fill_value=0.0,
                           keep_neg=True)


def syn_flat(nm_lo, nm_hi) -> SpectralElement:
    return SpectralElement(Empirical1D, points=np.array([nm_lo, nm_hi]) * 10.0, lookup_table=np.ones(2),
                           fill_value=0.0, keep_neg=True)


def syn_table_on(table: Table, grid_nm) -> SourceSpectrum:
    """A tabulated f_lambda (W m-2 nm-1) interpolated linearly in energy units onto grid_nm (radchain's interpolant)."""
    f = np.where((grid_nm >= table.lo) & (grid_nm <= table.hi), np.interp(grid_nm, table.nm, table.value), 0.0)
    return SourceSpectrum(Empirical1D, points=grid_nm * 10.0, lookup_table=f * (u.W / u.m ** 2 / u.nm),
                          fill_value=0.0, keep_neg=True)


def integral(sp: SourceSpectrum, bp: SpectralElement, grid_nm) -> float:
    """∫ photlam T dλ on grid_nm by synphot's trapezoid: photons s-1 cm-2."""
    return (sp * bp).integrate(wavelengths=grid_nm * 10.0, integration_type="trapezoid").to_value(PHOTON_RATE)


FLAT_NU = SourceSpectrum(ConstFlux1D, amplitude=0 * u.ABmag)   # AB magnitude 0
FLAT_LAMBDA = SourceSpectrum(ConstFlux1D, amplitude=0 * u.STmag)  # ST magnitude 0
_VEGA_SYN = None


def vega_table() -> Table:
    return bundled(VEGA_FILE)


def vega_spec() -> SourceSpectrum:
    global _VEGA_SYN
    if _VEGA_SYN is None:
        v = vega_table()
        _VEGA_SYN = SourceSpectrum(Empirical1D, points=v.nm * 10.0, lookup_table=v.value * (u.W / u.m ** 2 / u.nm),
                                   fill_value=0.0, keep_neg=True)
    return _VEGA_SYN


_ZERO_POINTS: dict = {}


def zero_point(system: str, band: Table) -> float:
    """synphot: photons s-1 cm-2 of magnitude 0 through the band (the whole table)."""
    if not band.text:  # a bundled table: computed once
        key = (system, band.name)
        if key not in _ZERO_POINTS:
            _ZERO_POINTS[key] = _zero_point(system, band)
        return _ZERO_POINTS[key]
    return _zero_point(system, band)


def _zero_point(system: str, band: Table) -> float:
    bp = syn_band(band)
    if system == "vega":  # the same union grid as radchain: Vega's nodes and the band's inside the band
        grid = grid_union(band.lo, band.hi, band.nm, vega_table().nm)
        return integral(syn_table_on(vega_table(), grid), bp, grid)
    grid = grid_union(band.lo, band.hi, band.nm, dense=True)
    return integral(FLAT_NU if system == "ab" else FLAT_LAMBDA, bp, grid)


# SEDs: "flat_f_nu" and "flat_f_lambda" are analytic; "vega", "table" (a random table) and "blackbody" (Planck
# sampled at radchain's nodes, physics/band.cpp planck_grid_m: every integer nm from 100 to 2500 nm) are tables.
ANALYTIC = {"flat_f_nu": FLAT_NU, "flat_f_lambda": FLAT_LAMBDA}


@dataclass
class Sed:
    kind: str
    table: Table = None       # tabulated kinds
    temperature: float = 0.0  # blackbody

    @property
    def analytic(self):
        return self.kind in ANALYTIC

    def integral(self, bp: SpectralElement, band_nodes, lo, hi) -> float:
        """∫ SED T λ/(hc) dλ over [lo, hi] (photons s-1 cm-2 per unit SED), on the grid radchain integrates on."""
        if self.analytic:
            grid = grid_union(lo, hi, band_nodes, dense=True)
            return integral(ANALYTIC[self.kind], bp, grid)
        grid = grid_union(max(lo, self.table.lo), min(hi, self.table.hi), band_nodes, self.table.nm)
        return integral(syn_table_on(self.table, grid), bp, grid)

    def spectrum(self, grid_nm=None) -> SourceSpectrum:
        return ANALYTIC[self.kind] if self.analytic else syn_table_on(self.table, grid_nm)


def random_sed_table(rng, folder: Path, name: str) -> Table:
    """A power law with bumps on 8-200 random nodes over 90-3000 nm (W m-2 nm-1)."""
    n = int(rng.integers(8, 201))
    nm = np.unique(np.round(np.concatenate([[90.0, 3000.0], np.exp(rng.uniform(np.log(90), np.log(3000), n))]), 3))
    slope = rng.uniform(-4.0, 2.0)
    f = 1e-12 * (nm / 500.0) ** slope * (1.0 + 0.5 * rng.uniform(-1.0, 1.0, nm.size))
    return write_table(folder, name, nm, f, column="flux_density_W_m-2_nm-1")


def planck_table(temperature: float) -> Table:
    nm = np.arange(100.0, 2501.0)
    bb = SourceSpectrum(BlackBody1D, temperature=temperature)
    f = bb(nm * 10.0, flux_unit=syn_units.FLAM).value  # any scale: only the shape enters
    return Table(f"planck_{temperature:.6g}K", nm, f)


def random_sed(rng, synthetic: Synthetic, kinds=("flat_f_nu", "flat_f_lambda", "vega", "table", "blackbody")) -> Sed:
    kind = kinds[rng.integers(len(kinds))]
    if kind == "vega":
        return Sed(kind, vega_table())
    if kind == "blackbody":
        t = float(np.exp(rng.uniform(np.log(2000.0), np.log(40000.0))))
        t = float(f"{t:.6g}")
        return Sed(kind, planck_table(t), t)
    if kind == "table":
        return Sed(kind, synthetic.get(rng, "sed", random_sed_table))
    return Sed(kind)


# ---------------------------------------------------------------------------------------------------------------
# radchain side: one sensor file per draw; optics transmittance 1, no obscuration, no atmosphere, no PSF (the whole
# image in the window: ensquared energy 1), no noise that matters.

def toml_string(s: str) -> str:
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"') + '"'


def sensor_text(*, system, band, magnitude, sed: Sed, reference_magnitude=None, aperture_m=1.0, qe=1.0,
                qe_curve=None, band_min=None, band_max=None, time_s=1.0, exposures=1, atmosphere=None,
                focal_length_m=None, pitch_um=10.0, binning=1, solve_snr=None, bracket=None) -> str:
    if sed.kind == "blackbody":
        source = f'plugin = "blackbody_lamp"\nconvention = "exact"\ntemperature = "{sed.temperature!r} K"'
    else:
        source = 'plugin = "sun"                  # not used: the target has its own SED'
    if sed.kind in ANALYTIC:
        sed_line = f'sed_shape = "{sed.kind}"'
    elif sed.kind == "blackbody":
        sed_line = 'sed_shape = "source"            # the blackbody_lamp Planck curve'
    else:
        sed_line = f"sed = {toml_string(sed.table.name)}"
    ref = f"\nreference_magnitude = {reference_magnitude!r}" if reference_magnitude is not None else ""
    band_min = band.lo if band_min is None else band_min
    band_max = band.hi if band_max is None else band_max
    qe_line = f"\nqe_curve = {toml_string(qe_curve.name)}" if qe_curve is not None else ""
    focal = f'\nfocal_length = "{focal_length_m!r} m"' if focal_length_m is not None else ""
    text = f"""\
[source]
{source}

[atmosphere]
{atmosphere or 'plugin = "none"'}

[target]
plugin = "point_source"
system = "{system}"
band = {toml_string(band.name)}
{sed_line}
magnitude = {magnitude!r}{ref}

[optics]
plugin = "telescope"
aperture = "{aperture_m!r} m"
obscuration = 0
transmittance = 1{focal}

[detector]
plugin = "emva1288"
qe = {qe!r}{qe_line}
band_min = "{band_min!r} nm"
band_max = "{band_max!r} nm"
integration_time = "{time_s!r} s"
exposures = {exposures}
binning = {binning}
gain = "1 DN/e-"
read_noise = "0 e-"
full_well = "1e30 e-"
adc_bits = 32
pixel_pitch = "{pitch_um!r} um"
"""
    if solve_snr is not None:
        text += f"""
[criteria.detection]
plugin = "snr_threshold"
threshold = {solve_snr!r}

[[solve]]
unknown = "target.magnitude"
criterion = "detection"
bracket = [{bracket[0]!r}, {bracket[1]!r}]
"""
    return text


def load(folder: Path, text: str):
    return radchain.loads(text, name=str(folder / "draw.toml"))


# ---------------------------------------------------------------------------------------------------------------
# Draw bookkeeping and failure reports.

@dataclass
class Row:
    delta: float
    tol: float
    draw: int
    quantity: str
    radchain: float
    synphot: float
    text: str
    tables: tuple  # the tables the test wrote (kept for a failure, to print)
    label: str
    synthetic: bool  # the draw uses a table the test wrote

    @property
    def ratio(self):
        return self.delta / self.tol


@dataclass
class Check:
    """One family's comparisons: counts and the worst rows are kept; of the failing rows, the first KEEP_FAILED with
    their sensor files (a long run stays small in memory)."""
    family: str
    seed: int
    draws: int
    count: int = 0
    worst: Row = None
    worst_bundled: Row = None
    failed: list = field(default_factory=list)
    failed_by_quantity: dict = field(default_factory=dict)  # quantity: [count, worst delta, worst ratio]
    KEEP_FAILED = 500

    def compare(self, draw, quantity, rc, syn, tol, text, tables=(), absolute=False, label=""):
        delta = abs(rc - syn) if absolute else (abs(rc / syn - 1.0) if syn != 0 else abs(rc))
        if not np.isfinite(delta):
            delta = np.inf
        tables = tuple(t for t in tables if t is not None and t.text)  # those the test wrote
        if tables and 0.9 * TOL_ANALYTIC <= tol <= 1.2 * TOL_ANALYTIC:  # a synthetic table, an analytic spectrum
            tol *= TOL_ANALYTIC_STEEP / TOL_ANALYTIC                      # (a rate's or a magnitude's): see above
        ok = delta <= tol
        row = Row(delta, tol, draw, quantity, rc, syn, "" if ok else text, () if ok else tables, label, bool(tables))
        self.count += 1
        if self.worst is None or row.ratio > self.worst.ratio:
            self.worst = row
        if not row.synthetic and (self.worst_bundled is None or row.ratio > self.worst_bundled.ratio):
            self.worst_bundled = row
        if not ok:
            entry = self.failed_by_quantity.setdefault(quantity, [0, 0.0, 0.0])
            entry[0] += 1
            entry[1], entry[2] = max(entry[1], delta), max(entry[2], row.ratio)
            if len(self.failed) < self.KEEP_FAILED:
                self.failed.append(row)

    def summary(self):
        if not self.count:
            return f"{self.family}: no comparison made", True
        w = self.worst
        n_failed = sum(e[0] for e in self.failed_by_quantity.values())
        line = (f"{self.family}: {self.count} comparisons over {self.draws} draws (seed {self.seed}); worst delta "
                f"{w.delta:.3g} (tolerance {w.tol:.0e}, draw {w.draw}, {w.quantity}; {w.label})")
        if self.worst_bundled is not None:
            wb = self.worst_bundled
            line += f"; with bundled tables only: {wb.delta:.3g} (tolerance {wb.tol:.0e}, draw {wb.draw})"
        return line + f"; {n_failed} outside tolerance", n_failed > 0

    def failure(self):
        """The failure text (None when every comparison held): counts by quantity, the shortest failing sensor file
        of the worst quantity with its tables and the two numbers, and the worst draw."""
        line, bad = self.summary()
        if not bad:
            return None
        if not self.failed_by_quantity:
            return line
        lines = [line, "failures by quantity: " + ", ".join(
            f"{q}: {e[0]} (worst {e[1]:.3g})" for q, e in self.failed_by_quantity.items())]
        q_worst = max(self.failed_by_quantity, key=lambda q: self.failed_by_quantity[q][2])
        kept = [r for r in self.failed if r.quantity == q_worst] or self.failed
        example = min(kept, key=lambda r: (sum(len(t.text) for t in r.tables), len(r.text)))
        lines.append(f"\nminimal failing draw {example.draw} of {self.family} (rng = default_rng([{self.seed}, "
                     f"{example.draw}])): {example.quantity} ({example.label}): radchain {example.radchain!r}, "
                     f"synphot {example.synphot!r}, delta {example.delta:.3g} > {example.tol:.0e}")
        lines.append("---- sensor file ----\n" + example.text)
        for t in example.tables:
            body = t.text if t.text.count("\n") <= 80 else "\n".join(t.text.splitlines()[:80]) + "\n..."
            lines.append(f"---- {t.name} (beside the sensor file) ----\n{body}")
        w = self.worst
        lines.append(f"worst: draw {w.draw}, {w.quantity} ({w.label}): radchain {w.radchain!r}, "
                     f"synphot {w.synphot!r}, delta {w.delta:.3g}")
        return "\n".join(lines)


def finish(*checks):
    """Prints each family's summary (pytest -s shows it) and fails with every failing family's report."""
    reports = []
    for c in checks:
        print(c.summary()[0])
        text = c.failure()
        if text:
            reports.append(text)
    if reports:
        pytest.fail("\n\n".join(reports), pytrace=False)


def draw_folder(tmp_path_factory, family):
    return tmp_path_factory.mktemp(family)


# ---------------------------------------------------------------------------------------------------------------
# 1. Zero points.

def test_zero_points_ab_st_vega(tmp_path_factory):
    folder = draw_folder(tmp_path_factory, "zero_points")
    check = Check("zero points", 1001, DRAWS)
    synthetic = Synthetic(folder, check.seed)
    for i in range(DRAWS):
        rng = np.random.default_rng([check.seed, i])
        band = pick_band(rng, synthetic, "band")
        system = ("ab", "st", "vega")[rng.integers(3)]
        ref = float(np.round(rng.uniform(-0.1, 0.1), 4)) if system == "vega" and rng.random() < 0.5 else None
        text = sensor_text(system=system, band=band, magnitude=float(np.round(rng.uniform(0, 20), 3)),
                           sed=Sed("flat_f_nu"), reference_magnitude=ref)
        rc = load(folder, text).evaluate()["target.zero_point_photon_rate"]  # m-2 s-1
        syn = zero_point(system, band) * 1e4 * (10 ** (0.4 * ref) if ref is not None else 1.0)
        tol = TOL_SAME_GRID if system == "vega" else TOL_ANALYTIC
        check.compare(i, f"zero_point_photon_rate ({system})", rc, syn, tol, text, (band,),
                      label=f"{band.name}, {band.lo:g}-{band.hi:g} nm, {band.nm.size} nodes")
    finish(check)


# ---------------------------------------------------------------------------------------------------------------
# 2. Count rates: normalised in band A, observed through the detector.

@dataclass
class CountDraw:
    text: str
    tables: tuple
    electrons: float   # synphot
    tol: float
    label: str
    magnitude: float
    system: str
    band: Table
    sed: Sed
    ref: float         # reference_magnitude (vega), else 0


def detector_range(rng, table: Table):
    """band_min, band_max inside a table (its ends 30 % of the time)."""
    lo, hi = table.lo, table.hi
    if rng.random() < 0.3:
        return lo, hi
    a = lo + rng.uniform(0.0, 0.45) * (hi - lo)
    b = hi - rng.uniform(0.0, 0.45) * (hi - lo)
    return float(np.round(a, 3)), float(np.round(b, 3))


def count_draw(rng, synthetic: Synthetic, *, solve=False) -> CountDraw:
    sed = random_sed(rng, synthetic)
    band = pick_band(rng, synthetic, "band")
    system = ("ab", "st", "vega")[rng.integers(3)]
    ref = float(np.round(rng.uniform(-0.1, 0.1), 4)) if system == "vega" and rng.random() < 0.5 else None
    m = float(np.round(rng.uniform(-1.0, 24.0), 4))
    # The detector: no curve (η = qe), a bundled QE or filter table, or a random band.
    r = rng.random()
    if r < 0.15:
        qe_curve = None
        lo = float(np.round(rng.uniform(120.0, 1500.0), 3))
        hi = float(np.round(lo + rng.uniform(10.0, 900.0), 3))
    elif r < 0.55:
        names = QE_TABLES + FILTER_TABLES
        qe_curve = bundled(names[rng.integers(len(names))])
        lo, hi = detector_range(rng, qe_curve)
    else:
        qe_curve = synthetic.band(rng, "qe")
        lo, hi = detector_range(rng, qe_curve)
    qe = float(np.round(rng.uniform(0.05, 1.0), 4))
    aperture = float(f"{np.exp(rng.uniform(np.log(0.01), np.log(10.0))):.6g}")
    time_s = float(f"{np.exp(rng.uniform(np.log(1e-3), np.log(1e3))):.6g}")
    exposures = int(rng.integers(1, 5))

    # synphot: the SED normalised to m in band A, then ∫ over [lo, hi] through η.
    bp_a = syn_band(band)
    n0 = zero_point(system, band) * (10 ** (0.4 * ref) if ref is not None else 1.0)   # photons s-1 cm-2
    band_rate = 10 ** (-0.4 * m) * n0  # photons s-1 cm-2 in band A
    if sed.analytic and system in ("ab", "st"):  # one grid serves both integrals: synphot's normalize()
        grid_a = grid_union(band.lo, band.hi, band.nm, dense=True)
        unit = u.ABmag if system == "ab" else u.STmag
        normalised = sed.spectrum().normalize(m * unit, band=bp_a, wavelengths=grid_a * 10.0)
        scale = None
    else:  # each integral on its own grid (as radchain): normalize() would put both on one
        scale = band_rate / sed.integral(bp_a, band.nm, band.lo, band.hi)
    bp_det = syn_band(qe_curve) if qe_curve is not None else syn_flat(lo, hi)
    det_nodes = qe_curve.nm if qe_curve is not None else np.array([])
    if sed.analytic:
        grid = grid_union(lo, hi, det_nodes, dense=True)
        spec = normalised if scale is None else sed.spectrum() * scale
    else:
        grid = grid_union(max(lo, sed.table.lo), min(hi, sed.table.hi), det_nodes, sed.table.nm)
        spec = sed.spectrum(grid) * scale
    area_cm2 = math.pi / 4.0 * (aperture * 100.0) ** 2
    electrons = integral(spec, bp_det, grid) * area_cm2 * qe * time_s * exposures

    solve_snr = bracket = None
    if solve:  # SNR = S / sqrt(S + M/12): shot noise and the quantisation of K = 1 DN/e- (dark noise 0)
        solve_snr = electrons / math.sqrt(electrons + exposures / 12.0)
        bracket = (max(m - 12.0, -30.0), min(m + 12.0, 40.0))
    text = sensor_text(system=system, band=band, magnitude=m, sed=sed, reference_magnitude=ref, aperture_m=aperture,
                       qe=qe, qe_curve=qe_curve, band_min=lo, band_max=hi, time_s=time_s, exposures=exposures,
                       solve_snr=solve_snr, bracket=bracket)
    tables = tuple(t for t in (band, qe_curve, sed.table) if t is not None and t.text)
    tol = TOL_SAME_GRID if (not sed.analytic and system == "vega") else TOL_ANALYTIC
    label = (f"{sed.kind}{f' {sed.temperature:g} K' if sed.kind == 'blackbody' else ''}, {system} in {band.name}, "
             f"observed {lo:g}-{hi:g} nm through {qe_curve.name if qe_curve is not None else 'no curve'}")
    return CountDraw(text, tables, electrons, tol, label, m, system, band, sed, ref or 0.0)


def test_count_rates_normalised_in_one_band_observed_in_another(tmp_path_factory):
    folder = draw_folder(tmp_path_factory, "count_rates")
    check = Check("count rates", 2002, DRAWS)
    synthetic = Synthetic(folder, check.seed)
    for i in range(DRAWS):
        d = count_draw(np.random.default_rng([check.seed, i]), synthetic)
        r = load(folder, d.text).evaluate()
        check.compare(i, f"signal_electrons [{d.sed.kind}]", r["detector.signal_electrons"], d.electrons, d.tol,
                      d.text, d.tables, label=d.label)
    finish(check)


# ---------------------------------------------------------------------------------------------------------------
# 3. Magnitudes both ways.

def syn_magnitude_of_band_rate(d: CountDraw, rate_m2: float) -> float:
    """synphot's magnitude (Observation.effstim) of the draw's SED scaled to rate_m2 photons s-1 m-2 in band A."""
    band = d.band
    if d.system in ("ab", "st"):
        # effstim in AB converts <f_lambda> at the pivot wavelength, which synphot computes on the bandpass's own
        # waveset: the band is given on the dense grid (the same piecewise-linear function) so that the pivot is
        # the exact one.
        grid = grid_union(band.lo, band.hi, band.nm, dense=True)
        bp = SpectralElement(Empirical1D, points=grid * 10.0, lookup_table=np.interp(grid, band.nm, band.value),
                             fill_value=0.0, keep_neg=True)
        sed = d.sed.spectrum(grid)
        sp = sed * (rate_m2 * 1e-4 / integral(sed, bp, grid))
        unit = u.ABmag if d.system == "ab" else u.STmag
        return Observation(sp, bp, force="extrap").effstim(unit, wavelengths=grid * 10.0).value
    # VEGAMAG: num on the SED's grid, den = vegaspec × band on the product's waveset. vegaspec is Vega on the union
    # of its nodes and the band's inside the band, interpolated in f_lambda: radchain's grid and interpolant (synphot's
    # own table would be integrated over all of Vega's range and interpolated in photlam: test_synphot_conventions).
    grid = grid_union(band.lo, band.hi, band.nm, *(() if d.sed.analytic else (d.sed.table.nm,)), dense=d.sed.analytic)
    sed = d.sed.spectrum(grid)
    bp = syn_band(band)
    sp = sed * (rate_m2 * 1e-4 / integral(sed, bp, grid))
    vega_grid = grid_union(band.lo, band.hi, band.nm, vega_table().nm)
    m = Observation(sp, bp, force="extrap").effstim(syn_units.VEGAMAG, wavelengths=grid * 10.0,
                                                    vegaspec=syn_table_on(vega_table(), vega_grid)).value
    return m + d.ref


def test_magnitudes_both_ways(tmp_path_factory):
    folder = draw_folder(tmp_path_factory, "magnitudes")
    forward = Check("magnitudes: radchain band rate -> synphot effstim", 3003, DRAWS)
    backward = Check("magnitudes: synphot electrons -> radchain solve", 3003, DRAWS)
    synthetic = Synthetic(folder, forward.seed)
    for i in range(DRAWS):
        rng = np.random.default_rng([forward.seed, i])
        d = count_draw(rng, synthetic, solve=True)
        session = load(folder, d.text)
        # m -> rate -> m: radchain's band rate at the file's magnitude (evaluate(): no solve), synphot's magnitude of
        # it; only the zero point enters (the SED's integral cancels on synphot's side).
        m_syn = syn_magnitude_of_band_rate(d, session.evaluate()["target.band_photon_rate"])
        tol = 1.0857 * (TOL_SAME_GRID if d.system == "vega" else TOL_ANALYTIC) + 1e-12
        forward.compare(i, f"effstim magnitude ({d.system}) of radchain's band_photon_rate", d.magnitude, m_syn, tol,
                        d.text, d.tables, absolute=True, label=d.label)
        # rate -> m: radchain solves target.magnitude at the SNR of synphot's electrons for m.
        solved = session.run().solves[0]
        m_rc = solved.value_si if solved.converged else float("nan")
        backward.compare(i, f"solved target.magnitude [{d.sed.kind}]", m_rc, d.magnitude,
                         1.0857 * d.tol + 1e-12, d.text, d.tables, absolute=True, label=d.label)
    finish(forward, backward)


# ---------------------------------------------------------------------------------------------------------------
# 4. Sky surface brightness per pixel.

def test_sky_electrons_per_pixel(tmp_path_factory):
    folder = draw_folder(tmp_path_factory, "sky")
    check = Check("sky per pixel", 4004, DRAWS)
    synthetic = Synthetic(folder, check.seed)
    sky = bundled(SKY_TABLE)
    for i in range(DRAWS):
        rng = np.random.default_rng([check.seed, i])
        mode = ("flat", "table_scaled", "table")[rng.integers(3)]
        m_sky = float(np.round(rng.uniform(16.0, 24.0), 4))
        airmass = float(np.round(rng.uniform(1.0, 3.0), 4))
        k = float(np.round(rng.uniform(0.0, 0.5), 4))  # extinction: the sky is never extinguished again
        lines = ['plugin = "site"', f"airmass = {airmass!r}", f"extinction = {k!r}"]
        sky_band = None
        if mode == "flat":
            lines.append(f"sky_brightness = {m_sky!r}")
        else:
            lines.append(f"sky_table = {toml_string(SKY_TABLE)}")
            # (the table is 0 from 1100 nm on: a sky_band there is refused, "the sky has no light in sky_band")
            sky_band = pick_band(rng, synthetic, "skyband", within=(sky.lo, 1100.0))
            lines.append(f"sky_band = {toml_string(sky_band.name)}")
            if mode == "table_scaled":
                lines.append(f"sky_brightness = {m_sky!r}")
        within = (sky.lo, sky.hi) if mode != "flat" else (100.0, 2500.0)
        if rng.random() < 0.5:
            names = [n for n in QE_TABLES + FILTER_TABLES if bundled(n).lo >= within[0] and bundled(n).hi <= within[1]]
            qe_curve = bundled(names[rng.integers(len(names))])
        else:
            qe_curve = synthetic.band(rng, "qe" if mode == "flat" else "skyqe", within)
        lo, hi = detector_range(rng, qe_curve)
        qe = float(np.round(rng.uniform(0.05, 1.0), 4))
        aperture = float(f"{np.exp(rng.uniform(np.log(0.05), np.log(8.0))):.6g}")
        focal = float(f"{aperture * rng.uniform(1.0, 20.0):.6g}")
        pitch = float(np.round(rng.uniform(1.0, 30.0), 3))
        binning = int(rng.integers(1, 4))
        time_s = float(f"{np.exp(rng.uniform(np.log(1e-2), np.log(1e3))):.6g}")
        text = sensor_text(system="ab", band=bundled("johnson_cousins_V_bessell1990.csv"), magnitude=20.0,
                           sed=Sed("flat_f_nu"), aperture_m=aperture, qe=qe, qe_curve=qe_curve, band_min=lo,
                           band_max=hi, time_s=time_s, atmosphere="\n".join(lines), focal_length_m=focal,
                           pitch_um=pitch, binning=binning)
        r = load(folder, text).evaluate()
        label = (f"{mode} sky{f' in {sky_band.name}' if sky_band is not None else ''}, observed {lo:g}-{hi:g} nm "
                 f"through {qe_curve.name}")
        # synphot: photons s-1 cm-2 arcsec-2 through η on [lo, hi], × pupil area × pixel solid angle × t qe b².
        bp_det = syn_band(qe_curve)
        if mode == "flat":
            grid = grid_union(lo, hi, qe_curve.nm, dense=True)
            per_arcsec2 = integral(SourceSpectrum(ConstFlux1D, amplitude=m_sky * u.ABmag), bp_det, grid)
            tol = TOL_ANALYTIC
        else:
            grid = grid_union(max(lo, sky.lo), min(hi, sky.hi), qe_curve.nm, sky.nm)  # the sky is 0 beyond its table
            per_arcsec2 = integral(syn_table_on(sky, grid), bp_det, grid)
            bp_sky = syn_band(sky_band)
            grid_b = grid_union(sky_band.lo, sky_band.hi, sky_band.nm, sky.nm)
            table_in_band = integral(syn_table_on(sky, grid_b), bp_sky, grid_b)
            ab_in_band = zero_point("ab", sky_band)
            if mode == "table_scaled":
                per_arcsec2 *= 10 ** (-0.4 * m_sky) * ab_in_band / table_in_band
            else:  # the table's own AB magnitude per arcsec² in sky_band
                check.compare(i, "atmosphere.sky_brightness (table)", r["atmosphere.sky_brightness"],
                              -2.5 * math.log10(table_in_band / ab_in_band), TOL_MAG, text, (sky_band,),
                              absolute=True, label=label)
            tol = TOL_ANALYTIC  # the AB zero point in sky_band (table_scaled); the table alone: the same grid
            if mode == "table":
                tol = TOL_SAME_GRID
        area_cm2 = math.pi / 4.0 * (aperture * 100.0) ** 2
        pixel_arcsec2 = (pitch * 1e-6 / focal * ARCSEC_PER_RAD) ** 2
        syn = per_arcsec2 * area_cm2 * pixel_arcsec2 * time_s * qe * binning ** 2
        tables = tuple(t for t in (qe_curve, sky_band) if t is not None and t.text)
        check.compare(i, f"sky_electrons_per_pixel ({mode})", r["detector.sky_electrons_per_pixel"], syn, tol, text,
                      tables, label=label)
    finish(check)


# ---------------------------------------------------------------------------------------------------------------
# The synphot conventions avoided above, pinned so that they are not mistaken for radchain bugs.

def test_synphot_conventions(tmp_path_factory):
    """1. synphot integrates vegaspec × band over the union of both wavesets: with the whole Vega table, a band whose
    table does not end at 0 (a box) ramps from its end value to 0 at Vega's next node (and with Empirical1D's default
    fill it would keep its end value over all of Vega's range). radchain integrates over the band's table only.
    2. synphot stores a table in photlam and interpolates f_lambda·λ between its nodes; radchain interpolates f_lambda
    and weights by λ at every node of the union grid. Where a band's nodes fall inside Vega's wide infrared intervals
    the two differ by ~1e-6 (7.6e-7 in the 1920-1950 nm band below, 1.4e-6 in random ones)."""
    folder = draw_folder(tmp_path_factory, "conventions")
    for band, ramp in ((write_table(folder, "box.csv", [500.0, 600.0], [1.0, 1.0]), True),
                       (write_table(folder, "ir.csv", np.linspace(1920.0, 1950.0, 31),
                                    np.concatenate([[0.0], 0.5 + 0.3 * np.sin(np.arange(29)), [0.0]])), False)):
        rc = load(folder, sensor_text(system="vega", band=band, magnitude=0.0, sed=Sed("vega", vega_table()),
                                      band_min=band.lo, band_max=band.hi)).evaluate()["target.zero_point_photon_rate"]
        same_grid = zero_point("vega", band) * 1e4  # Vega in f_lambda on the union grid inside the band
        assert rc == pytest.approx(same_grid, rel=TOL_SAME_GRID)
        own_table = (vega_spec() * syn_band(band)).integrate(integration_type="trapezoid").to_value(PHOTON_RATE) * 1e4
        if ramp:
            assert abs(own_table / same_grid - 1) > 1e-4
        else:
            assert 3e-7 < abs(own_table / same_grid - 1) < 1e-5
