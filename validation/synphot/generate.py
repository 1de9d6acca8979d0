#!/usr/bin/python3
"""Peer validation of radchain's photometry against synphot (Debian python3-synphot 1.1.1).

Run from anywhere:  /usr/bin/python3 validation/synphot/generate.py

What it does, in this order:
  1. writes the spectral tables synphot's own test suite and models need and radchain can read
     (spectra/synphot_*.csv, each with its provenance header; rewritten only if their content changes);
  2. computes every case with synphot, the way a synphot user writes it (normalize, Observation, countrate,
     effstim), and writes validation/synphot/reference.json (inputs, the call chain as text, outputs with units);
  3. writes one radchain sensor file per case, validation/synphot/<case>.toml, whose [expected] entries are the
     synphot numbers (so the reference values and the sensor files cannot drift apart).

Check:  RADCHAIN_PLUGIN_PATH=out/pch/plugins RADCHAIN_DATA_PATH=spectra out/pch/radchain catalogue validation/synphot
and     /usr/bin/python3 validation/synphot/compare.py   (per case radchain vs synphot deltas, colours, table cells).

The mapping between the two tools (the sensor files are built the way python/tests/test_differential_synphot.py
builds them; docs/validation.md, "Differential tests"):
  * synphot  sp.normalize(m * unit, band=A)            <->  radchain [target] point_source: magnitude m, system,
                                                             band = A, SED = sp's shape (sed table, sed_shape, or a
                                                             blackbody_lamp source with sed_shape = "source")
  * synphot  Observation(sp_n, B).countrate(area)      <->  detector.image_electrons with qe_curve = B over B's whole
                                                             table, optics aperture sqrt(4 area/pi), tau = 1, 1 s
  * synphot  m - Observation(sp_n, B).effstim(OBMAG, area)
                                                       <->  detector.instrumental_zero_point (m + 2.5 lg(S/t))
  * synphot  Observation(ref0, A).countrate(1 m^2)     <->  target.zero_point_photon_rate (ref0: 0 ABmag / 0 STmag
                                                             ConstFlux1D, or Vega)
  * synphot  Observation(0 ABmag, B).countrate(1 m^2)  <->  detector.ab_zero_point_electron_rate
  * synphot  effstim(ABmag / STmag / VEGAMAG) in B      <->  the radchain magnitude in B, m_B = ZP_B - 2.5 lg(S/t), a
             and colours m_B - m_A                           difference of two radchain results (compare.py computes
                                                             it; [expected] holds one result per entry)
"""
import datetime
import json
import math
import sys
import warnings
from pathlib import Path

import numpy as np
import astropy
import astropy.units as u
from astropy.io import fits
import synphot
from synphot import Observation, SourceSpectrum, SpectralElement, units as su
from synphot.models import (BlackBodyNorm1D, Box1D, ConstFlux1D, Empirical1D, GaussianFlux1D,
                            PowerLawFlux1D)

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
SPECTRA = ROOT / "spectra"
SYNPHOT_TESTS = Path(synphot.__file__).resolve().parent / "tests" / "data"
VERSION = f"synphot {synphot.__version__}"
M2 = 1e4  # cm^2 per m^2: synphot areas are in cm^2
HST_AREA_CM2 = 45238.93416  # synphot/tests/test_units.py _area (HST, 2.4 m unobscured)

warnings.filterwarnings("ignore", category=astropy.utils.exceptions.AstropyUserWarning)


# ---------------------------------------------------------------------------------------------------------------
# Tables (the CSV format of spectra/: '#' provenance lines, then wavelength_nm,<quantity>[_<unit>]).

def read_csv(name):
    rows = [r for r in (SPECTRA / name).read_text().splitlines() if not r.startswith("#")]
    data = np.array([[float(x) for x in r.split(",")] for r in rows[1:]])
    return data[:, 0].copy(), data[:, 1].copy()


def write_csv(name, provenance, column, nm, value):
    lines = [f"# {p}" for p in provenance] + [f"wavelength_nm,{column}"]
    lines += [f"{w!r},{v!r}" for w, v in zip(np.asarray(nm, float).tolist(), np.asarray(value, float).tolist())]
    text = "\n".join(lines) + "\n"
    path = SPECTRA / name
    if not path.exists() or path.read_text() != text:
        path.write_text(text)
    return name


SCRIPT = "validation/synphot/generate.py"


