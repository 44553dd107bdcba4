#!/usr/bin/env python3
"""The documents' examples as tests: what README.md shows is what cncc prints.

Every ```console block of README.md and lang/*.md is run and compared, line
for line, with what its commands print. In a block, a line starting with
`$ ` is a command and the lines after it, up to the next command or the end
of the block, are its output (standard output and standard error, as one
stream):

    ```console
    $ build/tools/cncc/cncc check examples/s_profile.cdl
    $ echo $?
    0
    ```

How the commands run, so that they work as written from the repository root:

  - each block runs in a fresh scratch directory that holds a symbolic link
    to every top-level entry of the repository (examples/, stdlib/, ...),
    except build/, and build/tools/cncc/cncc as a link to the cncc under
    test; files a command writes with a relative name (O1000) land there;
  - `/tmp/` in a command is the scratch directory's own tmp/, and is written
    back as `/tmp/` in the output, so /tmp/s_profile.nc is private to the run;
  - every command runs in its own `bash -c` (a `cd` does not carry over), in
    the C locale, with a 120 s timeout (generous for the sanitizer build);
  - `$?` is the previous command's exit code, so `$ echo $?` shows it. A
    command that exits with anything but 0 fails the test unless the next
    command is `echo $?`, which puts the exit code in the document; an exit
    code of 128 or more (a crash) always fails.

A block that must not be run (it needs an editor, the network, a machine)
is marked by this comment on the line before its opening fence:

    <!-- not run -->

(a reason may follow: `<!-- not run: needs Neovim -->`). Other fenced
blocks (```sh, ```cdl, ...) are never run.

    run_doc_examples.py --build build                 check every document
    run_doc_examples.py --build build README.md       check one document
    run_doc_examples.py --build build --update        rewrite the outputs in place
    run_doc_examples.py --build build --summary       README's command line vs --help

--update rewrites only the output lines of console blocks, with what the
commands print now; review the result with `git diff` before committing.

--summary checks that README.md's command-line summary (the section
"## The command line": its block of command forms and its table of options)
lists every subcommand and option that `cncc --help` and each subcommand's
--help list, and nothing else, and that the "## Targets" table lists the
targets `cncc --help` lists.
"""

import argparse
import difflib
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from cncc_binary import find_cncc  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent.parent
CNCC_AS_WRITTEN = Path("build/tools/cncc/cncc")
NOT_RUN = re.compile(r"^<!--\s*not run\b.*-->\s*$")
CONSOLE_FENCE = re.compile(r"^```console\s*$")
CLOSING_FENCE = re.compile(r"^```\s*$")
PROMPT = "$ "
# A path that starts with /tmp/ (not /x/tmp/ or ./tmp/).
TMP_PATH = re.compile(r"(?<![\w./-])/tmp/")
TIMEOUT_SECONDS = 120


def default_documents():
    return [ROOT / "README.md", *sorted((ROOT / "lang").glob("*.md"))]


class Command:
    def __init__(self, line_index, text):
        self.line_index = line_index  # of the `$ ` line in the document
        self.text = text
        self.expected = []  # output lines as the document shows them
        self.actual = None  # as cncc prints them now


class Block:
    def __init__(self, document, opening_index):
        self.document = document
        self.opening_index = opening_index  # of the ```console line
        self.commands = []

    def where(self):
        return f"{self.document.relative_to(ROOT)}:{self.opening_index + 1}"

    def transcript(self, actual):
        lines = []
        for command in self.commands:
            lines.append(PROMPT + command.text)
            lines += command.actual if actual else command.expected
        return [line + "\n" for line in lines]


def parse_blocks(document, lines):
    """The console blocks of a document that are to be run, and the problems
    that make a block unreadable (output before its first command)."""
    blocks, problems = [], []
    index = 0
    while index < len(lines):
        if not CONSOLE_FENCE.match(lines[index]):
            index += 1
            continue
        block = Block(document, index)
        previous = index - 1
        while previous >= 0 and not lines[previous].strip():
            previous -= 1
        skipped = previous >= 0 and NOT_RUN.match(lines[previous])
        index += 1
        while index < len(lines) and not CLOSING_FENCE.match(lines[index]):
            line = lines[index]
            if line.startswith(PROMPT):
                block.commands.append(Command(index, line[len(PROMPT):]))
            elif block.commands:
                block.commands[-1].expected.append(line)
            elif not skipped:
                problems.append(f"{document.relative_to(ROOT)}:{index + 1}: output before "
                                f"the block's first `$ ` command")
            index += 1
        if index == len(lines):
            problems.append(f"{block.where()}: the console block is not closed")
        if not skipped and block.commands:
            blocks.append(block)
        index += 1
    return blocks, problems


