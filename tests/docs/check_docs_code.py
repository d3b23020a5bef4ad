#!/usr/bin/python3
"""Every file, CMake target and function the documents name exists in the tree.

    /usr/bin/python3 tests/docs/check_docs_code.py [--root DIR] [--cmake-targets FILE] [--list]
    /usr/bin/python3 tests/docs/check_docs_code.py --self-test

Reads docs/**/*.md, README.md and the other pages docs/README.md lists (bench/RESULTS.md;
not the changelog, which records the past) and checks, against the tree as it is when the check runs (nothing is listed here):

  files      a path from the repository root, `src/hexdyn/io/schema.hpp`, `tests/sweep/`,
             `configs/paper.yaml` (first folder one of src tests bench analysis pipelines
             configs bindings docs examples robots cmake), anywhere in the text, in code
             spans and in code blocks: the file or folder must exist;
             a relative source path, `io/output.cpp`, `sweep/checkpoint.hpp`,
             `hexdyn/results.py` (folder/.../name.cpp|hpp|h|py|sh): some file of the tree
             must end with /that path (src/hexdyn/io/output.cpp does for io/output.cpp);
             a bare source file name, `schema.hpp`, `check_result.py` (.cpp .hpp .h .py .sh):
             some file of the tree must have that name.
             A FILE.in template counts for FILE (version.hpp from version.hpp.in). Names
             with a placeholder (`*`, `<stage>`, `{a,b}`, `$VAR`, `...`) are not checked.
  links      the target of a Markdown link to a file of the repository, [api](docs/user/api.md):
             the file must exist (anchors are not checked here).
  targets    a `hexdyn_*` name in a code span or a code block: a CMake target (a library,
             executable or custom target of the build), or a CMake function defined in the
             tree (`hexdyn_layer`), or else an identifier of the C++ or Python code
             (a benchmark column, `hexdyn_us`). The targets come from --cmake-targets FILE,
             the list CMake writes at configure time (ctest passes it), and from a reading
             of the CMake files (alone when the list is not given; it also covers targets
             a configuration leaves out): add_library, add_executable, add_custom_target
             and pybind11_add_module with a literal name, calls of a CMake function that
             adds `PREFIX${ARG}` (hexdyn_layer core -> hexdyn_core), and executables named
             `PREFIX${VAR}` in a foreach over a list of `VAR=...` entries
             (HEXDYN_TEST_LAYERS -> hexdyn_tests_dynamics).
  functions  a code span (in running text, not a code block) that is an identifier the
             document presents as hexdyn's code:
               - a call, `run_scene(scene)`, `Result.write(path)`, `hexdyn.run(...)`:
                 the name before the parenthesis;
               - one identifier with an inner underscore, `load_sweep`, `check_cancelled`;
               - a CamelCase type name, `SweepCoordinator`, `ActiveSetExit`;
               - a qualified name, `Terrain::mean_slope_rad`, `Sweep.to_xarray`;
               - a name of the Python package, `hexdyn.open_result`, `hexdyn.xr.open_envelope`
                 (in code blocks too).
             Each part must occur as an identifier in the tree's code (C++, Python, shell
             and CMake files, comments included; Markdown, YAML and data files excluded);
             `hexdyn.NAME` must be a public name of the package (a top-level def, class,
             import or __all__ entry of bindings/python/hexdyn/__init__.py, a submodule, or
             a name the compiled module registers), `hexdyn.MODULE.NAME` a top-level name of
             that module. Not checked: spans qualified by another library (plt., np.,
             xr., xarray., ds., os., scipy., h5py., std::, Eigen::, ...), CMake's own
             commands (`add_test(...)`, `foreach(...)`), dotted lowercase names (scene keys
             `gait.duty_factor`, ctest names `docs.citations`), names with a leading,
             trailing or double underscore (`_mp4`, `PMPI_`, `H5F__close_cb`), ALL-CAPS
             names (environment variables, macros), file names. A page names what is not
             hexdyn's and would be checked with an HTML comment, <!-- not hexdyn: pmix_v4 -->,
             which exempts those names on that page.
  index      every Markdown page under docs/ is linked from docs/README.md, or from the
             README.md of a folder that docs/README.md links to (docs/validation/README.md).

Output: one line per broken reference, `docs/FILE:LINE: NAME not found (kind)`, and exit
status 1; exit 0 when every reference holds. --list prints every reference checked.
--self-test copies the tree's code into a temporary folder with a small docs tree, renames
a function and moves a file there, and checks that both are reported (and nothing else).
"""
import argparse
import ast
import os
import re
import shutil
import sys
import tempfile

