"""Markdown report, PNG plots and printed summary of calibration studies
(``studies.calibration.calibration.run_study``), one per model family.

Everything here reads a study through its JSON document (``output.calibration.calibration``), so a
field the report shows has one name. The text is a pure function of the studies; the plots
import matplotlib inside the functions that draw and return PNG bytes; ``report_files`` hands
the caller every file's content to write atomically."""

from __future__ import annotations

import io

import numpy as np

from flexlink.output.calibration.calibration import study_document
from flexlink.studies.calibration.calibration import CalibrationStudy, best_family


def _f(x, fmt="{:.1f}"):
    """None (JSON's stand-in for NaN) and NaN read "n/a": a failed evaluation."""
    return "n/a" if x is None or x != x else fmt.format(x)


def mean_text(s: dict, key: str) -> str:
    """A mean |error| [%], or "n/a (K of M failed)": ``comparison`` gives no mean when any case
    or mode failed (``calibration.mean_abs`` says why)."""
    failed = len(s["errors_failed"][key])
    if not failed:
        return _f(s["errors_mean_abs_pct"][key])
    return f"n/a ({failed} of {s['errors_count'][key]} failed)"


def _table(header: list[str], rows: list[list[str]]) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    lines += ["| " + " | ".join(r) + " |" for r in rows]
    return "\n".join(lines)


def _fmt_value(value, unit):
    """None stands for an infinite (rigid) stiffness: JSON has no infinity."""
    return "rigid" if value is None else f"{value:.4g} {unit}"


def _se_text(p):
    se = p["relative_se"]
    if se is None:
        return "not identifiable"
    if se < 1:
        return f"±{100 * se:.3g} %"
    # beyond a factor e^5 ~ 150 the linearised error only says "not determined by the data"
    return f"×/÷ {np.exp(se):.3g}" if se < 5 else "not determined"


def summary_lines(studies: list[dict], best: str | None) -> list[str]:
    """The summary table of mean |errors|; ``best``: the family with the lowest cross-validated
    error (``calibration_study.best_family``), named when several are compared."""
    rows = []
    keys = ("assumed_inputs_vs_Ex", "calibrated_to_Ex_in_sample", "cross_validated_vs_Ex",
            "per_case_fit_in_sample", "calibrated_to_FE_vs_FE", "paper_FE_vs_Ex")
    for s in studies:
        rows.append([s["family"]] + [mean_text(s, k) for k in keys])
    lines = [_table(["family", "assumed inputs vs Ex", "calibrated to Ex (in sample)",
                     "cross-validated vs Ex", "each case fitted alone", "calibrated to FE vs FE",
                     "paper FE vs Ex"], rows)]
    if len(studies) > 1 and best is not None:
        best = next(s for s in studies if s["family"] == best)
        lines.append(f"\nBy the cross-validated error the **{best['family']}** family explains "
                     f"Table III best ({best['errors_mean_abs_pct']['cross_validated_vs_Ex']:.1f} % "
                     "mean |error| predicting a case it was not fitted to).")
    return lines


def _failure_lines(s: dict) -> list[str]:
    """Which case and mode failed in which comparison, and why; nothing if none did."""
    rows = [[key.replace("_", " "), f["case"], str(f["mode"]), f["reason"]]
            for key, failed in s["errors_failed"].items() for f in failed]
    if not rows:
        return []
    return ["### Failed evaluations", "",
            f"{len(rows)} case/mode evaluations failed; a mean |error| that would include them "
            "is given as n/a rather than as the mean of the others:", "",
            _table(["comparison", "case", "mode", "why"], rows), ""]


def _convergence_text(fit: dict) -> str:
    """Which starts stopped at the least-squares evaluation limit, not at a tolerance."""
    converged = fit.get("starts_converged") or []
    stopped = converged.count(False)
    if not stopped:
        return " Every start converged."
    best = ("including the best one, whose inputs are therefore not a converged optimum"
            if not converged[fit["best_start"]] else "not the best one")
    return (f" {stopped} of {len(converged)} starts stopped at the evaluation limit, not at a "
            f"tolerance ({best}).")