def write_tables():
    """The tables synphot's tests and models use, as radchain tables (values exact: float32 FITS values written as
    the doubles they are, Angstrom / 10 -> nm, FLAM x 0.01 -> W m-2 nm-1)."""
    with fits.open(SYNPHOT_TESTS / "hst_acs_hrc_f555w.fits") as h:
        w = h[1].data["WAVELENGTH"].astype(float)
        t = h[1].data["THROUGHPUT"].astype(float)
    write_csv("synphot_hst_acs_hrc_f555w.csv", [
        "HST ACS/HRC F555W total system throughput band(acs,hrc,f555w) (HST OTA x ACS x HRC x F555W), the bandpass of",
        "synphot's own tests (TestObsPar, TestNormalize, test_spectrum_bandpass uresp etc.; values there from IRAF SYNPHOT).",
        "Source used: Debian package python3-synphot 1.1.1 (bookworm), file /usr/lib/python3/dist-packages/synphot/tests/data/",
        "  hst_acs_hrc_f555w.fits (header GRFTABLE u921351jm_tmg.fits, CMPTABLE ub31649mm_tmc.fits). BSD-3-Clause (AURA/STScI).",
        "Original units: WAVELENGTH Angstrom (float32), THROUGHPUT dimensionless (float32); 10000 rows, 3480-10500 A.",
        f"Processing ({SCRIPT}): wavelength / 10 -> nm (the float32 values as doubles, then divided); throughput unchanged.",
        "Relative to the HST pupil: synphot's tests use area = 45238.93416 cm^2 (2.4 m, unobscured: the OTA's obscuration is in",
        "  the throughput).",
    ], "throughput", w / 10.0, t)

    with fits.open(SYNPHOT_TESTS / "grw_70d5824_stisnic_005.fits") as h:
        w = h[1].data["WAVELENGTH"].astype(float)
        f = h[1].data["FLUX"].astype(float)
    write_csv("synphot_grw_70d5824_stisnic_005.csv", [
        "GRW+70 5824 (white dwarf, HST standard) absolute spectral flux density, HST CALSPEC grw_70d5824_stisnic_005",
        "  (STIS 1140-10155 A, NICMOS 10155-24977 A; Bohlin 2014 flux scale), the source spectrum of synphot's TestObsPar.",
        "Source used: Debian package python3-synphot 1.1.1 (bookworm), file /usr/lib/python3/dist-packages/synphot/tests/data/",
        "  grw_70d5824_stisnic_005.fits. BSD-3-Clause package; CALSPEC is a public STScI product (cite Bohlin, Gordon & Tremblay 2014).",
        "Original units: WAVELENGTH Angstrom (vacuum), FLUX FLAM = erg s-1 cm-2 A-1 (float32); 3991 rows.",
        f"Processing ({SCRIPT}): wavelength / 10 -> nm; flux x 0.01 -> W m-2 nm-1 (1 FLAM = 1e-2 W m-2 nm-1), full double precision.",
    ], "flux_density_W_m-2_nm-1", w / 10.0, f * 0.01)

    write_csv("synphot_box_5500A_width1A.csv", [
        "A 1-Angstrom box bandpass centred at 5500 A: synphot Box1D(amplitude=1, x_0=5500, width=1), the renormalisation band",
        "  box(5500,1) of synphot's TestNormalize (synphot/tests/test_spectrum_source.py).",
        f"Written by {SCRIPT}: two nodes, 549.95 and 550.05 nm, throughput 1 (a box: non-zero at its ends).",
    ], "throughput", [549.95, 550.05], [1.0, 1.0])

    em = SourceSpectrum(GaussianFlux1D, mean=5500, total_flux=1e-13 * u.erg / u.cm ** 2 / u.s, fwhm=250)
    nm = np.concatenate([[300.0], np.round(np.arange(4500, 6500.5, 0.5) / 10.0, 2), [1100.0]])
    flam = em(nm * 10.0, flux_unit=su.FLAM).value
    flam[0] = flam[-1] = 0.0
    write_csv("synphot_gaussian_em_5500A_fwhm250A.csv", [
        "Gaussian emission line em(5500, 250, 1e-13, flam): synphot GaussianFlux1D(mean=5500 A, fwhm=250 A, total_flux=1e-13",
        "  erg s-1 cm-2) of synphot's TestNormalize (synphot/tests/test_spectrum_source.py), evaluated by synphot 1.1.1.",
        f"Written by {SCRIPT}: the model's f_lambda (synphot evaluates GaussianFlux1D in PHOTLAM; converted to FLAM by synphot,",
        "  x 0.01 -> W m-2 nm-1) every 0.05 nm over 450-650 nm (+-9.4 sigma), and 0 at 300 nm and 1100 nm (the line has",
        "  fallen below 1e-19 of its peak at 450 and 650 nm), so that the table covers the ACS/HRC F555W band.",
    ], "flux_density_W_m-2_nm-1", nm, flam * 0.01)

    pl = SourceSpectrum(PowerLawFlux1D, amplitude=1 * su.PHOTLAM, x_0=6000 * u.AA, alpha=4)
    nm = np.geomspace(300.0, 1100.0, 4001)
    flam = pl(nm * 10.0, flux_unit=su.FLAM).value
    write_csv("synphot_powerlaw_6000A_alpha4.csv", [
        "Power law PowerLawFlux1D(amplitude=1 PHOTLAM, x_0=6000 A, alpha=4), i.e. photlam = (lambda/6000 A)^-4 and",
        "  f_lambda proportional to lambda^-5: the model of synphot's TestPowerLawSource (synphot/tests/test_spectrum_source.py).",
        f"Written by {SCRIPT}: synphot 1.1.1 evaluates it in FLAM (x 0.01 -> W m-2 nm-1) on 4001 log-spaced points,",
        "  300-1100 nm (step 3.25e-4 relative: linear interpolation between nodes errs by < 1e-6).",
    ], "flux_density_W_m-2_nm-1", nm, flam * 0.01)


