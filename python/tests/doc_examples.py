"""The console examples of README.md and docs/: found, run, and their printed figures compared.

Every fenced block of a shell language (console, sh, bash, shell) or of no language carries
a marker on the line before its fence, an HTML comment that neither GitHub nor the docs site
shows:

    <!-- example: run -->                      run by `make test`
    <!-- example: run slow -->                 run by `make test-docs` (minutes)
    <!-- example: run tolerance=2% vary="steps/s|ms" -->
    <!-- example: run float-libm -->
    <!-- example: not-run: why it cannot run in a test -->

Blocks in other languages (python, yaml, cpp, text) need no marker: the Python examples run
in test_docs.py, the others are not commands.

In a block, a line that starts with `$ ` is a command (continued on the next lines while a
line ends with a backslash); the lines after it, up to the next command, are what it prints.
A `#` comment after a command is the reader's, not the shell's. Commands run in order, with
bash, in a scratch directory that holds links to the repository's configs/, models/, tests/,
examples/ and to the build directory as build/, with the build directory first on PATH (so
`upkie-rl` is build/upkie-rl). A command that ends with `&` runs in the background until the
block ends.

What a command prints is compared with the text line by line: every printed line of the text
must appear in the command's standard output or standard error, in order within each stream
(`...` lines, and lines the text leaves out, are not compared; `...` inside a line stands
for any text). Two lines match when their words are the same and each figure is within the block's tolerance of the text's: by
default half a unit of the last digit the text shows (the text's rounding) or 0.1 % of it,
whichever is larger; `tolerance=P%` widens the relative part to P %. The figures inside
the text that the block's `vary` regular expression matches (timings, dates) are not
compared, only the words around them.

`float-libm` marks a block whose figures depend on the last bit of the C library's float
functions: the `lqr` controller of a velocity task is designed by fitting closed-loop
episodes, and the pitch it feeds back comes from `atan2f`, which glibc 2.41 rounds correctly
and glibc 2.36 (Debian 12, where the docs' figures were measured) rounds one unit off for
about half the inputs; one unit in the last place grows into other gains (18.40 instead of
12.45 on Debian 13). Such a block's figures are compared where `atan2f` rounds as glibc
2.36's does (a probe input below tells); elsewhere its commands must still succeed and print
the same words, with any figures.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import dataclasses
import functools
import os
import re
import shlex
import shutil
import signal
import struct
import subprocess
import tempfile
import time
from pathlib import Path

SHELL_LANGUAGES = {"console", "sh", "bash", "shell", ""}
MARKER = re.compile(r"^<!-- example: (?P<body>.*?) -->$")
FENCE = re.compile(r"^(?P<indent>\s*)```(?P<language>[\w-]*)\s*$")
# A figure: thousands separated by commas (1,001,640) or not, a decimal part, an exponent.
NUMBER = re.compile(r"[-+]?(?:\d{1,3}(?:,\d{3})+(?:\.\d+)?|\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
DEFAULT_RELATIVE_TOLERANCE = 1e-3
REPOSITORY_LINKS = ("configs", "models", "tests", "examples")
# atan2f(y, x) at the input of the C++ twin (atan2f_rounds_as_recorded in
# tests/apps/velocity_command_test.cpp): glibc 2.36 returns -0x1.0c4eb8p-3, one unit from
# the correctly rounded -0x1.0c4ebap-3 of glibc 2.41 (docs measured with the former).
ATAN2F_PROBE = (float.fromhex("-0x1.e5c998p-4"), float.fromhex("0x1.ccd96p-1"),
                float.fromhex("-0x1.0c4eb8p-3"))
# A background command (a spine) gets this long to be ready before the next command runs.
BACKGROUND_START_SECONDS = 2.0


@dataclasses.dataclass
class Command:
    text: str                 # as the shell runs it: continuations joined, comment dropped
    expected: list[str]       # the lines the text shows it printing


@dataclasses.dataclass
class Example:
    path: Path
    line: int                 # of the opening fence, 1-based
    language: str
    body: list[str]
    marker: str | None        # the marker's body, None when the block has none
    run: bool = False
    slow: bool = False
    reason: str = ""
    relative_tolerance: float = DEFAULT_RELATIVE_TOLERANCE
    vary: re.Pattern | None = None
    float_libm: bool = False  # figures depend on atan2f's rounding (module docstring)

    @property
    def name(self) -> str:
        return f"{self.path.name}:{self.line}"


def parse_marker(example: Example) -> None:
    """Fills run/slow/reason/tolerance/vary from the marker; raises ValueError when bad."""
    body = example.marker or ""
    if body.startswith("not-run:"):
        example.reason = body[len("not-run:"):].strip()
        if not example.reason:
            raise ValueError(f"{example.name}: not-run needs a reason")
        return
    words = shlex.split(body)
    if not words or words[0] != "run":
        raise ValueError(f"{example.name}: marker {body!r} is neither run nor not-run: REASON")
    example.run = True
    for word in words[1:]:
        if word == "slow":
            example.slow = True
        elif word.startswith("tolerance=") and word.endswith("%"):
            example.relative_tolerance = float(word[len("tolerance="):-1]) / 100.0
        elif word.startswith("vary="):
            example.vary = re.compile(word[len("vary="):])
        elif word == "float-libm":
            example.float_libm = True
        else:
            raise ValueError(f"{example.name}: unknown marker word {word!r}")


def find_examples(path: Path) -> list[Example]:
    """Every fenced block of a shell language, or of none, in a Markdown file."""
    lines = path.read_text().split("\n")
    examples = []
    index = 0
    while index < len(lines):
        fence = FENCE.match(lines[index])
        if not fence:
            index += 1
            continue
        end = index + 1
        while not lines[end].strip().startswith("```"):
            end += 1
        language = fence.group("language")
        if language in SHELL_LANGUAGES:
            previous = lines[index - 1].strip() if index > 0 else ""
            marker = MARKER.match(previous)
            indent = len(fence.group("indent"))
            example = Example(path, index + 1, language,
                              [line[indent:] for line in lines[index + 1:end]],
                              marker.group("body") if marker else None)
            if example.marker is not None:
                parse_marker(example)
            examples.append(example)
        index = end + 1
    return examples


def strip_comment(command: str) -> str:
    """Drops a reader's `# ...` after a command (outside quotes)."""
    quote = None
    for position, character in enumerate(command):
        if quote:
            if character == quote:
                quote = None
        elif character in "'\"":
            quote = character
        elif character == "#" and (position == 0 or command[position - 1] in " \t"):
            return command[:position].rstrip()
    return command.rstrip()


