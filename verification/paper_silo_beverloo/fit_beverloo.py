#!/usr/bin/env python3
"""Fit the 2D Beverloo law W = C rho_b sqrt(g) (D - k d)^n to the steady rates of the study
paper_silo_beverloo (refs §6.2): n, k, C free, and C, k with n = 3/2.
Usage: fit_beverloo.py build/studies/paper_silo_beverloo/result.json"""
import json, math, sys

RHO_B, G, D_GRAIN = 2173.0, 9.80665, 0.01
checks = json.load(open(sys.argv[1]))["checks"]
pts = []
for c in checks:
    if c["quantity"].startswith("steady rate"):
        d_cm = float(c["quantity"].rsplit("D=", 1)[1].split()[0])
        pts.append((d_cm / 100.0, c["dem"]))
scale = RHO_B * math.sqrt(G)


def fit_c_n(k):
    """least squares of log W = log(C scale) + n log(D - k d) for a given k; returns n, C, rms of log."""
    xs = [math.log(D - k * D_GRAIN) for D, _ in pts]
    ys = [math.log(w / scale) for _, w in pts]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    n = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    c = math.exp(my - n * mx)
    rms = math.sqrt(sum((y - (math.log(c) + n * x)) ** 2 for x, y in zip(xs, ys)) / len(xs))
    return n, c, rms


def fit_c_k():
    """n = 3/2: W^(2/3) is linear in D: (W/(C scale))^(2/3) = D - k d."""
    ys = [(w / scale) ** (2.0 / 3.0) for _, w in pts]
    xs = [D for D, _ in pts]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    a = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    b = my - a * mx
    c = a ** 1.5
    k = -b / a / D_GRAIN
    return c, k


print("D [cm]  W [kg/(s m)]  W [g/(s cm)]")
for D, w in pts:
    print(f"{D*100:6.1f}  {w:10.2f}  {w*10:10.1f}")
c, k = fit_c_k()
print(f"n = 3/2 fixed: C = {c:.3f}, k = {k:.3f}")
for k_try in (1.0, 1.5, 2.0):
    n, cc, rms = fit_c_n(k_try)
    print(f"k = {k_try}: fitted n = {n:.3f}, C = {cc:.3f}, rms(log) = {rms:.4f}")
best = min((fit_c_n(kk / 100.0)[2], kk / 100.0) for kk in range(0, 300))
n, cc, rms = fit_c_n(best[1])
print(f"k, n, C all free: k = {best[1]:.2f}, n = {n:.3f}, C = {cc:.3f}, rms(log) = {rms:.4f}")
