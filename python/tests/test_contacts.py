"""Result.contacts: contacts.csv ([output] contacts = true) as a DataFrame, the file's numbers bit for bit and
the same as the command line's file; None when the case does not ask for it."""
import subprocess

import pandas

import dem2d


def test_contacts_of_a_disk_on_a_floor(root, exe, scratch):
    case_file = root / "cases/basic/rest_on_wall.toml"
    r = dem2d.run(dem2d.load_case(case_file, sets={"output.contacts": True, "element.0.mass": "2 kg"}))
    c = r.contacts
    assert isinstance(c, pandas.DataFrame) and r.out is None  # read before the temporary folder went
    last = c[c["step"] == r.steps]
    assert len(last) == 1
    row = last.iloc[0]
    assert (row["i"], row["j"], row["wall"], row["law"], row["links"], row["segments"]) == (0, -1, "floor", "linear", 1, "")
    assert abs(row["fn [N]"] / (2 * 9.80665) - 1) < 1e-12 and (row["nx"], row["ny"]) == (0.0, -1.0)
    subprocess.run([exe, "run", str(case_file), "--out", str(scratch / "cli"), "-q", "--set", "output.contacts=true",
                    "--set", "element.0.mass=2 kg"], check=True)
    from_file = pandas.read_csv(scratch / "cli" / "contacts.csv", float_precision="round_trip", keep_default_na=False)
    assert from_file.equals(c)


def test_no_contacts_unless_asked(root):
    assert dem2d.run(dem2d.load_case(root / "cases/impact/disk_disk.toml")).contacts is None


def test_rolling_moment_of_a_disk_rolling_to_rest(root):
    """Rolling resistance (docs/model.md §4) through the module: the moment at its cap μ_r r e_n while the
    disk rolls, in contacts.csv's `mr` and in the series' e0.mr.floor; a case without it has mr = 0."""
    case_file = root / "cases/basic/disk_rolling.toml"
    r = dem2d.run(dem2d.load_case(case_file, sets={"output.contacts": True, "numerics.duration": "0.05 s"}))
    last = r.contacts[r.contacts["step"] == r.steps].iloc[0]
    m, g, radius = 0.8325220532012952, 9.80665, 0.01
    cap = 0.1 * radius * m * g  # μ_r r e_n, e_n = m g at the equilibrium overlap
    assert abs(last["mr [N*m]"] / cap - 1) < 1e-9
    assert abs(r.series["e0.mr.floor [N*m]"].iloc[-1] / cap - 1) < 1e-9
    flat = dem2d.run(dem2d.load_case(root / "cases/basic/rest_on_wall.toml", sets={"output.contacts": True}))
    assert (flat.contacts["mr [N*m]"] == 0.0).all()


def test_contact_points_of_a_polygon_block(root):
    """A polygon block (docs/model.md §5) on the slope of Matsui's Table 1: contacts.csv has one row per
    contact point, its two base corners, pressed together by m g cos α, both with the slope's normal."""
    r = dem2d.run(dem2d.load_case(root / "cases/polygon/block_on_slope.toml",
                                  sets={"output.contacts": True, "numerics.duration": "0.01 s"}))
    last = r.contacts[r.contacts["step"] == r.steps]
    assert len(last) == 2
    assert set(last["i"]) == {0} and set(last["wall"]) == {"slope"} and set(last["law"]) == {"linear"}
    weight = 0.0671 * 9.80665 * 0.766044443118978  # m g cos 40°
    assert abs(last["fn [N]"].sum() / weight - 1) < 1e-6
    assert set(last["ny"]) == {-1.0}
    assert abs(r.series["e0.fn.slope [N]"].iloc[-1] / weight - 1) < 1e-6  # the two points summed
