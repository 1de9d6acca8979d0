"""radchain from Python: sensor files loaded, run, solved and swept by the C++ framework (docs/python.md).

    import numpy as np, radchain
    s = radchain.load("sensors/msx-sbv.toml", set={"optics.aperture": "20 cm"})
    r = s.run()                              # every result (SI and display), the [[solve]] roots, the [expected] checks
    r["target.magnitude"]                    # a result in SI
    r.frame()                                # pandas DataFrame: name, value_si, si_unit, value, unit, stage, equation
    s.set("optics.aperture", "25 cm")        # TOML value text, as `radchain run --set` takes it
    s.set("optics.aperture", 0.25, si=True)  # or a number: in SI, said so, for a key with a unit
    s.solve(); s.evaluate()                  # the solves only; forward only (`--no-solve`)
    out = s.sweep({"optics.aperture": np.linspace(0.15, 0.30, 1_000_000)}, results=["target.magnitude"])

Bad input raises radchain.InputError (a ValueError) with the command line's one-line located message and the
fields file, line, column, context, subject, problem; a name or value of the wrong Python type (a bare number for a
key with a unit without si=True, a name that is not a str) raises TypeError. Values are in SI everywhere except the
display columns.
"""
from __future__ import annotations

import io as _io
import json as _json
import numbers as _numbers
import os as _os
import warnings as _warnings
from collections import namedtuple as _namedtuple
from collections.abc import Mapping as _Mapping

import numpy as _np

from . import _radchain
from ._radchain import InputError, framework_version, plugin_abi_version

__all__ = [
    "InputError", "Session", "Result", "load", "loads", "describe", "plugins", "compare", "catalogue", "grid", "budget",
    "uncertainty",
    "render", "Image",
    "configure", "search_path", "set_threads", "threads", "framework_version", "plugin_abi_version",
    "Stage", "parameter", "register_stage",
]
__version__ = framework_version

#: One result: its name, value in SI and SI unit, value in the display unit and that unit, the plugin that produced it
#: and the equation it came from.
Value = _namedtuple("Value", "name value_si si_unit value unit stage equation")
#: One [[solve]]: the unknown, its criteria, the binding one, the root (SI), whether it converged, evaluations,
#: why not (message), each criterion's own root, the bracket (SI).
Solve = _namedtuple("Solve", "unknown criteria binding value_si converged evaluations message roots bracket_si")
#: One [expected] check: result, printed value (as written and SI), the erratum's value that follows (SI or None),
#: computed (SI), tolerances, passed, source.
Check = _namedtuple("Check", "result printed printed_si follows_si computed_si tolerance_si rel_tolerance passed source")


def _pandas():
    try:
        import pandas
    except ImportError as error:  # pragma: no cover - pandas is in scripts/setup-debian.sh
        raise ImportError("this radchain call returns a pandas DataFrame: install python3-pandas") from error
    return pandas


def _astropy_unit(unit: str):
    """radchain's unit text ("W m-2 sr-1 m-1", "electron-1", "1") as an astropy unit (the same text)."""
    try:
        import astropy.units as u
    except ImportError as error:
        raise ImportError("Result.quantity() returns an astropy Quantity: install python3-astropy") from error
    return u.dimensionless_unscaled if unit in ("", "1") else u.Unit(unit)


def _is_number(value) -> bool:
    return isinstance(value, (_numbers.Real, _np.floating, _np.integer)) and not isinstance(value, (bool, _np.bool_))


def _text_of(value) -> str:
    if isinstance(value, (bool, _np.bool_)):
        return "true" if value else "false"
    if isinstance(value, str):
        return _no_nul(value, "a parameter value")
    raise TypeError(f"a parameter value is TOML value text (str) or a number in SI, not {type(value).__name__}")


def _no_nul(text: str, what: str) -> str:
    # The C++ side would cut the text at a NUL and act on (or name) a different key than the one given.
    if "\0" in text:
        raise ValueError(f"{what} {text!r} contains a NUL character")
    return text


def _name(value, what: str = "a name", example: str = "optics.aperture") -> str:
    """A parameter or result name as given: a str ("optics.aperture"); anything else is refused, not str()-ed
    (3 would become "3", b"x" "b'x'")."""
    if not isinstance(value, str):
        raise TypeError(f"{what} is a str such as \"{example}\", not {type(value).__name__} {value!r}")
    return _no_nul(value, what)


