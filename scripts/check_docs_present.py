#!/usr/bin/env python3
"""Documentation states the present: no lab-notebook history in the docs.

usage: scripts/check_docs_present.py [REPOSITORY_ROOT]

Scans doc/**/*.md, README.md and benchmarks/README.md of the repository (default: the folder
above this script) and lists, as FILE:LINE: what: text, every

  - ISO date (2026-11-24),
  - clock time in UTC (23:33 UTC, 19:02-19:50 UTC),
  - issue reference ("issue 7", "Issue #12", "issues 7"),
  - git commit hash: a word of 7-40 lowercase hex digits with at least one
    digit and one letter a-f, not part of a longer word (file names,
    identifiers and numbers such as 1.5e7 are not words of their own).

History belongs in `git log`; a document says what is measured now, how,
and on which machine. Exit status 0 when every file is clean, 1 when
anything was found, 2 on a usage error. Standard library only.
"""

import pathlib
import re
import sys

# Hex-looking words that are not commit hashes (add one here, lowercase,
# with the reason, if a genuine word of a document is flagged).
ALLOWED_HEX_WORDS = {
}

DATE = re.compile(r"(?<![\w-])\d{4}-(?:0[1-9]|1[0-2])-(?:0[1-9]|[12]\d|3[01])(?![\w-])")
TIME = re.compile(r"(?<![\w:])\d{1,2}:\d{2}(?::\d{2})?(?:\s*-\s*\d{1,2}:\d{2}(?::\d{2})?)?\s*UTC\b")
ISSUE = re.compile(r"\bissues?\s*(?:no\.?\s*)?#?\s*\d+", re.IGNORECASE)
# a word: not preceded or followed by a letter, digit, underscore, dot,
# hyphen or slash that would make it part of a longer token (a file name,
# a path, a number like 1.5e7, an identifier)
HEX_WORD = re.compile(r"(?<![\w./\\-])[0-9a-f]{7,40}(?![\w/\\-])(?!\.\w)")


def is_hash(word):
    return (any(c.isdigit() for c in word) and any(c in "abcdef" for c in word)
            and word not in ALLOWED_HEX_WORDS)


def findings(line):
    for what, pattern in (("date", DATE), ("time", TIME), ("issue reference", ISSUE)):
        for match in pattern.finditer(line):
            yield what, match.group(0)
    for match in HEX_WORD.finditer(line):
        if is_hash(match.group(0)):
            yield "commit hash", match.group(0)


def documents(root):
    files = sorted((root / "doc").glob("**/*.md"))
    for readme in (root / "README.md", root / "benchmarks" / "README.md"):
        if readme.is_file():
            files.append(readme)
    return files


def main(argv):
    if len(argv) > 2 or (len(argv) == 2 and argv[1] in ("-h", "--help")):
        print(__doc__.strip(), file=sys.stderr if len(argv) > 2 else sys.stdout)
        return 2 if len(argv) > 2 else 0
    root = pathlib.Path(argv[1] if len(argv) == 2
                        else pathlib.Path(__file__).resolve().parent.parent)
    if not (root / "doc").is_dir():
        print(f"check_docs_present.py: {root}/doc: not a folder", file=sys.stderr)
        return 2
    files = documents(root)
    found = 0
    for path in files:
        text = path.read_text(encoding="utf-8", errors="replace")
        for number, line in enumerate(text.splitlines(), start=1):
            for what, token in findings(line):
                found += 1
                print(f"{path.relative_to(root)}:{number}: {what}: {token}")
    if found:
        print(f"{found} lab-notebook reference(s) in {len(files)} documents: "
              "state the present, history lives in git log", file=sys.stderr)
        return 1
    print(f"{len(files)} documents state the present (no dates, UTC times, "
          "issue numbers or commit hashes)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
