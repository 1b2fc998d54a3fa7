"""An uploaded machine file is sandboxed (issue 31, security): the reader and the app's messages.

What is checked here without a browser (``tests/test_app_browser.py`` drives the same cases in
Chromium):

* an uploaded machine file may name only the files uploaded with it, by base name; any other
  value (absolute, ``..``, a subfolder, a name not uploaded, a Windows path) of any file-valued
  key (``[structure]`` mass, stiffness, damping and ``[friction] table``) is refused in one
  line, the same whether or not such a file exists on the server, and nothing on disk is
  opened or even looked at (every file-system call used by the readers is made to fail);
* a refusal never shows a file's content ("hunter2" below) or a server path (the pickle
  refusal showed the temporary folder);
* the limits (MB of files, DOF) are enforced with a message naming them;
* the command line keeps reading files relative to the machine file;
* the app's messages are shown literally (Markdown escaped, checked by rendering with
  markdown-it, the CommonMark parser) and stripped of server paths.
"""

from __future__ import annotations

import builtins
import contextlib
import io
import os
import re
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import scipy.io
import scipy.sparse

from stickslip.app.machine_page import machine_from_files
from stickslip.app.messages import WORD_JOINER, literal_markdown, sanitised
from stickslip.io.machine_file import (
    UPLOAD_MAX_DOF,
    UPLOAD_MAX_MB,
    UPLOAD_MAX_TOML_MB,
    machine_from_file,
    read_machine_file,
    uploaded_file,
)

SLIDEWAY = Path(__file__).resolve().parents[1] / "examples" / "slideway"
SECRET = "hunter2"


def _slideway() -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in SLIDEWAY.iterdir() if p.suffix in (".toml", ".mtx")}


def _with(files: dict[str, bytes], old: str, new: str) -> dict[str, bytes]:
    """The slideway's uploads with ``old`` replaced by ``new`` in its machine.toml."""
    text = files["machine.toml"].decode()
    assert old in text
    return {**files, "machine.toml": text.replace(old, new).encode()}


def _refusal(files: dict[str, bytes]) -> str:
    """The one-line refusal of ``files``, read without looking at the disk."""
    with pytest.raises(ValueError) as info, _disk_untouched():
        machine_from_files(files)
    message = str(info.value)
    assert len(message.splitlines()) == 1, message
    return message


@pytest.fixture
def secret_file(tmp_path: Path) -> Path:
    """A file on the "server" that an upload must not reach."""
    path = tmp_path / "secret.csv"
    path.write_text(f"1,0\n0,{SECRET}\n")
    return path


@pytest.fixture(autouse=True, scope="module")
def _warm() -> None:
    """Load what the readers load lazily from the installation (the unit registry, modules)."""
    machine_from_files(_slideway())


@contextlib.contextmanager
def _disk_untouched() -> Iterator[None]:
    """Inside: every file-system call the readers could make raises (caught by the caller)."""
    def refuse(*args: Any, **kwargs: Any) -> Any:
        raise _DiskTouched(f"the disk was looked at: {args!r}")

    with pytest.MonkeyPatch.context() as patch:
        for name in ("is_file", "exists", "open", "read_bytes", "read_text", "stat", "resolve"):
            patch.setattr(Path, name, refuse)
        patch.setattr(builtins, "open", refuse)
        patch.setattr(os, "stat", refuse)
        yield


class _DiskTouched(BaseException):
    """Raised when a reader looks at the disk (a BaseException: no ``except`` hides it)."""


FILE_KEYS = [
    ('stiffness = "K.mtx"', 'stiffness = "{}"'),
    ('mass = "M.mtx"', 'mass = "{}"'),
    ('damping = "C.mtx"', 'damping = "{}"'),
    ('attach_dof = 2\n', 'attach_dof = 2\n\n[friction]\nlaw = "table"\ntable = "{}"\n'),
]


