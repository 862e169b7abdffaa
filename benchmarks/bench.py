"""flexlink speed, side by side with OpenSeesPy and with the bare LAPACK eigen call.

Run through ``bash benchmarks/run.sh`` (sets up OpenSeesPy and its system libraries first).
Every target is printed with its measured value and MET or NOT MET; none is asserted except the
agreement of the frequencies with OpenSees (exit code 1 if they differ by more than 1e-8
relative). Section 5 also times the shipped calibration report (about two minutes;
``--skip-full-calibration`` leaves it out).

Per-pose and cycle-map times are CPU times of this process (``time.process_time``) with BLAS held
to one thread, medians over repeats: on a machine shared with other jobs the CPU time of a
single-threaded run is what the run costs, while its wall time also counts the waits for a core.
The parallel section measures wall time, which is what parallel runs shorten.
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")  # one core: set before numpy loads its BLAS

import argparse  # noqa: E402
import json  # noqa: E402
import statistics  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402
import scipy.linalg as la  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(Path(__file__).resolve().parent))

from flexlink.fe.assembly import rigid_elimination  # noqa: E402
from flexlink.fe.model import build_model  # noqa: E402
from flexlink.scene import load_scene  # noqa: E402
from flexlink.analysis.sweep import _DensePlan, modal_sweep  # noqa: E402
from flexlink.fe.craig_bampton import _families  # noqa: E402

CASES = [ROOT / "cases" / f"case{i}.toml" for i in (1, 2, 3, 4)]
N_MODES = 6
TOLERANCE = 1e-8


def median_time(work, repeats: int, clock=time.process_time) -> float:
    """Median over ``repeats`` of the seconds ``work()`` takes on ``clock``."""
    times = []
    for _ in range(repeats):
        start = clock()
        work()
        times.append(clock() - start)
    return statistics.median(times)


def cycle_poses(scene, count: int):
    """``count`` poses evenly spaced over one crank turn, on the scene's branch."""
    thetas = np.radians(np.arange(count) * 360.0 / count + 0.5)
    return [scene.rigid_pose(t).joints for t in thetas]


def target(name: str, measured: str, goal: str, met: bool) -> None:
    print(f"  target {name}: {measured} (goal {goal}) {'MET' if met else 'NOT MET'}")


