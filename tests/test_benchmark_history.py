"""benchmarks/RESULTS.md keeps the latest run of each benchmark and history/<benchmark>.jsonl the runs it superseded:
the history parses, and nothing the journal held before the split is lost (every heading it had is in one or the
other). Read as plain files: the tests do not import the benchmarks."""

import json
import re
from pathlib import Path

import pytest

BENCHMARKS = Path(__file__).resolve().parents[1] / "benchmarks"
HISTORY = BENCHMARKS / "history"
SCRIPTS = {p.stem for p in BENCHMARKS.glob("bench_*.py")}
KEYS = {"benchmark", "heading", "parent_heading", "date", "commit", "machine", "command", "tables", "text"}


def headings(markdown: str) -> list[str]:
    """Titles of the heading lines of ``markdown``, fenced code left out."""
    out, fenced = [], False
    for line in markdown.splitlines():
        if line.startswith("```"):
            fenced = not fenced
        elif not fenced and re.match(r"#{1,6} ", line):
            out.append(line.lstrip("#").strip())
    return out


def history_files() -> list[Path]:
    return sorted(HISTORY.glob("*.jsonl"))


def records(path: Path) -> list[dict]:
    return [json.loads(line) for line in path.read_text().splitlines() if line.strip()]


def test_history_holds_a_file_per_benchmark_with_superseded_runs():
    names = {p.stem for p in history_files()}
    assert {"bench_solver", "bench_two_scale", "one_off"} <= names
    assert names - {"one_off"} <= SCRIPTS  # a history file belongs to a script that exists


@pytest.mark.parametrize("path", history_files(), ids=lambda p: p.stem)
def test_history_records_parse(path):
    recs = records(path)
    assert recs
    for rec in recs:
        assert KEYS <= set(rec), set(rec) ^ KEYS
        assert rec["benchmark"] == path.stem
        assert headings(rec["text"])[0] == rec["heading"]  # the section's own heading comes first
        assert rec["date"] is None or re.fullmatch(r"20\d\d-\d\d-\d\d", rec["date"])
        assert rec["commit"] is None or re.fullmatch(r"[0-9a-f]{7,40}", rec["commit"])
        for table in rec["tables"]:
            assert table["rows"], rec["heading"]
            for row in table["rows"]:
                assert list(row) == table["header"]
                cells = [c for c in row.values() if c]
                # each parsed row is a row of the text, cells in order
                assert any(all(c in line.replace("\\|", "|") for c in cells) for line in rec["text"].splitlines()
                           if line.lstrip().startswith("|")), (rec["heading"], row)


def test_every_heading_before_the_split_is_in_results_or_history():
    before = json.loads((HISTORY / "headings_before_split.json").read_text())["headings"]
    kept = set(headings((BENCHMARKS / "RESULTS.md").read_text()))
    for path in history_files():
        for rec in records(path):
            kept.update(headings(rec["text"]) + headings(rec.get("parent_text", "")))
            kept.update(h for h in (rec["heading"], rec["parent_heading"]) if h)
    missing = [h for h in before if h not in kept]
    assert len(before) > 90 and not missing, missing


def test_results_keeps_one_latest_section_per_benchmark():
    text = (BENCHMARKS / "RESULTS.md").read_text()
    sections = re.split(r"^## ", text, flags=re.M)[1:]
    names = [s.splitlines()[0].strip() for s in sections]
    assert len(names) == len(set(names))
    assert set(names) <= SCRIPTS, set(names) - SCRIPTS
    for section in sections:
        for field in ("run", "date", "commit", "machine", "command"):
            assert re.search(rf"^- {field}: \S", section, re.M), (section.splitlines()[0], field)
    with_history = {p.stem for p in history_files()} - {"one_off"}
    assert with_history <= set(names)  # a benchmark with superseded runs keeps its latest here
    assert names[-1] == "bench_solver" and "Issue 38" in sections[-1]
