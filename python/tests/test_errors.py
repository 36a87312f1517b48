"""Bad input through the module: the reader's own errors, raised as dem2d.CaseError with the file, line, key
and message the command line prints (file:line: key: what)."""
import pytest

import dem2d
from conftest import write_case


def test_unknown_key(root, scratch):
    bad = write_case(scratch, "bad.toml", root / "cases/impact/disk_disk.toml",
                     replace=('duration = "15 ms"', 'duration = "15 ms"\ndurration_extra = 1'))
    with pytest.raises(dem2d.CaseError) as e:
        dem2d.load_case(bad)
    err = e.value
    assert err.file == str(bad) and err.key == "numerics.durration_extra"
    lines = bad.read_text().splitlines()
    assert lines[err.line - 1].startswith("durration_extra")
    assert str(err).startswith(f"{bad}:{err.line}: numerics.durration_extra: ")
    assert isinstance(err, ValueError) and err.message.startswith("unknown key")


def test_wrong_unit(root, scratch):
    bad = write_case(scratch, "bad_unit.toml", root / "cases/impact/disk_disk.toml",
                     replace=('kn = "1e6 N/m"', 'kn = "38 deg"'))
    with pytest.raises(dem2d.CaseError) as e:
        dem2d.load_case(bad)
    err = e.value
    assert (err.file, err.key) == (str(bad), "contact.0.kn")
    assert bad.read_text().splitlines()[err.line - 1].startswith('kn = "38 deg"')
    assert "stiffness" in err.message and "'38 deg'" in err.message


def test_wrong_unit_in_an_override(root):
    with pytest.raises(dem2d.CaseError) as e:
        dem2d.load_case(root / "cases/impact/disk_disk.toml", sets={"numerics.dt": "2 kg"})
    err = e.value
    assert err.file == "--set numerics.dt=2 kg" and err.line is None and err.key == "numerics.dt"
    assert "time" in err.message


def test_override_with_a_line_break(root):
    # the value used to be cut at the line break, the rest ignored without a word
    with pytest.raises(dem2d.CaseError) as e:
        dem2d.load_case(root / "cases/impact/disk_disk.toml", sets={"numerics.dt": "2e-6\nnumerics.duration=1"})
    assert "one line" in str(e.value) and "\\n" in str(e.value)


def test_missing_file(scratch):
    with pytest.raises(dem2d.CaseError) as e:
        dem2d.load_case(scratch / "no_such_case.toml")
    assert e.value.file == str(scratch / "no_such_case.toml") and e.value.message == "file not found"


def test_time_step_above_the_limit_is_refused_by_check_and_run(root):
    case = dem2d.load_case(root / "cases/impact/disk_disk.toml", sets={"numerics.dt": "5 ms"})
    with pytest.raises(dem2d.CaseError) as e:
        case.check()
    assert e.value.key == "numerics.dt" and "limit" in e.value.message
    with pytest.raises(dem2d.CaseError):
        dem2d.run(case)
