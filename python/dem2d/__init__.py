"""dem2d from Python: read, check and run cases, run studies (python/README.md).

    import dem2d
    case = dem2d.load_case("cases/pre/block_on_slope.toml", sets={"numerics.dt": "1e-7 s"})
    case.check()["stability"]["limit"]       # the time-step limit [s]
    r = dem2d.run(case)                      # r.status, r.series (DataFrame), r.summary, r.probes

Every call goes to the same C++ functions as the command line `dem2d`, so a case is read as strictly
(dem2d.CaseError with .file, .line, .key, .message) and a run gives the same numbers bit for bit.
"""
import json
import os
import re
import tempfile
import threading

from . import _core

__all__ = ["CaseError", "OutputError", "Case", "Result", "load_case", "run", "study", "sweep", "schema", "version"]

OutputError = _core.OutputError


class CaseError(ValueError):
    """A mistake in a case (or study) file or an override, named as the command line names it:
    str(e) is `file:line: key: what`; e.file, e.line (int or None), e.key (or None), e.message."""

    def __init__(self, text, file=None, line=None, key=None, message=None):
        super().__init__(text)
        self.file, self.line, self.key, self.message = file, line, key, message if message is not None else text

    @classmethod
    def from_text(cls, text, sets=()):
        for s in sets:  # an override names itself: "--set key=value: key: what"
            origin = "--set " + s + ": "
            if text.startswith(origin):
                key, _, what = text[len(origin):].partition(": ")
                return cls(text, origin[:-2], None, key if what else None, what or key)
        m = re.match(r"(?s)^(?P<file>.+?):(?P<line>\d+): (?P<key>[^\s:]+): (?P<msg>.*)$", text)
        if m:
            return cls(text, m["file"], int(m["line"]), m["key"], m["msg"])
        m = re.match(r"(?s)^file not found: (?P<file>.+?)( \(from .*\))?$", text)
        if m:
            return cls(text, m["file"], None, None, "file not found")
        m = re.match(r"(?s)^(?P<file>[^:]+): (?P<msg>.*)$", text)
        if m:
            return cls(text, m["file"], None, None, m["msg"])
        return cls(text)


def _reraise(e, sets=()):
    raise CaseError.from_text(str(e), sets) from None


def _in_main_thread():
    return threading.current_thread() is threading.main_thread()


class Case:
    """A case as `dem2d` reads it (dem2d.load_case). Properties: path, title, source, overrides, dt,
    duration [s], elements, series_names, as_read (the TOML after overrides, as a dict)."""

    def __init__(self, core, sets):
        self._core, self._sets = core, sets

    def __getattr__(self, name):
        if name == "as_read":
            return json.loads(self._core.as_read)
        return getattr(self._core, name)

    def check(self):
        """What `dem2d check` prints, as a dict: the resolved case in SI, and under "stability" the
        time-step limit [s] over every contact the case can form, dt / limit and what sets it.
        Raises CaseError where `dem2d check` fails (a dt above the limit, an unknown quantity)."""
        try:
            return json.loads(_core.check(self._core))
        except _core.CaseError as e:
            _reraise(e, self._sets)

    def __repr__(self):
        return f"<dem2d.Case {self.path!r}: {self.title!r}, {self.elements} elements, dt = {self.dt:g} s>"


def _override(key, value):
    if isinstance(value, bool):
        value = "true" if value else "false"
    elif isinstance(value, (int, float)):
        value = repr(value)
    return f"{key}={value}"


def load_case(path, sets=None):
    """Reads a case file with overrides {"key": value} (a value: a number in SI, or a string with a unit,
    "12 kN/mm"); the same reader as `dem2d run --set key=value`. Raises CaseError."""
    overrides = [_override(k, v) for k, v in (sets or {}).items()]
    try:
        return Case(_core.read_case(os.fspath(path), overrides), overrides)
    except _core.CaseError as e:
        _reraise(e, overrides)


def _read_series(csv_path):
    """series.csv as a DataFrame (pandas present) or a dict of numpy arrays; the column names carry the
    SI unit ("t [s]"). Read with round-trip precision: the values are those of the file bit for bit."""
    if not os.path.exists(csv_path):
        return None
    try:
        import pandas
        return pandas.read_csv(csv_path, float_precision="round_trip")
    except ImportError:
        import csv
        import numpy
        with open(csv_path, newline="") as f:
            rows = list(csv.reader(f))
        return {name: numpy.array([float(r[k]) for r in rows[1:]]) for k, name in enumerate(rows[0])}


