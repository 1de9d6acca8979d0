#!/usr/bin/python3
"""Reference numbers from m4opt (github.com/m4opt/m4opt) for radchain's peer validation.

    /usr/bin/python3 validation/m4opt/generate.py /path/to/m4opt-src [--commit SHA] [--write-spectra]

/path/to/m4opt-src is a checkout (or `git archive` export) of m4opt: the directory holding src/m4opt. Nothing of m4opt
is copied here: this script imports m4opt's own modules from that path and calls them (its `Detector`,
`countrate`, `ZodiacalBackground`, `GalacticBackground`), and takes the ULTRASAT and UVEX detector definitions by
evaluating the `detector=` argument of the `Mission(...)` call in m4opt's mission files.

Runs on Debian bookworm's /usr/bin/python3 (3.11, numpy 1.24, scipy 1.10, astropy 5.2, synphot 1.1.1) although m4opt
asks for Python >= 3.12 and newer packages; what is stubbed (see install_stubs):
  * typing.override (3.12) -> identity decorator;
  * np.vectorize used as a decorator factory (numpy 2) -> wrapper;
  * m4opt._version (generated at build time) -> "stub";
  * astroquery (SVO filter look-up), dust_extinction + dustmaps (Planck dust map), frozendict: modules that are
    imported but never called on the paths used here (no dust extinction, no SVO bandpass);
  * aep8 (AE8/AP8 radiation-belt model): needed by ULTRASAT's CerenkovBackground and not installable here. The
    Cerenkov term is therefore NOT computed: case 1 infers it from the limiting magnitudes m4opt's own test pins
    (the other two backgrounds, galactic and zodiacal, are computed), and every other ULTRASAT case uses a
    background given explicitly (zodiacal only, or none).
The ULTRASAT observer location (TLE -> sgp4) is not needed: the zodiacal and galactic models ignore it.

--commit: the m4opt commit the source tree is (default: `git rev-parse HEAD` in the tree, if it is a checkout).
--write-spectra: also (re)write the spectra/m4opt_*.csv tables (bandpasses on synphot's own sampling grid, the
STIS "high" zodiacal spectrum) beside radchain's other spectra.
"""
import argparse
import ast
import hashlib
import json
import os
import subprocess
import sys
import types
import typing
import warnings

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.normpath(os.path.join(HERE, "..", ".."))


def install_stubs(src):
    import numpy as np

    if not hasattr(typing, "override"):
        typing.override = lambda f: f
    if np.lib.NumpyVersion(np.__version__) < "2.0.0":
        orig = np.vectorize

        class vectorize(orig):
            def __new__(cls, pyfunc=None, **kw):
                if pyfunc is None:
                    return lambda f: orig(f, **kw)
                return orig(pyfunc, **kw)

        np.vectorize = vectorize

    def missing(*a, **k):
        raise RuntimeError("stubbed dependency: not available in this environment")

    def module(name, **attrs):
        if name in sys.modules:
            return
        try:
            __import__(name)
            return  # the real one is installed
        except ImportError:
            pass
        m = types.ModuleType(name)
        m.__dict__.update(attrs)
        sys.modules[name] = m

    module("m4opt._version", version="unknown")
    module("astroquery")
    module("astroquery.svo_fps", SvoFps=missing)
    module("dust_extinction")
    module("dust_extinction.parameter_averages", G23=lambda: None)
    module("dustmaps")
    module("dustmaps.planck", PlanckGNILCQuery=missing)
    module("frozendict", frozendict=dict)
    module("aep8", flux=missing)
    sys.path.insert(0, os.path.join(src, "src"))


