"""The stage file by which the caller tells the second process how far its share of the
engine's compilation has come (structures.compiled.ahead), so that neither compiles the other's
share."""

from __future__ import annotations

import threading
import time

from structures.compiled import ahead


def test_no_stage_file_means_nobody_helps_and_nothing_is_waited_for(tmp_path):
    start = time.perf_counter()
    assert not ahead.wait_for_stage(None, 1)
    assert not ahead.wait_for_stage(tmp_path / "stage", 1)
    assert time.perf_counter() - start < 1.0


def test_the_second_process_waits_until_the_stage_is_reached(tmp_path):
    stage = tmp_path / "stage"
    ahead.write_stage(stage, 0)
    assert stage.read_text() == "0"
    timer = threading.Timer(0.1, ahead.write_stage, (stage, 2))
    timer.start()
    try:
        assert ahead.wait_for_stage(stage, 2, limit=30.0)
    finally:
        timer.cancel()
    assert ahead.wait_for_stage(stage, 1, limit=1.0)  # a later stage includes the earlier
    assert not list(tmp_path.glob("*.partial"))  # written whole, by a rename


def test_a_stage_not_reached_in_time_or_a_removed_file_ends_the_wait(tmp_path):
    stage = tmp_path / "stage"
    ahead.write_stage(stage, 1)
    assert not ahead.wait_for_stage(stage, 2, limit=0.05)  # then it compiles that share itself
    threading.Timer(0.05, stage.unlink).start()
    assert not ahead.wait_for_stage(stage, 2, limit=30.0)  # the caller failed: stop waiting


def test_a_handle_without_a_process_helps_with_nothing_and_leaves_no_stage_folder(tmp_path):
    stage = tmp_path / "folder" / "stage"
    stage.parent.mkdir()
    ahead.write_stage(stage, 0)
    handle = ahead.CompileAhead(None, stage)
    assert handle.help() == 0.0 and handle.wait()
    handle.stop()
    assert not stage.parent.exists()
