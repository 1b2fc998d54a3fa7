"""The docs show what their commands print (issue 32, point 6).

Every ``$ stickslip ...`` line of a fenced code block in ``docs/*.md`` that is followed by an
output sample is run as a user would (in a fresh folder, from the repository root for the
files it names) and its output compared with the sample: the sample's lines must come out, in
order and next to each other, after two normalisations that only a clock can change -- run
times (``in 1.52 s``) and rates (``1,579 cells/s``) -- and with ``...`` in a sample standing
for any text (a sample may leave out the end of a long line). ``| tail -N`` after a command
keeps its last ``N`` lines, as the shell would. The Python blocks of the user guides that
build their result from scratch (``docs/absorber.md``) run too.

The sample commands whose runs are heavy (a Dask cluster, thousands of disturbed runs) are
marked slow; the others take a few seconds each on this project's machine.
"""

from __future__ import annotations

import re
import shlex
from dataclasses import dataclass
from pathlib import Path

import pytest

from tests.cli_helpers import run_cli

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"

#: Substrings of the sample commands that run for more than a few seconds (slow marker): the
#: Dask basin, the basin maps, 40,000 disturbed starts, the Stribeck cycle search, the maps of
#: hundreds to thousands of cells, the brake-pad eigenvalue analysis, time histories, cycles
#: and boundary (10-40 s each on this project's loaded 2-core machine; the pad's 8 cycle starts
#: 2.4 min), the contact machines' maps (a minute or more).
HEAVY = ("--backend dask", "basin-map", "--samples 40000", "stribeck:vs=0.3333", "map --lam",
         "stability --config", "simulate --config examples/brake_pad",
         "cycles --config examples/brake_pad", "map --config examples/brake_pad",
         "boundary --config examples/brake_pad", "map --config examples/jenkins_boundary")


@dataclass(frozen=True)
class Sample:
    """A documented command and the output shown under it."""

    page: str
    line: int
    command: str
    output: tuple[str, ...]

    @property
    def id(self) -> str:
        return f"{self.page}:{self.line}"


def samples() -> list[Sample]:
    """Every ``$ stickslip`` command of a fenced block in docs/*.md that has an output sample."""
    found = []
    for page in sorted(DOCS.glob("*.md")):
        text = page.read_text(encoding="utf-8")
        for block in re.finditer(r"^```[a-z]*\n(.*?)^```", text, flags=re.S | re.M):
            first_line = text[: block.start()].count("\n") + 2
            lines = block.group(1).splitlines()
            i = 0
            while i < len(lines):  # bounded: every pass consumes at least one line
                if not lines[i].startswith("$ stickslip "):
                    i += 1
                    continue
                start = i
                command = lines[i][2:]
                while command.endswith("\\") and i + 1 < len(lines):
                    i += 1
                    command = command[:-1] + " " + lines[i].strip()
                i += 1
                output = []
                while i < len(lines) and not lines[i].startswith("$ "):
                    output.append(lines[i])
                    i += 1
                while output and not output[-1].strip():
                    output.pop()
                if output:
                    found.append(Sample(page.name, first_line + start, command, tuple(output)))
    return found


SAMPLES = samples()

_TIME = re.compile(r"\bin \d[\d,]*(?:\.\d+)? s\b")
_RATE = re.compile(r"\b\d[\d,]*(?:\.\d+)? (cells|samples|runs)/s\b")


def normalised(line: str) -> str:
    """``line`` with run times and rates replaced by placeholders, trailing blanks removed."""
    return _RATE.sub(r"<rate> \1/s", _TIME.sub("in <time> s", line)).rstrip()


def _matches(sample: str, line: str) -> bool:
    parts = [re.escape(part) for part in normalised(sample).split("...")]
    return re.fullmatch(".*".join(parts), normalised(line)) is not None


