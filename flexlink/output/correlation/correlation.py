"""A test-model correlation (``studies.correlation.correlation``) as JSON, text, CSV, pictures
(the MAC heat map; test and model shapes of each pair overlaid on the linkage) and ParaView
files (the model's paired shapes on the links, the test's at the sensors, both scaled onto the
test by the modal scale factor)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from flexlink.analysis.correlation import ALIAS_MAC, DOUBTFUL_MAC, GOOD_MAC
from flexlink.fe.motions import Part
from flexlink.output.figures import figure_png
from flexlink.studies.correlation.correlation import TestCorrelation

WORST_COMAC = 5  # channels listed in the text, lowest CoMAC first
DRAWN_SHARE = 0.08  # largest drawn displacement, as a fraction of the linkage's size


def _number(value) -> float | None:
    return None if value is None or not math.isfinite(value) else float(value)


def correlation_json(c: TestCorrelation) -> dict:
    """JSON-ready: the test, the model's modes, thresholds, MAC matrix, pairs (1-based), the
    unpaired modes of both sides, CoMAC per channel, the test's autoMAC and its aliased pairs,
    the pairing by mode order beside it, and where each sensor sits."""
    t, m, r = c.test, c.model, c.correlation
    errors = c.errors_pct()
    names = t.channel_names()
    links = [link.name for link in c.model.solved[0].model.links]
    return {
        "scene": c.scene.name, "file": c.scene.path,
        "test": {"file": t.source, "sensors": len(t.labels), "channels": len(names),
                 "modes": [{"mode": i + 1, "Hz": float(f), "damping": _number(z),
                            "field": t.mode_fields[i]}
                           for i, (f, z) in enumerate(zip(t.frequencies, t.damping))]},
        "model": {"family": str(c.scene.options.family), "elements_per_link": m.elements_per_link,
                  "modes": [{"mode": j + 1, "Hz": float(f), "part": str(p), "label": label}
                            for j, (f, p, label) in enumerate(zip(m.frequencies, m.parts,
                                                                  m.labels))]},
        "thresholds": {"good": GOOD_MAC, "doubtful": DOUBTFUL_MAC, "aliased": ALIAS_MAC},
        "mac": r.mac.tolist(),
        "pairs": [{"test": i + 1, "model": j + 1, "test_Hz": float(t.frequencies[i]),
                   "model_Hz": float(m.frequencies[j]), "error_pct": float(e),
                   "mac": float(v), "quality": str(q), "test_damping": _number(t.damping[i]),
                   "scale": float(s), "model_label": m.labels[j]}
                  for (i, j), e, v, q, s in zip(r.pairs, errors, r.pair_mac, r.pair_quality,
                                                r.scale)],
        "unpaired_test": [{"mode": i + 1, "Hz": float(t.frequencies[i]),
                           "best_mac": float(r.mac[i].max()),
                           "best_model": int(r.mac[i].argmax()) + 1} for i in r.unpaired_test],
        "unpaired_model": [{"mode": j + 1, "Hz": float(m.frequencies[j]), "label": m.labels[j],
                            "best_mac": float(r.mac[:, j].max())} for j in r.unpaired_model],
        "comac": [{"channel": n, "comac": _number(v)} for n, v in zip(names, r.comac)],
        "auto_mac": r.auto_mac.tolist(),
        "aliased": [{"a": i + 1, "b": j + 1, "auto_mac": float(r.auto_mac[i, j])}
                    for i, j in r.aliased],
        "by_order": [{"test": i + 1, "model": j + 1, "mac": v} for i, j, v in c.by_order],
        "sensors": [{"sensor": label, "link": links[int(k)], "fraction": float(f),
                     "distance_mm": float(d * 1e3)}
                    for label, k, f, d in zip(t.labels, c.sensors.placement.link,
                                              c.sensors.placement.fraction,
                                              c.sensors.placement.distance)],
    }


def correlation_text(document: dict) -> str:
    """The pairing table, unpaired modes, the lowest CoMACs, aliasing warnings and where
    pairing by mode order differs."""
    d = document
    lines = [f"{d['scene']} ({d['file']}) against test {d['test']['file']}: "
             f"{d['test']['sensors']} sensors, {d['test']['channels']} channels, "
             f"{len(d['test']['modes'])} test modes, {len(d['model']['modes'])} model modes "
             f"({d['model']['family']}, {d['model']['elements_per_link']} elements/link)",
             f"pairs by MAC (optimal assignment): >= {GOOD_MAC} good, {DOUBTFUL_MAC}-{GOOD_MAC} "
             f"doubtful, below {DOUBTFUL_MAC} not paired",
             "test  test Hz  model  model Hz  error %    MAC  quality   damping %  model mode"]
    for p in d["pairs"]:
        damping = "-" if p["test_damping"] is None else f"{100 * p['test_damping']:.2f}"
        lines.append(f"{p['test']:>4} {p['test_Hz']:>8.2f} {p['model']:>6} {p['model_Hz']:>9.2f} "
                     f"{p['error_pct']:>+8.2f} {p['mac']:>6.3f}  {p['quality']:<9} "
                     f"{damping:>9}  {p['model_label']}")
    for u in d["unpaired_test"]:
        lines.append(f"unpaired test mode {u['mode']} ({u['Hz']:.2f} Hz): best MAC "
                     f"{u['best_mac']:.3f} with model mode {u['best_model']}")
    if d["unpaired_model"]:
        lines.append("model modes not paired: " + ", ".join(
            f"{u['mode']} ({u['Hz']:.2f} Hz, {u['label']})" for u in d["unpaired_model"]))
    worst = sorted((c for c in d["comac"] if c["comac"] is not None), key=lambda c: c["comac"])
    if worst:
        lines.append("lowest CoMAC: " + ", ".join(f"{c['channel']} {c['comac']:.3f}"
                                                  for c in worst[:WORST_COMAC]))
    for a in d["aliased"]:
        lines.append(f"warning: test modes {a['a']} and {a['b']} have autoMAC {a['auto_mac']:.3f} "
                     f">= {ALIAS_MAC}: the sensors cannot tell them apart (spatial aliasing)")
    by_mac = {p["test"]: p["model"] for p in d["pairs"]}
    differ = [o for o in d["by_order"] if by_mac.get(o["test"]) != o["model"]]
    if differ:
        lines.append("pairing by mode order would differ: " + ", ".join(
            f"test {o['test']} with model {o['model']} (MAC {o['mac']:.3f})" for o in differ))
    return "\n".join(lines)


def pairs_csv(document: dict) -> str:
    lines = ["test_mode,test_Hz,model_mode,model_Hz,error_pct,mac,quality,test_damping,scale"]
    for p in document["pairs"]:
        damping = "" if p["test_damping"] is None else f"{p['test_damping']:.6g}"
        lines.append(f"{p['test']},{p['test_Hz']:.6f},{p['model']},{p['model_Hz']:.6f},"
                     f"{p['error_pct']:.4f},{p['mac']:.6f},{p['quality']},{damping},"
                     f"{p['scale']:.6g}")
    return "\n".join(lines) + "\n"


def mac_matrix_csv(c: TestCorrelation) -> str:
    """The MAC matrix: rows the test modes, columns the model modes."""
    mac = c.correlation.mac
    lines = ["test_mode," + ",".join(f"model{j + 1}" for j in range(mac.shape[1]))]
    lines += [f"{i + 1}," + ",".join(f"{v:.6f}" for v in row) for i, row in enumerate(mac)]
    return "\n".join(lines) + "\n"


def mac_heat_map(c: TestCorrelation) -> bytes:
    """PNG: the MAC matrix (test rows, model columns), accepted pairs outlined."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    mac = c.correlation.mac
    fig, ax = plt.subplots(figsize=(1.2 + 0.55 * mac.shape[1], 1.2 + 0.5 * mac.shape[0]))
    image = ax.imshow(mac, vmin=0.0, vmax=1.0, cmap="viridis", origin="upper")
    for i in range(mac.shape[0]):
        for j in range(mac.shape[1]):
            ax.text(j, i, f"{mac[i, j]:.2f}", ha="center", va="center", fontsize=7,
                    color="black" if mac[i, j] > 0.5 else "white")
    for (i, j), q in zip(c.correlation.pairs, c.correlation.pair_quality):
        ax.add_patch(plt.Rectangle((j - 0.5, i - 0.5), 1, 1, fill=False, lw=2,
                                   ec="red" if q == "doubtful" else "white"))
    ax.set_xticks(range(mac.shape[1]),
                  [f"{j + 1}\n{f:.0f}" for j, f in enumerate(c.model.frequencies)], fontsize=7)
    ax.set_yticks(range(mac.shape[0]),
                  [f"{i + 1}: {f:.0f}" for i, f in enumerate(c.test.frequencies)], fontsize=7)
    ax.set_xlabel("model mode / Hz")
    ax.set_ylabel("test mode: Hz")
    ax.set_title(f"MAC, {c.scene.name}\n(outlined: pairs; red: doubtful)", fontsize=9)
    fig.colorbar(image, ax=ax, shrink=0.8)
    fig.tight_layout()
    return figure_png(fig, 110)


