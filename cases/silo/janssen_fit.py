#!/usr/bin/env python3
"""Side-wall normal force per depth band of a settled silo run against Janssen (refs §6.1): fits the
lateral ratio K (least squares over the bands of both walls, μ_w = tan φ_w as in the case) and compares
it with K_geom of the ordered packing. Usage: janssen_fit.py CASE.toml RUN_FOLDER S
(S: disks in a full row; the free surface H = 2r + (rows − 1) d_y of the (S−1)/S packing, refs §6.1)."""
import json, math, re, sys, tomllib

case, run, s_row = sys.argv[1], sys.argv[2], int(sys.argv[3])
B, r, rho, g, mu_w = 0.40, 0.01, 2650.0, 9.80665, math.tan(math.radians(10.0))
summary = json.load(open(run + "/summary.json"))
n = summary["elements"]
dx = (B - 2 * r) / (s_row - 1)
dy = math.sqrt(4 * r * r - dx * dx / 4)
k_geom = (dx / 2) ** 2 / dy ** 2
phi_a = (2 * s_row - 1) * math.pi * r * r / (2 * B * dy)
rho_b = rho * phi_a
rows = 2 * (n // (2 * s_row - 1)) + (1 if n % (2 * s_row - 1) else 0)
H = 2 * r + (rows - 1) * dy

def janssen(z1, z2, K):  # horizontal force per unit thickness on the band z1..z2 (refs §6.1)
    z0 = B / (2 * K * mu_w)
    return rho_b * g * B / (2 * mu_w) * ((z2 - z1) - z0 * (math.exp(-z1 / z0) - math.exp(-z2 / z0)))

probes = {k: (v["value"] if isinstance(v, dict) else v) for k, v in summary["probes"].items()}
bands = []
for pr in tomllib.load(open(case, "rb"))["probe"]:
    m = re.fullmatch(r"(left|right)\.fn\(([-0-9.e]+),([-0-9.e]+)\)", pr.get("quantity", ""))
    if m:
        y0, y1 = float(m.group(2)), min(float(m.group(3)), H)
        bands.append((m.group(1), max(H - y1, 0.0), H - y0, probes[pr["name"]]))

def sse(K): return sum((f - janssen(z1, z2, K)) ** 2 for _, z1, z2, f in bands)
lo, hi = 1e-3, 20.0  # golden section on K (sse is unimodal here)
for _ in range(200):
    a, b = lo + (hi - lo) * 0.382, lo + (hi - lo) * 0.618
    lo, hi = (lo, b) if sse(a) < sse(b) else (a, hi)
k_fit = 0.5 * (lo + hi)
mean = sum(f for *_, f in bands) / len(bands)
r2 = 1 - sse(k_fit) / sum((f - mean) ** 2 for *_, f in bands)
print(f"{case}: {n} disks, {rows} rows, H = {100*H:.2f} cm, rho_b = {rho_b:.1f} kg/m^3, mu_w = {mu_w:.4f}")
print(f"K_geom = {k_geom:.4f}; K fitted = {k_fit:.4f} (R^2 = {r2:.3f}); K_fit/K_geom = {k_fit/k_geom:.3f}")
print("wall  z1[cm] z2[cm]  DEM[N/m]  Janssen(K_geom)  Janssen(K_fit)  DEM/J(K_geom)  K of the band")
for w, z1, z2, f in bands:
    jg, jf = janssen(z1, z2, k_geom), janssen(z1, z2, k_fit)
    lo, hi = 1e-4, 50.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if janssen(z1, z2, mid) < f else (lo, mid)
    print(f"{w:5s} {100*z1:6.2f} {100*z2:6.2f} {f:9.2f} {jg:14.2f} {jf:14.2f} {f/jg:13.3f} {0.5*(lo+hi):10.3f}")