# ---------------------------------------------------------------------------------------------------------------
# synphot objects

def band(name):
    nm, t = read_csv(name)
    return SpectralElement(Empirical1D, points=nm * 10.0 * u.AA, lookup_table=t, fill_value=0.0)


def sed_table(name):
    nm, f = read_csv(name)
    return SourceSpectrum(Empirical1D, points=nm * 10.0 * u.AA, lookup_table=f * (u.W / u.m ** 2 / u.nm),
                          fill_value=0.0)


VEGA_FILE = "vega_alpha_lyr_stis_002.csv"
AB0 = SourceSpectrum(ConstFlux1D, amplitude=0 * u.ABmag)
ST0 = SourceSpectrum(ConstFlux1D, amplitude=0 * u.STmag)


def dense(bp, n=20001):
    """A 20,001-point geometric grid merged with the band's nodes (the exact integral of an analytic spectrum)."""
    w = bp.waveset.value
    return np.unique(np.concatenate([w, np.geomspace(w[0], w[-1], n)]))


UNITS = {"ab": u.ABmag, "st": u.STmag, "vega": su.VEGAMAG}


# ---------------------------------------------------------------------------------------------------------------
# Cases

class Case:
    def __init__(self, cid, title, origin, *, sed, sed_call, system, band_a, magnitude, band_b=None, area_cm2=1e4,
                 sed_radchain, source_radchain=None, table=None, notes=""):
        self.cid, self.title, self.origin, self.notes = cid, title, origin, notes
        self.sed, self.sed_call, self.system = sed, sed_call, system
        self.band_a, self.band_b = band_a, band_b or band_a
        self.magnitude, self.area_cm2 = magnitude, area_cm2
        self.sed_radchain, self.source_radchain, self.table = sed_radchain, source_radchain, table


def bp_of(spec):
    """spec: a spectra/ file name, a list of them (multiplied), or ('box', ...) for synphot's Box1D."""
    if isinstance(spec, (list, tuple)) and spec and spec[0] == "Box1D":
        return SpectralElement(Box1D, amplitude=1, x_0=5500, width=1)
    if isinstance(spec, (list, tuple)):
        out = band(spec[0])
        for s in spec[1:]:
            out = out * band(s)
        return out
    return band(spec)


def bp_call(spec):
    if isinstance(spec, (list, tuple)) and spec and spec[0] == "Box1D":
        return "SpectralElement(Box1D, amplitude=1, x_0=5500, width=1)"
    if isinstance(spec, (list, tuple)):
        return " * ".join(f"bp({s!r})" for s in spec)
    return f"bp({spec!r})"


