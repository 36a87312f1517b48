#!/usr/bin/env python3
"""Calibrates the wall friction μ_w of a small silo to a target discharge rate (python/README.md, "Calibration").

The discharge of a silo is chaotic: runs that differ only in the last digits of the fill give rates that
differ by about 10 %. So each friction value is run with several replicates (fills of different seeds, the
same seeds at every μ_w: common random numbers), a smooth model rate(μ_w) = a + b μ_w + c μ_w² is fitted to
every run by least squares (scipy.optimize.curve_fit, with the covariance of a, b, c), and the μ_w whose
model rate equals the target is found with scipy.optimize.brentq. Its uncertainty is propagated from the
fit's covariance and the target's own standard error (delta method):

    var(μ*) = (gᵀ C g + se_target²) / (d rate/d μ_w)²,   g = (1, μ*, μ*²)

Usage (PYTHONPATH=build/python /usr/bin/python3 python/examples/calibrate_friction.py ...):
    --target 170 --target-se 3        a measured rate [1/s] and its standard error
    --true-mu 0.25                    or: make the target from runs at a known μ_w (other seeds), to test
Options: --case, --grid 0,0.1,0.2,0.3,0.4, --replicates 4, --target-replicates 8, --jobs 2, --parameter,
--seed-key, --probe. The case's probe (default `rate`, the slope of discharged.count) is the rate.
"""
import argparse
import concurrent.futures
import math
import os
import pathlib
import sys

import numpy
import scipy.optimize

import dem2d

HERE = pathlib.Path(__file__).resolve().parent


def rate(case_path, mu, seed, parameter, seed_key, probe):
    """One run: the probe's value [1/s] at wall friction `mu` for the fill of `seed`."""
    case = dem2d.load_case(case_path, sets={parameter: repr(float(mu)), seed_key: str(int(seed))})
    r = dem2d.run(case, out=None, threads=1)
    if r.status != "completed" or r.probes.get(probe) is None:
        raise RuntimeError(f"mu = {mu}, seed = {seed}: run {r.status}, {probe} = {r.probes.get(probe)}: {r.message}")
    return float(r.probes[probe])


def run_all(points, args):
    """The rates of (mu, seed) points, `args.jobs` runs at a time (the GIL is released while a run runs)."""
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        jobs = [pool.submit(rate, args.case, mu, seed, args.parameter, args.seed_key, args.probe) for mu, seed in points]
        return numpy.array([j.result() for j in jobs])


def model(mu, a, b, c):
    return a + b * mu + c * mu * mu


def calibrate(mus, rates, target, target_se):
    """μ* with model(μ*) = target and its standard deviation; the fit (parameters, covariance, residual sd)."""
    p, cov = scipy.optimize.curve_fit(model, mus, rates, p0=(rates.mean(), 0.0, 0.0))
    lo, hi = float(mus.min()), float(mus.max())
    f = lambda m: model(m, *p) - target  # noqa: E731
    if f(lo) * f(hi) > 0:
        raise ValueError(f"the target {target:.4g} lies outside the fitted rates {model(lo, *p):.4g} .. "
                         f"{model(hi, *p):.4g} over mu_w = {lo:g} .. {hi:g}: widen the grid")
    mu_star = scipy.optimize.brentq(f, lo, hi, xtol=1e-10)
    g = numpy.array([1.0, mu_star, mu_star ** 2])
    slope = p[1] + 2.0 * p[2] * mu_star
    sd = math.sqrt(float(g @ cov @ g) + target_se ** 2) / abs(slope)
    residual_sd = float(numpy.std(rates - model(mus, *p), ddof=3))
    return mu_star, sd, {"params": p, "cov": cov, "slope": slope, "residual_sd": residual_sd}


def make_target(args):
    """The mean rate and its standard error of `target_replicates` runs at the known μ_w (seeds after the fit's)."""
    seeds = range(1001, 1001 + args.target_replicates)
    r = run_all([(args.true_mu, s) for s in seeds], args)
    return float(r.mean()), float(r.std(ddof=1) / math.sqrt(len(r))), r


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--case", default=str(HERE / "small_silo.toml"))
    ap.add_argument("--target", type=float, help="the target rate [1/s]")
    ap.add_argument("--target-se", type=float, default=0.0, help="its standard error [1/s]")
    ap.add_argument("--true-mu", type=float, help="make the target from runs at this mu_w instead")
    ap.add_argument("--target-replicates", type=int, default=8)
    ap.add_argument("--grid", default="0,0.1,0.2,0.3,0.4", help="mu_w values run (comma-separated)")
    ap.add_argument("--replicates", type=int, default=4, help="fills (seeds 1..N) per mu_w")
    ap.add_argument("--jobs", type=int, default=min(2, os.cpu_count() or 1))
    ap.add_argument("--parameter", default="contact.1.friction", help="the override key of mu_w")
    ap.add_argument("--seed-key", default="arrangement.0.seed", help="the override key of the fill's seed")
    ap.add_argument("--probe", default="rate")
    args = ap.parse_args(argv)
    if (args.target is None) == (args.true_mu is None):
        ap.error("give exactly one of --target or --true-mu")
    if args.true_mu is not None:
        args.target, args.target_se, runs = make_target(args)
        print(f"target: {len(runs)} runs at mu_w = {args.true_mu:g}: rate = {args.target:.4g} ± {args.target_se:.2g} 1/s "
              f"(run sd {runs.std(ddof=1):.3g})")
    grid = [float(x) for x in args.grid.split(",")]
    points = [(mu, s) for mu in grid for s in range(1, args.replicates + 1)]
    rates = run_all(points, args)
    mus = numpy.array([mu for mu, _ in points])
    for mu in grid:
        r = rates[mus == mu]
        print(f"  mu_w = {mu:5.3f}: rate = {r.mean():7.4g} ± {r.std(ddof=1) / math.sqrt(len(r)):.2g} 1/s ({len(r)} runs)")
    mu_star, sd, fit = calibrate(mus, rates, args.target, args.target_se)
    a, b, c = fit["params"]
    print(f"fit: rate = {a:.4g} + {b:.4g} mu_w + {c:.4g} mu_w^2 (residual sd {fit['residual_sd']:.3g} 1/s, "
          f"{len(rates)} runs)")
    print(f"mu_w = {mu_star:.4f} ± {sd:.4f} (1 sd; 95 %: {mu_star - 1.96 * sd:.3f} .. {mu_star + 1.96 * sd:.3f})")
    return mu_star, sd


if __name__ == "__main__":
    try:
        main()
    except dem2d.CaseError as e:
        sys.exit(f"error: {e}")