def family_section(s: dict, plots: dict[str, str]) -> str:
    fam, cases = s["family"], s["cases"]
    e = s["errors_mean_abs_pct"]
    out = [f"## Family: {fam}", ""]
    out.append(f"Mean |error| vs Ex: assumed inputs {mean_text(s, 'assumed_inputs_vs_Ex')} %, "
               f"calibrated {mean_text(s, 'calibrated_to_Ex_in_sample')} % (in sample), "
               f"cross-validated {mean_text(s, 'cross_validated_vs_Ex')} %. The paper's own FE is "
               f"{mean_text(s, 'paper_FE_vs_Ex')} % from Ex.")
    cv_mean, in_sample = e["cross_validated_vs_Ex"], e["calibrated_to_Ex_in_sample"]
    if cv_mean is not None and in_sample is not None and cv_mean > 1.5 * max(in_sample, 1e-9):
        out.append("The calibration looks better in sample than it predicts: cross-validated "
                   "errors are the ones to quote.")
    out.append("")
    out += _failure_lines(s)
    for key, title in (("fit_Ex", "Calibrated to Ex"), ("fit_FE", "Calibrated to the paper's FE")):
        fit = s[key]
        rows = []
        for p, free in zip(fit["parameters"], s["free"]):
            rows.append([p["name"], _fmt_value(free["nominal"], p["unit"]),
                         _fmt_value(p["value"], p["unit"]), _se_text(p),
                         f"{_fmt_value(p['low'], p['unit'])} .. {_fmt_value(p['high'], p['unit'])}",
                         "yes" if p["at_bound"] else ""])
        costs = fit["start_costs"]
        out += [f"### {title}", "",
                _table(["input", "assumed", "fitted", "std. error", "bounds", "at bound"], rows), "",
                f"Best of {len(costs)} starts; costs (0.5 sum ln-residual^2) of all starts: "
                + ", ".join(f"{c:.3g}" for c in sorted(costs)) + "; "
                f"{fit['evaluations']} function evaluations (without Jacobians)."
                + _convergence_text(fit), ""]
    corr = s["fit_Ex"]["correlation"]
    if corr is not None:
        names = [p["name"] for p in s["fit_Ex"]["parameters"]]
        rows = [[n] + [_f(c, "{:+.2f}") for c in row] for n, row in zip(names, corr)]
        out += ["Correlation of the fitted ln inputs (Ex fit); |r| near 1 = the data cannot tell "
                "them apart:", "", _table([""] + names, rows), ""]

    rows = []
    cv = s["cross_validation"]
    for i, case in enumerate(cases):
        for k in range(len(s["Ex_Hz"][i])):
            rows.append([case, str(k + 1), f"{s['Ex_Hz'][i][k]:g}", f"{s['paper_FE_Hz'][i][k]:g}",
                         _f(s['nominal_Hz'][i][k]), _f(s['nominal_errors_pct'][i][k], "{:+.1f}"),
                         _f(s['fit_Ex']['predicted_Hz'][i][k]),
                         _f(s['fit_Ex']['errors_pct'][i][k], "{:+.1f}"),
                         _f(cv['predicted_Hz'][i][k]), _f(cv['errors_pct'][i][k], "{:+.1f}")])
    out += ["### Per-mode residuals (pairing by mode order)", "",
            _table(["case", "mode", "Ex Hz", "paper FE Hz", "assumed Hz", "err %", "calibrated Hz",
                    "err %", "cross-validated Hz", "err %"], rows), "",
            f"![frequencies]({plots['frequencies']})", ""]
    rows = [[c, _f(a), _f(b)] for c, a, b in
            zip(cases, cv["fold_fitted_mean_abs_pct"], cv["fold_predicted_mean_abs_pct"])]
    out += ["### Leave-one-case-out cross-validation", "",
            _table(["held-out case", "mean |err| on the 3 fitted cases %",
                    "mean |err| predicting the held-out case %"], rows), "",
            f"![cross-validation]({plots['cross_validation']})", ""]

    r = s["ratios"]
    rows = []
    for i, case in enumerate(cases):
        rows.append([case, " : ".join(f"{v:.2f}" for v in r["measured"][i]),
                     " : ".join(_f(v, "{:.2f}") for v in r["nominal_model"][i]),
                     " : ".join(_f(v, "{:.2f}") for v in r["best_model"][i]),
                     ", ".join(_f(v, "{:+.1f}") for v in r["best_errors_pct"][i]),
                     _f(s['per_case_fits'][i]['mean_abs_pct'])])
    # NaN (a failed case) propagates: the worst over the others would understate it
    worst = float(np.max(np.abs(np.array(r["best_errors_pct"], dtype=float))))
    c2c = np.array(r["case_to_case_measured"], dtype=float)
    model = np.array(s["fit_Ex"]["predicted_Hz"], dtype=float)
    model_c2c = model / model[:1]
    spread = lambda m: 100 * (np.max(m, axis=1) / np.min(m, axis=1) - 1)  # noqa: E731
    rows_c2c = [[c, ", ".join(f"{v:.2f}" for v in a), _f(sa),
                 ", ".join(_f(v, "{:.2f}") for v in b), _f(sb)]
                for c, a, sa, b, sb in zip(cases, c2c, spread(c2c), model_c2c, spread(model_c2c))]
    out += ["### Proportionality test (mode ratios f_k / f_1)", "",
            f"Case-to-case ratios per mode (case / {cases[0]}), measured and from the model "
            "calibrated to Ex; 'spread' = how much that ratio varies over the modes (0 % = "
            "exactly proportional spectra):", "",
            _table(["case", "measured, modes 1..4", "spread %", "model (calibrated), modes 1..4",
                    "spread %"], rows_c2c), "",
            "Within each case, the measured mode ratios against the best this family can do "
            "for that case alone (ratio fit, scale-free):", "",
            _table(["case", "measured", "model, assumed inputs", "model, best inputs for this case",
                    "best ratio error % (modes 2..4)", "abs. fit of this case alone, mean |err| %"],
                   rows), "",
            (f"Over all cases the closest any input set of this family comes to the measured "
             f"ratios is {worst:.1f} % (worst mode). "
             + ("The family can reproduce every case's ratios within 5 %."
                if worst <= 5 else "The family cannot reproduce the measured mode ratios of "
                "every case: a shared or per-case choice of inputs moves frequencies, not this "
                "pattern.")) if worst == worst else
            "A ratio fit failed (see Failed evaluations), so the closest this family comes to "
            "the measured ratios over all cases is not known.",
            "", f"![ratios]({plots['ratios']})", ""]

    for key, title in (("uncertainty_nominal", "assumed inputs"),
                       ("uncertainty_calibrated", "inputs calibrated to Ex")):
        u = s[key]
        rows = []
        for i, case in enumerate(cases):
            for k in range(len(s["Ex_Hz"][i])):
                rows.append([case, str(k + 1), f"{s['Ex_Hz'][i][k]:g}", _f(u['mean_Hz'][i][k]),
                             f"{_f(u['low95_Hz'][i][k])} .. {_f(u['high95_Hz'][i][k])}",
                             f"{_f(u['first_order_low95_Hz'][i][k])} .. "
                             f"{_f(u['first_order_high95_Hz'][i][k])}",
                             "yes" if u["Ex_inside"][i][k] else "no"])
        ranked = ", ".join(f"{x['input']} {x['max_abs']:.3f}" for x in u["ranked"])
        sd = u["inputs"]["sd"]
        out += [f"### Uncertainty at the {title}", "",
                f"Monte Carlo, {u['samples']} samples, seed {u['seed']} ({u['failed_samples']} "
                f"failed); Table I spreads read as one standard deviation; fibre volume fraction "
                f"sd {sd['vf']:g}, thickness sd {1e3 * sd['thickness']:g} mm. Ex inside the 95 % "
                f"interval for {u['Ex_inside_count']} of {u['count']} modes.", "",
                _table(["case", "mode", "Ex Hz", "MC mean Hz", "MC 95 % interval Hz",
                        "first-order 95 % Hz", "Ex inside"], rows), "",
                "Normalised sensitivities d ln f / d ln p, largest |value| over cases and modes: "
                + ranked + ".", ""]
    out.append(f"![intervals]({plots['intervals']})")
    return "\n".join(out)