def compute(case, vega):
    bpa, bpb = bp_of(case.band_a), bp_of(case.band_b)
    unit = UNITS[case.system]
    kw = {"vegaspec": vega} if case.system == "vega" else {}
    sp_n = case.sed.normalize(case.magnitude * unit, band=bpa, **kw)
    obs = Observation(sp_n, bpb, force="extrap")
    area = case.area_cm2
    out = {}
    out["countrate"] = (obs.countrate(area=area).value, "count s-1")
    out["countrate_unbinned"] = (obs.countrate(area=area, binned=False).value, "count s-1")
    out["effstim_obmag"] = (obs.effstim(su.OBMAG, area=area).value, "OBMAG")
    out["effstim_flam"] = (obs.effstim(su.FLAM).value, "FLAM (erg s-1 cm-2 A-1)")
    out["effstim_photlam"] = (obs.effstim(su.PHOTLAM).value, "PHOTLAM (photon s-1 cm-2 A-1)")
    out["effstim_stmag"] = (obs.effstim(u.STmag).value, "STmag")
    out["effstim_abmag"] = (obs.effstim(u.ABmag).value, "ABmag")
    out["effstim_vegamag"] = (obs.effstim(su.VEGAMAG, vegaspec=vega).value, "VEGAMAG")
    # zero points: photons s-1 m-2 of magnitude 0 in band A (target.zero_point_photon_rate) and of 0 ABmag in B
    ref0 = {"ab": AB0, "st": ST0, "vega": vega}[case.system]
    out["zero_point_rate_A"] = (Observation(ref0, bpa, force="extrap").countrate(area=M2, binned=False).value,
                                "photon s-1 m-2")
    out["ab_zero_point_rate_B"] = (Observation(AB0, bpb, force="extrap").countrate(area=M2, binned=False).value,
                                   "photon s-1 m-2")
    # the same analytic zero points integrated exactly (dense grid): how far synphot's own trapezoid is from it
    if case.system in ("ab", "st"):
        out["zero_point_rate_A_dense"] = ((ref0 * bpa).integrate(wavelengths=dense(bpa), integration_type="trapezoid")
                                          .to_value(u.ph / u.s / u.cm ** 2) * M2, "photon s-1 m-2")
    out["ab_zero_point_rate_B_dense"] = ((AB0 * bpb).integrate(wavelengths=dense(bpb), integration_type="trapezoid")
                                         .to_value(u.ph / u.s / u.cm ** 2) * M2, "photon s-1 m-2")
    # the same with synphot given the wavelengths to integrate on: a 20,001-point geometric grid merged with the
    # band's nodes (the exact integral of an analytic spectrum; for a table it changes only the interpolation)
    if not isinstance(case.sed.model, Empirical1D):
        sp_x = case.sed.normalize(case.magnitude * unit, band=bpa, wavelengths=dense(bpa), **kw)
        obs_x = Observation(sp_x, bpb, force="extrap")
        out["countrate_exact"] = (obs_x.countrate(area=area, binned=False, wavelengths=dense(bpb)).value, "count s-1")
        out["instrumental_zero_point_exact"] = (
            case.magnitude - obs_x.effstim(su.OBMAG, area=area, wavelengths=dense(bpb)).value, "mag")
    # effstim magnitudes in B from exact integrals: the band resampled on the dense grid (the same piecewise-linear
    # function, so that effstim's den and the pivot wavelength are exact too), the spectrum given that grid
    grid_b = dense(bpb)
    bp_d = SpectralElement(Empirical1D, points=grid_b * u.AA, lookup_table=bpb(grid_b).value, fill_value=0.0)
    sp_e = sp_x if "countrate_exact" in out else sp_n
    obs_d = Observation(sp_e, bp_d, force="extrap")
    out["effstim_abmag_exact"] = (obs_d.effstim(u.ABmag, wavelengths=grid_b).value, "ABmag")
    out["effstim_stmag_exact"] = (obs_d.effstim(u.STmag, wavelengths=grid_b).value, "STmag")
    vega_b = Observation(vega, bpb, force="extrap").countrate(area=area, binned=False).value
    cr_e = out["countrate_exact"][0] if "countrate_exact" in out else out["countrate_unbinned"][0]
    out["effstim_vegamag_exact"] = (-2.5 * math.log10(cr_e / vega_b), "VEGAMAG (-2.5 lg of the count-rate ratio to Vega)")
    # instrumental zero point: the band-A magnitude giving 1 count/s through B
    out["instrumental_zero_point"] = (case.magnitude - out["effstim_obmag"][0], "mag")
    out["band_photon_rate_A"] = (10 ** (-0.4 * case.magnitude) * out["zero_point_rate_A"][0], "photon s-1 m-2")
    chain = (f"sp = {case.sed_call}\n"
             f"sp_n = sp.normalize({case.magnitude!r} * {unit.to_string() if case.system != 'vega' else 'units.VEGAMAG'}, "
             f"band={bp_call(case.band_a)}{', vegaspec=vega' if kw else ''})\n"
             f"obs = Observation(sp_n, {bp_call(case.band_b)}, force='extrap')\n"
             f"obs.countrate(area={area!r})            # binned (default) and binned=False\n"
             f"obs.effstim(units.OBMAG, area={area!r}); obs.effstim(units.FLAM | units.PHOTLAM | u.STmag | u.ABmag)\n"
             f"obs.effstim(units.VEGAMAG, vegaspec=vega)\n"
             f"Observation({ {'ab': 'AB0', 'st': 'ST0', 'vega': 'vega'}[case.system]}, band_A).countrate(area=1e4, binned=False)  # zero point, m-2\n"
             f"Observation(AB0, band_B).countrate(area=1e4, binned=False)\n"
             "with bp(f) = SpectralElement(Empirical1D, points=<f's nm> * 10 A, lookup_table=<f's values>, fill_value=0),\n"
             "vega = SourceSpectrum(Empirical1D, points=<vega_alpha_lyr_stis_002.csv nm> * 10 A, lookup_table=<W m-2 nm-1>),\n"
             "AB0 = SourceSpectrum(ConstFlux1D, amplitude=0*u.ABmag), ST0 = ... 0*u.STmag")
    return out, chain


def aperture_m(area_cm2):
    return math.sqrt(4.0 * area_cm2 * 1e-4 / math.pi)