def _names(values, what: str = "a result name", example: str = "target.magnitude") -> list:
    """One name or a list of names (None: none); each a str."""
    if values is None:
        return []
    if isinstance(values, str):
        values = [values]
    elif isinstance(values, (bytes, dict)) or not hasattr(values, "__iter__"):
        raise TypeError(f"{what} is a str or a list of str such as [\"{example}\"], not {type(values).__name__} {values!r}")
    return [_name(v, what, example) for v in values]


def _path(value, what: str = "a path") -> str:
    try:
        value = _os.fspath(value)
    except TypeError:
        raise TypeError(f"{what} is a str or os.PathLike of str, not {type(value).__name__} {value!r}") from None
    if not isinstance(value, str):
        raise TypeError(f"{what} is a str or os.PathLike of str, not {type(value).__name__} {value!r}")
    return _no_nul(value, what)


def _integer(value, what: str, minimum: int | None = None) -> int:
    """An int (or numpy integer) as given, not int()-ed from text or a float; below `minimum` is a ValueError."""
    if isinstance(value, bool) or not isinstance(value, (int, _np.integer)):
        raise TypeError(f"{what} is an int, not {type(value).__name__} {value!r}")
    if minimum is not None and value < minimum:
        raise ValueError(f"{what} is at least {minimum}, not {value}")
    return int(value)


def _real(value, what: str) -> float:
    if not _is_number(value):
        raise TypeError(f"{what} is a number, not {type(value).__name__} {value!r}")
    return float(value)


def _split_sets(set):
    """{"key": "20 cm", "other": 0.5} -> ([("key", "20 cm")], [("other", 0.5)])"""
    texts, numbers = [], []
    if set is not None and not isinstance(set, dict):
        raise TypeError(f"set is a dict such as {{\"optics.aperture\": \"20 cm\"}}, not {type(set).__name__} {set!r}")
    for key, value in (set or {}).items():
        if _is_number(value):
            numbers.append((_name(key, "a parameter key"), float(value)))
        else:
            texts.append((_name(key, "a parameter key"), _text_of(value)))
    return texts, numbers


