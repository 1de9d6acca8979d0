#!/usr/bin/python3
"""Write the radchain sensor files of validation/instrupy/ from reference.json (run generate.py first).

    /usr/bin/python3 validation/instrupy/write_sensors.py [--write-spectra]

Every number a file checks is taken from reference.json; the instrupy -> radchain mapping is in one place here and
explained in CONVENTIONS.md:
  * instrupy's reflected term (calculate_number_of_signal_electrons -> radiance_with_earth_as_reflector) is the Sun
    as a 6000 K blackbody of radius 6.957e8 m at the computed Sun-target distance d, reflected by a surface of unit
    reflectivity into 4 pi sr: L = E cos(theta_s) cos(theta_v) / (4 pi), E = pi B_6000 (R_sun/d)^2
    -> `sun` model = "planck", temperature 6000 K, total_irradiance = sigma 6000^4 (R_sun / 1 AU)^2 at 1 AU,
       distance d, solar_zenith theta_s; `reflectance_ground` reflectance 0.25 (L = rho E cos theta_s / pi:
       rho = pi/(4 pi)); instrupy's cos(theta_v) cancels against its pixel area 1/cos(theta_v) (CONVENTIONS.md);
  * instrupy's emitted term (radiance_with_earth_as_bb_radiator) is B_T of the targetBlackBodyTemp, photon units
    -> at night (the reflected term is instrupy's 1e-19 "small number"): the ground as a unit-reflectance
       Lambertian mirror of a hemisphere at T: `sun` planck of temperature T with total_irradiance sigma T^4 at 1 AU,
       solar_zenith 0, reflectance 1 (L = E/pi = B_T): radchain has no self-emitting target (CONVENTIONS.md);
    -> by day with both terms (FireSat MWIR): the emitted B_T as the `tabulated_transmittance` atmosphere's
       path radiance table (spectra/instrupy_blackbody_<T>K_radiance.csv, written by --write-spectra), tau = 1;
  * integration time: instrupy's (recorded) -> `integration_time`; pixel: detectorWidth -> pixel_pitch,
    focalLength and apertureDia -> the telescope (obscuration 0, transmittance = opticsSysEff), quantumEff -> qe
    (flat over the box band operatingWavelength +- bandwidth/2);
  * noise sqrt(Ne + numOfReadOutE^2): `emva1288` dark_noise = numOfReadOutE, no dark current, no PRNU/DSNU,
    quantisation = "none" (instrupy has no ADC noise), a 1e12 e- well and a 32-bit ADC (never reached).
"""
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SPECTRA = os.path.normpath(os.path.join(HERE, "..", "..", "spectra"))
SIGMA = 5.670374419e-8  # W m-2 K-4 (CODATA 2018, exact from h, c, k)
AU = 149597870700.0
H, C, K = 6.62607015e-34, 299792458.0, 1.380649e-23

# Tolerances (relative): the tightest that holds, with its reason (CONVENTIONS.md "Deltas"). radchain samples the
# Planck spectrum on its own grid (physics::planck_grid_m: 1 nm from 100 nm to 2.5 um, then 2000 logarithmic steps
# to 100 um, i.e. 0.184 % of lambda: 7.7 nm at 4.2 um, 20 nm at 10.9 um) and integrates the sampled product
# piecewise linearly (trapezoids); instrupy integrates Planck in closed form (Widger & Woodall series). The
# trapezoid error is ~ -h^2 f''/(12 f): negative where the Planck curve is concave (near its peak: the 6000 K Sun
# at 0.4-0.7 um, 290 K at 10.9 um), positive on its convex Wien side (290 K at 3.25-5.15 um). Observed:
# -1.2e-6 .. -1.7e-6 below 2.5 um (1 nm grid), -1.3e-6 at 10.9 um, +8.4e-6 at 3.25-5.15 um (290 K).
TOL_1NM = 5e-6   # bands inside the 1 nm part of the grid (< 2.5 um): 3x the largest observed (1.7e-6)
TOL_LOG = 2e-5   # bands on the logarithmic part (> 2.5 um): 2.4x the largest observed (8.4e-6, FireSat night)


def tolerance(band_max_m):
    return TOL_1NM if band_max_m < 2.5e-6 else TOL_LOG


