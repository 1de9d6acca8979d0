"""Bad input raises radchain.InputError (a ValueError) with the command line's one-line message and its fields."""
import pytest

import radchain


def bad_copy(tmp_path, sbv, old, new):
    text = open(sbv).read()
    assert old in text
    path = tmp_path / "bad.toml"
    path.write_text(text.replace(old, new, 1))
    return path, path.read_text()


def location_of(text, needle):
    """1-based line and column of the first occurrence of needle in text (the independent reference)."""
    before = text[: text.index(needle)]
    return before.count("\n") + 1, len(before) - before.rfind("\n")


def test_bad_unit_in_file_has_cli_message_and_fields(cli, sbv, tmp_path):
    path, text = bad_copy(tmp_path, sbv, 'aperture = "15 cm"', 'aperture = "15 kg"')
    with pytest.raises(radchain.InputError) as caught:
        radchain.load(str(path))
    e = caught.value
    assert isinstance(e, ValueError)
    done = cli("run", path, check=False)
    assert done.returncode == 2
    assert str(e) == done.stderr.strip()
    line, column = location_of(text, 'aperture = "15 kg"')  # the key's position (toml++ locates the key)
    assert (e.file, e.line, e.column) == (str(path), line, column)
    assert e.subject == 'aperture = "15 kg"'
    assert e.context == 'optics (plugin "telescope")'
    assert str(e).startswith(f"{path}:{line}:{column}: optics (plugin \"telescope\"): aperture = \"15 kg\": ")


def test_toml_syntax_error_from_text(cli, sbv, tmp_path):
    path, text = bad_copy(tmp_path, sbv, "qe = 0.27", "qe = = 0.27")
    with pytest.raises(radchain.InputError) as caught:
        radchain.loads(text, name=str(path))
    assert str(caught.value) == cli("run", path, check=False).stderr.strip()
    assert caught.value.line == location_of(text, "qe = = 0.27")[0]


def test_bad_set_text_is_the_cli_set_message_and_changes_nothing(cli, sbv):
    s = radchain.load(sbv)
    before = s.run().json()
    with pytest.raises(radchain.InputError) as caught:
        s.set("optics.aperture", "15 kg")
    done = cli("run", sbv, "--set", "optics.aperture=15 kg", check=False)
    assert done.returncode == 2 and str(caught.value) == done.stderr.strip()
    assert s.run().json() == before
    with pytest.raises(radchain.InputError) as caught:
        radchain.load(sbv, set={"optcs.aperture": "20 cm"})
    done = cli("run", sbv, "--set", "optcs.aperture=20 cm", check=False)
    assert str(caught.value) == done.stderr.strip() and "did you mean \"optics\"" in str(caught.value)


def test_bad_set_number(sbv):
    s = radchain.load(sbv)
    with pytest.raises(radchain.InputError) as caught:
        s.set("optics.aperture", -0.1, si=True)
    assert "out of range" in caught.value.problem and caught.value.file == "set optics.aperture"
    with pytest.raises(radchain.InputError) as caught:
        s.set("optics.apertur", 0.2, si=True)
    assert 'did you mean "aperture"' in caught.value.problem
    with pytest.raises(radchain.InputError) as caught:
        s.set("detector.adc_bits", 12.5)
    assert "integer" in caught.value.problem
    with pytest.raises(radchain.InputError):
        s.set("detector.quantisation", 1.0)  # a choice, not a number
    assert s.get("optics.aperture") == 0.15
    # A bare number for a key with a unit is not taken as SI by default (15 meant as cm would be 15 m).
    with pytest.raises(TypeError, match=r"optics.aperture has a unit \(m\).*si=True"):
        s.set("optics.aperture", 15)
    with pytest.raises(TypeError, match="si=True"):
        radchain.load(sbv, set={"optics.aperture": 0.2})
    assert radchain.load(sbv, set={"optics.aperture": 0.2}, si=True).get("optics.aperture") == 0.2
    s.set("target.magnitude", 14)  # no unit: a number as it is
    assert s.get("target.magnitude") == 14


def test_missing_file(cli, tmp_path):
    missing = tmp_path / "nope.toml"
    with pytest.raises(radchain.InputError) as caught:
        radchain.load(str(missing))
    assert str(caught.value) == cli("run", missing, check=False).stderr.strip()
    assert caught.value.file == str(missing)


