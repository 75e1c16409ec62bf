"""Ctrl-C during a render: KeyboardInterrupt soon after, with the image so far."""

import os
import signal
import threading
import time

import numpy as np
import pytest

import lumis


@pytest.fixture(autouse=True)
def sigint_raises_keyboard_interrupt():
    """Python's own SIGINT handler, whatever this process inherited: a
    process started with SIGINT ignored (a background job of a
    non-interactive shell) would otherwise never see the interrupt."""
    old = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, old)


def interrupt_after(seconds):
    t = threading.Timer(seconds, lambda: os.kill(os.getpid(), signal.SIGINT))
    t.start()
    return t


def test_ctrl_c_stops_the_render_and_keeps_the_image_so_far():
    # Passes of 1 spp at 48x48 take milliseconds; the budget would take minutes.
    # A time budget too, so a lost signal fails the test rather than hanging it.
    scene = lumis.load(integrator="path", resolution=(48, 48), spp=1_000_000)
    timer = interrupt_after(1.0)
    start = time.monotonic()
    try:
        with pytest.raises(KeyboardInterrupt) as info:
            lumis.render(scene, time=30, threads=1, progress=False)
    finally:
        timer.cancel()
    elapsed = time.monotonic() - start
    assert elapsed < 5.0, elapsed
    e = info.value
    assert isinstance(e, lumis.Interrupted)
    img = e.image
    assert isinstance(img, lumis.Image) and img.shape == (48, 48, 3)
    assert img.stats["interrupted"]
    assert 1 <= img.stats["spp"] < 1_000_000
    assert img.metadata["lumis:spp"] == str(img.stats["spp"])
    assert np.isfinite(img).all() and img.mean() > 0
    assert lumis.last_render() is img


def test_the_partial_image_is_the_render_at_that_sample_count():
    # Interrupted at n spp, the image is the n-spp render, bit for bit.
    scene = lumis.load(integrator="path", resolution=(24, 24))
    timer = interrupt_after(0.5)
    try:
        with pytest.raises(lumis.Interrupted) as info:
            lumis.render(scene, time=30, threads=1, progress=False)
    finally:
        timer.cancel()
    partial = info.value.image
    n = partial.stats["spp"]
    assert n >= 1
    full = lumis.render(integrator="path", resolution=(24, 24), spp=n, progress=False)
    assert np.array_equal(partial, full)


def test_a_render_after_an_interrupt_runs_normally():
    img = lumis.render(integrator="path", resolution=(8, 8), spp=2, progress=False)
    assert img.stats["spp"] == 2 and not img.stats["interrupted"]
    assert lumis.last_render() is img
