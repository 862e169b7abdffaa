"""Write the table in docs/beam-theories.md (between its table markers) and docs/beam-continuum.png: both beam theories
against the plane-stress continuum reference (flexlink/studies/verification/continuum.py) for L/h 2 to 100.

Run: PYTHONPATH=. python scripts/beam-continuum.py   (about a minute)
"""

from __future__ import annotations

from pathlib import Path

from flexlink.materials.mixtures import load_constituent, woven_composite
from flexlink.studies.verification.continuum import compare

ROOT = Path(__file__).resolve().parent.parent
SLENDERNESS = (2, 3, 5, 10, 20, 50, 100)
START, END = "<!-- table: scripts/beam-continuum.py -->", "<!-- end of table -->"
NU = 0.3  # in-plane Poisson's ratio of the strip (woven laminate ~0.28, steel 0.3)


def materials():
    fiber, matrix = load_constituent("carbon_fiber"), load_constituent("polyester")
    printed = woven_composite(fiber, matrix, 0.5)
    isotropic = woven_composite(fiber, matrix, 0.5, shear="isotropic")
    return [("isotropic solid, E/G = 2.6 (steel-like)", 210e9, 210e9 / 2.6, 7850.0),
            ("Table II laminate, G from Table I's printed G", printed.E, printed.G, printed.density),
            ("Table II laminate, G from E / 2 (1 + nu)", isotropic.E, isotropic.G, isotropic.density)]


def main() -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    lines = ["| material | E/G | L/h | continuum Hz (coarse -> fine mesh change) | "
             "Timoshenko error | Euler-Bernoulli error |", "|---|---|---|---|---|---|"]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for label, E, G, rho in materials():
        rows = compare(E, G, NU, rho, SLENDERNESS)
        for r in rows:
            lines.append(f"| {label} | {E / G:.3g} | {r.slenderness:g} | {r.continuum:.6g} "
                         f"({r.mesh_change:.1e}) | {100 * r.error('timoshenko'):+.3g} % | "
                         f"{100 * r.error('euler-bernoulli'):+.3g} % |")
        x = [r.slenderness for r in rows]
        line, = ax.loglog(x, [abs(r.error("euler-bernoulli")) for r in rows], "o-",
                          label=f"Euler-Bernoulli, {label}")
        ax.loglog(x, [max(abs(r.error("timoshenko")), 1e-7) for r in rows], "s--",
                  color=line.get_color(), label=f"Timoshenko, {label}")
    ax.axhline(0.01, color="grey", lw=0.8)
    ax.set_xlabel("slenderness L/h")
    ax.set_ylabel("|first flexural frequency / continuum - 1|")
    ax.set_title("Pinned-pinned strip: beam theories against plane stress")
    ax.legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(ROOT / "docs" / "beam-continuum.png", dpi=120)
    page = ROOT / "docs" / "beam-theories.md"
    head, _, rest = page.read_text().partition(START)
    _, _, tail = rest.partition(END)
    page.write_text(head + START + "\n" + "\n".join(lines) + "\n" + END + tail)
    print("\n".join(lines))


if __name__ == "__main__":
    main()
