#!/usr/bin/env python3
"""Write the radchain sensor files of pyBSM's geometry + MTF cases (B1-B7 of reference.json).

    /usr/bin/python3 validation/pybsm/write_sensors.py

Each file is the case's camera in radchain with pyBSM's conventions switched on in the giqe criterion
(edge_integration = "pybsm", elevation = "sensor"; CONVENTIONS.md, items 4 and 5) and an [expected] entry per
quantity pyBSM computed, at the precision both compute it to. Quantities radchain models differently (pyBSM's
phase-screen wavefront OTF, GIQE-4 with its 0.334 noise coefficient) are left out with the reason in the file.
Reads reference.json only; pyBSM is not needed.
"""
import json
import math
import pathlib

HERE = pathlib.Path(__file__).resolve().parent
NYQUIST = 3  # index of 1.0 x Nyquist in mtf_frequencies.nyquist_fraction


def entry(result, value, tolerance, what, case, unit=""):
    v = f'"{value!r} {unit}"' if unit else repr(value)
    t = f'"{tolerance:g} {unit}"' if unit else f"{tolerance:g}"
    return (f'"{result}" = {{ value = {v}, tolerance = {t}, kind = "peer", '
            f'source = "pyBSM {COMMIT8} {what}, case {case}" }}')


def write(case):
    i, o = case["inputs"], case["outputs"]
    cid = i["name"].split("-")[0]
    slug = i["name"].lower()
    nadir = o["nadir_angle_rad"]["value"]
    lines = [
        f"# pyBSM peer case {cid} (validation/pybsm/reference.json, kind \"mtf_geometry\"): {case.get('doc', '')}.",
        "# Written by validation/pybsm/write_sensors.py from reference.json; do not edit by hand. pyBSM takes the",
        "# ground range and computes the angle at the sensor (geospatial.nadir_angle); radchain takes the look angle,",
        "# so roll = pyBSM's nadir angle, on pyBSM's sphere (R = 6378.164 km). pyBSM's conventions are switched on in",
        "# [criteria.iq]: its edge-response rule and its elevation (validation/pybsm/CONVENTIONS.md, items 4 and 5).",
        "",
        "[sensor]",
        f'name = "pyBSM peer case {cid}: {i["altitude"] / 1e3:g} km, {i["ground_range"] / 1e3:g} km ground range, '
        f'D {i["D"]:g} m, f\' {i["f"]:g} m, p {i["p_x"] * 1e6:g} um, {i["wavelength_um"] * 1e3:g} nm"',
        f'reference = "Kitware/pybsm {COMMIT} (geospatial, otf.functional.common_OTFs, metrics.functional.giqe5); '
        f'validation/pybsm/reference.json case {cid}"',
        "",
        "[platform]",
        'plugin = "earth_orbit"',
        f'altitude = "{i["altitude"]:g} m"',
        f'roll = "{nadir!r} rad"' + ("" if nadir else "                     # nadir"),
        'earth_radius = "6378.164 km"          # pyBSM geospatial.r_earth',
        "",
        "[optics]",
        'plugin = "telescope"',
        f'aperture = "{i["D"]:g} m"',
        f'focal_length = "{i["f"]:g} m"',
    ]
    if i.get("eta"):
        lines.append(f'obscuration = {i["eta"]:g}                  # pyBSM eta')
    lines += [
        "",
        "[detector]",
        'plugin = "pixel_array"',
        f'pixel_pitch = "{i["p_x"] * 1e6:g} um"',
        "pixel_count = 10000",
        "",
        "[criteria.iq]",
        'plugin = "giqe"',
        "niirs = 1",
        "informational = true                 # a peer comparison, not a requirement",
        f'wavelength = "{i["wavelength_um"] * 1e3:g} nm"',
        f'snr = {i["snr"]:g}',
        'edge_integration = "pybsm"           # pyBSM metrics.functional.edge_response: 50-node trapezoid',
        'elevation = "sensor"                 # pyBSM niirs5: elev = pi/2 - geospatial.nadir_angle',
    ]
    if i.get("s_x"):
        assert i["s_x"] == i["s_y"], "radchain has one jitter for both axes"
        lines.append(f'jitter_rms = "{i["s_x"] * i["f"] * 1e6:.12g} um"   # pyBSM s_x = s_y = {i["s_x"]:g} rad, times f\'')
    if i.get("da_x"):
        assert not i.get("da_y"), "radchain smears along one axis"
        ifov = i["p_x"] / i["f"]
        smear = i["da_x"] * i["int_time"] / ifov
        lines.append(f"smear_pixels = {smear:.12g}             # pyBSM drift da_x t / ifov (one axis; GIQE-5 weights "
                     "the axes symmetrically)")
    lines += ["", "[expected]"]
    e = []
    e.append(entry("platform.slant_range", o["slant_range_m"]["value"], 1e-6, "geospatial.curved_earth_slant_range",
                   cid, "m"))
    e.append(entry("criteria.iq.gsd_normal_plane", o["gsd_m"]["value"], 1e-9 * o["gsd_m"]["value"],
                   "geospatial.ground_sample_distance", cid, "m"))
    mu = o["mtf_u"]
    e.append(entry("criteria.iq.mtf_nyquist_diffraction", mu["diffraction"]["values"][NYQUIST], 1e-9,
                   "otf.functional.circular_aperture_OTF at 0.5/ifov", cid))
    e.append(entry("criteria.iq.mtf_nyquist_pixel", mu["detector"]["values"][NYQUIST], 1e-12,
                   "otf.functional.detector_OTF at 0.5/ifov", cid))
    phase_screen = i.get("pv")
    if phase_screen:
        lines.insert(len(lines) - 2, "")
        lines.insert(len(lines) - 2,
                     "# Not compared: pyBSM's wavefront OTF is Goodman's random phase screen (wavefront_OTF), radchain's "
                     "Shannon's\n# aberration factor (CONVENTIONS.md, item 7); the system MTF, RER and NIIRS follow "
                     "from it. Geometry and\n# the other components are compared.")
    else:
        other = mu["jitter"]["values"][NYQUIST] * mu["drift"]["values"][NYQUIST]
        e.append(entry("criteria.iq.mtf_nyquist_other", other, 1e-12, "jitter_OTF x drift_OTF at 0.5/ifov", cid))
        e.append(entry("criteria.iq.mtf_nyquist_system", mu["system"]["values"][NYQUIST], 1e-9,
                       "common_OTFs.system_OTF at 0.5/ifov", cid))
        e.append(entry("criteria.iq.rer", o["rer_giqe5"]["value"], 1e-9, "metrics.functional.giqe5 weighted RER", cid))
        e.append(entry("criteria.iq.gsd_inches", o["gsd_w_m"]["value"] / 0.0254, 1e-9 * o["gsd_w_m"]["value"] / 0.0254,
                       "giqe5 GSD_W = gsd / sin(elev)^0.25, in inches", cid))
        e.append(entry("criteria.iq.niirs", o["niirs_giqe5"]["value"], 1e-8, "metrics.functional.giqe5", cid))
    lines += e
    lines.append("")
    path = HERE / f"case-{slug}.toml"
    path.write_text("\n".join(lines))
    return path


if __name__ == "__main__":
    reference = json.loads((HERE / "reference.json").read_text())
    COMMIT = reference["header"]["commit"]
    COMMIT8 = COMMIT[:8]
    for old in HERE.glob("case-b*.toml"):
        old.unlink()
    for case in reference["cases"]:
        if case["kind"] == "mtf_geometry":
            print(write(case).relative_to(HERE.parent.parent))
