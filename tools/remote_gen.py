#!/usr/bin/env python3
"""Writes a lab's proxies and worker table from its stubs (docs/grading.md, "Where submitted code runs").

    remote_gen.py STAGE_DIR PROXY_CPP SERVER_CPP [IN_WORKER_CPP...]

Reads every function defined in the stub files of STAGE_DIR (labs/NN_name/*.cpp: the student
functions, with the exact signatures of the headers), and in IN_WORKER_CPP, framework files that
run in the worker (a loop that calls a student function thousands of times a step: one call
crosses instead of thousands; the checker links the other framework files only), and writes
  PROXY_CPP   the same functions for the checker: each sends its arguments to the worker and
              reads back what the student's function changed and returned (tests/support/remote);
  SERVER_CPP  the worker's main: a table that reads those arguments, calls the student's function
              and writes the reply.
Arguments cross by value: const references and values go in; non-const references, pointers,
Eigen::Ref<VecX> and Points views go in and come back. A member function sends its object too (and
gets it back when not const), so its class must cross (an aggregate, or a state list in
tests/support/remote/state.hpp). Objects that are code rather than data (a System, a Force the
worker cannot rebuild) cross as handles whose methods call back into the checker (handles.hpp).
The worker reads each argument into a remote::Arg<T>, which holds what the argument refers to. A
parameter of a kind that cannot cross (a function, another view) is refused by name: such a lab is
not graded remotely. A stub's parameter without a name is named and sent (the student's function
may use it); an in-worker file's is one its function does not use: it stays in the checker, and
the worker passes a blank one.
"""

import re
import sys
from pathlib import Path

INCLUDE_RE = re.compile(r'^#include\s+"(physlab/[^"]+)"', re.MULTILINE)
COMMENT_RE = re.compile(r"//[^\n]*|/\*.*?\*/", re.DOTALL)
STRING_RE = re.compile(r'"(?:[^"\\\n]|\\.)*"')
NAME_RE = re.compile(r"([A-Za-z_]\w*)\s*$")


class Refused(Exception):
    pass


def split_top(text: str, sep: str = ",") -> list:
    """Splits at `sep` outside (), <>, [] and {}."""
    parts, depth, start = [], 0, 0
    for i, c in enumerate(text):
        if c in "(<[{":
            depth += 1
        elif c in ")>]}":
            depth -= 1
        elif c == sep and depth == 0:
            parts.append(text[start:i])
            start = i + 1
    parts.append(text[start:])
    return [p.strip() for p in parts if p.strip()]


def definitions(source: str):
    """(return type, name, parameter list text) of each function defined at namespace level,
    but for an unnamed namespace's and templates (the file's own helpers, which stay beside their
    callers: a template is instantiated where it is used)."""
    text = STRING_RE.sub('""', COMMENT_RE.sub(" ", source))
    text = re.sub(r"^\s*#[^\n]*", " ", text, flags=re.MULTILINE)
    depth, start, found = 0, 0, []
    namespaces = []  # brace depths that opened a namespace
    unnamed = []  # those of them that opened an unnamed one
    for i, c in enumerate(text):
        if c == "{":
            head = text[start:i].strip()
            if re.match(r"^namespace\b", head):
                namespaces.append(depth)
                if head == "namespace":
                    unnamed.append(depth)
            elif depth == len(namespaces) and "(" in head:
                if not unnamed and not re.match(r"^template\b", head):
                    found.append(head)
            depth += 1
            start = i + 1
        elif c == "}":
            depth -= 1
            if namespaces and namespaces[-1] == depth:
                namespaces.pop()
                if unnamed and unnamed[-1] == depth:
                    unnamed.pop()
            start = i + 1
        elif c == ";" and depth == len(namespaces):
            start = i + 1
    for head in found:
        head = " ".join(head.split())
        m = re.match(r"^(.*?)\b([A-Za-z_][\w:]*)\s*\((.*)\)\s*(const)?\s*(noexcept)?$", head)
        if not m:
            raise Refused(f"cannot read the definition '{head}'")
        ret, name, params, const = m.group(1).strip(), m.group(2), m.group(3), bool(m.group(4))
        if name.count("::") > 1:
            raise Refused(f"{name}: a member of a nested class")
        yield ret, name, params, const


def parameter(text: str, name_of: str) -> tuple:
    """(kind, value type, name): kind 'in', 'inout', 'pointer', 'ref' or 'system'."""
    m = NAME_RE.search(text)
    if not m:
        raise Refused(f"{name_of}: a parameter without a name ('{text}')")
    name, kind_text = m.group(1), text[:m.start()].strip()
    if re.fullmatch(r"Eigen::Ref<\s*VecX\s*>", kind_text):
        return "ref", "VecX", name  # a writable view of a vector: its entries go in and come back
    if kind_text == "const System&":
        return "system", "System", name  # a copy or a handle; the evaluations made on it come back
    if kind_text == "Points":
        return "ref", "Points", name  # a writable 3 x n view: its entries go in and come back
    if "Eigen::Ref" in kind_text or "std::function" in kind_text or "(" in kind_text:
        raise Refused(f"{name_of}: parameter {name} ('{kind_text}') is a view or a function")
    const = re.match(r"^const\b", kind_text) is not None
    value = re.sub(r"^const\s+", "", kind_text)
    if value.endswith("&"):
        return ("in" if const else "inout"), value[:-1].strip(), name
    if value.endswith("*"):
        if const:
            raise Refused(f"{name_of}: parameter {name} is a pointer to const")
        return "pointer", value[:-1].strip(), name
    return "in", value, name


