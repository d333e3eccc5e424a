"""Every console example of README.md and docs/ is marked, and the marked ones print what the
text shows (doc_examples.py says how blocks are marked, run and compared). The slow ones run
with UPKIE_RL_DOCS_SLOW=1 (`make test-docs`)."""

import math
import os
import re
from pathlib import Path

import numpy as np
import pytest

import doc_examples
from doc_examples import (ATAN2F_PROBE, NUMBER, as_float32, figures_vary, find_examples,
                          line_mismatch, output_mismatches, run_example)
from spine_process import cli_path

ROOT = Path(__file__).resolve().parents[2]
DOCS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
EXAMPLES = [example for path in DOCS for example in find_examples(path)]
RUN_SLOW = os.environ.get("UPKIE_RL_DOCS_SLOW") == "1"
README_MAX_LINES = 250


def build_dir() -> Path:
    return cli_path().resolve().parent


def test_every_console_example_is_marked():
    unmarked = [example.name for example in EXAMPLES if example.marker is None]
    assert not unmarked, ("console examples without a `<!-- example: run -->` or "
                          f"`<!-- example: not-run: REASON -->` line before them: {unmarked}")
    assert any(example.run for example in EXAMPLES)


@pytest.mark.parametrize(
    "example",
    [pytest.param(example, id=example.name,
                  marks=[pytest.mark.skipif(example.slow and not RUN_SLOW,
                                            reason="slow: `make test-docs` runs it")])
     for example in EXAMPLES if example.run])
def test_console_example_prints_what_the_text_shows(example):
    problems = run_example(example, ROOT, build_dir())
    assert not problems, f"{example.name}:\n" + "\n".join(problems)


def test_readme_is_a_front_page():
    lines = (ROOT / "README.md").read_text().splitlines()
    assert len(lines) <= README_MAX_LINES, f"README.md has {len(lines)} lines"


def test_a_figure_beyond_the_tolerance_is_a_mismatch():
    shown = "mean return 297.106 +- 0 over 1 episodes, mean length 300"
    assert line_mismatch(shown, shown, 1e-3, None) is None
    assert line_mismatch(shown, shown.replace("297.106", "297.2"), 1e-3, None) is None
    assert line_mismatch(shown, shown.replace("297.106", "290.5"), 1e-3, None) is not None
    assert line_mismatch(shown, shown.replace("300", "299"), 1e-3, None) is not None
    assert line_mismatch(shown, shown.replace("return", "reward"), 1e-3, None) == "other words"
    timing = "trained 2,048 steps in 00:03 (682 steps/s); mean return 12.5"
    speed = re.compile(r"in \d+:\d+ \([\d,]+ steps/s\)")
    assert line_mismatch(timing, timing.replace("682", "1,000"), 1e-3, speed) is None
    assert line_mismatch(timing, timing.replace("12.5", "13.5"), 1e-3, speed) is not None
    assert output_mismatches([shown, "video a.mp4: 46 frames"], f"x\n{shown}\n",
                             "video a.mp4: 46 frames\n", 1e-3, None) == []
    assert output_mismatches([shown], shown.replace("297.106", "-112.073"), "", 1e-3, None)


def test_the_runner_fails_on_a_changed_figure(tmp_path):
    """A real command whose text shows one figure changed: the runner reports that figure."""
    page = tmp_path / "page.md"
    command = ("$ upkie-rl rollout --env Upkie-Bullet-Pendulum --controller zero --episodes 1"
               " --exact-start")
    page.write_text("<!-- example: run -->\n```console\n" + command + "\n"
                    "mean return -48.0 +- 0 over 1 episodes from the exact start (--exact-start), "
                    "mean length 216\n```\n")
    [example] = find_examples(page)
    problems = run_example(example, ROOT, build_dir())
    assert len(problems) == 1 and "figure -61.2293 is not -48.0" in problems[0], problems


def test_an_unmarked_block_and_a_bad_marker_are_found(tmp_path):
    page = tmp_path / "page.md"
    page.write_text("```console\n$ upkie-rl envs\n```\n\n<!-- example: not-run: a reason -->\n"
                    "```sh\nmake train\n```\n\n```python\nprint(1)\n```\n")
    unmarked, skipped = find_examples(page)
    assert unmarked.marker is None and skipped.reason == "a reason" and not skipped.run
    page.write_text("<!-- example: not-run: -->\n```console\n$ ls\n```\n")
    with pytest.raises(ValueError, match="needs a reason"):
        find_examples(page)


def test_float_libm_figures_are_compared_only_where_atan2f_rounds_as_measured(tmp_path,
                                                                            monkeypatch):
    """The probe tells the two roundings apart (glibc 2.36's result is one float32 unit from
    the correctly rounded one), and a `float-libm` block's figures are compared only where
    atan2f gives the former."""
    y, x, measured = ATAN2F_PROBE
    assert as_float32(y) == y and as_float32(x) == x  # the probe's inputs are float32s
    correctly_rounded = as_float32(math.atan2(y, x))
    assert correctly_rounded != measured
    assert np.nextafter(np.float32(measured), np.float32(-np.inf)) == correctly_rounded
    page = tmp_path / "page.md"
    page.write_text('<!-- example: run float-libm vary="ms" -->\n```console\n$ ls\n```\n')
    [example] = find_examples(page)
    assert example.float_libm and example.run
    monkeypatch.setattr(doc_examples, "atan2f_rounds_as_measured", lambda: True)
    assert figures_vary(example).pattern == "ms"
    monkeypatch.setattr(doc_examples, "atan2f_rounds_as_measured", lambda: False)
    assert figures_vary(example) is NUMBER


def test_the_readme_results_are_the_checked_examples_figures():
    """Each row of the README's results table that is not marked `measured` shows figures
    that a run example prints: of the page it links, or of the README's first result."""
    text = (ROOT / "README.md").read_text()
    table = text[text.index("## Results"):text.index("## Platforms")]
    rows = [row for row in table.splitlines() if row.startswith("| ") and "---" not in row][1:]
    checked = 0
    for row in rows:
        what, figures, reproduce = [cell.strip() for cell in row.strip().strip("|").split("|")]
        if "measured" in figures:
            continue
        link = re.search(r"\(docs/([\w-]+\.md)", reproduce)
        page = ROOT / "docs" / link.group(1) if link else ROOT / "README.md"
        shown = "\n".join("\n".join(example.body) for example in find_examples(page)
                          if example.run)
        for figure in re.findall(r"\d+(?:\.\d+)?", figures):
            assert re.search(rf"(?<![\d.]){re.escape(figure)}(?![\d])", shown), (
                f"README result {figure!r} ({what}) is in no run example of {page.name}")
        checked += 1
    assert checked >= 3


def test_every_make_target_is_in_the_commands_page():
    makefile = (ROOT / "Makefile").read_text()
    phony = re.search(r"^\.PHONY:(.*)$", makefile, flags=re.MULTILINE).group(1).split()
    table = (ROOT / "docs" / "commands.md").read_text()
    documented = set(re.findall(r"`make ([\w-]+)`", table))
    missing = sorted(set(phony) - {"all"} - documented)
    assert not missing, f"make targets docs/commands.md does not list: {missing}"