THIS_FILE = os.path.abspath(__file__)
MD = ".md"  # file names below spelt with it, so that docs.citations does not take them for citations
README = f"README{MD}"
INDEX_PAGE = f"docs/{README}"
ROOT_DIRS = ["src", "tests", "bench", "analysis", "pipelines", "configs", "bindings", "docs",
             "examples", "robots", "cmake"]
SOURCE_EXT = (".cpp", ".hpp", ".h", ".py", ".sh")
CODE_EXT = (".cpp", ".hpp", ".h", ".c", ".py", ".sh", ".cmake", ".in", ".sbatch", ".pyi")
SKIP_DIRS = {".git", "results", "__pycache__"}
FOREIGN = {"plt", "np", "numpy", "xr", "xarray", "ds", "os", "sys", "scipy", "h5py", "pd",
           "pandas", "std", "Eigen", "yaml", "YAML", "json", "math", "f", "fig", "ax", "mpl",
           "matplotlib", "subprocess", "signal", "pathlib", "Path", "netCDF4", "h5netcdf",
           "pinocchio", "dart", "Ipopt", "MPI", "H5", "pybind11", "py", "Catch", "pytest",
           "unittest", "shutil", "tempfile", "re", "collections", "itertools", "functools"}
CMAKE_COMMANDS = {
    "add_compile_definitions", "add_compile_options", "add_custom_command", "add_custom_target",
    "add_dependencies", "add_executable", "add_library", "add_subdirectory", "add_test",
    "cmake_minimum_required", "cmake_language", "configure_file", "enable_testing", "file",
    "find_package", "foreach", "function", "get_target_property", "if", "include", "install",
    "list", "macro", "message", "option", "project", "set", "set_target_properties",
    "set_tests_properties", "string", "target_compile_definitions", "target_compile_options",
    "target_include_directories", "target_link_libraries", "target_sources", "while",
    "get_property", "set_property", "export", "catch_discover_tests", "pybind11_add_module",
    "write_basic_package_version_file", "configure_package_config_file", "find_dependency",
    "execute_process"}
