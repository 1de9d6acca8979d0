"""describe, plugins, compare and catalogue against the command line's own output."""
import json
import math
import re

import pytest

import radchain


def test_describe_plugin_lists_the_cli_keys(cli):
    d = radchain.describe("telescope")
    text = cli("describe", "telescope").stdout
    cli_keys = re.findall(r"^  (\w+)\s", text.split("keys:")[1].split("publishes:")[0], re.M)
    assert [k["key"] for k in d["keys"]] == [k for k in cli_keys if k != ""]
    aperture = next(k for k in d["keys"] if k["key"] == "aperture")
    assert aperture["type"] == "quantity" and aperture["si_unit"] == "m" and aperture["required"]
    assert d["kind"] == "optics" and d["summary"] in text
    assert [t["name"] for t in d["publishes"]] == re.findall(r"^  (\S+)\s+\[", text.split("publishes:")[1].split("needs:")[0], re.M)
    assert "aperture" in str(d)


def test_describe_kind_and_tables(cli):
    kind = radchain.describe("criterion")
    text = cli("describe", "criterion").stdout
    assert [p["name"] for p in kind["plugins"]] == re.findall(r"^  (\w+)\s", text, re.M)
    solve = radchain.describe("solve")
    assert [k["key"] for k in solve["keys"]] == ["unknown", "criterion", "bracket"]


@pytest.mark.parametrize("name", ["sensor", "solve", "expected", "table", "render", "validate", "criterion", "telescope"])
def test_describe_is_the_cli_model(cli, name):
    """Python and the command line show one describe model: the same title, keys and example for every table,
    command, kind and plugin (Python once lacked `table`)."""
    d = radchain.describe(name)
    text = cli("describe", name).stdout
    first = text.splitlines()[0]
    assert first == d["title"] or first == d["title"] + ":"
    if "keys" in d:
        keys_text = text.split("keys:\n")[-1].split("options:\n")[-1].split("\npublishes:")[0].split("\nexample:")[0]
        listed = re.findall(r"^  (-{0,2}\w[\w-]*)\s", keys_text, re.M)
        assert [k["key"] for k in d["keys"]] == listed
    if d.get("example"):
        assert text.endswith(d["example"])


def test_describe_render_and_validate_list_the_cli_options(cli):
    for command in ("render", "validate"):
        d = radchain.describe(command)
        text = cli("describe", command).stdout
        assert d["what"] == "command"
        assert [k["key"] for k in d["keys"]] == re.findall(r"^  (--[\w-]+)\s", text, re.M)
    width = next(k for k in radchain.describe("render")["keys"] if k["key"] == "--width")
    assert width["type"] == "integer" and width["default"] == "512"


def test_plugins_equal_cli_listing(cli):
    df = radchain.plugins()
    lines = cli("plugins").stdout.splitlines()[2:-1]
    assert list(df["name"]) == [line.split()[0] for line in lines]
    assert list(df["file"]) == [line.split()[-1] for line in lines]
    assert df["usable"].all()
    assert {"telescope", "ccd_frame", "snr_threshold", "sun"} <= set(df["name"])


def test_compare_equals_cli_compare_json(cli, sbv, tmp_path):
    other = tmp_path / "sbv-20cm.toml"
    other.write_text(open(sbv).read().replace('aperture = "15 cm"', 'aperture = "20 cm"'))
    df = radchain.compare(sbv, str(other))
    ref = cli.json("compare", sbv, other, "--format", "json")
    rows = ref["rows"]
    assert list(df["name"]) == [r["name"] for r in rows]
    assert list(df["kind"]) == [r["kind"] for r in rows]
    assert list(df["status"]) == [r["status"] for r in rows]
    aperture = df[df["name"] == "optics.aperture"].iloc[0]
    assert aperture["kind"] == "input" and aperture["a_si"] == 0.15 and aperture["b_si"] == 0.2
    checked = 0
    for r, (_, row) in zip(rows, df.iterrows()):
        if row["kind"] == "result" and r["a"] not in (None, "", "nan"):
            assert row["a_value"] == pytest.approx(float(r["a"]), rel=1e-9), r["name"]
            assert row["b_value"] == pytest.approx(float(r["b"]), rel=1e-9), r["name"]
            checked += 1
    assert checked > 10
    magnitude = df[df["name"] == "target.magnitude"].iloc[0]
    assert magnitude["status"] == "differs" and magnitude["delta"] > 0.5