@pytest.mark.parametrize("old,new", FILE_KEYS, ids=["stiffness", "mass", "damping", "friction"])
def test_a_path_on_the_server_is_refused_the_same_whether_it_exists_or_not(
        old: str, new: str, secret_file: Path) -> None:
    files = _slideway()
    missing = str(secret_file.with_name("absent.csv"))
    found = _refusal(_with(files, old, new.format(secret_file)))
    absent = _refusal(_with(files, old, new.format(missing)))
    assert SECRET not in found and "does not exist" not in absent
    assert found.replace(str(secret_file), "X") == absent.replace(missing, "X")
    assert "not one of the files uploaded with it" in found


@pytest.mark.parametrize("spec", [
    "../../../../etc/passwd", "..", ".", "", "sub/K.mtx", "./K.mtx", "K.mtx/", "Q.mtx",
    "C:\\K.mtx", "..\\K.mtx", "\\\\server\\share\\K.mtx", "/K.mtx",
])
def test_anything_but_an_uploaded_base_name_is_refused(spec: str) -> None:
    message = _refusal(_with(_slideway(), 'stiffness = "K.mtx"',
                             'stiffness = "' + spec.replace("\\", "\\\\") + '"'))
    assert "not one of the files uploaded with it" in message
    assert "uploaded: C.mtx, K.mtx, M.mtx, machine.toml" in message


def test_a_friction_table_uploaded_with_it_is_read_from_memory() -> None:
    files = _with(_slideway(), "attach_dof = 2\n",
                  'attach_dof = 2\n\n[friction]\nlaw = "table"\ntable = "mu.csv"\n')
    files["mu.csv"] = b"v,mu\n0,0.15\n0.001,0.12\n0.01,0.10\n"
    with _disk_untouched():
        machine, _, _ = machine_from_files(files)
    assert machine.friction.law == "table"
    assert machine.friction.table_v == (0.0, 0.001, 0.01)


def test_the_uploaded_slideway_is_the_one_the_command_line_reads_from_disk() -> None:
    operating = {"mu_s": 0.15, "mu_k": 0.1, "load": 2600.0, "speed": 5e-4}
    from_disk, _ = machine_from_file(read_machine_file(SLIDEWAY / "machine.toml"), operating)
    uploaded, _ = machine_from_file(read_machine_file(Path("machine.toml"), files=_slideway()),
                                    operating)
    np.testing.assert_array_equal(uploaded.stiffness, from_disk.stiffness)
    np.testing.assert_array_equal(uploaded.damping, from_disk.damping)


def test_the_command_line_still_reads_files_relative_to_the_machine_file(tmp_path: Path) -> None:
    folder = tmp_path / "sub"
    folder.mkdir()
    (folder / "K.csv").write_text("3e4,-1e4\n-1e4,2e4\n")
    path = tmp_path / "machine.toml"
    path.write_text('mu_s = 0.5\nmu_k = 0.3\nload = "100 N"\nspeed = "1 cm/s"\n[structure]\n'
                    'mass = [[2.0, 0.0], [0.0, 1.0]]\nstiffness = "sub/K.csv"\ncontact_dof = 0\n')
    machine, _ = machine_from_file(read_machine_file(path), {"mu_s": 0.5, "mu_k": 0.3,
                                                             "load": 100.0, "speed": 0.01})
    np.testing.assert_array_equal(machine.stiffness, [[3e4, -1e4], [-1e4, 2e4]])


def _csv_machine(stiffness: bytes, name: str = "K.csv") -> dict[str, bytes]:
    toml = ('mu_s = 0.5\nmu_k = 0.3\nload = "100 N"\nspeed = "1 cm/s"\n[structure]\n'
            f'mass = [[2.0, 0.0], [0.0, 1.0]]\nstiffness = "{name}"\ncontact_dof = 0\n')
    return {"m.toml": toml.encode(), name: stiffness}


def test_a_bad_entry_is_named_by_row_and_column_not_quoted() -> None:
    message = _refusal(_csv_machine(f"3e4,-1e4\n-1e4,{SECRET}\n".encode()))
    assert SECRET not in message
    assert "'K.csv' cannot be read: row 2, column 2 is not a number" in message


def test_a_bad_friction_table_line_is_not_quoted() -> None:
    files = _with(_slideway(), "attach_dof = 2\n",
                  'attach_dof = 2\n\n[friction]\nlaw = "table"\ntable = "mu.csv"\n')
    files["mu.csv"] = f"v,mu\n0,0.15\n0.001,{SECRET}\n".encode()
    message = _refusal(files)
    assert SECRET not in message and "'mu.csv', line 3: not two numbers" in message