def test_describe_unknown_plugin():
    with pytest.raises(radchain.InputError) as caught:
        radchain.describe("telescop")
    assert 'did you mean "telescope"' in str(caught.value)


def test_sweep_values_that_are_not_numbers_name_the_parameter(sbv):
    import numpy as np
    s = radchain.load(sbv)
    with pytest.raises(TypeError, match=r"^sweep: optics\.aperture: values are numbers in SI .*'x'"):
        s.sweep({"optics.aperture": [0.15, "x"]})
    with pytest.raises(TypeError, match=r"^sweep: detector\.qe: values are numbers in SI"):
        s.sweep({"optics.aperture": 0.2, "detector.qe": {"a": 1}})
    with pytest.raises(ValueError, match=r"do not broadcast together.*optics\.aperture \(3,\), detector\.qe \(2,\)"):
        s.sweep({"optics.aperture": np.linspace(0.15, 0.3, 3), "detector.qe": [0.2, 0.3]})
    # Numbers as text are numbers (numpy's own conversion), and the point is the one a number gives.
    assert s.sweep({"optics.aperture": ["0.2"]}, results=["detector.snr"])["detector.snr"][0] == \
        s.sweep({"optics.aperture": [0.2]}, results=["detector.snr"])["detector.snr"][0]


# Every argument of the wrong type or range names its function and argument and says what is expected, instead of
# Python's or pybind11's generic message ("'int' object is not iterable", "incompatible function arguments",
# "invalid literal for int()") or a silent str() of it (compare(path, 5) looked for a file named "5").
@pytest.mark.parametrize("call, error, message", [
    (lambda sbv: radchain.load(123), TypeError, r"^load: path is a str or os\.PathLike of str, not int 123$"),
    (lambda sbv: radchain.load(sbv, set=["a"]), TypeError, r"^set is a dict such as"),
    (lambda sbv: radchain.budget(sbv, 5), TypeError, r"^budget: results is a str or a list of str .*, not int 5$"),
    (lambda sbv: radchain.uncertainty(sbv, 5, "target.magnitude"), TypeError, r"^uncertainty: vary is a str or a list of str"),
    (lambda sbv: radchain.uncertainty(sbv, "optics.transmittance=normal(0.5, 0.01)", "target.magnitude", samples="x"),
     TypeError, r"^uncertainty: samples is an int, not str 'x'$"),
    (lambda sbv: radchain.uncertainty(sbv, "optics.transmittance=normal(0.5, 0.01)", "target.magnitude", samples=-5),
     ValueError, r"^uncertainty: samples is at least 1, not -5$"),
    (lambda sbv: radchain.uncertainty(sbv, "optics.transmittance=normal(0.5, 0.01)", "target.magnitude", samples=2.0),
     TypeError, r"^uncertainty: samples is an int, not float 2\.0$"),
    (lambda sbv: radchain.catalogue(5), TypeError, r"^catalogue: inputs are a path or a list of paths"),
    (lambda sbv: radchain.catalogue(sbv, results=7), TypeError, r"^catalogue: results is a str or a list of str"),
    (lambda sbv: radchain.compare(sbv, 5), TypeError, r"^compare: b \(a sensor file, a results \.json or a Session\) is a str"),
    (lambda sbv: radchain.compare(sbv, sbv, tolerance="x"), TypeError, r"^compare: tolerance is a number, not str 'x'$"),
    (lambda sbv: radchain.grid(sbv, ["optics.aperture"]), TypeError, r"^grid: axes are a dict such as"),
    (lambda sbv: radchain.grid(sbv, {"optics.aperture": 5}), TypeError, r"^grid: the axis of optics\.aperture is a str"),
    (lambda sbv: radchain.render(sbv, seed="x"), TypeError, r"^render: seed is an int, not str 'x'$"),
    (lambda sbv: radchain.describe(5), TypeError, r"^describe: a plugin, kind, table or command name is a str such as \"telescope\""),
    (lambda sbv: radchain.set_threads(-1), ValueError, r"^set_threads: n is at least 0, not -1$"),
    (lambda sbv: radchain.load(sbv).sweep({"optics.aperture": [0.1]}, results=5), TypeError, r"^sweep: results is a str or a list"),
])
def test_wrong_argument_types_name_the_function_and_argument(sbv, call, error, message):
    with pytest.raises(error, match=message):
        call(sbv)