def names(spec):
    return [spec] if isinstance(spec, str) else list(spec)


def toml_list(spec):
    n = names(spec)
    return f'"{n[0]}"' if len(n) == 1 else "[" + ", ".join(f'"{s}"' for s in n) + "]"


def band_limits(spec):
    lo, hi = [], []
    for s in names(spec):
        nm, _ = read_csv(s)
        lo.append(nm[0])
        hi.append(nm[-1])
    return max(lo), min(hi)


def fmt(x, digits=10):
    return float(f"{x:.{digits}g}")


def toml_text(case, out):
    src = case.source_radchain or 'plugin = "sun"                       # not used: the target has its own SED'
    band_a_file = "synphot_box_5500A_width1A.csv" if isinstance(case.band_a, (list, tuple)) and case.band_a[0] == "Box1D" \
        else case.band_a
    lo, hi = band_limits(case.band_b)
    ref = f"synphot 1.1.1"
    cr = out["countrate_unbinned"][0]
    zp_a, zp_a_call = out["zero_point_rate_A"][0], "Observation(ref0, A).countrate(area=1e4 cm2, binned=False)"
    box = isinstance(case.band_a, (list, tuple)) and case.band_a[0] == "Box1D"
    if case.system in ("ab", "st") and not box:  # an analytic reference: its exact integral (synphot, dense grid)
        zp_a, zp_a_call = out["zero_point_rate_A_dense"][0], "(ref0 * A).integrate(wavelengths=dense grid) x 1e4 cm2"
    zp_b = out["ab_zero_point_rate_B_dense"][0]
    izp, izp_call = out["instrumental_zero_point"][0], f"m - Observation(sp_n, B).effstim(OBMAG, area={case.area_cm2!r})"
    cr_call = f"Observation(sp_n, B).countrate(area={case.area_cm2!r}, binned=False)"
    if "countrate_exact" in out:  # an analytic SED: synphot given the dense grid (its exact integral)
        cr, izp = out["countrate_exact"][0], out["instrumental_zero_point_exact"][0]
        cr_call = f"Observation(sp_n, B).countrate(area={case.area_cm2!r}, binned=False, wavelengths=dense grid)"
        izp_call = f"m - Observation(sp_n, B).effstim(OBMAG, area={case.area_cm2!r}, wavelengths=dense grid)"
    lines = [
        f"# radchain vs synphot 1.1.1, case {case.cid}: {case.title}",
        f"# Origin: {case.origin}",
        "# Written by validation/synphot/generate.py from reference.json: do not edit by hand (re-run the script).",
        "# synphot: sp.normalize(m, band=A) then Observation(sp_n, B).countrate(area) / effstim; radchain: the same SED of",
        "# magnitude m in band A, counted through qe_curve = B over B's whole table, optics area = synphot's area, 1 s.",
    ]
    if case.notes:
        lines += [f"# {l}" for l in case.notes.split("\n")]
    lines += [
        "",
        "[sensor]",
        f'name = "synphot peer case {case.cid}"',
        f'reference = "{case.origin.split(";")[0]}"',
        "",
        "[source]",
        src,
        "",
        "[atmosphere]",
        'plugin = "none"',
        "",
        "[target]",
        'plugin = "point_source"',
        f'system = "{case.system}"',
        f'band = "{band_a_file}"',
        case.sed_radchain,
        f"magnitude = {case.magnitude!r}",
        "",
        "[optics]",
        'plugin = "telescope"',
        f'aperture = "{aperture_m(case.area_cm2)!r} m"   # sqrt(4 A / pi), A = {case.area_cm2!r} cm^2 (synphot area)',
        "obscuration = 0",
        "transmittance = 1",
        "",
        "[detector]",
        'plugin = "emva1288"',
        f"qe_curve = {toml_list(case.band_b)}",
        f'band_min = "{lo!r} nm"',
        f'band_max = "{hi!r} nm"',
        'integration_time = "1 s"',
        'gain = "0.001 DN/e-"                  # ADC range 4.3e12 e-: nothing saturates (the counts do not depend on K)',
        'read_noise = "0 e-"',
        'full_well = "1e30 e-"',
        "adc_bits = 32",
        'pixel_pitch = "10 um"',
        "",
        "[expected]",
        f'"detector.image_electrons" = {{ value = "{cr:.10g} electron", rel_tolerance = 1e-5, kind = "peer", source = "{ref} {cr_call} x 1 s, case {case.cid}" }}',
        f'"detector.instrumental_zero_point" = {{ value = {fmt(izp)!r}, tolerance = 1e-5, kind = "peer", source = "{ref} {izp_call}, case {case.cid}" }}',
        f'"target.zero_point_photon_rate" = {{ value = "{zp_a:.10g} m-2 s-1", rel_tolerance = 1e-5, kind = "peer", source = "{ref} {zp_a_call}, case {case.cid}" }}',
        f'"detector.ab_zero_point_electron_rate" = {{ value = "{zp_b:.10g} m-2 s-1", rel_tolerance = 1e-5, kind = "peer", source = "{ref} (ConstFlux1D(0 ABmag) * B).integrate(wavelengths=dense grid) x 1e4 cm2, case {case.cid}" }}',
    ]
    if case.table:
        vary, values, results = case.table
        lines += ["", "[[table]]", f'name = "{case.cid}: {vary} scan (compare.py checks each row against synphot)"',
                  f'vary = "{vary}"', "values = [" + ", ".join(f'"{v}"' for v in values) + "]",
                  "results = [" + ", ".join(f'"{r}"' for r in results) + "]"]
    return "\n".join(lines) + "\n"


