"""The numerical self-checks (``studies.verification.self_checks``) as the JSON document and the
text of `flexlink verify`: per check what it expected, what it got and whether it passed."""

from __future__ import annotations

from flexlink.studies.verification.self_checks import Check


def self_checks_document(scene, checks: list[Check], slow: bool) -> dict:
    """The JSON document of `flexlink verify` (without its ``files``)."""
    return {"command": "verify", "scene": scene.path, "slow": slow,
            "passed": sum(c.passed for c in checks), "total": len(checks),
            "checks": [{"id": c.id, "name": c.name, "expected": c.expected, "got": c.got,
                        "passed": c.passed, "details": c.details} for c in checks]}


def self_checks_text(document: dict) -> str:
    """Expected / got / pass per check, then the count passed."""
    lines = [f"[{'PASS' if c['passed'] else 'FAIL'}] {c['id']}: {c['name']}\n"
             f"        expected: {c['expected']}\n        got:      {c['got']}"
             for c in document["checks"]]
    lines.append(f"\n{document['passed']} of {document['total']} checks passed"
                 + ("" if document["slow"] else " (slow checks skipped: --slow)"))
    return "\n".join(lines)
