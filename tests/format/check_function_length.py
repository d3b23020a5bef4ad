#!/usr/bin/python3
"""Function length check (ctest format.function_length): no C++ function over LIMIT lines.

    /usr/bin/python3 tests/format/check_function_length.py [--limit 80] PATH...

Each PATH is a C++ file or a folder searched recursively for *.cpp and *.hpp files.

What is a function: every definition with a body at namespace or class scope -- free
functions, member functions defined in or out of their class, constructors (their member
initialiser lists included) and destructors, operators, function templates, test-case
macros written as `NAME(...) {`, and a lambda assigned to a variable at namespace or class
scope. Everything inside a function's body -- lambdas, local classes and their member
functions -- counts as part of that function, never as a function of its own.

What is counted: the lines from the first line of the declaration (its `template <...>`
line, specifiers and return type included; comments and preprocessor lines before it not)
through the line of the closing brace of its body, both included: a function whose
declaration starts on line 10 and whose body closes on line 90 is 81 lines. Blank lines,
comment lines and preprocessor lines inside that span count.

How: a brace-matching scanner. Comments, string literals (raw strings too), character
literals and preprocessor lines are blanked first, so braces in them are ignored; then
each `{` at namespace or class scope is classified by the text before it (namespace,
class/struct/union, enum, initialiser, or a function body, told by a parameter list).
Both branches of an `#if` are scanned as they stand.

Output: one line per function over the limit, `FILE:LINE: FUNCTION is N lines (limit L)`
(LINE where the declaration starts, FUNCTION qualified by its enclosing classes), in file
order. Exit 0 when none is over the limit, 1 when some are, 2 on bad arguments or an
unreadable file.
"""

import argparse
import os
import re
import sys

SOURCE_SUFFIXES = (".cpp", ".hpp")


def blank_code(text):
    """Return text with comments, literals' contents and preprocessor lines as spaces.

    Line breaks are kept (so offsets and line numbers are those of the original); string
    and character literals keep their quotes with blanked contents, so `extern "C"` stays
    recognisable as `extern " "`.
    """
    out = list(text)
    n = len(text)
    i = 0
    at_line_start = True  # only whitespace since the last line break

    def blank(a, b):
        for k in range(a, b):
            if out[k] != "\n":
                out[k] = " "

    while i < n:
        c = text[i]
        if c == "\n":
            at_line_start = True
            i += 1
            continue
        if c in " \t\r\f\v":
            i += 1
            continue
        if at_line_start and c == "#":
            # A preprocessor line, with its backslash continuations (and comments in it).
            j = i
            while j < n:
                if text[j] == "\n" and text[j - 1] != "\\":
                    break
                if text.startswith("/*", j):
                    end = text.find("*/", j + 2)
                    j = n if end < 0 else end + 2
                    continue
                j += 1
            blank(i, j)
            i = j
            continue
        at_line_start = False
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            blank(i, j)
            i = j
            continue
        if text.startswith("/*", i):
            end = text.find("*/", i + 2)
            j = n if end < 0 else end + 2
            blank(i, j)
            i = j
            continue
        raw = re.match(r'(?:u8|u|U|L)?R"([^()\\\s]{0,16})\(', text[i:i + 40])
        if raw and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            delim = ")" + raw.group(1) + '"'
            start = i + raw.end()
            end = text.find(delim, start)
            j = n if end < 0 else end + len(delim)
            blank(start, j - 1)
            i = j
            continue
        if c == '"' or (c == "'" and not is_digit_separator(text, i)):
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            blank(i + 1, min(j, n))
            i = j + 1
            continue
        i += 1
    return "".join(out)


def is_digit_separator(text, i):
    """True when the quote at i is a digit separator (1'000), not a character literal."""
    j = i
    while j > 0 and (text[j - 1].isalnum() or text[j - 1] in "_."):
        j -= 1
    return j < i and text[j].isdigit()


def match_brace(code, i):
    """Offset of the `}` matching the `{` at i (len(code) when unbalanced)."""
    depth = 0
    for k in range(i, len(code)):
        if code[k] == "{":
            depth += 1
        elif code[k] == "}":
            depth -= 1
            if depth == 0:
                return k
    return len(code)


OPERATOR = re.compile(
    r"\boperator\s*(?:\(\s*\)|\[\s*\]|\"\"\s*\w+|new\s*\[\s*\]|delete\s*\[\s*\]|"
    r"<=>|->\*|->|<<=|>>=|<<|>>|<=|>=|==|!=|&&|\|\||\+\+|--|[-+*/%^&|~!=<>,]=?|"
    r"[\w:]+(?:\s*[*&]+)?)")
