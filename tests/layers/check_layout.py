#!/usr/bin/env python3
"""The layout rules that keep the paper's operations apart from how a run is carried out.

    python3 tests/layers/check_layout.py SOURCE_DIR

Fails (exit 1), printing one line per problem, if
  - a module below apps/ (the folders of check_layers.MODULE_DIRS) makes a process-wide call: the allocator
    (malloc_trim, mallopt), the environment (setenv, putenv), the process (exit, abort is allowed only through
    assert), signals, the locale, the thread count of a runtime (omp_set_num_threads), the terminate handler;
  - the sweep's state, front::detail::FrontState, has a member about a region, a slab or a cut other than the one
    region value (`region`): what a region is lives in front/region.h, not in fields of the paper's state;
  - `departure_step`, Algorithm 1's loop body, is longer than MAX_DEPARTURE_STEP lines;
  - `sweep_decomposed`, the fallback ladder (regions, groups of components, one sweep), is longer than MAX_LADDER
    lines or catches an exception (each rung's failure is a value);
  - a stage's options struct (a struct named ...Options in a module at or above skin/) holds what every stage
    must agree on — C and Q (SizeConstants), a thread count, a progress callback — instead of reading it from the
    run's one skin::RunContext; mesher::MeshOptions, where the user sets them once, is the exception. (geometry/
    lies below the context and keeps its own thread count.)
"""
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_layers import MODULE_DIRS  # noqa: E402

PROCESS_WIDE = re.compile(r"\b(malloc_trim|mallopt|setenv|putenv|unsetenv|std::exit|_exit|quick_exit|signal|sigaction|"
                          r"setlocale|omp_set_num_threads|set_terminate|setrlimit)\s*\(")
REGION_WORDS = re.compile(r"slab|park|ghost|owns|upper|lower|cut|band|region", re.IGNORECASE)
MAX_DEPARTURE_STEP = 55
MAX_LADDER = 40
SHARED_MEMBER = re.compile(r"^\s*(?:skin::)?SizeConstants\s+\w+\s*[;={]|^\s*int\s+threads\b|"
                           r"^\s*std::function<.*>\s+progress\s*[;={]")
STRUCT = re.compile(r"^\s*struct\s+(\w+)\b[^;]*$")


def code_lines(path):
    """The lines of a C++ file with // comments and string literals blanked out."""
    for n, line in enumerate(open(path, encoding="utf-8"), 1):
        line = re.sub(r'"(\\.|[^"\\])*"', '""', line)
        yield n, line.split("//", 1)[0]


def process_wide_calls(root):
    problems = []
    for folder in MODULE_DIRS:
        path = os.path.join(root, folder)
        for name in sorted(os.listdir(path)):
            if not name.endswith((".h", ".cpp")):
                continue
            for n, line in code_lines(os.path.join(path, name)):
                m = PROCESS_WIDE.search(line)
                if m:
                    problems.append(f"{folder}/{name}:{n}: process-wide call {m.group(1)}() below apps/")
    return problems


def front_state_members(root):
    """(line, name) of every data member of FrontState, from its body in front/front_state.h."""
    path = os.path.join(root, "front", "front_state.h")
    lines = list(code_lines(path))
    start = next(i for i, (_, l) in enumerate(lines) if re.match(r"\s*struct FrontState\s*\{", l))
    depth, parens, members = 0, 0, []
    for n, line in lines[start:]:
        before, open_parens = depth, parens
        depth += line.count("{") - line.count("}")
        parens += line.count("(") - line.count(")")
        # Members: the statements at the struct's own depth, outside a call or a signature, that end with ';'
        # and declare no function.
        text = line.strip()
        if before != 1 or depth != 1 or open_parens or not text.endswith(";") or \
                re.match(r"(using|friend|return|template)\b", text):
            if depth == 0 and before > 0:
                break
            continue
        decl = text.rstrip(";")
        while re.search(r"<[^<>]*>", decl):
            decl = re.sub(r"<[^<>]*>", "", decl)
        decl = re.sub(r"\([^()]*\)", "()", decl)
        if re.search(r"\w\s*\(\)\s*(const)?\s*$", decl.split("=")[0]):
            continue  # a member function's declaration
        for part in decl.split(","):
            words = part.split("=")[0].split("{")[0].split()
            if words:
                members.append((n, words[-1].lstrip("*&")))
    return members


def function_body(root, path, head):
    """The lines of the top-level function of `path` whose definition starts with `head`, to its closing brace."""
    lines = open(os.path.join(root, path), encoding="utf-8").read().split("\n")
    start = next(i for i, l in enumerate(lines) if l.startswith(head) and not l.rstrip().endswith(";"))
    end = next(i for i in range(start, len(lines)) if lines[i] == "}")
    return lines[start:end + 1]


def departure_step_length(root):
    return len(function_body(root, "front/sweep.cpp", "bool departure_step("))


def ladder_problems(root):
    """The decomposition's fallback ladder is one short function whose rungs fail by value: no catch in it."""
    body = function_body(root, "decompose/decomposed.cpp", "DecomposedSweep sweep_decomposed(")
    problems = []
    if len(body) > MAX_LADDER:
        problems.append(f"decompose/decomposed.cpp: sweep_decomposed (the ladder) is {len(body)} lines, more than "
                        f"{MAX_LADDER}")
    if any(re.search(r"\bcatch\s*\(", line.split("//", 1)[0]) for line in body):
        problems.append("decompose/decomposed.cpp: sweep_decomposed catches an exception: a rung's failure is a value")
    return problems, len(body)


def shared_settings_in_options(root):
    """Members of stage options structs that belong in skin::RunContext."""
    problems = []
    for folder in MODULE_DIRS:
        if folder.startswith("geometry") or folder == "core":
            continue
        path = os.path.join(root, folder)
        for name in sorted(os.listdir(path)):
            if not name.endswith(".h"):
                continue
            struct = None
            for n, line in code_lines(os.path.join(path, name)):
                m = STRUCT.match(line)
                if m:
                    struct = m.group(1)
                elif struct and struct.endswith("Options") and struct != "MeshOptions" and SHARED_MEMBER.match(line):
                    problems.append(f"{folder}/{name}:{n}: {struct} holds `{line.strip()}`: it belongs in the run's "
                                    "skin::RunContext")
    return problems


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    root = sys.argv[1]
    problems = process_wide_calls(root) + shared_settings_in_options(root)
    members = front_state_members(root)
    if len(members) < 20:
        problems.append(f"front/front_state.h: found only {len(members)} members of FrontState: the parser is stale")
    for n, name in members:
        if REGION_WORDS.search(name) and name != "region":
            problems.append(f"front/front_state.h:{n}: FrontState member `{name}` belongs in the region value "
                            "(front/region.h)")
    length = departure_step_length(root)
    ladder, ladder_length = ladder_problems(root)
    problems += ladder
    if length > MAX_DEPARTURE_STEP:
        problems.append(f"front/sweep.cpp: departure_step is {length} lines, more than {MAX_DEPARTURE_STEP}")
    for p in problems:
        print("problem: " + p)
    print(f"layout: {len(members)} FrontState members, departure_step {length} lines, "
          f"sweep_decomposed {ladder_length} lines; {len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