def test_compare_sessions_and_tolerance(sbv):
    a = radchain.load(sbv)
    b = radchain.load(sbv)
    same = radchain.compare(a, b)
    assert (same[same["kind"] == "result"]["status"] == "same").all()
    assert (same["kind"] == "result").all()  # no input differs
    b.set("detector.qe", 0.28)
    df = radchain.compare(a, b, tolerance=1e-6)
    qe = df[df["name"] == "detector.qe"].iloc[0]
    assert qe["kind"] == "input" and qe["b_si"] == 0.28
    assert "EXCEEDS" in set(df["status"])


def test_catalogue_equals_cli_catalogue_json(cli, source_dir):
    folder = str(source_dir / "sensors")
    df = radchain.catalogue([folder])
    ref = cli.json("catalogue", folder, "--format", "json")
    assert list(df.columns) == ref["columns"]
    assert len(df) == len(ref["rows"]) > 10
    for r, row in zip(ref["rows"], df.to_dict("records")):
        for column in ref["columns"]:
            a, b = r[column], row[column]
            if a is None:
                assert b is None or (isinstance(b, float) and math.isnan(b)), (column, a, b)
            else:
                assert a == b, (column, a, b)
    assert df.attrs["exit_code"] == cli("catalogue", folder).returncode
    assert df.attrs["summary"] == ref.get("summary", "")


def assert_rows_equal_to_the_printed_digits(records, printed_rows):
    """Python's numbers are the library's doubles; the command line prints 10 significant digits of the same."""
    assert len(records) == len(printed_rows)
    for mine, printed in zip(records, printed_rows):
        assert mine.keys() == printed.keys()
        for key, value in printed.items():
            if isinstance(value, float) or (isinstance(value, int) and not isinstance(value, bool) and key != "rank"):
                assert mine[key] == pytest.approx(value, rel=6e-10, abs=1e-300), key
            elif value is None:
                assert math.isnan(mine[key]), key
            else:
                assert mine[key] == value, key


def test_budget_equals_cli_and_the_closed_form(cli, sbv):
    df = radchain.budget(sbv, "target.magnitude")
    data = json.loads(cli("budget", sbv, "--results", "target.magnitude", "--format", "json").stdout)
    assert_rows_equal_to_the_printed_digits(df.to_dict("records"), data["rows"])
    assert df["rank"].dtype.kind == "i"
    # m_lim ∝ 5 log10 D (S ∝ D², the floor fixed): dm/dln D = 5/ln 10 exactly (Pan 2010 eq. 11)
    aperture = df[df["parameter"] == "optics.aperture"].iloc[0]
    assert aperture["elasticity"] == pytest.approx(5 / math.log(10), rel=1e-6)


def test_uncertainty_equals_cli_for_the_same_seed(cli, sbv):
    vary = ["optics.transmittance=normal(0.56, 0.02)", "detector.read_noise=uniform(5 e-, 7 e-)"]
    df = radchain.uncertainty(sbv, vary, "target.magnitude", samples=2000, seed=7)
    args = ["uncertainty", sbv, "--results", "target.magnitude", "--samples", "2000", "--seed", "7", "--format", "json"]
    for v in vary:
        args += ["--vary", v]
    assert_rows_equal_to_the_printed_digits(df.to_dict("records"), json.loads(cli(*args).stdout)["rows"])
    # Full precision, not the printed 10 digits: the nominal value is the run's own double.
    nominal = df[(df["input"] == "") & (df["statistic"] == "nominal")]["value"].iloc[0]
    assert nominal == radchain.load(sbv).run()["target.magnitude"]
    sd = df[(df["input"] == "") & (df["statistic"] == "sd")]["value"].iloc[0]
    linear = df[(df["input"] == "") & (df["statistic"] == "linear_sd")]["value"].iloc[0]
    assert sd == pytest.approx(linear, rel=0.1)  # small spreads: Monte Carlo ≈ linear propagation


def test_budget_bad_result_is_an_input_error(sbv):
    with pytest.raises(radchain.InputError) as error:
        radchain.budget(sbv, "target.magnitud")
    assert "did you mean" in str(error.value)
