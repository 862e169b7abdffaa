"""The studies' records refuse parts of the wrong shape, naming the record and the part
(``owner.part has shape ..., expected ...``), so a wiring slip is found where it is made."""

import numpy as np
import pytest
from conftest import CASES_DIR

from flexlink.studies.calibration.fit import FitResult, Problem, parse_free
from flexlink.studies.calibration.calibration import UncertaintySummary
from flexlink.studies.calibration.uncertainty import Inputs, MonteCarlo, Sensitivities

CASE2 = str(CASES_DIR / "case2.toml")


def test_a_fit_result_with_a_correlation_of_the_wrong_size_names_it():
    problem = Problem(scenes=(CASE2,), parameters=(parse_free("L1=100 mm:1 m"),), n_modes=4)
    with pytest.raises(ValueError, match=r"^FitResult\.correlation has shape \(2, 2\), "
                                         r"expected \(1, 1\)$"):
        FitResult(problem=problem, values=np.ones(1), rel_se=np.ones(1),
                  correlation=np.ones((2, 2)), at_bound=np.zeros(1, bool), cost=0.0,
                  start_costs=np.zeros(3), predicted=np.ones((1, 4)),
                  reference=np.ones((1, 4)), evaluations=1)


def test_an_uncertainty_summary_with_sensitivities_of_the_wrong_size_names_them():
    inputs = Inputs(nominal={"vf": 0.5}, sd={"vf": 0.05}, fiber_name="carbon_fiber",
                    matrix_name="polyester")
    wrong = Sensitivities(names=("vf",), values={"vf": np.ones((1, 3))}, sd_ln_f=np.ones((1, 3)))
    with pytest.raises(ValueError, match=r"^UncertaintySummary\.sensitivities\.sd_ln_f has "
                                         r"shape \(1, 3\), expected \(1, 4\)$"):
        UncertaintySummary(inputs=inputs, monte_carlo=MonteCarlo(np.ones((5, 1, 4)), seed=0),
                           sensitivities=wrong, reference=np.ones((1, 4)))
