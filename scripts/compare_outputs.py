"""Compare two folders of JSON documents from scripts/output-snapshot.sh.

Timings, file paths and run folders are left out; every other value must be equal (floats to
1e-12 relative, since summation order may move the last bits). Keys renamed on purpose are
given as OLD=NEW arguments. Prints each difference and exits 1 if there is any.

    python scripts/compare_outputs.py BEFORE AFTER [old_key=new_key ...]
"""

import json
import math
import sys
from pathlib import Path

VOLATILE = ("seconds", "time", "_s", "wall", "cpu", "files", "file", "out", "path", "written",
            "version", "timings", "date")


def volatile(key: str) -> bool:
    k = key.lower()
    return any(k == v or k.endswith(v) or k.startswith(v) for v in VOLATILE)


def differences(a, b, where="$", renames=None):
    renames = renames or {}
    if isinstance(a, dict) and isinstance(b, dict):
        a = {renames.get(k, k): v for k, v in a.items()}
        for key in sorted(set(a) | set(b)):
            if volatile(key):
                continue
            if key not in a:
                yield f"{where}.{key}: only after"
            elif key not in b:
                yield f"{where}.{key}: only before"
            else:
                yield from differences(a[key], b[key], f"{where}.{key}", renames)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            yield f"{where}: {len(a)} items before, {len(b)} after"
        for i, (x, y) in enumerate(zip(a, b)):
            yield from differences(x, y, f"{where}[{i}]", renames)
    elif isinstance(a, float) or isinstance(b, float):
        if not (isinstance(a, (int, float)) and isinstance(b, (int, float))):
            yield f"{where}: {a!r} before, {b!r} after"
        elif not (a == b or (math.isnan(a) and math.isnan(b))
                  or math.isclose(a, b, rel_tol=1e-12, abs_tol=1e-300)):
            yield f"{where}: {a!r} before, {b!r} after"
    elif a != b:
        yield f"{where}: {a!r} before, {b!r} after"


def main(argv):
    before, after = Path(argv[1]), Path(argv[2])
    renames = dict(arg.split("=", 1) for arg in argv[3:])
    bad = 0
    for doc in sorted(before.glob("*.json")):
        other = after / doc.name
        if not other.exists():
            print(f"{doc.name}: missing after")
            bad += 1
            continue
        try:
            a, b = json.loads(doc.read_text() or "null"), json.loads(other.read_text() or "null")
        except json.JSONDecodeError as exc:
            print(f"{doc.name}: not JSON ({exc})")
            bad += 1
            continue
        found = list(differences(a, b, renames=renames))
        for line in found[:20]:
            print(f"{doc.name}: {line}")
        if len(found) > 20:
            print(f"{doc.name}: ... {len(found) - 20} more")
        bad += bool(found)
    print(f"{bad} of {len(list(before.glob('*.json')))} documents differ")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