def _sensor_displacements(c: TestCorrelation, values: np.ndarray) -> np.ndarray:
    """(P, 3) displacement of each sensor point from its channels' readings ``values`` (C,)
    along their scene directions (channels of one point added)."""
    out = np.zeros((len(c.test.labels), 3))
    np.add.at(out, c.test.channel_point, values[:, None] * c.sensors.directions)
    return out


def link_stations(model, per_element: int = 4):
    """(points (P, 2) [m], their Placement, one index array per link from start to end):
    ``per_element`` segments per element along every link's axis."""
    from flexlink.fe.sensors import Placement

    points, link, element, xi, fraction, chains = [], [], [], [], [], []
    for k, l in enumerate(model.links):
        t = np.linspace(0.0, 1.0, l.elements * per_element + 1)
        where = t * l.elements
        e = np.minimum(np.floor(where).astype(int), l.elements - 1)
        start, end = model.nodes[l.first_node], model.nodes[l.first_node + l.elements]
        chains.append(len(points) + np.arange(len(t)))
        points += list(start + t[:, None] * (end - start))
        link += [k] * len(t)
        element += list(e)
        xi += list(where - e)
        fraction += list(t)
    points = np.array(points)
    zeros = np.zeros(len(points))
    return points, Placement(np.array(link), np.array(element), np.array(xi), points,
                             np.zeros_like(points), zeros, np.array(fraction)), chains