def bb_source(t):
    return ('plugin = "blackbody_lamp"\n'
            'convention = "exact"                 # c2 = h c / k (SI 2019), as astropy\'s constants in BlackBodyNorm1D\n'
            f'temperature = "{t!r} K"')


BB_SED = 'sed_shape = "source"                  # the blackbody_lamp Planck curve (sampled every nm, 100-2500 nm)'
TEMPERATURES = [3000.0, 4000.0, 5000.0, 5800.0, 7500.0, 10000.0, 20000.0, 40000.0]


def cases(vega):
    grw = sed_table("synphot_grw_70d5824_stisnic_005.csv")
    acs = "synphot_hst_acs_hrc_f555w.csv"
    bb5000 = SourceSpectrum(BlackBodyNorm1D, temperature=5000)
    em = SourceSpectrum(GaussianFlux1D, mean=5500, total_flux=1e-13 * u.erg / u.cm ** 2 / u.s, fwhm=250)
    powerlaw = SourceSpectrum(PowerLawFlux1D, amplitude=1 * su.PHOTLAM, x_0=6000 * u.AA, alpha=4)
    box = ("Box1D",)
    obs_grw = Observation(grw, band(acs))
    m_st, m_ab = obs_grw.effstim(u.STmag).value, obs_grw.effstim(u.ABmag).value
    bessell = {b: f"johnson_cousins_{b}_bessell1990.csv" for b in "BVRI"}
    c = []
    for sysname, m in (("st", m_st), ("ab", m_ab)):
        c.append(Case(f"grw_acs_f555w_{sysname}", f"GRW+70 5824 through HST ACS/HRC F555W, {sysname.upper()}mag, HST area",
                      "synphot/tests/test_observation.py TestObsPar (values from IRAF SYNPHOT CALCPHOT: effstim STmag "
                      "12.68878224, ABmag 12.73668646, FLAM 3.05131543e-14; effstim(count) 101462.396 (pysynphot); "
                      "test_spectrum_bandpass uresp 3.00737e-19 FLAM)",
                      sed=grw, sed_call="SourceSpectrum(Empirical1D, <synphot_grw_70d5824_stisnic_005.csv>)  "
                                        "# = SourceSpectrum.from_file('grw_70d5824_stisnic_005.fits')",
                      system=sysname, band_a=acs, magnitude=fmt(m, 12), area_cm2=HST_AREA_CM2,
                      sed_radchain='sed = "synphot_grw_70d5824_stisnic_005.csv"',
                      notes=f"The magnitude is synphot's effstim({sysname.upper()}mag) of the absolute GRW spectrum through "
                            "F555W: radchain's count\nrate at that magnitude must be synphot's count rate of the spectrum."))
    for sysname, m, ans in (("st", 20.0, 118.5366), ("ab", 20.0, 117.4757)):
        c.append(Case(f"bb5000_box5500_acs_{sysname}", f"bb(5000) renormalised to 20 {sysname.upper()}mag in box(5500,1), "
                      "observed through ACS/HRC F555W, HST area",
                      f"synphot/tests/test_spectrum_source.py TestNormalize.test_renorm_density ('bb', 20 {sysname.upper()}mag): "
                      f"IRAF SYNPHOT COUNTRATE {ans} (test tolerance 0.7 %)",
                      sed=bb5000, sed_call="SourceSpectrum(BlackBodyNorm1D, temperature=5000)", system=sysname,
                      band_a=box, band_b=acs, magnitude=m, area_cm2=HST_AREA_CM2, sed_radchain=BB_SED,
                      source_radchain=bb_source(5000.0)))
    for sysname, m, ans in (("st", 18.0, 175.9712), ("ab", 18.0, 174.3967)):
        c.append(Case(f"em5500_box5500_acs_{sysname}", f"Gaussian emission line em(5500, 250, 1e-13, flam) renormalised to "
                      f"18 {sysname.upper()}mag in box(5500,1), observed through ACS/HRC F555W, HST area",
                      f"synphot/tests/test_spectrum_source.py TestNormalize.test_renorm_density ('em', 18 {sysname.upper()}mag): "
                      f"IRAF SYNPHOT COUNTRATE {ans} (test tolerance 0.7 %)",
                      sed=em, sed_call="SourceSpectrum(GaussianFlux1D, mean=5500, total_flux=1e-13 erg s-1 cm-2, fwhm=250)",
                      system=sysname, band_a=box, band_b=acs, magnitude=m, area_cm2=HST_AREA_CM2,
                      sed_radchain='sed = "synphot_gaussian_em_5500A_fwhm250A.csv"   # the GaussianFlux1D sampled every 0.05 nm',
                      notes="radchain has no analytic Gaussian SED: the line is a table of synphot's model (spectra/ header)."))
    for b in "BVRI":
        c.append(Case(f"vega_bessell_{b}", f"Vega (CALSPEC alpha_lyr_stis_002) zero point through Johnson-Cousins {b} "
                      "(Bessell 1990), 1 m^2",
                      "synphot docs 'Observation' / VEGAMAG examples (effstim of Vega in a standard band); Vega given as the "
                      "table radchain ships (SourceSpectrum.from_vega() downloads alpha_lyr_stis_010)",
                      sed=vega, sed_call="vega", system="vega", band_a=bessell[b], magnitude=0.0,
                      sed_radchain=f'sed = "{VEGA_FILE}"'))
    for b in "BRI":
        c.append(Case(f"bb5800_V_to_{b}", f"5800 K blackbody at V = 0 (VEGAMAG, Bessell V) observed through Bessell {b}, 1 m^2: "
                      f"the colour {'B-V' if b == 'B' else 'V-' + b} with case vega_bessell_{b}",
                      "synphot docs: colour of a normalised spectrum, Observation(sp.normalize(0*VEGAMAG, V, vegaspec), "
                      f"{b}).effstim(VEGAMAG, vegaspec)",
                      sed=SourceSpectrum(BlackBodyNorm1D, temperature=5800), sed_call="SourceSpectrum(BlackBodyNorm1D, "
                      "temperature=5800)", system="vega", band_a=bessell["V"], band_b=bessell[b], magnitude=0.0,
                      sed_radchain=BB_SED, source_radchain=bb_source(5800.0),
                      table=("source.temperature", [f"{t:g} K" for t in TEMPERATURES],
                             ["detector.image_electrons", "detector.instrumental_zero_point"])))
    for b in "gi":
        c.append(Case(f"powerlaw_sdss_r_to_{b}", f"power law photlam (lambda/6000 A)^-4 at r = 18 ABmag (SDSS r, Doi 2010) "
                      f"observed through SDSS {b}, 1 m^2: the colour {'g-r' if b == 'g' else 'r-i'}",
                      "synphot/tests/test_spectrum_source.py TestPowerLawSource model, PowerLawFlux1D(1 PHOTLAM, 6000 A, 4); "
                      "normalize + Observation as in the synphot docs",
                      sed=powerlaw, sed_call="SourceSpectrum(PowerLawFlux1D, amplitude=1*PHOTLAM, x_0=6000*u.AA, alpha=4)",
                      system="ab", band_a="sdss_r_doi2010.csv", band_b=f"sdss_{b}_doi2010.csv", magnitude=18.0,
                      sed_radchain='sed = "synphot_powerlaw_6000A_alpha4.csv"   # the PowerLawFlux1D sampled on 4001 log points',
                      notes="radchain has no analytic power-law SED: the model is a table (spectra/ header)."))
    c.append(Case("flat_fnu_lsst_r", "flat f_nu (AB) at 20 ABmag in the LSST r hardware band, observed through hardware r x "
                  "atmosphere X=1.0 (throughputs 1.9), 6.423 m",
                  "synphot docs: ConstFlux1D(0 ABmag) renormalised and observed; the Rubin r zero point of SMTN-002 "
                  "(28.36 for 1 s through hardware x atmosphere) as synphot computes it",
                  sed=AB0, sed_call="SourceSpectrum(ConstFlux1D, amplitude=0*u.ABmag)", system="ab",
                  band_a="lsst_hardware_r_throughputs1.9.csv",
                  band_b=["lsst_hardware_r_throughputs1.9.csv", "lsst_atmos_10_throughputs1.9.csv"], magnitude=20.0,
                  area_cm2=math.pi / 4 * 642.3 ** 2, sed_radchain='sed_shape = "flat_f_nu"'))
    c.append(Case("flat_flambda_galex_nuv_to_fuv", "flat f_lambda (ST) at 15 STmag in GALEX NUV observed through GALEX FUV, "
                  "50 cm pupil", "synphot docs: ConstFlux1D(0 STmag) renormalised in one band, observed in another",
                  sed=ST0, sed_call="SourceSpectrum(ConstFlux1D, amplitude=0*u.STmag)", system="st",
                  band_a="galex_nuv_throughput.csv", band_b="galex_fuv_throughput.csv", magnitude=15.0,
                  area_cm2=math.pi / 4 * 50.0 ** 2, sed_radchain='sed_shape = "flat_f_lambda"'))
    c.append(Case("vega_gaia_g", "Vega through Gaia G (EDR3 passband) with the 0.7278 m^2 pupil: Vega zero point, AB zero "
                  "point, Vega's G_AB", "synphot as a zero-point calculator (Riello et al. 2021 define ZP_AB = 2.5 lg of the "
                  "AB count rate: 25.8010)", sed=vega, sed_call="vega", system="vega", band_a="gaia_dr3_G.csv",
                  magnitude=0.0, area_cm2=7278.0, sed_radchain=f'sed = "{VEGA_FILE}"'))
    c.append(Case("vega_swift_uvot_v", "Vega through Swift UVOT V (A_eff / 30 cm pupil), 30 cm: the Vega count-rate zero point",
                  "synphot as a zero-point calculator (Poole et al. 2008 / Breeveld et al. 2011: V 17.89)", sed=vega,
                  sed_call="vega", system="vega", band_a="swift_uvot_v_throughput.csv", magnitude=0.0,
                  area_cm2=math.pi / 4 * 30.0 ** 2, sed_radchain=f'sed = "{VEGA_FILE}"'))
    return c


