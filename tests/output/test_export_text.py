"""`flexlink export`'s text: per scene the number of each kind of file it wrote, then every
file that lists them (each scene's export.json and the combined record). A stand-in summary
carries only what the text reads."""

import re
from types import SimpleNamespace

import numpy as np

from flexlink.output.export import export_text


def _summary(name, n_modes):
    return SimpleNamespace(case=SimpleNamespace(scene=SimpleNamespace(name=name)),
                           frequencies=np.arange(1.0, n_modes + 1), note=None,
                           mesh=SimpleNamespace(describe=lambda: "8 elements per link"))


def _files(folder, pictures, plots):
    return {"folder": folder, "vtu": [f"{folder}/a.vtu"], "pvd": ["1.pvd", "2.pvd"],
            "frames": [f"f{i}.vtu" for i in range(48)],
            "pictures": [f"p{i}.png" for i in range(pictures)],
            "plot": [f"q{i}.png" for i in range(plots)], "record": [f"{folder}/export.json"]}


def test_counts_and_records_are_those_of_the_files():
    done = [(_summary("case 1", 4), _files("out/case1", 5, 1)),
            (_summary("case 3", 1), _files("out/case3", 2, 0))]
    lines = export_text(done, combined=None).splitlines()
    first = lines[0]
    assert first.startswith("case 1: 4 modes -> out/case1/")
    counts = dict((kind, int(n)) for n, kind in re.findall(r"(\d+) \.?(\w+)", first.split("(")[1]))
    assert counts == {"vtu": 1, "pvd": 2, "frames": 48, "pictures": 5, "plot": 1}
    assert "1 mode ->" in lines[2] and "2 pictures, 0 plots" in lines[2]
    assert lines[-1] == "written: out/case1/export.json, out/case3/export.json"
    with_combined = export_text(done, combined="out/export.json").splitlines()[-1]
    assert with_combined.endswith("out/case3/export.json, out/export.json")