def report_markdown(studies: list[CalibrationStudy], plots: dict[str, dict[str, str]],
                    command: str) -> str:
    """report.md; ``plots``: family -> plot name -> its file name beside the report."""
    best = best_family(studies)
    studies = [study_document(s) for s in studies]
    s0 = studies[0]
    st = s0["settings"]
    head = ["# flexlink calibration report: model vs Table III", "",
            f"Command: `{command}`", "",
            f"Scenes: {', '.join(s0['files'])}. Starts per fit: {st['starts']}, seed "
            f"{st['seed']}, {st['elements'] or 'scene'} elements per link. Every free input is "
            "fitted as ln p within its bounds, one set shared by all cases (except where a table "
            "says 'each case alone'). Errors are (model / reference - 1) in %, paired by mode "
            "order only; no per-mode or per-case factors.", "",
            "## Summary: mean |error| in %", ""]
    head += summary_lines(studies, best and best.family)
    return "\n".join(head + [""] + [family_section(s, plots[s["family"]]) for s in studies]) + "\n"


# -- plots (matplotlib only here) --------------------------------------------------------------
def _png(fig) -> bytes:
    import matplotlib.pyplot as plt

    buf = io.BytesIO()
    fig.tight_layout()
    fig.savefig(buf, format="png", dpi=110, bbox_inches="tight")
    plt.close(fig)
    return buf.getvalue()


