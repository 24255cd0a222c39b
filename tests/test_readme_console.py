"""README and docs examples are what the code prints: the console blocks run verbatim (README.md and the command-line
page, ``readme_console.FILES``), the README's Python block's commented values hold."""

import contextlib
import io
import re
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "examples"))

import readme_console  # noqa: E402

README = (ROOT / "README.md").read_text(encoding="utf-8")
CLI_PAGE = (ROOT / "docs" / "cli.md").read_text(encoding="utf-8")


@pytest.mark.parametrize("name", readme_console.FILES)
def test_readme_console_blocks_match_the_cli(name):
    """Every `$ dfa ...` line of the file prints exactly the output shown under it (make readme rewrites them)."""
    text = (ROOT / name).read_text(encoding="utf-8")
    assert readme_console.BLOCK.search(text), f"{name} has no console block"
    rendered = readme_console.render(text)
    if rendered != text:
        import difflib

        diff = "".join(difflib.unified_diff(text.splitlines(True), rendered.splitlines(True), name, "code now"))
        pytest.fail(f"{name} console output differs from the code; run `make readme`:\n" + diff[:4000])


def test_readme_console_check_detects_a_changed_number(tmp_path):
    """The checker can fail: one changed digit in a documented output is reported."""
    m = re.search(r"margin\s+(\d\.\d+)", CLI_PAGE)
    assert m, "the command-line page's dfa check example shows a margin row"
    start = CLI_PAGE.rindex("```console\n", 0, m.start())  # that example's block alone: its command runs once
    block = CLI_PAGE[start : CLI_PAGE.index("```\n", m.end()) + 4]
    assert block.count("$ dfa") >= 1
    bad = block.replace(m.group(0), m.group(0)[:-1] + str((int(m.group(0)[-1]) + 1) % 10), 1)
    good, path = tmp_path / "good.md", tmp_path / "cli.md"
    good.write_text(block, encoding="utf-8")
    path.write_text(bad, encoding="utf-8")
    with contextlib.redirect_stdout(io.StringIO()):
        assert readme_console.main(["--readme", str(good)]) == 0
        assert readme_console.main(["--readme", str(path)]) == 1


def _python_block() -> str:
    m = re.search(r"```python\nimport dfa\n(.*?)```", README, re.S)
    assert m, "README has the Python example"
    return "import dfa\n" + m.group(1)


def _agrees(printed: str, expected: str) -> bool:
    p, e = printed.split(), expected.split()
    if not p or not e:
        return False
    try:
        digits = len(e[0].split(".")[1]) if "." in e[0] else 0
        ok = round(float(p[0]), digits) == float(e[0])
    except ValueError:
        ok = p[0] == e[0]
    return ok and (len(p) == 1 or p[: len(e)] == e[: len(p)] or p[1:] == e[1 : len(p)])


def test_readme_python_example_prints_its_commented_values():
    """Each `print(...)  # value` line of the README's Python example prints that value (to its shown digits)."""
    code = _python_block()
    expected = [
        line.split("#", 1)[1].split(":")[0].strip()
        for line in code.splitlines()
        if line.startswith("print(") and "#" in line
    ]
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        exec(compile(code, "README.md", "exec"), {})
    printed = buf.getvalue().splitlines()
    assert len(printed) == len(expected)
    for got, want in zip(printed, expected, strict=False):
        assert _agrees(got, want), (got, want)
