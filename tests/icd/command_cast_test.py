#!/usr/bin/python3
"""icd/commands.h makes reading a recorded command through the wrong struct impossible to write: a Cmd header
cannot be cast to a command struct (its base is private), two command structs cannot be cast into each other,
and visit_command refuses a visitor that lacks an overload for some command. Each snippet is compiled with the
project's compiler; the control snippet (the one way that works) must compile, the others must not."""
import os
import subprocess
import sys
import tempfile

ICD_DIR = sys.argv[1]
CXX = sys.argv[2:]

HEAD = '#include "commands.h"\nusing namespace tilevk::icd;\n'
VISITOR = '''
struct Every {
#define OVERLOAD(name) void operator()(const Cmd##name&) {}
    TILEVK_COMMANDS(OVERLOAD)
#undef OVERLOAD
};
'''
CASES = {
    'visit with an overload per command': (True, VISITOR + 'void f(const Cmd& c) { Every e; visit_command(c, e); }'),
    'header cast to a command struct': (
        False, 'uint32_t f(const Cmd& c) { return static_cast<const CmdSetStencilReference&>(c).value; }'),
    'header pointer cast to a command struct': (
        False, 'uint32_t f(const Cmd* c) { return static_cast<const CmdDrawIndirect*>(c)->stride; }'),
    'one command struct cast to another': (
        False,
        'uint32_t f(const CmdSetStencilCompareMask& c) { return static_cast<const CmdSetStencilReference&>(c).value; }'),
    'command struct cast to another through its header': (
        False, 'uint32_t f(CmdDrawIndexedIndirect& c) { return static_cast<CmdDrawIndirect&>(c.header()).stride; }'),
    'visitor missing a command': (
        False, 'struct Some { void operator()(const CmdDraw&) {} };\n'
               'void f(const Cmd& c) { Some s; visit_command(c, s); }'),
}

failures = []
with tempfile.TemporaryDirectory() as d:
    for name, (should_compile, body) in CASES.items():
        src = os.path.join(d, 'case.cpp')
        with open(src, 'w') as f:
            f.write(HEAD + body + '\n')
        p = subprocess.run(CXX + ['-std=c++20', '-fsyntax-only', '-I', ICD_DIR, src], capture_output=True, text=True)
        compiled = p.returncode == 0
        print(f'{name}: {"compiles" if compiled else "does not compile"}')
        if compiled != should_compile:
            failures.append(name)
            if not compiled:
                print(p.stderr)
if failures:
    print('FAILED:', ', '.join(failures))
    sys.exit(1)
print('ok')