def make_scratch(cncc):
    """A directory in which the documents' commands work as written."""
    scratch = Path(tempfile.mkdtemp(prefix="cncc-doc-")).resolve()
    for entry in ROOT.iterdir():
        if entry.name not in ("build", ".git"):
            (scratch / entry.name).symlink_to(entry)
    (scratch / CNCC_AS_WRITTEN).parent.mkdir(parents=True)
    (scratch / CNCC_AS_WRITTEN).symlink_to(cncc)
    (scratch / "tmp").mkdir()
    return scratch


def environment():
    env = dict(os.environ)
    env.pop("CNCC_STDLIB", None)
    env.update(TERM="dumb", LC_ALL="C")
    return env


def run_shell(script, directory):
    """(exit code, standard output and error as one text), or (None, "") on
    a timeout. The command runs in its own process group, so that a timeout
    also ends the processes of a pipeline (which would hold the pipe open)."""
    process = subprocess.Popen(
        ["bash", "-c", script], cwd=directory, env=environment(), stdin=subprocess.DEVNULL,
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, start_new_session=True,
    )
    try:
        output, _ = process.communicate(timeout=TIMEOUT_SECONDS)
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        process.communicate()
        return None, ""
    return process.returncode, output.decode("utf-8", errors="backslashreplace")


def run_block(block, cncc):
    """Runs the block's commands, filling in their output; returns the
    failures that no expected output can fix."""
    failures = []
    scratch = make_scratch(cncc)
    try:
        exit_code = 0
        for position, command in enumerate(block.commands):
            text = TMP_PATH.sub(f"{scratch}/tmp/", command.text)
            # `(exit N)` makes $? the previous command's exit code.
            script = f"(exit {exit_code}); {text}"
            exit_code, output = run_shell(script, scratch)
            if exit_code is None:
                failures.append(f"timed out after {TIMEOUT_SECONDS} s: {command.text}")
                command.actual = command.expected
                exit_code = 124
                continue
            output = output.replace(f"{scratch}/tmp/", "/tmp/").replace(str(scratch), "<scratch>")
            command.actual = output.splitlines()
            shown = (position + 1 < len(block.commands)
                     and block.commands[position + 1].text.strip() == "echo $?")
            if exit_code < 0 or exit_code >= 128:
                failures.append(f"crashed (exit code {exit_code}): {command.text}")
            elif exit_code != 0 and not shown:
                failures.append(f"exit code {exit_code}, which the document does not show "
                                f"(add `$ echo $?` after the command): {command.text}")
    finally:
        # rmtree removes the links without following them: the repository stays.
        shutil.rmtree(scratch)
    return failures


def rewrite(lines, blocks):
    """The document's lines with each run block's outputs replaced by the
    actual ones; everything else is left as it is."""
    outputs = {}  # a command's line index -> the command
    for block in blocks:
        for command in block.commands:
            outputs[command.line_index] = command
    result, index = [], 0
    while index < len(lines):
        result.append(lines[index])
        command = outputs.get(index)
        if command is not None:
            result += command.actual
            index += len(command.expected)
        index += 1
    return result


def check_document(document, cncc, update):
    """Returns (examples run, failure messages)."""
    text = document.read_text(encoding="utf-8")
    lines = text.splitlines()
    blocks, failures = parse_blocks(document, lines)
    for block in blocks:
        for problem in run_block(block, cncc):
            failures.append(f"{block.where()}: {problem}")
        expected, actual = block.transcript(False), block.transcript(True)
        if expected != actual and not update:
            diff = difflib.unified_diff(expected, actual, fromfile=f"{block.where()} (expected)",
                                        tofile="actual")
            failures.append(f"{block.where()}: the output differs\n" + "".join(diff))
    if update:
        new_text = "".join(line + "\n" for line in rewrite(lines, blocks))
        if new_text != text:
            document.write_text(new_text, encoding="utf-8")
            print(f"updated {document.relative_to(ROOT)}")
    return len(blocks), failures


def run_documents(cncc, documents, update):
    failures, examples = 0, 0
    for document in documents:
        count, messages = check_document(document, cncc, update)
        examples += count
        for message in messages:
            failures += 1
            print(f"FAIL {message.rstrip()}\n")
    names = ", ".join(str(d.relative_to(ROOT)) for d in documents)
    print(f"{examples} console blocks run in {names}; {failures} failures")
    return 1 if failures else 0


# --summary ------------------------------------------------------------------

SUMMARY_HEADING = "## The command line"
TARGETS_HEADING = "## Targets"
# An option as written in prose or help: -t, --emit (not the -zero of non-zero).
OPTION = re.compile(r"(?<![\w-])(--[A-Za-z][\w-]*|-[A-Za-z](?![A-Za-z-]))")


