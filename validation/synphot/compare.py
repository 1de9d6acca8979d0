#!/usr/bin/python3
"""radchain vs synphot, per case: every [expected] quantity, plus what [expected] cannot hold (one result per entry):
effstim magnitudes in band B and colours, which are differences of two radchain results (or of two files), and the
rows of the blackbody temperature tables.

    RADCHAIN=$PWD/out/pch/radchain RADCHAIN_PLUGIN_PATH=$PWD/out/pch/plugins RADCHAIN_DATA_PATH=$PWD/spectra \
        /usr/bin/python3 validation/synphot/compare.py [--markdown]

Exit status 1 if any delta exceeds its tolerance (1e-4 relative for rates, 1e-4 mag for magnitudes and colours).
"""
import json
import math
import os
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
RADCHAIN = os.environ.get("RADCHAIN", str(ROOT / "out/pch/radchain"))
TOL_REL, TOL_MAG = 1e-4, 1e-4


def run(cid):
    env = dict(os.environ)
    env.setdefault("RADCHAIN_PLUGIN_PATH", str(ROOT / "out/pch/plugins"))
    env.setdefault("RADCHAIN_DATA_PATH", str(ROOT / "spectra"))
    p = subprocess.run([RADCHAIN, "run", str(HERE / f"{cid}.toml"), "--format", "json"], capture_output=True, text=True,
                       env=env)
    d = json.loads(p.stdout)
    return {r["name"]: r["value_si"] for r in d["results"]}, d.get("tables", [])


