#!/usr/bin/env python3
"""Writes a program's man page from its own --help and --version, so that the two never disagree.

Usage: help_to_man.py PROGRAM OUT.1 SUMMARY [SEE_ALSO...]

The help texts of this toolchain share one layout, which is all this reads:
  usage: NAME ...            (continuation lines indented)   -> SYNOPSIS
  paragraphs                  -> DESCRIPTION (the one-line summary of NAME is given by the caller)
  heading:                    a short unindented line ending in ':' -> a section
    --option ARG   text       an indented line starting with '-'   -> a tagged paragraph
                   more text  (deeper indentation continues the item above)
    WORD   text               other indented lines with two spaces inside -> a tagged paragraph
    command line              other indented lines (under an 'examples:' heading) -> verbatim
"""
import os
import re
import subprocess
import sys

ITEM = re.compile(r"^(\s{1,6})(\S.*?)(?:\s{2,}(\S.*))?$")


def run(program, flag):
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen")
    done = subprocess.run([program, flag], capture_output=True, text=True, env=env, timeout=60)
    if done.returncode != 0:
        sys.exit(f"help_to_man: {program} {flag} exited with {done.returncode}: {done.stderr.strip()}")
    return done.stdout


def escape(text):
    text = text.replace("\\", "\\e")
    text = re.sub(r"(?<![\w])-", r"\\-", text)
    # Non-ASCII characters (such as the reference's section sign) as groff's named Unicode escapes.
    text = "".join(c if ord(c) < 128 else f"\\[u{ord(c):04X}]" for c in text)
    return "\\&" + text if text[:1] in (".", "'") else text


def blocks(lines):
    block = []
    for line in lines:
        if line.strip():
            block.append(line.rstrip())
        elif block:
            yield block
            block = []
    if block:
        yield block


def is_heading(line):
    return not line[:1].isspace() and line.endswith(":") and len(line) < 40


class Page:
    def __init__(self):
        self.out = []
        self.section = ""

    def emit(self, *lines):
        self.out.extend(lines)

    def heading(self, title):
        self.section = title.lower()
        self.emit(".SH " + escape(title.upper()))

    def paragraph(self, lines):
        self.emit(".PP", *(escape(line.strip()) for line in lines))

    def items(self, lines):
        if self.section == "examples":
            margin = min(len(line) - len(line.lstrip()) for line in lines)
            self.emit(".PP", ".nf", ".RS 4", *(escape(line[margin:]) for line in lines), ".RE", ".fi")
            return
        indent = None
        for line in lines:
            match = ITEM.match(line)
            width = len(line) - len(line.lstrip())
            if match and (indent is None or width <= indent):
                indent = width
                self.emit(".TP", "\\fB" + escape(match.group(2)) + "\\fR")
                if match.group(3):
                    self.emit(escape(match.group(3)))
            else:
                self.emit(escape(line.strip()))


def convert(name, version, help_text, summary, see_also):
    lines = help_text.splitlines()
    usage = []
    while lines and (lines[0].startswith("usage:") or (usage and lines[0][:1].isspace())):
        usage.append(lines.pop(0).removeprefix("usage:").strip())
    if not usage:
        sys.exit(f"help_to_man: {name} --help does not start with 'usage:'")
    parts = list(blocks(lines))
    page = Page()
    page.emit(f'.TH {name.upper()} 1 "" "{escape(version)}" "Meld toolchain"', ".nh", ".ad l",
              ".SH NAME", f"{escape(name)} \\- {escape(summary)}",
              ".SH SYNOPSIS", ".nf", *(escape(u) for u in usage), ".fi", ".SH DESCRIPTION")
    for block in parts:
        start = 0
        if is_heading(block[0]):
            page.heading(block[0][:-1])
            start = 1
        while start < len(block):
            end = start
            indented = block[start][:1].isspace()
            while end < len(block) and block[end][:1].isspace() == indented:
                end += 1
            (page.items if indented else page.paragraph)(block[start:end])
            start = end
    if see_also:
        page.emit(".SH SEE ALSO", ", ".join(f"\\fB{escape(s)}\\fR(1)" for s in see_also))
        page.emit(".PP", "The user guide and the language reference: share/doc/meld-toolchain/ of the "
                  "installation, docs/ of the source tree.")
    return "\n".join(page.out) + "\n"


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    program, out, summary, see_also = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
    name = os.path.basename(program)
    version = run(program, "--version").strip().splitlines()[0]
    with open(out, "w", encoding="utf-8") as page:
        page.write(convert(name, version, run(program, "--help"), summary, see_also))


if __name__ == "__main__":
    main()
