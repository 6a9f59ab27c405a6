#!/usr/bin/env python3
"""function-length.py: the C and C++ functions longer than a limit, outside tests.

    python3 tools/function-length.py [--limit N] [--all] [ROOT]

Reads every .c .cc .cpp .h .hpp file below ROOT (default: the repository this script is in),
leaving out tests/, build directories and dot-folders, and prints one line a function whose
lines, from its signature to its closing brace, exceed the limit (default 80):
    path:line: NAME: LINES lines
A function is let pass when a comment in the three lines above its signature (or on the
signature's line) holds `function-length:` followed by the reason (a marker without one
does not count), e.g.
    // function-length: a token state machine, one case a token
Such functions are printed with `(justified: REASON)` under --all and do not count.
Exit status: 0 when no function over the limit is left unjustified, 1 when one is, 2 on bad
arguments. The parse is a brace count over the text with comments, strings and character
literals removed (raw strings included): a function is a brace block at namespace or class
scope whose header holds a parenthesis; lambdas and local classes count toward the function
that holds them.
"""
import argparse
import os
import re
import sys

SOURCE_ENDINGS = (".c", ".cc", ".cpp", ".h", ".hpp")
SKIPPED_DIRS = {"tests", ".git"}
MARKER = "function-length:"
CONTAINER = re.compile(r"^\s*(?:(?:export|inline)\s+)*(namespace|struct|class|union|enum|extern)\b")


def strip(text):
    """The text with comments, strings and character literals blanked (newlines kept), and
    the comments' text a line."""
    out = []
    comments = {}
    i, n, line = 0, len(text), 1

    def note(start, end, at):
        comments.setdefault(at, []).append(text[start:end])

    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
            out.append(c)
            i += 1
        elif text.startswith("//", i):
            end = text.find("\n", i)
            end = n if end < 0 else end
            note(i, end, line)
            out.append(" " * (end - i))
            i = end
        elif text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end < 0 else end + 2
            chunk = text[i:end]
            for k, part in enumerate(chunk.split("\n")):
                comments.setdefault(line + k, []).append(part)
            out.append("".join(ch if ch == "\n" else " " for ch in chunk))
            line += chunk.count("\n")
            i = end
        elif c == "R" and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            open_paren = text.find("(", i + 2)
            delim = text[i + 2:open_paren]
            end = text.find(")" + delim + '"', open_paren)
            end = n if end < 0 else end + len(delim) + 2
            chunk = text[i:end]
            out.append("".join(ch if ch == "\n" else " " for ch in chunk))
            line += chunk.count("\n")
            i = end
        elif c == '"' or (c == "'" and not (i > 0 and text[i - 1].isalnum())):
            # a character literal follows no digit (1'000 is a digit separator)
            j = i + 1
            while j < n and text[j] != c:
                if text[j] == "\\":
                    j += 1
                elif text[j] == "\n":
                    break
                j += 1
            out.append(" " * (j + 1 - i))
            i = j + 1
        else:
            out.append(c)
            i += 1
    lines = "".join(out).split("\n")
    continued = False
    for k, text_line in enumerate(lines):
        if continued or text_line.lstrip().startswith("#"):
            continued = text_line.rstrip().endswith("\\")
            lines[k] = " " * len(text_line)
    return "\n".join(lines), comments


def function_name(header):
    """The name before the parameter list of a function header (or a lambda's variable)."""
    flat = " ".join(header.split())
    flat = re.sub(r"^template\s*<.*?>\s*", "", flat)
    paren = flat.find("(")
    before = flat[:paren].rstrip()
    m = re.search(r"(operator\s*\S+|[~\w:]+)\s*(?:<[^()]*>)?$", before)
    if m:
        return m.group(1)
    m = re.search(r"([\w:]+)\s*=\s*\[", flat)
    return m.group(1) if m else flat[:40]


def functions(path):
    """(name, first line, last line, justification or None) for each function in a file."""
    with open(path, encoding="utf-8", errors="replace") as f:
        text = f.read()
    code, comments = strip(text)
    found = []
    stack = []              # one kind a open brace: "container", "function", "other"
    header_start = 0        # where the current declaration's text begins
    line = 1
    header_line = 1
    function_start = None
    for i, c in enumerate(code):
        if c == "\n":
            line += 1
            continue
        in_function = "function" in stack
        if c in ";{}" and not in_function:
            header = code[header_start:i]
        if c == "{":
            if in_function:
                stack.append("other")
            else:
                without_template = re.sub(r"^\s*template\s*<[^{;]*?>\s*(?=\w)", "", header)
                label = re.sub(r"^\s*(public|private|protected)\s*:", "", without_template)
                if CONTAINER.match(label) and "(" not in label.split("{")[0].split(":")[0]:
                    stack.append("container")
                elif "(" in label:
                    stack.append("function")
                    function_start = (function_name(label), header_line)
                else:
                    stack.append("other")
                header_start = i + 1
        elif c == "}":
            kind = stack.pop() if stack else "other"
            if kind == "function" and "function" not in stack:
                name, first = function_start
                reason = None   # the marker's text and the comment lines after it
                for at in range(first - 3, first + 1):
                    for note in comments.get(at, []):
                        text = note.strip().lstrip("/*").rstrip("*/").strip()
                        if reason is not None:
                            reason = (reason + " " + text).strip()
                        elif MARKER in text:
                            reason = text[text.find(MARKER) + len(MARKER):].strip()
                if reason is not None and not reason:
                    reason = None   # the marker without a reason says nothing
                found.append((name, first, line, reason))
            if "function" not in stack:
                header_start = i + 1
        elif c == ";" and not in_function:
            header_start = i + 1
        elif not c.isspace() and not in_function and code[header_start:i].strip() == "":
            header_line = line
    return found


def main():
    parser = argparse.ArgumentParser(description="C and C++ functions longer than a limit, outside tests.")
    parser.add_argument("root", nargs="?", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    parser.add_argument("--limit", type=int, default=80, help="most lines a function may have (default 80)")
    parser.add_argument("--all", action="store_true", help="also print the justified functions over the limit")
    args = parser.parse_args()
    if not os.path.isdir(args.root):
        print(f"function-length: {args.root} is not a directory", file=sys.stderr)
        return 2
    failures = 0
    for dirpath, dirnames, filenames in os.walk(args.root):
        rel_dir = os.path.relpath(dirpath, args.root)
        dirnames[:] = sorted(d for d in dirnames
                             if not d.startswith(".") and not (rel_dir == "." and (d in SKIPPED_DIRS or d.startswith("build")))
                             and not os.path.exists(os.path.join(dirpath, d, "CMakeCache.txt")))
        for name in sorted(filenames):
            if not name.endswith(SOURCE_ENDINGS):
                continue
            path = os.path.join(dirpath, name)
            rel = os.path.relpath(path, args.root)
            for fname, first, last, reason in functions(path):
                length = last - first + 1
                if length <= args.limit:
                    continue
                if reason is None:
                    failures += 1
                    print(f"{rel}:{first}: {fname}: {length} lines")
                elif args.all:
                    print(f"{rel}:{first}: {fname}: {length} lines (justified: {reason})")
    if failures:
        print(f"function-length: {failures} function(s) over {args.limit} lines without a "
              f"'{MARKER}' comment", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
