#!/usr/bin/env python3
"""Each man page renders without a groff warning and says what the program's --help says: every
word of --help appears in the rendered page, in the same order.
Usage: check_man_pages.py MAN_DIR PROGRAM..."""
import os
import re
import subprocess
import sys

DASHES = str.maketrans({"\u2010": "-", "\u2011": "-", "\u2212": "-", "\u2018": "'", "\u2019": "'",
                        "\u201c": '"', "\u201d": '"', "\u00b4": "'", "`": "'"})


def words(text):
    # Case and a heading's colon aside (headings become upper-case section titles).
    return [w.lower().rstrip(":") for w in re.findall(r"\S+", text.translate(DASHES))]


def rendered(page):
    done = subprocess.run(["groff", "-man", "-Tutf8", "-ww", "-rLL=200n", "-P-cbou", page],
                          capture_output=True, text=True, env=dict(os.environ, LC_ALL="C.UTF-8"))
    if done.returncode != 0 or done.stderr.strip():
        sys.exit(f"FAIL: groff on {page}: {done.stderr.strip()}")
    return done.stdout


def check(man_dir, program):
    name = os.path.basename(program)
    page = os.path.join(man_dir, name + ".1")
    if not os.path.isfile(page):
        sys.exit(f"FAIL: no man page {page}")
    help_text = subprocess.run([program, "--help"], capture_output=True, text=True, check=True,
                               env=dict(os.environ, QT_QPA_PLATFORM="offscreen")).stdout
    wanted = words(help_text.replace("usage:", "", 1))
    have = words(rendered(page))
    at = 0
    for i, word in enumerate(wanted):
        try:
            at = have.index(word, at) + 1
        except ValueError:
            context = " ".join(wanted[max(0, i - 6):i + 1])
            sys.exit(f"FAIL: {name}.1 lacks --help's word {word!r} (after: ...{context})")
    for section in ("NAME", "SYNOPSIS", "DESCRIPTION", "SEE ALSO"):
        if section.lower().split()[0] not in have:
            sys.exit(f"FAIL: {name}.1 has no {section} section")
    print(f"{name}.1: {len(wanted)} words of --help, in order")


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    for program in sys.argv[2:]:
        check(sys.argv[1], program)


if __name__ == "__main__":
    main()