class Result(_Mapping):
    """What Session.run() / evaluate() return: a mapping result name -> value in SI, with units and provenance.

    r["detector.snr"]     value in SI (float; NaN when not evaluated)
    r.record(name)        Value(name, value_si, si_unit, value, unit, stage, equation)
    r.frame()             pandas DataFrame of every result, in the chain's order
    r.solves, r.expected  lists of Solve and Check records; r.passed: every solve converged and every check held
    r.json(), r.text()    exactly what `radchain run --format json` / `radchain run` print
    """

    def __init__(self, report):
        self._report = report
        self.names = list(report.names)
        self.values_si = report.values_si
        self.values = report.values
        self.si_units = list(report.si_units)
        self.units = list(report.units)
        self.stages = list(report.stages)
        self.equations = list(report.equations)
        self._index = {name: i for i, name in enumerate(self.names)}
        self.solves = [Solve(**s) for s in report.solves]
        self.expected = [Check(**e) for e in report.expected]
        self.passed = bool(report.passed)
        self.sensor = report.sensor
        self.file = report.file

    def __getitem__(self, name):
        return float(self.values_si[self._position(name)])

    def _position(self, name) -> int:
        try:
            return self._index[name]
        except KeyError:
            import difflib
            near = difflib.get_close_matches(str(name), self.names, n=1, cutoff=0.6)
            raise KeyError(f"{name}: no such result" + (f" (did you mean {near[0]!r}?)" if near else "")) from None

    def __iter__(self):
        return iter(self.names)

    def __len__(self):
        return len(self.names)

    def record(self, name) -> Value:
        i = self._position(name)
        return Value(name, float(self.values_si[i]), self.si_units[i], float(self.values[i]), self.units[i],
                     self.stages[i], self.equations[i])

    def display(self, name) -> str:
        """The value as the report prints it ("15.5565"), in r.record(name).unit."""
        return self._report.display(self._position(name))

    def quantity(self, name):
        """The result as an astropy Quantity in its SI unit (astropy: Debian's python3-astropy)."""
        i = self._position(name)
        return float(self.values_si[i]) * _astropy_unit(self.si_units[i])

    def quantities(self) -> dict:
        """{name: astropy Quantity} for every result."""
        return {name: self.quantity(name) for name in self.names}

    def frame(self):
        pd = _pandas()
        return pd.DataFrame({"name": self.names, "value_si": self.values_si, "si_unit": self.si_units,
                             "value": self.values, "unit": self.units, "stage": self.stages,
                             "equation": self.equations}).set_index("name", drop=False)

    to_frame = frame

    def solves_frame(self):
        return _pandas().DataFrame([s._asdict() for s in self.solves], columns=Solve._fields)

    def expected_frame(self):
        return _pandas().DataFrame([e._asdict() for e in self.expected], columns=Check._fields)

    def json(self) -> str:
        return self._report.json()

    def tables(self) -> list:
        """The file's [[table]] entries (e.g. limiting magnitude vs exposure), one pandas DataFrame each: the varied
        parameter and a column per result, all in SI (NaN in a row whose solve failed). attrs: name, vary, the values
        as written, the results' SI units and each row's note (why a solve failed, else "")."""
        pd = _pandas()
        frames = []
        for t in _json.loads(self.json())["tables"]:
            names = [c["name"] for c in t["columns"]]
            df = pd.DataFrame({t["vary"]: t["values_si"],
                               **{n: [_np.nan if row[i] is None else row[i] for row in t["rows_si"]] for i, n in enumerate(names)}})
            df.attrs.update(name=t["name"], vary=t["vary"], values=t["values"],
                            units={c["name"]: c["si_unit"] for c in t["columns"]}, notes=t["notes"])
            frames.append(df)
        return frames

    def text(self) -> str:
        return self._report.text()

    def __repr__(self):
        return f"<radchain.Result {self.sensor!r}: {len(self.names)} results, {len(self.solves)} solves, " \
               f"{len(self.expected)} checks, {'passed' if self.passed else 'FAILED'}>"

    def __str__(self):
        return self.text()


def _si_values(key, values):
    """A sweep's values of one parameter as float64 (SI), or TypeError naming the parameter (numpy's own message names
    neither the parameter nor what it expects)."""
    try:
        return _np.asarray(values, dtype=_np.float64)
    except (TypeError, ValueError) as e:
        raise TypeError(f"sweep: {key}: values are numbers in SI (an array, a list or a scalar), not {values!r:.60}: "
                        f"{e}") from None