def unused(text: str, index: int) -> tuple:
    """An in-worker function's unnamed parameter (kind 'unused'): not sent; the worker passes a
    blank of its value type, named unused<index>."""
    return "unused", re.sub(r"^const\s+", "", text).rstrip("&* ").strip(), f"unused{index}"


def generate(stage_dir: Path, in_worker: list = ()) -> tuple:
    files = sorted(stage_dir.glob("*.cpp"))
    if not files:
        raise Refused(f"no stubs in {stage_dir}")
    includes, functions = set(), []
    for f in files + list(in_worker):
        source = f.read_text()
        includes |= set(INCLUDE_RE.findall(source))
        for ret, name, params, const in definitions(source):
            if f in in_worker:  # an unnamed parameter is unused: it stays behind
                parsed = [parameter(p, name) if NAME_RE.search(p) else unused(p, i)
                          for i, p in enumerate(split_top(params))]
                functions.append((ret, name, params, const, parsed))
                continue
            # A parameter the stub leaves unnamed (its name commented out) gets one: the proxy sends it.
            named = [p if NAME_RE.search(p) else f"{p} unnamed{i}"
                     for i, p in enumerate(split_top(params))]
            functions.append((ret, name, ", ".join(named), const, [parameter(p, name) for p in named]))
    stage = stage_dir.name
    head = (f"// Generated by tools/remote_gen.py from labs/{stage}/*.cpp: do not edit.\n"
            + "".join(f'#include "{i}"\n' for i in sorted(includes))
            + '#include "remote/handles.hpp"\n#include "remote/remote.hpp"\n#include "remote/state.hpp"\n\n')
    proxy = [head, "namespace physlab {\n"]
    server = [head, "namespace physlab::remote {\n\n// A friend of the classes whose member functions it calls (state.hpp).\n"
                    "template <>\nstruct Access<1> {"]
    for index, (ret, name, signature, const, params) in enumerate(functions):
        owner = name.split("::")[0] if "::" in name else None
        body = [f"\n{ret} {name}({signature}){' const' if const else ''} {{", f'  remote::Call call({index}, "{name}");']
        if owner:
            body.append("  call.in(*this);")
        body += [f"  call.inPointer({n});" if k == "pointer" else f"  call.in({t}::PlainObject({n}));"
                 if k == "ref" and t != "VecX" else f"  call.in(VecX({n}));" if k == "ref"
                 else f"  call.in({n});" for k, t, n in params if k != "unused"]
        body.append("  call.send();")
        if owner and not const:
            body.append("  call.back(*this);")
        body += [f"  remote::addEvaluations(call, {n});" if k == "system" else
                 f"  call.{'backPointer' if k == 'pointer' else 'backInto' if k == 'ref' else 'back'}({n});"
                 for k, _, n in params if k not in ("in", "unused")]
        body.append(f"  {'return ' if ret != 'void' else ''}call.result<{ret}>();")
        body.append("}")
        proxy.append("\n".join(body) + "\n")
        entry = [f"static void entry{index}(Reader& in, Writer& out) {{"]
        if owner:
            entry.append(f"  remote::Arg<{owner}> self(in);")
        for k, t, n in params:
            if k == "unused":
                entry.append(f"  {t} {n} = blank<{t}>();")
            elif k == "pointer":
                entry.append(f"  {t} {n} = blank<{t}>();")
                entry.append(f"  bool {n}_given = false;")
                entry.append(f"  remote::get(in, {n}_given);")
                entry.append(f"  if ({n}_given) remote::get(in, {n});")
            else:
                entry.append(f"  remote::Arg<{t}> {n}(in);")
        arguments = ", ".join(f"{n}_given ? &{n} : nullptr" if k == "pointer" else n if k == "unused" else f"*{n}"
                              for k, _, n in params)
        back = ["self.back(out);"] if owner and not const else []
        for k, _, n in params:
            if k in ("inout", "ref", "system"):
                back.append(f"{n}.back(out);")
            elif k == "pointer":
                back.append(f"remote::put(out, {n}_given); if ({n}_given) remote::put(out, {n});")
        callee = f"(*self).{name.split('::')[1]}" if owner else f"physlab::{name}"
        entry.append(f"  respond(out, [&] {{ return {callee}({arguments}); }}, [&] {{ {' '.join(back)} }});")
        entry.append("}")
        server.append("\n" + "\n".join("  " + line for line in entry) + "\n")
    proxy.append("\n}  // namespace physlab\n")
    table = ", ".join(f"physlab::remote::Access<1>::entry{i}" for i in range(len(functions)))
    server.append(f"}};\n\n}}  // namespace physlab::remote\n\n"
                  f"int main() {{\n  static constexpr physlab::remote::Entry kTable[] = {{{table}}};\n"
                  f"  return physlab::remote::serve(kTable, {len(functions)});\n}}\n")
    return "".join(proxy), "".join(server)


def write_if_changed(path: Path, text: str) -> None:
    if not path.exists() or path.read_text() != text:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)


def main() -> int:
    if len(sys.argv) < 4:
        print(__doc__.strip().splitlines()[2].strip(), file=sys.stderr)
        return 2
    try:
        proxy, server = generate(Path(sys.argv[1]), [Path(a) for a in sys.argv[4:]])
    except Refused as why:
        print(f"remote_gen.py: {Path(sys.argv[1]).name} cannot be graded remotely: {why}", file=sys.stderr)
        return 1
    write_if_changed(Path(sys.argv[2]), proxy)
    write_if_changed(Path(sys.argv[3]), server)
    return 0


if __name__ == "__main__":
    sys.exit(main())
