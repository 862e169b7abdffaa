"""Rendering of the stability map: JSON document, CSV, text lines and the PNG of the largest
Floquet multiplier against crank speed with the unstable ranges shaded."""

from __future__ import annotations

from flexlink.studies.campbell import RPM

# Said with every map until the basis is checked as the cycle map's Craig-Bampton basis is.
BASIS_CAVEAT = ("the reduced basis (the reference pose's lowest static modes) is not checked "
                "for convergence: ranges change with the number of modes, so treat them as "
                "indicative (docs/critical-speeds.md)")


def stability_document(scene_name: str, result, model) -> dict:
    """The JSON document: per speed the largest modulus and growth rate, and the ranges."""
    return {
        "command": "stability-map", "scene": scene_name, "caveat": BASIS_CAVEAT,
        "damping_ratio": model.damping_ratio, "poses": len(model.angles),
        "basis_frequencies_Hz": model.frequencies.tolist(),
        "speeds_rev_per_min": (result.speeds / RPM).tolist(),
        "largest_modulus": result.largest_modulus.tolist(),
        "growth_rate_per_s": result.growth_rate.tolist(),
        "instability_ranges": [
            {"from_rev_per_min": r.low / RPM, "to_rev_per_min": r.high / RPM,
             "modes": list(r.modes), "harmonic": r.harmonic, "kind": r.kind,
             "largest_growth_rate_per_s": r.growth_rate} for r in result.ranges],
    }


def stability_csv(result) -> str:
    lines = ["speed_rev_per_min,largest_modulus,growth_rate_per_s"]
    lines += [f"{w / RPM:.6g},{m:.10g},{g:.10g}" for w, m, g in
              zip(result.speeds, result.largest_modulus, result.growth_rate)]
    return "\n".join(lines) + "\n"


def stability_lines(document: dict) -> list[str]:
    out = [f"{document['scene']}: {len(document['basis_frequencies_Hz'])} modes, damping ratio "
           f"{document['damping_ratio']:g}, {len(document['speeds_rev_per_min'])} speeds",
           f"caveat: {document['caveat']}"]
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


def plot_stability(result, path, title: str) -> None:
    """PNG: largest multiplier modulus against speed [rev/min], unstable ranges shaded."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from flexlink.output.figures import write_figure

    fig, ax = plt.subplots(figsize=(8, 4))
    ax.plot(result.speeds / RPM, result.largest_modulus, lw=1.2)
    ax.axhline(1.0, color="k", lw=0.6, ls="--")
    for r in result.ranges:
        ax.axvspan(r.low / RPM, max(r.high, r.low + 1e-9) / RPM, color="tab:red", alpha=0.25)
    ax.set(xlabel="crank speed [rev/min]", ylabel="largest |Floquet multiplier|", title=title)
    write_figure(fig, path)