CODE_SPAN = re.compile(r"(`+)(.+?)\1")
FENCE = re.compile(r"^\s*(```|~~~)")
ROOT_PATH = re.compile(r"(?<![\w./\-])((?:\.\./)*(?:%s)/[^\s`'\"()\[\],;:|\\]*)" % "|".join(ROOT_DIRS))
REL_SOURCE = re.compile(r"(?<![\w./\-$])((?:[A-Za-z_][\w\-]*/)+[\w\-]+\.(?:cpp|hpp|h|py|sh))(?![\w])")
BARE_SOURCE = re.compile(r"(?<![\w./\-$*])([A-Za-z_][\w\-]*\.(?:cpp|hpp|h|py|sh))(?![\w.]*\w)")
TARGET = re.compile(r"(?<![\w.$/-])(hexdyn_[A-Za-z0-9_]+)(?![\w<>{$*])")
LINK = re.compile(r"\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
NOT_HEXDYN = re.compile(r"<!--\s*not hexdyn:\s*(.*?)\s*-->")
BARE_ONLY = re.compile(r"^[A-Za-z_][\w\-]*\.(?:cpp|hpp|h|py|sh)$")
PACKAGE_NAME = re.compile(r"(?<![\w./\-])(hexdyn(?:\.[A-Za-z_]\w*)+)(?![\w.]*\w)(?!\.)")
PLACEHOLDER = re.compile(r"[*<>{}$…]|\.\.\.|~")
IDENT = r"[A-Za-z_]\w*"
NAME_SPAN = re.compile(r"^(%s(?:(?:\.|::)%s)*)(\(.*\))?$" % (IDENT, IDENT))


def repository_root():
    return os.path.abspath(os.path.join(os.path.dirname(THIS_FILE), "..", ".."))


# ----------------------------------------------------------------------------- the tree


class Tree:
    """What exists: files, file names, code identifiers, CMake targets and functions, the
    Python package's public names. Everything read from ROOT when the check runs."""

    def __init__(self, root, targets_file=None):
        self.root = root
        self.files = self._files()
        self.names = {os.path.basename(f) for f in self.files}
        self.words = self._code_words()
        self.cmake_functions, static_targets = self._cmake()
        self.targets_source = "static reading of the CMake files"
        self.targets = static_targets
        if targets_file:
            with open(targets_file, encoding="utf-8") as fh:
                # With the reading's: a target the configuration left out (no pybind11, no
                # benchmarks) is still the build's.
                self.targets = static_targets | {line.strip() for line in fh if line.strip()}
            self.targets_source = f"{targets_file} and the CMake files"
        self.package = self._package_names()

    def _files(self):
        out = []
        for dirpath, dirnames, filenames in os.walk(self.root):
            rel = os.path.relpath(dirpath, self.root)
            top = rel.split(os.sep)[0]
            dirnames[:] = [d for d in dirnames
                           if d not in SKIP_DIRS and not (rel == "." and d.startswith("build"))]
            if top in SKIP_DIRS:
                continue
            for name in filenames:
                out.append(os.path.normpath(os.path.join(rel, name)).replace(os.sep, "/"))
        return out

    def read(self, rel):
        try:
            with open(os.path.join(self.root, rel), encoding="utf-8", errors="replace") as fh:
                return fh.read()
        except OSError:
            return ""

    def _is_code(self, rel):
        base = os.path.basename(rel)
        return base == "CMakeLists.txt" or base.endswith(CODE_EXT) or \
            (rel.startswith((".githooks/", ".ci/")))

    def _code_words(self):
        words = set()
        for rel in self.files:
            if self._is_code(rel) and not rel.endswith("tests/docs/check_docs_code.py"):
                words.update(re.findall(IDENT, self.read(rel)))
        return words

    def _cmake(self):
        functions, targets = set(), set()
        cmake_files = [f for f in self.files
                       if os.path.basename(f) == "CMakeLists.txt" or f.endswith(".cmake")]
        texts = {f: self.read(f) for f in cmake_files}
        adders = {}  # CMake function name -> prefix of the target it adds from its first argument
        for text in texts.values():
            for m in re.finditer(r"(?is)\b(function|macro)\s*\(\s*(\w+)\s*(\w*)(.*?)\bend\1\s*\(",
                                 text):
                name, arg, body = m.group(2), m.group(3), m.group(4)
                functions.add(name)
                if arg:
                    a = re.search(r"add_(?:library|executable)\s*\(\s*([\w\-]*)\$\{%s\}" % arg, body)
                    if a:
                        adders[name] = a.group(1)
        for text in texts.values():
            body = re.sub(r"#[^\n]*", "", text)
            for m in re.finditer(r"\b(?:add_library|add_executable|add_custom_target|pybind11_add_module"
                                 r"|python3?_add_library)\s*\(\s*([\w\-]+)(?![\w\-$])", body):
                targets.add(m.group(1))
            for name, prefix in adders.items():
                for m in re.finditer(r"(?<![\w])%s\s*\(\s*([\w\-]+)" % re.escape(name), body):
                    targets.add(prefix + m.group(1))
            # set(exe PREFIX${var}) ... add_executable(${exe} ...) inside
            # foreach(entry IN LISTS LIST) over "var=..." entries.
            for m in re.finditer(r"\bset\s*\(\s*(\w+)\s+([\w\-]+)\$\{\w+\}\s*\)", body):
                var, prefix = m.group(1), m.group(2)
                if not re.search(r"add_(?:library|executable)\s*\(\s*\$\{%s\}" % var, body):
                    continue
                for lst in re.finditer(r"\bforeach\s*\(\s*\w+\s+IN\s+LISTS\s+(\w+)", body):
                    decl = re.search(r"\bset\s*\(\s*%s\s+(.*?)\)" % lst.group(1), body, re.S)
                    if decl:
                        for key in re.findall(r"\"([\w\-]+)=", decl.group(1)):
                            targets.add(prefix + key)
        return functions, targets

    def _package_names(self):
        """hexdyn.NAME -> set of NAME; hexdyn.MODULE -> names of that module."""
        pkg = "bindings/python/hexdyn"
        out = {"": set()}
        for rel in self.files:
            if not rel.startswith(pkg + "/"):
                continue
            sub = rel[len(pkg) + 1:]
            if "/" in sub:
                out[""].add(sub.split("/")[0])
                continue
            mod = re.sub(r"\.py(\.in)?$", "", sub)
            if mod == sub:
                continue
            if mod != "__init__":
                out[""].add(mod)
            out.setdefault("" if mod == "__init__" else mod, set()).update(
                top_level_names(self.read(rel)))
        # Names the compiled module registers: m.def("run", ...), new_exception(m, "IoError"...),
        # py::class_<...>(m, "RunHandle").
        for rel in self.files:
            if rel.startswith("bindings/") and rel.endswith(".cpp"):
                for a, b in re.findall(r"\(\s*m\s*,\s*\"(\w+)\"|m\.def\(\s*\"(\w+)\"",
                                      self.read(rel)):
                    out[""].add(a or b)
        return out

    def path_exists(self, rel):
        rel = rel.rstrip("/")
        full = os.path.join(self.root, rel)
        return os.path.exists(full) or os.path.exists(full + ".in")

    def suffix_exists(self, rel):
        tail = "/" + rel
        return any(f.endswith(tail) or f.endswith(tail + ".in") for f in self.files)

    def name_exists(self, name):
        return name in self.names or name + ".in" in self.names


def top_level_names(text):
    try:
        tree = ast.parse(text)
    except SyntaxError:
        return set(re.findall(r"^(?:def|class)\s+(\w+)", text, re.M))
    names = set()
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, ast.Assign):
            for t in node.targets:
                if isinstance(t, ast.Name):
                    names.add(t.id)
                    if t.id == "__all__" and isinstance(node.value, (ast.List, ast.Tuple)):
                        names.update(e.value for e in node.value.elts
                                     if isinstance(e, ast.Constant) and isinstance(e.value, str))
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            for a in node.names:
                names.add((a.asname or a.name).split(".")[0])
    return names


