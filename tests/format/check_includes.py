#!/usr/bin/python3
"""No #include under src/hexdyn/ points up the layers.

    check_includes.py SOURCE_DIR            checks SOURCE_DIR/src; exit 1 naming each upward include
    check_includes.py SOURCE_DIR --self-test
        also checks that the check fails on a copy of src/ with an upward include injected

The allowed graph is read from src/CMakeLists.txt, the one place that declares it: every
hexdyn_layer(NAME FOLDER [PUBLIC ...] [PRIVATE ...]) makes the files of src/hexdyn/FOLDER/
the library hexdyn_NAME; hexdyn_split_layer(NAME FOLDER FILES a.cpp ... ) moves those files
(and their headers a.hpp ...) to hexdyn_NAME; target_link_libraries(T ...) adds links; an
add_executable(T .../FOLDER/x.cpp) makes x.cpp a file of T (of any of them, when
several compile it, each choosing its includes by #ifdef). A file of target T may include
the headers of T and of every hexdyn_* target that T links, directly or transitively
(public or private links alike: the layering is the link graph). A header belongs to the
target of its folder, or to the split target whose FILES name its stem (a_detail.hpp, the
internals of a.cpp, goes with a.cpp). A folder that no
declaration names is an error, so a new folder cannot escape the check.
"""
import argparse
import pathlib
import re
import shutil
import sys
import tempfile

INCLUDE = re.compile(r'^\s*#\s*include\s*[<"](hexdyn/[^">]+)[">]', re.M)
CALL = re.compile(r"\b(hexdyn_layer|hexdyn_split_layer|add_executable|target_link_libraries)"
                  r"\s*\(([^()]*)\)", re.S)
KEYWORDS = {"PUBLIC", "PRIVATE", "INTERFACE", "FILES"}
# Files of the root folder src/hexdyn/: the umbrella header (the package hexdyn::hexdyn,
# cmake/install.cmake) and the generated version header, usable by every layer.
ROOT_FILES = {"hexdyn.hpp", "version.hpp"}


def strip_comments(text):
    return "\n".join(line.split("#", 1)[0] for line in text.splitlines())


class Layers:
    """Targets, their links and which target each src/hexdyn/ file belongs to."""

    def __init__(self, cmake_text):
        self.links = {}  # target -> hexdyn_* targets it links
        self.folder_target = {}  # folder -> target of its files
        self.split = {}  # (folder, stem) -> split target
        self.file_targets = {}  # "folder/x.cpp" of an executable -> set of targets
        for kind, body in CALL.findall(strip_comments(cmake_text)):
            words = body.split()
            if len(words) < 2:
                continue
            if kind == "hexdyn_layer":
                name, folder = "hexdyn_" + words[0], words[1]
                self.folder_target[folder] = name
                self._link(name, words[2:])
            elif kind == "hexdyn_split_layer":
                name, folder = "hexdyn_" + words[0], words[1]
                rest = words[2:]
                if rest[0] == "FILES":
                    for w in rest[1:]:
                        if w in KEYWORDS:
                            break
                        self.split[(folder, pathlib.PurePath(w).stem)] = name
                self._link(name, rest)
            elif kind == "add_executable":
                self._link(words[0], [])
                for w in words[1:]:
                    m = re.search(r"hexdyn/([^/]+/[^/]+\.cpp)$", w)
                    if m:
                        self.file_targets.setdefault(m.group(1), set()).add(words[0])
            else:  # target_link_libraries of a target declared above
                self._link(words[0], words[1:])

    def _link(self, target, words):
        self.links.setdefault(target, set()).update(w for w in words if w.startswith("hexdyn_"))

    def reach(self, target):
        seen, todo = set(), [target]
        while todo:
            t = todo.pop()
            if t in seen:
                continue
            seen.add(t)
            todo.extend(self.links.get(t, ()))
        return seen

    def owners(self, rel):
        """Targets of the file src/hexdyn/<rel> ("io/output.cpp"); None for a root file."""
        parts = rel.split("/")
        if len(parts) == 1:
            return None
        folder, stem = parts[0], pathlib.PurePath(parts[-1]).stem
        stem = stem.removesuffix("_detail")  # a.cpp's internals, a_detail.hpp, go with a.cpp
        if rel in self.file_targets:
            return self.file_targets[rel]
        if (folder, stem) in self.split:
            return {self.split[(folder, stem)]}
        if folder in self.folder_target:
            return {self.folder_target[folder]}
        raise KeyError(f"src/hexdyn/{folder}/ is in no hexdyn_layer of src/CMakeLists.txt")


def violations(src):
    """Upward includes under src/hexdyn/ as lines "FILE:LINE: ... " (empty: none)."""
    layers = Layers((src / "CMakeLists.txt").read_text())
    root = src / "hexdyn"
    out = []
    for path in sorted(root.rglob("*")):
        if path.suffix not in (".cpp", ".hpp") or not path.is_file():
            continue
        rel = path.relative_to(root).as_posix()
        try:
            mine = layers.owners(rel)
        except KeyError as e:
            out.append(f"{path}: {e}")
            continue
        if mine is None:
            continue
        text = path.read_text()
        for m in INCLUDE.finditer(text):
            header = m.group(1)[len("hexdyn/"):]
            try:
                theirs = layers.owners(header)
            except KeyError as e:
                out.append(f"{path}: includes {m.group(1)}: {e}")
                continue
            if theirs is None:
                continue
            # A file compiled into several targets (cli/main.cpp: hexdyn and hexdyn_sweep_cli)
            # chooses its includes per target by #ifdef: any of them may reach the header.
            allowed = set().union(*(layers.reach(t) for t in mine))
            if not theirs & allowed:
                line = text.count("\n", 0, m.start()) + 1
                out.append(f"{path}:{line}: includes {m.group(1)} ({min(theirs)}), which "
                           f"{' or '.join(sorted(mine))} does not link (src/CMakeLists.txt)")
    return out


def self_test(source):
    """The check names each upward include injected (as line 1) into a copy of src/."""
    injected = {
        "process/paths.cpp": "hexdyn/io/h5io.hpp",  # process below io
        "core/common.cpp": "hexdyn/config/config.hpp",  # physics below config
        "config/config.cpp": "hexdyn/io/output.hpp",  # config below io
    }
    with tempfile.TemporaryDirectory() as tmp:
        copy = pathlib.Path(tmp) / "src"
        shutil.copytree(source / "src", copy)
        for rel, header in injected.items():
            f = copy / "hexdyn" / rel
            f.write_text(f'#include "{header}"\n' + f.read_text())
        found = violations(copy)
        missed = [rel for rel in injected if not any(f"/hexdyn/{rel}:1:" in v for v in found)]
        return [f"self-test: an injected upward include in {rel} was not found" for rel in missed]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("source", type=pathlib.Path)
    ap.add_argument("--self-test", action="store_true")
    args = ap.parse_args()
    problems = violations(args.source / "src")
    if args.self_test:
        problems += self_test(args.source)
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
