#!/usr/bin/python3
"""Every document a source comment cites exists in the repository, with the heading it names.

    /usr/bin/python3 tests/docs/check_citations.py [--root DIR] [--skip PATH ...] [--list] [DIR ...]

Scans the text files under DIR ... (default: src tests bench analysis pipelines configs,
relative to the repository root) for

  - Markdown file names with an optional heading anchor, `docs/theory/allocation.md#exact-l1-penalty`,
    `bench/RESULTS.md`, `../docs/dev/testing.md`: the file must exist in the repository
    (resolved from the repository root or from the citing file's folder), and the anchor
    must be the slug of one of its headings;
  - README section citations, README "Output grid": README.md must have that heading;
  - citations of design notes outside the repository: the name of the old design file
    (D-E-S-I-G-N dot md) and paths into ../shared/. Each is an error wherever it appears.

Anchors follow GitHub's rules: the heading's text (inline code, emphasis and link targets
stripped) in lower case, every character that is not a letter, digit, space, '-' or '_'
removed, spaces turned into '-'; a repeated heading gets -1, -2, ... Explicit HTML anchors
(<a id="x">, <a name="x">) count too.

--skip PATH (repeatable, a file or folder relative to the root) leaves those files out of
the verdict: their problems are listed separately, as "skipped", and do not fail the check.
--list prints every citation found. Exit status: 0 when every citation holds, 1 otherwise,
with one line per problem, `file:line: what`.
"""
import argparse
import os
import re
import sys

DEFAULT_DIRS = ["src", "tests", "bench", "analysis", "pipelines", "configs"]
THIS_FILE = os.path.abspath(__file__)
MAX_BYTES = 4 * 1024 * 1024

# A Markdown file name, optionally with a #anchor. The name may start with ../ or ./.
MD_CITATION = re.compile(r"(?<![\w.\-/])((?:\.{1,2}/)*[\w\-]+(?:/[\w.\-]+)*\.md)(?![\w])(#[\w\-]+)?")
# README "Section", README, "Section", README 'Section', README “Section”.
README_SECTION = re.compile(r"\bREADME(?:\.md)?,?\s*[\"'“]([^\"'”]+)[\"'”]")
OLD_DESIGN = re.compile("DESIGN" + r"\.md")
OUTSIDE_REPO = re.compile(r"\.\./shared\b")
URL_BEFORE = re.compile(r"[a-z]+://\S*$")


def repository_root():
    here = os.path.dirname(THIS_FILE)
    return os.path.abspath(os.path.join(here, "..", ".."))


