"""Writes the key tables of docs/user/configuration.md from the scene key table.

Every scene key is declared once, in the table of src/hexdyn/config/scene_key_table.hpp (its
rows in scene_key_rows*.cpp): path, kind, range or choices, unit, default, section and
meaning. The program hexdyn_scene_key_tables, built beside hexdyn, prints the Markdown table
of each section between marker lines; this script puts each in the region of the same name
of docs/user/configuration.md:

    <!-- BEGIN GENERATED: gait -->
    ...
    <!-- END GENERATED -->

and leaves the text around the regions alone.

    /usr/bin/python3 docs/gen_config_tables.py          # rewrite (build/hexdyn_scene_key_tables)
    /usr/bin/python3 docs/gen_config_tables.py --check  # exit 1 if a table is stale
    /usr/bin/python3 docs/gen_config_tables.py --tool PATH/hexdyn_scene_key_tables --check

Exit status: 0 up to date (or rewritten), 1 a region differs (--check), 2 the document or
the program cannot be used (missing or unknown regions, a program that fails).
"""

import argparse
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
DEFAULT_DOC = os.path.join(HERE, "user", "configuration.md")
DEFAULT_TOOL = os.path.join(ROOT, "build", "hexdyn_scene_key_tables")

BEGIN = re.compile(r"^<!-- BEGIN GENERATED: ([\w-]+) -->$")
END = "<!-- END GENERATED -->"


class DocumentError(Exception):
    """The document or the program cannot be used; exit status 2."""


def regions(lines, what):
    """{name: [lines between its markers]} of the marked regions in `lines`, in order."""
    out = {}
    name = None
    for no, line in enumerate(lines, 1):
        m = BEGIN.match(line)
        if m:
            if name is not None:
                raise DocumentError(f"{what}: line {no}: region '{m.group(1)}' inside "
                                    f"'{name}'")
            name = m.group(1)
            if name in out:
                raise DocumentError(f"{what}: line {no}: region '{name}' twice")
            out[name] = []
        elif line == END:
            if name is None:
                raise DocumentError(f"{what}: line {no}: {END} without a BEGIN")
            name = None
        elif name is not None:
            out[name].append(line)
    if name is not None:
        raise DocumentError(f"{what}: region '{name}' not closed")
    return out


def generated_tables(tool):
    """{section: [table lines]} printed by the program `tool`."""
    try:
        run = subprocess.run([tool], capture_output=True, text=True, check=False)
    except OSError as e:
        raise DocumentError(f"{tool}: {e.strerror} (build it: hexdyn_build "
                            "hexdyn_scene_key_tables)") from e
    if run.returncode != 0:
        raise DocumentError(f"{tool}: exit {run.returncode}: {run.stderr.strip()}")
    return regions(run.stdout.split("\n"), tool)


def rewrite(lines, tables):
    """`lines` with each region's content replaced by its table."""
    out = []
    skipping = False
    for line in lines:
        m = BEGIN.match(line)
        if m:
            out.append(line)
            out.extend(tables[m.group(1)])
            skipping = True
        elif line == END:
            skipping = False
            out.append(line)
        elif not skipping:
            out.append(line)
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--check", action="store_true",
                        help="exit 1 if a region differs instead of rewriting")
    parser.add_argument("--tool", default=DEFAULT_TOOL,
                        help="the program hexdyn_scene_key_tables (default: %(default)s)")
    parser.add_argument("--doc", default=DEFAULT_DOC, help="the page (default: %(default)s)")
    args = parser.parse_args()
    rel = os.path.relpath(args.doc, ROOT)
    try:
        with open(args.doc, encoding="utf-8") as f:
            lines = f.read().split("\n")
        tables = generated_tables(args.tool)
        present = regions(lines, rel)
        if set(present) != set(tables):
            missing = sorted(set(tables) - set(present))
            unknown = sorted(set(present) - set(tables))
            raise DocumentError(f"regions missing: {missing or 'none'}, unknown: "
                                f"{unknown or 'none'} (the table's sections: {sorted(tables)})")
    except (OSError, DocumentError) as e:
        print(f"gen_config_tables: {rel}: {e}", file=sys.stderr)
        return 2
    stale = [name for name in tables if present[name] != tables[name]]
    if args.check:
        for name in stale:
            print(f"gen_config_tables: {rel}: table '{name}' is out of date with "
                  "src/hexdyn/config/scene_key_table.hpp", file=sys.stderr)
        if stale:
            print("gen_config_tables: run /usr/bin/python3 docs/gen_config_tables.py",
                  file=sys.stderr)
        return 1 if stale else 0
    if stale:
        with open(args.doc, "w", encoding="utf-8") as f:
            f.write("\n".join(rewrite(lines, tables)))
        print(f"gen_config_tables: rewrote {rel}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