# ----------------------------------------------------------------------------- the documents


# The one page of the index that is not checked: a record of past changes, which names files
# and functions as they were then.
HISTORY = "CHANGELOG.md"


def indexed_pages_outside_docs(root):
    """The Markdown pages outside docs/ that docs/README.md links to, bench/RESULTS.md, apart
    from the README (always read) and the changelog (HISTORY)."""
    index = os.path.join(root, "docs", README)
    if not os.path.isfile(index):
        return []
    with open(index, encoding="utf-8") as f:
        text = f.read()
    out = []
    for target in re.findall(r"\]\(([^)#\s]+\.md)(?:#[^)]*)?\)", text):
        page = os.path.relpath(os.path.normpath(os.path.join(root, "docs", target)), root)
        page = page.replace(os.sep, "/")
        if (not page.startswith(("docs/", "../")) and page not in (README, HISTORY)
                and os.path.isfile(os.path.join(root, page)) and page not in out):
            out.append(page)
    return out


def documents(root):
    out = []
    if os.path.isfile(os.path.join(root, README)):
        out.append(README)
    for dirpath, dirnames, filenames in os.walk(os.path.join(root, "docs")):
        dirnames.sort()
        for name in sorted(filenames):
            if name.endswith(MD):
                out.append(os.path.relpath(os.path.join(dirpath, name), root).replace(os.sep, "/"))
    return out + indexed_pages_outside_docs(root)


def lines_of(text):
    """(line number, text, in a code block) for every line of a Markdown text."""
    fenced = False
    for n, line in enumerate(text.splitlines(), 1):
        if FENCE.match(line):
            fenced = not fenced
            continue
        yield n, line, fenced


def clean_path(token):
    token = token.split("#")[0]
    return token.rstrip(".,:;!?'\"")