# -- 1. one pose: flexlink vs OpenSeesPy vs bare LAPACK -------------------------------------------
def per_pose(repeats: int) -> bool:
    import openseespy.opensees as ops

    import opensees_frame

    ops.logFile(os.devnull, "-noEcho")  # OpenSees chats on every eigen call
    scene = load_scene(CASES[1])
    topology = scene.topology(8)
    poses = cycle_poses(scene, 36)
    models = [build_model(topology, p) for p in poses]
    print(f"1. per pose: {scene.name}, 8 elements/link, {models[0].n_dofs} DOFs, "
          f"{N_MODES} modes, {len(poses)} poses over the cycle, medians of {repeats} repeats")

    ours = modal_sweep(topology, poses, N_MODES).frequencies
    reduced = modal_sweep(topology, poses, N_MODES, reduction="craig-bampton").frequencies
    solvers = ("-genBandArpack", "-fullGenLapack")
    worst = {}
    for solver in solvers:
        theirs = []
        for model in models:
            opensees_frame.build(ops, model)
            theirs.append(opensees_frame.frequencies(ops, N_MODES, solver))
        worst[solver] = float(np.max(np.abs(np.array(theirs) - ours) / ours))
    agree = all(w <= TOLERANCE for w in worst.values())
    for solver in solvers:
        print(f"  frequencies vs OpenSees eigen {solver}: max relative difference "
              f"{worst[solver]:.2e} (tolerance {TOLERANCE:g})")

    plan = _DensePlan(models[0], rigid_elimination(models[0]))
    matrices = [plan.matrices(m) for m in models]
    n = matrices[0][0].shape[0]

    def opensees_all(solver):
        for model in models:
            opensees_frame.build(ops, model)
            opensees_frame.frequencies(ops, N_MODES, solver)

    def bare(subset):
        for K, M in matrices:
            la.eigh(K, M, subset_by_index=subset)

    # the contenders take turns within each repeat, so that a change of load on the shared
    # machine hits all of them; ratios are medians of the per-repeat ratios
    def cold_craig_bampton():
        _families.cache_clear()  # every link's fixed-interface modes computed again
        modal_sweep(topology, poses, N_MODES, reduction="craig-bampton")

    work = {"flexlink": lambda: modal_sweep(topology, poses, N_MODES),
            "craig-bampton": lambda: modal_sweep(topology, poses, N_MODES,
                                                 reduction="craig-bampton"),
            "craig-bampton cold": cold_craig_bampton,
            **{s: (lambda s=s: opensees_all(s)) for s in solvers},
            "bare": lambda: bare([0, N_MODES - 1]), "full": lambda: bare(None)}
    runs = {name: [] for name in work}
    for _ in range(repeats):
        for name, job in work.items():
            start = time.process_time()
            job()
            runs[name].append((time.process_time() - start) / len(poses))
    t = {name: statistics.median(v) for name, v in runs.items()}
    ratio = {name: statistics.median(np.array(v) / np.array(runs["flexlink"]))
             for name, v in runs.items()}
    ms = 1e3
    print(f"  flexlink  modal_sweep (model + assembly + solve + checks): "
          f"{t['flexlink'] * ms:7.3f} ms/pose")
    for solver in solvers:
        print(f"  OpenSees  rebuild + eigen {solver:15s}:        {t[solver] * ms:7.3f} ms/pose"
              f"  ratio {ratio[solver]:.1f}x")
    print(f"  LAPACK    scipy.linalg.eigh(K, M), lowest {N_MODES} of {n}:       "
          f"{t['bare'] * ms:7.3f} ms/pose  flexlink/bare ratio {1 / ratio['bare']:.2f}x")
    print(f"  LAPACK    scipy.linalg.eigh(K, M), all {n}:                 "
          f"{t['full'] * ms:7.3f} ms/pose")
    cb_ratio = {(name, s): statistics.median(np.array(runs[s]) / np.array(runs[name]))
                for name in ("craig-bampton", "craig-bampton cold") for s in solvers}
    for name, what in (("craig-bampton", "repeated"), ("craig-bampton cold", "first call")):
        print(f"  flexlink  modal_sweep(reduction='craig-bampton'), {what + ':':12s}"
              f"{t[name] * ms:7.3f} ms/pose  ratio vs OpenSees "
              + ", ".join(f"{s} {cb_ratio[name, s]:.1f}x" for s in solvers))
    deviation = _deviation(reduced, ours)
    print("  (repeated: each sweep builds its plan, each link's fixed-interface modes are kept "
          "from the previous call of the mesh, as before; first call: those computed again) "
          f"max relative difference from the full model {deviation:.1e}")
    fastest = min(ratio[s] for s in solvers)
    print(f"  (full-model path: {fastest:.1f}x the faster OpenSees solver)")
    cb_fastest = min(cb_ratio["craig-bampton", s] for s in solvers)
    cold = min(cb_ratio["craig-bampton cold", s] for s in solvers)
    target(">= 10x faster than OpenSeesPy (its faster solver), with equal answers (Craig-Bampton "
           f"path within 1e-6 of the full model; repeated sweeps, first call {cold:.1f}x)",
           f"ratio {cb_fastest:.1f}x, max relative difference {deviation:.1e}",
           ">= 10x and <= 1e-6", cb_fastest >= 10 and deviation <= 1e-6)
    target("full-model sweep <= 2x the bare LAPACK call", f"ratio {1 / ratio['bare']:.2f}x",
           "<= 2x", 1 / ratio["bare"] <= 2)
    return agree


# -- 2. whole-cycle map ---------------------------------------------------------------------------
def cycle_map(scene_path, n_poses=360):
    """Frequencies over a whole crank turn: kinematics + sweep (what a cycle map computes)."""
    scene = load_scene(scene_path)
    return modal_sweep(scene.topology(), cycle_poses(scene, n_poses), N_MODES).frequencies


