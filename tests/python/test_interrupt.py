# Ctrl-C during the work ends it early and raises KeyboardInterrupt, as a Python user expects
# of a call that takes seconds; nothing half made is kept. Each interrupted call is compared
# with the same call run whole just before, in the same test (a ratio, not a time).
import os
import signal
import threading
import time

import numpy as np
import pytest

import pss
from conftest import DATA

ENGINE = os.path.join(DATA, "engine_256x256x128_uint8.nrrd")


def interrupted_after(seconds, call):
    """Runs call() with a SIGINT sent to this process after `seconds`; returns how long the
    call took before KeyboardInterrupt ended it."""
    timer = threading.Timer(seconds, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.perf_counter()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        call()
        time.sleep(10)  # had the work ignored it, the interrupt lands here, late
    timer.join()
    return time.perf_counter() - start


def timed(call):
    start = time.perf_counter()
    result = call()
    return result, time.perf_counter() - start


def test_ctrl_c_stops_a_render_of_points(bunny):
    render = lambda: pss.render(bunny, size=(1024, 1024), reflections=True, backend="cpu")
    _, whole = timed(render)
    assert interrupted_after(0.1 * whole, render) < 0.6 * whole


def test_ctrl_c_stops_a_volume_s_rays():
    volume = pss.read_volume(ENGINE)
    volume.render(iso=75, size=(8, 8))  # prepared: what follows is rays
    render = lambda: volume.render(iso=75, size=(384, 384), backend="cpu")
    _, whole = timed(render)
    assert interrupted_after(0.1 * whole, render) < 0.6 * whole


def test_a_preparation_that_ctrl_c_cut_short_is_not_kept():
    # Most of a fresh preparation is memory being set up, which no flag stops; its parallel
    # loops skip their work once the flag is set, and what they leave must not be reused.
    render = lambda volume: volume.render(iso=75, size=(64, 64), backend="cpu")
    reference, whole = timed(lambda: render(pss.read_volume(ENGINE)))
    volume = pss.read_volume(ENGINE)
    interrupted_after(0.1 * whole, lambda: render(volume))
    assert np.array_equal(render(volume), reference)