def _npy(array: np.ndarray, allow_pickle: bool = False) -> bytes:
    buffer = io.BytesIO()
    np.save(buffer, array, allow_pickle=allow_pickle)
    return buffer.getvalue()


def test_pickled_data_is_refused_without_a_server_path() -> None:
    message = _refusal(_csv_machine(_npy(np.array([SECRET, None], dtype=object), True), "K.npy"))
    assert "'K.npy' cannot be read: it holds Python objects (pickled data)" in message
    assert "/" not in message.split("'K.npy'", 1)[1] and SECRET not in message


@pytest.mark.parametrize("name,content", [
    ("K.npy", f"\x93NUMPY{SECRET}".encode()),
    ("K.npy", SECRET.encode()),
    ("K.mtx", f"%%MatrixMarket matrix coordinate real general\n2 2 1\n1 1 {SECRET}\n".encode()),
    ("K.mtx", f"%%MatrixMarket matrix {SECRET}\n".encode()),
    ("K.csv", b"\xff\xfe" + SECRET.encode("utf-16-le")),
])
def test_a_garbled_upload_is_refused_without_its_content(name: str, content: bytes) -> None:
    message = _refusal(_csv_machine(content, name))
    assert SECRET not in message and f"{name!r} cannot be read" in message


def test_the_largest_model_is_a_stated_limit() -> None:
    n = UPLOAD_MAX_DOF + 1
    buffer = io.BytesIO()
    scipy.io.mmwrite(buffer, scipy.sparse.identity(n, format="coo"), symmetry="symmetric")
    files = {"m.toml": b'mu_s = 0.5\nmu_k = 0.3\nload = "100 N"\nspeed = "1 cm/s"\n[structure]\n'
                       b'mass = "I.mtx"\nstiffness = "I.mtx"\ncontact_dof = 0\n',
             "I.mtx": buffer.getvalue()}
    message = _refusal(files)
    assert f"a {n}-DOF model, beyond the {UPLOAD_MAX_DOF} DOF accepted here" in message


def test_the_largest_upload_is_a_stated_limit() -> None:
    files = _slideway()
    files["padding.csv"] = b"0" * (UPLOAD_MAX_MB * 1024**2 + 1 - sum(map(len, files.values())))
    message = _refusal(files)
    assert f"beyond the {UPLOAD_MAX_MB} MB accepted" in message


@pytest.mark.parametrize(("case", "needle"), [
    # hostile uploads of the audit of 2026-11-27, each refused before its bulk is parsed
    # (a 50 MB one-value-per-line CSV took 44 s and 2.8 GB, a 13 M-row friction table 45 s)
    ("rows", "'K.csv' cannot be read: it has 2000000 line breaks and 1 values in its first row"),
    # (the first row's count is checked against the upload's DOF limit first)
    ("columns", "'K.csv' cannot be read: it is 2000001x2000001, a 2000001-DOF model, beyond the "
                f"{UPLOAD_MAX_DOF} DOF accepted here"),
    ("table", "friction table 'mu.csv' has 2000001 lines, far more than the 1999 points"),
    ("toml", f"the machine file holds 2.9 MB, beyond the {UPLOAD_MAX_TOML_MB} MB accepted"),
    ("name", "[structure]: name is 201 characters long; at most 200"),
    ("nested", "its arrays or tables nest too deeply"),
])
def test_a_hostile_upload_is_refused_before_its_bulk_is_read(case: str, needle: str) -> None:
    if case == "rows":
        files = _csv_machine(b"1\n" * 2_000_000)
    elif case == "columns":
        files = _csv_machine(b"1" + b",1" * 2_000_000 + b"\n")
    elif case == "table":
        files = _with(_slideway(), "attach_dof = 2\n",
                      'attach_dof = 2\n\n[friction]\nlaw = "table"\ntable = "mu.csv"\n')
        files["mu.csv"] = b"v,mu\n" + b"0.1,0.2\n" * 2_000_000
    elif case == "toml":
        files = _csv_machine(b"3e4,-1e4\n-1e4,2e4\n")
        files["m.toml"] += b"# " + b"x" * int(2.9 * 1024**2 - len(files["m.toml"]) - 3) + b"\n"
    elif case == "name":
        files = _with(_slideway(), 'name = "slideway"', f'name = "{"n" * 201}"')
    else:
        files = _csv_machine(b"3e4,-1e4\n-1e4,2e4\n")
        files["m.toml"] += b"deep = " + b"[" * 50_000 + b"]" * 50_000 + b"\n"
    message = _refusal(files)  # each message names the bound checked before the bulk is read
    assert needle in message, message


