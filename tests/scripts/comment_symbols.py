#!/usr/bin/env python3
"""Every symbol a comment in include/ names still exists in include/: run by ctest
(tests/CMakeLists.txt) as

    comment_symbols.py INCLUDE_DIR        check the headers under INCLUDE_DIR
    comment_symbols.py --self-test        check the checker on small headers written here

What a comment names:
- a qualified name, `Class::member` or `ns::Class::member` (also split over two comment lines);
- a backticked identifier, call or member chain: `set_simd`, `lower()`, `options.tolerance`.
Each part of a qualified name, and each identifier of a backticked one, must be declared somewhere
in the headers: a class, struct, union, enum, namespace or alias name, a macro, an enumerator, or
a name that follows a type (a function, member, variable or parameter). A backticked identifier
may also be a string literal of the headers (a scene file's key or value, an option's name).

Not checked (names that are not ours):
- qualified names under EXTERNAL (std::, Eigen::, ...) and the CMake targets in CMAKE_TARGETS;
- backticked text that is not an identifier (XML, JSON, formulas, messages);
- in a comment that cites FOSSSim, the FOSSSim sources' own names: a member in lowerCamelCase
  (FOSSSim's style; ours is snake_case), a family written `Class::prefix*`, or a class that is
  not declared here.
A stale name is reported as file:line and the name; the exit status is 1 when there is one.
Only the standard library."""

import os
import re
import sys
import tempfile

EXTERNAL = {"std", "Eigen", "pugi", "nlohmann", "pybind11", "doctest", "OpenMP", "CLI"}
# Names of other libraries used without their namespace (Eigen's solver classes).
EXTERNAL_CLASSES = {"SimplicialLLT", "SimplicialLDLT"}
CMAKE_TARGETS = {"massspring::massspring", "massspring::io", "massspring::cholmod"}
KEYWORDS = {"return", "else", "case", "throw", "new", "delete", "goto", "operator", "sizeof",
            "typename", "template", "co_return", "not", "and", "or", "public", "private",
            "protected", "do", "using", "if", "while", "for", "switch"}


def split_source(text):
    """(code, strings, comments) of a C++ source: code with comments blanked and string literals
    emptied (line breaks kept, so offsets keep their line), the string literals' contents, and
    the comments as (line, text) with one entry per comment line."""
    code, strings, comments = [], [], []
    i, n, line = 0, len(text), 1
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            end = text.find("\n", i)
            end = n if end < 0 else end
            comments.append((line, text[i:end]))
            i = end
        elif text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end < 0 else end + 2
            for k, part in enumerate(text[i:end].split("\n")):
                comments.append((line + k, part))
            code.append("\n" * text.count("\n", i, end))
            line += text.count("\n", i, end)
            i = end
        elif c == 'R' and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or
                                                                      text[i - 1] == "_")):
            open_paren = text.find("(", i)
            delimiter = ")" + text[i + 2:open_paren] + '"'
            end = text.find(delimiter, open_paren)
            end = n if end < 0 else end + len(delimiter)
            strings.append(text[open_paren + 1:end - len(delimiter)])
            code.append('""' + "\n" * text.count("\n", i, end))
            line += text.count("\n", i, end)
            i = end
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            if c == '"':
                strings.append(text[i + 1:j])
            code.append(c + c)
            i = j + 1
        else:
            if c == "\n":
                line += 1
            code.append(c)
            i += 1
    return "".join(code), strings, comments


DECLARATIONS = [
    re.compile(r"\b(?:class|struct|union|enum(?:\s+class|\s+struct)?)\s+"
               r"(?:\[\[[^\]]*\]\]\s*)?(\w+)"),
    re.compile(r"\busing\s+(\w+)\s*="),
    re.compile(r"#\s*define\s+(\w+)"),
    # a name after a type: `T name(`, `T& name;`, `T* name =`, `T name{`, `T name[`, `T name,`
    re.compile(r"(?:(\w+)|[>&*\]}])\s*[&*]*\s+~?(\w+)\s*(?:\(|;|=|\{|\[|,|\))"),
    # a constructor or a conversion in its class: `explicit Name(`, `Name(` alone on a line
    re.compile(r"(?:^|\bexplicit\s+)\s*(\w+)\s*\(", re.M),
]
NAMESPACE = re.compile(r"\bnamespace\s+(\w+(?:::\w+)*)")
ENUM_BODY = re.compile(r"\benum(?:\s+class|\s+struct)?\s+\w+\s*(?::\s*[\w:]+\s*)?\{([^}]*)\}")


def declared_names(include_dir):
    """The names declared in the headers under include_dir, and their string literals."""
    names, literals = set(), set()
    for root, _, files in os.walk(include_dir):
        for name in files:
            if not name.endswith((".hpp", ".h")):
                continue
            with open(os.path.join(root, name), encoding="utf-8") as handle:
                code, strings, _ = split_source(handle.read())
            literals.update(strings)
            for pattern in DECLARATIONS:
                for match in pattern.finditer(code):
                    groups = match.groups()
                    if len(groups) == 2:  # the name-after-a-type pattern
                        if groups[0] in KEYWORDS:
                            continue
                        names.add(groups[1])
                    else:
                        names.add(groups[0])
            for match in NAMESPACE.finditer(code):
                names.update(match.group(1).split("::"))
            for body in ENUM_BODY.finditer(code):
                for item in body.group(1).split(","):
                    word = re.match(r"\s*(\w+)", item)
                    if word:
                        names.add(word.group(1))
    return names - KEYWORDS, literals


