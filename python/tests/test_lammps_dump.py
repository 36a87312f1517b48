"""[output] lammps_dump = true: dump.lammpstrj in LAMMPS' `dump custom` text format, read back by a small
parser of its own (as OVITO's LAMMPS dump reader reads it: ITEM lines, then the values) and compared with the
run's series."""
import math

import pandas

import dem2d


def read_lammps_dump(path):
    """Frames of a LAMMPS text dump: [{timestep, n, box [(lo, hi)]*3, box_flags, columns, atoms [[...]]}]."""
    frames, lines, k = [], path.read_text().splitlines(), 0
    while k < len(lines):
        assert lines[k] == "ITEM: TIMESTEP", lines[k]
        frame = {"timestep": int(lines[k + 1])}
        assert lines[k + 2] == "ITEM: NUMBER OF ATOMS"
        n = frame["n"] = int(lines[k + 3])
        head = lines[k + 4].split()
        assert head[:3] == ["ITEM:", "BOX", "BOUNDS"] and len(head) == 6, lines[k + 4]
        frame["box_flags"] = head[3:]
        frame["box"] = [tuple(float(v) for v in lines[k + 5 + d].split()) for d in range(3)]
        atoms_head = lines[k + 8].split()
        assert atoms_head[:2] == ["ITEM:", "ATOMS"]
        frame["columns"] = atoms_head[2:]
        frame["atoms"] = [lines[k + 9 + a].split() for a in range(n)]
        assert all(len(a) == len(frame["columns"]) for a in frame["atoms"])
        frames.append(frame)
        k += 9 + n
    return frames


def test_dump_reads_back(root, scratch):
    case = dem2d.load_case(root / "cases/impact/disk_disk.toml",
                           sets={"output.lammps_dump": True, "output.every": 100, "output.vtk": False})
    r = dem2d.run(case, out=scratch / "run")
    frames = read_lammps_dump(scratch / "run" / "dump.lammpstrj")
    steps = list(range(0, r.steps + 1, 100)) + ([r.steps] if r.steps % 100 else [])  # and the last step
    assert len(frames) == len(r.series) == len(steps)
    assert [f["timestep"] for f in frames] == steps
    for f, (_, row) in zip(frames, r.series.iterrows()):
        assert f["columns"] == ["id", "type", "x", "y", "vx", "vy", "omegaz", "radius", "fx", "fy"]
        assert f["n"] == 2 and f["box_flags"] == ["ff", "ff", "pp"]
        atoms = {int(a[0]): dict(zip(f["columns"], map(float, a))) for a in f["atoms"]}
        assert sorted(atoms) == [1, 2] and atoms[1]["type"] == 1.0  # ids from 1: dem2d's id + 1
        assert atoms[1]["x"] == row["e0.x [m]"] and atoms[2]["x"] == row["e1.x [m]"]  # %.17g both: exact
        assert atoms[1]["vx"] == row["e0.vx [m/s]"] and atoms[2]["vx"] == row["e1.vx [m/s]"]
        assert atoms[1]["radius"] == 0.01
        (xlo, xhi), (ylo, yhi), _ = f["box"]
        assert math.isclose(xlo, atoms[1]["x"] - 0.01) and math.isclose(xhi, atoms[2]["x"] + 0.01)
        assert math.isclose(ylo, -0.01) and math.isclose(yhi, 0.01)
        assert atoms[1]["fx"] == -atoms[2]["fx"]  # action and reaction
    assert any(float(f["atoms"][0][8]) < 0 for f in frames)  # the contact pushed disk 1 back at some frame


def test_no_dump_unless_asked(root, scratch):
    dem2d.run(dem2d.load_case(root / "cases/impact/disk_disk.toml"), out=scratch / "run")
    assert not (scratch / "run" / "dump.lammpstrj").exists()


def test_lammps_dump_is_read_strictly(root):
    import pytest
    with pytest.raises(dem2d.CaseError) as e:
        dem2d.load_case(root / "cases/impact/disk_disk.toml", sets={"output.lammps_dump": "yes"})
    assert e.value.key == "output.lammps_dump"
