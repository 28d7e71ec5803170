#!/usr/bin/env python3
"""What calling rigidity from Python costs on top of the C++ it calls.

    PYTHONPATH=build-tests/python /usr/bin/python3 bench/python_overhead.py

1. rigidity.run on the paper's scene (a dict, parsed by the same strict loader as a file):
   wall time per call against the solve time the run reports (stats.wall_time_s).
2. rigidity.material("hooke").p on arrays of 1, 10^3 and 10^6 stretches, against the same
   law written in NumPy.
Best of several repetitions, one core.
"""

import time

import numpy

import rigidity

PAPER = {
    "name": "paper_wall_impact",
    "materials": {"rigid_steel": {"model": "rigid"}},
    "bodies": [{"name": "bar", "material": "rigid_steel", "position": 0, "length": 1, "velocity": 0.6}],
    "boundaries": {"left": {"type": "free"}, "right": {"type": "wall", "position": 0.8}},
    "time": {"end": 1.5},
    "outputs": {"probes": [{"name": "wall", "body": "bar", "at": "right", "quantities": ["p", "v", "s"],
                            "every": 0.05}]},
}


def best(function, repeat=5, number=1):
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        for _ in range(number):
            function()
        times.append((time.perf_counter() - start) / number)
    return min(times)


def main():
    calls = 200
    solve = []

    def one_run():
        solve.append(rigidity.run(PAPER).summary["stats"]["wall_time_s"])

    per_call = best(one_run, repeat=5, number=calls)
    print("rigidity.run(paper scene dict): %.1f us per call, of which the solve %.1f us (%d calls)"
          % (per_call * 1e6, min(solve) * 1e6, calls))

    m = rigidity.material("hooke", wave_speed=0.5)
    b = 0.5
    for n in (1, 1000, 1000000):
        s = numpy.linspace(0.5, 1.5, n)
        number = max(1, 100000 // n)
        c_time = best(lambda: m.p(s), number=number)

        def numpy_law():
            R = numpy.sqrt(b * b + (1 - b * b) / (s * s))
            e = (R - b * b) / (1 - b * b)
            return e / R - 1.0

        n_time = best(numpy_law, number=number)
        assert numpy.allclose(m.p(s), numpy_law(), rtol=1e-12, atol=1e-15)
        print("hooke p(s) on %7d stretches: rigidity %.3g s (%.1f ns each), NumPy %.3g s (%.1f ns each)"
              % (n, c_time, c_time / n * 1e9, n_time, n_time / n * 1e9))


if __name__ == "__main__":
    main()