def planck_radiance_per_nm(lam_m, t):
    x = H * C / (lam_m * K * t)
    return 2 * H * C * C / lam_m ** 5 / math.expm1(x) * 1e-9  # W m-2 sr-1 nm-1


def blackbody_csv(t, lo_m, hi_m, commit):
    name = f"instrupy_blackbody_{t:g}K_radiance.csv"
    lo_nm = math.floor(lo_m * 1e9) - 50
    hi_nm = math.ceil(hi_m * 1e9) + 50
    lines = [
        f"# Planck spectral radiance B_lambda(T = {t:g} K) in W m-2 sr-1 nm-1, 1 nm steps {lo_nm}-{hi_nm} nm: the emitted term of",
        f"# instrupy's passive optical scanner (github.com/EarthObservationSimulator/instrupy @ {commit},",
        "# instrupy/passive_optical_scanner_model.py radiance_with_earth_as_bb_radiator: the Earth as a blackbody at targetBlackBodyTemp),",
        "# for radchain's tabulated_transmittance path_radiance key (radchain has no self-emitting target).",
        "# Processing: B = 2hc^2/lambda^5/(exp(hc/(lambda k T)) - 1), CODATA 2018 exact h, c, k, 12 significant digits;",
        "# linear interpolation between 1 nm rows integrates B to ~1e-7 relative over 3-5 um.",
        "# Written by validation/instrupy/write_sensors.py --write-spectra.",
        "wavelength_nm,radiance_W_m-2_sr-1_nm-1",
    ]
    for nm in range(lo_nm, hi_nm + 1):
        lines.append(f"{nm},{planck_radiance_per_nm(nm * 1e-9, t):.12e}")
    return name, "\n".join(lines) + "\n"


def q(x, unit, fmt="{:.15g}"):
    return f'"{fmt.format(x)} {unit}"'