class Session:
    """A sensor loaded once; parameters set, then run, solved, evaluated forward or swept (radchain.load/loads)."""

    def __init__(self, native):
        self._native = native

    @property
    def path(self) -> str:
        return self._native.path

    @property
    def sensor(self) -> str:
        return self._native.sensor

    @property
    def solved(self) -> list:
        """The unknowns of the file's [[solve]] entries."""
        return list(self._native.solved)

    def set(self, key: str, value, si: bool = False) -> "Session":
        """Sets <section>.<key>: TOML value text ("25 cm", "\\"e490\\"", "true") as `radchain run --set` takes it,
        or a number: as it is for a key without a unit (a magnitude, a reflectance), in SI with si=True for a key
        with one (set("optics.aperture", 0.25, si=True) is 25 cm; a bare 15 is refused, not taken as 15 m). Checked
        against the parameter's range. Returns the session. InputError when refused (nothing changes then)."""
        key = _name(key, "a parameter key")
        if key in self._native.solved:
            _warnings.warn(f"a [[solve]] overwrites {key} in run() and solve() (evaluate() uses the value set)",
                           stacklevel=2)
        if _is_number(value):
            unit = self._native.si_unit(key)
            if unit != "1" and not si:
                raise TypeError(f"{key} has a unit ({unit}): give it as text, e.g. set({key!r}, \"{value:g} <unit>\"), "
                                f"or as a number in {unit} with si=True")
            self._native.set_si(key, float(value))
        else:
            self._native.set_text(key, _text_of(value))
        return self

    def get(self, key: str) -> float:
        """The current value of a numeric parameter, in SI."""
        return self._native.get(_name(key, "a parameter key"))

    def run(self) -> Result:
        """Every result, the [[solve]] roots and the [[expected]] checks: `radchain run --set ...`."""
        return Result(self._native.run())

    def solve(self) -> list:
        """Runs the [[solve]] entries from the values set; returns their Solve records (s[name] reads the results)."""
        return Result(self._native.run()).solves

    def evaluate(self) -> Result:
        """Forward only at the values set, the solves skipped: `radchain run --no-solve --set ...`."""
        return Result(self._native.evaluate())

    def __getitem__(self, name) -> float:
        """A result (SI) as the last run/solve/evaluate left it."""
        return self._native.value(_name(name, "a result name"))

    def sweep(self, parameters: dict, results=None, solve: bool = True, frame: bool = False, allow_large: bool = False):
        """Evaluates the chain at every point, on all cores with the GIL released (C++ lanes and solves).

        parameters: {"<section>.<key>": array of SI values}; the arrays broadcast together (numpy rules), so
        {"optics.aperture": a[:, None], "detector.integration_time": t[None, :]} is a grid. results: result names
        (default: every result). solve=False evaluates forward only (a solved unknown may then be a parameter).
        Returns {name: array in SI of the broadcast shape} for each parameter and each result, plus "ok" (False
        where a solve failed; its unknown is NaN there), or with frame=True a pandas DataFrame of the flattened
        points. A failed solve warns (RuntimeWarning) with the first failing point. More than 10^8 points are refused
        unless allow_large=True (as `radchain sweep --allow-large`); the values are copied before they are checked.
        """
        if not parameters:
            raise ValueError("sweep: give at least one parameter, e.g. {\"optics.aperture\": numpy.linspace(0.15, 0.3, 16)}")
        keys = [_name(k, "a parameter key") for k in parameters]
        values = [_si_values(k, v) for k, v in zip(keys, parameters.values())]
        try:
            shape = _np.broadcast_shapes(*(v.shape for v in values))
        except ValueError:
            raise ValueError("sweep: the parameters' arrays do not broadcast together (numpy rules): shapes " +
                             ", ".join(f"{k} {v.shape}" for k, v in zip(keys, values))) from None
        # Refused before the broadcast arrays are made (a typo'd shape would allocate gigabytes first).
        _radchain.check_sweep_size(int(_np.prod(shape, dtype=_np.float64)), bool(allow_large))
        arrays = _np.broadcast_arrays(*values)
        flat = [_np.ascontiguousarray(a.reshape(-1)) for a in arrays]
        if isinstance(results, str):
            results = [results]
        names, units, out, ok, failed, failure = self._native.sweep(keys, flat, _names(results, "sweep: results"),
                                                                    not solve, bool(allow_large))
        if failed:
            _warnings.warn(f"{failed} of {ok.size} points: {failure}", RuntimeWarning, stacklevel=2)
        columns = {}
        for k, a in zip(keys, flat):
            columns[k] = a.reshape(shape)
        for i, name in enumerate(names):
            columns[name] = out[i].reshape(shape)
        columns["ok"] = ok.reshape(shape)
        if frame:
            pd = _pandas()
            df = pd.DataFrame({k: v.reshape(-1) for k, v in columns.items()})
            df.attrs["units"] = {**{k: self._native.si_unit(k) for k in keys}, **dict(zip(names, units))}
            return df
        return columns

    def __repr__(self):
        return f"<radchain.Session {self.sensor!r} ({self.path})>"


def load(path, set: dict | None = None, si: bool = False) -> Session:
    """Loads a sensor file, with overrides: {"optics.aperture": "20 cm"} (TOML text, as --set) or numbers as
    Session.set takes them (a key with a unit: in SI with si=True)."""
    texts, numbers = _split_sets(set)
    session = Session(_radchain.load(_path(path, "load: path"), texts))
    for key, value in numbers:
        session.set(key, value, si=si)
    return session


def loads(text: str, set: dict | None = None, name: str = "<string>", si: bool = False) -> Session:
    """Loads a sensor file's text. `name` stands for the file in messages; relative data files are looked for beside
    it (if it is a path), then in RADCHAIN_DATA_PATH and the bundled spectra."""
    texts, numbers = _split_sets(set)
    session = Session(_radchain.loads(_name(text, "the sensor file's text"), _path(name, "name"), texts))
    for key, value in numbers:
        session.set(key, value, si=si)
    return session