def _read_contacts(csv_path):
    """contacts.csv ([output] contacts = true) as a DataFrame, an empty `wall` or `segments` kept as "" (not
    NaN), numbers bit for bit; a dict of columns (lists of strings) without pandas; None if not written."""
    if not os.path.exists(csv_path):
        return None
    try:
        import pandas
        return pandas.read_csv(csv_path, float_precision="round_trip", keep_default_na=False)
    except ImportError:
        import csv
        with open(csv_path, newline="") as f:
            rows = list(csv.reader(f))
        return {name: [r[k] for r in rows[1:]] for k, name in enumerate(rows[0])}


class Result:
    """A finished run: status ("completed", "settled", "past peak", "blow-up", "interrupted", "refused": the
    time-step guard's re-check, docs/model.md G7), message, steps, time [s], wall_seconds, probes {name: value in SI or None}, summary (summary.json as a dict),
    series (series.csv: a pandas DataFrame, SI units in the column names), contacts (contacts.csv, when the
    case asks for it with [output] contacts = true, else None), out (the output folder or None)."""

    def __init__(self, d, series, out, contacts=None):
        self.status, self.message, self.steps, self.time = d["status"], d["message"], d["steps"], d["time"]
        self.wall_seconds, self.stability_limit = d["wall_seconds"], d["stability_limit"]
        self.probes, self.summary = dict(d["probes"]), json.loads(d["summary"])
        self.series, self.out, self.contacts = series, out, contacts

    def __repr__(self):
        return f"<dem2d.Result {self.status}: {self.steps} steps, t = {self.time:g} s, {len(self.probes)} probes>"


def run(case, out=None, threads=1):
    """Runs a case (a Case, or a path read with no overrides) as `dem2d run` does. out: the output folder
    (series.csv, summary.json, vtk/, ...; cleared first); None: a temporary folder, removed after the series
    is read. threads: 1 to 1024 (ValueError otherwise, TypeError for a non-integer), never more than the
    cores this process may use (summary "threads" records the number asked and the number used). The GIL is
    released while it runs; Ctrl-C (SIGINT) stops the run at the next step with status "interrupted",
    everything written. A blow-up is status "blow-up", not an exception."""
    if not isinstance(case, Case):
        case = load_case(case)
    if out is None:
        with tempfile.TemporaryDirectory(prefix="dem2d-run-") as tmp:
            return _run_into(case, os.path.join(tmp, "run"), threads, keep=False)
    return _run_into(case, os.fspath(out), threads, keep=True)


def _run_into(case, out, threads, keep):
    if isinstance(threads, bool) or not isinstance(threads, int):
        raise TypeError(f"threads={threads!r}: expected a whole number from 1 to 1024 (as dem2d run --threads)")
    try:
        d = _core.run(case._core, out, threads, _in_main_thread())
    except _core.CaseError as e:
        _reraise(e, case._sets)
    return Result(d, _read_series(os.path.join(out, "series.csv")), out if keep else None,
                  _read_contacts(os.path.join(out, "contacts.csv")))


def _study(path, out, jobs, fresh, sweep):
    path = os.fspath(path)
    if out is None:
        out = os.path.join("build", "studies", os.path.basename(os.path.dirname(os.path.abspath(path))))
    try:
        passed, text = _core.study(path, os.fspath(out), int(jobs), bool(fresh), sweep, _in_main_thread())
    except _core.CaseError as e:
        _reraise(e)
    except RuntimeError as e:  # a malformed study file: file:line: key: what
        if re.match(r"(?s)^.+?:\d+: ", str(e)):
            raise CaseError.from_text(str(e)) from None
        raise
    result = json.loads(text)
    result.setdefault("passed", passed)
    return result


def study(path, out=None, jobs=1, fresh=False):
    """Runs a verification study (verification/<name>/study.toml) as `dem2d study` does and returns its
    result.json as a dict (result["passed"]: every check passed). out: default build/studies/<name>."""
    return _study(path, out, jobs, fresh, False)


def sweep(path, out=None, jobs=1, fresh=False):
    """Runs a sensitivity study (sensitivity.toml) as `dem2d sweep` does; returns its result.json as a dict."""
    return _study(path, out, jobs, fresh, True)


def schema():
    """The JSON Schema (draft-07) of the case format as a dict: what `dem2d schema` prints, made from the
    reader's own key table (keys, types, units, allowed words, defaults, descriptions). Validate a case
    with it: jsonschema.validate(tomllib.load(f), dem2d.schema())."""
    return json.loads(_core.schema())


def version():
    """The code version, build type and compiler (what every result file records)."""
    return json.loads(_core.version())