def _figure(n):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    cols = min(n, 2)
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(5.2 * cols, 3.6 * rows), squeeze=False)
    return fig, axes.ravel()


def plot_frequencies(s: dict) -> bytes:
    """Per case: Ex, paper FE, model with assumed inputs, calibrated to Ex, calibrated to FE."""
    fig, axes = _figure(len(s["cases"]))
    series = (("Ex_Hz", "Ex (measured)", "ko-"), ("paper_FE_Hz", "paper FE", "s--"),
              ("nominal_Hz", "assumed inputs", "^:"))
    for i, (ax, case) in enumerate(zip(axes, s["cases"])):
        modes = np.arange(1, len(s["Ex_Hz"][i]) + 1)
        for key, label, style in series:
            ax.plot(modes, np.array(s[key][i], dtype=float), style, label=label)
        ax.plot(modes, np.array(s["fit_Ex"]["predicted_Hz"][i], dtype=float), "o-", label="calibrated to Ex")
        ax.plot(modes, np.array(s["fit_FE"]["predicted_Hz"][i], dtype=float), "x-", label="calibrated to FE")
        ax.set(yscale="log", xticks=modes, xlabel="mode", ylabel="Hz", title=f"{case} ({s['family']})")
    axes[0].legend(fontsize=7)
    return _png(fig)


def plot_cross_validation(s: dict) -> bytes:
    fig, (ax,) = _figure(1)
    cases = s["cases"]
    x = np.arange(len(cases))
    cv = s["cross_validation"]
    # a failed fold (None) is drawn as no bar
    ax.bar(x - 0.2, np.array(cv["fold_fitted_mean_abs_pct"], dtype=float), 0.4,
           label="fitted cases (in sample)")
    ax.bar(x + 0.2, np.array(cv["fold_predicted_mean_abs_pct"], dtype=float), 0.4,
           label="held-out case (predicted)")
    ax.set(xticks=x, xticklabels=cases, ylabel="mean |error| vs Ex [%]",
           title=f"leave-one-case-out ({s['family']})")
    ax.legend(fontsize=8)
    return _png(fig)


