#!/usr/bin/env python3
"""Static checks of a settled silo run (refs §6.1): the force on all walls together equals the total
weight (bottom normal + side-wall friction = weight), left and right side-wall normal forces cancel.
Usage: balance.py RUN_FOLDER (reads summary.json)."""
import json, math, sys

s = json.load(open(sys.argv[1] + "/summary.json"))
p = {k: (v["value"] if isinstance(v, dict) else v) for k, v in s["probes"].items()}
n = s.get("elements") or int(sys.argv[2])
weight = n * 2650.0 * math.pi * 0.01 ** 2 * 1.0 * 9.80665  # ρ π r² l g per disk, l = 1 m
bottom = -(p["bottom_fy"] + p["bottom_right_fy"] + p["gate_fy"])
side = -(p["left_fy"] + p["right_fy"])
print(f"disks {n}, weight {weight:.6g} N/m; bottom normal {bottom:.6g}, side-wall friction {side:.6g} "
      f"({100*side/weight:.3f} %); balance error {(bottom + side - weight) / weight:.3e}; "
      f"all walls (walls.fy) {(-p['walls_fy'] - weight) / weight:.3e}")
print(f"left.fx {p['left_fx']:.6g}, right.fx {p['right_fx']:.6g}, (left+right)/|left| = "
      f"{(p['left_fx'] + p['right_fx']) / abs(p['left_fx']):.3e}")