def table_rows(case, vega):
    """Rows of a case's [[table]] (blackbody temperature scans): synphot's count rate and instrumental zero point."""
    rows = []
    if not case.table:
        return rows
    bpa, bpb = bp_of(case.band_a), bp_of(case.band_b)
    for t in TEMPERATURES:
        sp = SourceSpectrum(BlackBodyNorm1D, temperature=t)
        sp_n = sp.normalize(case.magnitude * su.VEGAMAG, band=bpa, vegaspec=vega)
        obs = Observation(sp_n, bpb, force="extrap")
        cr = obs.countrate(area=case.area_cm2, binned=False).value
        sp_x = sp.normalize(case.magnitude * su.VEGAMAG, band=bpa, vegaspec=vega, wavelengths=dense(bpa))
        cr_x = Observation(sp_x, bpb, force="extrap").countrate(area=case.area_cm2, binned=False,
                                                                 wavelengths=dense(bpb)).value
        vega_b = Observation(vega, bpb, force="extrap").countrate(area=case.area_cm2, binned=False).value
        rows.append({"source.temperature": [t, "K"], "detector.image_electrons": [cr, "electron"],
                     "detector.instrumental_zero_point": [case.magnitude - obs.effstim(su.OBMAG, area=case.area_cm2).value,
                                                          "mag"],
                     "effstim_vegamag_B": [obs.effstim(su.VEGAMAG, vegaspec=vega).value, "VEGAMAG"],
                     "countrate_exact": [cr_x, "count s-1"],
                     "effstim_vegamag_B_exact": [-2.5 * math.log10(cr_x / vega_b), "VEGAMAG"]})
    return rows


