"""The cycle map's PNG is written like every other output: a drawing that fails half-way
leaves the previous picture as it was, and the new one gets the umask's permissions."""

import os
import stat

import numpy as np
import pytest
from matplotlib.figure import Figure

from flexlink.output.cycle.modal_map import plot_map
from flexlink.studies.cycle.modal_map import ModalMap


def small_map() -> ModalMap:
    q = np.linspace(0, 2 * np.pi, 12, endpoint=False)
    return ModalMap(scene="test", q=q, frequencies=np.column_stack([10 + np.sin(q), 30 + np.cos(q)]),
                    mechanism_counts=np.ones(12, dtype=int), mu90={"a/b": np.array([1.0])})


def half_then_fail(self, fname, **kwargs):
    """Figure.savefig that writes half a PNG, then fails as a dying renderer would."""
    if hasattr(fname, "write"):
        fname.write(b"\x89PNG half")
    else:
        with open(fname, "wb") as fh:
            fh.write(b"\x89PNG half")
    raise RuntimeError("renderer died")


def test_a_drawing_that_fails_half_way_keeps_the_old_picture(tmp_path, monkeypatch):
    target = tmp_path / "case-cycle.png"
    target.write_bytes(b"old picture")
    real = Figure.savefig

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


def test_tracked_and_campbell_pictures_are_written_atomically(tmp_path, monkeypatch):
    """The Campbell diagram and the tracked map go through the same writer: a renderer dying
    half-way leaves the old picture and no temporary file."""
    from flexlink.output.cycle.campbell import plot_campbell
    from flexlink.output.cycle.tracking import plot_tracked
    from flexlink.studies.cycle.bands import Band
    from flexlink.units import RPM
    from flexlink.studies.cycle.tracking import TrackedMap, Tracks

    q = small_map().q
    f = small_map().frequencies
    tracked = TrackedMap(scene="test", q=q, frequencies=f, mu90={},
                         tracks=Tracks(frequencies=f, shapes=(), mac=np.ones_like(f),
                                       rank=np.zeros_like(f, dtype=int), events=()))
    draws = {
        "campbell.png": lambda path: plot_campbell([Band(1, 9.0, 11.0)], (0.0, 3000 * RPM), 0.05,
                                                   3, [], path),
        "tracked.png": lambda path: plot_tracked(tracked, path),
    }

    monkeypatch.setattr(Figure, "savefig", half_then_fail)
    for name, draw in draws.items():
        target = tmp_path / name
        target.write_bytes(b"old picture")
        with pytest.raises(RuntimeError):
            draw(target)
        assert target.read_bytes() == b"old picture"
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(draws)
