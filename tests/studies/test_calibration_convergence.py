"""A fit whose starts stopped at the least-squares evaluation limit says so in the report, and
says whether the reported (best) start is one of them."""

from flexlink.output.calibration.calibration_report import _convergence_text


def test_every_start_converged():
    assert _convergence_text({"starts_converged": [True, True], "best_start": 1}) == \
        " Every start converged."


def test_the_best_start_stopped_at_the_limit():
    text = _convergence_text({"starts_converged": [True, False, False], "best_start": 2})
    assert "2 of 3 starts stopped at the evaluation limit" in text
    assert "including the best one" in text


def test_only_other_starts_stopped():
    text = _convergence_text({"starts_converged": [True, False], "best_start": 0})
    assert "1 of 2 starts" in text and "not the best one" in text
