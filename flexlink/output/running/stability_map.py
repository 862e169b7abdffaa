"""Rendering of the stability map: JSON document, CSV, text lines and the PNG of the unstable
speed ranges over the Campbell diagram and of the largest Floquet multiplier against speed."""

from __future__ import annotations

from flexlink.units import rev_per_min


def basis_caveat(model) -> str | None:
    """What the reader must be told about the basis: None when its check holds."""
    basis = model.basis
    if basis is None or basis.checked:
        return None
    n = basis.exact.shape[1]
    return (f"the reduced basis ({basis.size} vectors) fails its check: its lowest {n} "
            f"frequencies exceed the full model's by up to {100 * basis.error:.3g} % at some "
            f"pose (asked: {100 * basis.tolerance:.3g} %): the ranges are not converged in the "
            "basis (docs/critical-speeds.md)")


def damping_line(ratios: list[float], source: str) -> str:
    """The damping in one line: the ratios' span over the basis vectors and where they came
    from."""
    low, high = min(ratios), max(ratios)
    span = f"{low:g}" if low == high else f"{low:g} to {high:g} over the basis vectors"
    return f"damping ratio {span} ({source})"


def mesh_json(mesh) -> dict | None:
    """The mesh (an ``analysis.mesh.MeshRule``) and why, with its one-line description."""
    return None if mesh is None else {**mesh.as_dict(), "description": mesh.describe()}


def stability_document(scene_name: str, result, model, mesh=None) -> dict:
    """The JSON document: per speed the largest modulus and growth rate, the ranges, the
    basis with its check and the mesh (an ``analysis.mesh.MeshRule``, None: not stated)."""
    basis = model.basis
    return {
        "command": "stability-map", "scene": scene_name, "caveat": basis_caveat(model),
        "mesh": mesh_json(mesh),
        "damping_ratio": model.damping_ratio.tolist(), "damping_source": model.damping_source,
        "poses": len(model.angles), "integrator": result.integrator.value,
        "magnus_fallback_rev_per_min": (rev_per_min(result.speeds[result.magnus_fallback])).tolist(),
        "quasi_static_rev_per_min": rev_per_min(result.speeds[result.quasi_static]).tolist(),
        "basis": None if basis is None else {
            "size": basis.size, "modes_checked": int(basis.exact.shape[1]),
            "tolerance": basis.tolerance, "largest_frequency_error": basis.error,
            "checked": bool(basis.checked),
            "snapshot_poses": basis.snapshot_poses.tolist()},
        "basis_frequencies_Hz": model.frequencies.tolist(),
        "frequencies_over_turn_Hz": (None if basis is None else
                                     {"low": basis.exact.min(axis=0).tolist(),
                                      "high": basis.exact.max(axis=0).tolist()}),
        "speeds_rev_per_min": (rev_per_min(result.speeds)).tolist(),
        "largest_modulus": result.largest_modulus.tolist(),
        "growth_rate_per_s": result.growth_rate.tolist(),
        "stiffness_floor_rad2_per_s2": result.stiffness_floor.tolist(),
        "instability_ranges": [
            {"from_rev_per_min": rev_per_min(r.low), "to_rev_per_min": rev_per_min(r.high),
             "modes": list(r.modes), "harmonic": r.harmonic, "kind": r.kind,
             "largest_growth_rate_per_s": r.growth_rate} for r in result.ranges],
    }


def stability_csv(result) -> str:
    lines = ["speed_rev_per_min,largest_modulus,growth_rate_per_s,stiffness_floor_rad2_per_s2"]
    lines += [f"{rev_per_min(w):.6g},{m:.10g},{g:.10g},{f:.6g}" for w, m, g, f in
              zip(result.speeds, result.largest_modulus, result.growth_rate,
                  result.stiffness_floor)]
    return "\n".join(lines) + "\n"


