"""The commands of docs/performance.md run, shortened to 0.2 s of road: bench_rough_road
prints every figure the table quotes, its converging steps allocate no heap memory (a step
that fails and is cut allocates its message), and with a step budget it prints the budget's
report and the forces against the default.

    test_performance_doc.py BENCH_ROUGH_ROAD
"""
import os
import re
import subprocess
import sys

SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def documented_commands():
    with open(os.path.join(SOURCE, "docs", "performance.md")) as doc:
        return [line.strip().split()[1:] for line in doc if line.startswith("    build/bench_rough_road")]


def main(bench):
    commands = documented_commands()
    assert len(commands) >= 2, commands  # a budget of iterations and one of time
    for arguments in commands:
        run = subprocess.run([bench] + arguments + ["--seconds", "0.2"], capture_output=True, text=True, timeout=300)
        assert run.returncode == 0, (arguments, run.stderr)
        out = run.stdout
        assert re.search(r"^machine: \d+ processors online, \S", out, re.M), out
        assert "steps: 200 of 1 ms" in out, out
        figures = re.findall(r"step time \[ms\]: median ([\d.]+), 99th ([\d.]+), 99.9th ([\d.]+), max ([\d.]+)", out)
        assert figures and all(0 < float(a) <= float(b) <= float(c) <= float(d) for a, b, c, d in figures), out
        assert re.search(r"Newton iterations per step: mean [\d.]+, max \d+; time per iteration [\d.]+ us", out), out
        counts = re.findall(r"steps cut: (\d+); heap allocations during the steps: (\d+)", out)
        assert counts, out
        for cuts, allocations in counts:
            assert int(allocations) <= 20 * int(cuts), out
        if "--max-iterations" in arguments:
            budget = re.search(r"budget report: (\d+) steps, (\d+) ended unconverged \(worst relative residual (\S+)\), "
                               r"(\d+) overran the iterations", out)
            assert budget and int(budget.group(1)) >= 200, out
            assert re.search(r"against the default: largest \|dFx\| [\d.]+ N, \|dFz\| [\d.]+ N; peak Fz [-+][\d.]+ %",
                             out), out
    print(f"{len(commands)} documented commands ran")


if __name__ == "__main__":
    main(sys.argv[1])