class Description(dict):
    """radchain.describe(): a dict (what, name, keys, ...) that prints like `radchain describe`."""

    def __str__(self):
        lines = []
        if self["what"] == "kind":
            lines.append(f"{self['name']} plugins:")
            for p in self["plugins"]:
                lines.append(f"  {p['name']:<24} {p['summary']}")
            return "\n".join(lines)
        if self["what"] == "plugin":
            lines.append(f"{self['name']} — {self['kind']} plugin (framework {self['framework_version']}, "
                         f"ABI {self['abi_version']})")
            lines.append(f"  {self['summary']}")
            lines.append(f"  physics: {self['reference']}")
            lines.append(f"  file: {self['file']}")
        elif self["what"] == "command":
            lines.append(f"radchain {self['name']} options (radchain.{self['name']}: the keys with '_' for '-')")
        else:
            lines.append(f"[{self['name']}]")
        lines.append("keys:")
        for k in self["keys"]:
            kind = k["type"] + (f" [{k['si_unit']}]" if k["si_unit"] else "")
            status = "required" if k["required"] else (f"default {k['default']}" if k["default"] is not None else "optional")
            lines.append(f"  {k['key']:<24} {kind:<28} {status:<22} {k['doc']}")
            if k["accepted"]:
                lines.append(f"  {'':<24} accepted: {k['accepted']}")
        for heading in ("publishes", "needs"):
            if heading in self:
                lines.append(f"{heading}:")
                for t in self[heading] or [{"name": "(none)", "unit": "", "meaning": ""}]:
                    lines.append(f"  {t['name']:<32} [{t['unit']}]  {t['meaning']}")
        return "\n".join(lines)

    def keys_frame(self):
        return _pandas().DataFrame(self["keys"])


def describe(name: str) -> Description:
    """A plugin's keys (units, defaults, accepted ranges), what it publishes and needs; a kind's plugins
    ("criterion"); a sensor file's own table ("sensor", "solve", "expected"); or the options of the imaging
    commands ("render": what radchain.render takes, "validate")."""
    return Description(_radchain.describe(_name(name, "describe: a plugin, kind, table or command name", "telescope")))


def plugins():
    """The plugins on the search path: DataFrame of name, kind, file, version, summary, usable, problem."""
    return _pandas().DataFrame(_radchain.plugins(),
                               columns=["name", "kind", "file", "version", "summary", "usable", "problem"])


def configure(plugin_path=()):
    """Sets the plugin search path: these folders, then RADCHAIN_PLUGIN_PATH, the build tree, the install prefix."""
    if isinstance(plugin_path, str):
        plugin_path = [plugin_path]
    _radchain.configure([_path(p, "configure: a plugin folder") for p in plugin_path])


def search_path() -> list:
    return list(_radchain.search_path())


def set_threads(n: int = 0):
    """Caps the threads of sweeps and catalogues (0: every core), like --threads."""
    _radchain.set_threads(_integer(n, "set_threads: n", minimum=0))


def threads() -> int:
    return int(_radchain.threads())


def _compare_operand(x, what):
    if isinstance(x, Session):
        return x._native
    return _path(x, f"compare: {what} (a sensor file, a results .json or a Session)")


def compare(a, b, set: dict | None = None, solve: bool = True, tolerance: float | None = None):
    """Two sensor files, saved results (`radchain run --format json`, a .json path) or Sessions side by side, as
    `radchain compare`: DataFrame of kind (input/result), name, a, b, unit, a_value, b_value, a_si, b_si, si_unit,
    delta, delta_pct, status (same / ok / differs / EXCEEDS / only in A|B). `set` applies to files (TOML text)."""
    texts, numbers = _split_sets(set)
    if numbers:
        raise TypeError("compare(set=...) takes TOML value text, as --set does (set numbers on a Session instead)")
    rows = _radchain.compare(_compare_operand(a, "a"), _compare_operand(b, "b"), texts, bool(solve),
                             None if tolerance is None else _real(tolerance, "compare: tolerance"))
    columns = ["kind", "name", "a", "b", "unit", "a_value", "b_value", "a_si", "b_si", "si_unit", "delta",
               "delta_pct", "status"]
    return _pandas().DataFrame(rows, columns=columns)


