"""The Campbell diagrams and the convergence plot as drawn: each axis labelled with its
quantity and unit, and on the Campbell diagrams the harmonic lines read in those units, n x
speed / 60 Hz at a speed in rev/min. The figures are caught before they are written (the
plot functions hand them to ``write_figure`` or close them after saving), from hand-made
bands, so nothing is solved."""

from __future__ import annotations

import math

import numpy as np
import pytest

import flexlink.output.cycle.campbell as campbell_report
import flexlink.output.verification.convergence as convergence_report
from flexlink.studies.cycle.bands import Band, CriticalSpeed
from flexlink.studies.verification.convergence import CHOICES, Level
from flexlink.studies.running.dynamic_campbell import DynamicCampbell

RAD_S_PER_RPM = 2 * math.pi / 60
HARMONICS = 3


@pytest.fixture
def caught(monkeypatch):
    import matplotlib.pyplot as plt

    figures = []

    def keep(fig, path):
        figures.append(fig)

    monkeypatch.setattr(campbell_report, "write_figure", keep)
    monkeypatch.setattr(convergence_report, "write_figure", keep)
    yield figures
    for fig in figures:
        plt.close(fig)


def _harmonic_slopes(ax) -> list[float]:
    """The slope [Hz per rev/min] of each straight line through the origin on ``ax``."""
    slopes = []
    for line in ax.get_lines():
        x, y = (np.asarray(v, dtype=float) for v in line.get_data())
        if len(x) >= 2 and x[-1] > 0 and abs(y[0] - x[0] * y[-1] / x[-1]) < 1e-9 * y[-1]:
            slopes.append(y[-1] / x[-1])
    return slopes


def test_campbell_diagram_axes_are_speed_in_rev_per_min_and_frequency_in_hz(caught):
    bands = [Band(1, 9.0, 11.0), Band(2, 29.0, 31.0)]
    critical = [CriticalSpeed(2, 3, 580 * RAD_S_PER_RPM, 620 * RAD_S_PER_RPM)]
    campbell_report.plot_campbell(bands, (0.0, 1000 * RAD_S_PER_RPM), 0.05, HARMONICS,
                                  critical, "unused.png", "synthetic")
    [fig] = caught
    [ax] = fig.axes
    assert ax.get_xlabel() == "crank speed [rev/min]"
    assert ax.get_ylabel() == "frequency [Hz]"
    assert ax.get_xlim() == pytest.approx((0, 1000))
    assert sorted(_harmonic_slopes(ax)) == pytest.approx([n / 60 for n in (1, 2, 3)], rel=1e-12)


def test_campbell_at_speed_axes_are_the_same(monkeypatch, tmp_path):
    import matplotlib.pyplot as plt

    figures = []
    monkeypatch.setattr(plt, "close", figures.append)  # keep the figure plot_dynamic closes
    q = np.linspace(0, 2 * math.pi, 4, endpoint=False)
    static = np.column_stack([10 + np.sin(q), 30 + np.cos(q)])
    speeds = np.array([0.0, 500.0, 1000.0]) * RAD_S_PER_RPM
    result = DynamicCampbell(scene="synthetic", q=q, speeds=speeds,
                             frequencies=np.stack([static, static, static]), static=static,
                             basis=5)
    campbell_report.plot_dynamic(result, 0.05, HARMONICS, tmp_path / "at_speed.png", "synthetic")
    [fig] = figures
    [ax] = fig.axes
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("crank speed [rev/min]", "frequency [Hz]")
    assert sorted(_harmonic_slopes(ax)) == pytest.approx([n / 60 for n in (1, 2, 3)], rel=1e-12)
    monkeypatch.undo()
    plt.close(fig)


def test_convergence_plot_axes_name_time_in_seconds_and_the_error(caught):
    levels = [Level(CHOICES[0], n, 3 * n, 1e-3 * n, 2e-3 * n, np.array([1 + n**-2.0]))
              for n in (1, 2, 4)]
    convergence_report.plot_error_time(levels, np.array([1.0]), "unused.png")
    [fig] = caught
    [ax] = fig.axes
    assert ax.get_xlabel() == "median wall time per solve, assembly + eigen solve [s]"
    assert ax.get_ylabel() == "max relative frequency error vs Richardson reference"
    # the points are (time, error) of each level: error 1 / n^2 of the reference 1
    x, y = ax.get_lines()[0].get_data()
    assert list(x) == pytest.approx([3e-3 * n for n in (1, 2, 4)], rel=1e-12)
    assert list(y) == pytest.approx([n**-2.0 for n in (1, 2, 4)], rel=1e-12)