def comment_blocks(comments):
    """Consecutive comment lines joined: [(first line, [(line, text without the markers)])]."""
    blocks = []
    for line, text in comments:
        stripped = re.sub(r"^\s*(?://+!?<?|/\*+|\*+/?)?", "", text)
        stripped = re.sub(r"\*+/\s*$", "", stripped)
        if blocks and blocks[-1][-1][0] == line - 1:
            blocks[-1].append((line, stripped))
        else:
            blocks.append([(line, stripped)])
    return blocks


QUALIFIED = re.compile(r"(?<![\w:])(~?\w+(?:::[ \t]*~?\w+)+)(\*)?")
BACKTICKED = re.compile(r"`([^`\n]+)`")
PLAIN_SYMBOL = re.compile(r"^(\w+(?:(?:\.|::)\w+)*)(?:\(\))?$")
CAMEL = re.compile(r"^[a-z][a-z0-9]*[A-Z]")


def stale_names(path, names, literals):
    """([(line, name, why)] for the names the comments of `path` give that do not exist, the
    number of names checked)."""
    with open(path, encoding="utf-8") as handle:
        _, _, comments = split_source(handle.read())
    found, checked = [], 0
    for block in comment_blocks(comments):
        # The block as one text, with the line each character came from.
        text, lines = "", []
        for line, part in block:
            text += part + " "
            lines += [line] * (len(part) + 1)
        cites_fosssim = "FOSSSim" in text
        seen_spans = []
        for match in BACKTICKED.finditer(text):
            seen_spans.append(match.span())
            symbol = PLAIN_SYMBOL.match(match.group(1).strip())
            if not symbol:
                continue
            parts = re.split(r"\.|::", symbol.group(1))
            if parts[0] in EXTERNAL or parts[0] in EXTERNAL_CLASSES or \
                    "::".join(parts) in CMAKE_TARGETS:
                continue
            if "::" in symbol.group(1):
                continue  # checked as a qualified name below
            checked += 1
            missing = [p for p in parts
                       if not p.isdigit() and p not in names and p not in literals]
            if missing:
                found.append((lines[match.start()], match.group(1),
                              "not declared in include/: " + ", ".join(missing)))
        for match in QUALIFIED.finditer(text):
            qualified = re.sub(r"\s+", "", match.group(1))
            parts = [p.lstrip("~") for p in qualified.split("::")]
            if parts[0] in EXTERNAL or parts[0] in EXTERNAL_CLASSES or qualified in CMAKE_TARGETS:
                continue
            if cites_fosssim and (CAMEL.match(parts[-1]) or match.group(2) or
                                  any(p not in names for p in parts[:-1])):
                continue
            checked += 1
            missing = [p for p in parts if p not in names]
            if missing:
                found.append((lines[match.start()], qualified,
                              "not declared in include/: " + ", ".join(missing)))
    return found, checked


def check(include_dir):
    """(the stale names under include_dir as "file:line: `name` why", the number checked)."""
    names, literals = declared_names(include_dir)
    stale, checked = [], 0
    for root, _, files in os.walk(include_dir):
        for name in sorted(files):
            if name.endswith((".hpp", ".h")):
                path = os.path.join(root, name)
                found, count = stale_names(path, names, literals)
                checked += count
                for line, symbol, why in found:
                    stale.append("%s:%d: `%s` %s" % (os.path.relpath(path, include_dir), line,
                                                     symbol, why))
    return sorted(stale), checked


def self_test():
    """The checker finds a stale member, a stale backticked name and a stale name split over
    two lines, and passes what exists, what is external and FOSSSim's own names."""
    header = """\
/// @brief Widget: see Widget::resize and `Widget::count` and `options.tolerance`.
/// Eigen's `SimplicialLLT::solve`, std::vector, Eigen::LLT and massspring::cholmod are not ours.
/// FOSSSim's order (Theme 2, ParticleSimulation::stepSystem, Widget::respond*).
struct Widget {
  void resize(int size);
  int count() const;
  struct Options { double tolerance = 0; } options;
};
/// Stale: Widget::set_avx2, `vanished_option`,
/// and Widget::
/// gone_too; and in a block that does not cite its source, Widget::camelCase.
enum class Mode { Fast, Exact };
/* Mode::Exact exists, Mode::Slow does not. */
"""
    with tempfile.TemporaryDirectory() as folder:
        with open(os.path.join(folder, "widget.hpp"), "w", encoding="utf-8") as handle:
            handle.write(header)
        stale, _ = check(folder)
    expected = ["widget.hpp:10: `Widget::gone_too`", "widget.hpp:11: `Widget::camelCase`",
                "widget.hpp:13: `Mode::Slow`", "widget.hpp:9: `Widget::set_avx2`",
                "widget.hpp:9: `vanished_option`"]
    got = [s.split(" not declared")[0] for s in stale]
    if sorted(got) != sorted(expected):
        print("FAIL: the checker on its own example reported\n  " + "\n  ".join(stale) +
              "\nexpected\n  " + "\n  ".join(expected))
        return 1
    print("ok: the checker reports exactly the %d stale names of its example" % len(expected))
    return 0


def main(argv):
    if argv[1:] == ["--self-test"]:
        return self_test()
    if len(argv) != 2 or not os.path.isdir(argv[1]):
        print(__doc__)
        return 2
    stale, checked = check(argv[1])
    for line in stale:
        print(line)
    if stale:
        print("FAIL: %d comment(s) name symbols that do not exist in %s" % (len(stale), argv[1]))
        return 1
    print("ok: all %d symbols the comments name exist" % checked)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