def budget(path, results, set: dict | None = None, solve: bool = True):
    """The sensitivity budget, as `radchain budget --format json`: DataFrame of every (result, input) pair with the
    derivative ∂r/∂x (SI), the elasticity ∂r/∂ln x (for a magnitude input, ∂r/∂ln F of the flux it stands for; its
    note says so), ∂ln r/∂ln x, its error estimate and method, ranked."""
    texts, numbers = _split_sets(set)
    if numbers:
        raise TypeError("budget(set=...) takes TOML value text, as --set does")
    table = _radchain.budget(_path(path, "budget: path"), texts, _names(results, "budget: results"), not solve)
    df = _pandas().DataFrame(table["data"], columns=table["columns"])
    df["rank"] = df["rank"].astype(int)
    return df


def uncertainty(path, vary, results, samples: int = 1000, seed: int = 1, set: dict | None = None, solve: bool = True):
    """Monte Carlo over `vary` (["optics.transmittance=normal(0.56, 0.02)", ...], the key's units), as
    `radchain uncertainty --format json`: DataFrame of result, input, statistic, value, unit (mean, sd, p5, p50,
    p95, the linear-propagation sd, and per input its correlation and derivative)."""
    texts, numbers = _split_sets(set)
    if numbers:
        raise TypeError("uncertainty(set=...) takes TOML value text, as --set does")
    table = _radchain.uncertainty(_path(path, "uncertainty: path"), texts,
                                  _names(vary, "uncertainty: vary", "optics.transmittance=normal(0.56, 0.02)"),
                                  _names(results, "uncertainty: results"), _integer(samples, "uncertainty: samples", 1),
                                  _integer(seed, "uncertainty: seed", 0), not solve)
    return _pandas().DataFrame(table["data"], columns=table["columns"])


def catalogue(inputs, set: dict | None = None, results=None, solve: bool = True):
    """Sensor files and folders (their *.toml) on all cores, as `radchain catalogue`: DataFrame of sensor, instrument
    (the file's [sensor] name), result, kind (published / peer / paper / internal / unstated for an [expected] check; solve; criterion), computed,
    reference, tolerance (the deviation the check allows, in the row's unit), unit, delta, delta_pct, check, note. df.attrs["exit_code"] is the command's (0 all held,
    1 a check failed, 2 a file was bad input), df.attrs["errors"] the bad files' one-line messages."""
    texts, numbers = _split_sets(set)
    if numbers:
        raise TypeError("catalogue(set=...) takes TOML value text, as --set does")
    if isinstance(inputs, (str, _os.PathLike)):
        inputs = [inputs]
    elif not hasattr(inputs, "__iter__") or isinstance(inputs, (bytes, dict)):
        raise TypeError(f"catalogue: inputs are a path or a list of paths (sensor files, folders), not "
                        f"{type(inputs).__name__} {inputs!r}")
    table, errors, code = _radchain.catalogue([_path(i, "catalogue: an input") for i in inputs], texts,
                                              _names(results, "catalogue: results"), not solve)
    return _catalogue_frame(table, errors, code)