def main():
    ref = json.loads((HERE / "reference.json").read_text())
    cases = {c["id"]: c for c in ref["cases"]}
    rc, tables = {}, {}
    for cid in cases:
        rc[cid], tables[cid] = run(cid)
    rows, bad = [], 0

    def row(cid, quantity, r, s, kind, note=""):
        nonlocal bad
        if kind == "rel":
            delta = r / s - 1.0
            ok = abs(delta) <= TOL_REL
        else:
            delta = r - s
            ok = abs(delta) <= TOL_MAG
        bad += not ok
        rows.append((cid, quantity, r, s, delta, kind, "ok" if ok else "FAIL", note))

    for cid, c in cases.items():
        o = {k: v["value"] for k, v in c["outputs"].items()}
        r = rc[cid]
        area_m2 = c["inputs"]["area_cm2"] * 1e-4
        analytic = "countrate_exact" in o
        row(cid, "countrate (image_electrons, 1 s)", r["detector.image_electrons"], o["countrate_unbinned"], "rel",
            "info: binned=False, native" if analytic else "binned=False")
        row(cid, "countrate, synphot binned (default)", r["detector.image_electrons"], o["countrate"], "rel", "info")
        if analytic:
            row(cid, "countrate, synphot on the dense grid", r["detector.image_electrons"], o["countrate_exact"], "rel",
                "exact integral")
            row(cid, "instrumental zero point, dense grid", r["detector.instrumental_zero_point"],
                o["instrumental_zero_point_exact"], "mag", "exact integral")
        row(cid, "instrumental zero point", r["detector.instrumental_zero_point"], o["instrumental_zero_point"], "mag",
            "info: native" if analytic else "m - effstim(OBMAG)")
        zp_key = "zero_point_rate_A_dense" if ("zero_point_rate_A_dense" in o and c["inputs"]["band_A"] !=
                                               "Box1D(1, 5500 A, 1 A)") else "zero_point_rate_A"
        row(cid, f"zero point rate in A ({c['inputs']['system']})", r["target.zero_point_photon_rate"], o[zp_key], "rel",
            zp_key)
        row(cid, "AB zero point rate in B", r["detector.ab_zero_point_electron_rate"], o["ab_zero_point_rate_B_dense"],
            "rel", "dense grid")
        row(cid, "AB zero point rate in B, synphot native", r["detector.ab_zero_point_electron_rate"],
            o["ab_zero_point_rate_B"], "rel", "info: band's own nodes")
        # effstim(ABmag) in B from two radchain results: m_AB = -2.5 lg(S / (t A N_AB,0))
        m_ab = -2.5 * math.log10(r["detector.image_electrons"] / (area_m2 * r["detector.ab_zero_point_electron_rate"]))
        row(cid, "effstim ABmag in B (derived)", m_ab, o["effstim_abmag_exact"], "mag", "S / (A N_AB,0); exact effstim")
        row(cid, "effstim ABmag in B, synphot native", m_ab, o["effstim_abmag"], "mag", "info: native effstim")
        if c["inputs"]["band_A"] == c["inputs"]["band_B"] and c["inputs"]["system"] == "st":
            pass
    # colours: m_B - m_A in VEGAMAG (blackbody vs Vega files) and ABmag (power law)
    for b, name in (("B", "B-V"), ("R", "V-R"), ("I", "V-I")):
        cid = f"bb5800_V_to_{b}"
        zp = rc[f"vega_bessell_{b}"]["detector.instrumental_zero_point"]  # 2.5 lg(Vega's counts in b)
        m_b = zp - (rc[cid]["detector.instrumental_zero_point"] - 0.0)  # V = 0: m_b = ZP_b - 2.5 lg S_b
        colour = m_b if b == "B" else -m_b
        syn = cases[cid]["outputs"]["effstim_vegamag_exact"]["value"]
        row(cid, f"colour {name} (VEGAMAG) of 5800 K", colour, syn if b == "B" else -syn, "mag",
            f"IZP(vega_bessell_{b}) - IZP({cid}); exact")
        syn = cases[cid]["outputs"]["effstim_vegamag"]["value"]
        row(cid, f"colour {name} (VEGAMAG), synphot native", colour, syn if b == "B" else -syn, "mag",
            "info: native effstim(VEGAMAG)")
        # table rows: every temperature
        t = tables[cid][0]
        for ts, (elec, izp), srow in zip(t["values_si"], t["rows_si"], cases[cid]["table"]):
            row(cid, f"  T = {ts:g} K: countrate", elec, srow["countrate_exact"][0], "rel", "table row, exact")
            row(cid, f"  T = {ts:g} K: countrate, native", elec, srow["detector.image_electrons"][0], "rel",
                "info: table row, native")
            c_rc = zp - izp
            for key, note in (("effstim_vegamag_B_exact", "table row, exact"), ("effstim_vegamag_B", "info: native")):
                c_syn = srow[key][0]
                row(cid, f"  T = {ts:g} K: {name}{'' if 'exact' in key else ', native'}", c_rc if b == "B" else -c_rc,
                    c_syn if b == "B" else -c_syn, "mag", note)
    for b, name in (("g", "g-r"), ("i", "r-i")):
        cid = f"powerlaw_sdss_r_to_{b}"
        r = rc[cid]
        m_b = -2.5 * math.log10(r["detector.image_electrons"] / r["detector.ab_zero_point_electron_rate"])  # 1 m^2
        syn = cases[cid]["outputs"]["effstim_abmag_exact"]["value"]
        row(cid, f"colour {name} (AB) of the power law", (m_b - 18.0) if b == "g" else (18.0 - m_b),
            (syn - 18.0) if b == "g" else (18.0 - syn), "mag", "derived")
    # published zero points (synphot computes them too)
    g = rc["vega_gaia_g"]
    row("vega_gaia_g", "Gaia G AB zero point (e-/s, 0.7278 m2)", 2.5 * math.log10(g["detector.ab_zero_point_electron_rate"]
                                                                                  * 0.7278),
        2.5 * math.log10(cases["vega_gaia_g"]["outputs"]["ab_zero_point_rate_B_dense"]["value"] * 0.7278), "mag",
        "Riello 2021: 25.8010")

    md = "--markdown" in sys.argv
    if md:
        print("| case | quantity | radchain | synphot | delta | check | note |\n|---|---|---|---|---|---|---|")
    for cid, q, r, s, d, kind, ok, note in rows:
        dtxt = f"{d:+.2e}" + (" rel" if kind == "rel" else " mag")
        if note.startswith("info"):
            ok = "info" if ok == "ok" else "info!"
        if md:
            print(f"| {cid} | {q} | {r:.10g} | {s:.10g} | {dtxt} | {ok} | {note} |")
        else:
            print(f"{cid:30s} {q:42s} {r:18.10g} {s:18.10g} {dtxt:>14s} {ok:4s} {note}")
    hard = sum(1 for x in rows if x[6] == "FAIL" and not x[7].startswith("info"))
    worst = max((x for x in rows if not x[7].startswith("info")), key=lambda x: abs(x[4]) / (TOL_REL if x[5] == "rel" else TOL_MAG))
    print(f"worst checked delta: {worst[0]} {worst[1].strip()}: {worst[4]:+.2e} {worst[5]}")
    print(f"\n{len(rows)} comparisons, {hard} outside tolerance (info rows excluded: synphot's binned count rate and its "
          "native trapezoid for an analytic spectrum on a coarse band)")
    return 1 if hard else 0


if __name__ == "__main__":
    sys.exit(main())