def whole_cycle(repeats: int) -> None:
    scenes = [load_scene(p) for p in CASES]
    elements = scenes[0].topology().links[0].elements
    print(f"2. whole-cycle map: 360 poses x {len(CASES)} cases, {elements} elements/link "
          f"({build_model(scenes[0].topology(), scenes[0].rigid_pose().joints).n_dofs} DOFs), "
          f"{N_MODES} modes, one core, medians of {repeats} repeats")

    def all_cases():
        for path in CASES:
            cycle_map(path)
    cpu = median_time(all_cases, repeats)
    wall = median_time(all_cases, repeats, time.perf_counter)
    print(f"  {cpu:.3f} s CPU ({cpu / (360 * len(CASES)) * 1e3:.3f} ms/pose), {wall:.3f} s wall")
    bare = 0.0
    for scene in scenes:  # the bare LAPACK call alone on the same 1440 pencils
        models = [build_model(scene.topology(), p) for p in cycle_poses(scene, 360)]
        plan = _DensePlan(models[0], rigid_elimination(models[0]))
        pencils = [plan.matrices(m) for m in models]
        bare += median_time(lambda pencils=pencils: [la.eigh(K, M, subset_by_index=[0, N_MODES - 1])
                                                     for K, M in pencils], repeats)
    print(f"  for scale, scipy.linalg.eigh(K, M) alone on the same 1440 pencils: {bare:.3f} s CPU")
    # no target here: the full model cannot beat its own LAPACK calls (over 1 s on this kind of
    # machine); the cycle map's target is section 2b's, through the Craig-Bampton sweep
    print(f"  full-model path: {cpu / bare:.2f}x the bare LAPACK calls on the same pencils "
          "(the cycle-map target is section 2b's)")


# -- 2b. whole-cycle map at the default converged mesh, Craig-Bampton links ---------------------
def _deviation(reduced: np.ndarray, full: np.ndarray) -> float:
    return float(np.max(np.abs(reduced - full) / full))


def converged_cycle(repeats: int, every: int = 10) -> None:
    """The 4 cycle maps at the mesh ``convergence.mesh_for_tolerance`` picks (6 modes,
    relative tolerance DEFAULT_TOL), through the Craig-Bampton sweep; the full model is solved
    at every ``every``-th pose to measure the deviation (all 1440 would take a minute)."""
    from flexlink.studies.verification.convergence import DEFAULT_TOL, mesh_for_tolerance

    scenes = [load_scene(p) for p in CASES]
    rules = [mesh_for_tolerance(scene, N_MODES) for scene in scenes]
    print(f"2b. whole-cycle map at the default converged mesh (convergence.mesh_for_tolerance, "
          f"{N_MODES} modes, tol {DEFAULT_TOL:g}): " + ", ".join(
              f"{Path(s.path).stem} {r.elements} elements/link (estimate {r.estimate:.1e})"
              for s, r in zip(scenes, rules)))
    work = [(s.topology(r.elements), cycle_poses(s, 360)) for s, r in zip(scenes, rules)]
    model = build_model(work[0][0], work[0][1][0])
    print(f"  360 poses x {len(CASES)} cases, {model.n_dofs} DOFs in the full model, "
          f"modal_sweep(reduction='craig-bampton'), one core, medians of {repeats} repeats "
          "(each repeat builds its Craig-Bampton plans afresh)")

    def all_cases():
        return [modal_sweep(t, poses, N_MODES, reduction="craig-bampton").frequencies
                for t, poses in work]

    def first_call():
        _families.cache_clear()  # every link's fixed-interface modes computed again
        all_cases()
    maps = all_cases()
    cpu = median_time(all_cases, repeats)
    wall = median_time(all_cases, repeats, time.perf_counter)
    cold = median_time(first_call, repeats)
    print(f"  {cpu:.3f} s CPU ({cpu / (360 * len(CASES)) * 1e3:.3f} ms/pose), {wall:.3f} s wall; "
          f"first call of each mesh (each link's fixed-interface modes computed too, which "
          f"repeated calls keep): {cold:.3f} s CPU")
    worst, full_cpu = 0.0, 0.0
    for (t, poses), reduced in zip(work, maps):
        start = time.process_time()
        full = modal_sweep(t, poses[::every], N_MODES).frequencies
        full_cpu += time.process_time() - start
        worst = max(worst, _deviation(reduced[::every], full))
    n_full = len(CASES) * len(work[0][1][::every])
    print(f"  full model at every {every}th pose ({n_full} poses): {full_cpu / n_full * 1e3:.2f} "
          f"ms/pose CPU, i.e. about {full_cpu / n_full * 360 * len(CASES):.1f} s for the 1440")
    target("whole-cycle map, 360 poses x 4 cases at the converged mesh, under 0.2 s CPU on one "
           f"core (repeated maps of one mesh; first call {cold:.3f} s)", f"{cpu:.3f} s", "< 0.2 s",
           cpu < 0.2)
    target("Craig-Bampton vs full model, first 6 modes", f"max relative difference {worst:.1e}",
           "<= 1e-6", worst <= 1e-6)