def grid(path, axes: dict, set: dict | None = None, results=None, solve: bool = True, allow_large: bool = False):
    """`radchain sweep path --set key=from:to:steps …` on all cores, in memory: a DataFrame of the grid's points in
    point order (the last axis varying fastest), one column per axis and result under its bare name
    ("optics.aperture", "target.magnitude") in SI, as Session.sweep(frame=True) has them; df.attrs["units"] names each
    column's SI unit. (`radchain sweep --out grid.npy` writes the same points in the units written and displayed.)

    axes: {"<section>.<key>": "from:to:steps"} (e.g. "15 cm:30 cm:100"), the first outermost; set: fixed values, TOML
    text. A grid of limiting magnitudes is factored by axis where the chain allows it (docs/performance.md, "Factored
    grids"): df.attrs["method"] says how the points were solved, or why each was solved on its own, as `radchain sweep
    --explain` does. df.attrs["exit_code"] is the command's (1: a solve failed at some point, NaN there; a
    RuntimeWarning says where). More than 10^8 points are refused unless allow_large=True (--allow-large). Session.sweep
    takes arbitrary values per point instead."""
    if not isinstance(axes, dict):
        raise TypeError(f"grid: axes are a dict such as {{\"optics.aperture\": \"15 cm:30 cm:16\"}}, not {type(axes).__name__} {axes!r}")
    if not axes:
        raise ValueError("grid: give at least one axis, e.g. {\"optics.aperture\": \"15 cm:30 cm:16\"}")
    texts, numbers = _split_sets(set)
    if numbers:
        raise TypeError("grid(set=...) takes TOML value text, as --set does")
    table, failure, code, method, units = _radchain.sweep_table(
        _path(path, "grid: path"), texts,
        [(_name(k, "grid: an axis key"), _name(v, f"grid: the axis of {k}", "15 cm:30 cm:16")) for k, v in axes.items()],
        _names(results, "grid: results"), not solve,
        "npy", "", "block", bool(allow_large), True)
    if failure:
        _warnings.warn(f"radchain sweep: {failure}", RuntimeWarning, stacklevel=2)
    # (radchain's own bytes: a wide table's header may exceed np.load's default 10000-byte guard against hostile files)
    df = _pandas().DataFrame(_np.load(_io.BytesIO(table), max_header_size=len(table)))
    df.attrs["units"] = dict(zip(df.columns, units))
    df.attrs["exit_code"] = code
    df.attrs["method"] = method
    return df


Image = _namedtuple("Image", "pixels header cards summary kind")
Image.__doc__ = """radchain.render's answer: pixels (numpy float32, [row, column], row 0 at the top of the picture; a
FITS file stores the bottom row first), header {key: value} (the FITS header's cards, bool/int/float/str), cards [(key, value, comment)] in order,
summary (the lines `radchain render` prints) and kind ("frame": a detector frame of point targets; "scene": an
Earth scene)."""


def render(path, set: dict | None = None, targets=None, scene: str | None = None, seed: int = 1, star_seed: int = 1,
           **options) -> Image:
    """The image `radchain render` draws for a sensor file: a detector frame with point targets (and field stars)
    or an Earth scene, as a numpy array and its FITS header — the same pixels as `radchain render PATH … --out
    x.fits` with the same options. set: overrides as for load() (TOML value text). targets: "x,y,mag" or "mag"
    texts, or (x, y, mag) tuples (mag may be "limit"); none: one at the limiting magnitude in the centre.
    options: the command's render options (`radchain describe render`) with '_' for '-', written as on the command
    line: width=64, height=64, stars=200, star_magnitudes="8:17", no_noise=["shot", "read"], gsd="5 m", ...
    InputError for an option, target or sensor the command would refuse."""
    from . import _imaging  # OpenImageIO and FFTW load with the first render, not with `import radchain`
    texts, numbers = _split_sets(set)
    if numbers:
        raise TypeError("render(set=...) takes TOML value text, as --set does")
    target_texts = [t if isinstance(t, str) else ",".join(str(v) for v in t) for t in (targets or [])]
    given = []
    for key, value in options.items():
        if isinstance(value, bool):
            if value:
                given.append((key.replace("_", "-"), "true"))
            continue
        if isinstance(value, (list, tuple)):
            value = ",".join(str(v) for v in value)
        given.append((key.replace("_", "-"), str(value)))
    pixels, cards, summary, kind = _imaging.render(
        _path(path, "render: path"), texts, given, target_texts, "" if scene is None else _path(scene, "render: scene"),
        _integer(seed, "render: seed", 0), _integer(star_seed, "render: star_seed", 0))
    header = {key: value for key, value, _comment in cards if key not in ("COMMENT", "HISTORY", "")}
    return Image(pixels, header, cards, summary, kind)


def _catalogue_frame(table: str, errors, code: int):
    """The DataFrame of a catalogue's JSON table; errors None: the notes of its ERROR rows (the same messages)."""
    data = _json.loads(table)
    df = _pandas().DataFrame(data["rows"], columns=data["columns"])
    df.attrs["exit_code"] = code
    df.attrs["errors"] = list(df.loc[df["check"] == "ERROR", "note"]) if errors is None else list(errors)
    df.attrs["summary"] = data.get("summary", "")
    return df


#: One parameter of a stage written in Python (radchain.parameter).
Parameter = _namedtuple("Parameter", "key type unit example default required min max min_exclusive max_exclusive doc spectral")


