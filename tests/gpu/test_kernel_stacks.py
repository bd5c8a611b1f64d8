"""kernel_stacks.py, the stack budget check of every CUDA build, on reports written here:
it must fail for each way a kernel can be over the budget or unaccounted for, and pass
otherwise. No GPU or nvcc needed (ctest: kernel_stacks_script); the standard library's
unittest, so that any python3 runs it."""
import pathlib, subprocess, sys, tempfile, unittest

SCRIPT = pathlib.Path(__file__).with_name('kernel_stacks.py')


def entry(name, arch, frame, cumulative=None, registers=40):
    used = f"ptxas info    : Used {registers} registers, used 0 barriers"
    if cumulative:
        used += f", {cumulative} bytes cumulative stack size"
    return (f"ptxas info    : Compiling entry function '{name}' for '{arch}'\n"
            f"ptxas info    : Function properties for {name}\n"
            f"    {frame} bytes stack frame, 0 bytes spill stores, 0 bytes spill loads\n"
            f"{used}\nptxas info    : Compile time = 1.0 ms\n")


def callee(name, frame):
    return (f"ptxas info    : Function properties for {name}\n"
            f"    {frame} bytes stack frame, 8 bytes spill stores, 8 bytes spill loads\n")


def run(tmp_path, reports, extra_objects=(), flags=()):
    objects = []
    for i, text in enumerate(reports):
        obj = tmp_path / f'k{i}.cu.o'
        obj.write_bytes(b'')
        (tmp_path / f'k{i}.cu.o.ptxas').write_text(text)
        objects.append(str(obj))
    r = subprocess.run([sys.executable, str(SCRIPT), '--budget', '1024', *flags, *objects, *extra_objects],
                       capture_output=True, text=True)
    return r.returncode, r.stdout


class KernelStacks(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.tmp = pathlib.Path(self.dir.name)

    def tearDown(self):
        self.dir.cleanup()

    def test_kernels_within_the_budget_pass_and_are_tabled(self):
        rc, out = run(self.tmp, [entry('_Z1av', 'sm_90', 1024, 1024) + callee('_Z6helperv', 64) +
                                 entry('_Z1bv', 'sm_75', 0)])
        self.assertTrue(rc == 0, out)
        self.assertTrue('| _Z1av' in out or 'a()' in out, out)
        self.assertTrue('2 kernels, 0 over the budget' in out, out)

    def test_a_frame_over_the_budget_fails(self):
        rc, out = run(self.tmp, [entry('_Z1av', 'sm_90', 1028, 1028)])
        self.assertTrue(rc == 1 and '1 over the budget' in out and 'OVER' in out, out)

    def test_the_calls_count_cumulative_beyond_the_own_frame(self):
        rc, out = run(self.tmp, [entry('_Z1av', 'sm_90', 16, 4096)])
        self.assertTrue(rc == 1 and '4096' in out, out)

    def test_every_architecture_counts_suffixed_ones_too(self):
        rc, out = run(self.tmp, [entry('_Z1av', 'sm_90', 16) + entry('_Z1av', 'sm_90a', 4000, 4000)])
        self.assertTrue(rc == 1 and 'sm_90a' in out, out)

    def test_a_stack_ptxas_cannot_bound_fails(self):
        text = entry('_Z1av', 'sm_90', 16) + \
            "ptxas warning : Stack size for entry function '_Z1av' cannot be statically determined\n"
        rc, out = run(self.tmp, [text])
        self.assertTrue(rc == 1 and 'unbounded' in out, out)

    def test_a_kernel_without_its_frame_line_fails(self):
        text = "ptxas info    : Compiling entry function '_Z1av' for 'sm_90'\n" + callee('_Z6helperv', 16) + \
            "ptxas info    : Used 40 registers, used 0 barriers\n"
        rc, out = run(self.tmp, [text])
        self.assertTrue(rc == 1 and 'with a stack figure read' in out, out)

    def test_a_kernel_over_its_registers_or_absent_fails(self):
        report = [entry('_Z1av', 'sm_90', 16, registers=128) + entry('_Z1av', 'sm_75', 16, registers=120)]
        rc, out = run(self.tmp, report, flags=['--registers', 'a()=128'])
        self.assertTrue(rc == 0 and 'a(): 128 registers, within its 128' in out, out)
        rc, out = run(self.tmp, report, flags=['--registers', 'a()=127'])
        self.assertTrue(rc == 1 and 'a(): 128 registers, over its 127' in out, out)
        rc, out = run(self.tmp, report, flags=['--registers', 'b()=200'])
        self.assertTrue(rc == 1 and 'b(): not in the reports' in out, out)

    def test_a_missing_report_or_none_at_all_fails(self):
        missing = self.tmp / 'absent.cu.o'
        rc, out = run(self.tmp, [entry('_Z1av', 'sm_90', 16)], [str(missing)])
        self.assertTrue(rc == 1 and 'no ptxas report' in out, out)
        rc, out = run(self.tmp, [''])
        self.assertTrue(rc == 1 and 'no kernel' in out, out)


if __name__ == '__main__':
    unittest.main()
