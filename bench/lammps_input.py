#!/usr/bin/env python3
"""Translates the benchmark case (cases/bench/settle_10k.toml) into a LAMMPS data file and input script
for the same physical setup, single core:

    python3 bench/lammps_input.py CASE OUTDIR [--style gran|granular]

Writes OUTDIR/settle.data and OUTDIR/in.settle. Supports only what the benchmarks use: [[row]]
generators of disks, axis-aligned segment walls forming a box, one grain-grain and one grain-wall
linear law (kn, ks_ratio, friction, damping_ratio), gravity, K18 with dt and duration.

A case with [discharge] (the silo, bench/make_silo_case.py) is written as OUTDIR/silo.data and
OUTDIR/in.silo instead: vertical walls as `fix wall/gran xplane`; each horizontal wall (the floor on
either side of the slit, and the gate across it) as `fix wall/gran/region` on a thin block (0.1 mm) under
the segment with `side out` (particles outside the block meet its surface: its top face, and its
corners at the segment's ends, as dem2d's segment ends); the run in two parts, the gate's fix removed
after open_at (`unfix`); the box's bottom lies outlet_depth below the slit and atoms leaving it are lost
(`thermo_modify lost ignore`: dem2d removes a disk once its centre is that deep, LAMMPS at the next
neighbour-list rebuild after it crossed). The speed is the sum of both parts' Loop times.

Mapping of the linear spring-dashpot (dem2d: eta_n = 2 zeta sqrt(m_eff k_n), eta_s = eta_n sqrt(k_s/k_n))
onto LAMMPS' Hookean styles, whose dashpot is m_eff gamma:
  gran       pair_style gran/hooke/history kn kt gamma_n gamma_t mu 1 with gamma_n = 2 zeta sqrt(k_n/m_eff)
             for the mean reduced mass of the packing (LAMMPS has one gamma_n per run, dem2d one eta per pair:
             with radii within +-5 % of the mean the dashpots agree within about 5 %),
             gamma_t = gamma_n sqrt(k_s/k_n); walls: fix wall/gran hooke/history, m_eff = particle mass.
  granular   pair_style granular, hooke + damping mass_velocity + tangential linear_history, same numbers.
Known differences that do not change the work per contact: LAMMPS caps the total tangential force at
mu times the total normal force (dem2d: the elastic parts), integrates with velocity Verlet (dem2d: K18,
symplectic Euler), and rotates the tangential history vector (dem2d: a scalar on the current tangent)."""
import math
import sys
import tomllib
from pathlib import Path