def git_blob_sha1(path):
    data = open(path, "rb").read()
    return hashlib.sha1(b"blob %d\0" % len(data) + data).hexdigest()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("src")
    ap.add_argument("--commit")
    ap.add_argument("--write-spectra", action="store_true")
    ap.add_argument("--out", default=os.path.join(HERE, "reference.json"))
    args = ap.parse_args()
    src = os.path.abspath(args.src)
    commit = args.commit
    if commit is None:
        try:
            commit = subprocess.check_output(["git", "-C", src, "rev-parse", "HEAD"], text=True).strip()
        except Exception:
            sys.exit("not a git checkout: give --commit")

    install_stubs(src)
    warnings.simplefilter("ignore")
    import numpy as np
    import synphot
    from astropy import units as u
    from astropy.coordinates import EarthLocation, GeocentricTrueEcliptic, SkyCoord, get_sun
    from astropy.time import Time
    from astropy.utils import iers
    from synphot import ConstFlux1D, Gaussian1D, SourceSpectrum, SpectralElement

    iers.conf.auto_download = False  # offline; positions only set the zodiacal/galactic look-up

    from m4opt.synphot import Detector, observing
    from m4opt.synphot._detector import amplitude_oir_ccd, exptime_oir_ccd  # noqa: F401 (named in the json)
    from m4opt.synphot._math import countrate
    from m4opt.synphot.background import GalacticBackground, ZodiacalBackground
    from m4opt.synphot.background._core import BACKGROUND_SOLID_ANGLE
    from m4opt.synphot.background._zodiacal import ZodiacalBackgroundScaleFactor, mag_high

    pkg = os.path.join(src, "src", "m4opt")
    used = [
        "synphot/_detector.py", "synphot/_math.py", "synphot/background/_core.py",
        "synphot/background/_zodiacal/__init__.py", "synphot/background/_zodiacal/data/leinert_zodi.txt",
        "synphot/background/_zodiacal/data/stis_zodi_high.ecsv", "synphot/background/_galactic.py",
        "missions/_ultrasat/__init__.py", "missions/_uvex/__init__.py", "missions/_ultrasat/tests/test_detector.py",
    ]

    def mission_detector(relpath):
        """Evaluate the `detector=` argument of Mission(...) in an m4opt mission file."""
        path = os.path.join(pkg, relpath)
        tree = ast.parse(open(path).read())
        cerenkov = []

        def CerenkovBackground(**kw):  # needs aep8: left out, recorded
            cerenkov.append(kw)
            return SourceSpectrum(ConstFlux1D, amplitude=0 * synphot.units.PHOTLAM)

        for node in ast.walk(tree):
            if isinstance(node, ast.Call) and getattr(node.func, "id", None) == "Mission":
                for kw in node.keywords:
                    if kw.arg == "detector":
                        ns = dict(np=np, u=u, Detector=Detector, SpectralElement=SpectralElement,
                                  Gaussian1D=Gaussian1D, GalacticBackground=GalacticBackground,
                                  ZodiacalBackground=ZodiacalBackground, CerenkovBackground=CerenkovBackground)
                        return eval(compile(ast.Expression(kw.value), path, "eval"), ns), cerenkov
        raise RuntimeError(f"no Mission(detector=...) in {path}")

    ultrasat, ultrasat_cerenkov = mission_detector("missions/_ultrasat/__init__.py")
    uvex, _ = mission_detector("missions/_uvex/__init__.py")
    # the ULTRASAT test's pinned values (assert_almost_equal, 7 decimals), read from the test file itself
    test_src = open(os.path.join(pkg, "missions/_ultrasat/tests/test_detector.py")).read()
    pinned = None
    tree = ast.parse(test_src)
    for node in ast.walk(tree):
        if isinstance(node, ast.List) and len(node.elts) == 2 and all(isinstance(e, ast.Constant) for e in node.elts):
            vals = [e.value for e in node.elts]
            if all(isinstance(v, float) for v in vals):
                pinned = vals
    assert pinned is not None

    AB0 = SourceSpectrum(ConstFlux1D, amplitude=0 * u.ABmag)
    ZERO = SourceSpectrum(ConstFlux1D, amplitude=0 * synphot.units.PHOTLAM)
    LOC = EarthLocation.from_geocentric(0 * u.m, 0 * u.m, 0 * u.m)  # ignored by the zodiacal/galactic models
    T0 = Time("2025-05-18T02:48:00Z")  # the ULTRASAT test's epoch
    COORD0 = SkyCoord(ra=180 * u.deg, dec=0 * u.deg)  # the ULTRASAT test's target

    def geometry(coord, obstime):
        frame = GeocentricTrueEcliptic(equinox=obstime)  # as ZodiacalBackgroundScaleFactor.at
        obj = SkyCoord(coord).transform_to(frame)
        sun = get_sun(obstime).transform_to(frame)
        dlon = abs((obj.lon - sun.lon).wrap_at(180 * u.deg).deg)
        scale = ZodiacalBackgroundScaleFactor().at(LOC, coord, obstime)
        vmag = mag_high - 2.5 * np.log10(scale)
        return dict(helioecliptic_longitude_deg=float(dlon), ecliptic_latitude_deg=float(abs(obj.lat.deg)),
                    galactic_latitude_deg=float(coord.galactic.b.deg),
                    zodiacal_scale_to_high=float(scale), zodiacal_V_mag_arcsec2=float(vmag),
                    zodiacal_S10=float(10 ** (-0.4 * (vmag - 10)) * 3600.0**2))

    def ecliptic_coord(dlon_deg, beta_deg, obstime):
        frame = GeocentricTrueEcliptic(equinox=obstime)
        sun = get_sun(obstime).transform_to(frame)
        return SkyCoord(lon=sun.lon + dlon_deg * u.deg, lat=beta_deg * u.deg, frame=frame)

    def rates(det, band, background=None):
        """m4opt Detector._get_count_rates for an AB = 0 flat-f_nu source (under the current `observing`)."""
        if background is not None:
            det = Detector(**{**{f: getattr(det, f) for f in det.__dataclass_fields__}, "background": background})
        src, bkg = det._get_count_rates(AB0, band)
        return det, src.to_value(u.Hz), bkg.to_value(u.Hz)

    def sky_mag(det, band, bkg_rate_per_pixel):
        """The background as a flat-f_nu sky: AB mag/arcsec^2 giving the same count rate through the band."""
        ab_rate = (countrate(AB0, det.bandpasses[band]) * det.area).to_value(u.Hz)
        per_arcsec2 = bkg_rate_per_pixel / det.plate_scale.to_value(u.arcsec**2)
        return float(-2.5 * np.log10(per_arcsec2 / ab_rate))

    def detector_dict(det, band):
        bp = det.bandpasses[band]
        w = bp.waveset.to_value(u.nm)
        m = bp.model
        return dict(
            area_cm2=float(det.area.to_value(u.cm**2)),
            plate_scale_arcsec2=float(det.plate_scale.to_value(u.arcsec**2)),
            npix=float(det.npix), aperture_correction=float(det.aperture_correction),
            read_noise_e=float(det.read_noise), dark_rate_per_pixel_s=float(det.dark_noise.to_value(u.Hz)),
            gain=float(det.gain),
            bandpass=dict(model="synphot Gaussian1D", amplitude=float(m.amplitude.value),
                          mean_nm=float(m.mean.value) / 10, stddev_nm=float(m.stddev.value) / 10,
                          waveset_nm=[float(w[0]), float(w[-1]), len(w)],
                          note="synphot integrates on bandpass.waveset: mean ± 5σ step 0.1σ, right end excluded "
                               "(Gaussian1D.sampleset), trapezoid"),
        )

    def evaluate(det, band, exptimes, snr=5.0, mags_for_exptime=(), snr_for_exptime=5.0):
        src, bkg = det._get_count_rates(AB0, band)
        out = dict(
            source_rate_AB0_per_s=float(src.to_value(u.Hz)),
            background_rate_per_pixel_per_s=float(bkg.to_value(u.Hz)),
            background_AB_mag_arcsec2_in_band=sky_mag(det, band, bkg.to_value(u.Hz)) if bkg.value > 0 else None,
            instrumental_zero_point_AB=float(2.5 * np.log10(src.to_value(u.Hz))),
            limmag={},
            exptime_s={},
        )
        lm = det.get_limmag(snr, np.asarray(exptimes, float) * u.s, AB0, band).to_value(u.mag)
        for t, m in zip(exptimes, np.atleast_1d(lm)):
            out["limmag"][f"{t:g} s"] = float(m)
            mag_spec = SourceSpectrum(ConstFlux1D, amplitude=float(m) * u.ABmag)
            out.setdefault("snr_at_limmag", {})[f"{t:g} s"] = float(det.get_snr(t * u.s, mag_spec, band))
        out["limmag_snr"] = snr
        for mag in mags_for_exptime:
            spec = SourceSpectrum(ConstFlux1D, amplitude=mag * u.ABmag)
            out["exptime_s"][f"AB {mag:g}, SNR {snr_for_exptime:g}"] = float(
                det.get_exptime(snr_for_exptime, spec, band).to_value(u.s))
        return out

    cases = []
    funcs = ("m4opt.synphot.Detector.get_limmag (amplitude_oir_ccd), Detector.get_exptime (exptime_oir_ccd), "
             "Detector.get_snr (astropy.stats.signal_to_noise_oir_ccd), Detector._get_count_rates, "
             "m4opt.synphot._math.countrate")

    # ---- case 1: the ULTRASAT test (pinned), full background; Cerenkov inferred from the pin
    with observing(LOC, COORD0, T0):
        det1, src, bkg_gz = rates(ultrasat, "NUV")
        _, _, zodi = rates(ultrasat, "NUV", ZodiacalBackground())
        _, _, gal = rates(ultrasat, "NUV", GalacticBackground())
        geo = geometry(COORD0, T0)
        lm_noc = ultrasat.get_limmag(5, [300, 900] * u.s, AB0, "NUV").to_value(u.mag)
    t = np.array([300.0, 900.0])
    S = t * 10 ** (-0.4 * np.array(pinned)) * src
    npix, rd, dark = ultrasat.npix, ultrasat.read_noise, ultrasat.dark_noise.to_value(u.Hz)
    sky_total = (S**2 / 25 - S - npix * rd**2) / (npix * t) - dark  # gain 1
    cases.append(dict(
        id="ultrasat_test_limmag", mission="ultrasat", band="NUV",
        description="m4opt's own test (missions/_ultrasat/tests/test_detector.py::test_ultrasat_limmag): 5σ limiting "
                    "AB magnitude of a flat-f_nu source, 300 s and 900 s, target RA 180° Dec 0° at 2025-05-18T02:48Z, "
                    "background GalacticBackground + ZodiacalBackground + CerenkovBackground(factor=21) at the GEO TLE",
        functions=funcs + ", test_ultrasat_limmag",
        pinned=True, detector=detector_dict(ultrasat, "NUV"), geometry=geo,
        limmag={"300 s": pinned[0], "900 s": pinned[1]},
        limmag_without_cerenkov={"300 s": float(lm_noc[0]), "900 s": float(lm_noc[1])},
        source_rate_AB0_per_s=src,
        background_rate_per_pixel_per_s={
            "total_inferred_from_pin_300s": float(sky_total[0]), "total_inferred_from_pin_900s": float(sky_total[1]),
            "zodiacal": zodi, "galactic": gal, "cerenkov_inferred": float(sky_total.mean() - zodi - gal)},
        background_AB_mag_arcsec2_in_band=sky_mag(ultrasat, "NUV", float(sky_total.mean())),
        note="aep8 (AE8/AP8) is not available: the Cerenkov term is the pinned limits' total sky minus the computed "
             "zodiacal and galactic terms. The two exposures give the same total sky to "
             f"{abs(sky_total[0] / sky_total[1] - 1):.1e} (a check of source rate and noise model against the pin).",
        cerenkov_args=ultrasat_cerenkov,
    ))

    # ---- cases 2-4: ULTRASAT with m4opt's fixed zodiacal levels (no position): high / mid / low
    for level in ("high", "mid", "low"):
        det = rates(ultrasat, "NUV", getattr(ZodiacalBackground, level)())[0]
        r = evaluate(det, "NUV", [300, 900], mags_for_exptime=(21.0, 22.0))
        cases.append(dict(id=f"ultrasat_zodi_{level}", mission="ultrasat", band="NUV",
                          description=f"ULTRASAT detector, background = ZodiacalBackground.{level}() only "
                                      f"(STIS 'high' zodiacal spectrum x 10^(-0.4 (V_{level} - 22.1)), "
                                      f"V = {dict(high=22.1, mid=22.7, low=23.3)[level]})",
                          functions=funcs, pinned=False, detector=detector_dict(det, "NUV"), **r))

    # ---- cases 5-7: ULTRASAT, zodiacal light at given ecliptic positions (Leinert via m4opt's table), same epoch
    for dlon, beta in ((90, 30), (180, 0), (0, 90)):
        coord = ecliptic_coord(dlon, beta, T0)
        with observing(LOC, coord, T0):
            det = rates(ultrasat, "NUV", ZodiacalBackground())[0]
            r = evaluate(det, "NUV", [300, 900], mags_for_exptime=(21.0,))
            geo = geometry(coord, T0)
        cases.append(dict(id=f"ultrasat_zodi_ecliptic_{dlon}_{beta}", mission="ultrasat", band="NUV",
                          description=f"ULTRASAT detector, background = ZodiacalBackground() at helioecliptic "
                                      f"longitude {dlon}°, ecliptic latitude {beta}° (epoch {T0.isot})",
                          functions=funcs + ", ZodiacalBackgroundScaleFactor.at", pinned=False,
                          detector=detector_dict(det, "NUV"), geometry=geo, **r))

    # ---- case 8: ULTRASAT with no background at all (read noise + dark only)
    det = rates(ultrasat, "NUV", ZERO)[0]
    r = evaluate(det, "NUV", [300, 900], mags_for_exptime=(21.0,))
    cases.append(dict(id="ultrasat_no_background", mission="ultrasat", band="NUV",
                      description="ULTRASAT detector with a zero background: source shot noise, dark 0.04 e-/s/pixel "
                                  "and read noise 6 e- over 4π pixels only",
                      functions=funcs, pinned=False, detector=detector_dict(det, "NUV"), **r))

    # ---- cases 9-12: UVEX FUV and NUV: full m4opt background (galactic + zodiacal) at the test's target/epoch,
    # and zodiacal "high" only
    for band in ("FUV", "NUV"):
        with observing(LOC, COORD0, T0):
            _, _, zodi = rates(uvex, band, ZodiacalBackground())
            _, _, gal = rates(uvex, band, GalacticBackground())
            r = evaluate(uvex, band, [900, 2700], mags_for_exptime=(24.0,))
            geo = geometry(COORD0, T0)
        r["background_components_per_pixel_per_s"] = dict(zodiacal=zodi, galactic=gal)
        cases.append(dict(id=f"uvex_{band.lower()}_full_background", mission="uvex", band=band,
                          description=f"UVEX {band}, m4opt's background GalacticBackground + ZodiacalBackground at "
                                      f"RA 180° Dec 0°, {T0.isot}; 5σ for 900 s (one dwell) and 2700 s",
                          functions=funcs, pinned=False, detector=detector_dict(uvex, band), geometry=geo, **r))
        det = rates(uvex, band, ZodiacalBackground.high())[0]
        r = evaluate(det, band, [900, 2700], mags_for_exptime=(24.0,))
        cases.append(dict(id=f"uvex_{band.lower()}_zodi_high", mission="uvex", band=band,
                          description=f"UVEX {band}, background = ZodiacalBackground.high() only",
                          functions=funcs, pinned=False, detector=detector_dict(det, band), **r))

    # ---- the zodiacal model's spectrum against radchain's (E-490 solar spectrum at Leinert's 500 nm radiance)
    zhigh = ZodiacalBackground.high()
    zodi_model = dict(
        doctest_pins={"ZodiacalBackground.low()(3000 A) AB": [26.16417045, float(
            ZodiacalBackground.low()(3000 * u.AA, flux_unit=u.ABmag).value)],
            "ZodiacalBackground.mid()(3000 A) AB": [25.56417045, float(
                ZodiacalBackground.mid()(3000 * u.AA, flux_unit=u.ABmag).value)],
            "ZodiacalBackground.high()(3000 A) AB": [24.96417045, float(
                zhigh(3000 * u.AA, flux_unit=u.ABmag).value)]},
        high_V_label=22.1, mag_per_S10="V = 10 - 2.5 lg(S10 / 60^4) = 27.78 - 2.5 lg S10 (same as radchain)",
    )
    # the STIS high spectrum per arcsec^2 at 500 nm, in W m-2 nm-1 arcsec-2 and as S10 at radchain's 1.28e-8 W/m2/sr/um
    flam500 = zhigh(5000 * u.AA, flux_unit=synphot.units.FLAM).value  # erg s-1 cm-2 A-1 per arcsec^2
    L500_si = flam500 * 1e-7 * 1e4 * 1e10 / (np.pi / 180 / 3600) ** 2  # W m-2 sr-1 m-1
    zodi_model["high_radiance_500nm_W_m2_sr_um"] = float(L500_si * 1e-6)
    zodi_model["high_as_S10_at_500nm_radchain_units"] = float(L500_si / (1.28e-8 * 1e6))
    zodi_model["high_S10_from_V_label"] = float(10 ** (-0.4 * (22.1 - 10)) * 3600.0**2)
    # V of the STIS high spectrum through radchain's Johnson V (CDBS johnson_v_004) with radchain's Vega
    try:
        def csv(path):
            rows = [l for l in open(path) if not l.startswith("#")][1:]
            a = np.array([[float(x) for x in l.split(",")] for l in rows])
            return a[:, 0], a[:, 1]
        wv, tv = csv(os.path.join(REPO, "spectra", "johnson_V_stsci_cdbs_johnson_v_004.csv"))
        Vbp = SpectralElement(synphot.Empirical1D, points=wv * 10, lookup_table=tv)
        wg, fg = csv(os.path.join(REPO, "spectra", "vega_alpha_lyr_stis_002.csv"))
        vega = SourceSpectrum(synphot.Empirical1D, points=wg * 10, lookup_table=fg * 100 * synphot.units.FLAM)
        c_z = countrate(zhigh, Vbp).value
        zodi_model["high_V_vega_mag_arcsec2_computed"] = float(-2.5 * np.log10(c_z / countrate(vega, Vbp).value))
        zodi_model["high_V_AB_mag_arcsec2_computed"] = float(-2.5 * np.log10(c_z / countrate(AB0, Vbp).value))
    except OSError:
        pass
    # In-band comparison of the zodiacal models at equal S10 (the label's 187.33 S10 of "high"), each integrated
    # finely (0.0017 nm steps), so that only the models differ: m4opt = STIS high spectrum (linear in photon flux
    # between its 10 nm nodes, as synphot interpolates); radchain = S10 x 1.28e-8 W m-2 sr-1 um-1 x E490(l)/E490(500 nm)
    # (linear in energy flux, as radchain interpolates). Also: how much m4opt's own countrate (trapezoid on the
    # bandpass waveset only) differs from the fine integral of the same spectrum.
    try:
        we, fe = csv(os.path.join(REPO, "spectra", "am0_astm_e490_00a.csv"))
        e500 = np.interp(500.0, we, fe)  # W m-2 nm-1
        s10 = zodi_model["high_S10_from_V_label"]
        hc = 6.62607015e-34 * 299792458.0
        zw = zhigh.waveset.to_value(u.nm)
        zphot = zhigh(zhigh.waveset).value  # PHOTLAM per arcsec^2 = photons s-1 cm-2 A-1 arcsec-2
        arcsec2_sr = (np.pi / 180 / 3600) ** 2
        ratios = {}
        for name, det, band in (("ultrasat NUV", ultrasat, "NUV"), ("uvex NUV", uvex, "NUV"), ("uvex FUV", uvex, "FUV")):
            bp = det.bandpasses[band]
            w0 = bp.waveset.to_value(u.nm)
            lam = np.linspace(w0[0], w0[-1], 200001)  # nm
            T = bp(lam * u.nm).value
            m4_fine = np.trapz(np.interp(lam, zw, zphot) * T, lam * 10)  # photons s-1 cm-2 arcsec-2
            m4_own = countrate(zhigh, bp).to_value(1 / (u.s * u.cm**2))
            # W m-2 sr-1 nm-1: 1 S10 = 1.28e-8 W m-2 sr-1 um-1 = 1.28e-11 W m-2 sr-1 nm-1 at 500 nm
            L = s10 * 1.28e-11 * np.interp(lam, we, fe) / e500
            rc_fine = np.trapz(L * T * lam * 1e-9 / hc, lam) * 1e-4 * arcsec2_sr  # photons s-1 cm-2 arcsec-2
            ratios[name] = dict(m4opt_over_radchain_model_same_S10=float(m4_fine / rc_fine),
                                m4opt_countrate_over_fine_integral=float(m4_own / m4_fine))
        zodi_model["inband_zodiacal_model_ratios"] = ratios
    except OSError:
        pass

    out = dict(
        tool="m4opt", repository="github.com/m4opt/m4opt", commit=commit,
        generated_by="validation/m4opt/generate.py",
        environment=dict(python=sys.version.split()[0], numpy=np.__version__, synphot=synphot.__version__,
                         astropy=__import__("astropy").__version__,
                         stubs="typing.override, np.vectorize decorator, m4opt._version, astroquery, dust_extinction, "
                               "dustmaps, frozendict, aep8 (Cerenkov not computed)"),
        source_files_git_blob_sha1={p: git_blob_sha1(os.path.join(pkg, p)) for p in used},
        conventions=dict(
            snr="SNR = t S g / sqrt(t (S g + npix (B g + D)) + npix R^2) (astropy signal_to_noise_oir_ccd); "
                "S = aperture_correction * area * countrate(source, bp), B = area * plate_scale/1arcsec^2 * "
                "countrate(background per arcsec^2, bp)",
            countrate="trapezoid of photon flux density x throughput on bandpass.waveset",
            AB_zero="astropy u.ABmag: 48.60 mag = 3630.78 Jy",
        ),
        zodiacal_model=zodi_model,
        cases=cases,
    )
    with open(args.out, "w") as f:
        json.dump(out, f, indent=1)
        f.write("\n")
    print(f"wrote {args.out}: {len(cases)} cases, m4opt {commit}")

    if args.write_spectra:
        write_spectra(commit, ultrasat, uvex, zhigh, u, np)


