"""Seeded mutations of configs/paper.yaml (a line dropped, duplicated or cut short, a value
replaced by another type, a character swapped for a YAML metacharacter) through
hexdyn.validate in process and `hexdyn validate` as a program: for every mutant both accept,
or the module raises the hexdyn.Error class matching the CLI's exit status (2: ConfigError
or IoError, 3: the others) with the CLI's message; no other exception comes through and the
interpreter survives them all.
    test_mutations.py HEXDYN_BINARY SOURCE_DIR [COUNT]"""

import os
import random
import subprocess
import sys
import tempfile

import hexdyn

HEXDYN, SRC = sys.argv[1], os.path.realpath(sys.argv[2])
COUNT = int(sys.argv[3]) if len(sys.argv) > 3 else 80
lines = open(os.path.join(SRC, "configs", "paper.yaml")).read().splitlines()
rng = random.Random(20)
REPLACEMENTS = ["", "[1, 2", "{a: 1}", "null", "-1e308", "nan", "'x'", "[]", "3/0", "1/3", "true", "&a *a"]


def mutate():
    out = list(lines)
    for _ in range(rng.randint(1, 3)):
        i = rng.randrange(len(out))
        kind = rng.randrange(4)
        if kind == 0:
            del out[i]
        elif kind == 1:
            out.insert(i, out[i])
        elif kind == 2 and ":" in out[i]:
            key = out[i].split(":", 1)[0]
            out[i] = f"{key}: {rng.choice(REPLACEMENTS)}"
        elif out[i]:
            j = rng.randrange(len(out[i]))
            out[i] = out[i][:j] + rng.choice(":-[]{}#&*!|>'\"%@`\t") + out[i][j + 1:]
    return "\n".join(out) + "\n"


accepted = refused = 0
with tempfile.TemporaryDirectory() as d:
    path = os.path.join(d, "mutant.yaml")
    for k in range(COUNT):
        text = mutate()
        with open(path, "w") as f:
            f.write(text)
        p = subprocess.run([HEXDYN, "validate", path], capture_output=True, text=True)
        try:
            hexdyn.validate(path)
            got = None
        except hexdyn.Error as e:
            got = e
        except BaseException as e:  # noqa: B036 (anything else is the failure)
            raise AssertionError(f"mutant {k}: {type(e).__name__}: {e}\n{text}")
        if p.returncode == 0:
            assert got is None, f"mutant {k}: the CLI accepts it, the module raises {got!r}"
            accepted += 1
            continue
        assert got is not None, f"mutant {k}: the CLI refuses it ({p.stderr.strip()}), the module accepts it"
        line = p.stderr.strip().splitlines()[-1]
        prefix = "hexdyn: error: "
        assert line.startswith(prefix), line
        assert str(got) == line[len(prefix):], f"mutant {k}:\n  module: {got}\n  cli:    {line}"
        input_error = isinstance(got, (hexdyn.ConfigError, hexdyn.IoError))
        assert (p.returncode == 2) == input_error, f"mutant {k}: exit {p.returncode}, raised {type(got).__name__}"
        refused += 1
print(f"python mutations: ok ({accepted} accepted, {refused} refused alike by module and CLI)")
