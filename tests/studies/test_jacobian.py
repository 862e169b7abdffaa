"""The calibration's Jacobian from eigenvalue sensitivities (studies/calibration/jacobian.py) against central
finite differences of the residuals on full evaluations, for every free input of each model
family, both residual kinds, and a joint that keeps a bearing stiffness of its own (so it must
not follow the global Kt)."""


import numpy as np
import pytest

from flexlink.studies.calibration import fit as cal
from flexlink.studies.calibration.calibration import default_free

from conftest import CASES_DIR as CASES
SCENES = tuple(str(CASES / f"case{i}.toml") for i in (1, 3))


def finite_difference(problem, reference, x, h=1e-3):
    """Central differences on fresh evaluations (truncation ~h^2, round-off ~1e-13 / h)."""
    columns = []
    for j in range(len(x)):
        up, down = x.copy(), x.copy()
        up[j] += h
        down[j] -= h
        columns.append((cal._Residuals(problem, reference).residuals(up)
                        - cal._Residuals(problem, reference).residuals(down)) / (2 * h))
    return np.array(columns).T


@pytest.mark.parametrize("family,target,fixed", [
    ("planar", "frequencies", ()),
    ("planar", "ratios", (("joints.O2.Kt", "3e6 N/m"),)),
    ("out-of-plane", "frequencies", (("joints.A.Ktilt", "20 N*m/rad"),)),
    ("3d", "frequencies", ()),
])
def test_sensitivities_match_finite_differences(family, target, fixed):
    problem = cal.Problem(scenes=SCENES, parameters=default_free(family), elements=4,
                          target=target, fixed=(("model.family", family),) + fixed)
    reference = cal.measured(problem)
    lo, hi = problem.bounds
    rng = np.random.default_rng(3)
    for _ in range(2):
        x = lo + (hi - lo) * rng.uniform(0.3, 0.6, size=len(lo))
        fit = cal._Residuals(problem, reference)
        fit.residuals(x)
        J = fit.jacobian(x)
        F = finite_difference(problem, reference, x)
        assert J.shape == F.shape
        scale = np.abs(F).max(axis=0)
        # the forward steps of L1 and the section inputs carry O(1e-5) truncation
        np.testing.assert_allclose(J, F, rtol=0, atol=1e-3 * scale.max() + 1e-5)
        assert np.all(np.abs(J - F).max(axis=0) <= 2e-3 * scale + 1e-5), \
            [p.name for p in problem.parameters]


def test_a_joint_with_its_own_stiffness_does_not_follow_the_global_key():
    problem = cal.Problem(scenes=SCENES[:1], parameters=default_free("planar"), elements=4,
                          fixed=(("model.family", "planar"), ("joints.O2.Kt", "3e6 N/m")))
    x = np.mean(problem.bounds, axis=0)
    fit = cal._Residuals(problem, cal.measured(problem))
    fit.residuals(x)
    fit.jacobian(x)
    kt = [p.name for p in problem.parameters].index("Kt")
    [(springs, masses)] = fit.followers[(0, kt)]
    labels = fit._evaluate(x)[0].parts[0].model.springs.labels
    followed = {label.split()[0] for label, on in zip(labels, springs) if on}
    assert followed == {"A", "B", "O4"} and not masses.any()


def test_followers_probe_downwards_where_the_upward_probe_fails():
    """At the top of a range the scaled-up load fails: the probe goes down instead and finds
    the same springs."""
    from flexlink.errors import InputError
    from flexlink.studies.calibration.jacobian import followers

    problem = cal.Problem(scenes=SCENES[:1], parameters=default_free("planar"), elements=4,
                          fixed=(("model.family", "planar"),))
    values = np.exp(np.mean(problem.bounds, axis=0))
    kt = [p.name for p in problem.parameters].index("Kt")

    def capped(v):
        if v[kt] > values[kt]:
            raise InputError("above the range", field="joints.Kt")
        return problem.scene(SCENES[0], v)

    free = followers(lambda v: problem.scene(SCENES[0], v), values, kt, ["in-plane"], 4)
    down = followers(capped, values, kt, ["in-plane"], 4)
    assert down is not None and np.array_equal(free[0][0], down[0][0]) and free[0][0].any()
