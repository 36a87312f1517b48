#!/usr/bin/env python3
# The start-up inertia of base_friction_stiffness (README, "The residual at 100 k"): a rigid 1 x 3 PRE
# block pivoting about its fixed toe corner P under Matsui's M21 (per element: force against the
# centre's velocity relative to the plate, spin moment (2/3) mu m g r (r w)/V), alpha = 45 deg, the
# plate starting at v_B at t = 0. Quasi-static rotation (moment about P zero at every theta) against the
# motion with inertia from rest, I_P theta'' = M(theta, theta'); prints theta_dyn - theta_qs.
# Usage: python3 rigid_block_inertia.py [v_B in m/s, default 5e-3]  (pure Python, ~2 min CPU)
import math, sys
v = float(sys.argv[1]) if len(sys.argv) > 1 else 5e-3
alpha = math.radians(45.0); r = 0.0125; m = 0.2014/3; g = 9.80665; mu = 0.42
gh = (-math.sin(alpha), -math.cos(alpha))            # plate direction (case: -90 deg - alpha)
b = [(r, (2*i+1)*r) for i in range(3)]               # element centres from P, block frame
IP = sum((2/3)*m*r*r + m*(bx*bx+by*by) for bx, by in b)
def moment(th, w):
    c, s = math.cos(th), math.sin(th); M = 0.0
    for bx, by in b:
        px, py = c*bx - s*by, s*bx + c*by            # rho_i
        ux, uy = -w*py - v*gh[0], w*px - v*gh[1]     # w z x rho - v g
        V = math.sqrt(ux*ux + uy*uy + (r*w)**2)
        fx, fy = -mu*m*g*ux/V, -mu*m*g*uy/V
        M += px*fy - py*fx - (2/3)*mu*m*g*r*(r*w)/V
    return M
def w_qs(th):                                        # moment(th, w) decreases in w: bisection
    lo, hi = 0.0, 10.0*v/0.075
    for _ in range(80):
        mid = 0.5*(lo+hi)
        if moment(th, mid) > 0: lo = mid
        else: hi = mid
    return 0.5*(lo+hi)
dt = 2e-5; T = 4.0; n = int(round(T/dt))
th_q = 0.0; th = 0.0; w = 0.0; out = {}
for k in range(n):
    # quasi-static: RK4 on th' = w_qs(th)
    k1 = w_qs(th_q); k2 = w_qs(th_q+0.5*dt*k1); k3 = w_qs(th_q+0.5*dt*k2); k4 = w_qs(th_q+dt*k3)
    th_q += dt*(k1+2*k2+2*k3+k4)/6
    # dynamic: RK4 on (th, w)' = (w, M/IP)
    a1 = moment(th, w)/IP; a2 = moment(th+0.5*dt*w, w+0.5*dt*a1)/IP
    a3 = moment(th+0.5*dt*(w+0.5*dt*a1), w+0.5*dt*a2)/IP; a4 = moment(th+dt*(w+0.5*dt*a2), w+dt*a3)/IP
    th += dt*(w + dt*(a1+a2+a3)/6); w += dt*(a1+2*a2+2*a3+a4)/6
    t = (k+1)*dt
    for d in (0.1e-3, 1e-3, 10e-3, 20e-3):
        if abs(t*v - d) < 0.5*dt*v: out[d] = (th, th_q)
for d, (a, q) in sorted(out.items()):
    print(f"v_B = {v*1e3:g} mm/s  delta_B = {d*1e3:5.1f} mm  theta_dyn - theta_qs = {a-q:.3e} rad  (theta_qs = {q:.6f})")
print(f"I_P = {IP:.4e} kg m^2; start-up time I_P w_qs/M(0,0) = {IP*w_qs(0.0)/moment(0.0,0.0):.3e} s")
