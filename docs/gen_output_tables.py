"""Writes the tables of docs/user/output.md from src/hexdyn/io/schema.hpp.

The file layouts hexdyn writes (hexdyn-result/5, hexdyn-sweep/5, hexdyn-envelope/2,
hexdyn-replay/3, hexdyn-robustness/1) are declared once, in the C++ header src/hexdyn/io/schema.hpp and the parts
it includes. The declarations are those of the
Python reader (`hexdyn.results.SCHEMA`, from the module hexdyn._schema the build generates
from the compiled header), so the tables say what the writers write and what the reader
checks. The header's text gives only what the compiler drops: each table's "meaning" column
is the `///` comment of its declaration, and the section banner of each declaration says
which file kind's table it goes in. A replay file's datasets keep a result file's names for
the replayed motion: its tables follow its declaration lists (one table per list, under the
list's comment), and a dataset declared in the result's section is "as in" a result.

docs/user/output.md holds one region per file kind between marker comments:

    <!-- BEGIN GENERATED: result -->
    ...
    <!-- END GENERATED -->

(regions `result`, `sweep`, `envelope`, `replay`, `robustness`). This script rewrites the regions and leaves the
text around them alone.

    PYTHONPATH=build/python /usr/bin/python3 docs/gen_output_tables.py          # rewrite
    PYTHONPATH=build/python /usr/bin/python3 docs/gen_output_tables.py --check  # exit 1 if stale

(build/python: the package hexdyn of the build tree, or an installed one.)

Exit status: 0 up to date (or rewritten), 1 a region differs (--check), 2 the document or
the header cannot be used (missing or unknown markers, an unreadable header).
"""

import argparse
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(ROOT, "analysis"))
import hexdyn_path  # noqa: E402  the package hexdyn, from build/python when not installed
hexdyn_path.ensure()
from hexdyn.results import SCHEMA, AttributeSpec, DatasetSpec, FlagSpec

DEFAULT_SCHEMA = os.path.join(ROOT, "src", "hexdyn", "io", "schema.hpp")
DEFAULT_DOC = os.path.join(HERE, "user", "output.md")

BEGIN = re.compile(r"^<!-- BEGIN GENERATED: (\w+) -->$")
END = "<!-- END GENERATED -->"

# Section banners of the header: "// ====...==== hexdyn-result/5".
SECTION = re.compile(r"^// =+ (hexdyn-[a-z]+/\d+)\s*$", re.M)
# The name of each declaration and where it starts (the declarations themselves come from
# hexdyn.results.SCHEMA; this only places names in sections and finds their comments).
DECLARATION = re.compile(r"^inline\s+constexpr\s+[^;]*?\b(k\w+)\s*(?:=|\{)", re.M)

# Region name -> the header's constants of that file kind's schema name and version.
REGIONS = {"result": ("kResultSchema", "kResultSchemaVersion"),
           "sweep": ("kSweepSchema", "kSweepSchemaVersion"),
           "envelope": ("kEnvelopeSchema", "kEnvelopeSchemaVersion"),
           "replay": ("kReplaySchema", "kReplaySchemaVersion"),
           "robustness": ("kRobustnessSchema", "kRobustnessSchemaVersion")}
# Regions whose datasets are tabled by the declaration lists of their section (list_tables).
BY_LISTS = ("replay",)

# Which datasets of a result file are written when (the lists of schema.hpp).
RESULT_PRESENCE = {
    "kModelDatasets": "always",
    "kKinematicDatasets": "always",
    "kUrdfRobotDatasets": "URDF robot",
    "kSphereFootDatasets": "sphere feet",
    "kDynamicsDatasets": "dynamics",
    "kRequiredFrictionDatasets": "dynamics, unless output.required_friction is false",
    "kDriveTrainDatasets": "actuators",
    "kThermalDatasets": "actuators with a thermal model",
}


class DocumentError(Exception):
    """The document or the header cannot be used; exit status 2."""


# The parts the header includes at its end (`#include "hexdyn/io/schema_*.hpp"`).
SCHEMA_PART = re.compile(r'^#include "hexdyn/io/(schema_\w+\.hpp)".*$', re.M)


def read_schema_text(path):
    """The text of the schema header at `path` with the parts it includes at its end
    (read from the same folder) put in place."""
    with open(path, encoding="utf-8") as f:
        text = f.read()

    def part(m):
        with open(os.path.join(os.path.dirname(path), m.group(1)), encoding="utf-8") as f:
            return f.read()
    return SCHEMA_PART.sub(part, text)


