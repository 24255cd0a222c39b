"""Files the command line reads and writes (issue 27): the output folder of ``report`` (a folder nothing can be
written in is bad input, exit 2; a path through a file says so; one level is created, as the help says) and the
validation summary it reads (a regular file of bounded size, never ``/dev/zero`` read until killed)."""

from __future__ import annotations

import json
import os

import pytest

from dfa import _io
from dfa.cli import main
from dfa.cli.report import VALIDATION_MAX_BYTES
from dfa.errors import DFAValueError

IMPULSE = ["--device", "impulse", "--velocity", "0.05"]


def _refused(capsys, *argv: str) -> str:
    code = main(list(argv))
    out, err = capsys.readouterr()
    assert code == 2, (argv, out, err)
    assert err.count("\n") == 1 and err.startswith("dfa") and "Traceback" not in err, err
    return err


# ------------------------------------------------------------------ report --out
def test_out_through_a_file_names_the_file(capsys, tmp_path):
    (tmp_path / "afile").write_text("keep")
    for sub in ("sub", os.path.join("sub", "deeper")):
        err = _refused(capsys, "report", *IMPULSE, "--out", str(tmp_path / "afile" / sub))
        assert f"{str(tmp_path / 'afile')!r} is a file, not a folder" in err, err
    assert (tmp_path / "afile").read_text() == "keep"


def test_out_with_a_missing_parent_says_one_level_is_created(capsys, tmp_path):
    err = _refused(capsys, "report", *IMPULSE, "--out", str(tmp_path / "no" / "new"))
    assert "does not exist; create it first (only the last folder of the path is created)" in err
    assert os.listdir(tmp_path) == []


def test_out_where_nothing_can_be_written_is_bad_input_not_a_failed_write(capsys):
    if not os.path.isdir("/proc/self"):
        pytest.skip("no /proc")
    err = _refused(capsys, "report", *IMPULSE, "--out", "/proc/x")  # exit 1 before, even for root
    assert "--out '/proc/x' is invalid: nothing can be written in folder '/proc'" in err
    assert "nothing can be written in the folder" in _refused(capsys, "report", *IMPULSE, "--out", "/proc")


def test_check_output_folder_tries_rather_than_asks(tmp_path, monkeypatch):
    monkeypatch.setattr(_io, "_probe", lambda folder: "Read-only file system")
    with pytest.raises(DFAValueError, match="nothing can be written in the folder .Read-only file system"):
        _io.check_output_folder("--out", str(tmp_path), create=True)
    monkeypatch.undo()
    assert _io.check_output_folder("--out", str(tmp_path / "new"), create=True) == str(tmp_path / "new")
    assert os.listdir(tmp_path) == []  # the check leaves nothing behind
    assert _io.make_output_folder("--out", str(tmp_path / "new")) and (tmp_path / "new").is_dir()


def test_make_output_folder_failure_is_bad_input(tmp_path):
    (tmp_path / "f").write_text("x")
    with pytest.raises(DFAValueError, match=r"^--out .* is invalid: the folder cannot be created"):
        _io.make_output_folder("--out", str(tmp_path / "f" / "sub"))


# ------------------------------------------------------------------ report --validation
@pytest.mark.parametrize("path, word", [("/dev/zero", "is not a regular file"), ("{tmp}", "is not a regular file")])
def test_validation_refuses_what_is_not_a_regular_file(capsys, tmp_path, path, word):
    out = tmp_path / "r"
    err = _refused(capsys, "report", *IMPULSE, "--out", str(out), "--validation", path.format(tmp=tmp_path))
    assert word in err and "--validation" in err
    assert not out.exists()


def test_validation_refuses_a_huge_file_without_reading_it(capsys, tmp_path):
    big = tmp_path / "big.json"
    with open(big, "wb") as fh:
        fh.truncate(VALIDATION_MAX_BYTES + 1)  # sparse: no disk used
    err = _refused(capsys, "report", *IMPULSE, "--out", str(tmp_path / "r"), "--validation", str(big))
    assert "is too large" in err and str(VALIDATION_MAX_BYTES) in err


@pytest.mark.parametrize("content, word", [(b"\xff\xfe", "not JSON"), (b"[1]", "not a validation summary")])
def test_validation_bad_content(capsys, tmp_path, content, word):
    f = tmp_path / "v.json"
    f.write_bytes(content)
    assert word in _refused(capsys, "report", *IMPULSE, "--out", str(tmp_path / "r"), "--validation", str(f))
    f.write_text(json.dumps({"soundness_violations": 0}))  # the summary itself is read (the report is not run here)
    from dfa.cli.report import _read_validation

    assert _read_validation(str(f)) == {"soundness_violations": 0}