# -- 3. sparse-path scaling -----------------------------------------------------------------------
def scaling_point(spans: int) -> dict:
    """One size, run in its own process so that its peak memory is its own. The model is the
    stability suite's row of graded pinned spans (``stability.graded_spans``): well conditioned
    at any size, with a closed-form lowest frequency, unlike one link cut ever finer (which
    flexlink refuses past double precision)."""
    from flexlink.fe.model_at_pose import in_plane_eigen_scale
    from flexlink.fe.assembly import assemble, rigid_elimination
    from flexlink.fe.energy import twice_strain_energy
    from flexlink.fe.model import build_model
    from flexlink.analysis.eigensolver import EigenSolver
    from flexlink.analysis.solve import solve_modes
    from flexlink.studies.verification.self_checks import LONG_SPANS, graded_spans

    section = next(iter(load_scene(CASES[1]).sections.values()))

    def solve(n):
        topology, points = graded_spans(section, n)
        model = build_model(topology, points)
        K, M = assemble(model)
        return solve_modes(K, M, N_MODES, T=rigid_elimination(model), lambda_ref=in_plane_eigen_scale(model),
                           solver=EigenSolver("sparse"), energy=lambda U: twice_strain_energy(model, U))

    solve(2)  # load the code paths first
    rss = lambda key: int(next(line.split()[1] for line in  # noqa: E731  [kB]
                               Path("/proc/self/status").read_text().splitlines()
                               if line.startswith(key)))
    Path("/proc/self/clear_refs").write_text("5")  # restart the peak-RSS count from here
    before = rss("VmRSS:")
    seconds = median_time(lambda: solve(spans), 3)
    peak = rss("VmHWM:") - before
    result = solve(spans)
    longest = LONG_SPANS[0]
    exact = (np.pi / longest) ** 2 * np.sqrt(section.EI / section.mass_per_length) / (2 * np.pi)
    return {"spans": spans, "dofs": result.n_dofs, "seconds": seconds, "peak_mb": peak / 1024,
            "f1": float(result.frequencies[0]), "f1_exact": float(exact),
            "elastic": len(result.elastic)}


def scaling() -> None:
    from flexlink.studies.verification.self_checks import SPAN_ELEMENTS

    sizes = [1e3, 3e3, 1e4, 3e4, 1e5]
    print("3. sparse path: a row of graded pinned spans (stability.graded_spans, "
          f"{SPAN_ELEMENTS} elements each), assembly + reduction + shift-invert ARPACK for "
          f"{N_MODES} modes, CPU medians of 3, peak RSS above the start")
    rows = []
    for dofs in sizes:
        spans = max(1, round(dofs / (3 * (SPAN_ELEMENTS + 1) - 4)))
        out = subprocess.run([sys.executable, __file__, "--scaling-point", str(spans)],
                             check=True, capture_output=True, text=True).stdout
        row = json.loads(out.strip().splitlines()[-1])
        rows.append(row)
        print(f"  {row['dofs']:7d} DOFs: {row['seconds']:8.4f} s  {row['peak_mb']:8.1f} MB   "
              f"lowest mode {row['f1']:9.3f} Hz (closed form {row['f1_exact']:9.3f}), "
              f"{row['elastic']} of {N_MODES} labelled elastic")
    n = np.log([r["dofs"] for r in rows])
    t_exp = np.polyfit(n, np.log([r["seconds"] for r in rows]), 1)[0]
    m_exp = np.polyfit(n, np.log([max(r["peak_mb"], 1e-3) for r in rows]), 1)[0]
    target("time ~ DOFs^1", f"fitted exponent {t_exp:.2f}", "close to 1", t_exp < 1.25)
    target("peak memory ~ DOFs^1", f"fitted exponent {m_exp:.2f}", "close to 1", m_exp < 1.25)


# -- 4. start-up and imports ----------------------------------------------------------------------
_PROBE = """
import contextlib, io, json, sys, time
start = time.perf_counter()
from flexlink.cli import main
with contextlib.redirect_stdout(io.StringIO()):
    try:
        main(sys.argv[1:], prog_name="flexlink")
    except SystemExit:
        pass
print(json.dumps({"seconds": time.perf_counter() - start,
                  "heavy": sorted(m for m in ("pyvista", "matplotlib", "vtk") if m in sys.modules)}))
"""


