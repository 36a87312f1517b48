#!/usr/bin/env python3
"""Reads dem2d's ParaView snapshots with VTK's own XML reader (python3-vtk9) and checks what they hold.

1. cases/basic/rest_on_wall.toml (one disk of 1 kg settled on a floor): the last snapshot has 4 points
   (centre, the floor's two ends, the contact point), 1 vert, 2 lines (floor, contact), no polygon; the
   contact's normal force is m g (references §1.6) and its force vector, the force of the disk on the
   floor, is (0, -m g, 0); ids: element 0, wall 0, no other element; TimeValue 0.1 s.
2. cases/pre/block_mode.toml (3 bonded PREs, r = 12.5 mm), 1 ms: one polygon per PRE with 4 corners at
   r sqrt(2) from its centre.
3. snapshots.pvd lists every snapshot file, and each exists.

Exit status 1 on any failure, also when the vtk module is missing (install python3-vtk9:
scripts/setup.sh). Usage: check_vtk_snapshots.py <dem2d> <source dir> <work dir> [--expect-fn N]
"""
import math
import pathlib
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

try:
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
except ImportError as e:  # the test must fail, not skip
    print(f"FAIL: cannot import vtk ({e}); install python3-vtk9 (scripts/setup.sh)")
    sys.exit(1)

failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def run(dem2d, case, out, *sets):
    if out.exists():
        shutil.rmtree(out)
    cmd = [dem2d, "run", str(case), "--out", str(out), "-q"] + [a for s in sets for a in ("--set", s)]
    subprocess.run(cmd, check=True)


def read(path):
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(str(path))
    r.Update()
    check(r.GetErrorCode() == 0, f"{path.name}: the VTK reader reports no error")
    return r.GetOutput()


def snapshots(out):
    pvd = ET.parse(out / "snapshots.pvd").getroot()
    files = [(float(d.get("timestep")), d.get("file")) for d in pvd.iter("DataSet")]
    check(len(files) >= 2, f"{out.name}: snapshots.pvd lists {len(files)} snapshots")
    for _, f in files:
        check((out / f).is_file(), f"{out.name}: {f} listed in snapshots.pvd exists")
    return files


def cell_array(pd, name):
    a = pd.GetCellData().GetArray(name)
    check(a is not None, f"cell array {name} present")
    return vtk_to_numpy(a)


def main():
    dem2d, src, work = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    expect_fn = float(sys.argv[sys.argv.index("--expect-fn") + 1]) if "--expect-fn" in sys.argv else 9.80665
    work.mkdir(parents=True, exist_ok=True)

    # 1. A disk resting on a floor.
    out = work / "rest_on_wall"
    run(dem2d, src / "cases/basic/rest_on_wall.toml", out)
    files = snapshots(out)
    t_last, last = files[-1]
    pd = read(out / last)
    check(pd.GetNumberOfPoints() == 4, f"points: {pd.GetNumberOfPoints()} == 4 (centre, 2 wall ends, contact point)")
    check(pd.GetNumberOfVerts() == 1, f"verts: {pd.GetNumberOfVerts()} == 1")
    check(pd.GetNumberOfLines() == 2, f"lines: {pd.GetNumberOfLines()} == 2 (floor, contact)")
    check(pd.GetNumberOfPolys() == 0, f"polys: {pd.GetNumberOfPolys()} == 0")
    kind = cell_array(pd, "kind")
    check(list(kind) == [0, 2, 3], f"cell kinds {list(kind)} == [0, 2, 3]")
    fn = cell_array(pd, "normal_force")[2]
    check(abs(fn - expect_fn) <= 1e-6 * expect_fn, f"contact normal force {fn!r} N == {expect_fn} N (m g) to 1e-6")
    f = cell_array(pd, "force")[2]
    check(abs(f[0]) < 1e-9 and abs(f[1] + expect_fn) <= 1e-6 * expect_fn and f[2] == 0.0,
          f"contact force vector {list(f)} == (0, -{expect_fn}, 0)")
    el, wall, other = (cell_array(pd, n)[2] for n in ("element_id", "wall_id", "other_element_id"))
    check((el, wall, other) == (0, 0, -1), f"contact ids element {el}, wall {wall}, other element {other}")
    check(cell_array(pd, "wall_id")[1] == 0 and cell_array(pd, "element_id")[1] == -1, "the floor cell is wall 0, no element")
    pts = vtk_to_numpy(pd.GetPoints().GetData())
    check(abs(pts[0][1] - (0.01 - 9.80665e-6)) < 1e-9, f"disk centre y {pts[0][1]!r} == r - mg/K")
    check(abs(pts[3][1]) < 1e-4 and abs(pts[3][0]) < 1e-9, f"contact point {list(pts[3])} on the floor below the centre")
    radius = vtk_to_numpy(pd.GetPointData().GetArray("radius"))
    check(radius[0] == 0.01 and all(r == 0.0 for r in radius[1:]), f"point radius {list(radius)}")
    tv = vtk_to_numpy(pd.GetFieldData().GetArray("TimeValue"))[0]
    check(abs(tv - 0.1) < 1e-12 and abs(t_last - 0.1) < 1e-12, f"TimeValue {tv} and the .pvd time {t_last} are 0.1 s")

    # 2. PREs as squares.
    out = work / "block_mode"
    run(dem2d, src / "cases/pre/block_mode.toml", out, "numerics.duration=1 ms", "output.vtk=true")
    _, last = snapshots(out)[-1]
    pd = read(out / last)
    n_pre = int((vtk_to_numpy(pd.GetPointData().GetArray("radius")) > 0).sum())
    check(n_pre == 3, f"3 element centres ({n_pre})")
    check(pd.GetNumberOfPolys() == 3, f"polys: {pd.GetNumberOfPolys()} == 3 (one square per PRE)")
    pts = vtk_to_numpy(pd.GetPoints().GetData())
    polys = pd.GetPolys()
    ids = vtk.vtkIdList()
    polys.InitTraversal()
    k = 0
    while polys.GetNextCell(ids):
        corners = [pts[ids.GetId(q)] for q in range(ids.GetNumberOfIds())]
        centre = pts[k]
        d = [math.hypot(c[0] - centre[0], c[1] - centre[1]) for c in corners]
        check(len(corners) == 4 and all(abs(x - 0.0125 * math.sqrt(2)) < 1e-9 for x in d),
              f"square {k}: 4 corners at r sqrt(2) from the centre ({[round(x, 9) for x in d]})")
        k += 1
    check(list(cell_array(pd, "kind")).count(4) == 3, "3 cells of kind 4 (PRE squares)")
    disk_r = vtk_to_numpy(pd.GetPointData().GetArray("disk_radius"))
    check(all(r == 0.0 for r in disk_r), "disk_radius is 0 for PREs (circle glyphs only for disks)")

    if failures:
        print(f"{len(failures)} check(s) failed")
        sys.exit(1)
    print("all checks passed")


main()