def check_paths(tree, doc, n, line, fenced, report):
    for m in ROOT_PATH.finditer(line):
        token = clean_path(m.group(1))
        if PLACEHOLDER.search(token) or (fenced and token.startswith("..")):
            continue
        rel = os.path.normpath(os.path.join(os.path.dirname(doc), token)) if token.startswith("..") \
            else token
        report(n, token, "file", tree.path_exists(rel))
    spans = [s for _, s in CODE_SPAN.findall(line)]
    for text in [line] + spans:
        for m in REL_SOURCE.finditer(text):
            token = m.group(1)
            parts = token.split("/")
            if parts[0] in ROOT_DIRS or parts[0] in ("build", "results"):
                continue
            if PLACEHOLDER.search(text[max(0, m.start() - 1):m.end() + 1]):
                continue
            inner = [i for i, p in enumerate(parts) if p in ROOT_DIRS]
            if inner:  # an installed copy, share/hexdyn/src/hexdyn/io/schema.hpp
                rel = "/".join(parts[inner[0]:])
                report(n, rel, "file", tree.path_exists(rel))
            else:
                report(n, token, "file", tree.suffix_exists(token))
    if fenced:
        return
    # Bare file names: in running text and table cells, and code spans that are only a name
    # (not inside a command line, `c++ app.cpp ...`, which may name the reader's own files).
    prose = CODE_SPAN.sub(lambda m: m.group(2) if BARE_ONLY.match(m.group(2)) else " ", line)
    for m in BARE_SOURCE.finditer(prose):
        name = m.group(1)
        before = prose[max(0, m.start() - 1):m.start()]
        if before in ("/", "*", "<", "{", "$") or PLACEHOLDER.search(prose[m.end():m.end() + 1]):
            continue
        report(n, name, "file", tree.name_exists(name))


def check_links(tree, doc, n, line, report):
    for m in LINK.finditer(line):
        target = m.group(1)
        if re.match(r"^[a-z][a-z0-9+.\-]*:", target) or target.startswith("#"):
            continue
        path = target.split("#")[0]
        if not path:
            continue
        rel = os.path.normpath(os.path.join(os.path.dirname(doc), path)).replace(os.sep, "/")
        if rel.startswith("..") or rel.split("/")[0] in ("build", "results"):
            continue  # outside the repository, or written by a run (never committed)
        report(n, path, "link", tree.path_exists(rel))


def check_targets(tree, n, text, report):
    for m in TARGET.finditer(text):
        name = m.group(1)
        if name.endswith("_"):
            continue
        if name in tree.targets:
            report(n, name, "CMake target", True)
        elif name in tree.cmake_functions:
            report(n, name, "CMake function", True)
        else:
            report(n, name, "CMake target", name in tree.words)


def function_parts(span):
    """The name a code span presents as hexdyn's code, split into its parts, or None."""
    m = NAME_SPAN.match(span.strip())
    if not m:
        return None
    name, call = m.group(1), m.group(2)
    parts = re.split(r"\.|::", name)
    if parts[0] in FOREIGN or any(p.startswith("_") or p.endswith("_") or "__" in p for p in parts):
        return None
    if re.search(r"\.(cpp|hpp|h|py|sh|md|yaml|yml|h5|png|csv|txt|json|urdf|cff|in|conf|sbatch|gif"
                 r"|mp4|html|nc|log|toml|cfg)$", name):
        return None
    if call is not None:
        if len(parts) == 1 and parts[0] in CMAKE_COMMANDS:
            return None
        return parts
    if "::" in name:
        return parts
    if name.startswith("hexdyn.") and len(parts) > 1:
        return parts
    if "." in name:
        return parts if re.match(r"^[A-Z][a-z]\w*$", parts[0]) and parts[0] != "OUT" else None
    if name.isupper() or name.upper() == name:
        return None
    if re.match(r"^[a-z][a-z0-9]*(?:_[a-z0-9]+)+$", name):
        return parts
    if re.match(r"^[A-Z][a-z0-9]+(?:[A-Z][a-z0-9]*)+$", name):
        return parts
    return None


