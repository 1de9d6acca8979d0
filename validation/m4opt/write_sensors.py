#!/usr/bin/python3
"""Write the radchain sensor files of validation/m4opt/ from reference.json (run generate.py first).

    /usr/bin/python3 validation/m4opt/write_sensors.py

Every number a file checks is taken from reference.json; the mapping m4opt -> radchain is in CONVENTIONS.md:
  * m4opt Detector(area = pi (D/2)^2) -> telescope aperture D, obscuration 0, transmittance 1;
  * bandpass (total throughput, a Gaussian) -> the detector's qe_curve (spectra/m4opt_*_gaussian.csv) and the
    target's band; gain g (astropy's signal_to_noise_oir_ccd multiplies source and sky, not dark, by it) -> qe = g;
  * plate_scale (pixel solid angle) -> 10 um pixels and f' = 10 um / pixel angle;
  * npix = 4 pi with aperture_correction = 1 -> photometry = "circle" of radius 2 pixels (area pi 2^2 = 4 pi pixels)
    around a PSF far smaller than the circle (a 1 um FWHM Gaussian: encircled energy 1 - exp(-2 ln2 (40)^2) = 1);
  * read_noise -> dark_noise (sigma_d0); dark_noise (rate) -> dark_current; quantisation 1/(12 K^2) made negligible
    with K = 1000 DN/e- (32-bit ADC, saturation 1e9 e-: never reached);
  * background -> `site` sky (airmass 1, no extinction): the m4opt background's count rate through the band as a
    flat-f_nu AB mag/arcsec^2 (`sky_brightness`), or the STIS zodiacal table itself (`sky_table`); or radchain's own
    zodiacal model (`space`) for the comparison files named *-radchain-zodi.
"""
import json
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))

MISSIONS = {
    "ultrasat": dict(name="ULTRASAT", aperture="33 cm", pixel_arcsec=5.4, csv={"NUV": "m4opt_ultrasat_nuv_gaussian.csv"},
                     where="src/m4opt/missions/_ultrasat/__init__.py"),
    "uvex": dict(name="UVEX", aperture="75 cm", pixel_arcsec=1.0,
                 csv={"FUV": "m4opt_uvex_fuv_gaussian.csv", "NUV": "m4opt_uvex_nuv_gaussian.csv"},
                 where="src/m4opt/missions/_uvex/__init__.py"),
}


def focal_length_m(pixel_arcsec, pitch_m=10e-6):
    return pitch_m / (pixel_arcsec * math.pi / (180 * 3600))


