"""The documentation stays reference: docs/ and the README say what the tool does and why, not
when something was measured. Dated runs, timing diaries and mutation logs belong in
notes/history.md (outside docs/ and outside the package) or in commit messages.

Guarded here: docs/testing.md stays short enough to read; no page under docs/ (nor the README)
holds an ISO date, an issue number, a hash-number id (a mutant's "#33") or a diary word such as
"today"; every relative link of the README and docs/ points at a file that exists; the README's
set-up commands are the two the project promises, and both scripts exist."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from conftest import ROOT

DOCS = ROOT / "docs"
TEXT_SUFFIXES = {".md", ".json", ".txt", ".csv", ".html"}
# docs/testing.md is read by people adding tests: what the suite checks, how to run it, how
# mutation testing is run and read, the latest kill rates. The logs of each mutation round
# live in notes/history.md, so the page does not grow with every round.
TESTING_MAX_LINES = 300

# What makes a line a diary entry rather than reference:
DIARY = {
    "an ISO date": re.compile(r"\b(?:19|20)\d\d-(?:0[1-9]|1[0-2])-(?:0[1-9]|[12]\d|3[01])\b"),
    "an issue number": re.compile(r"\bissues?\s*(?:no\.?\s*)?#?\s*\d+", re.IGNORECASE),
    # "#33" (an issue or a mutant id); an HTML entity (&#38;) or a URL fragment (page#3) is not
    "a hash-number id": re.compile(r"(?<![\w&/])#\d+\b"),
    "a diary word": re.compile(r"\b(?:today|yesterday|this morning|this afternoon)\b",
                               re.IGNORECASE),
}


def text_files() -> list[Path]:
    pages = sorted(p for p in DOCS.rglob("*") if p.is_file() and p.suffix in TEXT_SUFFIXES)
    return [ROOT / "README.md", *pages]


def diary_lines(path: Path) -> list[str]:
    found = []
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
        for what, pattern in DIARY.items():
            match = pattern.search(line)
            if match:
                found.append(f"{path.relative_to(ROOT)}:{number}: {what} ({match.group(0)!r}): "
                             f"{line.strip()[:100]}")
    return found


def test_testing_page_stays_under_its_length():
    lines = len((DOCS / "testing.md").read_text(encoding="utf-8").splitlines())
    assert lines < TESTING_MAX_LINES, (
        f"docs/testing.md has {lines} lines (under {TESTING_MAX_LINES} expected): keep it to "
        "what the suite checks and how to run it; put mutation logs in notes/history.md")


@pytest.mark.parametrize("path", text_files(), ids=lambda p: str(p.relative_to(ROOT)))
def test_no_dated_measurement_or_issue_number(path):
    found = diary_lines(path)
    assert not found, ("reference pages hold no dates, issue numbers or diary words; move the "
                       "measurement to notes/history.md or a commit message:\n" + "\n".join(found))


@pytest.mark.parametrize("text, what", [
    ("measured 2026-11-26 (steps taken after refinement)", "an ISO date"),
    ("it took 28 minutes before issue 15", "an issue number"),
    ("see issue #32", "an issue number"),
    ("`parts.drive` #45 (tests/analysis)", "a hash-number id"),
    ("Today's benchmark lines", "a diary word"),
])
def test_the_diary_patterns_catch_what_they_name(text, what):
    assert DIARY[what].search(text)


@pytest.mark.parametrize("text", [
    "Ex = 53.4 GPa at 2000 rev/min, 1e-12 relative",
    "the 16-vector basis over 50:3000 rev/min",
    "a colour given as &#35;444 or a link to page#3",
    "the tissue of the joint",  # the word inside another word
])
def test_reference_text_is_not_taken_for_a_diary(text):
    assert not any(pattern.search(text) for pattern in DIARY.values())


LINK = re.compile(r"\]\(([^)\s]+)\)")


def relative_links(path: Path) -> list[str]:
    links = LINK.findall(path.read_text(encoding="utf-8"))
    return [link.split("#")[0] for link in links
            if not re.match(r"[a-z]+:", link) and not link.startswith("#")]


@pytest.mark.parametrize("path", [p for p in text_files() if p.suffix == ".md"],
                         ids=lambda p: str(p.relative_to(ROOT)))
def test_every_relative_link_points_at_a_file(path):
    missing = [link for link in relative_links(path) if not (path.parent / link).exists()]
    assert not missing, f"{path.relative_to(ROOT)} links to files that do not exist: {missing}"


def test_readme_set_up_commands_are_the_two_promised():
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    commands = re.findall(r"^    (bash scripts/\S+)\s*$", text, re.MULTILINE)
    assert commands == ["bash scripts/run-cases.sh", "bash scripts/test.sh"]
    for command in commands:
        assert (ROOT / command.split()[1]).is_file()
