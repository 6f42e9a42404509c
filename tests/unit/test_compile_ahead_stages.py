"""The stage file by which the caller tells the second process how far its share of the
engine's compilation has come (structures.compiled.ahead), so that neither compiles the other's
share."""

from __future__ import annotations

from structures.compiled import ahead


def test_the_stage_is_written_whole_by_a_rename(tmp_path):
    stage = tmp_path / "stage"
    for value in (0, 1, 2):
        ahead.write_stage(stage, value)
        assert stage.read_text() == str(value)
    assert not list(tmp_path.glob("*.partial"))


def test_a_handle_without_a_process_helps_with_nothing_and_leaves_no_stage_folder(tmp_path):
    stage = tmp_path / "folder" / "stage"
    stage.parent.mkdir()
    ahead.write_stage(stage, 0)
    handle = ahead.CompileAhead(None, stage)
    assert handle.help() == 0.0 and handle.wait()
    handle.stop()
    assert not stage.parent.exists()
