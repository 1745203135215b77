#!/usr/bin/env python3
"""Checks editors/meld.tmLanguage.json the way an editor would use it.

Loads the grammar, compiles every pattern, and tokenises Meld files line by line as a TextMate
engine does for single-line `match` rules: at each point the pattern matching earliest wins, the
first in grammar order on a tie. Fails when a pattern does not compile, when a file leaves any
character other than blanks without a scope (the grammar misses a token), or when a token of the
list below gets another scope than it should.

    check_grammar.py GRAMMAR FILE.meld...
"""
import json
import re
import sys

# (text of a token, the line it is on contains, the scope it must get) on the files checked.
EXPECTED = [
    ("// catoms3d-walk.meld: a catom walks along a row of Catoms 3D by 60-degree rotations over it.",
     "catoms3d-walk.meld: a catom", "comment.line.double-slash.meld"),
    ("include", "include #catoms3d.meld", "keyword.control.import.meld"),
    ("#catoms3d.meld", "include #catoms3d.meld", "string.unquoted.file.meld"),
    ("const", "const last = 6.", "storage.modifier.meld"),
    ("6", "const last = 6.", "constant.numeric.meld"),
    ("-o", "X < last -o moveTo", "keyword.operator.arrow.meld"),
    ("moveTo", "X < last -o moveTo", "entity.name.function.meld"),
    ("!", "X < last -o moveTo", "keyword.operator.modifier.meld"),
    ("X", "X < last -o moveTo", "variable.parameter.meld"),
    ("_", "!at(B, X, _, 1) -o !setColor2", "variable.language.anonymous.meld"),
    ("@+50ms", "tick(B)@+50ms", "keyword.other.delay.meld"),
    ("@0", "!path(@0, 0).", "constant.other.node.meld"),
    ("fun", "fun goalX(int T) : float =", "storage.modifier.meld"),
    ("float", "fun goalX(int T) : float =", "storage.type.meld"),
    ("if", "if T <= 10000 then 75.0", "keyword.control.meld"),
    ("75.0", "if T <= 10000 then 75.0", "constant.numeric.meld"),
    ("type", "type linear tick(node).", "storage.modifier.meld"),
    ("linear", "type linear tick(node).", "storage.modifier.meld"),
    ("east", "!neighbor(B, N, east) -o fire(N, east", "variable.other.constant.meld"),
]


def flatten(grammar, rules, out):
    for rule in rules:
        if "include" in rule:
            entry = grammar["repository"][rule["include"].lstrip("#")]
            flatten(grammar, entry.get("patterns", [entry]), out)
        else:
            out.append(rule)
    return out


def tokenise(line, rules):
    """[(start, end, scope)] and the unscoped characters as [(column, char)]."""
    tokens, unscoped, pos = [], [], 0
    while pos < len(line):
        best = None
        for regex, rule in rules:
            m = regex.search(line, pos)
            if m and (best is None or m.start() < best[0].start()):
                best = (m, rule)
        if best is None:
            unscoped += [(c, line[c]) for c in range(pos, len(line))]
            break
        m, rule = best
        unscoped += [(c, line[c]) for c in range(pos, m.start())]
        if "captures" in rule:
            for group, capture in rule["captures"].items():
                if m.group(int(group)) is not None:
                    tokens.append((m.start(int(group)), m.end(int(group)), capture["name"]))
        else:
            tokens.append((m.start(), m.end(), rule["name"]))
        pos = m.end() if m.end() > pos else pos + 1
    return tokens, unscoped


def main(argv):
    if len(argv) < 3:
        print(__doc__)
        return 2
    grammar = json.load(open(argv[1], encoding="utf-8"))
    for key in ("scopeName", "patterns", "repository", "fileTypes"):
        if key not in grammar:
            print(f"{argv[1]}: no '{key}'")
            return 1
    rules = []
    for rule in flatten(grammar, grammar["patterns"], []):
        try:
            rules.append((re.compile(rule["match"]), rule))
        except re.error as e:
            print(f"{argv[1]}: pattern {rule['match']!r} does not compile: {e}")
            return 1
    problems, found, lines = 0, set(), 0
    for path in argv[2:]:
        for number, line in enumerate(open(path, encoding="utf-8").read().split("\n"), 1):
            lines += 1
            tokens, unscoped = tokenise(line, rules)
            for column, char in unscoped:
                if not char.isspace():
                    print(f"{path}:{number}:{column + 1}: no scope for {char!r} in: {line.strip()}")
                    problems += 1
            for i, (text, context, scope) in enumerate(EXPECTED):
                if context not in line:
                    continue
                got = [s for (a, b, s) in tokens if line[a:b] == text]
                if got and got[0] == scope:
                    found.add(i)
                elif got:
                    print(f"{path}:{number}: {text!r} is {got[0]}, expected {scope}")
                    problems += 1
    for i, (text, context, scope) in enumerate(EXPECTED):
        if i not in found:
            print(f"no line containing {context!r} with the token {text!r} ({scope}) in the files")
            problems += 1
    print(f"{len(argv) - 2} files, {lines} lines, {len(rules)} patterns, {len(found)} expected tokens: "
          f"{problems} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