def main():
    args = sys.argv[1:]
    style = "gran"
    if "--style" in args:
        k = args.index("--style")
        style = args[k + 1]
        del args[k:k + 2]
    case_path, out = Path(args[0]), Path(args[1])
    out.mkdir(parents=True, exist_ok=True)
    c = tomllib.loads(case_path.read_text())

    mats = {m["name"]: m for m in c["material"]}
    disks = []  # (r, x, y, density)
    for row in c["row"]:
        rho = mats[row["material"]]["density"]
        for k in range(row["count"]):
            disks.append((row["radius"], row["start"][0] + k * row["step"][0], row["start"][1] + k * row["step"][1], rho))
    xs = [p for w in c["wall"] for p in (w["from"][0], w["to"][0])]
    ys = [p for w in c["wall"] for p in (w["from"][1], w["to"][1])]
    for w in c["wall"]:
        assert w["from"][0] == w["to"][0] or w["from"][1] == w["to"][1], "walls must be axis-aligned"
    xlo, xhi, ylo, yhi = min(xs), max(xs), min(ys), max(ys)
    silo = c.get("discharge")
    name = "silo" if silo else "settle"
    wall_material = c["wall"][0]["material"]

    def law(a, b):
        for ct in c["contact"]:
            if sorted(ct["between"]) == sorted([a, b]):
                return ct
        raise SystemExit(f"no contact law between {a} and {b}")

    grain = c["row"][0]["material"]
    gg, gw = law(grain, grain), law(grain, wall_material)
    for ct in (gg, gw):
        assert ct.get("law", "linear") == "linear" and "eta_n" not in ct and "ks" not in ct
    rho = mats[grain]["density"]
    thickness = c.get("physics", {}).get("thickness", 1.0)
    masses = [rho * math.pi * r * r * thickness for r, *_ in disks]
    m_mean = sum(masses) / len(masses)
    m_eff_pair = m_mean / 2.0  # mean reduced mass of two disks of the mean mass

    def coeffs(ct, m_eff):
        kn = ct["kn"]
        ks_ratio = ct.get("ks_ratio", 0.0)
        gamma_n = 2.0 * ct.get("damping_ratio", 0.0) * math.sqrt(kn / m_eff)
        return kn, ks_ratio * kn, gamma_n, gamma_n * math.sqrt(ks_ratio), ct.get("friction", 0.0)

    kn, kt, gn, gt, mu = coeffs(gg, m_eff_pair)
    wkn, wkt, wgn, wgt, wmu = coeffs(gw, m_mean)
    num = c["numerics"]
    assert num.get("integrator", "K18") == "K18"
    dt = num["dt"]
    steps = math.ceil(num["duration"] / dt - 1e-9)
    rmin = min(r for r, *_ in disks)
    skin = num.get("skin", 0.0) or 0.25 * rmin
    g = c["physics"]["gravity"]
    gmag = math.hypot(g[0], g[1])

    pad = 0.0  # the box is the walls' box; LAMMPS needs atoms inside [lo, hi)
    if silo:  # the box reaches outlet_depth below the slit: an atom leaving it is lost (dem2d: removed)
        gate = next(w for w in c["wall"] if w["name"] == silo["slit"])
        assert gate["from"][1] == gate["to"][1], "the slit must be horizontal"
        ylo = gate["from"][1] - silo["outlet_depth"]
    with open(out / f"{name}.data", "w") as f:
        f.write(f"LAMMPS data file from {case_path} (bench/lammps_input.py)\n\n{len(disks)} atoms\n1 atom types\n\n")
        f.write(f"{xlo - pad!r} {xhi + pad!r} xlo xhi\n{ylo - pad!r} {yhi + pad!r} ylo yhi\n-0.5 0.5 zlo zhi\n\nAtoms # sphere\n\n")
        for k, (r, x, y, d) in enumerate(disks, 1):
            f.write(f"{k} 1 {2.0 * r!r} {d!r} {x!r} {y!r} 0.0\n")
    if style == "gran":
        pair = f"pair_style gran/hooke/history {kn!r} {kt!r} {gn!r} {gt!r} {mu!r} 1\npair_coeff * *"
        wall_model = f"hooke/history {wkn!r} {wkt!r} {wgn!r} {wgt!r} {wmu!r} 1"
    elif style == "granular":
        pair = (f"pair_style granular\npair_coeff * * hooke {kn!r} {gn!r} tangential linear_history {kt!r} "
                f"{gt / gn!r} {mu!r} damping mass_velocity")
        wall_model = (f"granular hooke {wkn!r} {wgn!r} tangential linear_history {wkt!r} {wgt / wgn!r} {wmu!r} "
                      f"damping mass_velocity")
    else:
        raise SystemExit(f"unknown --style {style}")
    if silo:
        walls = f"fix             xwalls all wall/gran {wall_model} xplane {xlo!r} {xhi!r}\n"
        for w in c["wall"]:
            if w["from"][0] == w["to"][0]:
                assert w["from"][0] in (xlo, xhi), "vertical walls: the box's sides only"
                continue
            x0, x1 = sorted((w["from"][0], w["to"][0]))
            y = w["from"][1]
            walls += (f"region          {w['name']} block {x0!r} {x1!r} {y - 1e-4!r} {y!r} -0.5 0.5 side out units box\n"
                      f"fix             {w['name']} all wall/gran/region {wall_model} region {w['name']}\n")
        open_steps = round(silo.get("open_at", 0.0) / dt)
        if open_steps >= steps:  # the gate stays closed to the end
            runs = f"run             {steps}\n"
        else:
            runs = (f"run             {open_steps}\nunfix           {silo['slit']}\n" if open_steps > 0 else
                    f"unfix           {silo['slit']}\n") + f"run             {steps - open_steps}\n"
    else:
        walls = (f"fix             xwalls all wall/gran {wall_model} xplane {xlo!r} {xhi!r}\n"
                 f"fix             ywalls all wall/gran {wall_model} yplane {ylo!r} {yhi!r}\n")
        runs = f"run             {steps}\n"
    (out / f"in.{name}").write_text(f"""# {c['case']['title']}: the same setup as {case_path} (bench/lammps_input.py)
units           si
dimension       2
atom_style      sphere
atom_modify     map array
boundary        f f p
newton          off
comm_modify     vel yes
read_data       {name}.data
set             group all density/disc {rho * thickness!r}
variable        m1 equal mass[1]
print           "mass of disk 1: ${{m1}} kg"
neighbor        {skin!r} bin
neigh_modify    delay 0 every 1 check yes
{pair}
timestep        {dt!r}
fix             integrate all nve/sphere disc
fix             gravity all gravity {gmag!r} vector {g[0] / gmag!r} {g[1] / gmag!r} 0.0
{walls}fix             plane all enforce2d
compute         contacts all contact/atom
compute         ncontacts all reduce sum c_contacts
variable        pair_contacts equal c_ncontacts/2
thermo_style    custom step atoms ke v_pair_contacts
thermo          {max(1, steps // 10)}
thermo_modify   norm no lost {"ignore" if silo else "error"}
{runs}""")
    print(f"{len(disks)} disks, {steps} steps, dt = {dt} s, skin = {skin} m, style {style}")


main()
