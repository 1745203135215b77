#!/usr/bin/env python3
"""Runs the Meld examples of the documentation and compares them with the text the documents show.

Usage: check_doc_examples.py MELD MELDC VSIM ABI_INCLUDE_DIR SOURCE_DIR WORK DOC.md...

The examples, each a fenced block whose info string names it:

  ```meld example=NAME            a program; the next fenced block (```dump) is what
  ...                             `meld NAME.meld --dump` prints, byte for byte. It is run in every
  ```                             execution mode: the bytecode VM, the JIT (--jit), a shared object
  ```dump                         (meldc --emit=native), and on 2 worker threads (-j 2), except
  ...                             with `serial` in the info string (a result that depends on the
  ```                             order nodes run in, said so in the text around it).

  Attributes of an example: `serial` (above); `args=A,B` (program arguments, `-- A B`, read as
  @arg1, @arg2). A block ```meld file=NAME``` is written as NAME.meld for the examples after it to
  include (`include #NAME.meld`).

  ```meld error=NAME              a program meldc refuses: `meldc --check` exits 1, and every line of
  ...                             the next fenced block (```text) appears in what it prints, with
  ```                             NAME.meld as the file name.
  ```text
  NAME.meld:3:1: error: ...
  ```

  ```xml world=NAME               a world file, written as NAME.xml for the robot examples below
  ```meld robot=NAME world=W      a robot program, written as NAME.meld and run by `vsim W.xml` (the
  ```                             world names it), as bytecode and with --jit; every line of the
  ```text                         next block (```text) must appear in what vsim prints.
  ```

  ```c example=NAME world=PATH    a C BlockCode: built with `cc -shared -fPIC` against the block ABI
  ...                             and run by vsim on the world PATH (relative to SOURCE_DIR), which
  ```                             must exit 0.
"""
import collections
import os
import re
import subprocess
import sys

FENCE = re.compile(r"^```(\S*)(.*)$")


def fenced_blocks(path):
    """(info, text, line) for every fenced block of a Markdown file."""
    with open(path, encoding="utf-8") as doc:
        lines = doc.read().split("\n")
    i = 0
    while i < len(lines):
        match = FENCE.match(lines[i])
        if match and match.group(1):
            start = i
            i += 1
            body = []
            while i < len(lines) and lines[i] != "```":
                body.append(lines[i])
                i += 1
            yield (match.group(1) + match.group(2)).split(), "\n".join(body) + "\n", start + 1
        i += 1


# kind: file, world (written for the examples after them), dump, error, robot, blockcode (checked).
Example = collections.namedtuple("Example", "kind name attrs text expected where")


def examples(path):
    blocks = list(fenced_blocks(path))
    for k, (info, text, line) in enumerate(blocks):
        attrs = dict(a.split("=", 1) if "=" in a else (a, "") for a in info[1:])
        where = f"{path}:{line}"

        def followed_by(language, within=1):
            # A robot example's output may come after a shell block (the command that runs it).
            found = [b for b in blocks[k + 1:k + 1 + within] if b[0][0] == language]
            if not found:
                sys.exit(f"FAIL: {where}: the example is not followed by a ```{language} block")
            return found[0][1]

        language = info[0]
        if language == "xml" and "world" in attrs:
            yield Example("world", attrs["world"], attrs, text, None, where)
        elif language == "c" and "example" in attrs:
            yield Example("blockcode", attrs["example"], attrs, text, None, where)
        elif language != "meld":
            continue
        elif "file" in attrs:
            yield Example("file", attrs["file"], attrs, text, None, where)
        elif "example" in attrs:
            yield Example("dump", attrs["example"], attrs, text, followed_by("dump"), where)
        elif "error" in attrs:
            yield Example("error", attrs["error"], attrs, text, followed_by("text"), where)
        elif "robot" in attrs:
            yield Example("robot", attrs["robot"], attrs, text, followed_by("text", within=2), where)


def run(command, cwd):
    return subprocess.run(command, cwd=cwd, capture_output=True, text=True, timeout=60)


def write(work, filename, text):
    path = os.path.join(work, filename)
    with open(path, "w", encoding="utf-8") as out:
        out.write(text)
    return path