def test_uploaded_file_takes_only_plain_names() -> None:
    files = {"K.mtx": b"k"}
    assert uploaded_file("K.mtx", files, "key") == b"k"
    for spec in ("./K.mtx", "/K.mtx", 3, None, ["K.mtx"]):
        with pytest.raises(ValueError, match="not one of the files uploaded"):
            uploaded_file(spec, files, "key")
    with pytest.raises(ValueError, match="not one of the files uploaded"):
        uploaded_file("a/K.mtx", {"a/K.mtx": b"k"}, "key")  # a crafted upload name


# The app's second line of defence: whatever reaches the page is shown literally and pathless.


@pytest.mark.parametrize("message,kept", [
    ("file '/tmp/stickslip-machine-x1/K.csv' cannot be read", "file '<path>' cannot be read"),
    ("'/etc/shadow' has suffix ''", "'<path>' has suffix ''"),
    ("'C:\\Users\\me\\K.csv' is bad", "'<path>' is bad"),
    ("damping_unit = 'N*s/m', speed in m/s, shapes in 1/sqrt(kg), rate 1/s",
     "damping_unit = 'N*s/m', speed in m/s, shapes in 1/sqrt(kg), rate 1/s"),
    ("stiffness = '[click me](http://example.com)'", "stiffness = '[click me](http://example.com)'"),
])
def test_server_paths_are_removed_and_units_kept(message: str, kept: str) -> None:
    assert sanitised(message) == kept


@pytest.mark.parametrize("text", [
    "[click me](http://example.com)", "__import__('os').system('x')", "*a* _b_ `c` # d",
    "<b>bold</b> <script>x</script> &amp;", "$x^2$ ~~s~~ | a | b |", "1. one\n- two",
    "http://example.com www.example.com me@example.com", "a\\b",
])
def test_messages_render_literally_in_markdown(text: str) -> None:
    import html

    markdown_it = pytest.importorskip("markdown_it", reason="markdown-it-py renders CommonMark")
    parser = markdown_it.MarkdownIt("commonmark").enable(["table", "strikethrough", "linkify"])
    rendered = parser.render(literal_markdown(" ".join(text.split())))
    body = re.fullmatch(r"<p>(.*)</p>\n", rendered, flags=re.S)
    assert body is not None, rendered
    assert "<a " not in body.group(1)
    assert html.unescape(body.group(1)).replace(WORD_JOINER, "") == " ".join(text.split())


def test_a_message_echoing_a_huge_upload_is_shortened() -> None:
    """An upload with 100,000 unknown tables was refused in a line of 800 kB (an independent
    audit): the message keeps its start and its end, where the allowed keys are."""
    from stickslip.app.messages import MAX_MESSAGE, sanitised

    names = ", ".join(f"t{i}" for i in range(100_000))
    text = sanitised(f"upload m.toml: unknown keys {names} (allowed: structure, system)")
    assert len(text) <= MAX_MESSAGE + 40
    assert text.startswith("upload m.toml: unknown keys t0, t1,")
    assert text.endswith("t99999 (allowed: structure, system)") and "characters ...]" in text
    assert sanitised("a short one") == "a short one"


def test_a_dotted_key_bomb_upload_is_one_line_and_costs_nothing() -> None:
    """A 200 kB dotted key took the server to 22 GB (an independent audit): refused unparsed."""
    from stickslip.app.machine_page import uploaded_machine_file

    bomb = ("a" + ".a" * 100_000 + " = 1\n").encode()
    with pytest.raises(ValueError, match="dotted parts"):
        uploaded_machine_file({"machine.toml": bomb})