def startup(repeats: int) -> None:
    print(f"4. start-up (wall, medians of {repeats} fresh processes)")
    flexlink = Path(sys.executable).parent / "flexlink"
    with tempfile.TemporaryDirectory() as out:
        runs = {"flexlink --help": ["--help"],
                "flexlink modes cases/case2.toml --json": ["modes", str(CASES[1]), "--json",
                                                          "--out", out]}
        for label, args in runs.items():
            probes = [json.loads(subprocess.run([sys.executable, "-c", _PROBE, *args], check=True,
                                                capture_output=True, text=True,
                                                cwd=ROOT).stdout.splitlines()[-1])
                      for _ in range(repeats)]
            heavy = sorted({m for p in probes for m in p["heavy"]})
            inside = statistics.median(p["seconds"] for p in probes)
            whole = median_time(lambda args=args: subprocess.run([str(flexlink), *args], check=True,
                                                       capture_output=True, cwd=ROOT),
                                repeats, time.perf_counter)
            print(f"  {label}: {whole:.3f} s whole process ({inside:.3f} s after the "
                  f"interpreter started); imports pyvista/matplotlib: "
                  f"{', '.join(heavy) if heavy else 'neither'}")
            target(f"{label} without pictures", "imports " + (', '.join(heavy) or "neither"),
                   "neither", not heavy)


# -- 5. calibration: parse once, the small run, parallel speed-up, dask --------------------------
SMALL = dict(starts=2, samples=8, elements=6)  # flexlink calibrate cases/ --family planar
SHIPPED = dict(starts=8, samples=200, elements=6)  # the shipped report: 3 families


def _study(families, n_jobs, **settings):
    from flexlink.scene import scene_files
    from flexlink.studies.calibration.calibration import StudySettings, run_study

    files = [str(f) for f in scene_files([ROOT / "cases"])]
    return [run_study(files, fam, None, StudySettings(n_jobs=n_jobs, **settings))
            for fam in families]


def _numbers(studies) -> str:
    """The studies' results without their settings (which name the worker count)."""
    from flexlink.output.calibration.calibration import study_document

    return json.dumps([{k: v for k, v in study_document(st).items() if k != "settings"}
                       for st in studies])


def _burn(n: int) -> int:
    total = 0
    for i in range(n):
        total += i * i
    return total


def calibration(full: bool) -> None:
    import flexlink.scene.source as source
    from joblib import Parallel, delayed

    print("5. calibration (flexlink calibrate cases/ --family planar --starts 2 --samples 8 -e 6, "
          "in this process; wall and CPU of this process and its workers' wall)")
    # parse once: loads with overrides after the first read no file
    parsed = source._parsed.cache_info().misses
    for k in range(50):
        load_scene(CASES[1], overrides={"section.width": f"{20 + k * 0.1!r} mm"})
    again = source._parsed.cache_info().misses - parsed
    target("scene files parsed once: TOML parses in 50 loads with overrides of a read scene",
           f"{again}", "0", again == 0)

    jobs = os.cpu_count() or 1
    start, wall = time.process_time(), time.perf_counter()
    serial = _study(["planar"], 1, **SMALL)
    serial_cpu, serial_wall = time.process_time() - start, time.perf_counter() - wall
    wall = time.perf_counter()
    together = _study(["planar"], -1, **SMALL)
    together_wall = time.perf_counter() - wall
    same = _numbers(serial) == _numbers(together)
    print(f"  one process: {serial_wall:.1f} s wall, {serial_cpu:.1f} s CPU; {jobs} workers: "
          f"{together_wall:.1f} s wall (load average now {os.getloadavg()[0]:.2f}); "
          f"identical results: {'yes' if same else 'NO'}")
    target("small calibration run under 20 s (all cores)", f"{together_wall:.1f} s", "< 20 s",
           together_wall < 20)
    speedup = serial_wall / together_wall
    target(f"parallel speed-up of the calibration on {jobs} cores", f"{speedup:.2f}x",
           ">= 1.5x", speedup >= 1.5)
    burn = [3_000_000] * jobs
    alone = median_time(lambda: [_burn(n) for n in burn], 3, time.perf_counter)
    shared = median_time(lambda: Parallel(n_jobs=jobs)(delayed(_burn)(n) for n in burn), 3,
                         time.perf_counter)
    print(f"  for scale, what the machine gives {jobs} processes now: a pure-Python loop speeds "
          f"up {alone / shared:.2f}x")
    try:
        from flexlink.parallel import use_scheduler

        wall = time.perf_counter()
        with use_scheduler("local"):
            on_dask = _study(["planar"], -1, **SMALL)
        dask_wall = time.perf_counter() - wall
        same = _numbers(serial) == _numbers(on_dask)
        target("dask LocalCluster (--scheduler local) gives the serial results",
               f"{'identical' if same else 'DIFFERENT'}, {dask_wall:.1f} s wall with the "
               "cluster's start", "identical", same)
    except ImportError:
        print("  dask.distributed not installed (pip install 'flexlink[dask]'): not measured")
    if not full:
        print("  target shipped report (3 families, 8 starts, 200 samples, -e 6) under 2 "
              "minutes: not run (--skip-full-calibration) "
              "NOT MEASURED")
        return
    wall = time.perf_counter()
    studies = _study(["planar", "out-of-plane", "3d"], -1, **SHIPPED)
    full_wall = time.perf_counter() - wall
    for st in studies:  # the numbers, to compare with a report made before a change
        starts = [c for fit in (st.fit_ex, st.fit_fe) for c in fit.converged]
        pct = {k: "n/a" if e.mean_abs_pct is None else f"{e.mean_abs_pct:.3f} %"
               for k, e in st.errors.items()}
        print(f"  {st.family}: mean |error| vs Ex: assumed {pct['assumed_inputs_vs_Ex']}, "
              f"calibrated {pct['calibrated_to_Ex_in_sample']}, cross-validated "
              f"{pct['cross_validated_vs_Ex']}; Ex and FE fits: "
              f"{starts.count(False)} of {len(starts)} starts stopped at the evaluation limit")
    target("shipped report (3 families, 8 starts, 200 samples, -e 6) under 2 minutes",
           f"{full_wall:.0f} s", "< 120 s", full_wall < 120)


