"""Docs are tests (issue 43): every command of docs/*.md runs as written or says why it cannot.

* A line `    $ build/bin/layerjkr ...` in an indented block is an example: the page's examples run in
  order, in one scratch directory per page where `data/` is the repository's bundled data (so a
  later example may read what an earlier one wrote), each must exit 0, and each line shown after
  it (up to a "...") must begin a printed line - its text exactly, its numbers to 1e-4 - as
  README's examples are checked (tests/cli/test_readme_examples.cpp, which runs README's).
* Any other shell command in an indented block of README.md or docs/*.md - a synopsis with
  placeholders, a developer's or an installer's command - sits in a block preceded by
  `<!-- shell: not run (why) -->`.
A deliberately broken example or an unmarked command fails the runner (the last two tests)."""
import os
import pathlib
import re
import shlex
import subprocess

import pytest

SOURCE = pathlib.Path(os.environ.get("LAYERJKR_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
PROMPT = "    $ build/bin/layerjkr "
NOT_RUN = re.compile(r"<!--\s*shell:\s*not run\s*\(.+\)\s*-->")
COMMAND = re.compile(r"^    (\$ )?((build/bin/)?layerjkr [a-z-]+( |$)|cmake |ctest |pip |python3 |/usr/bin/python3 |bash |scripts/|\./|git |sudo |apt-get )")
NUMBER = re.compile(r"(?<![A-Za-z0-9_])[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def examples(text):
    """(line number, arguments, shown lines) of each `$ build/bin/layerjkr` example."""
    lines, out = text.splitlines(), []
    for k, line in enumerate(lines):
        if line.startswith(PROMPT):
            shown = []
            for follow in lines[k + 1:]:
                if not follow.startswith("    ") or follow.startswith("    $"):
                    break
                shown.append(follow.strip())
            out.append((k + 1, line[len(PROMPT):], shown))
    return out


def unmarked_commands(text):
    """(line number, line) of each shell command in an indented block that is neither an example
    nor in a block marked `<!-- shell: not run (why) -->` (within the 3 lines before the block)."""
    lines, out = text.splitlines(), []
    block_start = None  # the first line of the indented block the current line is in
    for k, line in enumerate(lines):
        if not line.strip():
            continue  # a blank line neither opens nor closes a block
        if not line.startswith("    "):
            block_start = None
            continue
        if block_start is None:
            block_start = k
        if COMMAND.match(line) and not line.startswith(PROMPT):
            if not any(NOT_RUN.search(lines[j]) for j in range(max(0, block_start - 3), block_start)):
                out.append((k + 1, line.strip()))
    return out


def shows(printed, expected):
    """Whether `printed` begins with `expected`: text exactly, numbers within 1e-4 relative."""
    i = j = 0
    while j < len(expected):
        m_e, m_p = NUMBER.match(expected, j), NUMBER.match(printed, i)
        if m_e and m_p and (j == 0 or not expected[j - 1].isalnum()):
            e, p = float(m_e.group()), float(m_p.group())
            if abs(e - p) > 1e-4 * abs(e):
                return False
            i, j = m_p.end(), m_e.end()
        elif i < len(printed) and printed[i] == expected[j]:
            i, j = i + 1, j + 1
        else:
            return False
    return True


def run_page(cli, path, text, scratch):
    (scratch / "data").symlink_to(SOURCE / "data")
    for line, args, shown in examples(text):
        run = subprocess.run([cli] + shlex.split(args), cwd=scratch, capture_output=True, text=True, timeout=300)
        where = "%s:%d: layerjkr %s" % (path.name, line, args)
        assert run.returncode == 0, "%s exited %d: %s" % (where, run.returncode, run.stderr)
        printed = [p.strip() for p in (run.stdout + run.stderr).splitlines()]
        for expected in shown:
            expected = expected.split("...")[0].rstrip()
            if expected:
                assert any(shows(p, expected) for p in printed), "%s: shows %r, printed:\n%s" % (
                    where, expected, "\n".join(printed))


def pages():
    return sorted((SOURCE / "docs").glob("*.md"))


@pytest.mark.parametrize("page", pages(), ids=lambda p: p.name)
def test_every_example_runs_and_prints_what_the_page_shows(page, cli, tmp_path):
    run_page(cli, page, page.read_text(), tmp_path)


@pytest.mark.parametrize("page", [SOURCE / "README.md"] + pages(), ids=lambda p: p.name)
def test_every_other_command_says_why_it_is_not_run(page):
    assert unmarked_commands(page.read_text()) == []


def test_the_pages_have_examples():
    assert sum(len(examples(p.read_text())) for p in pages()) >= 6


def test_a_broken_example_fails(cli, tmp_path):
    page = "Text.\n\n    $ build/bin/layerjkr summary data/scenes/no_such.json\n"
    (tmp_path / "a").mkdir()
    with pytest.raises(AssertionError, match="exited 2"):
        run_page(cli, pathlib.Path("broken.md"), page, tmp_path / "a")
    page = "Text.\n\n    $ build/bin/layerjkr curve data/scenes/hertz_R40nm.json --at 1e-8\n    a,P,delta,X\n"
    (tmp_path / "b").mkdir()
    with pytest.raises(AssertionError, match="shows 'a,P,delta,X'"):
        run_page(cli, pathlib.Path("broken.md"), page, tmp_path / "b")


def test_an_unmarked_command_fails():
    page = "Text:\n\n    layerjkr fit FILE --scene S.json\n\nMore.\n\n<!-- shell: not run (a synopsis) -->\n\n" \
           "    layerjkr fit FILE --scene S.json\n    layerjkr export FILE --out X.csv\n"
    assert unmarked_commands(page) == [(3, "layerjkr fit FILE --scene S.json")]