def commands_of(example: Example) -> list[Command]:
    commands: list[Command] = []
    lines = iter(example.body)
    for line in lines:
        if line.startswith("$ "):
            parts = [line[2:]]
            while parts[-1].rstrip().endswith("\\"):
                parts[-1] = parts[-1].rstrip()[:-1]
                parts.append(next(lines).strip())
            commands.append(Command(strip_comment(" ".join(part.strip() for part in parts)),
                                    []))
        elif commands and line.strip() and line.strip() != "...":
            commands[-1].expected.append(line)
    return commands


def figure(text: str) -> float:
    return float(text.replace(",", ""))


def figure_tolerance(text: str, relative: float) -> float:
    """Half a unit of the figure's last shown digit, or `relative` of it."""
    text = text.replace(",", "")
    mantissa = re.split(r"[eE]", text)[0]
    exponent = int(re.split(r"[eE]", text)[1]) if re.search(r"[eE]", text) else 0
    decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
    rounding = 0.5 * 10.0 ** (exponent - decimals)
    return max(rounding, relative * abs(figure(text)))


def line_pattern(expected: str) -> re.Pattern:
    """The expected line as a regular expression: its words literal, any run of white space
    as white space, each figure a group, and `...` inside a line as any text."""
    pattern = []
    for token in re.split(rf"(\.\.\.|\s+|{NUMBER.pattern})", expected.strip()):
        if not token:
            continue
        if token == "...":
            pattern.append(".*?")
        elif token.isspace():
            pattern.append(r"\s+")
        elif NUMBER.fullmatch(token):
            pattern.append(f"({NUMBER.pattern})")
        else:
            pattern.append(re.escape(token))
    return re.compile("".join(pattern))


