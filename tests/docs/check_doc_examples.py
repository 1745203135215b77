#!/usr/bin/env python3
"""Runs the Meld examples of the documentation and compares them with the text the documents show.

Usage: check_doc_examples.py MELD MELDC VSIM ABI_INCLUDE_DIR SOURCE_DIR WORK DOC.md...

Three kinds of example, each a fenced block whose info string names it:

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


def examples(path):
    blocks = list(fenced_blocks(path))
    for k, (info, text, line) in enumerate(blocks):
        if info[0] not in ("meld", "c", "xml"):
            continue
        attrs = dict(a.split("=", 1) if "=" in a else (a, "") for a in info[1:])
        if info[0] == "xml":
            if "world" in attrs:
                yield attrs["world"], attrs, text, "", f"{path}:{line}"
            continue
        if info[0] == "meld" and "file" in attrs:
            yield attrs["file"], attrs, text, "", f"{path}:{line}"
            continue
        if "example" not in attrs and "error" not in attrs and "robot" not in attrs:
            continue
        if info[0] == "c":
            yield attrs.get("example"), attrs, text, None, f"{path}:{line}"
            continue
        want = "dump" if "example" in attrs else "text"
        if "robot" in attrs:
            # The robot example's text block may follow a shell block (the command to run it).
            following = [b for b in blocks[k + 1:k + 3] if b[0][0] == "text"]
            if not following:
                sys.exit(f"FAIL: {path}:{line}: the robot example is not followed by a ```text block")
            yield attrs["robot"], attrs, text, following[0][1], f"{path}:{line}"
            continue
        if k + 1 >= len(blocks) or blocks[k + 1][0][0] != want:
            sys.exit(f"FAIL: {path}:{line}: the example is not followed by a ```{want} block")
        name = attrs.get("example") or attrs.get("error")
        yield name, attrs, text, blocks[k + 1][1], f"{path}:{line}"


def run(command, cwd):
    return subprocess.run(command, cwd=cwd, capture_output=True, text=True, timeout=60)


def check_example(meld, meldc, work, name, attrs, program, expected, where):
    source = os.path.join(work, name + ".meld")
    with open(source, "w", encoding="utf-8") as out:
        out.write(program)
    args = ["--"] + attrs["args"].split(",") if attrs.get("args") else []
    modes = [("bytecode", [meld, source, "--dump"] + args), ("jit", [meld, source, "--jit", "--dump"] + args)]
    native = os.path.join(work, name + ".so")
    built = run([meldc, "--emit=native", "--no-progress", "-o", native, source], work)
    if built.returncode != 0:
        return [f"{where} ({name}): meldc --emit=native failed:\n{built.stderr}"]
    modes.append(("native", [meld, native, "--dump"] + args))
    if "serial" not in attrs:
        modes.append(("-j 2", [meld, source, "-j", "2", "--dump"] + args))
    failures = []
    for mode, command in modes:
        done = run(command, work)
        if done.returncode != 0 or done.stdout != expected:
            failures.append(f"{where} ({name}, {mode}): exit {done.returncode}\n--- the document\n{expected}"
                            f"--- meld\n{done.stdout}{done.stderr}")
    return failures


def check_error(meldc, work, name, program, expected, where):
    source = name + ".meld"
    with open(os.path.join(work, source), "w", encoding="utf-8") as out:
        out.write(program)
    done = run([meldc, "--check", source], work)
    said = done.stdout + done.stderr
    if done.returncode != 1:
        return [f"{where} ({name}): meldc --check exited {done.returncode}, not 1:\n{said}"]
    return [f"{where} ({name}): meldc does not say {line!r}; it says:\n{said}"
            for line in expected.splitlines() if line.strip() and line not in said]


def check_robot(vsim, work, name, attrs, program, expected, where):
    with open(os.path.join(work, name + ".meld"), "w", encoding="utf-8") as out:
        out.write(program)
    world = os.path.join(work, attrs.get("world", "") + ".xml")
    if not os.path.isfile(world):
        return [f"{where} ({name}): no ```xml world={attrs.get('world')} block before it"]
    failures = []
    for mode, extra in (("bytecode", []), ("jit", ["--jit"])):
        done = run([vsim, world, "--no-progress"] + extra, work)
        said = done.stdout + done.stderr
        missing = [line for line in expected.splitlines() if line.strip() and line not in said.splitlines()]
        if done.returncode != 0 or missing:
            failures.append(f"{where} ({name}, {mode}): exit {done.returncode}, missing {missing}; vsim says:\n{said}")
    return failures


def check_blockcode(vsim, abi_include, source_dir, work, name, attrs, program, where):
    source = os.path.join(work, name + ".c")
    with open(source, "w", encoding="utf-8") as out:
        out.write(program)
    library = os.path.join(work, name + ".so")
    built = run(["cc", "-shared", "-fPIC", "-Wall", "-Werror", "-I", abi_include, source, "-o", library], work)
    if built.returncode != 0:
        return [f"{where} ({name}): cc failed:\n{built.stderr}"]
    if "world" not in attrs:
        return [f"{where} ({name}): a C example names the world it runs on (world=PATH)"]
    done = run([vsim, os.path.join(source_dir, attrs["world"]), "--code", library, "--quiet"], work)
    if done.returncode != 0:
        return [f"{where} ({name}): vsim exited {done.returncode}:\n{done.stdout}{done.stderr}"]
    return []


def main():
    if len(sys.argv) < 8:
        sys.exit(__doc__)
    meld, meldc, vsim, abi_include, source_dir, work = (os.path.abspath(a) for a in sys.argv[1:7])
    os.makedirs(work, exist_ok=True)
    failures, count, names = [], 0, set()
    for doc in sys.argv[7:]:
        for name, attrs, program, expected, where in examples(doc):
            if name in names:
                sys.exit(f"FAIL: {where}: a second example named {name}")
            names.add(name)
            count += 1
            if "file" in attrs and "example" not in attrs:
                with open(os.path.join(work, name + ".meld"), "w", encoding="utf-8") as out:
                    out.write(program)
                continue
            if "world" in attrs and "robot" not in attrs and "example" not in attrs:
                with open(os.path.join(work, name + ".xml"), "w", encoding="utf-8") as out:
                    out.write(program)
                continue
            if "robot" in attrs:
                failures += check_robot(vsim, work, name, attrs, program, expected, where)
            elif program is not None and expected is None:
                failures += check_blockcode(vsim, abi_include, source_dir, work, name, attrs, program, where)
            elif "example" in attrs:
                failures += check_example(meld, meldc, work, name, attrs, program, expected, where)
            else:
                failures += check_error(meldc, work, name, program, expected, where)
    for failure in failures:
        print("FAIL:", failure)
    if count == 0:
        sys.exit("FAIL: no examples found")
    print(f"{count} examples of {len(sys.argv) - 7} documents, {len(failures)} failures")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
