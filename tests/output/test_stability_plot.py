"""The stability map's picture draws what its docstring promises: each unstable range shaded on
both panels (red: parametric, grey: divergence) and every crank harmonic k x speed labelled.

A hand-built map and model (plain namespaces: the picture reads only these fields)."""

from types import SimpleNamespace

import numpy as np
import pytest
from matplotlib.colors import to_rgba

import flexlink.output.figures
from flexlink.output.running.stability_map import plot_stability
from flexlink.units import RPM


def test_ranges_are_shaded_by_kind_and_harmonics_labelled(tmp_path, monkeypatch):
    kept = []
    monkeypatch.setattr(flexlink.output.figures, "write_figure",
                        lambda fig, path, dpi=120: kept.append(fig))
    speeds = np.arange(0.0, 1001.0, 100.0) * RPM
    result = SimpleNamespace(
        speeds=speeds, largest_modulus=np.linspace(0.9, 1.3, speeds.size),
        ranges=(SimpleNamespace(kind="divergence", low=200 * RPM, high=300 * RPM),
                SimpleNamespace(kind="parametric", low=700 * RPM, high=800 * RPM)))
    model = SimpleNamespace(checked=np.array([10.0, 30.0]), basis=None)
    plot_stability(result, model, tmp_path / "map.png", "case1", harmonics=3)
    [fig] = kept
    campbell, modulus = fig.axes
    for ax in (campbell, modulus):
        spans = [p for p in ax.patches if p.get_x() > 100.0]  # the bands start at x = 0
        # each unstable speed stands for half a grid step (50 rev/min) either side
        by_start = {round(p.get_x()): p.get_facecolor()[:3] for p in spans}
        assert by_start == {150: pytest.approx(to_rgba("0.5")[:3]),
                            650: pytest.approx(to_rgba("tab:red")[:3])}
    labels = sorted(t.get_text() for t in campbell.texts)
    assert labels == ["1x", "2x", "3x"]
    # top of the diagram: 1.15 x 30 Hz; k x speed reaches it at 60 top / k rev/min
    top = 1.15 * 30.0
    for t in campbell.texts:
        k = int(t.get_text()[:-1])
        at = min(1000.0, 60.0 * top / k)
        assert t.xy == pytest.approx((at, k * at / 60.0))