def declaration_comments(text):
    """{constant name: its documentation}: the `///` lines right above the declaration
    and the `///<` comments inside it, joined into one line."""
    lines = text.split("\n")
    starts = {}
    for m in DECLARATION.finditer(text):
        starts[text.count("\n", 0, m.start())] = m.group(1)
    comments = {}
    for line_no, name in starts.items():
        above = []
        k = line_no - 1
        while k >= 0 and lines[k].lstrip().startswith("///") and \
                not lines[k].lstrip().startswith("///<"):
            above.insert(0, lines[k].lstrip()[3:].strip())
            k -= 1
        inside = []
        k = line_no
        while k < len(lines):
            m = re.search(r"///<\s*(.*)$", lines[k])
            if m:
                inside.append(m.group(1).strip())
            if ";" in re.sub(r"//.*$", "", lines[k]):
                break
            k += 1
        comments[name] = " ".join(above + inside).strip()
    return comments


def declaration_sections(text):
    """{constant name: file kind of the header section it is declared in}."""
    banners = [(m.start(), m.group(1)) for m in SECTION.finditer(text)]
    sections = {}
    for m in DECLARATION.finditer(text):
        kind = None
        for pos, name in banners:
            if pos < m.start():
                kind = name
        sections[m.group(1)] = kind
    return sections


def cell(text):
    """Table cell text: one line, pipes escaped."""
    return " ".join(str(text).split()).replace("|", "\\|")


def shape_text(shape):
    return "(" + ", ".join(str(d) for d in shape) + ")" if shape else "()"


def attribute_meaning(attr, schema, kind):
    """What a /meta attribute of a `kind` file holds: the schema name and version for
    `schema` and `schema_version`; else the comment of the AttributeSpec or, in the
    section that declares it, of the name constant it was built from; an attribute
    declared in another section is "as in" that file kind."""
    if attr.name == "schema":
        return f"`{kind}`"
    if attr.name == "schema_version":
        return str(schema.version[kind])
    home = schema.sections.get(attr.const)
    if schema.comments.get(attr.const):
        return schema.comments[attr.const]
    if home != kind:
        return f"as in `{home}`"
    for name, value in schema.decls.items():
        if name.startswith("kAttr") and value == attr.name and schema.comments.get(name):
            # "string, hexdyn release": the type is the table's own column.
            return re.sub(r"^(string|int64|double)\b,?\s*", "", schema.comments[name])
    return ""


class Schema:
    """The declarations (hexdyn.results.SCHEMA), their comments and sections in the header
    text `text`."""

    def __init__(self, text, decls=SCHEMA):
        self.decls = decls
        self.comments = declaration_comments(text)
        self.sections = declaration_sections(text)
        unknown = sorted(set(self.sections) ^ set(decls))
        if unknown:
            raise DocumentError(f"schema header: declarations {', '.join(unknown)} differ from "
                                "the package's hexdyn._schema (rebuild: it is generated from "
                                "the header)")
        self.kind = {r: self.decls[name] for r, (name, _) in REGIONS.items()}
        self.version = {self.decls[name]: self.decls[v] for name, v in REGIONS.values()}
        missing = [k for k in self.kind.values() if k not in self.sections.values()]
        if missing:
            raise DocumentError(f"schema header: no section banner for {', '.join(missing)}")

    def in_section(self, kind, cls):
        return [(n, v) for n, v in self.decls.items()
                if self.sections.get(n) == kind and isinstance(v, cls)]

    def lists_in_section(self, kind):
        return [(n, v) for n, v in self.decls.items()
                if self.sections.get(n) == kind and isinstance(v, list)]


def meta_table(schema, kind):
    lists = [(n, v) for n, v in schema.lists_in_section(kind) if n.endswith("MetaAttributes")]
    if len(lists) != 1:
        raise DocumentError(f"schema header: expected one *MetaAttributes list in {kind}")
    rows = ["| attribute of `/meta` | type | meaning |", "|---|---|---|"]
    for attr in lists[0][1]:
        rows.append(f"| `{attr.name}` | {attr.element} | "
                    f"{cell(attribute_meaning(attr, schema, kind))} |")
    return rows