def main():
    write_tables()
    vega = sed_table(VEGA_FILE)
    ref = {"header": {"peer": "synphot", "version": synphot.__version__, "astropy": astropy.__version__,
                      "numpy": np.__version__, "python": sys.version.split()[0],
                      "date": datetime.date.today().isoformat(),
                      "generator": SCRIPT,
                      "vega": f"spectra/{VEGA_FILE} (CALSPEC alpha_lyr_stis_002) as an Empirical1D table",
                      "conventions": "areas in cm^2; count rates in count/s for the area (1 s exposure in radchain); "
                                     "zero-point rates per m^2; bandpasses Empirical1D of the spectra/ tables with "
                                     "fill_value=0; see NOTES.md"},
           "cases": []}
    for case in cases(vega):
        out, chain = compute(case, vega)
        entry = {"id": case.cid, "title": case.title, "origin": case.origin,
                 "inputs": {"sed": case.sed_call, "system": case.system, "magnitude": case.magnitude,
                            "band_A": names(case.band_a) if case.band_a[0] != "Box1D" else "Box1D(1, 5500 A, 1 A)",
                            "band_B": names(case.band_b), "area_cm2": case.area_cm2},
                 "synphot_calls": chain,
                 "outputs": {k: {"value": v, "unit": un} for k, (v, un) in out.items()},
                 "radchain_file": f"validation/synphot/{case.cid}.toml"}
        rows = table_rows(case, vega)
        if rows:
            entry["table"] = rows
        ref["cases"].append(entry)
        (HERE / f"{case.cid}.toml").write_text(toml_text(case, out))
    (HERE / "reference.json").write_text(json.dumps(ref, indent=1) + "\n")
    print(f"{len(ref['cases'])} cases written to {HERE}")


if __name__ == "__main__":
    main()
