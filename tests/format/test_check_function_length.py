#!/usr/bin/python3
"""Checks of tests/format/check_function_length.py (ctest format.function_length_checker).

Each case writes a hand-made C++ file into a temporary folder, runs the checker on the
folder as ctest does (a separate process) and compares its report with the lengths and
lines the case was built with: a function is counted from the first line of its
declaration through its closing brace.

    /usr/bin/python3 tests/format/test_check_function_length.py
"""

import os
import subprocess
import sys
import tempfile
import textwrap
import unittest

CHECKER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "check_function_length.py")


def function(name, lines, indent="", signature=None, filler="  int x = 0;"):
    """C++ text of a function spanning exactly `lines` lines (signature to closing brace)."""
    assert lines >= 3
    head = signature or "int %s(int a) {" % name
    body = [indent + filler] * (lines - 3)
    return "\n".join([indent + head] + body + [indent + "  return a;", indent + "}"]) + "\n"


class CheckerRun:
    def __init__(self, files, limit=None):
        self.dir = tempfile.TemporaryDirectory()
        for name, text in files.items():
            path = os.path.join(self.dir.name, name)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w", encoding="utf-8") as f:
                f.write(text)
        args = [sys.executable, CHECKER] + (["--limit", str(limit)] if limit else [])
        proc = subprocess.run(args + ["src"], cwd=self.dir.name, capture_output=True,
                              text=True, check=False)
        self.code = proc.returncode
        self.stdout = proc.stdout
        self.stderr = proc.stderr
        self.reports = [line for line in proc.stdout.splitlines() if "(limit " in line]
        self.dir.cleanup()


def run(text, limit=None, name="src/a.cpp"):
    return CheckerRun({name: text}, limit)


class Limits(unittest.TestCase):
    def test_81_line_function_fails_with_its_line_and_length(self):
        text = "#include <x>\n\n" + function("long_one", 81)
        r = run(text)
        self.assertEqual(r.code, 1, r.stdout)
        self.assertEqual(r.reports, ["src/a.cpp:3: long_one is 81 lines (limit 80)"])

    def test_80_line_function_passes(self):
        r = run(function("fits", 80) + "\n" + function("small", 5))
        self.assertEqual(r.code, 0, r.stdout)
        self.assertEqual(r.reports, [])

    def test_limit_option(self):
        text = function("f", 11) + function("g", 10)
        r = run(text, limit=10)
        self.assertEqual(r.code, 1)
        self.assertEqual(r.reports, ["src/a.cpp:1: f is 11 lines (limit 10)"])

    def test_multi_line_signature_and_template_line_count(self):
        sig = "template <typename T,\n          typename U = int>\nstd::vector<T>\nsplit(T a,\n      U b) {"
        body = "\n".join(["  x();"] * 75)
        text = "// comment above is not counted\n" + sig + "\n" + body + "\n  return {};\n}\n"
        # 5 signature lines + 75 + return + brace = 82
        r = run(text)
        self.assertEqual(r.reports, ["src/a.cpp:2: split is 82 lines (limit 80)"])

    def test_every_file_and_folder_is_searched(self):
        r = CheckerRun({"src/x/a.hpp": function("h", 90), "src/y/z/b.cpp": function("c", 85),
                        "src/y/notes.txt": function("t", 200)})
        self.assertEqual(r.reports, ["src/x/a.hpp:1: h is 90 lines (limit 80)",
                                     "src/y/z/b.cpp:1: c is 85 lines (limit 80)"])


class Ignored(unittest.TestCase):
    """Braces that open no block do not end a function early or start a new one."""

    def long_with(self, line):
        """An 81-line function whose filler lines are `line` (balanced only when ignored)."""
        return run(function("f", 81, filler="  " + line) + function("g", 4))

    def test_brace_in_string(self):
        r = self.long_with('s = "}}} {";')
        self.assertEqual(r.reports, ["src/a.cpp:1: f is 81 lines (limit 80)"])

    def test_brace_in_escaped_string(self):
        r = self.long_with('s = "\\"}\\\\";')
        self.assertEqual(r.reports, ["src/a.cpp:1: f is 81 lines (limit 80)"])

    def test_brace_in_line_comment(self):
        r = self.long_with("x = 1;  // } closes nothing")
        self.assertEqual(r.reports, ["src/a.cpp:1: f is 81 lines (limit 80)"])

    def test_brace_in_block_comment(self):
        r = self.long_with("/* } { } */ x = 1;")
        self.assertEqual(r.reports, ["src/a.cpp:1: f is 81 lines (limit 80)"])

    def test_brace_in_char_literal(self):
        r = self.long_with("c = '}'; d = '\\'';")
        self.assertEqual(r.reports, ["src/a.cpp:1: f is 81 lines (limit 80)"])

    def test_brace_in_raw_string(self):
        r = self.long_with('s = R"x(}" )" })x";')
        self.assertEqual(r.reports, ["src/a.cpp:1: f is 81 lines (limit 80)"])

    def test_digit_separator_is_not_a_char_literal(self):
        r = self.long_with("n = 1'000'000; c = '}';")
        self.assertEqual(r.reports, ["src/a.cpp:1: f is 81 lines (limit 80)"])

    def test_brace_in_preprocessor_line(self):
        r = self.long_with("x = 1;\n#define OPEN {")
        # each filler is now two lines: 1 + 2 * 78 + 2
        self.assertEqual(r.reports, ["src/a.cpp:1: f is 159 lines (limit 80)"])

    def test_multi_line_block_comment_inside_counts(self):
        text = "int f() {\n  /*\n" + "   }\n" * 80 + "  */\n  return 0;\n}\n"
        r = run(text)
        self.assertEqual(r.reports, ["src/a.cpp:1: f is 85 lines (limit 80)"])

    def test_braces_that_only_hide_in_comments_are_no_function(self):
        text = "// int g() {\n" + "// x;\n" * 90 + "// }\nint h() { return 1; }\n"
        self.assertEqual(run(text).code, 0)


