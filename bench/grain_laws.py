"""The grains and contact laws shared by the speed suite's generated cases (bench/make_settle_case.py,
bench/make_silo_case.py; bench/lammps_input.py translates them): gravity, the grain and wall
materials, linear spring-dashpot contacts grain-grain and grain-wall. Plain numbers are SI units."""

GRAIN_LAWS = """[physics]
gravity = [0.0, -9.81]

[[material]]
name = "grain"
density = 2650.0           # kg/m^3; thickness 1 m: m = 2650 pi r^2

[[material]]
name = "wall"

[[contact]]
between = ["grain", "grain"]
law = "linear"
kn = 1.0e6                 # N/m
ks_ratio = 0.5
friction = 0.5
damping_ratio = 0.3        # with the reduced mass of the pair
end_rule = "elastic"

[[contact]]
between = ["grain", "wall"]
law = "linear"
kn = 1.0e6
ks_ratio = 0.5
friction = 0.5
damping_ratio = 0.3        # with the mass of the disk
end_rule = "elastic"
"""
