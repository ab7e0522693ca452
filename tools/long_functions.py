#!/usr/bin/env python3
"""Lists the C++ functions longer than a limit, counted from the first line of
the signature to the closing brace (issue 35: none over about 80 lines in the
runtime, renderer or editor without a one-line reason in a comment).

  tools/long_functions.py [--limit 80] [--exclude PATH ...] DIR_OR_FILE...

Prints `lines  file:line  name`, longest first. A function whose body has a
comment saying why it stays long is still listed, marked `(reason given)`: the
reason is a comment line within the first lines of the body or just above the
signature that starts with "Long:" (e.g. `// Long: one table, read in order.`).
A heuristic brace matcher, not a parser: lambdas and local classes count as
part of the function that holds them; macros that open braces may confuse it.
"""
import argparse
import os
import re
import sys

KEYWORDS = {"if", "for", "while", "switch", "catch", "else", "do", "return", "try"}
CTOR_INIT = re.compile(r"\)\s*(noexcept\s*)?:[^:]")
SCOPES = re.compile(r"\b(namespace|class|struct|union|enum)\b[^()]*$|extern\s+\"C\"\s*$")


def strip(text):
    """Blanks comments, strings and characters, keeping newlines (line numbers)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif c == 'R' and text.startswith('R"', i):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            end = text.find(")" + m.group(1) + '"', i) if m else -1
            j = n if end < 0 else end + len(m.group(1)) + 2
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            out.append(c + " " * (min(j, n) - i - 1) + (c if j < n else ""))
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def functions(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        raw = f.read()
    text = strip(raw)
    raw_lines = raw.split("\n")
    line_of = [0] * (len(text) + 1)
    line = 1
    for i, ch in enumerate(text):
        line_of[i] = line
        if ch == "\n":
            line += 1
    stack = []  # per open brace: ("scope" | "function" | "other", start line, name)
    head_start = 0  # where the text before the next brace began
    for i, ch in enumerate(text):
        if ch in ";":
            if not stack or stack[-1][0] == "scope":
                head_start = i + 1
        elif ch == "{":
            inside_function = any(kind == "function" for kind, _, _ in stack)
            head = text[head_start:i]
            kind = "other"
            if not inside_function:
                stripped = head.strip()
                if CTOR_INIT.search(stripped) and re.search(r"[\w>]$", stripped):
                    # a member's brace initialiser in a constructor's init list: still the head
                    stack.append(("init", line_of[i], ""))
                    continue
                if SCOPES.search(stripped) or stripped == "":
                    kind = "scope" if stripped else "other"
                elif "(" in stripped and "=" not in stripped.split("(")[0]:
                    first = re.match(r"[A-Za-z_]\w*", stripped)
                    if not first or first.group(0) not in KEYWORDS:
                        kind = "function"
            name = ""
            start = line_of[i]
            if kind == "function":
                stripped = head.strip()
                m = re.search(r"([~\w:<>]+|operator\s*\S+)\s*\(", stripped)
                name = m.group(1) if m else stripped[:40]
                offset = head_start + (len(head) - len(head.lstrip()))
                start = line_of[offset]
            stack.append((kind, start, name))
            head_start = i + 1
        elif ch == "}":
            if stack:
                kind, start, name = stack.pop()
                if kind == "function":
                    yield name, start, line_of[i], raw_lines
                if kind == "init":
                    continue
            if not stack or stack[-1][0] == "scope":
                head_start = i + 1


def has_reason(raw_lines, start, end):
    window = raw_lines[max(0, start - 4):min(end, start + 6)]
    return any(re.search(r"//\s*Long:", l) for l in window)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("paths", nargs="+")
    parser.add_argument("--limit", type=int, default=80)
    parser.add_argument("--exclude", action="append", default=[], help="a path prefix to leave out")
    args = parser.parse_args()
    files = []
    for p in args.paths:
        if os.path.isfile(p):
            files.append(p)
        for root, _, names in os.walk(p):
            files += [os.path.join(root, n) for n in names if n.endswith((".cpp", ".h", ".hpp", ".cc"))]
    rows = []
    for path in sorted(set(files)):
        if any(os.path.normpath(path).startswith(os.path.normpath(e)) for e in args.exclude):
            continue
        for name, start, end, raw_lines in functions(path):
            length = end - start + 1
            if length > args.limit:
                rows.append((length, path, start, name, has_reason(raw_lines, start, end)))
    for length, path, start, name, reason in sorted(rows, key=lambda r: (-r[0], r[1])):
        print(f"{length:5d}  {path}:{start}  {name}{'  (reason given)' if reason else ''}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