def line_mismatch(expected: str, actual: str, relative: float,
                  vary: re.Pattern | None) -> str | None:
    """None when the lines match, else why not."""
    expected = expected.strip()
    match = line_pattern(expected).fullmatch(actual.strip())
    if match is None:
        return "other words"
    varying = [span.span() for span in vary.finditer(expected)] if vary else []
    for shown, printed in zip(NUMBER.finditer(expected), match.groups()):
        if any(start <= shown.start() and shown.end() <= end for start, end in varying):
            continue
        tolerance = figure_tolerance(shown.group(), relative)
        if abs(figure(shown.group()) - figure(printed)) > tolerance:
            return f"figure {printed} is not {shown.group()} (tolerance {tolerance:g})"
    return None


def output_mismatches(expected: list[str], stdout: str, stderr: str, relative: float,
                      vary: re.Pattern | None) -> list[str]:
    """The text's lines that the output lacks, with the nearest printed line's difference."""
    streams = [stdout.splitlines(), stderr.splitlines()]
    cursors = [0, 0]
    problems = []
    for line in expected:
        found = False
        nearest = None
        for stream_index, stream in enumerate(streams):
            for position in range(cursors[stream_index], len(stream)):
                why = line_mismatch(line, stream[position], relative, vary)
                if why is None:
                    cursors[stream_index] = position + 1
                    found = True
                    break
                if why != "other words" and nearest is None:
                    nearest = f"{stream[position]!r}: {why}"
            if found:
                break
        if not found:
            problems.append(f"not printed: {line!r}" + (f"; nearest {nearest}" if nearest else ""))
    return problems


def as_float32(value: float) -> float:
    return struct.unpack("f", struct.pack("f", value))[0]


@functools.cache
def atan2f_rounds_as_measured() -> bool:
    """Whether this C library's atan2f gives the probe's glibc 2.36 result."""
    library = ctypes.util.find_library("m")
    if library is None:
        return False
    atan2f = ctypes.CDLL(library).atan2f
    atan2f.restype = ctypes.c_float
    atan2f.argtypes = [ctypes.c_float, ctypes.c_float]
    y, x, measured = ATAN2F_PROBE
    return atan2f(as_float32(y), as_float32(x)) == measured


def figures_vary(example: Example) -> re.Pattern | None:
    """The figures of the block's text left uncompared on this machine."""
    if example.float_libm and not atan2f_rounds_as_measured():
        return NUMBER
    return example.vary


def scratch_directory(root: Path, build_dir: Path) -> Path:
    directory = Path(tempfile.mkdtemp(prefix="upkie-rl-example-"))
    for name in REPOSITORY_LINKS:
        (directory / name).symlink_to(root / name)
    (directory / "build").symlink_to(build_dir.resolve())
    return directory


def run_example(example: Example, root: Path, build_dir: Path,
                timeout: float = 600.0) -> list[str]:
    """Runs the block's commands in a scratch directory; returns the mismatches found."""
    directory = scratch_directory(root, build_dir)
    environment = dict(os.environ)
    environment["PATH"] = f"{build_dir.resolve()}{os.pathsep}{environment.get('PATH', '')}"
    background = []
    problems = []
    try:
        for command in commands_of(example):
            if command.text.endswith("&"):
                background.append(subprocess.Popen(
                    ["bash", "-c", command.text[:-1]], cwd=directory, env=environment,
                    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                    start_new_session=True))
                time.sleep(BACKGROUND_START_SECONDS)
                continue
            result = subprocess.run(["bash", "-o", "pipefail", "-c", command.text],
                                    cwd=directory, env=environment, capture_output=True,
                                    text=True, timeout=timeout)
            if result.returncode != 0 and not any("error" in line for line in command.expected):
                problems.append(f"$ {command.text}\nexit status {result.returncode}:\n"
                                f"{result.stderr[-2000:]}")
                break
            for problem in output_mismatches(command.expected, result.stdout, result.stderr,
                                             example.relative_tolerance,
                                             figures_vary(example)):
                problems.append(f"$ {command.text}\n  {problem}")
    finally:
        for process in background:
            os.killpg(process.pid, signal.SIGINT)
            try:
                process.wait(timeout=10)
            except subprocess.TimeoutExpired:
                os.killpg(process.pid, signal.SIGKILL)
                process.wait()
        shutil.rmtree(directory, ignore_errors=True)
    return problems
