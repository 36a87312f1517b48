"""dem2d.load_case / check / run against the command line: the same numbers bit for bit, the GIL released,
Ctrl-C (SIGINT) stopping a run with status "interrupted"."""
import os
import signal
import subprocess
import threading
import time

import pandas
import pytest

import dem2d


def test_load_and_check(root):
    case = dem2d.load_case(root / "cases/impact/disk_disk.toml")
    assert case.title == "Disk–disk head-on impact"
    assert case.elements == 2
    assert case.series_names == ["t", "e0.x", "e1.x", "e0.vx", "e1.vx", "e0.fn.e1"]
    c = case.check()
    s = c["stability"]
    assert 0 < case.dt < s["limit"] and s["units"]["limit"] == "s"
    assert s["dt_over_limit"] == pytest.approx(case.dt / s["limit"])
    assert c["elements"]["disks"] == 2


def test_overrides_reach_the_case(root):
    case = dem2d.load_case(root / "cases/impact/disk_disk.toml",
                           sets={"numerics.dt": "3.5e-6 s", "numerics.duration": 0.001, "output.vtk": False})
    assert case.dt == 3.5e-6 and case.duration == 0.001
    assert case.overrides == ["numerics.dt=3.5e-6 s", "numerics.duration=0.001", "output.vtk=false"]


def test_run_gives_series_summary_probes(root):
    r = dem2d.run(dem2d.load_case(root / "cases/impact/disk_disk.toml"))
    assert r.status == "completed" and r.out is None
    assert isinstance(r.series, pandas.DataFrame)
    assert list(r.series.columns) == ["t [s]", "e0.x [m]", "e1.x [m]", "e0.vx [m/s]", "e1.vx [m/s]", "e0.fn.e1 [N]"]
    assert len(r.series) == r.steps // 10 + 1 + (r.steps % 10 != 0)  # every 10th step and the last
    assert r.summary["status"] == "completed" and r.summary["probes"]["e"]["unit"] == "1"
    assert set(r.probes) == {"e", "tc", "rebound"}
    assert r.probes["e"] == r.summary["probes"]["e"]["value"]
    assert 0.0 < r.probes["e"] < 1.0  # damped: some energy lost


def test_bit_for_bit_like_the_command_line(root, exe, scratch):
    """The same case and override through `dem2d run` and dem2d.run (2 threads against 1): series.csv
    byte for byte, the probes exactly, the DataFrame the file's numbers exactly."""
    case_file = root / "cases/pre/block_on_slope.toml"
    sets = {"numerics.duration": "20 ms"}
    subprocess.run([exe, "run", str(case_file), "--out", str(scratch / "cli"), "--quiet",
                    "--set", "numerics.duration=20 ms"], check=True)
    r = dem2d.run(dem2d.load_case(case_file, sets=sets), out=scratch / "module", threads=2)
    cli = (scratch / "cli" / "series.csv").read_bytes()
    assert cli == (scratch / "module" / "series.csv").read_bytes()
    assert len(cli) > 1000
    import json
    cli_summary = json.loads((scratch / "cli" / "summary.json").read_text())
    assert {k: v["value"] for k, v in cli_summary["probes"].items()} == r.probes
    assert cli_summary["case_hash"] == r.summary["case_hash"]
    from_file = pandas.read_csv(scratch / "cli" / "series.csv", float_precision="round_trip")
    assert from_file.equals(r.series)


def test_gil_is_released_and_sigint_interrupts(root):
    """A timer thread (it needs the GIL) sends SIGINT while a long run runs: the run stops with status
    "interrupted"; afterwards Python's own handler is back (SIGINT raises KeyboardInterrupt)."""
    case = dem2d.load_case(root / "cases/basic/rest_on_wall.toml",
                           sets={"numerics.duration": "1000 s", "output.every": 1000000, "output.vtk": False})
    timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
    t0 = time.monotonic()
    timer.start()
    r = dem2d.run(case)
    took = time.monotonic() - t0
    timer.join()
    assert r.status == "interrupted", r.message
    assert "SIGINT" in r.message
    assert 0 < r.steps < 10**8 and took < 20
    with pytest.raises(KeyboardInterrupt):
        os.kill(os.getpid(), signal.SIGINT)
        time.sleep(1)


def test_a_case_can_run_twice_the_same(root):
    case = dem2d.load_case(root / "cases/impact/disk_wall.toml")
    a, b = dem2d.run(case), dem2d.run(case)
    assert a.series.equals(b.series) and a.probes == b.probes


def test_threads_are_range_checked_and_the_number_used_recorded(root):
    """threads= as `dem2d run --threads`: 1 to 1024, else ValueError; not an integer: TypeError; above the
    usable cores: run on those, and summary.json records both numbers."""
    import json
    import os

    import pytest

    case = dem2d.load_case(root / "cases/basic/free_fall.toml")
    for bad in (0, -1, 10**6):
        with pytest.raises(ValueError, match="from 1 to 1024"):
            dem2d.run(case, threads=bad)
    for bad in (1.5, "2", True):
        with pytest.raises(TypeError):
            dem2d.run(case, threads=bad)
    usable = len(os.sched_getaffinity(0))
    r = dem2d.run(case, threads=1024)
    t = json.loads(r.summary) if isinstance(r.summary, str) else r.summary
    assert t["threads"]["asked"] == 1024
    assert t["threads"]["used"] <= usable
