"""Run every command on every shipped scene with --json and keep the documents, or compare two
such snapshots: a refactoring must leave every answer the same.

    python scripts/outputs_snapshot.py run DIR        # one JSON file per (command, scene)
    python scripts/outputs_snapshot.py compare A B    # differences, timings left out

Run from the checkout whose ``flexlink`` is to be judged (PYTHONPATH=$PWD). The options keep
the whole run to a few minutes on a shared machine (few poses, no pictures, short fits).
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SCENES = sorted((ROOT / "cases").glob("case*.toml")) + sorted((ROOT / "scenes").glob("*.toml"))

# (name, arguments after the scene, whether the scene needs a [prb] table)
RUNS = (
    ("modes", ["modes"], False),
    ("cycle", ["cycle", "--poses", "12"], False),
    ("cycle-sorted", ["cycle", "--sorted", "--poses", "12"], False),
    ("campbell", ["campbell", "--poses", "12", "--speeds", "0:3000 rev/min"], False),
    ("converge", ["converge", "--max-elements", "8", "--repeats", "1"], False),
    ("export", ["export", "--no-pictures", "--phases", "4"], False),
    ("mac-out-of-plane", ["mac", "--part", "out-of-plane", "-e", "4"], False),
    ("kinematics", ["kinematics", "--poses", "36"], False),
    ("prb", ["prb"], True),
    ("report", ["report", "--cycle-poses", "4"], False),
)
# keys whose values are wall times, sizes or paths of this run
VOLATILE = {"seconds", "elapsed", "out", "files", "file", "folder", "path", "report", "written",
            "version", "bytes", "vtu", "pvd", "frames", "pictures", "plot", "stderr_last"}


def _command(args: list[str], scene: Path, out: Path) -> list[str]:
    if args[0] == "mac":
        return [sys.executable, "-m", "flexlink.cli", *args, str(scene), str(scene), "--json",
                "--out", str(out)]
    return [sys.executable, "-m", "flexlink.cli", *args, str(scene), "--json", "--out", str(out)]


def run(target: Path) -> None:
    target.mkdir(parents=True, exist_ok=True)
    jobs = [(name, args, scene) for name, args, prb in RUNS for scene in SCENES
            if not prb or "[prb]" in scene.read_text()]
    jobs.append(("verify", ["verify"], None))
    for name, args, scene in jobs:
        with tempfile.TemporaryDirectory() as out:
            if scene is None:
                cmd = [sys.executable, "-m", "flexlink.cli", *args, "--json", "--out", out]
            else:
                cmd = _command(args, scene, Path(out))
            done = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)
        stem = f"{name}--{scene.stem if scene else 'default'}"
        document = {"exit": done.returncode, "stdout": _parsed(done.stdout),
                    "stderr_last": done.stderr.strip().splitlines()[-1:] if done.returncode else []}
        (target / f"{stem}.json").write_text(json.dumps(document, indent=1, sort_keys=True))
        print(stem, done.returncode, flush=True)


def _parsed(text: str):
    try:
        return json.loads(text)
    except json.JSONDecodeError:
        return text


def _volatile(key: str) -> bool:
    return key in VOLATILE or key.endswith(("_seconds", "_s", "_time"))


def differences(a, b, where: str = "") -> list[str]:
    if isinstance(a, dict) and isinstance(b, dict):
        out = []
        for key in sorted(set(a) | set(b)):
            if _volatile(str(key)):
                continue
            if key not in a or key not in b:
                out.append(f"{where}/{key}: only in {'A' if key in a else 'B'}")
            else:
                out += differences(a[key], b[key], f"{where}/{key}")
        return out
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return [f"{where}: length {len(a)} vs {len(b)}"]
        return [d for i, (x, y) in enumerate(zip(a, b)) for d in differences(x, y, f"{where}[{i}]")]
    return [] if a == b else [f"{where}: {a!r} vs {b!r}"[:300]]


def compare(first: Path, second: Path) -> int:
    bad = 0
    for path in sorted(first.glob("*.json")):
        other = second / path.name
        if not other.exists():
            print(f"{path.name}: missing in {second}")
            bad += 1
            continue
        found = differences(json.loads(path.read_text()), json.loads(other.read_text()))
        if found:
            bad += 1
            print(f"{path.name}: {len(found)} differences")
            for line in found[:8]:
                print("   ", line)
    print(f"{bad} of {len(list(first.glob('*.json')))} documents differ")
    return 1 if bad else 0


if __name__ == "__main__":
    if sys.argv[1:2] == ["run"] and len(sys.argv) == 3:
        run(Path(sys.argv[2]))
    elif sys.argv[1:2] == ["compare"] and len(sys.argv) == 4:
        sys.exit(compare(Path(sys.argv[2]), Path(sys.argv[3])))
    else:
        sys.exit(__doc__)