class Checker:
    """The programs and folders every check needs; one method per kind of example."""

    def __init__(self, meld, meldc, vsim, abi_include, source_dir, work):
        self.meld, self.meldc, self.vsim = meld, meldc, vsim
        self.abi_include, self.source_dir, self.work = abi_include, source_dir, work

    def check(self, ex):
        return getattr(self, ex.kind)(ex)

    def file(self, ex):
        write(self.work, ex.name + ".meld", ex.text)
        return []

    def world(self, ex):
        write(self.work, ex.name + ".xml", ex.text)
        return []

    def dump(self, ex):
        source = write(self.work, ex.name + ".meld", ex.text)
        args = ["--"] + ex.attrs["args"].split(",") if ex.attrs.get("args") else []
        native = os.path.join(self.work, ex.name + ".so")
        built = run([self.meldc, "--emit=native", "--no-progress", "-o", native, source], self.work)
        if built.returncode != 0:
            return [f"{ex.where} ({ex.name}): meldc --emit=native failed:\n{built.stderr}"]
        modes = [("bytecode", [source]), ("jit", [source, "--jit"]), ("native", [native])]
        if "serial" not in ex.attrs:
            modes.append(("-j 2", [source, "-j", "2"]))
        failures = []
        for mode, command in modes:
            done = run([self.meld] + command + ["--dump"] + args, self.work)
            if done.returncode != 0 or done.stdout != ex.expected:
                failures.append(f"{ex.where} ({ex.name}, {mode}): exit {done.returncode}\n--- the document\n"
                                f"{ex.expected}--- meld\n{done.stdout}{done.stderr}")
        return failures

    def error(self, ex):
        source = ex.name + ".meld"
        write(self.work, source, ex.text)
        done = run([self.meldc, "--check", source], self.work)
        said = done.stdout + done.stderr
        if done.returncode != 1:
            return [f"{ex.where} ({ex.name}): meldc --check exited {done.returncode}, not 1:\n{said}"]
        return [f"{ex.where} ({ex.name}): meldc does not say {line!r}; it says:\n{said}"
                for line in ex.expected.splitlines() if line.strip() and line not in said]

    def robot(self, ex):
        write(self.work, ex.name + ".meld", ex.text)
        world = os.path.join(self.work, ex.attrs.get("world", "") + ".xml")
        if not os.path.isfile(world):
            return [f"{ex.where} ({ex.name}): no ```xml world={ex.attrs.get('world')} block before it"]
        failures = []
        for mode, extra in (("bytecode", []), ("jit", ["--jit"])):
            done = run([self.vsim, world, "--no-progress"] + extra, self.work)
            said = done.stdout + done.stderr
            missing = [line for line in ex.expected.splitlines() if line.strip() and line not in said.splitlines()]
            if done.returncode != 0 or missing:
                failures.append(f"{ex.where} ({ex.name}, {mode}): exit {done.returncode}, missing {missing}; "
                                f"vsim says:\n{said}")
        return failures

    def blockcode(self, ex):
        if "world" not in ex.attrs:
            return [f"{ex.where} ({ex.name}): a C example names the world it runs on (world=PATH)"]
        source = write(self.work, ex.name + ".c", ex.text)
        library = os.path.join(self.work, ex.name + ".so")
        built = run(["cc", "-shared", "-fPIC", "-Wall", "-Werror", "-I", self.abi_include, source, "-o", library],
                    self.work)
        if built.returncode != 0:
            return [f"{ex.where} ({ex.name}): cc failed:\n{built.stderr}"]
        done = run([self.vsim, os.path.join(self.source_dir, ex.attrs["world"]), "--code", library, "--quiet"],
                   self.work)
        if done.returncode != 0:
            return [f"{ex.where} ({ex.name}): vsim exited {done.returncode}:\n{done.stdout}{done.stderr}"]
        return []


def main():
    if len(sys.argv) < 8:
        sys.exit(__doc__)
    checker = Checker(*(os.path.abspath(a) for a in sys.argv[1:7]))
    os.makedirs(checker.work, exist_ok=True)
    failures, names, checked = [], set(), 0
    for doc in sys.argv[7:]:
        for ex in examples(doc):
            if ex.name in names:
                sys.exit(f"FAIL: {ex.where}: a second example named {ex.name}")
            names.add(ex.name)
            checked += ex.kind not in ("file", "world")
            failures += checker.check(ex)
    for failure in failures:
        print("FAIL:", failure)
    if checked == 0:
        sys.exit("FAIL: no examples found")
    print(f"{checked} examples of {len(sys.argv) - 7} documents, {len(failures)} failures")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