def other_attributes_table(schema, kind):
    meta = {id(a) for n, v in schema.lists_in_section(kind) if n.endswith("MetaAttributes")
            for a in v}
    attrs = [(n, a) for n, a in schema.in_section(kind, AttributeSpec)
             if id(a) not in meta and a.object != schema.decls["kMetaGroup"]]
    if not attrs:
        return []
    rows = ["| object | attribute | type | meaning |", "|---|---|---|---|"]
    for name, a in attrs:
        rows.append(f"| `{a.object}` | `{a.name}` | {a.element} | "
                    f"{cell(schema.comments.get(name, ''))} |")
    return rows


def dataset_table(schema, kind, presence=None, datasets=None):
    """The table of `datasets` ((name, DatasetSpec) pairs; default: those declared in the
    section of `kind`); a dataset declared in another section is "as in" that file kind."""
    if datasets is None:
        datasets = schema.in_section(kind, DatasetSpec)
    head = "| path | shape | dimensions | type | units | long_name |"
    rule = "|---|---|---|---|---|---|"
    if presence is not None:
        head, rule = head + " written |", rule + "---|"
    rows = [head + " meaning |", rule + "---|"]
    for name, d in datasets:
        dims = "(" + ", ".join(d.dims) + ")" if d.dims else "()"
        units = {"": "—", "key": "of the key"}.get(d.units, f"`{d.units}`")
        row = (f"| `{d.path}` | {shape_text(d.shape)} | {cell(dims)} | {d.element} | "
               f"{cell(units)} | {cell(d.long_name)} |")
        if presence is not None:
            row += f" {presence.get(name, '')} |"
        home = schema.sections.get(name)
        meaning = schema.comments.get(name, "") if home == kind else f"as in `{home}`"
        rows.append(row + f" {cell(meaning)} |")
    return rows


def list_tables(schema, kind):
    """One dataset table per declaration list of datasets in the section of `kind`, in the
    header's order, each under the list's comment: a file kind (hexdyn-replay/3) that holds
    datasets of a result file's names besides its own. The section's datasets that no list
    holds follow in a last table (the reader checks them when present)."""
    lines, listed = [], set()
    for name, items in schema.lists_in_section(kind):
        if not items or not all(isinstance(d, DatasetSpec) for d in items):
            continue
        lines += [cell(schema.comments.get(name, "") or f"`{name}`").rstrip(".") + ":", ""]
        lines += dataset_table(schema, kind, datasets=[(d.name, d) for d in items]) + [""]
        listed.update(d.name for d in items)
    unlisted = [(n, d) for n, d in schema.in_section(kind, DatasetSpec) if n not in listed]
    if unlisted:
        lines += ["Declared in no list (written when the writer has them):", ""]
        lines += dataset_table(schema, kind, datasets=unlisted) + [""]
    return lines[:-1]


def result_presence(schema, kind):
    presence = {}
    for list_name, items in schema.lists_in_section(kind):
        if list_name in RESULT_PRESENCE:
            for d in items:
                presence.setdefault(d.name, RESULT_PRESENCE[list_name])
    return presence


# What the robot's sizes in the shapes are, by the file kind's dataset of names.
SIZE_SENTENCES = {
    "L": "L is the number of legs of the robot, the length of `{names}`",
    "J": "J the number of its joints, the length of `{names}`",
}


def size_sentence(schema, kind, datasets):
    """The sentence saying what the size symbols L and J of `datasets` ((name, DatasetSpec)
    pairs) are in a `kind` file: the lengths of the names it stores (a sweep: /joint_names);
    [] when no shape uses them."""
    used = {d for _, spec in datasets for d in spec.shape if d in SIZE_SENTENCES}
    if not used:
        return []
    sweep = kind == schema.kind["sweep"]
    names = {"L": schema.decls["kModelLegNames"].path,
             "J": schema.decls["kSweepJointNames" if sweep else "kModelJointNames"].path}
    parts = [SIZE_SENTENCES[s].format(names=names[s]) for s in ("L", "J") if s in used]
    if len(parts) == 1:
        parts[0] = parts[0].replace("J the number of its", "J is the number of the robot's")
    hexapod = {"L": "6", "J": "18"}
    example = " and ".join(hexapod[s] for s in ("L", "J") if s in used)
    return [("; ".join(parts) + f" ({example} for a hexapod of three-joint legs)."), ""]