class Kinds(unittest.TestCase):
    def test_lambda_counts_with_its_function(self):
        lam = ["  auto step = [&](int k) {"] + ["    k += 1;"] * 40 + ["    return k;", "  };"]
        text = "int outer(int a) {\n" + "\n".join(lam) + "\n" + "  a = 1;\n" * 36 + \
            "  return step(a);\n}\n"
        # 1 + 43 + 36 + 2 = 82 lines; the lambda's 43 lines are part of it, not reported alone
        r = run(text)
        self.assertEqual(r.reports, ["src/a.cpp:1: outer is 82 lines (limit 80)"])

    def test_member_functions_in_and_out_of_class(self):
        text = textwrap.dedent("""\
            namespace hexdyn {
            namespace {
            struct Solver : Base<int> {
             public:
              Solver(int a) : a_{a}, b_(a), c_{{1, 2}} {
            """) + "    x();\n" * 79 + textwrap.dedent("""\
              }
              int small() const { return a_; }
             private:
              int a_{0};
              std::vector<int> c_{1, 2};
            };
            }  // namespace
            """) + function("Solver::run", 83, signature="int Solver::run(int a) const noexcept {") + \
            "}  // namespace hexdyn\n"
        r = run(text)
        self.assertEqual(r.reports, ["src/a.cpp:5: Solver::Solver is 81 lines (limit 80)",
                                     "src/a.cpp:92: Solver::run is 83 lines (limit 80)"])

    def test_operator_and_destructor(self):
        text = function("op", 82, signature="bool operator==(const A& a, const A& b) {") + \
            "struct A {\n" + function("d", 81, indent="  ", signature="~A() {") + "};\n"
        r = run(text)
        self.assertEqual(r.reports, ["src/a.cpp:1: operator== is 82 lines (limit 80)",
                                     "src/a.cpp:84: A::~A is 81 lines (limit 80)"])

    def test_initialisers_and_enums_are_no_function(self):
        table = "const std::array<int, 90> kTable = {\n" + "    1,\n" * 90 + "};\n"
        braced = "const Foo kFoo{\n" + "    f(1),\n" * 90 + "};\n"
        enum = "enum class E {\n" + "  kA,\n" * 90 + "};\n"
        r = run(table + braced + enum + function("after", 81))
        self.assertEqual(r.reports, ["src/a.cpp:%d: after is 81 lines (limit 80)" % (3 * 92 + 1)])

    def test_lambda_at_namespace_scope_is_a_function(self):
        text = "const auto kStep = [](int a) {\n" + "  a += 1;\n" * 80 + "  return a;\n};\n"
        r = run(text)
        self.assertEqual(r.reports, ["src/a.cpp:1: kStep (lambda) is 83 lines (limit 80)"])

    def test_test_case_macro_is_a_function(self):
        text = function("t", 90, signature='TEST_CASE("paper run {", "[x]") {', filler="  CHECK(1);")
        r = run(text)
        self.assertEqual(r.reports, ["src/a.cpp:1: TEST_CASE is 90 lines (limit 80)"])

    def test_extern_c_block_is_a_scope(self):
        text = 'extern "C" {\n' + function("c_api", 81) + "}\n"
        self.assertEqual(run(text).reports, ["src/a.cpp:2: c_api is 81 lines (limit 80)"])


class Arguments(unittest.TestCase):
    def test_missing_path_is_an_error(self):
        proc = subprocess.run([sys.executable, CHECKER, "/nonexistent/folder"],
                              capture_output=True, text=True, check=False)
        self.assertEqual(proc.returncode, 2)
        self.assertEqual(len(proc.stderr.strip().splitlines()), 1, proc.stderr)


if __name__ == "__main__":
    unittest.main()