def check_function(tree, n, span, exempt, report):
    parts = function_parts(span)
    if not parts:
        return
    name = span.split("(")[0].strip()
    if name.startswith("hexdyn_"):
        return  # a CMake target (check_targets)
    if name in exempt or any(p in exempt for p in parts):
        return
    if name.startswith("hexdyn.") and len(parts) > 1:
        top = tree.package.get("", set())
        if parts[1] not in top:
            report(n, name, "Python name of the hexdyn package", False)
            return
        if len(parts) > 2 and parts[1] in tree.package:
            ok = parts[2] in tree.package[parts[1]]
            report(n, name, "Python name of the hexdyn package", ok)
            if not ok:
                return
            rest = parts[3:]
        else:
            rest = parts[2:]
        missing = [p for p in rest if p not in tree.words]
        report(n, name, "Python name of the hexdyn package", not missing)
        return
    missing = [p for p in parts if p not in tree.words]
    kind = "function" if "(" in span else "type" if re.match(r"^[A-Z]", parts[-1]) else "identifier"
    report(n, name, kind, not missing)


def index_problems(root):
    """Pages under docs/ that docs/README.md does not list: [(page, kind)]."""
    if not os.path.isfile(os.path.join(root, INDEX_PAGE)):
        return [INDEX_PAGE]

    def linked(md_rel):
        text = open(os.path.join(root, md_rel), encoding="utf-8", errors="replace").read()
        out = set()
        for m in LINK.finditer(text):
            path = m.group(1).split("#")[0]
            if not path or re.match(r"^[a-z][a-z0-9+.\-]*:", path):
                continue
            rel = os.path.normpath(os.path.join(os.path.dirname(md_rel), path)).replace(os.sep, "/")
            full = os.path.join(root, rel)
            if os.path.isdir(full):
                rel = rel.rstrip("/") + "/" + README
            out.add(rel)
        return out

    listed = linked(INDEX_PAGE)
    for page in list(listed):
        if os.path.basename(page) == README and page != INDEX_PAGE and page.startswith("docs/") \
                and os.path.isfile(os.path.join(root, page)):
            listed |= linked(page)
    missing = []
    for doc in documents(root):
        if doc.startswith("docs/") and doc != INDEX_PAGE and doc not in listed:
            missing.append(doc)
    return missing


def check(root, targets_file=None, list_all=False, out=sys.stdout):
    tree = Tree(root, targets_file)
    problems = []
    checked = 0
    for doc in documents(root):
        text = tree.read(doc)
        exempt = set()
        for m in NOT_HEXDYN.finditer(text):
            exempt.update(m.group(1).replace(",", " ").split())

        def report(n, name, kind, ok, doc=doc):
            nonlocal checked
            checked += 1
            if list_all:
                print(f"{doc}:{n}: {name} ({kind}){'' if ok else ' MISSING'}", file=out)
            if not ok:
                problems.append(f"{doc}:{n}: {name} not found ({kind})")

        for n, line, fenced in lines_of(text):
            check_paths(tree, doc, n, line, fenced, report)
            if fenced:
                check_targets(tree, n, line, report)
                for m in PACKAGE_NAME.finditer(line):
                    check_function(tree, n, m.group(1), exempt, report)
                continue
            check_links(tree, doc, n, line, report)
            for _, span in CODE_SPAN.findall(line):
                check_targets(tree, n, span, report)
                check_function(tree, n, span, exempt, report)
    for page in index_problems(root):
        problems.append(f"{page}:1: {page} not found (page in the index {INDEX_PAGE})")
    seen = set()
    unique = [p for p in problems if not (p in seen or seen.add(p))]
    for p in unique:
        print(p, file=out)
    return unique, checked, tree


# ----------------------------------------------------------------------------- self-test


