"""dem2d.study and dem2d.sweep against `dem2d study` and `dem2d sweep`: the same result files, every number bit
for bit (result.json but for its provenance and the measured speed in its setup; the CSV files byte for byte)."""
import json
import subprocess

import dem2d


def files(folder):
    """Every file under a study folder but the run cache's bookkeeping, by relative path."""
    return {str(p.relative_to(folder)): p for p in sorted(folder.rglob("*")) if p.is_file()}


def same_results(cli, module, result):
    a, b = json.loads((cli / "result.json").read_text()), json.loads((module / "result.json").read_text())
    a.pop("provenance"), b.pop("provenance")  # date, wall time, command, code version (of each binary's build)
    for d in (a, b):  # a speed, not a result
        d.get("setup", {}).pop("mean element-steps per second", None)
    assert a == b  # json's floats from 17-digit text: equal means equal bits
    assert result == json.loads((module / "result.json").read_text())  # the dict returned is the file
    fa, fb = files(cli), files(module)
    csvs = [k for k in fa if k.endswith(".csv")]
    assert csvs and set(csvs) <= set(fb)
    for k in csvs:
        assert fa[k].read_bytes() == fb[k].read_bytes(), k
    return a


def cli_and_module(exe, scratch, command, path):
    """`dem2d study|sweep PATH` and dem2d.study|sweep(PATH), fresh, into scratch/cli and scratch/module:
    the module's dict and the CLI's result.json (the same files, compared by same_results)."""
    subprocess.run([exe, command, str(path), "--out", str(scratch / "cli"), "--fresh"], check=True,
                   capture_output=True)
    r = getattr(dem2d, command)(path, out=scratch / "module", jobs=2, fresh=True)
    return r, same_results(scratch / "cli", scratch / "module", r)


def test_study_as_the_command_line(root, exe, scratch):
    r, a = cli_and_module(exe, scratch, "study", root / "verification/rest_on_wall/study.toml")
    assert r["passed"] and len(a["checks"]) == 2 and all(c["dem"] is not None for c in a["checks"])


def test_sweep_as_the_command_line(root, exe, scratch):
    r, a = cli_and_module(exe, scratch, "sweep", root / "verification/sensitivity_linear_morris/sensitivity.toml")
    assert r["passed"] and a["checks"]
