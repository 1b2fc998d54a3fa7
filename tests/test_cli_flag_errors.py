"""The command line names the flag in front of a model's message (issue 17, point 5).

Model parsers speak of the model ("friction law 'x' is not one of ..."); the command line adds
the flag the value came from, once, on one line, with exit code 2.
"""

from __future__ import annotations

import pytest

from stickslip.cli.console import BadInput, flag_error, parse_dva_option, parse_friction_option
from tests.cli_helpers import run_cli


def test_flag_error_prefixes_the_flag_and_value_once() -> None:
    model = ValueError("friction law 'x' is not one of coulomb, linear, table, stribeck")
    assert str(flag_error("--friction", "x", model)) == (
        "--friction 'x': friction law 'x' is not one of coulomb, linear, table, stribeck")
    already = ValueError("--friction 'x' is not one of: coulomb | linear:DELTA")
    assert str(flag_error("--friction", "x", already)) == str(already)  # never named twice


@pytest.mark.parametrize(("parse", "text", "flag"), [
    (parse_friction_option, "bogus", "--friction"),
    (parse_friction_option, "linear:abc", "--friction"),
    (parse_friction_option, "stribeck:n=2", "--friction"),
    (parse_dva_option, "1,2", "--dva"),
    (parse_dva_option, "a,b,c", "--dva"),
])
def test_model_parse_errors_name_the_flag(parse, text: str, flag: str) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(BadInput) as raised:
        parse(text)
    message = str(raised.value)
    assert message.startswith(f"{flag} {text!r}") and message.count(flag) == 1
    assert "\n" not in message


def test_k_scale_without_a_foundation_names_k_scale() -> None:
    with pytest.raises(BadInput, match=r"^--k-scale '2\.0': k_scale"):
        parse_dva_option("none", 2.0)


@pytest.mark.parametrize(("args", "flag"), [
    (["simulate", "--lam", "3", "--zeta", "0.1", "--friction", "bogus"], "--friction"),
    (["cycles", "--lam", "3", "--zeta", "0.1", "--dva", "1,2"], "--dva"),
    (["boundary", "--zeta", "0.1", "--friction", "linear:x"], "--friction"),
    (["map", "--lam", "1,2", "--zeta", "0.1", "--dva", "x,y,z", "--out", "never.nc"], "--dva"),
])
def test_commands_print_one_line_with_the_flag(args: list[str], flag: str, tmp_path, capsys,  # type: ignore[no-untyped-def]
                                               monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    code, out, err = run_cli(args, capsys)
    assert code == 2 and out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"stickslip: error: {flag} ")
    assert list(tmp_path.iterdir()) == []  # nothing written