def parameter(key: str, type: str = "number", unit: str = "", default: str | None = None, example: str | None = None,
              required: bool = False, min: float = -_np.inf, max: float = _np.inf, min_exclusive: bool = False,
              max_exclusive: bool = False, doc: str = "", spectral: bool = False) -> Parameter:
    """A key of a Python stage's schema, as the C++ schemas declare theirs (radchain/schema.hpp): type "quantity"
    (unit: its SI unit, "m"; values written "15 cm"), "number" or "integer"; default and example as written in a
    sensor file, without quotes ("15 cm", "5"); min/max in SI. spectral=True: the stage's prepare() reads it, so a
    change (set(), a sweep) re-runs the spectral phase (the C++ schemas' affects_spectrum())."""
    example = example if example is not None else default if default is not None else "1" + (f" {unit}" if unit else "")
    return Parameter(key, type, unit, f'"{example}"' if type == "quantity" else example, default, required,
                     float(min), float(max), min_exclusive, max_exclusive, doc, spectral)


class Stage:
    """A stage written in Python: subclass, fill in the contract and register it (radchain.register_stage), then a
    sensor file's `plugin = "<name>"` in the [<kind>] section builds it like a C++ plugin's stage.

        class MyCriterion(radchain.Stage):
            kind, name = "criterion", "py_snr_threshold"
            schema = [radchain.parameter("threshold", default="5", min=0, min_exclusive=True, doc="SNR threshold T")]
            publishes = {"criteria.*.margin": "SNR/T - 1"}      # vocabulary terms and their equations
            needs = ["detector.snr"]                             # vocabulary terms read (optional_needs: if present)
            def evaluate(self, params, inputs):                  # SI in, SI out
                return {"criteria.*.margin": inputs["detector.snr"] / params["threshold"] - 1}

    evaluate() runs at every evaluation of the chain's scalar phase (solves, sweeps: one point at a time, the GIL
    held), with params {key: SI value} (the keys given or defaulted) and inputs {term: SI value}, plus the light's
    scalars "light.signal.scale", "light.background.scale", "light.illumination.scale", "light.up_path.scale"; it
    returns a value for every published term.

    prepare(params, light) runs in the spectral phase (when the chain is built, and again when a spectral parameter
    changes: declare the keys it reads with parameter(..., spectral=True)). light is a dict of what the stages before
    this one made, per unit scale: "signal" and "background" ({"form", "wavelength_m", "value", "unit",
    "extrapolation"} with numpy arrays, or None), "illumination", "up_path_transmittance", "path_radiance"
    ({"wavelength_m", "value", "unit", "extrapolation"} or None) and "report_band_m" ((lo, hi) or None). A detector
    prototype integrates the signal there and keeps the result on self for evaluate(). It reads the light only:
    a Python stage cannot change what reaches the stages after it.
    """
    kind: str = ""
    name: str = ""
    summary: str = ""
    reference: str = ""
    schema: list = []
    publishes: dict = {}
    needs: list = []
    optional_needs: list = []

    def prepare(self, params: dict, light: dict) -> None:
        pass

    def evaluate(self, params: dict, inputs: dict) -> dict:
        raise NotImplementedError(f"{type(self).__name__}.evaluate(params, inputs)")


def register_stage(cls):
    """Adds a Stage subclass to the plugins sensor files can name (replacing an earlier registration of its name for
    chains built afterwards). Usable as a class decorator; returns the class."""
    if not (isinstance(cls, type) and issubclass(cls, Stage)):
        raise TypeError("register_stage takes a radchain.Stage subclass")
    if not cls.kind or not cls.name:
        raise ValueError(f"{cls.__name__}: set kind (e.g. \"detector\") and name (the sensor file's plugin = \"...\")")
    publishes = cls.publishes if isinstance(cls.publishes, _Mapping) else {t: "" for t in cls.publishes}
    _radchain.register_stage(cls.kind, cls.name, cls.summary or cls.__doc__ or "", cls.reference,
                             [tuple(p) for p in cls.schema],
                             [(str(t), str(e) or f"{cls.__qualname__}.evaluate (Python)") for t, e in publishes.items()],
                             [(str(t), False) for t in cls.needs] + [(str(t), True) for t in cls.optional_needs], cls)
    return cls