def region_lines(schema, region):
    kind = schema.kind[region]
    lines = meta_table(schema, kind) + [""]
    datasets = schema.in_section(kind, DatasetSpec) + [
        (d.name, d) for _, items in schema.lists_in_section(kind) for d in items
        if isinstance(d, DatasetSpec)]
    lines += size_sentence(schema, kind, datasets)
    if region in BY_LISTS:
        lines += list_tables(schema, kind)
    else:
        presence = result_presence(schema, kind) if region == "result" else None
        lines += dataset_table(schema, kind, presence)
    flags = schema.in_section(kind, FlagSpec)
    if flags:
        lines += ["", "CF flags (`flag_values` 0, 1, ... and `flag_meanings`):", "",
                  "| dataset | flag_meanings |", "|---|---|"]
        lines += [f"| `{f.path}` | {' '.join(f'{i} `{w}`' for i, w in enumerate(f.meanings))} |"
                  for _, f in flags]
    other = other_attributes_table(schema, kind)
    if other:
        lines += ["", "Other attributes:", ""] + other
    if region == "sweep":
        codes = ", ".join(f"{i} `{s}`" for i, s in enumerate(schema.decls["kScenarioStatusNames"]))
        lines += ["", f"Scenario status codes (`/scenarios/status`): {codes}."]
    return lines


def render(doc_text, schema):
    """The document with every region regenerated; {region: new lines} alongside."""
    out, regions, inside = [], {}, None
    for line_no, line in enumerate(doc_text.split("\n"), 1):
        m = BEGIN.match(line)
        if inside is None:
            out.append(line)
            if m:
                if m.group(1) not in REGIONS:
                    raise DocumentError(f"line {line_no}: unknown generated region "
                                        f"{m.group(1)!r} (known: {', '.join(REGIONS)})")
                if m.group(1) in regions:
                    raise DocumentError(f"line {line_no}: region {m.group(1)!r} twice")
                inside = m.group(1)
                regions[inside] = region_lines(schema, inside)
                out += regions[inside]
            elif line == END:
                raise DocumentError(f"line {line_no}: {END} without a BEGIN")
        elif line == END:
            out.append(line)
            inside = None
        elif m:
            raise DocumentError(f"line {line_no}: BEGIN inside region {inside!r}")
    if inside is not None:
        raise DocumentError(f"region {inside!r} has no {END}")
    absent = [r for r in REGIONS if r not in regions]
    if absent:
        raise DocumentError(f"no generated region for {', '.join(absent)}")
    return "\n".join(out)


def stale_regions(old_text, new_text):
    """Names of the regions whose text differs between the two documents."""
    def regions(text):
        found, inside = {}, None
        for line in text.split("\n"):
            m = BEGIN.match(line)
            if m and inside is None:
                inside = m.group(1)
                found[inside] = []
            elif line == END:
                inside = None
            elif inside is not None:
                found[inside].append(line)
        return found
    old, new = regions(old_text), regions(new_text)
    return [r for r in new if old.get(r) != new[r]]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--check", action="store_true",
                    help="write nothing; exit 1 naming each region that is out of date")
    ap.add_argument("--schema", default=DEFAULT_SCHEMA, help="the schema header")
    ap.add_argument("--doc", default=DEFAULT_DOC, help="the document to rewrite")
    args = ap.parse_args(argv)
    rel = os.path.relpath(args.doc, ROOT)
    try:
        schema = Schema(read_schema_text(args.schema))
        with open(args.doc, encoding="utf-8") as f:
            old = f.read()
        new = render(old, schema)
    except (OSError, ValueError, KeyError, DocumentError) as e:
        print(f"gen_output_tables: {rel}: {e}", file=sys.stderr)
        return 2
    if args.check:
        stale = stale_regions(old, new)
        if stale or new != old:
            for r in stale:
                print(f"gen_output_tables: {rel}: table '{r}' is out of date with "
                      f"{os.path.relpath(args.schema, ROOT)}", file=sys.stderr)
            print("gen_output_tables: run /usr/bin/python3 docs/gen_output_tables.py",
                  file=sys.stderr)
            return 1
        return 0
    if new != old:
        tmp = args.doc + ".tmp"
        with open(tmp, "w", encoding="utf-8") as f:
            f.write(new)
        os.replace(tmp, args.doc)
        print(f"gen_output_tables: rewrote {rel}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