def slug(text):
    """GitHub's anchor for a heading text."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)  # links and images: their text
    text = re.sub(r"<[^>]+>", "", text)                       # inline HTML tags
    text = text.strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)                      # keeps letters, digits, _, -, space
    return text.replace(" ", "-")


def anchors_of(path, cache={}):
    """Every anchor of the Markdown file `path`."""
    if path in cache:
        return cache[path]
    anchors, seen = set(), {}
    in_fence = False
    previous = ""
    with open(path, encoding="utf-8", errors="replace") as f:
        lines = f.read().splitlines()
    for line in lines:
        stripped = line.strip()
        if re.match(r"^(```|~~~)", stripped):
            in_fence = not in_fence
            previous = ""
            continue
        if in_fence:
            continue
        heading = None
        m = re.match(r"^ {0,3}#{1,6}\s+(.*?)\s*#*\s*$", line)
        if m:
            heading = m.group(1)
        elif re.match(r"^ {0,3}(=+|-+)\s*$", line) and previous.strip() and \
                not previous.lstrip().startswith(("|", "-", "*", ">")):
            heading = previous.strip()
        if heading is not None:
            s = slug(heading)
            n = seen.get(s, 0)
            anchors.add(s if n == 0 else f"{s}-{n}")
            seen[s] = n + 1
        for a in re.findall(r"<a\s+(?:id|name)=\"([^\"]+)\"", line):
            anchors.add(a)
        previous = line
    cache[path] = anchors
    return anchors


def is_text(path):
    try:
        if os.path.getsize(path) > MAX_BYTES:
            return False
        with open(path, "rb") as f:
            return b"\0" not in f.read(8192)
    except OSError:
        return False


def files_under(root, dirs):
    for d in dirs:
        top = os.path.join(root, d)
        if os.path.isfile(top):
            yield top
            continue
        for folder, subfolders, names in os.walk(top):
            subfolders[:] = sorted(s for s in subfolders if not s.startswith(".") and s != "__pycache__")
            for name in sorted(names):
                path = os.path.join(folder, name)
                if os.path.abspath(path) != THIS_FILE and is_text(path):
                    yield path


def resolve(root, citing_file, name):
    """The cited file as an absolute path inside the repository, or None."""
    for base in (os.path.dirname(citing_file), root):
        candidate = os.path.normpath(os.path.join(base, name))
        inside = os.path.commonpath([candidate, root]) == root
        if inside and os.path.isfile(candidate):
            return candidate
    return None


def check_file(root, path, readme_anchors, listing):
    problems = []
    rel = os.path.relpath(path, root)
    with open(path, encoding="utf-8", errors="replace") as f:
        lines = f.read().splitlines()
    for number, line in enumerate(lines, 1):
        where = f"{rel}:{number}"
        for m in OLD_DESIGN.finditer(line):
            problems.append(f"{where}: cites {m.group(0)}, a file that is not in the repository; "
                            "cite the docs/ file and heading that hold the design")
        for m in OUTSIDE_REPO.finditer(line):
            problems.append(f"{where}: cites {m.group(0)}/…, outside the repository")
        for m in MD_CITATION.finditer(line):
            name, anchor = m.group(1), m.group(2)
            if URL_BEFORE.search(line[:m.start()]) or OLD_DESIGN.search(name):
                continue
            if line[m.start() - 1:m.start()] == "[" and line[m.end():m.end() + 2] == "](":
                continue  # the text of a Markdown link; its target is checked instead
            if listing is not None:
                listing.append(f"{where}: {name}{anchor or ''}")
            target = resolve(root, path, name)
            if target is None:
                problems.append(f"{where}: cites {name}, which does not exist in the repository")
                continue
            if anchor and anchor[1:] not in anchors_of(target):
                problems.append(f"{where}: cites {name}{anchor}, but {os.path.relpath(target, root)} "
                                f"has no heading with the anchor '{anchor[1:]}'")
        # A citation broken across lines: README at the end of one, "Section" on the next.
        joined = line
        if re.search(r"\bREADME,?\s*$", line) and number < len(lines):
            joined = line + " " + re.sub(r"^\s*(?:///?|#|\*|--)?\s*", "", lines[number])
        for m in README_SECTION.finditer(joined):
            section = m.group(1)
            if listing is not None:
                listing.append(f"{where}: README \"{section}\"")
            if readme_anchors is None:
                problems.append(f"{where}: cites README \"{section}\", but there is no README.md")
            elif slug(section) not in readme_anchors:
                problems.append(f"{where}: cites README \"{section}\", a section README.md does not have; "
                                "cite the docs/ file that holds it")
    return problems


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dirs", nargs="*", default=DEFAULT_DIRS,
                    help="folders or files to scan, relative to the root")
    ap.add_argument("--root", default=repository_root(), help="repository root")
    ap.add_argument("--skip", action="append", default=[],
                    help="a file or folder (relative to the root) whose problems are shown but do not fail")
    ap.add_argument("--list", action="store_true", help="print every citation found")
    args = ap.parse_args()

    root = os.path.abspath(args.root)
    readme = os.path.join(root, "README.md")
    readme_anchors = anchors_of(readme) if os.path.isfile(readme) else None
    skipped = [os.path.normpath(os.path.join(root, s)) for s in args.skip]
    listing = [] if args.list else None

    failing, shown = [], []
    count = 0
    for path in files_under(root, args.dirs):
        count += 1
        problems = check_file(root, path, readme_anchors, listing)
        apath = os.path.abspath(path)
        if any(apath == s or apath.startswith(s + os.sep) for s in skipped):
            shown += problems
        else:
            failing += problems

    if listing is not None:
        print("\n".join(listing))
    for p in shown:
        print(f"skipped: {p}")
    for p in failing:
        print(p)
    print(f"check_citations: {count} files, {len(failing)} problems"
          + (f" ({len(shown)} more in skipped files)" if args.skip else ""))
    return 1 if failing else 0


if __name__ == "__main__":
    sys.exit(main())
