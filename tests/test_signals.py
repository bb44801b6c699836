"""tilekit.signals: Ctrl-C and SIGTERM wait for a catalogue write to end, then act as they
would have at once (the run layer's clean-up must not meet a write lock that an interrupted
commit left held; CI saw `search --executor local` hang 30 s after Ctrl-C)."""

from __future__ import annotations

import os
import signal

import pytest

from tilekit.signals import Terminated, checkpoint, deferred, sigterm_raises


def test_ctrl_c_inside_a_deferred_block_acts_at_its_end():
    done = []
    with pytest.raises(KeyboardInterrupt):
        with deferred():
            os.kill(os.getpid(), signal.SIGINT)
            done.append("write finished")
    assert done == ["write finished"]
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler  # restored


def test_sigterm_inside_a_deferred_block_raises_terminated_at_its_end():
    done = []
    with sigterm_raises():
        with pytest.raises(Terminated):
            with deferred():
                os.kill(os.getpid(), signal.SIGTERM)
                done.append("write finished")
    assert done == ["write finished"]


def test_checkpoint_acts_on_a_pending_signal_at_once():
    reached = []
    with pytest.raises(KeyboardInterrupt):
        with deferred():
            checkpoint()  # nothing pending: returns
            os.kill(os.getpid(), signal.SIGINT)
            checkpoint()
            reached.append("after the checkpoint")
    assert reached == []


def test_nested_blocks_act_once_at_the_outer_end_and_quiet_blocks_change_nothing():
    with deferred():
        pass
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    order = []
    with pytest.raises(KeyboardInterrupt):
        with deferred():
            with deferred():
                os.kill(os.getpid(), signal.SIGINT)
                order.append("inner")
            order.append("outer")
    assert order == ["inner", "outer"]


def test_the_catalogue_waiting_for_a_lock_answers_a_deferred_ctrl_c(tmp_path):
    """A write that waits for another process's lock holds nothing yet: Ctrl-C acts there, not
    after the 30 s busy timeout."""
    import sqlite3
    import time

    from tilekit.catalogue import open_catalogue

    path = tmp_path / "c.sqlite"
    cat = open_catalogue(f"sqlite:///{path}", seed=False)
    holder = sqlite3.connect(path, isolation_level=None)
    holder.execute("BEGIN IMMEDIATE")
    try:
        signal.setitimer(signal.ITIMER_REAL, 0.3)
        previous = signal.signal(signal.SIGALRM, lambda *_: os.kill(os.getpid(), signal.SIGINT))
        started = time.monotonic()
        try:
            with pytest.raises(KeyboardInterrupt), deferred():
                cat.stop_session("nobody")
        finally:
            signal.signal(signal.SIGALRM, previous)
        assert time.monotonic() - started < 5.0
    finally:
        holder.execute("ROLLBACK")
        holder.close()
        cat.close()
