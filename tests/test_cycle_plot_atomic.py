"""The cycle map's PNG is written like every other output: a drawing that fails half-way
leaves the previous picture as it was, and the new one gets the umask's permissions."""

import os
import stat

import numpy as np
import pytest
from matplotlib.figure import Figure

from flexlink.output.cycle_report import plot_map
from flexlink.studies.cycle import ModalMap


def small_map() -> ModalMap:
    q = np.linspace(0, 2 * np.pi, 12, endpoint=False)
    return ModalMap(scene="test", q=q, frequencies=np.column_stack([10 + np.sin(q), 30 + np.cos(q)]),
                    mechanism_counts=np.ones(12, dtype=int), mu90={"a/b": np.array([1.0])})


def test_a_drawing_that_fails_half_way_keeps_the_old_picture(tmp_path, monkeypatch):
    target = tmp_path / "case-cycle.png"
    target.write_bytes(b"old picture")
    real = Figure.savefig

    def half_then_fail(self, fname, **kwargs):
        if hasattr(fname, "write"):
            fname.write(b"\x89PNG half")
        else:
            with open(fname, "wb") as fh:
                fh.write(b"\x89PNG half")
        raise RuntimeError("renderer died")

    monkeypatch.setattr(Figure, "savefig", half_then_fail)
    with pytest.raises(RuntimeError):
        plot_map(small_map(), target)
    assert target.read_bytes() == b"old picture"
    monkeypatch.setattr(Figure, "savefig", real)
    previous = os.umask(0o022)
    try:
        plot_map(small_map(), target)
    finally:
        os.umask(previous)
    assert target.read_bytes()[:4] == b"\x89PNG"
    assert stat.S_IMODE(target.stat().st_mode) == 0o644
    assert [p.name for p in tmp_path.iterdir()] == ["case-cycle.png"]
