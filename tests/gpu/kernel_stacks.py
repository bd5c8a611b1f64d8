#!/usr/bin/env python3
"""The GPU kernels' per-thread stack frames against a budget, from ptxas's reports.

Every CUDA object of the library has its report beside it (OBJECT.ptxas, written by
cmake/ptxas_report.sh). Prints a table of each kernel's stack and spills for every
architecture built, and fails when a report is missing or unreadable, when no kernel was
reported, or when any kernel's stack exceeds the budget or has no bound ptxas can tell
(recursion, calls through pointers): a thread's stack lives in local memory, so every byte
of it is memory traffic and lost occupancy.
With --registers KERNEL=N (repeatable) it also fails when that kernel (its demangled type, as
the table shows it) uses more than N registers on some architecture, or was not reported: a
kernel held to its registers by a launch bound (backend/cuda/launch.cuh).
    kernel_stacks.py --budget 1024 [--registers KERNEL=N ...] OBJECT...
"""
import argparse, os, re, subprocess, sys

ENTRY = re.compile(r"Compiling entry function '([^']+)' for '(sm_\w+)'")
PROPERTIES = re.compile(r"Function properties for (\S+)")
FRAME = re.compile(r"(\d+) bytes stack frame, (\d+) bytes spill stores, (\d+) bytes spill loads")
# ptxas leaves the cumulative size out where it is 0.
USED = re.compile(r"Used (\d+) registers(?:.*?(\d+) bytes cumulative stack size)?")
# Recursion or calls through pointers: the stack has no bound ptxas can tell.
UNBOUNDED = re.compile(r"Stack size for entry function '([^']+)' cannot be statically determined")


def parse(text):
    """(mangled kernel, arch, registers, stack, spill stores, spill loads) for each entry function.
    The stack is ptxas's cumulative size: the kernel's own frame and those of the calls it makes;
    None where ptxas says it cannot be bounded."""
    rows, entry, properties, frame = [], None, None, None
    unbounded = set(UNBOUNDED.findall(text))
    for line in text.splitlines():
        m = ENTRY.search(line)
        if m:
            entry, properties, frame = m.groups(), None, None
            continue
        m = PROPERTIES.search(line)
        if m:
            properties = m.group(1)
            continue
        m = FRAME.search(line)
        if m and entry and properties == entry[0]:
            frame = tuple(map(int, m.groups()))
            continue
        m = USED.search(line)
        if m and entry and frame is not None:
            stack = None if entry[0] in unbounded else max(frame[0], int(m.group(2) or 0))
            rows.append((entry[0], entry[1], int(m.group(1)), stack, frame[1], frame[2]))
            entry = None
    return rows


def short_names(mangled):
    """The kernel type of each for_each_index<Kernel> instantiation, demangled."""
    try:
        out = subprocess.run(['c++filt'], input='\n'.join(mangled), capture_output=True, text=True).stdout.split('\n')
    except OSError:
        return mangled
    names = []
    for m, d in zip(mangled, out + [''] * len(mangled)):
        k = re.match(r'void pss::cuda::for_each_index<(.*)>\(long, long, ', d)
        names.append(k.group(1).strip() if k else d or m)
    return names


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--budget', type=int, required=True, help='bytes of stack per thread')
    ap.add_argument('--registers', action='append', default=[], metavar='KERNEL=N',
                    help='the most registers KERNEL may use')
    ap.add_argument('objects', nargs='+', help='the library\'s objects; those of .cu files must have reports')
    a = ap.parse_args()
    rows = []
    for obj in a.objects:
        if not obj.endswith('.cu.o'):
            continue
        report = obj + '.ptxas'
        if not os.path.isfile(report):
            print(f'{report}: no ptxas report (is cmake/ptxas_report.sh the CUDA compiler launcher?)')
            return 1
        text = open(report, encoding='utf-8', errors='replace').read()
        found = parse(text)
        if len(found) != len(ENTRY.findall(text)):
            print(f'{report}: {len(ENTRY.findall(text))} kernels, {len(found)} of them with a stack figure read')
            return 1
        rows += found
    if not rows:
        print('no kernel in the ptxas reports')
        return 1
    names = short_names([r[0] for r in rows])
    width = max(len(n) for n in names)
    print(f'| {"kernel":<{width}} | arch   | registers | stack B | spill stores B | spill loads B |')
    print(f'|{"-" * (width + 2)}|--------|-----------|---------|----------------|---------------|')
    def over(stack):
        return stack is None or stack > a.budget
    for name, (_, arch, regs, stack, stores, loads) in sorted(
            zip(names, rows), key=lambda x: (-(x[1][3] if x[1][3] is not None else 1 << 40), x[0], x[1][1])):
        shown = 'unbounded' if stack is None else stack
        print(f'| {name:<{width}} | {arch:<6} | {regs:>9} | {shown:>7} | {stores:>14} | {loads:>13} |'
              f'{"  OVER" if over(stack) else ""}')
    over = sum(over(r[3]) for r in rows)
    print(f'{len(rows)} kernels, {over} over the budget of {a.budget} bytes of stack per thread')
    failed = over > 0
    for limit in a.registers:
        kernel, _, most = limit.rpartition('=')
        used = [r[2] for n, r in zip(names, rows) if n == kernel]
        if not used:
            print(f'{kernel}: not in the reports')
            failed = True
        elif max(used) > int(most):
            print(f'{kernel}: {max(used)} registers, over its {most}')
            failed = True
        else:
            print(f'{kernel}: {max(used)} registers, within its {most}')
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main())
