"""Session.run / evaluate / solve / set against `radchain run` of the same file: bit for bit."""
import json
import math
import warnings
from pathlib import Path

import pytest

import radchain


def same_values(result, cli_json):
    """Every result of the Python run equals the CLI's value_si exactly (NaN where the CLI prints null)."""
    names = [r["name"] for r in cli_json["results"]]
    assert list(result) == names
    for r in cli_json["results"]:
        v = result[r["name"]]
        if r["value_si"] is None:
            assert math.isnan(v), r["name"]
        else:
            assert v == r["value_si"], (r["name"], v, r["value_si"])


def test_run_equals_cli_json_bit_for_bit(cli, sbv):
    r = radchain.load(sbv).run()
    out = cli("run", sbv, "--format", "json").stdout
    assert r.json() == out  # the same report, byte for byte
    ref = json.loads(out)
    same_values(r, ref)
    assert r["target.magnitude"] == ref["solves"][0]["value_si"]
    assert r.passed is ref["passed"] is True
    assert [s.unknown for s in r.solves] == ["target.magnitude"]
    assert r.solves[0].converged and r.solves[0].binding == "detection"
    assert [e.result for e in r.expected] == ["target.magnitude"]
    assert r.expected[0].passed and r.expected[0].printed_si == 15.55


def test_record_and_frame_carry_units_and_equations(cli, sbv):
    r = radchain.load(sbv).run()
    ref = {x["name"]: x for x in cli.json("run", sbv, "--format", "json")["results"]}
    rec = r.record("detector.snr")
    x = ref[rec.name]
    assert (rec.si_unit, rec.unit, rec.stage, rec.equation) == (x["si_unit"], x["unit"], x["stage"], x["equation"])
    assert rec.value == x["value"]
    df = r.frame()
    assert list(df["name"]) == list(ref)
    assert df.loc["detector.snr", "value_si"] == ref["detector.snr"]["value_si"]
    assert df.loc["detector.snr", "equation"] == ref["detector.snr"]["equation"]


def test_load_with_set_equals_cli_set(cli, sbv):
    r = radchain.load(sbv, set={"optics.aperture": "20 cm"}).run()
    assert r.json() == cli("run", sbv, "--set", "optics.aperture=20 cm", "--format", "json").stdout


def test_set_text_then_run_equals_cli(cli, sbv):
    s = radchain.load(sbv)
    base = s.run()["target.magnitude"]
    s.set("optics.aperture", "25 cm")
    r = s.run()
    assert r.json() == cli("run", sbv, "--set", "optics.aperture=25 cm", "--format", "json").stdout
    assert r["target.magnitude"] > base + 0.5  # a bigger pupil sees fainter: 2.5 log10((25/15)^2) ≈ 1.1 mag


def test_set_number_in_si_equals_cli_in_metres(cli, sbv):
    s = radchain.load(sbv)
    s.set("optics.aperture", 0.25, si=True)
    s.set("detector.integration_time", 1.5, si=True)
    assert s.get("optics.aperture") == 0.25
    ref = cli.json("run", sbv, "--set", "optics.aperture=0.25 m", "--set", "detector.integration_time=1.5 s",
                   "--format", "json")
    same_values(s.run(), ref)
    # and set() back as text replaces the number
    s.set("optics.aperture", "15 cm")
    s.set("detector.integration_time", "0.625 s")
    same_values(s.run(), cli.json("run", sbv, "--format", "json"))


def test_evaluate_is_run_no_solve(cli, sbv):
    s = radchain.load(sbv)
    with pytest.warns(UserWarning, match="solve"):
        s.set("target.magnitude", 14)
    r = s.evaluate()
    assert r.json() == cli("run", sbv, "--no-solve", "--set", "target.magnitude=14", "--format", "json").stdout
    assert r.solves == []
    # a run after evaluate() solves again from the value set, as `run --set target.magnitude=14` does
    assert s.run().json() == cli("run", sbv, "--set", "target.magnitude=14", "--format", "json").stdout


def test_solve_returns_roots_and_session_reads_results(cli, sbv):
    s = radchain.load(sbv)
    solves = s.solve()
    ref = cli.json("run", sbv, "--format", "json")
    assert len(solves) == 1 and solves[0].value_si == ref["solves"][0]["value_si"]
    assert solves[0].evaluations == ref["solves"][0]["evaluations"]
    assert s["target.magnitude"] == solves[0].value_si
    assert s["detector.snr"] == next(x["value_si"] for x in ref["results"] if x["name"] == "detector.snr")
    with pytest.raises(KeyError):
        s["detector.no_such_result"]


def test_repeated_runs_do_not_drift(sbv):
    s = radchain.load(sbv)
    first = s.run().json()
    s.evaluate()
    s.set("optics.aperture", 0.3, si=True)
    s.run()
    s.set("optics.aperture", "15 cm")
    assert s.run().json() == first


def test_loads_text_equals_load_file(cli, sbv):
    text = Path(sbv).read_text()
    r = radchain.loads(text, name=sbv).run()
    assert r.json() == cli("run", sbv, "--format", "json").stdout
    s = radchain.loads(text, set={"optics.aperture": "30 cm"})
    assert s.path == "<string>"
    ref = cli.json("run", sbv, "--set", "optics.aperture=30 cm", "--format", "json")
    same_values(s.run(), ref)


def test_all_bundled_sensors_match_cli(cli, source_dir):
    files = sorted((source_dir / "sensors").glob("*.toml"))
    assert len(files) >= 5
    for f in files:
        assert radchain.load(str(f)).run().json() == cli("run", f, "--format", "json").stdout, f.name


def test_tables_equal_runs_at_each_value(source_dir):
    """Result.tables(): Rubin r's m5-vs-exposure [[table]] as a DataFrame, each row equal to a run at that exposure."""
    rubin = str(source_dir / "sensors" / "rubin-lsst-r-m5.toml")
    (table,) = radchain.load(rubin).run().tables()
    assert table.attrs["vary"] == "detector.integration_time"
    assert table.attrs["values"][2] == "30 s"
    assert table.attrs["units"]["detector.background_electrons"] == "electron"
    assert list(table["detector.integration_time"]) == [5.0, 15.0, 30.0, 60.0, 150.0, 300.0]
    for t, m5 in zip(table["detector.integration_time"], table["target.magnitude"]):
        alone = radchain.load(rubin, set={"detector.integration_time": f"{t} s"}).run()
        assert m5 == pytest.approx(alone["target.magnitude"], abs=1e-9)
    assert radchain.load(str(source_dir / "sensors" / "msx-sbv.toml")).run().tables() == []