def plot_ratios(s: dict) -> bytes:
    fig, axes = _figure(len(s["cases"]))
    r = s["ratios"]
    for i, (ax, case) in enumerate(zip(axes, s["cases"])):
        modes = np.arange(1, len(r["measured"][i]) + 1)
        ax.plot(modes, r["measured"][i], "ko-", label="measured")
        ax.plot(modes, np.array(r["nominal_model"][i], dtype=float), "^:", label="model, assumed")
        ax.plot(modes, np.array(r["best_model"][i], dtype=float), "o-", label="model, best for case")
        ax.set(yscale="log", xticks=modes, xlabel="mode", ylabel="f_k / f_1", title=f"{case} ({s['family']})")
    axes[0].legend(fontsize=7)
    return _png(fig)


def plot_intervals(s: dict) -> bytes:
    """Monte Carlo 95 % intervals at assumed and calibrated inputs, with Ex."""
    fig, axes = _figure(len(s["cases"]))
    for i, (ax, case) in enumerate(zip(axes, s["cases"])):
        modes = np.arange(1, len(s["Ex_Hz"][i]) + 1)
        for key, label, dx in (("uncertainty_nominal", "assumed inputs", -0.1),
                               ("uncertainty_calibrated", "calibrated to Ex", 0.1)):
            u = s[key]
            mean = np.array(u["mean_Hz"][i], dtype=float)
            err = [mean - np.array(u["low95_Hz"][i], dtype=float),
                   np.array(u["high95_Hz"][i], dtype=float) - mean]
            ax.errorbar(modes + dx, mean, yerr=err, fmt="o", capsize=3, label=f"MC 95 %, {label}")
        ax.plot(modes, s["Ex_Hz"][i], "k*", markersize=9, label="Ex")
        ax.set(yscale="log", xticks=modes, xlabel="mode", ylabel="Hz", title=f"{case} ({s['family']})")
    axes[0].legend(fontsize=7)
    return _png(fig)


PLOTS = {"frequencies": plot_frequencies, "cross_validation": plot_cross_validation,
         "ratios": plot_ratios, "intervals": plot_intervals}


def report_files(studies: list[CalibrationStudy], command: str) -> dict[str, bytes | str]:
    """File name -> content of every plot (``<plot>-<family>.png``) and of report.md."""
    files, plots = {}, {}
    for study in studies:
        doc = study_document(study)
        plots[study.family] = {name: f"{name}-{study.family}.png" for name in PLOTS}
        for name, draw in PLOTS.items():
            files[plots[study.family][name]] = draw(doc)
    files["report.md"] = report_markdown(studies, plots, command)
    return files


def summary_text(studies: list[CalibrationStudy]) -> str:
    """What ``flexlink calibrate`` prints without --json: per family the mean |errors|, the
    inputs fitted to Ex and how many Ex values the Monte Carlo interval holds."""
    lines = []
    for s in map(study_document, studies):
        lines.append(f"family {s['family']}: mean |error| vs Ex: assumed inputs "
                     f"{mean_text(s, 'assumed_inputs_vs_Ex')} %, calibrated "
                     f"{mean_text(s, 'calibrated_to_Ex_in_sample')} % (in sample), cross-validated "
                     f"{mean_text(s, 'cross_validated_vs_Ex')} %; paper FE vs Ex "
                     f"{mean_text(s, 'paper_FE_vs_Ex')} %")
        lines.append("  fitted to Ex: " + ", ".join(
            f"{p['name']} = {p['value']:.4g} {p['unit']}" for p in s["fit_Ex"]["parameters"]))
        u = s["uncertainty_calibrated"]
        lines.append(f"  Ex inside the 95 % Monte Carlo interval (calibrated inputs): "
                     f"{u['Ex_inside_count']} of {u['count']} modes")
    if len(studies) > 1:
        best = best_family(studies)
        lines.append(f"best family by cross-validated error: {best and best.family}")
    return "\n".join(lines)