# -- 6. parallel sweeps ---------------------------------------------------------------------------
def parallel(repeats: int) -> None:
    from flexlink.analysis.sweep import parallel_modal_sweep

    jobs = os.cpu_count() or 1
    print(f"6. parallel: the 4 cycle maps of section 2 with parallel_modal_sweep ({jobs} joblib "
          f"worker processes, poses split in {jobs} chunks) vs modal_sweep; wall, medians of "
          f"{repeats}")
    work = [(load_scene(p).topology(), cycle_poses(load_scene(p), 360)) for p in CASES]
    parallel_modal_sweep(work[0][0], work[0][1][:jobs], N_MODES)  # start the workers first
    serial = median_time(lambda: [modal_sweep(t, poses, N_MODES) for t, poses in work], repeats,
                         time.perf_counter)
    together = median_time(lambda: [parallel_modal_sweep(t, poses, N_MODES) for t, poses in work],
                           repeats, time.perf_counter)
    print(f"  serial {serial:.3f} s, {jobs} workers {together:.3f} s: speed-up "
          f"{serial / together:.2f}x on {jobs} cores (load average now "
          f"{os.getloadavg()[0]:.2f})")


SECTIONS = ("1", "2", "2b", "3", "4", "5", "6")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=7)
    parser.add_argument("--scaling-point", type=int, help=argparse.SUPPRESS)
    parser.add_argument("--skip-full-calibration", action="store_true",
                        help="leave out the shipped calibration report (about two minutes)")
    parser.add_argument("--only", type=lambda text: set(text.split(",")), default=set(SECTIONS),
                        help="comma-separated sections to run, e.g. 1,2b (default: all of "
                             + ",".join(SECTIONS) + ")")
    args = parser.parse_args()
    unknown = args.only - set(SECTIONS)
    if unknown:
        parser.error(f"unknown section(s) {', '.join(sorted(unknown))}: "
                     f"one of {', '.join(SECTIONS)}")
    if args.scaling_point:
        print(json.dumps(scaling_point(args.scaling_point)))
        return 0
    from flexlink import logbook

    once = logbook.configure()  # each kind of warning once, repeats counted at the end
    print(f"flexlink benchmark: {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, "
          f"{os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f} at start")
    few = max(3, args.repeats // 2)
    agree = per_pose(args.repeats) if "1" in args.only else True
    runs = {"2": lambda: whole_cycle(few), "2b": lambda: converged_cycle(few), "3": scaling,
            "4": lambda: startup(args.repeats), "5": lambda: calibration(not args.skip_full_calibration),
            "6": lambda: parallel(few)}
    for section, run in runs.items():
        if section in args.only:
            run()
    checked = (f"; frequencies agree with OpenSees to {TOLERANCE:g}: {'yes' if agree else 'NO'}"
               if "1" in args.only else "")
    print(f"load average {os.getloadavg()[0]:.2f} at the end{checked}")
    logbook.report_repeats(once)
    return 0 if agree else 1


if __name__ == "__main__":
    sys.exit(main())