def self_test(root):
    """A temporary copy of the code with a docs tree that names one function and one file;
    then the function renamed and the file moved: both must be reported."""
    failures = []
    with tempfile.TemporaryDirectory(prefix="hexdyn-docs-code-") as tmp:
        copy = os.path.join(tmp, "tree")
        for top in ("src", "bindings", "tests", "bench", "analysis", "pipelines", "configs",
                    "examples", "robots", "cmake", "CMakeLists.txt"):
            src = os.path.join(root, top)
            if os.path.isdir(src):
                shutil.copytree(src, os.path.join(copy, top),
                                ignore=shutil.ignore_patterns("__pycache__", "*.h5"))
            elif os.path.isfile(src):
                shutil.copy(src, os.path.join(copy, top))
        os.makedirs(os.path.join(copy, "docs", "dev"))
        notes = f"docs/dev/notes{MD}"
        with open(os.path.join(copy, INDEX_PAGE), "w") as fh:
            fh.write(f"# Index\n\n- [notes](dev/notes{MD})\n")
        with open(os.path.join(copy, notes), "w") as fh:
            fh.write("# Notes\n\n"
                     "`docs_probe_function(x)` is defined in `src/hexdyn/core/docs_probe.hpp`\n"
                     "(`core/docs_probe.hpp`, `docs_probe.hpp`), built into `hexdyn_core`,\n"
                     "read by `hexdyn.open_result`; `gait.duty_factor` is a key, not code.\n")
        probe = os.path.join(copy, "src", "hexdyn", "core", "docs_probe.hpp")
        with open(probe, "w") as fh:
            fh.write("#pragma once\ninline int docs_probe_function(int x) { return x; }\n")
        os.makedirs(os.path.join(copy, "docs", "theory"))
        orphan_page = f"docs/theory/orphan{MD}"
        orphan = os.path.join(copy, orphan_page)

        def run(label, expected):
            sink = open(os.devnull, "w")
            problems, checked, _ = check(copy, out=sink)
            sink.close()
            got = sorted(problems)
            if got != sorted(expected):
                failures.append(f"{label}: expected {sorted(expected)}, got {got}")
            return checked

        checked = run("the consistent tree", [])
        if checked < 6:
            failures.append(f"the consistent tree: only {checked} references checked, expected 6")
        # The function renamed in the code.
        with open(probe, "w") as fh:
            fh.write("#pragma once\ninline int docs_probe_renamed(int x) { return x; }\n")
        run("a renamed function",
            [f"{notes}:3: docs_probe_function not found (function)"])
        # The file moved to another folder.
        os.makedirs(os.path.join(copy, "src", "hexdyn", "probe_moved"), exist_ok=True)
        shutil.move(probe, os.path.join(copy, "src", "hexdyn", "probe_moved", "docs_probe.hpp"))
        with open(os.path.join(copy, "src", "hexdyn", "probe_moved", "docs_probe.hpp"), "w") as fh:
            fh.write("#pragma once\ninline int docs_probe_function(int x) { return x; }\n")
        run("a moved file",
            [f"{notes}:3: src/hexdyn/core/docs_probe.hpp not found (file)",
             f"{notes}:4: core/docs_probe.hpp not found (file)"])
        # A renamed CMake target and a page missing from the index.
        with open(os.path.join(copy, notes)) as fh:
            text = fh.read()
        with open(os.path.join(copy, notes), "w") as fh:
            fh.write(text.replace("core/docs_probe.hpp", "probe_moved/docs_probe.hpp")
                     .replace("hexdyn_core", "hexdyn_kernel"))
        with open(orphan, "w") as fh:
            fh.write("# Orphan\n")
        run("a renamed target and an unlisted page",
            [f"{notes}:4: hexdyn_kernel not found (CMake target)",
             f"{orphan_page}:1: {orphan_page} not found (page in the index {INDEX_PAGE})"])
    for f in failures:
        print(f"self-test: {f}")
    if not failures:
        print("self-test: a renamed function, a moved file, a renamed target and an unlisted "
              "page are each reported; the consistent tree passes")
    return 1 if failures else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--root", default=repository_root())
    ap.add_argument("--cmake-targets", help="file with one CMake target per line (from configure)")
    ap.add_argument("--list", action="store_true", help="print every reference checked")
    ap.add_argument("--self-test", action="store_true")
    args = ap.parse_args()
    root = os.path.abspath(args.root)
    if args.self_test:
        return self_test(root)
    targets = args.cmake_targets
    if targets and not os.path.isfile(targets):
        print(f"docs-code: {targets}: no such file (the CMake target list)", file=sys.stderr)
        return 1
    problems, checked, tree = check(root, targets, args.list)
    if problems:
        print(f"docs-code: {len(problems)} of {checked} references broken "
              f"(targets from {tree.targets_source})")
        return 1
    print(f"docs-code: {checked} references in {len(documents(root))} documents hold "
          f"(targets from {tree.targets_source})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
