#!/usr/bin/env python3
"""Every section sign the repository cites (code comments, READMEs, help texts, diagnostics, tests:
"§6.4.3", "§6.4–6.11") names a section of the language reference docs/meld-language.md.
Usage: check_citations.py SOURCE_DIR"""
import os
import re
import sys

CITED = re.compile(r"§\s?(\d+(?:\.\d+)*)(?:\s?[–-]\s?§?(\d+(?:\.\d+)*))?")
HEADING = re.compile(r"^#{2,4} (\d+(?:\.\d+)*)\.? ", re.M)
SKIP_DIRS = {".git", "build", "node_modules", "__pycache__"}
TEXT = (".c", ".h", ".cpp", ".hpp", ".def", ".md", ".meld", ".g4", ".txt", ".sh", ".py", ".cmake",
        ".json", ".in", ".expected", ".xml")


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    root = sys.argv[1]
    with open(os.path.join(root, "docs", "meld-language.md"), encoding="utf-8") as ref:
        sections = set(HEADING.findall(ref.read()))
    if len(sections) < 50:
        sys.exit(f"FAIL: only {len(sections)} numbered sections found in docs/meld-language.md")
    bad, cited, files = [], 0, 0
    for folder, dirs, names in os.walk(root):
        dirs[:] = [d for d in dirs if d not in SKIP_DIRS and not d.startswith("build")]
        for name in names:
            if not name.endswith(TEXT) and name != "CMakeLists.txt":
                continue
            path = os.path.join(folder, name)
            with open(path, encoding="utf-8", errors="replace") as f:
                text = f.read()
            if "§" not in text:
                continue
            files += 1
            for line_no, line in enumerate(text.splitlines(), 1):
                for match in CITED.finditer(line):
                    for number in filter(None, match.groups()):
                        cited += 1
                        if number not in sections:
                            bad.append(f"{os.path.relpath(path, root)}:{line_no}: §{number} is not a section "
                                       "of docs/meld-language.md")
    for b in bad:
        print("FAIL:", b)
    print(f"{cited} citations in {files} files, {len(bad)} pointing nowhere")
    sys.exit(1 if bad or cited == 0 else 0)


if __name__ == "__main__":
    main()
