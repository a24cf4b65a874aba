"""flaplag.report and flaplag.merge against the command line's `flaplag report` and
`flaplag merge`: the same pages and the same merged bytes, refusals naming the argument."""

import json
import re
import subprocess

import pytest

import flaplag
from conftest import CLI


def _cli(*args, cwd=None):
    if not CLI:
        pytest.fail("FLAPLAG_CLI is not set (run the tests through ctest)")
    proc = subprocess.run([CLI, *args], capture_output=True, text=True, timeout=300, cwd=cwd)
    assert proc.returncode == 0, f"flaplag {' '.join(args)}: {proc.stderr}"
    return proc.stdout


def _without_date(page):
    """The page without its "made on" row (the minute the page was made)."""
    return re.sub(r"<tr><th>made on</th><td>[^<]*</td></tr>\n", "", page)


@pytest.fixture(scope="module")
def critical_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("critical") / "critical.json"
    _cli("critical", "--json", "-o", str(path))
    return path


@pytest.fixture(scope="module")
def study_parts(tmp_path_factory):
    d = tmp_path_factory.mktemp("parts")
    case = ["study", "--vary", "omega-lag=0.5:1.5:0.25", "--json"]
    parts = [d / "part-1.json", d / "part-2.json"]
    for i, p in enumerate(parts, start=1):
        _cli(*case, "--shard", f"{i}/2", "-o", str(p))
    merged = d / "merged-by-cli.json"
    _cli("merge", str(parts[0]), str(parts[1]), "-o", str(merged))
    return parts, merged


def test_report_shows_the_critical_advance_ratio_of_the_file(critical_file, tmp_path):
    mu_c = json.loads(critical_file.read_text())["mu_c"]
    page_path = tmp_path / "page.html"
    page = flaplag.report(critical_file, html=page_path)
    assert page_path.read_text() == page
    # The key result to six significant digits, as the page promises.
    assert f"&mu;<sub>c</sub> = {mu_c:.6g}" in page
    assert page.startswith("<!DOCTYPE html>") and "<script" not in page


def test_report_is_the_page_of_the_command_line(critical_file):
    by_cli = _cli("report", str(critical_file))
    assert _without_date(flaplag.report(str(critical_file))) == _without_date(by_cli)


def test_report_escapes_the_texts_of_a_received_file(critical_file, tmp_path):
    result = json.loads(critical_file.read_text())
    result["message"] = "<script>alert(1)</script>"
    hostile = tmp_path / "hostile.json"
    hostile.write_text(json.dumps(result))
    page = flaplag.report(hostile)
    assert "&lt;script&gt;alert(1)&lt;/script&gt;" in page
    assert "<script" not in page


def test_merge_is_the_command_lines_merge_byte_for_byte(study_parts, tmp_path):
    parts, merged_by_cli = study_parts
    out = tmp_path / "merged.json"
    # The parts in the other order: merge takes them in any order.
    text = flaplag.merge([parts[1], str(parts[0])], output=out)
    assert out.read_bytes() == merged_by_cli.read_bytes()
    assert text == merged_by_cli.read_text()
    merged = json.loads(text)
    assert "shard" not in merged and len(merged["rows"]) == 5


def _refusal(call):
    with pytest.raises(flaplag.InvalidInput) as info:
        call()
    message = str(info.value)
    assert "\n" not in message
    return info.value


def test_merge_refuses_a_missing_repeated_or_damaged_part(study_parts, tmp_path):
    parts, _ = study_parts
    e = _refusal(lambda: flaplag.merge([parts[0]]))
    assert e.field == "parts" and "part 2/2 missing" in e.reason
    e = _refusal(lambda: flaplag.merge([parts[0], parts[0]]))
    assert e.field == "parts" and "again" in e.reason
    damaged = json.loads(parts[0].read_text())
    damaged["rows"][0]["omega"] = 0.123
    path = tmp_path / "damaged.json"
    path.write_text(json.dumps(damaged, indent=2))
    e = _refusal(lambda: flaplag.merge([path, parts[1]]))
    assert e.field == "parts" and "digest" in e.reason


def test_refusals_name_the_argument(critical_file, tmp_path):
    not_json = tmp_path / "not.json"
    not_json.write_text("[1, 2")
    assert _refusal(lambda: flaplag.report(not_json)).field == "result"
    assert _refusal(lambda: flaplag.report(tmp_path / "missing.json")).field == "result"
    assert _refusal(lambda: flaplag.report(3)).field == "result"
    assert _refusal(lambda: flaplag.report(critical_file, html=tmp_path)).field == "html"
    assert _refusal(lambda: flaplag.merge("part-1.json")).field == "parts"
    assert _refusal(lambda: flaplag.merge([])).field == "parts"
    assert _refusal(lambda: flaplag.merge([critical_file])).field == "parts"
    assert _refusal(lambda: flaplag.report(critical_file, memory_limit="1K")).field == (
        "memory_limit"
    )
    # Nothing is written when the input is refused.
    out = tmp_path / "out.html"
    _refusal(lambda: flaplag.report(not_json, html=out))
    assert not out.exists()