def _model_displacements(part, shape: np.ndarray, placement) -> np.ndarray:
    """(P, 3) the model's displacement at placed points: (ux, uy, 0) of an in-plane shape,
    (0, 0, w) of an out-of-plane one, by the element interpolation (``fe.sensors``)."""
    from flexlink.fe.sensors import channel_operator

    n = len(placement.link)
    point = np.repeat(np.arange(n), 3)
    S = channel_operator(part.part, part.model, placement, point, np.tile(np.eye(3), (n, 1)))
    return (S @ shape).reshape(n, 3)


def overlay_pictures(c: TestCorrelation) -> bytes:
    """PNG: one panel per pair, the linkage (grey), the model's shape on the links (blue, the
    element interpolation) and the test's sensor displacements (red), the model scaled onto
    the test by the modal scale factor; out-of-plane pairs draw the deflection w normal to
    each link, in the plane of the drawing."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    pairs = c.correlation.pairs
    columns = min(3, max(1, len(pairs)))
    rows = max(1, math.ceil(len(pairs) / columns))
    fig, axes = plt.subplots(rows, columns, figsize=(4.6 * columns, 3.6 * rows), squeeze=False)
    base = c.model.solved[0].model
    size = float(np.ptp(base.nodes, axis=0).max())
    points, placement, chains = link_stations(base)
    normals = np.array([[-math.sin(base.links[k].angle), math.cos(base.links[k].angle)]
                        for k in placement.link])
    sensor_normals = np.array([[-math.sin(base.links[k].angle), math.cos(base.links[k].angle)]
                               for k in c.sensors.placement.link])
    for ax in axes.ravel():
        ax.set_axis_off()
    for n, ((i, j), s, v) in enumerate(zip(pairs, c.correlation.scale, c.correlation.pair_mac)):
        ax = axes.ravel()[n]
        part, shape = c.model.shape(j)
        model_disp = _model_displacements(part, shape * s, placement)
        test_disp = _sensor_displacements(c, c.test.shapes[:, i])
        if part.part is Part.OUT_OF_PLANE:  # w drawn normal to each link
            model_xy = model_disp[:, 2:3] * normals
            test_xy = test_disp[:, 2:3] * sensor_normals
        else:
            model_xy, test_xy = model_disp[:, :2], test_disp[:, :2]
        largest = max(np.abs(model_xy).max(), np.abs(test_xy).max(), 1e-300)
        k = DRAWN_SHARE * size / largest
        for chain in chains:
            ax.plot(*points[chain].T, color="0.7", lw=1)
            ax.plot(*(points[chain] + k * model_xy[chain]).T, color="tab:blue", lw=1.5)
        ax.plot(*c.sensors.points.T, "o", ms=3, mfc="none", mec="0.5")
        ax.plot(*(c.sensors.points + k * test_xy).T, "o", ms=4, color="tab:red")
        ax.set_aspect("equal")
        ax.set_title(f"test {i + 1} ({c.test.frequencies[i]:.1f} Hz) / model {j + 1} "
                     f"({c.model.frequencies[j]:.1f} Hz)\nMAC {v:.3f}, {part.part}", fontsize=8)
    fig.suptitle(f"{c.scene.name}: model (blue, x MSF) and test (red) shapes", fontsize=10)
    fig.tight_layout()
    return figure_png(fig, 110)


def paraview_meshes(c: TestCorrelation):
    """(model mesh, sensors mesh) for ParaView: the links with the model's shape of each pair
    scaled onto its test mode by the MSF ("pair<n> model (test <i>)", 3-vectors, z = w for
    out-of-plane modes), and the sensor points with each test mode ("test<i>") and the
    model's paired shape read at the channels ("pair<n> model at sensors"), in the scene's
    frame [m]."""
    import meshio

    base = c.model.solved[0].model
    points, placement, chains = link_stations(base)
    model_data, sensor_data = {}, {}
    for n, ((i, j), s) in enumerate(zip(c.correlation.pairs, c.correlation.scale)):
        part, shape = c.model.shape(j)
        model_data[f"pair{n + 1} model (test {i + 1})"] = _model_displacements(
            part, shape * s, placement)
        sensor_data[f"pair{n + 1} model at sensors"] = _sensor_displacements(
            c, c.model_readings[:, j] * s)
    for i in range(c.test.n_modes):
        sensor_data[f"test{i + 1}"] = _sensor_displacements(c, c.test.shapes[:, i])
    lines = np.vstack([np.column_stack([chain[:-1], chain[1:]]) for chain in chains])
    model = meshio.Mesh(np.column_stack([points, np.zeros(len(points))]), [("line", lines)],
                        point_data=model_data)
    sensor_points = np.column_stack([c.sensors.points, np.zeros(len(c.sensors.points))])
    sensors = meshio.Mesh(sensor_points, [("vertex", np.arange(len(sensor_points))[:, None])],
                          point_data=sensor_data)
    return model, sensors


def write_correlation_files(folder: Path, c: TestCorrelation, document: dict,
                            pictures: bool = True) -> list[Path]:
    """correlation_pairs.csv, correlation_mac.csv, the two .vtu files and (``pictures``) the
    heat map and the overlay, written atomically into ``folder``."""
    from flexlink.fileio import write_atomic
    from flexlink.output.export_vtk import write_vtu

    files = [write_atomic(folder / "correlation_pairs.csv", pairs_csv(document)),
             write_atomic(folder / "correlation_mac.csv", mac_matrix_csv(c))]
    model, sensors = paraview_meshes(c)
    files += [write_vtu(folder / "correlation_model.vtu", model),
              write_vtu(folder / "correlation_test.vtu", sensors)]
    if pictures:
        files += [write_atomic(folder / "correlation_mac.png", mac_heat_map(c)),
                  write_atomic(folder / "correlation_shapes.png", overlay_pictures(c))]
    return files
