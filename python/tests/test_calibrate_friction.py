"""python/examples/calibrate_friction.py: the wall friction of the small silo (python/examples/small_silo.toml)
is recovered from a target rate made with a known mu_w = 0.25 (8 fills other than the fit's 5 x 4), within
0.1 and within 3 of its own standard deviations (measured: 0.248 ± 0.048; python/README.md). About 10 s on
two threads. The fit and the inversion on synthetic data, and a target outside the fitted range is refused."""
import importlib.util
import pathlib

import numpy
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
spec = importlib.util.spec_from_file_location("calibrate_friction", ROOT / "python/examples/calibrate_friction.py")
calibrate_friction = importlib.util.module_from_spec(spec)
spec.loader.exec_module(calibrate_friction)

TRUE_MU, TOLERANCE = 0.25, 0.1


def test_recovers_a_known_wall_friction():
    mu, sd = calibrate_friction.main(["--true-mu", str(TRUE_MU), "--jobs", "2"])
    assert abs(mu - TRUE_MU) <= TOLERANCE, (mu, sd)
    assert abs(mu - TRUE_MU) <= 3 * sd, (mu, sd)
    assert 0 < sd < TOLERANCE, sd  # the replicates make the answer informative


def test_inversion_on_synthetic_rates():
    rng = numpy.random.default_rng(7)
    mus = numpy.repeat([0.0, 0.1, 0.2, 0.3, 0.4], 20)
    rates = 200.0 - 150.0 * mus + 50.0 * mus ** 2 + rng.normal(0.0, 5.0, mus.size)
    target = 200.0 - 150.0 * 0.3 + 50.0 * 0.09
    mu, sd, fit = calibrate_friction.calibrate(mus, rates, target, 1.0)
    assert abs(mu - 0.3) < 3 * sd and sd < 0.03, (mu, sd)
    assert fit["slope"] < 0


def test_a_target_outside_the_fitted_rates_is_refused():
    mus = numpy.repeat([0.0, 0.2, 0.4], 3)
    rates = 200.0 - 100.0 * mus + numpy.tile([-1.0, 0.0, 1.0], 3)
    with pytest.raises(ValueError, match="outside the fitted rates"):
        calibrate_friction.calibrate(mus, rates, 300.0, 0.0)
