"""The one TOML reader (machine files, uploads): inputs that cost unbounded work or crash later.

Source: an independent audit of the web app. ``tomllib`` takes memory growing with the square
of a dotted key's length (a 200 kB line ``a.a.a...a = 1`` reached 22 GB and was killed; 50 kB
took 2.8 GB), and a 4,000-digit integer reached the design as ``OverflowError: int too large
to convert to float``. Both are one line naming the file now, and the dotted key is refused
before the parser sees it.
"""

from __future__ import annotations

import tomllib

import pytest

from stickslip.io import toml_file
from stickslip.io.toml_file import MAX_KEY_PARTS, read_toml_file


def test_a_dotted_key_bomb_is_refused_before_parsing(monkeypatch: pytest.MonkeyPatch) -> None:
    def no_parse(text: str) -> dict:  # type: ignore[type-arg]
        raise AssertionError("tomllib was called on the bomb")

    monkeypatch.setattr(toml_file.tomllib, "loads", no_parse)
    for text in ("a" + ".a" * 100_000 + " = 1\n", "[" + ".".join(["t"] * 50_000) + "]\nx = 1\n"):
        message = rf"upload m.toml: line \d+ has a key of \d+ dotted parts, more than {MAX_KEY_PARTS}"
        with pytest.raises(ValueError, match=message):
            read_toml_file("m.toml", "upload m.toml", content=text.encode())


def test_dots_inside_quotes_and_ordinary_nesting_are_read() -> None:
    text = '[structure.chain]\n"x' + "." * 100 + 'y" = 1\nname = "' + "." * 100 + '"\n'
    assert read_toml_file("m.toml", "m", content=text.encode()) == tomllib.loads(text)
    deep = ".".join(["t"] * (MAX_KEY_PARTS - 1))
    assert read_toml_file("m.toml", "m", content=f"{deep} = 1\n".encode())


def test_an_integer_beyond_a_float_names_its_key() -> None:
    text = "[system]\nload = " + "9" * 4000 + "\nm = 2\n"
    with pytest.raises(ValueError, match=r"^m: system.load is an integer of 4000 digits, beyond"):
        read_toml_file("m.toml", "m", content=text.encode())
    # one that fits a float is read as it is
    assert read_toml_file("m.toml", "m", content=b"x = 100000000000000000000000\n")["x"] == 10**23