def stability_lines(document: dict) -> list[str]:
    basis = document["basis"]
    out = [f"{document['scene']}: {len(document['basis_frequencies_Hz'])} basis vectors, "
           f"{len(document['speeds_rev_per_min'])} speeds, {document['integrator']} steps",
           damping_line(document["damping_ratio"], document["damping_source"])]
    if document.get("mesh"):
        out.append(document["mesh"]["description"])
    fallback = document["magnus_fallback_rev_per_min"]
    if fallback:
        count = f"{len(fallback)} speed" + ("s" if len(fallback) > 1 else "")
        out.append(f"adiabatic steps refused at {count} ({fallback[0]:g} to {fallback[-1]:g} "
                   "rev/min; flexlink -v says why): Magnus steps there")
    quasi = document["quasi_static_rev_per_min"]
    if quasi:
        count = f"{len(quasi)} speed" + ("s" if len(quasi) > 1 else "")
        out.append(f"quasi-static at {count} ({quasi[0]:g} to {quasi[-1]:g} rev/min): every "
                   "frozen mode decays by more than 20 e-folds a turn, so no steps were taken; "
                   "|mu| there is the adiabatic bound")
    if basis is not None:
        out.append(f"basis check: lowest {basis['modes_checked']} frequencies within "
                   f"{100 * basis['largest_frequency_error']:.3g} % of the full model's at "
                   f"every one of {document['poses']} poses (asked "
                   f"{100 * basis['tolerance']:.3g} %)")
    if document["caveat"]:
        out.append(f"caveat: {document['caveat']}")
    ranges = document["instability_ranges"]
    if not ranges:
        return out + ["no parametric instability in the range"]
    out.append(f"{'from [rev/min]':>15} {'to [rev/min]':>13} {'modes':>7} {'k':>3} "
               f"{'kind':<12} {'growth [1/s]':>12}")
    for r in ranges:
        modes = "+".join(str(m) for m in r["modes"])
        out.append(f"{r['from_rev_per_min']:>15.1f} {r['to_rev_per_min']:>13.1f} {modes:>7} "
                   f"{r['harmonic']:>3} {r['kind']:<12} {r['largest_growth_rate_per_s']:>12.4g}")
    return out


def plot_stability(result, model, path, title: str, harmonics: int = 6) -> None:
    """PNG of two panels over crank speed [rev/min], unstable ranges shaded on both (red:
    parametric, grey: divergence): the Campbell diagram (each checked mode's frequency band
    over the turn, the crank-harmonic lines k x speed) and the largest multiplier modulus."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    from flexlink.output.figures import write_figure

    rpm = rev_per_min(result.speeds)
    bands = (np.vstack([model.checked, model.checked]) if model.basis is None else
             np.vstack([model.basis.exact.min(axis=0), model.basis.exact.max(axis=0)]))
    fig, (campbell, modulus) = plt.subplots(2, 1, figsize=(8, 7), sharex=True,
                                            gridspec_kw={"height_ratios": (3, 2)})
    top = 1.15 * bands[1].max()
    for i, (low, high) in enumerate(bands.T):
        campbell.axhspan(low, max(high, low + 1e-3 * top), color=f"C{i}", alpha=0.45, lw=0,
                         label=f"mode {i + 1}: {low:.0f}-{high:.0f} Hz over the turn")
    ends = np.array([rpm[0], rpm[-1]])
    for k in range(1, harmonics + 1):
        campbell.plot(ends, k * ends / 60.0, color="0.3", lw=0.8)
        at = min(ends[-1], 60.0 * top / k)
        campbell.annotate(f"{k}x", (at, k * at / 60.0), fontsize=7, ha="right", va="bottom")
    modulus.semilogy(rpm, result.largest_modulus, lw=1.2, color="k")
    modulus.axhline(1.0, color="k", lw=0.6, ls="--")
    half = 0.5 * float(np.median(np.diff(rpm))) if len(rpm) > 1 else 0.0
    for r in result.ranges:  # each unstable speed stands for half a grid step either side
        colour = "0.5" if r.kind == "divergence" else "tab:red"
        for ax in (campbell, modulus):
            ax.axvspan(rev_per_min(r.low) - half, rev_per_min(r.high) + half, color=colour, alpha=0.25, lw=0)
    campbell.set(ylim=(0, top), ylabel="frequency [Hz]",
                 title=f"{title}: unstable speed ranges over the Campbell diagram")
    campbell.legend(fontsize=7, loc="upper left")
    campbell.grid(alpha=0.3)
    modulus.set(xlim=(rpm[0], rpm[-1]), xlabel="crank speed [rev/min]",
                ylabel="largest |Floquet multiplier|")
    modulus.grid(alpha=0.3, which="both")
    fig.tight_layout()
    write_figure(fig, path)


def write_stability(result, model, folder, title: str) -> list:
    """stability-map.png and .csv in ``folder`` (atomically); returns their paths."""
    from flexlink.fileio import write_atomic

    paths = [folder / "stability-map.png", folder / "stability-map.csv"]
    plot_stability(result, model, paths[0], title)
    write_atomic(paths[1], stability_csv(result))
    return paths