def _run(command: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> list[str]:
    pipe = None
    if "|" in command:
        command, pipe = (part.strip() for part in command.split("|", 1))
    words = shlex.split(command)
    assert words[0] == "stickslip"
    # files the docs name from the repository root (examples/...) are found there
    args = [str(ROOT / w) if (ROOT / w).is_file() and "/" in w else w for w in words[1:]]
    code, out, err = run_cli(args, capsys)
    assert code == 0, f"`{command}` failed: {err}"
    lines = out.rstrip("\n").splitlines()
    if pipe is not None:
        match = re.fullmatch(r"tail -(\d+)", pipe)
        assert match, f"unknown pipe {pipe!r} in the docs"
        lines = lines[-int(match.group(1)):]
    return lines


def test_the_docs_show_commands_with_samples() -> None:
    # the extractor finds the samples this test is for (a format change must not empty it)
    pages = {s.page for s in SAMPLES}
    expected = {"maps.md", "friction.md", "disturbances.md", "continuation.md", "identification.md"}
    assert expected <= pages, pages
    assert len(SAMPLES) >= 10


@pytest.mark.parametrize("sample", [
    pytest.param(s, id=s.id, marks=[pytest.mark.slow] if any(h in s.command for h in HEAVY) else [])
    for s in SAMPLES
])
def test_a_documented_command_prints_its_sample(sample: Sample, tmp_path: Path,
                                                capsys: pytest.CaptureFixture[str],
                                                monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    lines = _run(sample.command, tmp_path, capsys)
    n = len(sample.output)
    starts = [i for i in range(len(lines) - n + 1)
              if all(_matches(s, line) for s, line in zip(sample.output, lines[i:i + n], strict=True))]
    assert starts, (f"{sample.id}: `{sample.command}` printed\n" + "\n".join(lines)
                    + "\n\nbut the page shows\n" + "\n".join(sample.output))


def _python_blocks(page: str) -> list[str]:
    text = (DOCS / page).read_text(encoding="utf-8")
    return [m.group(1) for m in re.finditer(r"^```python\n(.*?)^```", text, flags=re.S | re.M)
            if not m.group(1).lstrip().startswith(">>>")]


@pytest.mark.slow  # tuning_curve tunes five foundations: about 100 s on the loaded machine
def test_the_absorber_page_python_runs_and_gives_its_numbers(tmp_path: Path,
                                                            monkeypatch: pytest.MonkeyPatch) -> None:
    # docs/absorber.md imported stickslip.analysis.absorber, which does not exist
    monkeypatch.chdir(tmp_path)
    (block,) = _python_blocks("absorber.md")
    namespace: dict[str, object] = {}
    exec(compile(block, "docs/absorber.md", "exec"), namespace)  # the page's own code
    # the numbers its comments state (source: the page, and `stickslip tune --zeta 0.1` above it)
    best = namespace["best"]
    assert f"{best.foundation.mass_ratio:.6g}" == "2.81232"  # type: ignore[attr-defined]
    assert f"{best.foundation.stiffness_ratio:.6g}" == "1.09077"  # type: ignore[attr-defined]
    assert f"{best.foundation.damping_ratio:.6g}" == "1.49861"  # type: ignore[attr-defined]
    damping = namespace["equivalent_damping"](namespace["elastic_foundation"](0.1, best.foundation))  # type: ignore[operator, attr-defined]
    assert f"{damping:.6g}" == "0.257954"
    assert (tmp_path / "fig4.png").stat().st_size > 10_000


def test_the_maps_page_dataset_is_what_map_writes(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                                  monkeypatch: pytest.MonkeyPatch) -> None:
    # docs/maps.md's session on fig8b.nc (its flag meanings lacked slip-oscillation), run on
    # a small map of the same kind (the optimal foundation: the same variables)
    import doctest

    monkeypatch.chdir(tmp_path)
    code, _, err = run_cli(["map", "--lam", "1:5:3", "--zeta", "0.05:0.2:3", "--dva", "optimal",
                            "--out", "fig8b.nc"], capsys)
    assert code == 0, err
    text = (DOCS / "maps.md").read_text(encoding="utf-8")
    (session,) = [m.group(1) for m in re.finditer(r"^```python\n(.*?)^```", text, flags=re.S | re.M)
                  if m.group(1).lstrip().startswith(">>>")]
    test = doctest.DocTestParser().get_doctest(session, {}, "docs/maps.md", "docs/maps.md", 0)
    runner = doctest.DocTestRunner(optionflags=doctest.NORMALIZE_WHITESPACE)
    runner.run(test)
    result = runner.summarize(verbose=False)
    assert result.attempted >= 3 and result.failed == 0, capsys.readouterr().out