def sensor(ref, c, temperature_override=None):
    i, m, o = c["inputs"], c["intermediate"], c["outputs"]
    c8 = ref["commit"][:8]
    night = m["sun_below_horizon"]
    t_target = m_t = i["targetBlackBodyTemp_K"] if temperature_override is None else temperature_override
    lam_hi = i["band_max_m"]
    thermal_matters = lam_hi > 2.5e-6  # below, instrupy's B_290 term underflows (<1e-30 of the reflected term)
    suffix = "" if temperature_override is None else f"-T{temperature_override:g}K"
    cid = c["id"] + suffix
    if temperature_override is None:
        ne, snr = o["signal_electrons"], o["snr"]
    else:
        ne = o["signal_electrons_T_plus_1K"]
        snr = ne / math.sqrt(ne + i["numOfReadOutE"] ** 2)
    tol = tolerance(i["band_max_m"])
    spectra = []
    head = [
        f"# {c['instrument']}: {i['name']} as modelled by instrupy's passive optical scanner",
        f"# (github.com/EarthObservationSimulator/instrupy @ {ref['commit']}, {c['spec_file']}"
        + (f", overrides {c['overrides']}" if c["overrides"] else "") + "),",
        f"# case \"{c['id']}\" of validation/instrupy/reference.json; geometry: {c['geometry']['where']}.",
        "# instrupy: Ne = [B_T + E_sun cos(theta_s)/(4 pi)] (photons) x IFOV^2 x pi D^2/4 x tau x t x QE over the box band,",
        "# SNR = Ne / sqrt(Ne + read^2), no atmosphere (atmosLossModel None). Mapping: validation/instrupy/write_sensors.py",
        "# and CONVENTIONS.md. Written by write_sensors.py from reference.json; do not edit by hand.",
    ]
    if c.get("note"):
        head.append(f"# Note: {c['note']}.")
    if temperature_override is not None:
        head.append(f"# Target at T + 1 K = {temperature_override:g} K: instrupy's second call of calculate_number_of_signal_electrons")
        head.append("# (NEdT = sqrt(Ne(T)) / (Ne(T+1) - Ne(T)) from this file and the one at T).")
    lines = head + [
        "",
        "[sensor]",
        f'name = "instrupy {c8}: {cid}"',
        f'reference = "instrupy {c8}: PassiveOpticalScannerModel.calc_data_metrics / calculate_number_of_signal_electrons ({c["spec_file"]})"',
        "",
        "[platform]",
        'plugin = "earth_orbit"                # geometry only: the integration time below is instrupy\'s; its view angle cancels (CONVENTIONS.md)',
        f'altitude = {q(m["altitude_km"], "km")}',
        'earth_radius = "6378.137 km"        # instrupy Constants.radiusOfEarthInKM',
    ]
    # An uncapped pushbroom over a polar orbit's equator crossing (the geometries chosen in generate.py): radchain
    # computes the line time itself, GSD_along / ground speed over the rotating Earth (i = 90 deg, latitude 0:
    # v^2 = v0^2 + (omega R)^2), which is instrupy's angleHeight h / |omega_sat - omega_E z| R (angleHeight = IFOV).
    own_line_time = (i["scanTechnique"] == "PUSHBROOM" and not m["integration_time_capped"]
                     and "nadir_alt_km" in c["geometry"]
                     and abs(math.radians(i["fov_angleHeight_deg"]) / m["iFOV_rad"] - 1) < 1e-12)
    if own_line_time:
        lines += ['inclination = "90 deg"               # the polar orbit of the chosen geometry (generate.py equinox_noon)',
                  'latitude = "0 deg"                   # over the equator: instrupy subtracts the Earth\'s rotation vector']
    lines += [""]
    if night or temperature_override is not None and night:
        lines += [
            "[source]",
            'plugin = "sun"                       # stand-in: a hemisphere at the target temperature (radchain has no emitting target)',
            'model = "planck"',
            f'temperature = "{t_target:g} K"          # instrupy targetBlackBodyTemp' + (" + 1 K" if temperature_override else ""),
            f'total_irradiance = {q(SIGMA * t_target ** 4, "W/m2")}   # sigma T^4: E = pi B_T, so L = rho E / pi = B_T',
            'distance = "1 AU"',
            'solar_zenith = "0 deg"',
            "",
            "[atmosphere]",
            'plugin = "none"                      # instrupy atmosLossModel None',
            "",
            "[target]",
            'plugin = "reflectance_ground"        # L = rho E cos(theta_s) / pi = B_T (instrupy radiance_with_earth_as_bb_radiator x its 1/cos view factor)',
            "reflectance = 1",
            "",
        ]
    else:
        e_sun_1au = SIGMA * ref["constants"]["SunBlackBodyTemperature"] ** 4 * (ref["constants"]["SolarRadius_m"] / AU) ** 2
        lines += [
            "[source]",
            'plugin = "sun"                       # instrupy: the Sun as a 6000 K blackbody of radius 6.957e8 m',
            'model = "planck"',
            f'temperature = "{ref["constants"]["SunBlackBodyTemperature"]:g} K"        # instrupy Constants.SunBlackBodyTemperature',
            f'total_irradiance = {q(e_sun_1au, "W/m2")}   # sigma T^4 (R_sun / 1 AU)^2, instrupy Constants.SolarRadius',
            f'distance = {q(m["sun_target_distance_km"] * 1e3, "m")}   # instrupy compute_sun_zenith: Sun-target distance',
            f'solar_zenith = {q(math.degrees(m["solar_zenith_rad"]), "deg")}   # instrupy compute_sun_zenith',
            "",
        ]
        if thermal_matters:
            csv, text = blackbody_csv(t_target, i["band_min_m"], i["band_max_m"], ref["commit"])
            spectra.append((csv, text))
            lines += [
                "[atmosphere]",
                'plugin = "tabulated_transmittance"   # tau = 1 (instrupy atmosLossModel None); the path radiance carries the emitted B_T',
                'table = "instrupy_unit_transmittance.csv"',
                "down_path = false",
                f'path_radiance = "{csv}"   # B_T of targetBlackBodyTemp: instrupy radiance_with_earth_as_bb_radiator',
                "",
            ]
            spectra.append(("instrupy_unit_transmittance.csv", "\n".join([
                "# Transmittance 1 at every wavelength (two rows, linear between): no atmosphere, for radchain files that need a",
                "# tabulated_transmittance only to carry a path radiance table (validation/instrupy: instrupy's emitted term).",
                "# Source: none (a definition). Written by validation/instrupy/write_sensors.py --write-spectra.",
                "wavelength_nm,transmittance", "10,1", "1000000,1"]) + "\n"))
        else:
            lines += ["[atmosphere]", 'plugin = "none"                      # instrupy atmosLossModel None', ""]
        lines += [
            "[target]",
            'plugin = "reflectance_ground"        # L = rho E cos(theta_s)/pi; instrupy E cos(theta_s)/(4 pi): rho = 1/4',
            "reflectance = 0.25",
            "",
        ]
    lines += [
        "[optics]",
        'plugin = "telescope"',
        f'aperture = {q(i["apertureDia_m"] * 1e3, "mm")}        # instrupy apertureDia (its Fnum {i["Fnum"]:g} is not used in its radiometry)',
        f'focal_length = {q(i["focalLength_m"] * 1e3, "mm")}    # instrupy focalLength',
        "obscuration = 0",
        f'transmittance = {i["opticsSysEff"]:.15g}                # instrupy opticsSysEff',
        "",
        "[detector]",
        'plugin = "emva1288"',
        f'pixel_pitch = {q(i["detectorWidth_m"] * 1e6, "um")}      # instrupy detectorWidth (IFOV = p / f)',
        f'band_min = {q(i["band_min_m"] * 1e9, "nm")}   # operatingWavelength - bandwidth/2',
        f'band_max = {q(i["band_max_m"] * 1e9, "nm")}   # operatingWavelength + bandwidth/2',
        f'qe = {i["quantumEff"]:.15g}                           # instrupy quantumEff, flat over the band',
        (f'# integration_time: not given: radchain\'s line time GSD_along / ground speed, checked below against instrupy\'s {m["integration_time_s"]:.10g} s'
         if own_line_time else
         f'integration_time = {q(m["integration_time_s"], "s")}   # instrupy calculate_integration_time'
         + (" (capped at maxDetectorExposureTime)" if m["integration_time_capped"] else f" ({i['scanTechnique']}, access time)")),
        f'read_noise = "{i["numOfReadOutE"]:g} e-"                # instrupy numOfReadOutE',
        'dark_current = "0 e-/s"',
        'gain = "1 DN/e-"',
        'quantisation = "none"                # instrupy has no ADC noise',
        'full_well = "1e12 e-"      # never reached (instrupy has no well)',
        "adc_bits = 32",
        "",
        "[expected]",
        f'# tolerance {tol:g} relative: radchain integrates its sampled Planck grid by trapezoids, instrupy in closed form',
        f'"detector.signal_electrons" = {{ value = "{ne:.10g} e-", tolerance = "{tol * ne:.3g} e-", kind = "peer", '
        f'source = "instrupy {c8} calculate_number_of_signal_electrons, case {cid} (tolerance {tol:g} relative: radchain\'s sampled Planck grid, CONVENTIONS.md)" }}',
        f'"detector.snr" = {{ value = {snr:.10g}, tolerance = {tol * snr:.3g}, kind = "peer", '
        f'source = "instrupy {c8} calc_data_metrics SNR = Ne/sqrt(Ne + read^2), case {cid} (tolerance {tol:g} relative, CONVENTIONS.md)" }}',
    ]
    if own_line_time:
        t = m["integration_time_s"]
        lines.append(f'"detector.integration_time" = {{ value = "{t:.12g} s", tolerance = "{1e-9 * t:.3g} s", kind = "peer", '
                     f'source = "instrupy {c8} calculate_integration_time (PUSHBROOM: angleHeight h / footprint speed), case {cid} (1e-9 relative: same closed form, rounding only)" }}')
    return cid, "\n".join(lines) + "\n", spectra


def main():
    ref = json.load(open(os.path.join(HERE, "reference.json")))
    write_spectra = "--write-spectra" in sys.argv
    written = []
    for c in ref["cases"]:
        variants = [None]
        if c["outputs"]["nedt_K"] not in ("inf", None):
            variants.append(c["inputs"]["targetBlackBodyTemp_K"] + 1)
        for v in variants:
            cid, text, spectra = sensor(ref, c, v)
            with open(os.path.join(HERE, cid + ".toml"), "w") as f:
                f.write(text)
            written.append(cid)
            for name, body in spectra:
                path = os.path.join(SPECTRA, name)
                if write_spectra:
                    with open(path, "w") as f:
                        f.write(body)
                elif not os.path.exists(path):
                    sys.exit(f"{path} missing: run with --write-spectra")
    print("wrote", len(written), "files:", " ".join(written))


if __name__ == "__main__":
    main()