def sensor(ref, case, t, atmosphere, expected, extra_comment="", table=None, solve=None, magnitude=None):
    m = MISSIONS[case["mission"]]
    band = case["band"]
    d = case["detector"]
    bp = d["bandpass"]
    csv = m["csv"][band]
    lo, hi = bp["waveset_nm"][0], bp["waveset_nm"][1]
    c8 = ref["commit"][:8]
    f = focal_length_m(m["pixel_arcsec"])
    radius = 2 * m["pixel_arcsec"]
    assert abs(math.pi * 2**2 - d["npix"]) < 1e-12
    solve = solve or dict(unknown="target.magnitude", bracket="[15, 30]")
    lines = [
        f"# {m['name']} {band} as modelled by m4opt (github.com/m4opt/m4opt @ {ref['commit']}, {m['where']}),",
        f"# case \"{case['id']}\" of validation/m4opt/reference.json: {case['description']}.",
        "# m4opt: SNR = t S g / sqrt(t (S g + npix (B g + D)) + npix R^2) (astropy signal_to_noise_oir_ccd), npix = 4 pi,",
        "# S and B by synphot trapezoid on the bandpass grid. Mapping to radchain: validation/m4opt/write_sensors.py",
        "# and CONVENTIONS.md. Written by write_sensors.py from reference.json; do not edit by hand.",
    ]
    if extra_comment:
        lines += ["# " + l for l in extra_comment.split("\n")]
    lines += [
        "",
        "[sensor]",
        f'name = "m4opt {m["name"]} {band}: {case["id"]}"',
        f'reference = "m4opt {c8}: {case["functions"].split(",")[0]}"',
        "",
        "[source]",
        'plugin = "sun"                        # not used (the target is flat in f_nu); a Planck sun has no table limits',
        'model = "planck"',
        'total_irradiance = "1361 W/m2"',
        "",
        *atmosphere,
        "",
        "[target]",
        'plugin = "point_source"',
        'system = "ab"',
        f'band = "{csv}"',
        'sed_shape = "flat_f_nu"               # m4opt: SourceSpectrum(ConstFlux1D, amplitude=0 ABmag)',
        f"magnitude = {magnitude if magnitude is not None else 22}",
        "",
        "[optics]",
        'plugin = "telescope"',
        f'aperture = "{m["aperture"]}"                  # m4opt area = pi (D/2)^2',
        "obscuration = 0",
        "transmittance = 1                     # the whole throughput is the Gaussian qe_curve",
        f'focal_length = "{f:.15g} m"    # 10 um pixels of {m["pixel_arcsec"]:g} arcsec (m4opt plate_scale = its square)',
        'psf = "gaussian"                      # far smaller than the 2-pixel circle: encircled energy 1 (m4opt aperture_correction = 1)',
        'gaussian_fwhm = "1 um"',
        "",
        "[detector]",
        'plugin = "emva1288"',
        f'qe_curve = "{csv}"',
        f"qe = {d['gain']:g}                               # m4opt gain g multiplies source and sky (not dark) counts",
        f'band_min = "{lo:g} nm"',
        f'band_max = "{hi:g} nm"',
        f'integration_time = "{t:g} s"',
        'gain = "1000 DN/e-"                   # quantisation 1/(12 K^2) negligible (m4opt has none)',
        f'read_noise = "{d["read_noise_e"]:g} e-"                  # m4opt read_noise',
        f'dark_current = "{d["dark_rate_per_pixel_s"]:.10g} e-/s"       # m4opt dark_noise (per pixel)',
        'full_well = "1e9 e-"',
        "adc_bits = 32",
        'pixel_pitch = "10 um"',
        'photometry = "circle"                 # area pi (2 px)^2 = 4 pi pixels = m4opt npix',
        f'aperture_radius = "{radius:g} arcsec"',
        "",
        "[criteria.detection]",
        'plugin = "snr_threshold"',
        "threshold = 5",
        "",
        "[[solve]]",
        f'unknown = "{solve["unknown"]}"',
        'criterion = "detection"',
        f"bracket = {solve['bracket']}",
        "",
        "[expected]",
    ]
    for key, (value, tol, what, *unit) in expected.items():
        if unit:  # a dimensional result: value and tolerance carry the unit (tolerance given as relative here)
            v, t_ = f'"{value:.10g} {unit[0]}"', f'"{abs(value) * tol:.3g} {unit[0]}"'
        else:
            v, t_ = repr(value), f"{tol:g}"
        lines.append(f'"{key}" = {{ value = {v}, tolerance = {t_}, kind = "peer", source = "m4opt {c8} {what}" }}')
    if table:
        lines += ["", "[[table]]"] + table
    return "\n".join(lines) + "\n"


def site(sky_key_lines, comment):
    return ["[atmosphere]", f"plugin = \"site\"                       # {comment}", "airmass = 1", "extinction = 0",
            *sky_key_lines]