ACCESS = re.compile(r"^\s*(?:(?:public|private|protected|signals|slots)\s*:(?!:)\s*)+")
NOT_A_NAME = {"decltype", "alignas", "alignof", "sizeof", "noexcept", "requires",
              "__attribute__", "__declspec", "static_assert", "throw"}


def strip_template_heads(header):
    """header with every `template <...>` replaced by spaces (angle brackets balanced)."""
    out = header
    for m in re.finditer(r"\btemplate\s*<", header):
        depth = 0
        for k in range(m.end() - 1, len(header)):
            if header[k] == "<":
                depth += 1
            elif header[k] == ">":
                depth -= 1
                if depth == 0:
                    out = out[:m.start()] + " " * (k + 1 - m.start()) + out[k + 1:]
                    break
    return out


def top_level(header):
    """Yield (offset, char) of the header's characters outside (), [] and <>.

    `<` and `>` are taken as template brackets: the header is a declaration at namespace or
    class scope, where comparisons only occur inside parentheses. Arrows (`->`) do not close.
    """
    paren = angle = 0
    for k, ch in enumerate(header):
        if ch in "([":
            if paren == 0 and angle == 0:
                yield k, ch
            paren += 1
        elif ch in ")]":
            paren -= 1
        elif paren == 0 and ch == "<":
            angle += 1
        elif paren == 0 and ch == ">" and not header[k - 1] == "-":
            angle = max(0, angle - 1)
        elif paren == 0 and angle == 0:
            yield k, ch


def classify(header):
    """What a `{` after header opens: ('function', name), ('scope', name), ('skip', '')."""
    ops = []

    def keep_operator(m):
        ops.append(m.group(0))
        return "operator__%d__" % (len(ops) - 1)

    text = OPERATOR.sub(keep_operator, strip_template_heads(ACCESS.sub("", header)))
    words = set(re.findall(r"[A-Za-z_]\w*", text))
    if "namespace" in words or re.search(r'\bextern\s*"\s*"\s*$', text):
        return "scope", ""
    if text.count("(") != text.count(")"):
        return "skip", ""  # a brace inside parentheses: an argument or default value
    tops = list(top_level(text))
    top_text = "".join(ch for _, ch in tops)
    eq = next((k for k, ch in tops if ch == "=" and is_assignment(text, k)), None)
    if eq is not None:
        # An initialiser, unless it is a lambda assigned to a variable.
        if text[eq + 1:].lstrip().startswith("["):
            return "function", restore(last_identifier(text[:eq]), ops) + " (lambda)"
        return "skip", ""
    if "enum" in words:
        return "skip", ""
    if words & {"class", "struct", "union"} and "(" not in top_text:
        m = re.search(r"\b(?:class|struct|union)\b(?:\s*\[\[.*?\]\])?\s*([\w:]+)?", text)
        return "scope", (m.group(1) or "") if m else ""
    name = parameter_list_name(text)
    if name is None:
        return "skip", ""
    return "function", restore(name, ops)


def is_assignment(text, k):
    """True when the `=` at k is not part of ==, <=, >=, != or a compound assignment."""
    prev = text[k - 1] if k > 0 else " "
    nxt = text[k + 1] if k + 1 < len(text) else " "
    return prev not in "=!<>+-*/%^&|" and nxt != "="


def last_identifier(text):
    m = re.search(r"([~\w:]+)\s*$", text)
    return m.group(1) if m else "?"


def parameter_list_name(text):
    """Name before the header's parameter list, or None when the header has none.

    The parameter list is the first top-level `(` that follows a name (not decltype,
    alignas, ...). After its `)` come qualifiers, a trailing return type or a constructor's
    initialiser list; the `{` of a member initialiser (`: a_{x}`) is not a body.
    """
    for k, ch in top_level(text):
        if ch != "(":
            continue
        m = re.search(r"((?:~\s*)?[\w:]+(?:<[^(){};]*>)?)\s*$", text[:k])
        if not m:
            continue
        name = re.sub(r"\s+", "", m.group(1))
        base = re.sub(r"<.*", "", name).split("::")[-1].lstrip("~")
        if base in NOT_A_NAME or not base or base[0].isdigit():
            continue
        close = closing_paren(text, k)
        if close is None:
            return None
        rest = text[close + 1:]
        if re.match(r"\s*:(?!:)", strip_qualifiers(rest)):
            # A constructor's initialiser list: a `{` right after a name opens a member's
            # initialiser, a `{` after `)` or `}` the body.
            if re.search(r"[\w>]\s*$", rest):
                return None
        return name
    return None


