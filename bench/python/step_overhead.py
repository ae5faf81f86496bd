#!/usr/bin/env python3
"""What stepping and reading state cost from Python beyond the C++ (docs/python.md "Cost").

1. Per scene, World.step() called once per step from a Python loop: the median wall time of the
   call against the step's own clock (the StepReport's seconds, taken inside World::step); the
   difference is the binding's overhead per call (argument handling, GIL release and reacquire).
2. Reading the state of the 1 000-box pile (positions, quaternions, both velocities): median of
   each call.
Usage: PYTHONPATH=build/python python3 bench/python/step_overhead.py
"""
import statistics
import time

import coulomb


def median_us(samples):
    return 1e6 * statistics.median(samples)


def step_overhead(scene, steps=2000, warmup=200):
    world = coulomb.World(scene)
    world.step(warmup)
    calls, inside = [], []
    for _ in range(steps):
        start = time.perf_counter()
        world.step()
        calls.append(time.perf_counter() - start)
        inside.append(world.report()["seconds"])
    return median_us(calls), median_us(inside)


def main():
    print("| scene | call [us] | step inside [us] | overhead [us] |")
    print("|---|---|---|---|")
    for scene in ["box_on_plane", "sphere_slide", "box_incline_A_stick", "newton_cradle"]:
        call, inside = step_overhead(scene)
        print(f"| {scene} | {call:.2f} | {inside:.2f} | {call - inside:.2f} |")
    world = coulomb.World("box_pile_1000")
    world.step(2)
    print(f"\nreading the state of box_pile_1000 ({world.body_count} bodies):")
    for name in ["positions", "quaternions", "linear_velocities", "angular_velocities"]:
        read = getattr(world, name)
        samples = []
        for _ in range(2000):
            start = time.perf_counter()
            read()
            samples.append(time.perf_counter() - start)
        print(f"  {name}(): {median_us(samples):.1f} us")


if __name__ == "__main__":
    main()