def main():
    ref = json.load(open(os.path.join(HERE, "reference.json")))
    cases = {c["id"]: c for c in ref["cases"]}
    files = {}

    def zp(c):
        return 2.5 * math.log10(c["source_rate_AB0_per_s"])

    # 1. m4opt's pinned ULTRASAT test: total sky (galactic + zodiacal + Cerenkov inferred from the pin) as a flat sky
    c = cases["ultrasat_test_limmag"]
    sky = c["background_AB_mag_arcsec2_in_band"]
    bk = c["background_rate_per_pixel_per_s"]
    files["ultrasat-test-limmag.toml"] = sensor(
        ref, c, 300,
        site([f"sky_brightness = {sky!r}   # m4opt's total background rate through the band (pinned test) as AB mag/arcsec^2"],
             "space: no extinction, no seeing; the sky given as m4opt's"),
        {"target.magnitude": (c["limmag"]["300 s"], 0.001, "test_ultrasat_limmag (pinned), 300 s (case 1)"),
         "detector.instrumental_zero_point": (zp(c), 0.0005, "Detector._get_count_rates source rate of AB 0 (case 1)"),
         "detector.sky_electrons_per_pixel": (bk["total_inferred_from_pin_300s"] * 300, 1e-4,
                                              "sky rate per pixel x 300 s, from the pinned limits (case 1)", "electron")},
        extra_comment="The Cerenkov part of the sky (AE8 model, not runnable here) is inferred from the pinned limits.",
        table=['name = "5-sigma limit, m4opt test exposures"', 'vary = "detector.integration_time"',
               'values = ["300 s", "900 s"]', 'results = ["target.magnitude", "detector.sky_electrons_per_pixel"]'],
        magnitude=21.6)

    # 2. zodiacal "high": the STIS table itself as the sky (spectral path)
    c = cases["ultrasat_zodi_high"]
    files["ultrasat-zodi-high-table.toml"] = sensor(
        ref, c, 300,
        site(['sky_table = "m4opt_stis_zodi_high.csv"   # ZodiacalBackground.high() as given (per arcsec^2)'],
             "space: no extinction, no seeing"),
        {"target.magnitude": (c["limmag"]["300 s"], 0.001, "Detector.get_limmag, ZodiacalBackground.high(), 300 s (case ultrasat_zodi_high)"),
         "detector.sky_electrons_per_pixel": (c["background_rate_per_pixel_per_s"] * 300, 1.5e-3,
                                              "Detector._get_count_rates background x 300 s (case ultrasat_zodi_high); "
                                              "known -0.10 %: synphot interpolates the table in photon flux, radchain in "
                                              "energy flux, and samples it on the bandpass grid only (CONVENTIONS.md)", "electron")},
        table=['name = "5-sigma limit vs exposure"', 'vary = "detector.integration_time"', 'values = ["300 s", "900 s"]',
               'results = ["target.magnitude", "detector.sky_electrons_per_pixel"]'])

    # 3. zodiacal "mid", flat sky, and the exposure time to SNR 5 at AB 22
    c = cases["ultrasat_zodi_mid"]
    files["ultrasat-zodi-mid.toml"] = sensor(
        ref, c, 300,
        site([f"sky_brightness = {c['background_AB_mag_arcsec2_in_band']!r}   # ZodiacalBackground.mid() through the band"],
             "space: no extinction, no seeing"),
        {"target.magnitude": (c["limmag"]["300 s"], 0.001, "Detector.get_limmag, ZodiacalBackground.mid(), 300 s (case ultrasat_zodi_mid)")},
        table=['name = "5-sigma limit vs exposure"', 'vary = "detector.integration_time"', 'values = ["300 s", "900 s"]',
               'results = ["target.magnitude"]'])
    files["ultrasat-zodi-mid-exptime.toml"] = sensor(
        ref, c, 400,
        site([f"sky_brightness = {c['background_AB_mag_arcsec2_in_band']!r}   # ZodiacalBackground.mid() through the band"],
             "space: no extinction, no seeing"),
        {"detector.integration_time": (c["exptime_s"]["AB 22, SNR 5"], 1e-4,
                                       "Detector.get_exptime (exptime_oir_ccd), AB 22, SNR 5 (case ultrasat_zodi_mid)", "s")},
        solve=dict(unknown="detector.integration_time", bracket='["10 s", "10000 s"]'), magnitude=22.0)

    # 4. zodiacal light at ecliptic positions: m4opt's level as the sky, and radchain's own model beside it
    for dlon, beta in ((90, 30), (180, 0), (0, 90)):
        c = cases[f"ultrasat_zodi_ecliptic_{dlon}_{beta}"]
        g = c["geometry"]
        files[f"ultrasat-zodi-ecliptic-{dlon}-{beta}.toml"] = sensor(
            ref, c, 300,
            site([f"sky_brightness = {c['background_AB_mag_arcsec2_in_band']!r}   # m4opt ZodiacalBackground() at "
                  f"({dlon} deg, {beta} deg): {g['zodiacal_S10']:.4g} S10"], "space: no extinction, no seeing"),
            {"target.magnitude": (c["limmag"]["300 s"], 0.001,
                                  f"Detector.get_limmag, ZodiacalBackground() at lambda-lambda_sun {dlon} deg, beta {beta} deg, 300 s (case {c['id']})")})
    # 5. no background: read noise and dark only
    c = cases["ultrasat_no_background"]
    files["ultrasat-no-background.toml"] = sensor(
        ref, c, 300, ["[atmosphere]", 'plugin = "none"'],
        {"target.magnitude": (c["limmag"]["300 s"], 0.001, "Detector.get_limmag, zero background, 300 s (case ultrasat_no_background)"),
         "detector.instrumental_zero_point": (zp(c), 0.0005, "Detector._get_count_rates source rate of AB 0 (case ultrasat_no_background)")},
        table=['name = "5-sigma limit vs exposure"', 'vary = "detector.integration_time"', 'values = ["300 s", "900 s"]',
               'results = ["target.magnitude"]'])

    # 6. UVEX: full m4opt background (galactic + zodiacal) as a flat sky; zodiacal "high" as the STIS table
    for band in ("FUV", "NUV"):
        c = cases[f"uvex_{band.lower()}_full_background"]
        files[f"uvex-{band.lower()}-full-background.toml"] = sensor(
            ref, c, 900,
            site([f"sky_brightness = {c['background_AB_mag_arcsec2_in_band']!r}   # m4opt Galactic + Zodiacal background through the band"],
                 "space: no extinction, no seeing"),
            {"target.magnitude": (c["limmag"]["900 s"], 0.001, f"Detector.get_limmag, GalacticBackground + ZodiacalBackground, 900 s (case {c['id']})"),
             "detector.instrumental_zero_point": (zp(c) + 2.5 * math.log10(c["detector"]["gain"]), 0.0005,
                                                  f"Detector._get_count_rates source rate of AB 0 x gain (case {c['id']})")},
            table=['name = "5-sigma limit vs exposure"', 'vary = "detector.integration_time"', 'values = ["900 s", "2700 s"]',
                   'results = ["target.magnitude"]'], magnitude=24.5)
        c = cases[f"uvex_{band.lower()}_zodi_high"]
        files[f"uvex-{band.lower()}-zodi-high-table.toml"] = sensor(
            ref, c, 900,
            site(['sky_table = "m4opt_stis_zodi_high.csv"   # ZodiacalBackground.high() as given (per arcsec^2)'],
                 "space: no extinction, no seeing"),
            {"target.magnitude": (c["limmag"]["900 s"], 0.001, f"Detector.get_limmag, ZodiacalBackground.high(), 900 s (case {c['id']})"),
             "detector.sky_electrons_per_pixel": (c["background_rate_per_pixel_per_s"] * 900 * c["detector"]["gain"], {"FUV": 1.3e-2, "NUV": 2.5e-3}[band],
                                                  f"Detector._get_count_rates background x gain x 900 s (case {c['id']}); "
                                                  f"known {dict(FUV='-1.09', NUV='-0.18')[band]} %: table interpolation in "
                                                  "photon vs energy flux and bandpass-grid sampling (CONVENTIONS.md)", "electron")},
            magnitude=24.5)

    # radchain's own zodiacal model at the same positions (Leinert Table 17 at 500 nm x E-490 shape): no [expected]
    # check can hold these to 0.001 mag (CONVENTIONS.md, zodiacal model); the limits are compared in the report
    return files


if __name__ == "__main__":
    for name, text in main().items():
        with open(os.path.join(HERE, name), "w") as f:
            f.write(text)
        print("wrote", name)