def write_spectra(commit, ultrasat, uvex, zhigh, u, np):
    c8 = commit[:12]
    for name, det, band, where in (
            ("m4opt_ultrasat_nuv_gaussian.csv", ultrasat, "NUV", "missions/_ultrasat/__init__.py"),
            ("m4opt_uvex_fuv_gaussian.csv", uvex, "FUV", "missions/_uvex/__init__.py"),
            ("m4opt_uvex_nuv_gaussian.csv", uvex, "NUV", "missions/_uvex/__init__.py")):
        bp = det.bandpasses[band]
        w0 = bp.waveset.to_value(u.AA)
        # each interval of synphot's grid split in 10: radchain's tables are linear between nodes, and on synphot's
        # own 0.1-sigma grid the linear interpolant's integral is 3e-5 above the Gaussian's (which synphot's
        # trapezoid matches to 1e-8); at 0.01 sigma the difference is ~3e-7
        w = np.concatenate([np.linspace(a, b, 10, endpoint=False) for a, b in zip(w0[:-1], w0[1:])] + [w0[-1:]])
        w = w * u.AA
        v = bp(w).value
        m = bp.model
        with open(os.path.join(REPO, "spectra", name), "w") as f:
            f.write(f"# m4opt's {det is ultrasat and 'ULTRASAT' or 'UVEX'} {band} bandpass: a Gaussian stand-in for the "
                    f"total throughput (optics x filter x QE), synphot Gaussian1D(amplitude={m.amplitude.value:g}, "
                    f"mean={m.mean.value:g} A, stddev={m.stddev.value:g} A)\n")
            f.write(f"# Source: github.com/m4opt/m4opt @ {commit} : src/m4opt/{where} (BSD-3-Clause); "
                    "m4opt documents it as a toy model, not the mission's measured curve\n")
            f.write("# Processing: evaluated by synphot 1.1.1 from the first to the last node of the bandpass's own waveset "
                    "(mean - 5 sigma .. mean + 4.9 sigma, the range m4opt's countrate integrates over) at 0.01 sigma "
                    "steps (each 0.1-sigma synphot interval split in 10, so that linear interpolation reproduces the "
                    "Gaussian's integral to ~3e-7), Angstrom / 10 -> nm, 15 significant digits; written by "
                    "validation/m4opt/generate.py --write-spectra\n")
            f.write("wavelength_nm,throughput\n")
            for wi, vi in zip(w.to_value(u.nm), v):
                f.write(f"{wi:.10g},{vi:.15g}\n")
    w = zhigh.waveset
    flam = zhigh(w, flux_unit="flam").value  # erg s-1 cm-2 A-1 (per arcsec^2)
    with open(os.path.join(REPO, "spectra", "m4opt_stis_zodi_high.csv"), "w") as f:
        f.write("# Zodiacal light, HST STIS Instrument Handbook Table 6.4 'high' zodiacal spectrum (V = 22.1 mag/arcsec^2 "
                "by the handbook's label), as shipped by m4opt\n")
        f.write(f"# Source: github.com/m4opt/m4opt @ {commit} : "
                "src/m4opt/synphot/background/_zodiacal/data/stis_zodi_high.ecsv (BSD-3-Clause carrier; STScI "
                "handbook data)\n")
        f.write("# Original units: Angstrom; erg s-1 cm-2 A-1 arcsec-2. Processing: A / 10 -> nm; values x 1e-2 -> "
                "W m-2 nm-1 arcsec-2 (1 erg s-1 cm-2 A-1 = 1e-7 W / 1e-4 m2 / 0.1 nm = 1e-2 W m-2 nm-1), exact decimal "
                "shift; all rows kept; written by validation/m4opt/generate.py --write-spectra\n")
        f.write("wavelength_nm,surface_brightness_W_m-2_nm-1_arcsec-2\n")
        for wi, vi in zip(w.to_value(u.nm), flam):
            f.write(f"{wi:.10g},{vi * 1e-2:.6g}\n")


if __name__ == "__main__":
    main()