def closing_paren(text, k):
    depth = 0
    for j in range(k, len(text)):
        if text[j] == "(":
            depth += 1
        elif text[j] == ")":
            depth -= 1
            if depth == 0:
                return j
    return None


def strip_qualifiers(rest):
    """rest with leading cv/ref qualifiers, noexcept(...), override, final and attributes."""
    prev = None
    while prev != rest:
        prev = rest
        rest = re.sub(r"^\s*(?:(?:const|volatile|override|final|mutable|constexpr)\b|&&|&)",
                      "", rest)
        rest = re.sub(r"^\s*noexcept\s*(?:\([^()]*\))?", "", rest)
        rest = re.sub(r"^\s*\[\[.*?\]\]", "", rest)
    return rest


def restore(name, ops):
    """name with the operators set aside by classify put back (`operator==`)."""
    return re.sub(r"operator__(\d+)__",
                  lambda m: re.sub(r"\s+", " ", ops[int(m.group(1))]).replace("operator ", "operator"),
                  name)


def without_blocks(text):
    """text with the contents of every balanced {...} removed (`a_{x}` -> `a_{}`)."""
    out = []
    depth = 0
    for ch in text:
        if ch == "}":
            depth -= 1
        if depth == 0:
            out.append(ch)
        if ch == "{":
            depth += 1
    return "".join(out)


def functions(text):
    """Yield (start_line, end_line, name) of every function defined in text (1-based)."""
    code = blank_code(text)
    line_of = []
    line = 1
    for ch in code:
        line_of.append(line)
        if ch == "\n":
            line += 1
    line_of.append(line)

    # The scope stack holds class names ('' for namespaces); header_start is where the
    # text before the next `{` begins.
    scopes = []
    header_start = 0
    i = 0
    n = len(code)
    while i < n:
        ch = code[i]
        if ch == ";":
            header_start = i + 1
        elif ch == "}":
            if scopes:
                scopes.pop()
            header_start = i + 1
        elif ch == "{":
            header = code[header_start:i]
            kind, name = classify(without_blocks(header))
            if kind == "scope":
                scopes.append(name)
                header_start = i + 1
            elif kind == "function":
                end = match_brace(code, i)
                offset = header_start + len(header) - len(ACCESS.sub("", header).lstrip())
                qualified = "::".join([s for s in scopes if s] + [name])
                yield line_of[offset], line_of[min(end, n - 1)], qualified
                i = end + 1
                header_start = i
                continue
            else:
                # An initialiser, enum or member initialiser: skipped, the header goes on
                # to the `;` or the body after it.
                i = match_brace(code, i) + 1
                continue
        i += 1


def source_files(paths):
    for path in paths:
        if os.path.isfile(path):
            yield path
        elif os.path.isdir(path):
            found = []
            for root, dirs, files in os.walk(path):
                dirs[:] = sorted(d for d in dirs if not d.startswith("."))
                found += [os.path.join(root, f) for f in files if f.endswith(SOURCE_SUFFIXES)]
            yield from sorted(found)
        else:
            raise FileNotFoundError(path)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--limit", type=int, default=80, help="most lines a function may have")
    parser.add_argument("paths", nargs="+", help="C++ files or folders (*.cpp, *.hpp)")
    args = parser.parse_args(argv)
    if args.limit < 1:
        print("function length: --limit must be >= 1", file=sys.stderr)
        return 2
    over = 0
    checked = 0
    try:
        for path in source_files(args.paths):
            with open(path, encoding="utf-8") as f:
                text = f.read()
            checked += 1
            for start, end, name in functions(text):
                length = end - start + 1
                if length > args.limit:
                    print("%s:%d: %s is %d lines (limit %d)" % (path, start, name, length,
                                                                 args.limit))
                    over += 1
    except (OSError, UnicodeDecodeError) as e:
        print("function length: cannot read %s" % e, file=sys.stderr)
        return 2
    if over:
        print("function length: %d function(s) over %d lines in %d files; split them into "
              "named steps" % (over, args.limit, checked))
        return 1
    print("function length: %d files, every function at most %d lines" % (checked, args.limit))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