def help_sections(text):
    """{"Options": [...], "Subcommands": [...], ...}: the first word of each
    entry (indented by exactly two spaces) under each `Heading:` line."""
    sections, current = {}, None
    for line in text.splitlines():
        heading = re.match(r"^(\w+):$", line)
        if heading:
            current = sections.setdefault(heading.group(1), [])
        elif current is not None and re.match(r"^  \S", line):
            current.append(line.split()[0])
    return sections


def help_of(cncc, *subcommand):
    result = subprocess.run([str(cncc), *subcommand, "--help"], capture_output=True, text=True,
                            cwd=ROOT, env=environment(), timeout=TIMEOUT_SECONDS)
    if result.returncode != 0:
        sys.exit(f"run_doc_examples.py: cncc {' '.join(subcommand)} --help exited "
                 f"with {result.returncode}")
    return help_sections(result.stdout)


def help_options(entries):
    # "-t,--target" names two options; "--emit" one.
    return {name for entry in entries for name in entry.split(",") if name.startswith("-")}


def section_of(lines, heading):
    start = lines.index(heading) + 1
    end = next((i for i in range(start, len(lines)) if lines[i].startswith("## ")), len(lines))
    return lines[start:end]


def first_fenced_block(lines):
    opening = next(i for i, line in enumerate(lines) if line.startswith("```"))
    closing = next(i for i in range(opening + 1, len(lines)) if lines[i].startswith("```"))
    return lines[opening + 1:closing]


def first_column(lines):
    """The first cell of each row of the section's tables (header rows too)."""
    cells = []
    for line in lines:
        if line.startswith("|") and not re.match(r"^\|[-| ]+\|$", line):
            cells.append(re.split(r"(?<!\\)\|", line)[1].strip())
    return cells


def compare(what, documented, listed):
    problems = []
    for name in sorted(listed - documented):
        problems.append(f"{what} {name} is in cncc's help but not in README.md")
    for name in sorted(documented - listed):
        problems.append(f"{what} {name} is in README.md but not in cncc's help")
    return problems


def check_summary(cncc):
    lines = (ROOT / "README.md").read_text(encoding="utf-8").splitlines()
    summary = section_of(lines, SUMMARY_HEADING)
    forms = first_fenced_block(summary)  # `cncc check FILE...   description`
    documented_options = {option for text in forms + first_column(summary)
                          for option in OPTION.findall(text)}
    documented_subcommands = {m.group(1) for line in forms
                              for m in [re.match(r"^cncc ([a-z]+)\b", line)] if m}
    documented_targets = {cell.strip("`") for cell in first_column(section_of(lines, TARGETS_HEADING))
                          if cell.startswith("`")}

    main = help_of(cncc)
    subcommands = set(main.get("Subcommands", []))
    options = help_options(main.get("Options", []))
    for subcommand in subcommands:
        options |= help_options(help_of(cncc, subcommand).get("Options", []))

    problems = (compare("subcommand", documented_subcommands, subcommands)
                + compare("option", documented_options, options)
                + compare("target", documented_targets, set(main.get("Targets", []))))
    for problem in problems:
        print(f"FAIL {problem}")
    if problems:
        print(f"README.md's sections '{SUMMARY_HEADING}' and '{TARGETS_HEADING}' must list "
              "what `cncc --help` lists")
        return 1
    print(f"README.md lists the {len(subcommands)} subcommands, {len(options)} options and "
          f"{len(documented_targets)} targets of cncc --help")
    return 0


def select_documents(names):
    if not names:
        return default_documents()
    documents = []
    for name in names:
        path = next((p for p in (Path(name), ROOT / name) if p.is_file()), None)
        if path is None:
            sys.exit(f"run_doc_examples.py: no document '{name}'")
        documents.append(path.resolve())
    return documents


def main():
    parser = argparse.ArgumentParser(
        description="Run the console examples of README.md and lang/*.md.",
        epilog="Update the documents: python3 tests/docs/run_doc_examples.py --build build --update",
    )
    parser.add_argument("documents", nargs="*", help="documents to check (default: all)")
    parser.add_argument("--build", default="build", help="the build directory (default: build)")
    parser.add_argument("--cncc", help="the cncc binary (overrides --build)")
    parser.add_argument("--update", action="store_true",
                        help="rewrite the examples' outputs in the documents")
    parser.add_argument("--summary", action="store_true",
                        help="check README's command-line summary against cncc --help")
    arguments = parser.parse_args()
    cncc = find_cncc(arguments, "run_doc_examples.py")
    if arguments.summary:
        return check_summary(cncc)
    return run_documents(cncc, select_documents(arguments.documents), arguments.update)


if __name__ == "__main__":
    sys.exit(main())
